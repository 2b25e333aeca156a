//! The exact model's rows of `double_pendulum` (`docs/cases.md#double_pendulum`):
//! the two bars of `scenes/double_pendulum.toml` in an exact-model world,
//! their revolute joints constraints of the equations of motion
//! (`docs/joints.md`, "Joints under the exact model"), RK4 at
//! h = [`H`], against the DOP853 reference up to the horizon that the
//! chaos leaves the comparison, at least five times the soft step's.
//!
//! # The horizon
//!
//! Two solutions known to δ0 part by 1e-3 rad at
//! `DoublePendulum::divergence_time(δ0)`. Here δ0 is the larger of the
//! exact model's own angle error at the first compared time, 0.5 s (RK4's
//! global error gathered before the chaos amplifies it: its error after
//! one step, 1e-17 rad, would promise a horizon its accumulated error does
//! not keep), and the reference's local tolerance
//! [`DOUBLE_PENDULUM_TOLERANCE`] (the comparison cannot see further than
//! the reference's own error carries).
//!
//! # Tolerances
//!
//! The comparison also stops at the first compared time whose measured
//! angle error reaches the same 1e-3 rad ([`DIVERGENCE_THRESHOLD`]): the
//! estimate of divergence_time perturbs both angles alike, which the
//! motion need not amplify as fast as RK4's own error.
//!
//! Each state component at every 0.5 s before the horizon within
//! [`RICHARDSON_FACTOR`] × the step-doubling estimate of RK4's own error
//! (the same world at h/2, order 4) plus the reference's error, estimated
//! here as its difference from the same solve at [`CHECK_TOLERANCE`] (ten
//! times looser: an upper estimate of the tight solve's error; the case's
//! own estimate, from a solve at 1e-10, exceeds a radian past 6 s).

use super::double_pendulum::{COMPONENTS, errors, state_at, trim};
use super::joint_common::{JointScene, Run};
use crate::row::{RowKind, RowSink};
use crate::tolerance::{RICHARDSON_FACTOR, richardson_error};
use anyhow::Result;
use engine::prelude::{Method, World};
use references::double_pendulum::{
    DIVERGENCE_THRESHOLD, DOUBLE_PENDULUM_TOLERANCE, DoublePendulum, PendulumState,
};
use references::many_body::BodySample;

/// The exact model's step (s).
pub const H: f64 = 1e-3;
/// The tolerance of the solve that estimates the reference's error.
pub const CHECK_TOLERANCE: f64 = 1e-12;
/// Interval of the compared times (s).
const EVERY: f64 = 0.5;

/// The scene's bars in an exact-model world under RK4 at `h`, run to
/// `until` (s), every step sampled.
fn exact_run(js: &JointScene, h: f64, until: f64) -> Result<Run> {
    let scene = &js.scene;
    let mut world = World::new(Method::Rk4)?;
    if let Some(g) = scene.gravity() {
        world.set_gravity(g)?;
    }
    for def in scene.bodies() {
        world.add_body(def.clone())?;
    }
    for def in scene.joints() {
        world.add_joint(def.clone())?;
    }
    let trace = world.run(until, h)?;
    let samples = trace
        .samples
        .iter()
        .map(|s| {
            s.states
                .iter()
                .map(|b| BodySample {
                    position: [b.position.x, b.position.y],
                    angle: b.angle,
                    velocity: [b.velocity.x, b.velocity.y],
                    angular_velocity: b.angular_velocity,
                })
                .collect()
        })
        .collect();
    Ok(Run {
        dt: h,
        samples,
        seconds: 0.0,
    })
}

/// Adds the exact model's rows to `rows` of `report`: the states every
/// 0.5 s up to its horizon, and the horizon against five times the soft
/// step's `soft_horizon` (s). Returns a note.
pub fn rows(
    js: &JointScene,
    (pendulum, initial): (&DoublePendulum, PendulumState),
    bodies: [usize; 2],
    soft_horizon: f64,
    limit: f64,
    report_rows: &mut Vec<crate::row::Row>,
) -> Result<String> {
    let first = pendulum.states_at(initial, &[EVERY], DOUBLE_PENDULUM_TOLERANCE)?[0];
    let probe = exact_run(js, H, EVERY)?;
    let early = state_at(&probe, bodies, EVERY)?;
    let own = (early[0] - first.angles[0])
        .abs()
        .max((early[1] - first.angles[1]).abs());
    let delta0 = own.max(DOUBLE_PENDULUM_TOLERANCE);
    let horizon = pendulum
        .divergence_time(initial, delta0, limit)?
        .unwrap_or(limit);
    let count = ((horizon / EVERY).floor() as usize).max(1);
    let times: Vec<f64> = (1..=count).map(|k| k as f64 * EVERY).collect();
    let tight = pendulum.solve(initial, &times)?;
    let check = pendulum.states_at(initial, &times, CHECK_TOLERANCE)?;
    let until = times[times.len() - 1];
    let run = exact_run(js, H, until)?;
    let half = exact_run(js, H / 2.0, until)?;
    let mut sink = RowSink {
        case: "double_pendulum",
        method: Method::Rk4.id(),
        dt: H,
        rows: report_rows,
    };
    let mut largest = 0.0_f64;
    let mut compared = 0.0;
    for (r, c) in tight.iter().zip(&check) {
        let e = errors(state_at(&run, bodies, r.time)?, r);
        let e2 = errors(state_at(&half, bodies, r.time)?, r);
        // Past a measured angle error of 1e-3 rad the chaos, not the
        // method, sets the difference: the comparison stops there too.
        if e[0].abs().max(e[1].abs()) >= DIVERGENCE_THRESHOLD {
            break;
        }
        compared = r.time;
        let reference_error = (0..2)
            .map(|i| {
                (r.state.angles[i] - c.angles[i])
                    .abs()
                    .max((r.state.rates[i] - c.rates[i]).abs())
            })
            .fold(0.0, f64::max);
        for (i, (name, unit)) in COMPONENTS.iter().enumerate() {
            largest = largest.max(e[i].abs());
            let t = r.time;
            sink.within(
                RowKind::Consistency,
                &format!("exact_{name}_{}s", trim(t)),
                e[i],
                0.0,
                RICHARDSON_FACTOR * richardson_error(e[i], e2[i], 4).abs() + reference_error,
                format!(
                    "measured against a numerical reference (DOP853 at 1e-13), with a derived \
                     bound: the exact model (revolute joints as constraints, RK4 at h = {H:e} s) \
                     at t = {t} s minus the reference ({unit}; at h/2: {:+.3e}). Tolerance: \
                     1.5 x the step-doubling estimate of RK4's own error (order 4) plus the \
                     reference's error, its difference from the solve at {CHECK_TOLERANCE:e} \
                     ({reference_error:.1e}). t is before the horizon {horizon:.2} s",
                    e2[i]
                ),
            );
        }
    }
    sink.at_least(
        RowKind::Criterion,
        "exact_horizon",
        compared,
        5.0 * soft_horizon,
        0.0,
        format!(
            "a measured horizon against the issue's requirement: the last time at which the \
             exact model is compared with the reference (every {EVERY} s, while its angle errors \
             stay below {DIVERGENCE_THRESHOLD:e} rad and before divergence_time(δ0 = \
             {delta0:.1e} rad: the larger of its own error at {EVERY} s, {own:.1e} rad, and the \
             reference's tolerance) = {horizon:.2} s), at least five times the soft step's \
             {soft_horizon:.2} s"
        ),
    );
    Ok(format!(
        "Exact model (revolute joints as constraints, RK4 at h = {H:e} s): compared with the \
         reference every {EVERY} s up to {compared} s ({:.1} times the soft step's horizon), \
         largest error {largest:.2e}.",
        compared / soft_horizon
    ))
}
