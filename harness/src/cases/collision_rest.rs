//! Case III, `collision_rest` (docs/cases.md; seed §7.1 after Baraff): a box
//! resting on the ground for 10 s must not move, in the engine (exact
//! contact forces) and in rapier2d-f64 (soft contacts).

use super::collision_common::{
    run_soft_step, soft_step_sink,
    RAPIER, STILL, rapier_position, rapier_settings, run_engine, run_rapier,
};
use super::{Case, CaseReport, Headline, Snapshots};
use crate::row::{RowKind, RowSink};
use anyhow::Result;

/// A box resting on the ground.
pub const CASE: Case = Case {
    scenes: &["collision_rest"],
    snapshots: Snapshots::ContactEvents,
    headline: &[Headline::new("motion", "rk4")],
    ..Case::new(
        "collision_rest",
        "Case III: a box resting on the ground for 10 s (seed §7.1, after Baraff)",
        run,
    )
};

/// Runs `collision_rest`.
pub fn run() -> Result<CaseReport> {
    let id = "collision_rest";
    let run = run_engine(id)?;
    let b = run.body("box")?;
    let start = run.scene.bodies()[b].state;
    let end = run.world.states()[b];
    let motion = run
        .trace
        .samples
        .iter()
        .map(|s| (s.states[b].position - start.position).norm())
        .fold(0.0, f64::max);
    let mut report = CaseReport::default();
    let dt = run.scene.dt();
    let mut sink = RowSink {
        case: id,
        method: run.scene.method().id(),
        dt,
        rows: &mut report.rows,
    };
    sink.at_most(
        RowKind::Validation,
        "motion",
        motion,
        0.0,
        STILL,
        "largest distance from the start over 10 s; docs/cases.md: less than 1e-9 m (the contact \
         force equals the weight at every evaluation: nothing sinks, nothing is corrected)",
    );
    sink.at_most(
        RowKind::Validation,
        "rotation",
        (end.angle - start.angle).abs(),
        0.0,
        1e-12,
        "the two corners carry half the weight each (solved together): no torque, angle kept to \
         round-off",
    );
    sink.at_most(
        RowKind::Validation,
        "speed",
        end.velocity.norm(),
        0.0,
        1e-12,
        "at rest: speed 0 to round-off after 10 s",
    );
    let events = run.world.contact_events();
    sink.within(
        RowKind::Validation,
        "contact_events",
        events.len() as f64,
        1.0,
        0.0,
        "one event, the contact coming to rest at t = 0; no impact, no release, no jitter",
    );
    // rapier2d.
    let rapier = run_rapier(&run.scene)?;
    let rdt = rapier_settings(&run.scene).dt;
    let rmotion = (0..rapier.samples.len())
        .map(|k| (rapier_position(&rapier, k, b) - start.position).norm())
        .fold(0.0, f64::max);
    let sink_depth = start.position.y - rapier_position(&rapier, rapier.samples.len() - 1, b).y;
    // docs/cases.md: a resting body sinks about 3.1/f² m at contact frequency f;
    // against a fixed body rapier's contacts are 60 Hz.
    let f = 60.0;
    let soft = 3.1 / (f * f);
    RowSink {
        case: id,
        method: RAPIER,
        dt: rdt,
        rows: &mut report.rows,
    }
    .at_most(
        RowKind::Validation,
        "motion",
        rmotion,
        0.0,
        soft,
        format!(
            "rapier's contacts are soft: docs/cases.md's estimate of the sink of a resting body, \
             3.1/f² m with f = 60 Hz against a fixed body = {soft:.2e} m, bounds its motion"
        ),
    );
    report.notes.push(format!(
        "`{id}`: box 0.5 m, 2 kg on the ground, mu = 0.5. Engine: largest motion {motion:.3e} m \
         in 10 s, {} contact event(s). rapier2d: largest motion {rmotion:.3e} m, resting \
         {sink_depth:.3e} m into the ground at the end.",
        events.len()
    ));
    report.notes.push(run.profile_note(id));
    soft_step(&mut report, id)?;
    Ok(report)
}

/// The resting box under the soft-step model: it sinks by its contact
/// spring's static compression and stays there. Against a static body the
/// spring has 2 × 30 Hz, ω = 2π·60 rad/s; each of the two points carries
/// half the weight, so its impulse per substep is m g h/2 and the soft
/// update vanishes at s = −(m g/2)/(m_i ω²), m_i the point's effective mass
/// 1/(1/m + (w/2)²/I) (`engine::soft_step::softness`). For a square box
/// I = m w²/6, 1/m_i = 2.5/m: the sink is 1.25 g/ω².
fn soft_step(report: &mut CaseReport, id: &str) -> Result<()> {
    let run = run_soft_step(id)?;
    let b = run.body("box")?;
    let start = run.scene.bodies()[b].state;
    let end = run.world.states()[b];
    let g = super::collision_common::gravity(&run)?;
    let omega = 2.0 * std::f64::consts::PI * 60.0;
    let sink_depth = 1.25 * g / (omega * omega);
    let settled = super::collision_common::engine_motion_after(&run, b, 1.0);
    let mut sink = soft_step_sink(&mut report.rows, "collision_rest", &run);
    sink.within(
        RowKind::Validation,
        "sink",
        start.position.y - end.position.y,
        sink_depth,
        1e-12,
        format!(
            "the static soft contact's compression 1.25 g/ω², ω = 2π·60 rad/s: {sink_depth:.6e} m \
             (the update converges geometrically, by its impulse scale ≈ 0.06 per substep: \
             after 10 s only round-off, 1e-12 m)"
        ),
    );
    sink.at_most(
        RowKind::Validation,
        "motion_after_settling",
        settled,
        0.0,
        STILL,
        "distance moved from 1 s to 10 s, once the contact has settled; docs/cases.md's 1e-9 m",
    );
    sink.at_most(
        RowKind::Validation,
        "drift_x",
        (end.position.x - start.position.x).abs(),
        0.0,
        sink_depth,
        "sideways creep while settling: the two points are solved one after the other, so the \
         first push turns the box by at most the sink over its half-width, and its corner \
         slides by no more than the sink before friction holds it",
    );
    Ok(())
}

