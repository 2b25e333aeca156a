//! `ghost_collisions` (issue 19, `docs/cases.md#ghost_collisions`): a
//! 1 m box, and a capsule (cap centres 1 m apart, radius 0.25 m), sliding
//! at 5 m/s without friction along a flat ground made three ways: (a) a
//! chain of 100 unit segments (`scenes/ghost_collisions_chain.toml`, the
//! capsule's `..._chain_capsule.toml`), (b) 100 unit boxes side by side
//! (`..._boxes.toml`), (c) one long box (`..._long_box.toml`). The ground is
//! the plane y = 0 in all three, so the closed form is the same: the slider
//! moves at constant speed, its vertical speed and spin 0 throughout. Each
//! engine (this one's soft step, rapier2d with a polyline for the chain,
//! Box2D with its chain) is read for the largest upward speed and the
//! largest spin of the slider during the slide, from 0.1 s on (the first
//! step's contacts settle).
//!
//! # The tolerance: what a seamless ground allows
//!
//! A box resting on a flat ground is held by contacts whose impulses are
//! warm-started from the last step. Where the support passes from one
//! contact to a new one (a segment's end, a seam), the new contact's
//! impulse starts at zero: for at most one substep h the share it will
//! carry is missing, and the box gains at most g h downward; the contact
//! (over-damped, damping ratio 10) then gives back no more than that
//! speed. So a ground without ghost collisions leaves the box's vertical
//! speed within g h of 0 (0.042 m/s at g = 10 m/s², h = 1/240 s), and its
//! spin within g h/(w/2) (the same speed at a corner, w = 1 m the box's
//! width). A ghost collision, the box's corner stopped by the next
//! segment's or box's end, throws it at a speed of the order of the slide
//! speed (about 2 m/s at 5 m/s): 45 times the bound. A capsule lying on
//! the ground is held at its two core ends, L/2 = 0.5 m from its centre:
//! the same bounds with w/2 read as L/2.
//!
//! # Rows
//!
//! Per engine: where it slides smoothly (the long box for all; the chain
//! for this engine and Box2D), the largest upward speed and spin within
//! that bound of 0 (validation against the closed form); where it does not
//! (the 100 boxes for all; rapier2d's polyline), what happens, recorded
//! (the box is thrown: the bump is above the bound), the figure in the
//! row's value ([`Ground::smooth`]).
//!
//! The sliders ([`SLIDERS`]): the box, and the capsule, whose rounded
//! ends are the other usual remedy for ghost collisions.

use super::joint_common::{Config, Engine, JointScene, Run, steps};
use super::{Case, CaseReport, Snapshots};
use crate::row::{RowKind, RowSink};
use anyhow::{Context, Result};

/// The three grounds.
pub const CASE: Case = Case {
    scenes: &[
        "ghost_collisions_chain",
        "ghost_collisions_boxes",
        "ghost_collisions_long_box",
        "ghost_collisions_chain_capsule",
        "ghost_collisions_boxes_capsule",
        "ghost_collisions_long_box_capsule",
    ],
    snapshots: Snapshots::HarnessOnly(
        "three engines; harness/tests/chain_cases.rs checks the soft step alone with the same \
         rows",
    ),
    ..Case::new(
        "ghost_collisions",
        "Chains: a box and a capsule sliding at 5 m/s over a chain of 100 segments are not bumped at the joins (as on one long box); over 100 boxes they are thrown",
        run,
    )
};

/// A ground of the case: its scene's suffix and what it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ground {
    /// A chain of 100 unit segments.
    Chain,
    /// 100 unit boxes side by side.
    Boxes,
    /// One 100 m box.
    LongBox,
}

impl Ground {
    /// Every ground, in row order.
    pub const ALL: [Ground; 3] = [Ground::Chain, Ground::Boxes, Ground::LongBox];

    /// Its id in scene names and checks.
    pub fn id(self) -> &'static str {
        match self {
            Ground::Chain => "chain",
            Ground::Boxes => "boxes",
            Ground::LongBox => "long_box",
        }
    }

    /// Whether `engine` slides `slider` over this ground without a bump,
    /// as recorded from the runs. The box: every engine on the long box;
    /// on the chain, this engine and Box2D (whose chain segments read their
    /// ghost points) but not rapier2d, whose polyline (parry's, two-sided,
    /// no ghost points or internal-edge handling here) throws the box at a
    /// join as the boxes do (2.25 m/s); on the 100 boxes, none. The
    /// capsule: see [`Slider::Capsule`].
    pub fn smooth(self, engine: Engine, slider: Slider) -> bool {
        match (slider, self) {
            (_, Ground::LongBox) => true,
            (Slider::Box, Ground::Chain) => engine != Engine::Rapier,
            (Slider::Box, Ground::Boxes) => false,
            (Slider::Capsule, Ground::Chain) => CAPSULE_CHAIN_SMOOTH.contains(&engine),
            (Slider::Capsule, Ground::Boxes) => CAPSULE_BOXES_SMOOTH.contains(&engine),
        }
    }
}

/// A slider of the case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slider {
    /// The 1 m box, `scenes/ghost_collisions_<ground>.toml`'s `slider`.
    Box,
    /// The capsule (length 1 m between its cap centres, radius 0.25 m),
    /// `scenes/ghost_collisions_<ground>_capsule.toml`'s `slider`.
    Capsule,
}

impl Slider {
    /// Its scenes' suffix after the ground's id, also its rows'.
    pub fn suffix(self) -> &'static str {
        match self {
            Slider::Box => "",
            Slider::Capsule => "_capsule",
        }
    }

    /// How far from its centre the slider is held (m): the box's
    /// half-width w/2, the capsule's half core length L/2 (its two
    /// supports are its core's ends).
    pub fn arm(self) -> f64 {
        0.5
    }

    /// Its name in the rows' text.
    pub fn label(self) -> &'static str {
        match self {
            Slider::Box => "box",
            Slider::Capsule => "capsule",
        }
    }
}

/// The sliders, in row order (each body is named `slider` in its scenes).
pub const SLIDERS: [Slider; 2] = [Slider::Box, Slider::Capsule];

/// The engines under which the capsule slides over the chain without a
/// bump, as recorded from the runs (docs/cases.md#ghost_collisions): this
/// engine and Box2D (3e-5 and 1e-5 m/s); rapier2d's polyline throws it at
/// 0.78 m/s.
const CAPSULE_CHAIN_SMOOTH: &[Engine] = &[Engine::SoftStep, Engine::Box2d];

/// The engines under which the capsule slides over the 100 boxes without
/// a bump, as recorded from the runs: none, its rounded end still catches
/// the next box's corner (0.79 m/s in all three, under half the box's
/// 1.9).
const CAPSULE_BOXES_SMOOTH: &[Engine] = &[];

/// Reading starts here (s): the first steps' contacts settle.
const SETTLE: f64 = 0.1;

/// The largest upward speed (m/s) and the largest |spin| (rad/s) of body
/// `b` in `run` from [`SETTLE`] on.
pub fn bump(run: &Run, b: usize) -> (f64, f64) {
    run.samples
        .iter()
        .enumerate()
        .filter(|(k, _)| run.time(*k) >= SETTLE)
        .fold((0.0_f64, 0.0_f64), |(up, spin), (_, s)| {
            (
                up.max(s[b].velocity[1]),
                spin.max(s[b].angular_velocity.abs()),
            )
        })
}

/// Runs `ghost_collisions` with rapier2d and Box2D beside.
pub fn run() -> Result<CaseReport> {
    run_sized(true)
}

/// Runs `ghost_collisions`, with rapier2d and Box2D when
/// `reference_engines`.
pub fn run_sized(reference_engines: bool) -> Result<CaseReport> {
    let mut report = CaseReport::default();
    for slider_kind in SLIDERS {
        let (suffix, half_width) = (slider_kind.suffix(), slider_kind.arm());
        for ground in Ground::ALL {
            let id = format!("ghost_collisions_{}{suffix}", ground.id());
            let js = JointScene::load(&id)?;
            let slider = js.body("slider")?;
            let g = js.gravity()?;
            for &engine in Engine::of_run(reference_engines) {
                let config = Config::of(&js.scene, engine)?;
                let h = config.substep();
                let run = js
                    .run(&config, steps(js.scene.duration(), config.dt))
                    .with_context(|| format!("{id} under {}", engine.label()))?;
                let (up, spin) = bump(&run, slider);
                let speed_bound = g * h;
                let spin_bound = g * h / half_width;
                let mut rows = RowSink {
                    case: "ghost_collisions",
                    method: engine.id(),
                    dt: config.dt,
                    rows: &mut report.rows,
                };
                let check = |what: &str| format!("{what}_{}{suffix}", ground.id());
                let bound_reason = format!(
                    "a new contact's impulse starts at zero where the support passes to it, so \
                     for at most one substep h = {h:.6} s the {} misses that support: g h = \
                     {speed_bound:.4} m/s (docs/cases.md#ghost_collisions)",
                    slider_kind.label()
                );
                if ground.smooth(engine, slider_kind) {
                    rows.within(
                        RowKind::Validation,
                        &check("upward_speed"),
                        up,
                        0.0,
                        speed_bound,
                        format!(
                            "validation against the closed form 0 (a {} sliding on the flat \
                             ground y = 0 keeps a zero vertical speed) of the largest upward \
                             speed from {SETTLE} s on, {} under {}. Tolerance: {bound_reason}",
                            slider_kind.label(),
                            ground.id(),
                            engine.label()
                        ),
                    );
                    rows.within(
                        RowKind::Validation,
                        &check("spin"),
                        spin,
                        0.0,
                        spin_bound,
                        format!(
                            "validation against the closed form 0 of the largest |spin| from \
                             {SETTLE} s on. Tolerance g h/(w/2) = {spin_bound:.4} rad/s: the \
                             speed g h at a support, w/2 = {half_width} m from the centre; \
                             {bound_reason}"
                        ),
                    );
                } else {
                    rows.at_least(
                        RowKind::Criterion,
                        &check("upward_speed"),
                        up,
                        speed_bound,
                        0.0,
                        format!(
                            "what happens under {}, recorded: on the {} the {} catches on a \
                             seam (a ghost collision) and is thrown upward, above what a \
                             seamless ground allows ({bound_reason}); the value is the bump. \
                             This engine's chain removes it",
                            engine.label(),
                            match ground {
                                Ground::Chain => "polyline (rapier2d's, without ghost points)",
                                _ => "100 boxes side by side",
                            },
                            slider_kind.label()
                        ),
                    );
                }
            }
        }
    }
    Ok(report)
}
