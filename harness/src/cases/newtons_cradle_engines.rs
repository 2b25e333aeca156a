//! `newtons_cradle`'s comparison runs (`docs/cases.md#newtons_cradle`):
//! the same cradle (`scenes/newtons_cradle_soft.toml`, the balls and rods
//! of `scenes/newtons_cradle.toml`) under this engine's soft step,
//! rapier2d and Box2D at their defaults (60 Hz, 4 substeps), read the same
//! way from the body states after every step.
//!
//! # What is read
//!
//! Each ball's own energy E_i = m g (y_i − y_rest) + m |v_i|²/2 (J), which
//! a rigid rod keeps between impacts whatever the phase of the swing, read
//! at the apexes t_k = T/2 + k T/2 of one ball out for one in (T the period
//! at 30°, each a quarter period from the impacts on either side), and
//! given as the speed it would have at the bottom over the incoming one,
//! √(E_i/E_in). One ball out for one in leaves 1 on the outgoing ball
//! (ball 4 after an even chain, ball 0 after an odd) and 0 on the others.
//! The first impact's momentum: the horizontal momentum a quarter swing
//! (T/8) after the impact over a quarter swing before, which the
//! pendulums' symmetry about the bottom makes 1 for any outcome that
//! keeps momentum at the impact.
//!
//! # The rows: criteria, each engine's behaviour stated
//!
//!
//! The bounds are chosen by hand (RowKind::Criterion): one ball out means
//! the outgoing ball carries at least [`OUT_FRACTION`] of the incoming
//! speed and each other ball at most [`REST_FRACTION`]. Sequential-impulse
//! solvers (the soft step, rapier2d, Box2D) do not pass a chain of touching
//! balls' impulses on one by one: they solve the touching contacts
//! together, so which of the criteria an engine meets is a property of
//! the engine, recorded in [`expected`] from the runs (docs/cases.md
//! prints them), and each row checks that property, with the criterion's
//! verdict in its reason: a change of behaviour fails the row.

use super::joint_common::{Config, Engine, JointScene, steps};
use crate::row::{RowKind, RowSink};
use anyhow::{Result, bail};
use std::f64::consts::PI;

/// The scene of the comparison runs.
pub const SCENE: &str = "newtons_cradle_soft";

/// One ball out: the outgoing ball's share of the incoming speed, at least
/// (a hand-chosen bound: 90 %).
pub const OUT_FRACTION: f64 = 0.9;

/// One ball out: every other ball's share of the incoming speed, at most
/// (a hand-chosen bound: 10 %).
pub const REST_FRACTION: f64 = 0.1;

/// Energy kept (the total over the start) for "energy kept", at least
/// (a hand-chosen bound: 90 %), and the first impact's momentum ratio
/// within this of 1 (10 %).
pub const KEPT_FRACTION: f64 = 0.9;

/// The readings of one engine at one apex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Apex {
    /// Which apex (0: after the first impact).
    pub k: usize,
    /// Time (s).
    pub t: f64,
    /// √(E_i/E_in) of each ball.
    pub shares: [f64; 5],
    /// The total energy over the start.
    pub energy: f64,
}

impl Apex {
    /// The ball that should be out after chain `k`.
    pub fn out_ball(&self) -> usize {
        if self.k.is_multiple_of(2) { 4 } else { 0 }
    }

    /// The outgoing ball's share.
    pub fn out(&self) -> f64 {
        self.shares[self.out_ball()]
    }

    /// The largest share of the other balls.
    pub fn rest(&self) -> f64 {
        let o = self.out_ball();
        (0..5)
            .filter(|&i| i != o)
            .map(|i| self.shares[i])
            .fold(0.0, f64::max)
    }

    /// Whether it meets the one-out criteria.
    pub fn one_out(&self) -> bool {
        self.out() >= OUT_FRACTION && self.rest() <= REST_FRACTION
    }
}

/// One engine's readings.
#[derive(Debug, Clone, PartialEq)]
pub struct Readings {
    /// The engine.
    pub engine: Engine,
    /// The step (s).
    pub dt: f64,
    /// After the first impact.
    pub first: Apex,
    /// After the last whole chain of the run.
    pub last: Apex,
    /// The first impact's momentum ratio.
    pub momentum: f64,
}

/// What each engine does, recorded from the runs of
/// `scenes/newtons_cradle_soft.toml`: (one ball out, after the first
/// impact and after the last chain; the energy kept to
/// [`KEPT_FRACTION`] after the last chain). None of the three does either:
/// their solvers spread the first impact over the touching balls (each
/// left with 0.3 to 0.5 of the incoming speed) and lose energy at every
/// chain.
pub fn expected(engine: Engine) -> (bool, bool) {
    match engine {
        Engine::SoftStep | Engine::Rapier | Engine::Box2d => (false, false),
    }
}

/// The period (s) of a pendulum of length `l` (m) under `g` (m/s²) at
/// amplitude `theta0` (rad): 2π √(l/g) / AGM(1, cos(θ0/2)).
fn period(l: f64, g: f64, theta0: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, (theta0 / 2.0).cos());
    while (a - b).abs() > 1e-15 * a {
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    2.0 * PI * (l / g).sqrt() / a
}

/// Runs `engine` on the comparison scene and reads it.
pub fn measure(js: &JointScene, engine: Engine) -> Result<Readings> {
    let g = js.gravity()?;
    let config = Config::of(&js.scene, engine)?;
    let n = steps(js.scene.duration(), config.dt);
    let run = js.run(&config, n)?;
    let bodies = js.scene.bodies();
    if bodies.len() != 5 || js.neutral.joints.len() != 5 {
        bail!("{}: five balls on five rods expected", js.scene.origin());
    }
    // The rest height: the hanging balls' (ball 1's start); the rod's
    // length and the release angle from ball 0's start under its pivot.
    let rest = bodies[1].state.position.y;
    let rod = super::newtons_cradle::ROD;
    let theta0 = (1.0 - (bodies[0].state.position.y - rest) / rod).acos();
    let t_period = period(rod, g, theta0);
    let energy = |k: usize, b: usize| {
        let s = &run.samples[k][b];
        let (m, _) = js.mass(b);
        m * g * (s.position[1] - rest)
            + 0.5 * m * (s.velocity[0] * s.velocity[0] + s.velocity[1] * s.velocity[1])
    };
    let e_in = energy(0, 0);
    let index = |t: f64| (t / config.dt).round() as usize;
    let apex = |k: usize| {
        let t = t_period / 2.0 * (k as f64 + 1.0);
        let i = index(t);
        let mut shares = [0.0; 5];
        let mut total = 0.0;
        for (b, share) in shares.iter_mut().enumerate() {
            let e = energy(i, b);
            total += e;
            *share = (e.max(0.0) / e_in).sqrt();
        }
        Apex {
            k,
            t: i as f64 * config.dt,
            shares,
            energy: total / e_in,
        }
    };
    let last_k = ((js.scene.duration() - t_period / 8.0) / (t_period / 2.0)).floor() as usize - 1;
    let momentum_at = |t: f64| {
        let i = index(t);
        (0..5)
            .map(|b| js.mass(b).0 * run.samples[i][b].velocity[0])
            .sum::<f64>()
    };
    let t_impact = t_period / 4.0;
    let momentum = momentum_at(t_impact + t_period / 8.0) / momentum_at(t_impact - t_period / 8.0);
    Ok(Readings {
        engine,
        dt: config.dt,
        first: apex(0),
        last: apex(last_k),
        momentum,
    })
}

/// Runs the three engines, adds their rows and notes.
pub fn rows(report: &mut super::CaseReport) -> Result<()> {
    let js = JointScene::load(SCENE)?;
    for engine in [Engine::SoftStep, Engine::Rapier, Engine::Box2d] {
        let r = measure(&js, engine)?;
        let fmt = |a: &Apex| {
            a.shares
                .iter()
                .map(|s| format!("{s:.3}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        report.notes.push(format!(
            "{} on scenes/{SCENE}.toml (h = {:.4} s): after the first impact (t = {:.3} s) the \
             balls carry [{}] of the incoming speed (sqrt of each ball's energy over the \
             incoming), energy kept {:.3}; after chain {} (t = {:.3} s) [{}], energy kept {:.3}; \
             the first impact's momentum ratio {:.4}. One ball out (outgoing >= {OUT_FRACTION}, \
             others <= {REST_FRACTION}): {} after the first impact, {} after chain {}.",
            engine.label(),
            r.dt,
            r.first.t,
            fmt(&r.first),
            r.first.energy,
            r.last.k + 1,
            r.last.t,
            fmt(&r.last),
            r.last.energy,
            r.momentum,
            if r.first.one_out() { "yes" } else { "no" },
            if r.last.one_out() { "yes" } else { "no" },
            r.last.k + 1,
        ));
        add_rows(report, &r);
    }
    Ok(())
}

/// The rows of one engine: each criterion checked in the direction
/// [`expected`] records, its verdict in the reason.
fn add_rows(report: &mut super::CaseReport, r: &Readings) {
    let (one_out, kept) = expected(r.engine);
    let mut sink = RowSink {
        case: "newtons_cradle",
        method: r.engine.id(),
        dt: r.dt,
        rows: &mut report.rows,
    };
    let criterion = format!(
        "a hand-chosen criterion of one ball out for one in: the outgoing ball carries >= \
         {OUT_FRACTION} of the incoming speed, every other <= {REST_FRACTION} (sqrt of each \
         ball's energy over the incoming one, at the apex of the outgoing ball)"
    );
    for (check_out, check_rest, a, when) in [
        (
            "outgoing_share_first",
            "others_share_first",
            &r.first,
            "after the first impact".to_string(),
        ),
        (
            "outgoing_share_last",
            "others_share_last",
            &r.last,
            format!("after chain {}", r.last.k + 1),
        ),
    ] {
        let ball = a.out_ball();
        if one_out {
            sink.at_least(
                RowKind::Criterion,
                check_out,
                a.out(),
                OUT_FRACTION,
                0.0,
                format!("{criterion}: ball {ball}'s share {when}, met (as recorded)"),
            );
            sink.at_most(
                RowKind::Criterion,
                check_rest,
                a.rest(),
                REST_FRACTION,
                0.0,
                format!("{criterion}: the largest other share {when}, met (as recorded)"),
            );
        } else {
            sink.at_most(
                RowKind::Criterion,
                check_out,
                a.out(),
                OUT_FRACTION,
                0.0,
                format!(
                    "{criterion}: ball {ball}'s share {when}; NOT met by {}, as recorded: the \
                     row checks that it stays below (it fails if the engine starts to send \
                     one ball out)",
                    r.engine.label()
                ),
            );
            sink.at_least(
                RowKind::Criterion,
                check_rest,
                a.rest(),
                REST_FRACTION,
                0.0,
                format!(
                    "{criterion}: the largest other share {when}; NOT met by {}, as recorded: \
                     the other balls move too",
                    r.engine.label()
                ),
            );
        }
    }
    let energy_reason = format!(
        "a hand-chosen criterion of energy kept: the total energy after chain {} over the \
         start, >= {KEPT_FRACTION}",
        r.last.k + 1
    );
    if kept {
        sink.at_least(
            RowKind::Criterion,
            "energy_kept_last",
            r.last.energy,
            KEPT_FRACTION,
            0.0,
            format!("{energy_reason}: met (as recorded)"),
        );
    } else {
        sink.at_most(
            RowKind::Criterion,
            "energy_kept_last",
            r.last.energy,
            KEPT_FRACTION,
            0.0,
            format!(
                "{energy_reason}; NOT met by {}, as recorded: the row checks that it stays \
                 below (the impacts lose energy)",
                r.engine.label()
            ),
        );
    }
    sink.within(
        RowKind::Criterion,
        "momentum_first",
        r.momentum,
        1.0,
        1.0 - KEPT_FRACTION,
        "a hand-chosen criterion of momentum kept at the first impact: the horizontal momentum \
         T/8 after the impact over T/8 before, 1 for any outcome that keeps it when the \
         pendulums are symmetric about the bottom (balls swinging apart or together at other \
         amplitudes move it by a few per cent), within 10 %",
    );
}
