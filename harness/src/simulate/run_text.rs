//! What `simulate` prints about a run besides its events: the contact model
//! and settings that ran (so a user sees which of the two models a scene
//! got, and with what), and the final state, body by body for a few bodies
//! or as a summary for a pile.

use super::fmt_short as short;
use engine::{ContactModel, ToiMethod, World};
use std::fmt::Write as _;

/// `concave polygons: body 'l' (bodies[2].shape, 6 vertices) → 2 convex
/// parts`: what the engine cut each concave outline of the file into
/// (listed up to [`LISTED_OUTLINES`], then counted), or `None` if none.
pub fn outlines_line(file: &scene::SceneFile) -> Option<String> {
    let cuts = scene::outlines::cut_outlines(file);
    if cuts.is_empty() {
        return None;
    }
    let one = |c: &scene::outlines::CutOutline| {
        format!(
            "body '{}' ({}, {} vertices) → {} convex parts",
            c.body, c.field, c.vertices, c.parts
        )
    };
    let listed: Vec<String> = cuts.iter().take(LISTED_OUTLINES).map(one).collect();
    let mut line = format!("concave polygons: {}", listed.join("; "));
    if cuts.len() > LISTED_OUTLINES {
        let parts: usize = cuts.iter().map(|c| c.parts).sum();
        let _ = write!(
            line,
            "; … {} outlines cut into {parts} convex parts in all",
            cuts.len()
        );
    }
    Some(line)
}

/// Concave outlines listed one by one in [`outlines_line`].
const LISTED_OUTLINES: usize = 3;

/// Above this many bodies the final state is summarised (the CSV trace has
/// every body).
pub const LISTED_BODIES: usize = 12;

/// `contacts: soft_step (4 substeps, …)`, `contacts: exact (…)` or
/// `contacts: off (…)`: the model that runs and every setting that changes
/// what it computes, at the values the solver uses with the step `dt` (s)
/// (a contact stiffness above the cap is printed capped, and said so),
/// then the number of joints if any (`; 2 joints`).
pub fn model_line(world: &World, dt: f64) -> String {
    let joints = match world.joint_count() {
        0 => String::new(),
        1 => "; 1 joint".to_owned(),
        n => format!("; {n} joints"),
    };
    let model = match world.contact_model() {
        Some(ContactModel::SoftStep(s)) => format!(
            "contacts: soft_step ({} substeps, contact {}, damping ratio {}, push-out {} m/s, \
             friction {}, restitution {} above {} m/s, speculative {} m, continuous {}, sleeping {})",
            s.substeps,
            contact_hertz_used(s.contact_hertz, dt / s.substeps as f64),
            short(s.contact_damping_ratio),
            short(s.push_out_speed),
            short(s.friction),
            short(s.restitution),
            short(s.restitution_threshold),
            short(s.speculative_distance),
            on_off(s.continuous),
            on_off(s.sleeping),
        ),
        Some(ContactModel::Exact(s)) => format!(
            "contacts: exact (restitution {}, friction {}, tolerance {} m, resting below {} m/s, \
             time of impact by {})",
            short(s.restitution),
            short(s.friction),
            short(s.tolerance),
            short(s.resting_speed),
            match s.toi_method {
                ToiMethod::Bisection => "bisection",
                ToiMethod::ConservativeAdvancement => "conservative advancement",
                ToiMethod::Swept => "swept search (bisection, conservative advancement when fast)",
            },
        ),
        None => "contacts: off (the scene has no [contact] table: shapes pass through each other)"
            .to_owned(),
    };
    format!("{model}{joints}")
}

/// The contact stiffness the soft step uses, in Hz, as printed: the
/// engine caps the requested `hertz` at 1/(8 h) for the substep `h` (s)
/// (a quarter of the substep's Nyquist frequency,
/// `engine/src/soft_step/prepare.rs`), which the line says when it bites.
fn contact_hertz_used(hertz: f64, h: f64) -> String {
    let cap = 0.125 / h;
    if hertz > cap {
        format!(
            "{} Hz (capped: {} Hz requested, above 1/(8 h) for the substep h = {} s)",
            short(cap),
            short(hertz),
            short(h)
        )
    } else {
        format!("{} Hz", short(hertz))
    }
}

fn on_off(on: bool) -> &'static str {
    if on { "on" } else { "off" }
}

/// The final state of a world of more than [`LISTED_BODIES`] bodies in a
/// few lines: how many bodies, the fastest, the highest and the lowest
/// dynamic body.
pub fn pile_summary(world: &World, names: &[&str], fmt: impl Fn(f64) -> String) -> String {
    let mut out = String::new();
    let dynamic: Vec<usize> = (0..world.bodies().len())
        .filter(|&i| world.bodies()[i].is_dynamic())
        .collect();
    let _ = writeln!(
        out,
        "final state of {} bodies ({} dynamic; every body's state: --trace):",
        world.bodies().len(),
        dynamic.len()
    );
    let states = world.states();
    let by = |key: &dyn Fn(usize) -> f64| {
        dynamic
            .iter()
            .copied()
            .max_by(|&a, &b| key(a).total_cmp(&key(b)))
    };
    if let Some(i) = by(&|i| states[i].velocity.norm()) {
        let _ = writeln!(
            out,
            "  fastest: {} at {} m/s",
            names[i],
            fmt(states[i].velocity.norm())
        );
    }
    if let Some(i) = by(&|i| states[i].position.y) {
        let p = states[i].position;
        let _ = writeln!(
            out,
            "  highest: {} at x = {} m, y = {} m",
            names[i],
            fmt(p.x),
            fmt(p.y)
        );
    }
    if let Some(i) = by(&|i| -states[i].position.y) {
        let p = states[i].position;
        let _ = writeln!(
            out,
            "  lowest: {} at x = {} m, y = {} m",
            names[i],
            fmt(p.x),
            fmt(p.y)
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_model_line_names_the_model() {
        let mut world = World::new(engine::Method::Rk4).unwrap();
        assert!(model_line(&world, 0.01).starts_with("contacts: off"));
        world
            .set_contact_settings(engine::ContactSettings::default())
            .unwrap();
        let line = model_line(&world, 0.01);
        assert!(line.starts_with("contacts: exact (restitution 1"), "{line}");
        let soft = World::with_model(
            engine::Method::SemiImplicitEuler,
            ContactModel::SoftStep(engine::SoftStepSettings::default()),
        )
        .unwrap();
        let line = model_line(&soft, 1.0 / 60.0);
        assert!(
            line.starts_with("contacts: soft_step (4 substeps, contact 30 Hz, damping ratio 10,"),
            "{line}"
        );
        // dt = 0.1 s in 4 substeps: h = 0.025 s, cap 1/(8 h) = 5 Hz.
        let line = model_line(&soft, 0.1);
        assert!(
            line.contains(
                "contact 5 Hz (capped: 30 Hz requested, above 1/(8 h) for the substep h = 0.025 s)"
            ),
            "{line}"
        );
    }
}
