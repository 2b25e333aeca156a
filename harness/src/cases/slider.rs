//! `slider` (`docs/cases.md#slider`): two boxes of 2 kg on frictionless
//! prismatic joints inclined at 30°, each held by the joint's spring of
//! k = 50 N/m (`scenes/slider.toml`), against the damped oscillator
//! m x'' = −k x − c x' − m g sin θ (`references::slider`): ω = √(k/m) and
//! the equilibrium x_eq = −m g sin θ/k.
//!
//! # The soft spring's discrete response
//!
//! A joint spring is a soft row solved in both passes of every substep
//! (`docs/joints.md`); on a body alone along its line it maps the offset
//! from equilibrium and the velocity linearly, with eigenvalues of modulus
//! 1/(1 + ε) and phase φ per substep, ε = (hω)², cos φ = (2 + ε)/(2(1 + ε)):
//! the period is 2πh/φ = (2π/ω)(1 + 11/24 (hω)² + O(h⁴)), and even an
//! undamped spring loses amplitude by 1/(1 + ε) per substep. At rest its
//! bias balances the load exactly: the box rests at x_eq to round-off.
//! Box2D's joint springs are the same rows (f32).

use super::joint_common::{Config, Engine, JointScene, Run, SoftRows, crossing_error, crossings, steps};
use super::{Case, CaseReport, Headline, Snapshots};
use crate::row::{RowKind, RowSink};
use crate::tolerance::ROUND_OFF_RELATIVE;
use anyhow::{Result, bail};
use references::many_body::JointKind;
use references::slider::Slider;
use std::f64::consts::PI;

/// Two boxes on inclined sprung rails.
pub const CASE: Case = Case {
    scenes: &["slider"],
    snapshots: Snapshots::HarnessOnly(
        "three engines; harness/tests/joint_cases.rs checks the soft step alone with the same \
         rows",
    ),
    headline: &[Headline::new("period_free", "soft_step")],
    ..Case::new(
        "slider",
        "Joints: a box on an inclined prismatic joint with a spring: period 2π√(m/k) and rest at mg sin θ/k",
        run,
    )
};

/// Box2D's single precision on a translation read from its poses: an ulp
/// of 2.4e-7 m at 2 m from the origin, a few of them.
const BOX2D_ROUNDING: f64 = 1e-6;

/// Runs `slider`.
pub fn run() -> Result<CaseReport> {
    run_sized(true)
}

/// One slider of the scene: its body, joint and closed form.
struct Rail {
    name: String,
    joint: usize,
    closed: Slider,
}

fn rails(js: &JointScene) -> Result<Vec<Rail>> {
    let g = js.gravity()?;
    js.neutral
        .joints
        .iter()
        .enumerate()
        .map(|(joint, j)| {
            let (None, Some(body), JointKind::Prismatic(p)) = (j.body_a, j.body_b, j.kind) else {
                bail!("slider: joint {joint} must be a prismatic joint of a body on the world");
            };
            let Some(spring) = p.spring else {
                bail!("slider: joint {joint} has no spring");
            };
            let mass = js.neutral.bodies[body].mass();
            let omega = 2.0 * PI * spring.hertz;
            Ok(Rail {
                name: js.scene.bodies()[body].name.clone(),
                joint,
                closed: Slider {
                    mass,
                    stiffness: mass * omega * omega,
                    damping_ratio: spring.damping_ratio,
                    angle: p.axis[1].atan2(p.axis[0]),
                    gravity: g,
                    x0: 0.0,
                    v0: 0.0,
                },
            })
        })
        .collect()
}

/// The discrete period (s) of a soft spring of angular frequency `omega`
/// at substep `h`: 2πh/φ, cos φ = (2 + ε)/(2(1 + ε)), ε = (hω)².
fn discrete_period(omega: f64, h: f64) -> f64 {
    let eps = (h * omega).powi(2);
    2.0 * PI * h / ((2.0 + eps) / (2.0 * (1.0 + eps))).acos()
}

/// The translation of rail `joint` after every step of `run` (m).
fn translations(js: &JointScene, run: &Run, joint: usize) -> Vec<f64> {
    run.samples
        .iter()
        .map(|s| js.neutral.joint_states(s)[joint].coordinate)
        .collect()
}

/// Runs `slider`, with rapier2d and Box2D when `reference_engines`.
pub fn run_sized(reference_engines: bool) -> Result<CaseReport> {
    let js = JointScene::load("slider")?;
    let rails = rails(&js)?;
    let (Some(free), Some(damped)) = (
        rails.iter().find(|r| r.closed.damping_ratio == 0.0),
        rails.iter().find(|r| r.closed.damping_ratio > 0.0),
    ) else {
        bail!("slider: the scene needs an undamped and a damped rail");
    };
    let mut report = CaseReport::default();
    for &engine in Engine::of_run(reference_engines) {
        let config = Config::of(&js.scene, engine)?;
        let h = config.substep();
        let run = js.run(&config, steps(js.scene.duration(), config.dt))?;
        let s = &free.closed;
        let (omega, x_eq, t_exact) = (s.omega(), s.equilibrium(), s.period());
        let t_discrete = discrete_period(omega, h);
        let offsets: Vec<f64> = translations(&js, &run, free.joint)
            .iter()
            .map(|x| x - x_eq)
            .collect();
        let c = crossings(&offsets, run.dt);
        if c.len() < 3 {
            bail!("slider: {} crossings of the free rail", c.len());
        }
        let period = 2.0 * (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64;
        // Two crossings located inside their steps: a sinusoid has x'' = 0
        // at its zero and |x'''/x'| = ω² (its decay of ε per substep adds
        // (2ε/h)² ≪ ω²: 1e-3 of it).
        let crossing = 2.0 * crossing_error(run.dt, omega * omega) / ((c.len() - 1) as f64 / 2.0);
        let rest = *translations(&js, &run, damped.joint)
            .last()
            .expect("a run has samples");
        let across = |rail: &Rail| -> f64 {
            run.samples
                .iter()
                .map(|s| js.neutral.joint_states(s)[rail.joint].separation)
                .fold(0.0, f64::max)
        };
        let (across_free, across_damped) = (across(free), across(damped));
        let decay = (1.0 + (h * omega).powi(2)).powf(-t_discrete / h);
        let note = format!(
            "{}: the free box's period {period:.9} s (2π/ω = {t_exact:.9} s, the soft spring's \
             discrete period {t_discrete:.9} s), its amplitude falling by (1 + (hω)²)^(−T/h) = \
             {decay:.4} per period, the soft spring's own loss; the damped box at rest at \
             {rest:.12} m (x_eq = {x_eq:.12} m); the rails' largest offsets across their axes \
             {across_free:.3e} and {across_damped:.3e} m.",
            engine.label()
        );
        if engine == Engine::Rapier {
            report.notes.push(format!(
                "{note} Informational: rapier's spring is the same soft spring (its \
                 acceleration-based motor with k = (2πf)², c = 2ζ(2πf)), solved in its own pass \
                 order, for which the discrete period above is not derived."
            ));
            continue;
        }
        report.notes.push(note);
        let rounding = if engine == Engine::Box2d {
            BOX2D_ROUNDING
        } else {
            0.0
        };
        let mut sink = RowSink {
            case: "slider",
            method: engine.id(),
            dt: config.dt,
            rows: &mut report.rows,
        };
        sink.within(
            RowKind::Validation,
            "period_free",
            period,
            t_exact,
            (t_discrete - t_exact).abs() + crossing,
            format!(
                "mean period of the undamped box (s), from the first to the last zero crossing \
                 of x − x_eq, against 2π/ω = 2π √(m/k). Tolerance: the soft spring's discrete \
                 period 2πh/φ (cos φ = (2 + ε)/(2(1 + ε)), ε = (hω)², h = {h:.6} s) minus 2π/ω \
                 = {:.3e} s, plus the crossings' location, dt³ω²/8 each over the periods \
                 measured: {crossing:.1e} s",
                t_discrete - t_exact
            ),
        );
        if engine == Engine::SoftStep {
            sink.within(
                RowKind::Validation,
                "period_free_discrete",
                period,
                t_discrete,
                crossing,
                format!(
                    "mean period of the undamped box (s) against the soft spring's own discrete \
                     period 2πh/φ (cos φ = (2 + ε)/(2(1 + ε)), ε = (hω)², h = {h:.6} s): the \
                     spring row alone moves the box along the rail (its anchor at the centre, \
                     the other rows across the rail and on the angle), so only the crossings' \
                     location errs, dt³ω²/8 each over the periods measured: {crossing:.1e} s"
                ),
            );
        }
        sink.within(
            RowKind::Validation,
            "equilibrium_damped",
            rest,
            x_eq,
            ROUND_OFF_RELATIVE * x_eq.abs() + rounding,
            format!(
                "translation (m) of the damped box (ζ = 0.5) after {} s along the rail, against \
                 x_eq = −m g sin θ/k: at rest the soft spring's bias balances the load exactly \
                 (its sink λ/(m h ω²) = g sin θ/ω² is x_eq), so to round-off, 1e-9 relative{}",
                js.scene.duration(),
                if rounding > 0.0 {
                    format!(", plus Box2D's f32 poses, {rounding:.0e} m")
                } else {
                    String::new()
                }
            ),
        );
        let rows_model = SoftRows::defaults(h);
        let g_across = s.gravity * s.angle.cos();
        for (rail, value) in [(free, across_free), (damped, across_damped)] {
            sink.at_most(
                RowKind::Validation,
                &format!("across_{}", rail.name),
                value,
                0.0,
                2.0 * rows_model.sink(g_across) + rounding,
                format!(
                    "largest offset (m) of the {} box's anchor across the rail over the run. \
                     Bound: the line row's static sink under the load across it, g cos θ/ω_c² \
                     = {:.3e} m (ω_c = 2π × 60 Hz), doubled: the load comes at once, and a \
                     linear spring-damper loaded at once deflects at most twice its static \
                     deflection",
                    rail.name,
                    rows_model.sink(g_across)
                ),
            );
        }
    }
    Ok(report)
}
