//! `slider_crank` (`docs/cases.md#slider_crank`): a crank of radius
//! r = 0.5 m turned about the world origin at a prescribed ω = 2π rad/s, a
//! rod of l = 1.5 m from the crank pin to a slider on the x axis (a
//! prismatic joint), no gravity, ten turns (`scenes/slider_crank_exact.toml`,
//! the exact model, its crank a driven revolute: the rheonomic row
//! θ − ω t = 0 of `docs/joints.md`; `scenes/slider_crank.toml`, the soft
//! step, its crank driven by a motor of unbounded torque).
//!
//! # The closed form
//!
//! The mechanism has no degree of freedom left: the slider's centre is at
//! x(θ) = r cos θ + sqrt(l² − r² sin² θ), θ = ω t, at every instant.
//!
//! # Rows, and their tolerances
//!
//! - **exact_<method>** (validation): the largest |x_sim − x(ω t)| over the
//!   steps of the run. Fixed steps: [`RICHARDSON_FACTOR`] × the
//!   step-doubling estimate (the largest difference of the runs at h and
//!   h/2 over their common times, over 1 − 2^−p) plus the round-off floor
//!   of `pendulum_wall` ([`round_off_floor`], scaled to the slider's 2 m
//!   coordinate). Dormand–Prince: the sum of its local errors
//!   ([`dp_global_bound`], max|y| taken as ω (r + l), the largest speed
//!   bound, above the 2 m positions) plus the floor.
//! - **soft_step_linkage** (validation, first order): under the soft step
//!   at its scene's 60 Hz, the largest |x_sim − x(θ_sim)|, θ_sim the
//!   crank's own angle (its phase drifts, below, so x(ω t) is not a
//!   first-order target), within [`RICHARDSON_FACTOR`] × its first-order
//!   step-doubling estimate (the run at h/2) plus the floor.
//!
//! # The soft step's crank phase (notes, not a row)
//!
//! θ_sim − ω t at the end, θ_sim the crank body's angle (the soft step
//! never wraps a body's angle: `harness simulate` prints the same one).
//! The motor of unbounded torque is a velocity row solved before the
//! point rows in every pass (Box2D's order); the rows after it change the
//! crank's ω again by their angular impulse over the crank's inertia, and
//! nothing holds the angle, so the phase wanders by what those impulses
//! leave: the smaller the crank's inertia, the more (a 5 cm disc for a
//! crank drifts by turns in ten turns; the scene's bar by a fraction of a
//! radian). It is printed at h, h/2 and h/4 and not held: it does not
//! fall at first order with h, because the joints' stiffness stays at
//! 60 Hz (min(60 Hz, 1/(4 h_sub))) as h shrinks, so the soft step tends to
//! a compliant mechanism, not to the rigid one whose phase is 0.

use super::pendulum_wall::round_off_floor;
use super::{Case, CaseReport, DP_TOLERANCE, Snapshots, dp_global_bound};
use crate::row::{RowKind, RowSink};
use crate::tolerance::{RICHARDSON_FACTOR, richardson_error};
use anyhow::{Result, bail};
use engine::{Method, Tolerance};
use std::f64::consts::PI;

/// A driven slider-crank against its closed-form kinematics.
pub const CASE: Case = Case {
    scenes: &["slider_crank", "slider_crank_exact"],
    snapshots: Snapshots::HarnessOnly(
        "exact and soft runs at h and h/2: harness/tests/joint_cases.rs runs it whole",
    ),
    ..Case::new(
        "slider_crank",
        "Joints: a slider-crank driven at constant crank speed, the slider against x = r cos θ + sqrt(l² - r² sin² θ)",
        run,
    )
};

/// Crank radius r (m), rod length l (m), crank speed ω (rad/s): the scenes'.
pub const R: f64 = 0.5;
/// Rod length (m).
pub const L: f64 = 1.5;
/// Crank speed (rad/s): one turn a second.
pub const OMEGA: f64 = 2.0 * PI;

/// The slider's x (m) at crank angle θ (rad).
pub fn slider_x(theta: f64) -> f64 {
    let s = theta.sin();
    R * theta.cos() + (L * L - R * R * s * s).sqrt()
}

/// One run: the slider's x at each step's end (with its time), and the
/// integrator's steps.
struct Run {
    xs: Vec<(f64, f64)>,
    /// The crank's angle (rad) at each step's end.
    crank: Vec<f64>,
    /// The crank's moment of inertia about its centre (kg·m²).
    crank_inertia: f64,
    steps: u64,
}

impl Run {
    /// The largest |x_sim − x(ω t)| (m).
    fn error(&self) -> f64 {
        self.xs
            .iter()
            .map(|(t, x)| (x - slider_x(OMEGA * t)).abs())
            .fold(0.0, f64::max)
    }

    /// The largest |x_sim − x(θ_sim)| (m), θ_sim the crank's simulated
    /// angle: the joints' error apart from the crank's phase.
    fn linkage_error(&self) -> f64 {
        self.xs
            .iter()
            .zip(&self.crank)
            .map(|((_, x), th)| (x - slider_x(*th)).abs())
            .fold(0.0, f64::max)
    }

    /// The crank's phase error θ_sim − ω t (rad) at the end.
    fn phase_error(&self) -> f64 {
        let (t, _) = self.xs[self.xs.len() - 1];
        self.crank[self.crank.len() - 1] - OMEGA * t
    }

    /// The largest |x_h − x_{h/2}| at the common times (`half` at h/2).
    fn difference(&self, half: &Run) -> f64 {
        debug_assert!(half.xs.len() == 2 * self.xs.len() - 1);
        self.xs
            .iter()
            .enumerate()
            .map(|(k, (_, x))| (x - half.xs[2 * k].1).abs())
            .fold(0.0, f64::max)
    }

    /// The largest change of the linkage error |x − x(θ_sim)| from h to
    /// h/2 at the common times.
    fn linkage_difference(&self, half: &Run) -> f64 {
        self.xs
            .iter()
            .zip(&self.crank)
            .enumerate()
            .map(|(k, ((_, x), th))| {
                let e = x - slider_x(*th);
                let e_half = half.xs[2 * k].1 - slider_x(half.crank[2 * k]);
                (e - e_half).abs()
            })
            .fold(0.0, f64::max)
    }
}

fn simulate(scene_id: &str, method: Option<Method>, h: f64) -> Result<Run> {
    let scene = crate::scenes::load(scene_id)?;
    let mut world = scene.build_world(method)?;
    let slider = 2;
    let [crank, rod, body] = [0, 1, slider].map(|b| scene.bodies()[b].name.as_str());
    if [crank, rod, body] != ["crank", "rod", "slider"] {
        bail!("{scene_id}.toml: bodies {crank}, {rod}, {body}, not crank, rod, slider");
    }
    let start = scene.bodies()[slider].state.position.x;
    if (start - slider_x(0.0)).abs() > 1e-15 {
        bail!("{scene_id}.toml: the slider starts at {start} m, not r + l");
    }
    let trace = world.run(scene.duration(), h)?;
    Ok(Run {
        xs: trace
            .samples
            .iter()
            .map(|s| (s.t, s.states[slider].position.x))
            .collect(),
        crank: trace.samples.iter().map(|s| s.states[0].angle).collect(),
        crank_inertia: world.bodies()[0].inertia.unwrap_or(f64::NAN),
        steps: trace.stats.steps,
    })
}

/// Runs `slider_crank`.
pub fn run() -> Result<CaseReport> {
    let mut report = CaseReport::default();
    let scale = R + L;
    let mut notes = Vec::new();
    let exact: [(Method, f64); 2] = [
        (Method::Rk4, 1e-3),
        (Method::DormandPrince(Tolerance::uniform(DP_TOLERANCE)), 1e-2),
    ];
    for (method, h) in exact {
        let run = simulate("slider_crank_exact", Some(method), h)?;
        let error = run.error();
        let floor = scale * round_off_floor(run.steps as f64);
        let (tolerance, why) = if matches!(method, Method::DormandPrince(_)) {
            // max|y|: positions ≤ 2 m, speeds ≤ ω (r + l) ≈ 12.6 m/s.
            let bound = dp_global_bound(run.steps, OMEGA * scale);
            (
                bound + floor,
                format!(
                    "Dormand-Prince rtol = atol = {DP_TOLERANCE:e}: the sum of its {} accepted \
                     steps' local errors, each <= tol x max|y| (<= ω (r + l) = {:.2}), {bound:.1e} \
                     m, + the round-off floor {floor:.1e} m",
                    run.steps,
                    OMEGA * scale
                ),
            )
        } else {
            let half = simulate("slider_crank_exact", Some(method), h / 2.0)?;
            let order = method.order();
            let estimate = richardson_error(run.difference(&half), 0.0, order).abs();
            (
                RICHARDSON_FACTOR * estimate + floor,
                format!(
                    "{RICHARDSON_FACTOR} x the step-doubling estimate of the order-{order} error \
                     (largest |x_h - x_h/2| / (1 - 2^-{order})), {estimate:.1e} m, + the round-off \
                     floor {floor:.1e} m (pendulum_wall's, in ulps of the 2 m coordinate, {} steps)",
                    run.steps
                ),
            )
        };
        RowSink {
            case: "slider_crank",
            method: method.id(),
            dt: h,
            rows: &mut report.rows,
        }
        .within(
            RowKind::Validation,
            &format!("exact_{}", method.id()),
            error,
            0.0,
            tolerance,
            format!(
                "measured against a closed form: the largest |x_sim - x(ω t)| (m) of the slider \
                 over ten turns, the exact model with the crank's angle prescribed (a rheonomic \
                 row); tolerance {why}"
            ),
        );
        notes.push(format!(
            "exact model, {} at h = {h} s: {error:.3e} m",
            method.id()
        ));
    }
    // The soft step at its scene's step and at half of it (first order).
    let scene = crate::scenes::load("slider_crank")?;
    let h = scene.dt();
    let soft = simulate("slider_crank", None, h)?;
    let soft_half = simulate("slider_crank", None, h / 2.0)?;
    let soft_quarter = simulate("slider_crank", None, h / 4.0)?;
    // Against x at the soft step's own crank angle: its crank's phase
    // drifts (module docs), which is reported, not held.
    let error = soft.linkage_error();
    let estimate = richardson_error(soft.linkage_difference(&soft_half), 0.0, 1).abs();
    let floor = scale * round_off_floor(soft.steps as f64);
    RowSink {
        case: "slider_crank",
        method: "soft_step",
        dt: h,
        rows: &mut report.rows,
    }
    .within(
        RowKind::Validation,
        "soft_step_linkage",
        error,
        0.0,
        RICHARDSON_FACTOR * estimate + floor,
        format!(
            "measured against a closed form: the largest |x_sim - x(θ_sim)| (m) of the slider \
             over ten turns, θ_sim the crank's own angle, the soft step (first order; h/2: \
             {:.3e} m); tolerance {RICHARDSON_FACTOR} x the first-order step-doubling estimate \
             (largest change of x - x(θ_sim) from h to h/2, over 1/2), {estimate:.1e} m, + the \
             round-off floor {floor:.1e} m",
            soft_half.linkage_error()
        ),
    );
    let crank_inertia = soft.crank_inertia;
    notes.push(format!(
        "soft step at h = {h:.6} s: {:.3e} m against x(ω t), {error:.3e} m against x(θ_sim) \
         (h/2: {:.3e} m); its crank's phase θ_sim - ω t at the end (θ_sim the crank body's \
         angle, never wrapped) {:.4} rad (h/2: {:.4} rad, h/4: {:.4} rad): the motor row is \
         solved before the point rows, which change the crank's ω again by their impulses over \
         its inertia ({crank_inertia:.4e} kg m²), and no row holds the angle; not a first-order \
         error (the joints stay at 60 Hz as h shrinks: the soft step tends to a compliant \
         mechanism), so reported, not held",
        soft.error(),
        soft_half.linkage_error(),
        soft.phase_error(),
        soft_half.phase_error(),
        soft_quarter.phase_error()
    ));
    report.notes.push(format!(
        "Largest slider error against x(ω t) over ten turns: {}.",
        notes.join("; ")
    ));
    Ok(report)
}
