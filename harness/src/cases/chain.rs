//! `chain` (`docs/cases.md#chain`): 20 links of 0.6 m hung between two
//! anchors 10 m apart (`scenes/chain.toml`), started as a "V", damped at
//! their joints until at rest; then every pin against the exact
//! equilibrium of the chain.
//!
//! # What the pins are compared with
//!
//! - **The elastic equilibrium** (`references::elastic_chain`): rigid
//!   uniform links on pins that open under their load as a soft row does
//!   at rest, d = −K F/ω_c² (the static sink of `docs/joints.md`, exact at
//!   rest: the soft update vanishes at v = 0 exactly there), ω_c = 2π ×
//!   60 Hz. This is what the soft step and Box2D (the same rows) must rest
//!   on, to the rest criterion.
//! - **The rigid equilibrium** (`references::catenary::DiscreteChain`,
//!   the exact discrete catenary of 20 links): the pins hang lower by the
//!   pins' accumulated sag, about 1.1 mm of opening per pin under the
//!   chain's tension (2H/(m ω_c²)), 2.2 cm at midspan. The tolerance
//!   against it is that sag's effect, the elastic equilibrium's distance
//!   from the rigid one, plus the rest criterion.
//! - The continuous catenary, for reference: a chain of rigid links does
//!   not rest on it (3.8 mm off at midspan for 20 links).
//!
//! # The rest criterion
//!
//! The joints' dampers (springs of 0.001 Hz and damping ratio 1e5) bring
//! the chain to rest; what motion is left, at speed v, swings about the
//! equilibrium by at most v/ω_min, ω_min the chain's slowest mode: its
//! sway is a pendulum of its 2.9 m sag (3.4 s), so 10 s bounds every
//! period. The dampers' stiffness holds each link with at most
//! τ = m_eff ω² π (an angle error below π), which turns a link under the
//! tension H by at most 2τ/(ℓ H) and moves the pins by at most
//! 4 n τ/H. Box2D's positions are f32 (9.5e-7 m at 10 m).

use super::joint_common::{Config, Engine, JointScene, Run, SoftRows, steps};
use super::{Case, CaseReport, Headline, Snapshots};
use crate::row::{RowKind, RowSink};
use anyhow::{Result, bail};
use engine::Shape;
use references::catenary::{Catenary, DiscreteChain};
use references::elastic_chain::{ElasticChain, ElasticRest};
use references::many_body::JointKind;
use references::pendulum::polygon_area_moment;
use std::f64::consts::PI;

/// A chain at rest between two anchors.
pub const CASE: Case = Case {
    scenes: &["chain"],
    snapshots: Snapshots::HarnessOnly(
        "60 s of 20 links in three engines; harness/tests/joint_cases.rs checks the soft step \
         alone with the same rows",
    ),
    headline: &[Headline::new("pins_vs_elastic", "soft_step")],
    ..Case::new(
        "chain",
        "Joints: a chain of 20 links at rest between two anchors against its exact discrete equilibrium",
        run,
    )
};

/// The longest period of the chain's swing (s): its sag of 2.9 m swings as
/// a pendulum in 2π √(2.9/9.81) = 3.4 s; 10 s bounds every mode.
const SLOWEST_PERIOD: f64 = 10.0;

/// Box2D's single-precision positions: an ulp of 9.5e-7 m at 10 m, two of
/// them for a pin built from a pose.
const BOX2D_ROUNDING: f64 = 2e-6;

/// Runs `chain`.
pub fn run() -> Result<CaseReport> {
    run_sized(true)
}

/// The chain's geometry, read from the scene.
struct Geometry {
    links: Vec<usize>,
    start: [f64; 2],
    end: [f64; 2],
    link_length: f64,
    mass: f64,
    inertia: f64,
    /// The dampers' largest torque (N·m), m_eff ω² π.
    damper_torque: f64,
}

fn geometry(js: &JointScene) -> Result<Geometry> {
    let links: Vec<usize> = (0..js.scene.bodies().len())
        .filter(|&b| js.neutral.bodies[b].mass() > 0.0)
        .collect();
    let n = links.len();
    let joints = &js.neutral.joints;
    if joints.len() != n + 1 || n < 2 {
        bail!("chain: n links need n + 1 pins");
    }
    let (start, end) = (joints[0].anchors().0, joints[n].anchors().1);
    let body = &js.neutral.bodies[links[0]];
    let Shape::Polygon(p) = &body.shape else {
        bail!("chain: the links are boxes");
    };
    let vertices: Vec<[f64; 2]> = p.vertices().iter().map(|v| [v.x, v.y]).collect();
    let (area, _, j) = polygon_area_moment(&vertices);
    let link_length = vertices.iter().map(|v| v[0]).fold(f64::MIN, f64::max)
        - vertices.iter().map(|v| v[0]).fold(f64::MAX, f64::min);
    let mass = body.mass();
    let inertia = mass * j / area;
    // The dampers: revolute springs; the stiffest acts on the end pins
    // (one link: m_eff = I).
    let mut damper_torque: f64 = 0.0;
    for joint in joints {
        let JointKind::Revolute(r) = joint.kind else {
            bail!("chain: the pins are revolute joints");
        };
        if let Some(s) = r.spring {
            let omega = 2.0 * PI * s.hertz;
            damper_torque = damper_torque.max(inertia * omega * omega * PI);
        }
    }
    Ok(Geometry {
        links,
        start,
        end,
        link_length,
        mass,
        inertia,
        damper_torque,
    })
}

/// The pins of the chain in the last sample of `run`: each link's left end,
/// then the last link's right end (m).
fn pins(g: &Geometry, run: &Run) -> Vec<[f64; 2]> {
    let last = run.samples.last().expect("a run has samples");
    let a = 0.5 * g.link_length;
    let end = |b: usize, side: f64| {
        let s = &last[b];
        let (sin, cos) = s.angle.sin_cos();
        [
            s.position[0] + side * a * cos,
            s.position[1] + side * a * sin,
        ]
    };
    let mut out: Vec<[f64; 2]> = g.links.iter().map(|&b| end(b, -1.0)).collect();
    out.push(end(g.links[g.links.len() - 1], 1.0));
    out
}

/// The largest point speed of any link in the last sample (m/s): its
/// centre's speed plus ω times half its length.
fn fastest(g: &Geometry, run: &Run) -> f64 {
    let last = run.samples.last().expect("a run has samples");
    g.links
        .iter()
        .map(|&b| last[b].speed() + last[b].angular_velocity.abs() * 0.5 * g.link_length)
        .fold(0.0, f64::max)
}

fn largest_distance(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
        .fold(0.0, f64::max)
}

/// Runs `chain`, with rapier2d and Box2D when `reference_engines`.
pub fn run_sized(reference_engines: bool) -> Result<CaseReport> {
    let js = JointScene::load("chain")?;
    let g = geometry(&js)?;
    let n = g.links.len();
    let gravity = js.gravity()?;
    let length = n as f64 * g.link_length;
    let rigid = DiscreteChain::solve(g.start, g.end, length, n)?;
    let base = Config::of(&js.scene, Engine::SoftStep)?;
    let rows_model = SoftRows::defaults(base.substep());
    let elastic_chain = ElasticChain {
        links: n,
        link_length: g.link_length,
        mass: g.mass,
        inertia: g.inertia,
        gravity,
        omega: rows_model.omega,
    };
    let elastic: ElasticRest = elastic_chain.solve(g.start, g.end)?;
    let sag_effect = largest_distance(&elastic.pins, &rigid.joints);
    let h = elastic.horizontal_force;
    let springs = 4.0 * n as f64 * g.damper_torque / h;
    let mut report = CaseReport::default();
    for &engine in Engine::of_run(reference_engines) {
        let config = Config::of(&js.scene, engine)?;
        let run = js.run(&config, steps(js.scene.duration(), config.dt))?;
        let at_rest = pins(&g, &run);
        let speed = fastest(&g, &run);
        let rest = speed * SLOWEST_PERIOD / (2.0 * PI);
        let rounding = if engine == Engine::Box2d {
            BOX2D_ROUNDING
        } else {
            0.0
        };
        let vs_elastic = largest_distance(&at_rest, &elastic.pins);
        let vs_rigid = largest_distance(&at_rest, &rigid.joints);
        let separation = js
            .largest_separations(&Run {
                samples: vec![run.samples.last().expect("samples").clone()],
                ..run.clone()
            })
            .into_iter()
            .fold(0.0, f64::max);
        let midspan = at_rest[n / 2];
        let measured = format!(
            "{} after {} s: fastest point {speed:.1e} m/s; pins off the elastic equilibrium by \
             {vs_elastic:.2e} m at most, off the rigid one by {vs_rigid:.3e} m (the pins' sag \
             moves the elastic one {sag_effect:.3e} m from it); midspan pin at \
             ({:.6}, {:.6}) m (elastic {:.6}, rigid {:.6}); largest pin opening \
             {separation:.3e} m (elastic {:.3e}).",
            engine.label(),
            js.scene.duration(),
            midspan[0],
            midspan[1],
            elastic.pins[n / 2][1],
            rigid.joints[n / 2][1],
            elastic
                .separations
                .iter()
                .map(|d| d[0].hypot(d[1]))
                .fold(0.0, f64::max)
        );
        if engine == Engine::Rapier {
            report.notes.push(format!(
                "{measured} Informational: rapier's pins are rigid (1e6 Hz) but not warm-started \
                 and solved once per substep, so under the chain's tension they open by \
                 millimetres and its chain does not settle as the soft rows' does; no bound is \
                 derived for its solver."
            ));
            continue;
        }
        report.notes.push(measured);
        let mut sink = RowSink {
            case: "chain",
            method: engine.id(),
            dt: config.dt,
            rows: &mut report.rows,
        };
        let terms = format!(
            "the rest criterion, the fastest point's {speed:.1e} m/s times {SLOWEST_PERIOD} \
             s/(2π) (the chain's slowest swing is slower than 3.4 s, the pendulum of its 2.9 m \
             sag) = {rest:.1e} m; the dampers' stiffness, 4 n τ/H with τ = m_eff ω² π = \
             {:.1e} N·m and H = {h:.3} N: {springs:.1e} m{}",
            g.damper_torque,
            if rounding > 0.0 {
                format!("; Box2D's f32 positions, {rounding:.0e} m")
            } else {
                String::new()
            }
        );
        sink.at_most(
            RowKind::Validation,
            "pins_vs_elastic",
            vs_elastic,
            0.0,
            rest + springs + rounding,
            format!(
                "largest distance (m) of the {} pins at rest (each link's left end, the last's \
                 right end) from the elastic equilibrium: rigid links on pins that open as the \
                 soft rows do at rest, d = −K F/ω_c², ω_c = 2π × 60 Hz (references' \
                 ElasticChain, Newton to 1e-13 m). Tolerance: {terms}",
                n + 1
            ),
        );
        sink.at_most(
            RowKind::Validation,
            "pins_vs_rigid",
            vs_rigid,
            0.0,
            sag_effect + rest + springs + rounding,
            format!(
                "largest distance (m) of the pins at rest from the exact equilibrium of {n} \
                 rigid links (references' DiscreteChain, H = {:.4} link weights). Tolerance: \
                 the pins' accumulated sag, F/(m_eff ω_c²) each along the chain (about {:.1} \
                 mm per pin), which moves the equilibrium {sag_effect:.3e} m (the elastic \
                 equilibrium's largest distance from the rigid one); plus {terms}",
                rigid.horizontal_force,
                2e3 * h / (g.mass * rows_model.omega.powi(2)),
            ),
        );
    }
    let catenary = Catenary::through(g.start, g.end, length)?;
    let lowest = catenary.y(catenary.x0);
    report.notes.push(format!(
        "References: the continuous catenary through the anchors with 12 m of chain has a = \
         {:.6} m and its lowest point at y = {lowest:.6} m; the rigid 20-link chain's midspan \
         pin hangs at {:.6} m ({:.2e} m lower: links are not a continuum), the elastic one at \
         {:.6} m. The sag of the soft pins is the model's (60 Hz rows), not an error of the \
         solver: with stiffer pins it shrinks as 1/ω_c².",
        catenary.a,
        rigid.joints[n / 2][1],
        lowest - rigid.joints[n / 2][1],
        elastic.pins[n / 2][1],
    ));
    Ok(report)
}
