//! `joint_motor_limit` (`docs/cases.md#joint-limits-and-motors`): revolute
//! motors and a revolute limit (`scenes/joint_motor_limit.toml`).
//!
//! # Motors
//!
//! Two wheels pinned at their centres, each by a drive (a motor toward
//! ω* = 3 rad/s with at most τ = 10 N·m) and a brake (a motor toward 0
//! with at most τ_b: joint friction, the load). A motor row is a velocity
//! row whose accumulated impulse stays within h × its largest torque in
//! every substep, solved in both passes; the drive is solved before the
//! brake (the order the joints were added). So:
//!
//! - `driven` (τ_b = 5 N·m < τ): both rows saturate while the wheel spins
//!   up, each substep adds exactly h (τ − τ_b)/I, and symplectic Euler
//!   integrates that constant exactly: ω(t) = (τ − τ_b) t/I up to
//!   t* = I ω*/(τ − τ_b) = 0.15 s, then the drive's row lands on ω* and
//!   holds it, giving the brake's torque; to round-off;
//! - `stalled` (τ_b = 20 N·m > τ): the drive's 10 N·m never overcomes the
//!   brake, which takes back each substep's drive impulse before the
//!   positions move: the wheel never turns, to round-off.
//!
//! # The limit
//!
//! A 1 m × 0.1 m bar pinned at one end falls from horizontal onto its
//! lower limit at −0.5 rad. A limit row is speculative while open (bias
//! C/h, rigid: the approach closes the gap within the substep and no
//! further), soft at the joint's 60 Hz once past it. The point row solved
//! after it gives back at most one substep's turn at the impact speed, so
//! the bar passes the limit by at most h ω_impact + the sink (ω_impact
//! from energy, ½ I_p ω² = m g (L/2) sin 0.5). At rest the limit row
//! carries the weight's torque about the pivot, τ = m g (L/2) cos θ, over
//! its mass I_c (the bar's inertia about its centre: the row's inverse mass
//! is 1/I_c), so the bar rests past the limit by exactly τ/(I_c ω_c²) at
//! its rest angle θ (the static sink, solved for θ here).

use super::joint_common::{Config, Engine, JointScene, Run, SoftRows, steps};
use super::{Case, CaseReport, Headline, Snapshots};
use crate::row::{RowKind, RowSink};
use crate::tolerance::ROUND_OFF_RELATIVE;
use anyhow::{Result, bail};
use references::many_body::JointKind;
use references::pendulum::polygon_area_moment;

/// Motors and a limit.
pub const CASE: Case = Case {
    scenes: &["joint_motor_limit"],
    snapshots: Snapshots::HarnessOnly(
        "three engines; harness/tests/joint_cases.rs checks the soft step alone with the same \
         rows",
    ),
    headline: &[Headline::new("driven_speed", "soft_step")],
    ..Case::new(
        "joint_motor_limit",
        "Joints: revolute motors reaching their speed within their torque and stalling beyond it; an angle limit holding a falling bar",
        run,
    )
};

/// Box2D's joint angles: `b2Atan2`, a polynomial of error up to 2.8e-5 rad
/// (`references::box2d_world::joints`), plus its f32 rotations.
const BOX2D_ANGLE: f64 = 2.8e-5 + 1e-6;

/// rapier's joint softness (`SpringCoefficients::joint_defaults`, read in
/// its sources: `references::rapier_many::joints`): 1e6 Hz, ζ = 1.
const RAPIER_JOINT_HERTZ: f64 = 1e6;

/// f32's unit round-off, 2⁻²⁴.
const F32_EPSILON: f64 = 5.960464477539063e-8;

/// Runs `joint_motor_limit`.
pub fn run() -> Result<CaseReport> {
    run_sized(true)
}

/// The motor and brake of a wheel: (ω* rad/s, τ N·m, τ_b N·m).
fn motors(js: &JointScene, drive: usize, brake: usize) -> Result<(f64, f64, f64)> {
    let motor = |j: usize| match js.neutral.joints[j].kind {
        JointKind::Revolute(r) => r.motor,
        _ => None,
    };
    let (Some(d), Some(b)) = (motor(drive), motor(brake)) else {
        bail!("joint_motor_limit: joints {drive} and {brake} must be motors");
    };
    if b.speed != 0.0 {
        bail!("joint_motor_limit: a brake is a motor toward 0");
    }
    Ok((d.speed, d.max_force, b.max_force))
}

/// The index of the joint named `name`.
fn joint(js: &JointScene, name: &str) -> Result<usize> {
    js.scene
        .joints()
        .position(|j| j.name == name)
        .ok_or_else(|| anyhow::anyhow!("joint_motor_limit: no joint '{name}'"))
}

/// Body `b`'s angular velocity (rad/s) at time `t` (s) of `run`.
fn rate_at(run: &Run, b: usize, t: f64) -> f64 {
    run.samples[(t / run.dt).round() as usize][b].angular_velocity
}

/// Runs `joint_motor_limit`, with rapier2d and Box2D when
/// `reference_engines`.
pub fn run_sized(reference_engines: bool) -> Result<CaseReport> {
    let js = JointScene::load("joint_motor_limit")?;
    let (driven, stalled, bar) = (js.body("driven")?, js.body("stalled")?, js.body("bar")?);
    let (speed, torque, brake) = motors(&js, joint(&js, "driven_drive")?, joint(&js, "driven_brake")?)?;
    let (_, stall_torque, stall_brake) =
        motors(&js, joint(&js, "stalled_drive")?, joint(&js, "stalled_brake")?)?;
    if stall_brake <= stall_torque || brake >= torque {
        bail!("joint_motor_limit: `driven` must out-torque its brake, `stalled` not");
    }
    let hinge = joint(&js, "hinge")?;
    let JointKind::Revolute(r) = js.neutral.joints[hinge].kind else {
        bail!("joint_motor_limit: the hinge is revolute");
    };
    let Some([lower, upper]) = r.limits else {
        bail!("joint_motor_limit: the hinge has limits");
    };
    let (_, i_wheel) = js.mass(driven);
    let g = js.gravity()?;
    // The bar: its own area moment, computed here.
    let (m_bar, i_c, half) = {
        let b = &js.neutral.bodies[bar];
        let engine::Shape::Polygon(p) = &b.shape else {
            bail!("joint_motor_limit: the bar is a box");
        };
        let v: Vec<[f64; 2]> = p.vertices().iter().map(|q| [q.x, q.y]).collect();
        let (area, _, j) = polygon_area_moment(&v);
        let half = v.iter().map(|q| q[0]).fold(f64::MIN, f64::max);
        (b.mass(), b.mass() * j / area, half)
    };
    let i_pivot = i_c + m_bar * half * half;
    let spin_up = i_wheel * speed / (torque - brake);
    let mut report = CaseReport::default();
    let mut report_rapier_stall = None;
    for &engine in Engine::of_run(reference_engines) {
        let config = Config::of(&js.scene, engine)?;
        let h = config.substep();
        let rows_model = match engine {
            // rapier does not cap its joints' frequency; only the sink is
            // read from these rows.
            Engine::Rapier => SoftRows {
                omega: 2.0 * std::f64::consts::PI * RAPIER_JOINT_HERTZ,
                a3: 1.0,
            },
            _ => SoftRows::defaults(h),
        };
        let run = js.run(&config, steps(js.scene.duration(), config.dt))?;
        let t_ramp = (0.5 * spin_up / config.dt).round() * config.dt;
        let ramp = rate_at(&run, driven, t_ramp);
        let end = run.samples.last().expect("samples");
        let fastest = run
            .samples
            .iter()
            .map(|s| s[driven].angular_velocity)
            .fold(f64::MIN, f64::max);
        let stall = run
            .samples
            .iter()
            .map(|s| s[stalled].angle.abs().max(s[stalled].angular_velocity.abs()))
            .fold(0.0, f64::max);
        let angles: Vec<f64> = run
            .samples
            .iter()
            .map(|s| js.neutral.joint_states(s)[hinge].coordinate)
            .collect();
        let lowest = angles.iter().copied().fold(f64::MAX, f64::min);
        let highest = angles.iter().copied().fold(f64::MIN, f64::max);
        let rest = *angles.last().expect("samples");
        // The rest angle θ: θ = lower − m g (L/2) cos θ/(I_c ω_c²), by
        // fixed-point iteration (a contraction: its slope is the sink
        // times tan θ, 2e-4).
        let mut theta = lower;
        for _ in 0..50 {
            theta = lower - rows_model.sink(m_bar * g * half * theta.cos() / i_c);
        }
        let sink = lower - theta;
        let impact = (2.0 * m_bar * g * half * (-lower).sin() / i_pivot).sqrt();
        let slop = h * impact + sink;
        let note = format!(
            "{}: `driven` at {ramp:.12} rad/s at t = {t_ramp:.3} s (the ramp {:.12}), {:.12} \
             rad/s at the end, at most {fastest:.12}; `stalled` turned by at most {stall:.2e} \
             (rad or rad/s); the bar reached {lowest:.6} rad (the limit {lower}), rested at \
             {rest:.9} rad (the soft limit's rest {theta:.9}), never above {highest:.3e} rad \
             (the upper limit {upper}).",
            engine.label(),
            (torque - brake) * t_ramp / i_wheel,
            end[driven].angular_velocity,
        );
        report.notes.push(note);
        let (rapier, box2d) = (engine == Engine::Rapier, engine == Engine::Box2d);
        let mut sink_rows = RowSink {
            case: "joint_motor_limit",
            method: engine.id(),
            dt: config.dt,
            rows: &mut report.rows,
        };
        let s = &mut sink_rows;
        // Box2D sums its substeps' increments in f32: one rounding of ω
        // (at most ω*) per substep.
        let substeps_ramped = (t_ramp / h).round();
        let f32_sum = substeps_ramped * F32_EPSILON * speed;
        let round = ROUND_OFF_RELATIVE * speed + if box2d { f32_sum } else { 0.0 };
        let round_reason = if box2d {
            format!(
                "round-off, 1e-9 of ω*, plus Box2D's f32 sum of {substeps_ramped} substeps' \
                 increments, one rounding of ω* each: {f32_sum:.1e} rad/s"
            )
        } else if rapier {
            "round-off, 1e-9 of ω* (rapier's motor rows are rigid velocity rows: compliance \
             below 1e-12 per unit effective mass)"
                .to_string()
        } else {
            "round-off, 1e-9 of ω*".to_string()
        };
        {
            s.within(
                RowKind::Validation,
                "driven_ramp",
                ramp,
                (torque - brake) * t_ramp / i_wheel,
                round,
                format!(
                    "`driven`'s ω (rad/s) at t = {t_ramp:.3} s, half way through its spin-up, \
                     against (τ − τ_b) t/I = ({torque} − {brake}) t/{i_wheel}: both motor rows \
                     saturate, each substep adds exactly h (τ − τ_b)/I, which symplectic Euler \
                     sums exactly; {round_reason}"
                ),
            );
            s.within(
                RowKind::Validation,
                "driven_speed",
                end[driven].angular_velocity,
                speed,
                round,
                format!(
                    "`driven`'s ω (rad/s) at the end against the drive's target ω* = {speed}: \
                     past t* = I ω*/(τ − τ_b) = {spin_up} s the drive's row lands on ω* within \
                     its torque (it needs only the brake's {brake} N·m of its {torque}) and holds \
                     it; {round_reason}"
                ),
            );
            s.at_most(
                RowKind::Validation,
                "driven_overshoot",
                fastest - speed,
                0.0,
                round,
                format!(
                    "the largest ω of `driven` over the run above ω* (rad/s): the drive's row \
                     stops the spin-up on ω* itself, within a substep; {round_reason}"
                ),
            );
        }
        if rapier {
            report_rapier_stall = Some(stall);
        } else {
            let creep = if box2d {
                stall_torque * h * h / i_wheel
            } else {
                0.0
            };
            s.at_most(
                RowKind::Validation,
                "stalled_motion",
                stall,
                0.0,
                round + creep,
                format!(
                    "the largest |angle| (rad) or |ω| (rad/s) of `stalled` over the run: its \
                     drive's {stall_torque} N·m never overcomes its brake's {stall_brake} N·m, \
                     and the brake's row, solved after the drive's, takes back each drive \
                     impulse before the positions move; round-off{}",
                    if box2d {
                        format!(
                            ". Box2D solves its joints by graph colour, not in the order added: \
                             in the first substep its brake may come before the drive, which then \
                             turns the wheel for one substep at τh/I, at most τh²/I = {creep:.2e} \
                             rad (warm starting preloads the brake afterwards)"
                        )
                    } else {
                        String::new()
                    }
                ),
            );
        }
        let atan = if box2d { BOX2D_ANGLE } else { 0.0 };
        {
            s.at_most(
                RowKind::Validation,
                "limit_overshoot",
                lower - lowest,
                0.0,
                slop + atan,
                format!(
                    "how far the bar passes its lower limit {lower} rad (rad) over the run. \
                     Bound: the speculative row stops the approach within the substep, the \
                     point row after it gives back at most one substep's turn at the impact \
                     speed, h ω_impact = {:.3e} rad (ω_impact = {impact:.3} rad/s from ½ I_p ω² = \
                     m g (L/2) sin 0.5; rapier's limit rows act only once past the limit, within \
                     the same substep), plus the resting sink {sink:.3e} rad{}",
                    h * impact,
                    if atan > 0.0 {
                        ", plus Box2D's angle polynomial (b2Atan2, up to 2.8e-5 rad) and f32"
                    } else {
                        ""
                    }
                ),
            );
            s.within(
                RowKind::Validation,
                "limit_rest",
                rest,
                theta,
                ROUND_OFF_RELATIVE + atan,
                format!(
                    "the bar's angle (rad) after {} s against its soft limit's rest angle θ = \
                     lower − m g (L/2) cos θ/(I_c ω_c²) = {theta:.9} rad (ω_c = 2π × {:.0e} Hz, \
                     the engine's joint softness): at rest the limit row \
                     carries the weight's torque about the pivot over its mass I_c (its inverse \
                     mass 1/I_c), the static sink of a soft row, exact at rest; round-off, 1e-9 \
                     rad{}",
                    js.scene.duration(),
                    rows_model.omega / (2.0 * std::f64::consts::PI),
                    if atan > 0.0 {
                        ", plus Box2D's angle polynomial (b2Atan2, up to 2.8e-5 rad) and f32"
                    } else {
                        ""
                    }
                ),
            );
        }
        s.at_most(
            RowKind::Validation,
            "upper_limit",
            highest - upper,
            0.0,
            atan,
            format!(
                "the bar's highest angle above its upper limit {upper} rad: it falls from 0 and \
                 never reaches it (its rebound from the lower limit is damped by the soft row)"
            ),
        );
    }
    if let Some(stall) = report_rapier_stall {
        report.notes.push(format!(
            "rapier2d does not stall `stalled`: its drive and brake are two impulse joints on the \
             same axis, solved without warm starting, and the wheel turns (by {stall:.3} rad or \
             rad/s at most); no row, its motor rows' order is not derived here."
        ));
    }
    report.notes.push(
        "The exact contact model refuses joints (see `pendulum`): these run under the soft step \
         only."
            .into(),
    );
    Ok(report)
}
