//! `pendulum_wall` (`docs/cases.md#pendulum_wall`): a pendulum striking a
//! wall at its lowest point with restitution e, under the exact model, the
//! contact impulse solved with the joint held (`docs/joints.md`, "Impacts
//! on jointed bodies"); `scenes/pendulum_wall.toml`.
//!
//! # The closed form
//!
//! A rigid body on a revolute joint has one degree of freedom, its angle
//! θ. The wall touches the disc when θ = 0, at the height of its centre,
//! L = 1 m below the pivot, the normal horizontal: the contact's normal
//! velocity is L θ', so an impulse with restitution e (normal velocity
//! reversed and scaled by e, the joint held) maps θ' to −e θ', whatever
//! the body's inertia. Energy is conserved between the release and the
//! impact and from the impact to the rebound's apex, and the impact is at
//! the bottom, so
//!
//! ```text
//! 1 − cos θr = e² (1 − cos θ0),
//! ```
//!
//! with 1 − cos θ = y/L, y the centre's height above the hanging one. An
//! impulse solved as if the disc were free and then projected onto the
//! joint (the model before this case) gives θ' → (I_cm − e m L²)/(I_cm +
//! m L²) θ' instead: at e = 1, 1 − cos θr = 0.99005² × 0.5, 1e-2 off.
//!
//! # The tolerances
//!
//! - **Fixed-step methods**: [`RICHARDSON_FACTOR`] × the step-doubling
//!   estimate of the method's own error (the same run at h/2, at its
//!   order), plus the round-off floor [`round_off_floor`]: the height is a
//!   coordinate of order 1 m kept on the joint by the projection to
//!   [`RESIDUAL_ULPS`] ulps, and the energy's round-off walks three
//!   standard deviations of √steps ulps. The impact is located within
//!   ±ε = 1e-10 m of touching, an angle δ ≤ ε/L off the bottom; that moves
//!   1 − cos θr by (1 − e²) δ²/2 ≤ 5e-21, below the floor.
//! - **Dormand–Prince** at rtol = atol = [`DP_TOLERANCE`]: the sum of its
//!   accepted steps' local errors ([`dp_global_bound`]) plus the floor.
//! - **e = 0**: no rebound; the disc's largest height after the impact,
//!   L (1 − cos θ), against 0 within the same bounds (a disc left at rest
//!   against the wall by the impulse stays there, the wall's contact force
//!   holding it).
//! - **The impulse itself**: the contact event's normal velocity after
//!   over before, −e, to round-off (a consistency row: the pipeline's own
//!   numbers).

use super::{Case, CaseReport, DP_TOLERANCE, Snapshots, dp_global_bound};
use crate::row::{RowKind, RowSink};
use crate::tolerance::{RICHARDSON_FACTOR, richardson_error};
use anyhow::{Context, Result, bail};
use engine::{ContactEventKind, ContactSettings, Method, Tolerance, World};

/// A pendulum striking a wall at several restitutions and methods.
pub const CASE: Case = Case {
    scenes: &["pendulum_wall"],
    snapshots: Snapshots::HarnessOnly(
        "twelve runs of 0.6 to 2 s (three restitutions, four methods, each at h and h/2); \
         engine/tests/exact_joints.rs checks a reduced run: the impact of a pinned disc on a \
         wall at e = 0, 0.5 and 1",
    ),
    ..Case::new(
        "pendulum_wall",
        "Joints and impacts: a pendulum striking a wall with restitution e, the rebound against 1 - cos θr = e² (1 - cos θ0)",
        run,
    )
};

/// The restitutions run.
pub const RESTITUTIONS: [f64; 3] = [0.0, 0.5, 1.0];

/// Ulps of the coordinates the projection leaves on the joint (as the
/// `pendulum` case's exact rows measure it).
pub const RESIDUAL_ULPS: f64 = 8.0;

/// Ulps the impulse's few operations may move a normal velocity by.
pub const IMPULSE_ULPS: f64 = 16.0;

/// The methods and their steps (s): small enough that each is in its
/// asymptotic range over one swing (errors well below the 0.5 m height),
/// with the finest step's error still far above round-off.
pub fn methods() -> Vec<(Method, f64)> {
    vec![
        (Method::Rk4, 1e-3),
        (Method::Midpoint, 2e-4),
        (Method::VelocityVerlet, 2e-4),
        (Method::DormandPrince(Tolerance::uniform(DP_TOLERANCE)), 1e-2),
    ]
}

/// The round-off floor (m) of a height after `steps` steps: see the
/// module docs.
pub fn round_off_floor(steps: f64) -> f64 {
    (RESIDUAL_ULPS + 3.0 * steps.sqrt()) * f64::EPSILON
}

/// What one run measures.
struct Rebound {
    /// The height (m) of the rebound's first apex above the hanging
    /// centre, or the largest height after the impact when e = 0.
    height: f64,
    /// Normal velocity after over before of the impact.
    ratio: f64,
    /// Integrator steps.
    steps: u64,
}

fn simulate(method: Method, h: f64, e: f64) -> Result<Rebound> {
    let scene = crate::scenes::load("pendulum_wall")?;
    let mut world: World = scene.build_world(Some(method))?;
    world.set_contact_settings(ContactSettings {
        restitution: e,
        ..world.contact_settings()
    })?;
    let bottom = 0.0;
    let trace = world.run(scene.duration(), h)?;
    let impact = world
        .contact_events()
        .into_iter()
        .find(|c| c.kind == ContactEventKind::Impact)
        .context("pendulum_wall: no impact")?;
    let ratio = impact.normal_velocity_after / impact.normal_velocity_before;
    let height = if e > 0.0 {
        let apex = trace
            .events
            .iter()
            .find(|a| a.t > impact.t)
            .context("pendulum_wall: no apex after the impact")?;
        apex.states[0].position.y - bottom
    } else {
        trace
            .samples
            .iter()
            .filter(|s| s.t > impact.t)
            .map(|s| s.states[0].position.y - bottom)
            .fold(0.0, f64::max)
    };
    Ok(Rebound {
        height,
        ratio,
        steps: trace.stats.steps,
    })
}

/// Runs `pendulum_wall`.
pub fn run() -> Result<CaseReport> {
    let scene = crate::scenes::load("pendulum_wall")?;
    let start = scene.bodies()[0].state.position;
    let pivot_height = 1.0;
    let arm = (start - nalgebra::Vector2::new(0.0, pivot_height)).norm();
    if (arm - 1.0).abs() > 1e-12 {
        bail!("pendulum_wall.toml: the disc is {arm} m from the pivot, not 1 m");
    }
    // 1 − cos θ0 from the release height (the hanging centre at y = 0).
    let drop = start.y;
    let mut report = CaseReport::default();
    let mut notes = Vec::new();
    for (method, h) in methods() {
        let adaptive = matches!(method, Method::DormandPrince(_));
        let mut line = Vec::new();
        for e in RESTITUTIONS {
            let run = simulate(method, h, e)?;
            let expected = e * e * drop;
            let floor = round_off_floor(run.steps as f64);
            let (tolerance, why) = if adaptive {
                let bound = dp_global_bound(run.steps, 1.0);
                (
                    bound + floor,
                    format!(
                        "Dormand-Prince rtol = atol = {DP_TOLERANCE:e}: the sum of its {} \
                         accepted steps' local errors, each <= tol x max|y| (<= 1 m), {bound:.1e} \
                         m, + the round-off floor {floor:.1e} m",
                        run.steps
                    ),
                )
            } else {
                let half = simulate(method, h / 2.0, e)?;
                let order = method.order();
                let estimate = richardson_error(run.height, half.height, order).abs();
                (
                    RICHARDSON_FACTOR * estimate + floor,
                    format!(
                        "{RICHARDSON_FACTOR} x the step-doubling estimate of the order-{order} \
                         error (h/2: {:.12} m), {estimate:.1e} m, + the round-off floor \
                         {floor:.1e} m ({RESIDUAL_ULPS} ulps of the projection + 3 sqrt({}) \
                         ulps of the steps)",
                        half.height, run.steps
                    ),
                )
            };
            let mut sink = RowSink {
                case: "pendulum_wall",
                method: method.id(),
                dt: h,
                rows: &mut report.rows,
            };
            let contrast = if e > 0.0 {
                format!(
                    "; a free impulse projected onto the joint would give {:.6} m",
                    (free_then_projected(e)).powi(2) * drop
                )
            } else {
                String::new()
            };
            let what = if e > 0.0 {
                "the height of the rebound's first apex (located inside its step by the \
                 root finder) above the hanging centre, L (1 - cos θr)"
            } else {
                "the largest height of the disc's centre after the impact (no rebound)"
            };
            sink.within(
                RowKind::Validation,
                &format!("rebound_e{e}"),
                run.height,
                expected,
                tolerance,
                format!(
                    "measured against a closed form: {what}, m, against e^2 L (1 - cos θ0) = \
                     {e}^2 x {drop:.6} m (one degree of freedom: the impulse with the joint held \
                     maps θ' to -e θ'{contrast}); tolerance {why}"
                ),
            );
            sink.within(
                RowKind::Consistency,
                &format!("restitution_e{e}"),
                run.ratio,
                -e,
                IMPULSE_ULPS * f64::EPSILON,
                format!(
                    "the impulse's own numbers (the contact event's normal velocity after over \
                     before, the joint held through the solve): -e to {IMPULSE_ULPS} ulps"
                ),
            );
            line.push(format!(
                "e = {e}: {:.12} m against {expected:.12} m",
                run.height
            ));
        }
        notes.push(format!("{} at h = {h} s: {}", method.id(), line.join("; ")));
    }
    report.notes.push(format!(
        "Rebound heights L (1 - cos θr) of the disc released from {drop:.6} m: {}.",
        notes.join(". ")
    ));
    Ok(report)
}

/// θ' after over before when the impulse is solved as if the disc were
/// free and the velocities then projected onto the joint (the model before
/// the constrained impact): (I_cm − e m L²)/(I_cm + m L²) for the scene's
/// disc (m = 1 kg, r = 0.1 m, L = 1 m), its magnitude.
fn free_then_projected(e: f64) -> f64 {
    let (m, r, l) = (1.0, 0.1, 1.0);
    let inertia = 0.5 * m * r * r;
    ((inertia - e * m * l * l) / (inertia + m * l * l)).abs()
}
