//! `double_pendulum` (`docs/cases.md#double_pendulum`): two uniform bars
//! on revolute joints (`scenes/double_pendulum.toml`), released at rest
//! horizontal. Their angles and angular velocities at short times against
//! the references' DOP853 solve of the Lagrangian equations of two rigid
//! bodies with inertia (`references::double_pendulum`, rtol = atol =
//! 1e-13, its error estimated by a second solve at 1e-10), up to the
//! horizon the chaos leaves; and the energy over the whole run.
//!
//! # Tolerances
//!
//! The soft step's state errs at first order in h: its positions are
//! Störmer–Verlet's from a start half a kick later (an O(h) shift of the
//! initial velocities that the motion carries along), and its joints'
//! sink and drift add O(h²). Each row allows [`RICHARDSON_FACTOR`] × the
//! step-doubling estimate of the soft step's own error at order 1, from
//! the same scene at h/2 with its joints at 1/(4 h/2) Hz (the defaults'
//! family, as in `pendulum`), plus the reference's own error estimate.
//! Measured, the errors at 0.5 s halve per halving (2.0 and 2.04 times).
//!
//! # The horizon
//!
//! The motion from two bars released horizontal is chaotic: a reference
//! solution known to δ0 predicts the motion to 1e-3 rad only up to
//! `DoublePendulum::divergence_time(δ0)`. δ0 is the soft step's own error
//! after its first step (its local error, which the motion then
//! amplifies); the rows compare the states at every half second before
//! that time. Box2D and rapier2d are reported at the same times. The
//! exact model's rows ([`double_pendulum_exact`], full run only) go to
//! its own, longer horizon.

use super::joint_common::{Config, Engine, JointScene, Run, steps};
use super::{Case, CaseReport, Headline, Snapshots, double_pendulum_exact};
use crate::row::{RowKind, RowSink};
use crate::tolerance::{RICHARDSON_FACTOR, richardson_error};
use anyhow::{Result, bail};
use engine::Shape;
use references::double_pendulum::{DoublePendulum, PendulumState, ReferencePoint};
use references::pendulum::polygon_area_moment;
use std::f64::consts::PI;

/// Two bars on revolute joints.
pub const CASE: Case = Case {
    scenes: &["double_pendulum"],
    snapshots: Snapshots::HarnessOnly(
        "20 s in three engines with a chaos horizon search; harness/tests/joint_cases.rs checks \
         a reduced run (the soft step alone, its energy over 5 s) with the same rows",
    ),
    headline: &[Headline::new("upper_angle_1s", "soft_step")],
    ..Case::new(
        "double_pendulum",
        "Joints: a double pendulum of two bars against a DOP853 solve of its Lagrangian equations, up to the chaos horizon",
        run,
    )
};

/// How much of the case to run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Size {
    /// Length of the energy run (s).
    pub seconds: f64,
    /// Whether rapier2d and Box2D run too.
    pub reference_engines: bool,
}

impl Size {
    /// The harness's: the scene's 20 s, every engine.
    pub const FULL: Size = Size {
        seconds: 20.0,
        reference_engines: true,
    };
    /// The test's: 5 s of the soft step.
    pub const REDUCED: Size = Size {
        seconds: 5.0,
        reference_engines: false,
    };
}

/// Interval of the compared times (s).
const EVERY: f64 = 0.5;

/// Runs `double_pendulum`.
pub fn run() -> Result<CaseReport> {
    run_sized(Size::FULL)
}

/// The reference pendulum of the scene and its initial state.
fn reference(js: &JointScene) -> Result<(DoublePendulum, PendulumState)> {
    let (upper, lower) = (js.body("upper")?, js.body("lower")?);
    let [shoulder, elbow] = js.neutral.joints.as_slice() else {
        bail!("double_pendulum: the scene must have the shoulder and the elbow joints");
    };
    if (shoulder.body_a, shoulder.body_b, elbow.body_a, elbow.body_b)
        != (None, Some(upper), Some(upper), Some(lower))
    {
        bail!("double_pendulum: the shoulder holds the upper bar to the world, the elbow the lower to the upper");
    }
    let body = |b: usize| -> Result<(f64, f64, [f64; 2], f64)> {
        let s = &js.neutral.bodies[b];
        let Shape::Polygon(p) = &s.shape else {
            bail!("double_pendulum: the bars are polygons");
        };
        // The bar's area moment computed here, not by the engine.
        let vertices: Vec<[f64; 2]> = p.vertices().iter().map(|v| [v.x, v.y]).collect();
        let (area, _, j) = polygon_area_moment(&vertices);
        Ok((s.mass(), s.mass() * j / area, s.position, s.angle))
    };
    let ((m1, i1, c1, a1), (m2, i2, c2, a2)) = (body(upper)?, body(lower)?);
    let pendulum = DoublePendulum::from_world(
        [m1, m2],
        [i1, i2],
        shoulder.anchors().1,
        elbow.anchors().0,
        c1,
        c2,
        [a1, a2],
        js.gravity()?,
    );
    let (v1, v2) = (
        js.neutral.bodies[upper].angular_velocity,
        js.neutral.bodies[lower].angular_velocity,
    );
    Ok((
        pendulum,
        PendulumState {
            angles: [a1, a2],
            rates: [v1, v2],
        },
    ))
}

/// `a` wrapped into [−π, π).
fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(2.0 * PI) - PI
}

/// The state of the two bars in `run` at time `t` (s): angles (rad) and
/// angular velocities (rad/s).
pub(super) fn state_at(run: &Run, bodies: [usize; 2], t: f64) -> Result<[f64; 4]> {
    let k = (t / run.dt).round() as usize;
    let Some(s) = run.samples.get(k) else {
        bail!("no sample at t = {t} s");
    };
    Ok([
        s[bodies[0]].angle,
        s[bodies[1]].angle,
        s[bodies[0]].angular_velocity,
        s[bodies[1]].angular_velocity,
    ])
}

/// The four errors (rad, rad/s) of `state` against `r`, angles wrapped.
pub(super) fn errors(state: [f64; 4], r: &ReferencePoint) -> [f64; 4] {
    [
        wrap(state[0] - r.state.angles[0]),
        wrap(state[1] - r.state.angles[1]),
        state[2] - r.state.rates[0],
        state[3] - r.state.rates[1],
    ]
}

/// The energy of the two bars at sample `k` (J), V = 0 at the pivot.
fn energy(js: &JointScene, run: &Run, bodies: [usize; 2], k: usize) -> f64 {
    let g = js.gravity().unwrap_or(0.0);
    bodies
        .iter()
        .map(|&b| {
            let (m, i) = js.mass(b);
            let s = &run.samples[k][b];
            0.5 * m * (s.velocity[0].powi(2) + s.velocity[1].powi(2))
                + 0.5 * i * s.angular_velocity.powi(2)
                + m * g * s.position[1]
        })
        .sum()
}

/// The mean energy (J) over the last second of `run`.
fn final_energy(js: &JointScene, run: &Run, bodies: [usize; 2]) -> f64 {
    let n = run.samples.len() - 1;
    let window = (1.0 / run.dt).round() as usize;
    (n - window..=n)
        .map(|k| energy(js, run, bodies, k))
        .sum::<f64>()
        / (window + 1) as f64
}

pub(super) const COMPONENTS: [(&str, &str); 4] = [
    ("upper_angle", "rad"),
    ("lower_angle", "rad"),
    ("upper_rate", "rad/s"),
    ("lower_rate", "rad/s"),
];

/// Runs `double_pendulum` at `size`.
pub fn run_sized(size: Size) -> Result<CaseReport> {
    let js = JointScene::load("double_pendulum")?;
    let bodies = [js.body("upper")?, js.body("lower")?];
    let (pendulum, initial) = reference(&js)?;
    let base = Config::of(&js.scene, Engine::SoftStep)?;
    let n = steps(size.seconds, base.dt);
    let soft = js.run(&base, n)?;
    let half = js.run(&base.halved(), n)?;
    // The horizon: from the soft step's error after one step.
    let first = pendulum.states_at(initial, &[base.dt], 1e-13)?[0];
    let after_one = state_at(&soft, bodies, base.dt)?;
    let delta0 = (after_one[0] - first.angles[0])
        .abs()
        .max((after_one[1] - first.angles[1]).abs());
    let horizon = pendulum
        .divergence_time(initial, delta0, size.seconds)?
        .unwrap_or(size.seconds);
    let count = ((horizon / EVERY).floor() as usize).max(1);
    let times: Vec<f64> = (1..=count).map(|k| k as f64 * EVERY).collect();
    let reference = pendulum.solve(initial, &times)?;
    let mut report = CaseReport::default();
    let mut sink = RowSink {
        case: "double_pendulum",
        method: Engine::SoftStep.id(),
        dt: base.dt,
        rows: &mut report.rows,
    };
    for r in &reference {
        let e = errors(state_at(&soft, bodies, r.time)?, r);
        let e2 = errors(state_at(&half, bodies, r.time)?, r);
        for (i, (name, unit)) in COMPONENTS.iter().enumerate() {
            let tolerance =
                RICHARDSON_FACTOR * richardson_error(e[i], e2[i], 1).abs() + r.error_estimate;
            let t = r.time;
            sink.within(
                RowKind::Consistency,
                &format!("{name}_{}s", trim(t)),
                e[i],
                0.0,
                tolerance,
                format!(
                    "{} at t = {t} s minus the DOP853 reference's ({unit}; the reference {:.10}, its \
                     error estimate {:.1e}; at h/2: {:+.3e}). Tolerance: 1.5 x the step-doubling \
                     (Richardson) estimate of the soft step's own error at order 1, from the scene \
                     at h/2 = 1/480 s with its joints at 120 Hz, plus the reference's estimate. \
                     t is before the chaos horizon {horizon:.2} s (δ0 = {delta0:.1e} rad, the \
                     soft step's error after its first step). 1.5 is a chosen margin, covering a \
                     next-order term up to 2^1 - 1 = 1 x the leading one \
                     (harness/src/tolerance.rs)",
                    name.replace('_', " "),
                    [
                        r.state.angles[0],
                        r.state.angles[1],
                        r.state.rates[0],
                        r.state.rates[1]
                    ][i],
                    r.error_estimate,
                    e2[i]
                ),
            );
        }
    }
    let e0 = pendulum.energy(&initial);
    let scale = js.mass(bodies[0]).0 * js.gravity()? * 1.0;
    let drift = (final_energy(&js, &soft, bodies) - e0) / scale;
    let drift_half = (final_energy(&js, &half, bodies) - e0) / scale;
    sink.within(
        RowKind::Consistency,
        &format!("energy_{}s", trim(size.seconds)),
        drift,
        0.0,
        RICHARDSON_FACTOR * richardson_error(drift, drift_half, 1).abs(),
        format!(
            "mean energy over the last second of {} s minus the initial energy, over m g × 1 m = \
             {scale:.2} J (h/2: {drift_half:+.3e}; the mean over a second damps symplectic \
             Euler's O(h) energy oscillation). Tolerance: 1.5 x the step-doubling estimate at \
             order 1, from the scene at h/2 with its joints at 120 Hz (1.5: a chosen margin, \
             covering a next-order term up to 1 x the leading one, harness/src/tolerance.rs). \
             The energy stays a meaningful measure past the horizon: it needs no trajectory to \
             follow",
            size.seconds
        ),
    );
    report.notes.push(format!(
        "The horizon: a reference known to δ0 = {delta0:.2e} rad (the soft step's angle error \
         after its first step of 1/60 s) predicts the motion to 1e-3 rad for {horizon:.2} s \
         (references' divergence_time); the rows compare every {EVERY} s before it. Past it \
         chaos separates every run. DOP853's own energy drift over those times: {:.1e} J.",
        reference
            .iter()
            .map(|r| r.energy_drift)
            .fold(0.0, f64::max)
    ));
    if size.reference_engines {
        let note = double_pendulum_exact::rows(
            &js,
            (&pendulum, initial),
            bodies,
            horizon,
            size.seconds,
            &mut report.rows,
        )?;
        report.notes.push(note);
        for engine in [Engine::Box2d, Engine::Rapier] {
            let config = Config::of(&js.scene, engine)?;
            let run = js.run(&config, n)?;
            let items: Vec<String> = reference
                .iter()
                .map(|r| {
                    let e = errors(state_at(&run, bodies, r.time).unwrap_or([f64::NAN; 4]), r);
                    format!(
                        "t = {} s: {:+.2e}, {:+.2e} rad, {:+.2e}, {:+.2e} rad/s",
                        r.time, e[0], e[1], e[2], e[3]
                    )
                })
                .collect();
            let drift = (final_energy(&js, &run, bodies) - e0) / scale;
            report.notes.push(format!(
                "{} on the same file (informational; its own error has no step doubling here): \
                 errors of the upper and lower angles and rates {}; energy after {} s \
                 {drift:+.3e} m g × 1 m (the soft step {:+.3e}).",
                engine.label(),
                items.join("; "),
                size.seconds,
                (final_energy(&js, &soft, bodies) - e0) / scale
            ));
        }
    }
    Ok(report)
}

/// A time as a row name: `1`, `1.5`.
pub(super) fn trim(t: f64) -> String {
    let s = format!("{t:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
