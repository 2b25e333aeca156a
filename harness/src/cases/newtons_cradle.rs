//! `newtons_cradle` (`docs/cases.md#newtons_cradle`): five equal balls on
//! rods, touching to within 1e-9 m, e = 1 (`scenes/newtons_cradle.toml`),
//! under the exact model: the rods constraints of the equations of motion,
//! the impacts located inside the step and answered by impulses; beside
//! it the soft step, rapier2d and Box2D on the same cradle
//! (`newtons_cradle_engines.rs`, criterion rows).
//!
//! # What is measured, and the tolerances
//!
//! The impacts come in chains, one per half swing: the moving ball strikes
//! its neighbour, which strikes the next 1e-9 m further, and so on. For
//! one ball out for one in, every chain must be four impacts (ball 0 to 4
//! or back), each passing on the approach speed of the first and leaving
//! its striker at rest: the relative normal velocity reverses (e = 1) and
//! the next impact's approach speed equals the first's. Between two
//! impacts of a chain (about 4e-10 s apart at 2.4 m/s) gravity changes a
//! ball's speed by g sin θ Δt with θ ≲ 1e-9 rad (the balls hang within
//! 1e-9 m of their bottoms), 1e-17 m/s; but each chain leaves the balls
//! it passes through up to four gaps past their bottoms, from which they
//! swing back at up to √(g/L) × 4 gaps, so the next chain's approach
//! speeds differ by that much: the row allows it plus [`ROUND_OFF_ULPS`]
//! ulps. The relative velocity's reversal is held to round-off alone.
//! The energy over the whole run (ten chains and five swings) within
//! [`RICHARDSON_FACTOR`] × RK4's step-doubling estimate (the scene at h/2,
//! order 4) plus the steps' round-off, a random walk (three standard
//! deviations).

use super::{Case, CaseReport, Snapshots};
use crate::row::{RowKind, RowSink};
use crate::tolerance::{RICHARDSON_FACTOR, richardson_error};
use anyhow::{Result, bail};
use engine::{ContactEvent, ContactEventKind};

/// Five balls on rods, one in, one out.
pub const CASE: Case = Case {
    scenes: &["newtons_cradle", "newtons_cradle_soft"],
    snapshots: Snapshots::HarnessOnly(
        "10 s of RK4 at 1e-3 s twice (h and h/2) with about forty impacts; the engine's \
         tests/exact_joints.rs checks one chain",
    ),
    ..Case::new(
        "newtons_cradle",
        "Joints and impacts: Newton's cradle of five balls on rods under the exact model, one ball out for one in",
        run,
    )
};

/// Ulps of the speed the impulses' round-off may move a velocity by
/// over a chain of four impacts (each impulse a handful of operations).
pub const ROUND_OFF_ULPS: f64 = 64.0;

/// The rods' length (m) and the gaps between the hanging balls (m), as
/// `scenes/newtons_cradle.toml` sets them.
pub(crate) const ROD: f64 = 1.0;
const GAP: f64 = 1e-9;

/// Impacts closer in time than this (s) belong to one chain: a chain lasts
/// a few 1e-9 s, successive chains are a half period (1 s) apart.
const CHAIN_GAP: f64 = 1e-3;

/// The impact chains of a run and its energy change (J).
struct Outcome {
    chains: Vec<Vec<ContactEvent>>,
    energy_change: f64,
    swing_energy: f64,
}

fn simulate(h: f64) -> Result<Outcome> {
    let scene = crate::scenes::load("newtons_cradle")?;
    let mut world = scene.build_world(None)?;
    let e0 = world.energy();
    world.run(scene.duration(), h)?;
    let mut chains: Vec<Vec<ContactEvent>> = Vec::new();
    for e in world
        .contact_events()
        .into_iter()
        .filter(|e| e.kind == ContactEventKind::Impact)
    {
        match chains.last_mut() {
            Some(chain) if e.t - chain[chain.len() - 1].t < CHAIN_GAP => chain.push(e),
            _ => chains.push(vec![e]),
        }
    }
    // The swing energy m g L (1 − cos 30°) from the start: the first
    // ball's height above the others'.
    let s = world.bodies();
    let start = scene.bodies()[0].state.position.y - scene.bodies()[1].state.position.y;
    let g = scene.gravity().map_or(0.0, |g| -g.y);
    Ok(Outcome {
        chains,
        energy_change: world.energy() - e0,
        swing_energy: s[0].mass * g * start,
    })
}

/// Runs `newtons_cradle`.
pub fn run() -> Result<CaseReport> {
    let scene = crate::scenes::load("newtons_cradle")?;
    let h = scene.dt();
    let run = simulate(h)?;
    let half = simulate(h / 2.0)?;
    if run.chains.is_empty() {
        bail!("newtons_cradle: no impact");
    }
    let mut report = CaseReport::default();
    let mut sink = RowSink {
        case: "newtons_cradle",
        method: "rk4",
        dt: h,
        rows: &mut report.rows,
    };
    // Five swings of about 2 s in 10 s: a chain every half period after
    // the first quarter.
    sink.at_least(
        RowKind::Criterion,
        "impact_chains",
        run.chains.len() as f64,
        9.0,
        0.0,
        format!(
            "a count against the motion's: the impact chains in {} s, one per half period \
             (T(30°) = 2.04 s) after the first quarter: at least 9",
            scene.duration()
        ),
    );
    let (mut worst_count, mut worst_pass, mut worst_stop) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut speed = 0.0_f64;
    for chain in &run.chains {
        worst_count = worst_count.max((chain.len() as f64 - 4.0).abs());
        let v0 = -chain[0].normal_velocity_before;
        speed = speed.max(v0);
        for e in chain {
            worst_pass = worst_pass.max((-e.normal_velocity_before - v0).abs() / v0);
            worst_stop = worst_stop.max((e.normal_velocity_after + e.normal_velocity_before).abs() / v0);
        }
    }
    sink.within(
        RowKind::Validation,
        "impacts_per_chain",
        worst_count,
        0.0,
        0.0,
        "a count against the motion's: the largest distance of a chain's number of impacts from \
         4 (ball 0 strikes 1, 1 strikes 2, ... 3 strikes 4, or back): one ball out for one in",
    );
    let ulps = ROUND_OFF_ULPS * f64::EPSILON;
    // The balls "at rest" are not quite: each chain leaves each of them up
    // to 4 gaps (4e-9 m) past its bottom, from which it swings back at up
    // to ω × 4 gaps; the next chain's approach speeds differ by that.
    let g = scene.gravity().map_or(0.0, |g| -g.y);
    let rest_speed = (g / ROD).sqrt() * 4.0 * GAP;
    let slowest = run
        .chains
        .iter()
        .map(|c| -c[0].normal_velocity_before)
        .fold(f64::INFINITY, f64::min);
    sink.within(
        RowKind::Validation,
        "speed_passed_on",
        worst_pass,
        0.0,
        rest_speed / slowest + ulps,
        format!(
            "measured against the exact exchange, with a derived bound: the largest relative \
             difference between an impact's approach speed and its chain's first ({slowest:.6} \
             to {speed:.6} m/s): with e = 1 and equal masses each struck ball leaves with the \
             striker's speed; the balls at rest before a chain move at up to \
             sqrt(g/L) x 4 gaps = {rest_speed:.2e} m/s (left past their bottoms by the gaps), \
             over the slowest chain's speed, + {ROUND_OFF_ULPS} ulps"
        ),
    );
    sink.within(
        RowKind::Consistency,
        "striker_stops",
        worst_stop,
        0.0,
        ulps,
        format!(
            "a consistency check of the impulse (the contact pipeline's own before and after \
             velocities, so weak evidence): the largest relative |v_after + v_before| of an \
             impact's normal velocities: e = 1 reverses the relative velocity, which with equal \
             masses leaves the striker at rest; {ROUND_OFF_ULPS} ulps. The independent evidence \
             of one out for one in is speed_passed_on: each next approach speed, measured after \
             the impulse and the joints' projection, is the first's"
        ),
    );
    // Round-off per step: an ulp of each ball's potential (height within
    // L of the origin) and kinetic energy (speed at most the striker's).
    let steps = (scene.duration() / h).round();
    let balls = scene.bodies().len() as f64;
    let per_step = balls * f64::EPSILON * (g * ROD + speed * speed);
    let walk = 3.0 * steps.sqrt() * per_step;
    let (de, de_half) = (
        run.energy_change / run.swing_energy,
        half.energy_change / half.swing_energy,
    );
    sink.within(
        RowKind::Consistency,
        "energy",
        de,
        0.0,
        RICHARDSON_FACTOR * richardson_error(de, de_half, 4).abs() + walk / run.swing_energy,
        format!(
            "measured against conservation, with a derived bound: the total energy after {} s \
             minus the start, over the swing energy {:.4} J (h/2: {de_half:+.3e}); e = 1 \
             impulses keep it to round-off, RK4 between them to its own error: tolerance 1.5 x \
             its step-doubling estimate (order 4) + the round-off of the steps, a random walk \
             of {steps} steps each rounding every ball's m g y and m v^2/2 by an ulp: three \
             standard deviations, 3 sqrt(steps) x {per_step:.1e} J = {walk:.1e} J",
            scene.duration(),
            run.swing_energy
        ),
    );
    report.notes.push(format!(
        "Exact model, RK4 at h = {h} s: {} impact chains of {} impacts each; energy change \
         {de:+.2e} of the swing energy. The soft step, rapier2d and Box2D on the same cradle \
         (scenes/newtons_cradle_soft.toml) follow.",
        run.chains.len(),
        run.chains
            .iter()
            .map(|c| c.len().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    ));
    super::newtons_cradle_engines::rows(&mut report)?;
    Ok(report)
}
