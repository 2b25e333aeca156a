//! `simulate --compare rapier`: the same scene in rapier2d-f64
//! (`references::rapier_world`), compared step by step.
//!
//! The scene is translated by [`crate::rapier_scene::rapier_problem`]: one
//! dynamic body; gravity, an axial spring to an anchor, quadratic drag and
//! angular drag without windows; torques with or without one. Anything else
//! (several bodies, joints, a point force, a distance spring, a spring
//! between bodies, a window on another force) is refused with the reason, before
//! the run. Rapier steps with the scene's dt (4 substeps, its default); the
//! two runs are compared at every whole step `i·dt` both reached: the
//! engine's run may end earlier at a landing, or with a shortened last step
//! that rapier cannot take.

use crate::report::fmt_num;
use anyhow::{Result, bail};
use engine::{BodyKind, BodyState, World};
use references::rapier_world::{
    RapierBody, RapierForce, RapierSample, RapierSettings, configuration_summary, run_single_body,
};
use scene::Scene;
use std::fmt::Write as _;

/// Most steps compared (the engine's states are kept for each).
pub const MAX_COMPARED_STEPS: u64 = 2_000_000;

/// The rapier side of a comparison and the engine states seen so far.
pub(super) struct Rapier {
    body: RapierBody,
    forces: Vec<RapierForce>,
    index: usize,
    rotates: bool,
    /// The engine's state of the body at steps 0, 1, 2, ... (whole steps).
    engine: Vec<BodyState>,
    origin: String,
}

impl Rapier {
    /// Checks that `scene` can run in rapier and translates it.
    pub(super) fn prepare(scene: &Scene, steps: u64) -> Result<Self> {
        let origin = scene.origin().to_owned();
        let bodies = scene.bodies();
        if bodies.len() != 1 {
            bail!(
                "--compare rapier: {origin} has {} bodies; the rapier comparison handles scenes of one dynamic body only",
                bodies.len()
            );
        }
        if bodies[0].kind != BodyKind::Dynamic {
            bail!("--compare rapier: {origin}: its only body is static, nothing moves");
        }
        if scene.joint_count() > 0 {
            bail!(
                "--compare rapier: {origin} has joints; the rapier comparison does not translate them (yet): remove --compare"
            );
        }
        if steps > MAX_COMPARED_STEPS {
            bail!(
                "--compare rapier: {steps} steps; the comparison keeps every step and takes at most {MAX_COMPARED_STEPS}: raise --dt or shorten --until"
            );
        }
        let (body, forces) = crate::rapier_scene::rapier_problem(scene)
            .map_err(|e| e.context("--compare rapier: this scene has no rapier counterpart"))?;
        let mut engine = Vec::with_capacity(steps as usize + 1);
        let (_, initial) = engine::Body::from_def(&bodies[0])?;
        engine.push(initial);
        Ok(Self {
            rotates: body.inertia.is_some(),
            body,
            forces,
            index: 0,
            engine,
            origin,
        })
    }

    /// Keeps the engine's state after whole step `i`.
    pub(super) fn observe(&mut self, i: u64, whole: bool, world: &World) {
        if whole && i as usize == self.engine.len() {
            self.engine.push(world.states()[self.index]);
        }
    }

    /// Runs rapier over the whole steps the engine took and tells the
    /// largest differences.
    pub(super) fn report(self, dt: f64) -> Result<String> {
        let steps = self.engine.len() - 1;
        let mut out = String::new();
        let settings = RapierSettings::new(dt);
        if steps == 0 {
            let _ = writeln!(
                out,
                "rapier2d-f64: the run ended within its first step; no whole step of {dt} s to compare"
            );
            return Ok(out);
        }
        let duration = steps as f64 * dt;
        let rapier =
            run_single_body(&self.body, &self.forces, &settings, duration).map_err(|e| {
                anyhow::anyhow!(
                    "--compare rapier: {}: rapier2d run failed: {e}",
                    self.origin
                )
            })?;
        let _ = writeln!(
            out,
            "\nrapier2d-f64 against the engine, t in [0, {duration}] s ({steps} steps of {dt} s, rapier with {} substeps):",
            settings.substeps
        );
        let _ = writeln!(
            out,
            "  {:<16} {:>14} {:>10} {:>18} {:>18}",
            "quantity", "max |diff|", "at t (s)", "engine", "rapier"
        );
        type Pick = fn(&BodyState, &RapierSample) -> (f64, f64);
        let mut rows: Vec<(&str, Pick)> = vec![
            ("x (m)", |e, r| (e.position.x, r.position[0])),
            ("y (m)", |e, r| (e.position.y, r.position[1])),
            ("vx (m/s)", |e, r| (e.velocity.x, r.velocity[0])),
            ("vy (m/s)", |e, r| (e.velocity.y, r.velocity[1])),
        ];
        if self.rotates {
            rows.push(("angle (rad)", |e, r| (e.angle, r.angle)));
            rows.push(("omega (rad/s)", |e, r| {
                (e.angular_velocity, r.angular_velocity)
            }));
        }
        for (name, pick) in rows {
            let mut worst = (0.0, 0.0, 0.0, 0.0);
            for (e, r) in self.engine.iter().zip(&rapier) {
                let (a, b) = pick(e, r);
                let d = (a - b).abs();
                if d > worst.0 || d.is_nan() {
                    worst = (d, r.t, a, b);
                }
            }
            let _ = writeln!(
                out,
                "  {name:<16} {:>14.6e} {:>10} {:>18} {:>18}",
                worst.0,
                crate::pictures::sig(worst.1),
                fmt_num(worst.2),
                fmt_num(worst.3)
            );
        }
        let _ = writeln!(out, "rapier configuration:");
        for line in wrap(&configuration_summary(&settings), 96) {
            let _ = writeln!(out, "  {line}");
        }
        Ok(out)
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
    use super::wrap;

    #[test]
    fn wrapping_keeps_every_word() {
        let lines = wrap("a bb ccc dddd eeeee", 7);
        assert_eq!(lines, ["a bb", "ccc", "dddd", "eeeee"]);
    }
}
