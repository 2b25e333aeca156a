//! `simulate --compare rapier|box2d` (or both, `--compare rapier,box2d`):
//! the same scene in rapier2d-f64 0.36 and Box2D 3.2, compared step by
//! step with the engine's run.
//!
//! [`adapters`] picks the adapter that can represent the scene in each
//! engine or refuses it before the run, with the reason in the scene's
//! words. The references step with the run's dt (their substeps as
//! printed); the runs are compared at every whole step `i·dt` both
//! reached (the engine's run may end earlier at a landing, or with a
//! shortened last step no reference takes), over every moving body: the
//! largest difference of each quantity, where and when. Angles are
//! compared modulo a turn (the many-body adapters read principal values).
//! `--verbose` prints each engine's configuration. With `--html`, the
//! references' runs go into the replay beside the engine's.
//!
//! Memory: the many-body adapters (Box2D, rapier's soft-step scenes) step
//! alongside the engine and keep no state per step (with `--html`, their
//! run at the replay's samples only), so the comparison's memory does not
//! grow with the run. Rapier's single-body and exact-contact adapters run
//! after the engine from its states at every whole step: those are kept,
//! at most [`MAX_COMPARED_STATES`] of them (steps × bodies; a longer run
//! is refused before it starts), on the small scenes these adapters take.

pub(crate) mod adapters;

use super::CompareWith;
use crate::replay::ReplayRun;
use crate::report::fmt_num;
use adapters::{Adapter, Prepared};
use anyhow::{Result, anyhow, bail};
use engine::{BodyState, World};
use references::many_body::BodySample;
use references::rapier_contacts::run_contact_scene;
use references::rapier_world::{RapierSample, RapierSettings, run_single_body};
use scene::Scene;
use std::fmt::Write as _;

/// Most body states kept for a reference that runs after the engine
/// (rapier's single-body and exact-contact adapters): steps × bodies. The
/// many-body adapters step alongside the engine and keep none.
pub const MAX_COMPARED_STATES: u64 = 4_000_000;

/// The largest difference of one quantity.
#[derive(Debug, Clone, Copy, Default)]
struct Worst {
    /// Whether a step was compared.
    set: bool,
    diff: f64,
    body: usize,
    t: f64,
    engine: f64,
    reference: f64,
}

/// The quantities compared: name, and (engine, reference) values.
type Pick = fn(&BodyState, &BodyState) -> (f64, f64);
const QUANTITIES: [(&str, Pick); 6] = [
    ("x (m)", |e, r| (e.position.x, r.position.x)),
    ("y (m)", |e, r| (e.position.y, r.position.y)),
    ("vx (m/s)", |e, r| (e.velocity.x, r.velocity.x)),
    ("vy (m/s)", |e, r| (e.velocity.y, r.velocity.y)),
    ("angle (rad)", |e, r| (e.angle, r.angle)),
    ("omega (rad/s)", |e, r| {
        (e.angular_velocity, r.angular_velocity)
    }),
];

/// One reference engine and what it found.
struct Reference {
    prepared: Prepared,
    worst: [Worst; 6],
    /// Whole steps compared.
    compared: u64,
    /// Its states at every `stride`-th step, for the replay (only its
    /// first when no replay is asked: `keep_runs`).
    replay: ReplayRun,
    /// Why it stopped before the engine did.
    failure: Option<String>,
    scratch: Vec<BodySample>,
}

/// The references of a run and the engine's states they need.
pub(in crate::simulate) struct Comparison {
    references: Vec<Reference>,
    /// The engine's states at whole steps 0, 1, ... (kept only for the
    /// references that run after it).
    engine: Vec<Vec<BodyState>>,
    keep_engine: bool,
    /// Whether the references' runs are kept for the replay (`--html`):
    /// without it a reference keeps no state per step.
    keep_runs: bool,
    /// Whole steps the engine has taken so far.
    steps: u64,
    stride: u64,
    dt: f64,
    names: Vec<String>,
    moving: Vec<bool>,
    rotates: bool,
    verbose: bool,
    /// The engines of several that refused the scene, each with its reason
    /// (`--compare rapier,box2d` runs those that accept it).
    refused: Vec<String>,
    /// Moving bodies in contact (more than two): a chaotic scene, whose
    /// runs part whatever their accuracy (said under the tables).
    pile: Option<usize>,
}

fn wrap_angle(a: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    a - tau * (a / tau).round()
}

impl Comparison {
    /// Sets up every engine of `with` for `scene`, to run `steps` steps of
    /// `dt` (s) from `initial`, keeping every `stride`-th state for the
    /// replay when `keep_runs` (none otherwise). Refuses a scene an engine cannot represent; of several
    /// engines, runs those that can and names the others with their reason
    /// (refuses only when none can).
    pub(in crate::simulate) fn prepare(
        scene: &Scene,
        with: &[CompareWith],
        (dt, steps, stride): (f64, u64, u64),
        initial: &[BodyState],
        keep_runs: bool,
        verbose: bool,
    ) -> Result<Self> {
        let mut references = Vec::new();
        let mut refused = Vec::new();
        for &engine in with {
            let option = match engine {
                CompareWith::Rapier => "--compare rapier",
                CompareWith::Box2d => "--compare box2d",
            };
            let mut prepared = match adapters::prepare(scene, engine, dt) {
                Ok(prepared) => prepared,
                Err(e) if with.len() > 1 => {
                    refused.push(format!("{option}: {}", crate::simulate::one_line(&e)));
                    continue;
                }
                Err(e) => return Err(e.context(option)),
            };
            let states = initial.to_vec();
            let mut scratch = Vec::new();
            let mut first = states.clone();
            if let Adapter::Many(world) = &mut prepared.adapter {
                world
                    .samples(&mut scratch)
                    .map_err(|e| anyhow!(e).context(option))?;
                first = merged(&states, &scratch);
            }
            let label = format!(
                "{} ({} substeps, dt = {} s)",
                prepared.name,
                prepared.substeps,
                super::fmt_short(dt)
            );
            references.push(Reference {
                prepared,
                worst: [Worst::default(); 6],
                compared: 0,
                replay: ReplayRun {
                    label,
                    short: match engine {
                        CompareWith::Rapier => "rapier2d".into(),
                        CompareWith::Box2d => "Box2D".into(),
                    },
                    times: vec![0.0],
                    states: vec![first],
                    ..ReplayRun::default()
                },
                failure: None,
                scratch,
            });
        }
        if references.is_empty() {
            bail!(
                "--compare: no engine of those named takes this scene:\n  {}",
                refused.join("\n  ")
            );
        }
        let keep_engine = references
            .iter()
            .any(|r| !matches!(r.prepared.adapter, Adapter::Many(_)));
        let bodies = initial.len() as u64;
        if keep_engine && steps.saturating_mul(bodies.max(1)) > MAX_COMPARED_STATES {
            bail!(
                "--compare rapier: {steps} steps of {bodies} bodies; rapier runs after the engine \
                 from its states at every step and keeps at most {MAX_COMPARED_STATES:.0e}: raise \
                 --dt or shorten --until"
            );
        }
        let defs = scene.bodies();
        let moving_bodies = defs
            .iter()
            .filter(|b| b.kind != engine::BodyKind::Static)
            .count();
        let contacts = scene.file().contact.is_some() || scene.joint_count() > 0;
        let pile = (contacts && moving_bodies > 2).then_some(moving_bodies);
        Ok(Self {
            references,
            engine: if keep_engine {
                vec![initial.to_vec()]
            } else {
                Vec::new()
            },
            keep_engine,
            keep_runs,
            steps: 0,
            stride: stride.max(1),
            dt,
            names: defs.iter().map(|b| b.name.clone()).collect(),
            moving: defs
                .iter()
                .map(|b| b.kind != engine::BodyKind::Static)
                .collect(),
            rotates: defs.iter().any(|def| {
                engine::Body::from_def(def).is_ok_and(|(b, _)| b.is_dynamic() && b.rotates())
            }),
            verbose,
            refused,
            pile,
        })
    }

    /// After the engine's step `i`: at a whole step, the references that
    /// step alongside take theirs and are compared.
    pub(in crate::simulate) fn observe(&mut self, i: u64, whole: bool, world: &World) {
        if !whole || i != self.steps + 1 {
            return;
        }
        self.steps = i;
        let states = world.states();
        if self.keep_engine {
            self.engine.push(states.to_vec());
        }
        let t = world.time();
        let (stride, moving, keep_runs) = (self.stride, &self.moving, self.keep_runs);
        for r in &mut self.references {
            let Adapter::Many(reference) = &mut r.prepared.adapter else {
                continue;
            };
            if r.failure.is_some() {
                continue;
            }
            let stepped = reference
                .step()
                .and_then(|()| reference.samples(&mut r.scratch));
            if let Err(e) = stepped {
                r.failure = Some(format!("step {i} (t = {} s) failed: {e}", fmt_num(t)));
                continue;
            }
            let theirs = merged(states, &r.scratch);
            compare_step(&mut r.worst, moving, t, states, &theirs);
            r.compared = i;
            if keep_runs && i.is_multiple_of(stride) {
                r.replay.times.push(t);
                r.replay.states.push(theirs);
            }
        }
    }

    /// Runs the references that run after the engine, then tells the
    /// largest differences of each. Returns the text and the references'
    /// runs for the replay (angles made continuous).
    pub(in crate::simulate) fn report(mut self) -> Result<(String, Vec<ReplayRun>)> {
        let dt = self.dt;
        let steps = self.steps;
        for r in &mut self.references {
            if steps == 0 {
                continue;
            }
            let settings = RapierSettings::new(dt);
            let duration = steps as f64 * dt;
            let run: Vec<Vec<BodyState>> = match &r.prepared.adapter {
                Adapter::Many(_) => continue,
                Adapter::SingleBody(single) => {
                    let samples =
                        run_single_body(&single.body, &single.forces, &settings, duration)
                            .map_err(|e| anyhow!("--compare rapier: the rapier run failed: {e}"))?;
                    samples
                        .iter()
                        .map(|s| {
                            let mut states = self.engine[0].clone();
                            states[single.index] = state_of(s);
                            states
                        })
                        .collect()
                }
                Adapter::Contacts(scene) => run_contact_scene(scene, &settings, duration)
                    .map_err(|e| anyhow!("--compare rapier: the rapier run failed: {e}"))?
                    .samples
                    .iter()
                    .map(|states| states.iter().map(state_of).collect())
                    .collect(),
            };
            for (k, (ours, theirs)) in self.engine.iter().zip(&run).enumerate().skip(1) {
                let t = k as f64 * dt;
                compare_step(&mut r.worst, &self.moving, t, ours, theirs);
                if self.keep_runs && (k as u64).is_multiple_of(self.stride) {
                    r.replay.times.push(t);
                    r.replay.states.push(theirs.clone());
                }
            }
            r.compared = steps;
        }
        let mut out = String::new();
        for refused in &self.refused {
            let _ = writeln!(out, "\nnot compared: {refused}");
        }
        let mut runs = Vec::new();
        for mut r in self.references {
            self::write_reference(
                &mut out,
                &r,
                steps,
                dt,
                &self.names,
                self.rotates,
                self.verbose,
            );
            if let Some(n) = self.pile {
                let _ = writeln!(
                    out,
                    "  A pile of {n} moving bodies in contact is chaotic: a difference in the last \
                     digit grows at every collision, so the runs of two engines part, whatever their \
                     accuracy; these maxima say where and when they diverged, not which is right."
                );
            }
            crate::replay::unwrap_angles(&mut r.replay.states);
            runs.push(r.replay);
        }
        Ok((out, runs))
    }
}

/// The engine's `initial` states with the reference's samples put in.
fn merged(initial: &[BodyState], samples: &[BodySample]) -> Vec<BodyState> {
    initial
        .iter()
        .zip(samples)
        .map(|(_, s)| BodyState {
            position: nalgebra::Vector2::new(s.position[0], s.position[1]),
            angle: s.angle,
            velocity: nalgebra::Vector2::new(s.velocity[0], s.velocity[1]),
            angular_velocity: s.angular_velocity,
        })
        .collect()
}

fn state_of(s: &RapierSample) -> BodyState {
    BodyState {
        position: nalgebra::Vector2::new(s.position[0], s.position[1]),
        angle: s.angle,
        velocity: nalgebra::Vector2::new(s.velocity[0], s.velocity[1]),
        angular_velocity: s.angular_velocity,
    }
}

/// Updates the largest differences with the states of one step at `t`.
fn compare_step(
    worst: &mut [Worst; 6],
    moving: &[bool],
    t: f64,
    ours: &[BodyState],
    theirs: &[BodyState],
) {
    for (b, (e, r)) in ours.iter().zip(theirs).enumerate() {
        if !moving.get(b).copied().unwrap_or(false) {
            continue;
        }
        for (q, (_, pick)) in QUANTITIES.iter().enumerate() {
            let (a, c) = pick(e, r);
            let diff = if q == 4 {
                wrap_angle(a - c).abs()
            } else {
                (a - c).abs()
            };
            let w = &worst[q];
            if !w.set || diff > w.diff || (diff.is_nan() && !w.diff.is_nan()) {
                worst[q] = Worst {
                    set: true,
                    diff,
                    body: b,
                    t,
                    engine: a,
                    reference: c,
                };
            }
        }
    }
}

fn write_reference(
    out: &mut String,
    r: &Reference,
    steps: u64,
    dt: f64,
    names: &[String],
    rotates: bool,
    verbose: bool,
) {
    let p = &r.prepared;
    let short = p.name.split(' ').next().unwrap_or(p.name);
    if steps == 0 {
        let _ = writeln!(
            out,
            "\n{}: the run ended within its first step; no whole step of {} s to compare",
            p.name,
            super::fmt_short(dt)
        );
        return;
    }
    let _ = writeln!(
        out,
        "\n{} against the engine, t in [0, {}] s ({} steps of {} s; {} substeps):",
        p.name,
        super::fmt_short(r.compared as f64 * dt),
        r.compared,
        super::fmt_short(dt),
        p.substeps
    );
    let _ = writeln!(out, "  {}.", p.note);
    if let Some(failure) = &r.failure {
        let _ = writeln!(out, "  {short} stopped: {failure}");
    }
    let body_width = names
        .iter()
        .map(|n| n.chars().count())
        .max()
        .unwrap_or(4)
        .max(4);
    let _ = writeln!(
        out,
        "  {:<14} {:>13} {:<body_width$} {:>9} {:>18} {:>18}",
        "quantity", "max |diff|", "body", "at t (s)", "engine", short
    );
    for (q, (name, _)) in QUANTITIES.iter().enumerate() {
        if q >= 4 && !rotates {
            continue;
        }
        let w = &r.worst[q];
        let _ = writeln!(
            out,
            "  {name:<14} {:>13.6e} {:<body_width$} {:>9} {:>18} {:>18}",
            w.diff,
            names.get(w.body).map_or("", String::as_str),
            super::fmt_short(w.t),
            fmt_num(w.engine),
            fmt_num(w.reference)
        );
    }
    if verbose {
        let _ = writeln!(out, "{short} configuration:");
        for line in wrap(&p.configuration, 96) {
            let _ = writeln!(out, "  {line}");
        }
    } else {
        let _ = writeln!(out, "  (--verbose prints how {short} is configured)");
    }
}

/// Splits `text` into lines of at most `width` characters at spaces.
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapping_keeps_every_word() {
        let lines = wrap("a bb ccc dddd eeeee", 7);
        assert_eq!(lines, ["a bb", "ccc", "dddd", "eeeee"]);
    }

    #[test]
    fn angles_differ_modulo_a_turn() {
        assert!((wrap_angle(std::f64::consts::TAU + 0.1) - 0.1).abs() < 1e-12);
        assert!((wrap_angle(-0.1) + 0.1).abs() < 1e-15);
    }
}
