//! `bowl` (issue 19, `docs/cases.md#bowl`): a disc of radius r = 0.1 m
//! rolling without slipping inside a loop chain of N segments whose points
//! lie on a circle of radius R = 2 m (`scenes/bowl_<N>.toml`, N = 32, 128,
//! 512), released at rest θ₀ = 0.2 rad from the bottom. Its period, from
//! the crossings of the bottom (x = 0), is compared with the circle's,
//! T₀ (2/π) K(sin(θ₀/2)), T₀ = 2π √(3(R − r)/(2g)) (`references::bowl`).
//!
//! # Tolerance
//!
//! The polygon is not the circle: its error is derived by the polygon
//! model of `references::bowl` (the centre on straight pieces of apothem
//! R cos(π/N) − r, constant acceleration on each, the speed lost at each
//! join by a rigid rolling impact), |T_polygon − T_circle|, which falls
//! like 1/N² (docs/cases.md#bowl). Added to it, the soft step's own
//! errors:
//! - the contact's compliance: under the load m g the soft contact (its
//!   angular frequency ω_c against a static body) sinks by g/ω_c², which
//!   lengthens the pendulum 3(R − r)/2 by the same fraction as R − r:
//!   the period by half that fraction, T g/(2 ω_c² (R − r)); doubled for
//!   the centripetal load at the bottom (below g here: v²/(R − r) ≤ 2 g
//!   (1 − cos θ₀) = 0.4 g);
//! - the integration: symplectic Euler's phase error on an oscillation of
//!   angular frequency ω at substep h, T (ωh)²/24;
//! - the sampling: each crossing found by linear interpolation between
//!   steps, misplaced by at most dt³ ω²/8 (`crossing_error`), two
//!   crossings per period.
//!
//! # Rows
//!
//! Per N: the period against the circle's (validation, tolerance the
//! polygon's error plus the soft step's); then convergence: the error at
//! N = 128 at most that at N = 32, and at N = 512 at most that at 128
//! plus the soft step's error (it must approach the closed form as N grows).

use super::joint_common::{crossing_error, crossings};
use super::soft_step_common::SoftRun;
use super::{Case, CaseReport, Snapshots};
use crate::row::RowKind;
use anyhow::{Result, bail};
use references::bowl::PolygonBowl;

/// The three bowls.
pub const CASE: Case = Case {
    scenes: &["bowl_32", "bowl_128", "bowl_512"],
    snapshots: Snapshots::HarnessOnly(
        "not for its weight (three short runs) but because one of its rows fails, an open \
         finding of issue 19 (docs/cases.md#bowl): at N = 32 the soft step loses more speed \
         at each join than the rigid polygon model (an error of its impacts that shrinks \
         with dt but is not derived), and the period is shorter than the polygon's error \
         allows. harness/tests/chain_cases.rs runs it: the other rows pass and exactly that \
         one fails",
    ),
    ..Case::new(
        "bowl",
        "Chains: a disc rolling inside a loop of N segments on a circle: period 2π√(3(R − r)/(2g)) as N grows",
        run,
    )
};

/// The segment counts, one scene each.
pub const SIDES: [usize; 3] = [32, 128, 512];

/// Bowl radius R (m), disc radius r (m), release angle θ₀ (rad): those of
/// the scene files (their comments say so).
const BOWL_RADIUS: f64 = 2.0;
const DISC_RADIUS: f64 = 0.1;
const RELEASE: f64 = 0.2;

/// Runs `bowl`.
pub fn run() -> Result<CaseReport> {
    let mut report = CaseReport::default();
    let mut errors = Vec::new();
    for sides in SIDES {
        let id = format!("bowl_{sides}");
        let run = SoftRun::new(&id)?;
        let disc = run.body("disc")?;
        let g = -run.scene.gravity().map_or(0.0, |v| v.y);
        let model = PolygonBowl {
            bowl_radius: BOWL_RADIUS,
            disc_radius: DISC_RADIUS,
            sides,
            gravity: g,
            release: RELEASE,
        };
        // The scene's release point must be the model's.
        let start = run.trace.samples[0].states[disc].position;
        let [mx, my] = model.release_position();
        if (start.x - mx).abs() > 1e-9 || (start.y - my).abs() > 1e-9 {
            bail!("{id}: the disc starts at {start:?}, not at the model's [{mx}, {my}]");
        }
        let dt = run.scene.dt();
        let h = run.substep();
        let xs: Vec<f64> = run
            .trace
            .samples
            .iter()
            .map(|s| s.states[disc].position.x)
            .collect();
        let c = crossings(&xs, dt);
        if c.len() < 4 {
            bail!("{id}: {} crossings of the bottom in the run", c.len());
        }
        // Two periods' worth of crossings, averaged: (t3 − t1 + t4 − t2)/2.
        let period = 0.5 * ((c[2] - c[0]) + (c[3] - c[1]));
        let circle = model.circle_period();
        let m = model.crossings(4, 100.0);
        let polygon = 0.5 * ((m[2] - m[0]) + (m[3] - m[1]));
        let polygon_error = (polygon - circle).abs();
        let omega = 2.0 * std::f64::consts::PI / circle;
        let omega_c = run.omega(true);
        let compliance = circle * 2.0 * g / (2.0 * omega_c * omega_c * (BOWL_RADIUS - DISC_RADIUS));
        let integration = circle * (omega * h).powi(2) / 24.0;
        let sampling = 2.0 * crossing_error(dt, omega * omega);
        let soft = compliance + integration + sampling;
        let mut rows = run.sink("bowl", &mut report.rows);
        rows.within(
            RowKind::Validation,
            &format!("period_n{sides}"),
            period,
            circle,
            polygon_error + soft,
            format!(
                "validation against the circle's period T0 (2/π) K(sin(θ0/2)) = {circle:.6} s \
                 (T0 = 2π √(3(R − r)/(2g)) = {:.6} s, θ0 = {RELEASE} rad), the mean of two \
                 periods from the crossings of the bottom. Tolerance: the polygon's error \
                 |T_polygon − T_circle| = {polygon_error:.3e} s (T_polygon = {polygon:.6} s, \
                 references::bowl) plus the soft step's: compliance {compliance:.1e} s, \
                 integration {integration:.1e} s, sampling {sampling:.1e} s \
                 (docs/cases.md#bowl)",
                model.small_oscillation_period()
            ),
        );
        errors.push(((period - circle).abs(), soft));
    }
    let mut rows = report_sink(&mut report.rows);
    for k in 1..errors.len() {
        let ((coarse, _), (fine, soft)) = (errors[k - 1], errors[k]);
        rows.at_most(
            RowKind::Validation,
            &format!("converges_n{}", SIDES[k]),
            fine,
            coarse,
            soft,
            format!(
                "convergence: the period's error at N = {} is at most that at N = {} plus the \
                 soft step's own error at N = {} ({soft:.1e} s): the polygon's error falls like \
                 1/N² (docs/cases.md#bowl)",
                SIDES[k],
                SIDES[k - 1],
                SIDES[k]
            ),
        );
    }
    Ok(report)
}

fn report_sink(rows: &mut Vec<crate::row::Row>) -> crate::row::RowSink<'_> {
    crate::row::RowSink {
        case: "bowl",
        method: super::soft_step_common::SOFT_STEP,
        dt: 1.0 / 60.0,
        rows,
    }
}
