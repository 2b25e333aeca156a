//! What the soft-step behaviour cases (`stack`, `pyramid`, `friction_ramp`,
//! `overlap_recovery`, `mass_ratio`; `docs/soft_step.md#behaviour-scenes`)
//! share: running their scene file under its own `[contact]` (the soft-step
//! model), and the static compression of a soft contact, the closed form
//! most of their rows compare with.

use crate::row::RowSink;
use crate::scenes;
use anyhow::{Context, Result, bail};
use engine::{ContactModel, SoftStepSettings, Trace, World};
use scene::Scene;

/// Method id of the behaviour rows: the soft-step contact model.
pub const SOFT_STEP: &str = "soft_step";

/// A soft-step scene run to its duration.
pub struct SoftRun {
    /// The scene.
    pub scene: Scene,
    /// The world at the end.
    pub world: World,
    /// Every step's sample.
    pub trace: Trace,
    /// The soft step's settings.
    pub settings: SoftStepSettings,
}

impl SoftRun {
    /// Loads scene `id` (which must use the soft-step model) and runs it.
    pub fn new(id: &str) -> Result<SoftRun> {
        let scene = scenes::load(id)?;
        let settings = match scene.contact() {
            Some(ContactModel::SoftStep(s)) => s,
            _ => bail!("{id}: the scene does not use the soft-step contact model"),
        };
        let mut world = scene.build_world(None)?;
        let trace = world
            .run(scene.duration(), scene.dt())
            .with_context(|| format!("running {id}"))?;
        Ok(SoftRun {
            scene,
            world,
            trace,
            settings,
        })
    }

    /// The id of body `name`.
    pub fn body(&self, name: &str) -> Result<usize> {
        self.scene
            .body_id(name)
            .with_context(|| format!("{}: no body '{name}'", self.scene.origin()))
    }

    /// Rows of case `case` for this run.
    pub fn sink<'a>(&self, case: &'a str, rows: &'a mut Vec<crate::row::Row>) -> RowSink<'a> {
        RowSink {
            case,
            method: SOFT_STEP,
            dt: self.scene.dt(),
            rows,
        }
    }

    /// The substep (s).
    pub fn substep(&self) -> f64 {
        self.scene.dt() / self.settings.substeps as f64
    }

    /// The contact spring's angular frequency ω = 2π f (rad/s) between two
    /// dynamic bodies (`against_static` false) or against a static body
    /// (twice the frequency), with the cap 1/(8h) on f.
    pub fn omega(&self, against_static: bool) -> f64 {
        let f = self.settings.contact_hertz.min(0.125 / self.substep());
        let f = if against_static { 2.0 * f } else { f };
        2.0 * std::f64::consts::PI * f
    }

    /// The largest speed of any dynamic body in the last sample (m/s).
    pub fn fastest_at_end(&self) -> f64 {
        let last = self.trace.last().expect("a run has samples");
        self.world
            .bodies()
            .iter()
            .zip(&last.states)
            .filter(|(b, _)| b.is_dynamic())
            .map(|(_, s)| s.velocity.norm())
            .fold(0.0, f64::max)
    }
}

/// The static compression (m) of one contact point carrying `load` (N), of
/// inverse effective mass `inverse_mass` (1/kg) along the normal, under a
/// soft contact of angular frequency `omega` (rad/s): at rest the point's
/// impulse per substep is load·h and the soft update
/// Δλ = −m_i ms (v + br s) − is λ vanishes at v = 0 when
/// s = −is λ/(m_i ms br) = −(load/m_i)/ω² (`engine::soft_step::softness`).
pub fn point_compression(load: f64, inverse_mass: f64, omega: f64) -> f64 {
    load * inverse_mass / (omega * omega)
}

/// The inverse effective mass (1/kg) of a contact point at arms `ra`, `rb`
/// (m, across the normal) between bodies of inverse masses and inertias
/// `(1/m, 1/I)`; a static body contributes (0, 0).
pub fn inverse_point_mass(a: (f64, f64), ra: f64, b: (f64, f64), rb: f64) -> f64 {
    a.0 + b.0 + a.1 * ra * ra + b.1 * rb * rb
}
