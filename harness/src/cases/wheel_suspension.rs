//! `wheel_suspension` (`docs/cases.md#wheel_suspension`): a chassis of
//! 4 kg on a fixed wheel by a wheel joint whose suspension spring is
//! f = 2 Hz, ζ = 0.1 along a vertical axis (`scenes/wheel_suspension.toml`,
//! the soft step, rapier2d and Box2D; `scenes/wheel_suspension_exact.toml`,
//! the exact model under RK4 at h = 1e-3 s). Released with the spring at
//! rest, the chassis' height is the damped oscillator
//! ÿ = −g − ω² (y − y₀) − 2ζω ẏ about its sag −g/ω² (Box2D's springs are
//! mass-independent: stiffness m ω², damping 2ζmω, ω = 2πf): it swings at
//! the damped frequency f_d = f √(1 − ζ²) and its successive peaks fall by
//! the log decrement δ = 2πζ/√(1 − ζ²).
//!
//! # What is measured, and the tolerances
//!
//! From the chassis' height after every step: the **frequency** from the
//! zero crossings of y − y_eq (linear interpolation inside the step), the
//! mean over the first to the last crossing; the **damping ratio** from
//! the log decrement of the peaks of |y − y_eq| (each the vertex of the
//! parabola through its three samples), ζ = δ/√(4π² + δ²), averaged over
//! successive half periods (the ratio of successive opposite peaks is
//! e^{−δ/2}). Each measurement of each engine is made again at half its
//! step (the exact model at h/2; the soft step, rapier2d and Box2D with
//! twice the substeps), and its error against the closed form is held
//! within [`RICHARDSON_FACTOR`] × the step-doubling estimate of a
//! first-order error, (m_h − m_{h/2})/(1 − 2⁻¹): the soft springs of the
//! three impulse engines are implicit (their amplitude loses a factor
//! 1/(1 + (hω)²) per substep, an added damping ratio of about hω, first
//! order in h), and the exact run's error (RK4's, O(h⁴), and the
//! measurement's interpolation, O(dt²)) is of order ≥ 2, for which the
//! first-order estimate is larger still. A floor of 1e-9 relative covers
//! round-off, and Box2D's f32 heights ([`BOX2D_ROUNDING`]).

use super::joint_common::{Config, Engine, JointScene, crossings, steps, turning_values};
use super::{Case, CaseReport, Headline, Snapshots};
use crate::row::{RowKind, RowSink};
use crate::tolerance::{RICHARDSON_FACTOR, richardson_error};
use anyhow::{Context, Result, bail};
use std::f64::consts::PI;

/// A wheel's suspension against the damped oscillator.
pub const CASE: Case = Case {
    scenes: &["wheel_suspension", "wheel_suspension_exact"],
    snapshots: Snapshots::HarnessOnly("four engines and models; the engine's own tests hold the exact run to the closed form (engine/tests/wheel_motor_joints.rs)"),
    headline: &[Headline::new("frequency", "soft_step")],
    ..Case::new(
        "wheel_suspension",
        "Joints: a chassis on a wheel joint's suspension spring: frequency f√(1 − ζ²) and damping ratio ζ of the spring-mass-damper",
        run,
    )
};

/// Box2D's f32 heights: an ulp at 0.6 m is 6e-8 m; the measured frequency
/// and damping ratio move by a few of them over the 0.06 m amplitude:
/// 1e-5 relative.
const BOX2D_ROUNDING: f64 = 1e-5;

/// Round-off floor of a measured quantity (relative).
const FLOOR: f64 = 1e-9;

/// The closed form: ω (rad/s), ζ, the sag (m, from the start height).
struct Closed {
    omega: f64,
    zeta: f64,
    sag: f64,
}

impl Closed {
    fn damped_frequency(&self) -> f64 {
        self.omega * (1.0 - self.zeta * self.zeta).sqrt() / (2.0 * PI)
    }
}

/// One engine's (method id, step s, (frequency, damping ratio) at its step
/// and at half of it, whether it is Box2D).
type Measured = (String, f64, [(f64, f64); 2], bool);

/// Measured (frequency Hz, damping ratio) of the heights `y` sampled every
/// `dt` s about the equilibrium `y_eq`.
fn measure(y: &[f64], dt: f64, y_eq: f64) -> Result<(f64, f64)> {
    let x: Vec<f64> = y.iter().map(|v| v - y_eq).collect();
    let c = crossings(&x, dt);
    if c.len() < 4 {
        bail!("wheel_suspension: {} zero crossings", c.len());
    }
    let frequency = (c.len() - 1) as f64 / (2.0 * (c[c.len() - 1] - c[0]));
    let peaks = turning_values(&x);
    if peaks.len() < 4 {
        bail!("wheel_suspension: {} peaks", peaks.len());
    }
    let n = peaks.len() - 1;
    // Successive opposite peaks fall by e^{−δ/2}.
    let delta = 2.0 * (peaks[0] / peaks[n]).ln() / n as f64;
    let zeta = delta / (4.0 * PI * PI + delta * delta).sqrt();
    Ok((frequency, zeta))
}

/// The chassis' heights of the soft step, rapier2d or Box2D under `config`.
fn heights(js: &JointScene, config: &Config, chassis: usize) -> Result<Vec<f64>> {
    let run = js.run(config, steps(js.scene.duration(), config.dt))?;
    Ok(run.samples.iter().map(|s| s[chassis].position[1]).collect())
}

/// The chassis' heights under the exact model at step `dt`.
fn exact_heights(id: &str, dt: f64) -> Result<Vec<f64>> {
    let scene = crate::scenes::load(id)?;
    let mut world = scene.build_world(None)?;
    world.set_energy_limit(None)?;
    let chassis = scene.body_id("chassis").context("no chassis")?;
    let mut y = vec![world.states()[chassis].position.y];
    for _ in 0..steps(scene.duration(), dt) {
        world.step(dt)?;
        y.push(world.states()[chassis].position.y);
    }
    Ok(y)
}

/// Runs `wheel_suspension`.
pub fn run() -> Result<CaseReport> {
    let js = JointScene::load("wheel_suspension")?;
    let chassis = js.body("chassis")?;
    let Some(engine::JointKind::Wheel(w)) = js.scene.joints().next().map(|d| d.kind) else {
        bail!("wheel_suspension: the first joint must be a wheel");
    };
    let Some(spring) = w.spring else {
        bail!("wheel_suspension: the wheel has no spring");
    };
    let g = js.gravity()?;
    let omega = 2.0 * PI * spring.hertz;
    let closed = Closed {
        omega,
        zeta: spring.damping_ratio,
        sag: g / (omega * omega),
    };
    let y0 = js.neutral.bodies[chassis].position[1];
    let y_eq = y0 - closed.sag;
    let (f_exact, zeta_exact) = (closed.damped_frequency(), closed.zeta);
    let mut report = CaseReport::default();
    let mut measured: Vec<Measured> = Vec::new();
    for &engine in Engine::of_run(true) {
        let config = Config::of(&js.scene, engine)?;
        let half = Config {
            substeps: 2 * config.substeps,
            ..config
        };
        let m = [
            measure(&heights(&js, &config, chassis)?, config.dt, y_eq)?,
            measure(&heights(&js, &half, chassis)?, config.dt, y_eq)?,
        ];
        measured.push((engine.id().into(), config.dt, m, engine == Engine::Box2d));
    }
    let exact_scene = crate::scenes::load("wheel_suspension_exact")?;
    let h = exact_scene.dt();
    let m = [
        measure(&exact_heights("wheel_suspension_exact", h)?, h, y_eq)?,
        measure(&exact_heights("wheel_suspension_exact", h / 2.0)?, h / 2.0, y_eq)?,
    ];
    measured.push(("exact_rk4".into(), h, m, false));
    for (method, dt, [(f_h, z_h), (f_half, z_half)], box2d) in measured {
        let floor = if box2d { BOX2D_ROUNDING } else { FLOOR };
        report.notes.push(format!(
            "{method}: frequency {f_h:.9} Hz at its step, {f_half:.9} Hz at half of it (closed \
             form f√(1 − ζ²) = {f_exact:.9} Hz); damping ratio {z_h:.6} and {z_half:.6} (ζ = \
             {zeta_exact})"
        ));
        let mut sink = RowSink {
            case: "wheel_suspension",
            method: &method,
            dt,
            rows: &mut report.rows,
        };
        let tol_f = (RICHARDSON_FACTOR * richardson_error(f_h, f_half, 1).abs())
            .max(floor * f_exact);
        sink.within(
            RowKind::Validation,
            "frequency",
            f_h,
            f_exact,
            tol_f,
            format!(
                "the chassis' oscillation frequency (Hz), from the zero crossings of y − y_eq, \
                 against the spring-mass-damper's f√(1 − ζ²) (f = {} Hz, ζ = {}). Tolerance: \
                 {RICHARDSON_FACTOR} × the step-doubling estimate of a first-order error, \
                 (m_h − m_h/2)/(1 − 2⁻¹), m_h/2 = {f_half:.9} Hz (the implicit soft spring's \
                 error is first order in h; the exact run's, RK4's and the crossings', of order \
                 ≥ 2, which this overestimates), floor {floor:.0e} relative",
                spring.hertz, spring.damping_ratio
            ),
        );
        let tol_z = (RICHARDSON_FACTOR * richardson_error(z_h, z_half, 1).abs())
            .max(floor * zeta_exact);
        sink.within(
            RowKind::Validation,
            "damping_ratio",
            z_h,
            zeta_exact,
            tol_z,
            format!(
                "the damping ratio from the log decrement of the peaks of |y − y_eq|, \
                 ζ = δ/√(4π² + δ²), against the spring's ζ = {zeta_exact}. Tolerance: \
                 {RICHARDSON_FACTOR} × the first-order step-doubling estimate, m_h/2 = \
                 {z_half:.6} (an implicit soft spring adds about hω of damping ratio, first \
                 order in h), floor {floor:.0e} relative"
            ),
        );
    }
    Ok(report)
}
