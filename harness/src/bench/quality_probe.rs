//! What would close a missed quality target: this engine's scene run
//! again, measured, in two ways.
//!
//! # The figure's own spread under rounding
//!
//! A quality figure of a pile (its deepest overlap, its fastest body at
//! the end) comes out of thousands of steps of a chaotic system: a change
//! at the last bit of one coordinate grows until the pile's details
//! differ. Two runs that differ only by rounding say how far the figure
//! moves for no physical reason; a miss smaller than that cannot tell the
//! engines apart.
//!
//! - This engine: the scene with every body (static and kinematic ones
//!   too) moved sideways by [`SHIFT_M`] before the first step, the final
//!   states moved back before the figures are read. The model is
//!   translation-invariant (gravity is uniform, and no stage depends on
//!   where a body is, only on where it is relative to the others), so in
//!   exact arithmetic every figure would be the same; in floating point
//!   every coordinate is a different number and rounds differently. The
//!   shift is a power of two, so moving by it adds at most half an ulp of
//!   each coordinate. It is preferred to mirroring the scene or creating
//!   the bodies in reverse order, which also change the order in which the
//!   solver visits the contacts (a different Gauss–Seidel sweep, not only
//!   rounding): the shift keeps every order the positions decide, but for
//!   near-ties.
//! - Box2D: its builds of one run (f32 AVX2, and with `--box2d-sse2`,
//!   `--box2d-double` its SSE2 build and its f64-positions build), the same
//!   model at other precisions and lane widths: the largest figure less
//!   the smallest.
//!
//! # A setting that closes it
//!
//! The scene is run again with one soft-step setting changed at a time,
//! from a short list ([`SETTINGS`]) aimed at the missed figures, cheapest
//! first; the first setting whose figure meets a target
//! ([`super::targets::at_least_as_good`]) is what closes that target
//! (a setting aimed at another missed figure of the scene counts too: its
//! run measured every figure). The
//! figures are deterministic, so each setting runs once; a setting that
//! closes a target is then timed against the default settings,
//! [`TIMED_REPEATS`] runs each (the runs above among them), and its cost
//! is the ratio of the minima (ms per step). The list stops as soon as every missed target is closed.
//! Sleeping and damping are not in the list: they change what the scene
//! simulates (a sleeping body's speed is zero by fiat), not how well.
//! The benchmark's settings stay Box2D's; the probe only reports.

use super::figures::{DEEPEST_OVERLAP, FASTEST_AT_END, Figures};
use super::measure::{BenchRow, run_engine};
use super::ours::SoftStepEngine;
use super::targets::{QualityTarget, at_least_as_good};
use anyhow::{Context, Result, bail};
use engine::{ContactModel, SoftStepSettings};
use nalgebra::Vector2;
use references::many_body::ManyBodyScene;
use scene::Scene;
use serde::Serialize;

/// The sideways shift of every body in the rounding run (m): 2⁻¹⁰,
/// exact in binary, small beside every benchmark scene's bodies and far
/// above the rounding of their coordinates.
pub const SHIFT_M: f64 = 1.0 / 1024.0;

/// Timed runs of the default settings and of each closing setting; the
/// minimum of each is kept (a shared machine slows a run, never speeds it
/// up). The first of each is the run the probe made anyway (for the
/// default settings the shifted run: the same work, translated), the
/// others alternate. Three, as the profiled runs
/// ([`super::stages::PROFILED_REPEATS`]).
pub const TIMED_REPEATS: usize = 3;

/// A soft-step setting the probe changes, with its value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Setting {
    /// [`SoftStepSettings::push_out_speed`] (m/s).
    PushOutSpeed(f64),
    /// [`SoftStepSettings::contact_damping_ratio`].
    DampingRatio(f64),
    /// [`SoftStepSettings::substeps`].
    Substeps(usize),
    /// [`SoftStepSettings::substeps`] with [`SoftStepSettings::contact_hertz`]
    /// raised to the cap those substeps allow (1/(8h) with h = dt/substeps,
    /// at dt = 1/60 s, every benchmark scene's): the contact spring alone
    /// is already at its cap at 4 substeps (30 Hz), so a stiffer one comes
    /// with the substeps that allow it.
    Stiffer {
        /// Substeps per step.
        substeps: usize,
        /// Contact spring frequency (Hz).
        hertz: f64,
    },
}

impl Setting {
    /// In words, with its unit: "push-out speed 6 m/s", "8 substeps".
    pub fn label(&self) -> String {
        match self {
            Setting::PushOutSpeed(v) => format!("push-out speed {v} m/s"),
            Setting::DampingRatio(z) => format!("contact damping ratio {z}"),
            Setting::Substeps(n) => format!("{n} substeps"),
            Setting::Stiffer { substeps, hertz } => {
                format!("{substeps} substeps with {hertz} Hz contact springs")
            }
        }
    }

    /// `settings` with this one changed.
    pub fn apply(&self, settings: SoftStepSettings) -> SoftStepSettings {
        match *self {
            Setting::PushOutSpeed(v) => SoftStepSettings {
                push_out_speed: v,
                ..settings
            },
            Setting::DampingRatio(z) => SoftStepSettings {
                contact_damping_ratio: z,
                ..settings
            },
            Setting::Substeps(n) => SoftStepSettings {
                substeps: n,
                ..settings
            },
            Setting::Stiffer { substeps, hertz } => SoftStepSettings {
                substeps,
                contact_hertz: hertz,
                ..settings
            },
        }
    }
}

/// Every figure (the substeps are aimed at all of them).
const ALL: &[&str] = &[];

/// The settings tried, in order of cost (the push-out speed and the
/// damping ratio cost nothing per step; substeps cost in proportion),
/// each with the figures it is aimed at (empty: every figure). Against
/// Box2D's defaults (3 m/s, ζ = 10, 4 substeps):
/// - push-out speed 6 m/s: an overlap deeper than the soft spring's reach
///   is pushed out at most at this speed, so twice the speed halves the
///   time a deep overlap (an impact, a pile's deepest contact) lasts;
/// - push-out speed 1.5 m/s: half the speed a push-out gives a body, for
///   the fastest body at the end (a pile's jitter is overlap pushed out);
/// - damping ratio 5: the soft contact's bias rate ω/(2ζ + hω) nearly
///   doubles (30 Hz, h = 1/240 s: 9.1 → 17.5 1/s), a stiffer hold on the
///   overlap at rest;
/// - 5, 6 and 8 substeps: a shorter substep and more solver sweeps per
///   step (Box2D's own advice for a taller stack), at 5/4, 6/4 and 2× the
///   solver's work; the contact spring stays at 30 Hz, so each substep's
///   soft row is softer (its mass scale hω(2ζ + hω)/(1 + hω(2ζ + hω))
///   falls with h);
/// - 6 and 8 substeps with the contact spring at their cap, 45 and 60
///   Hz: a stiffer spring (a resting overlap under a load scales as
///   1/f²), at the substeps' cost.
pub const SETTINGS: [(Setting, &[&str]); 8] = [
    (Setting::PushOutSpeed(6.0), &[DEEPEST_OVERLAP]),
    (Setting::PushOutSpeed(1.5), &[FASTEST_AT_END]),
    (Setting::DampingRatio(5.0), &[DEEPEST_OVERLAP]),
    (Setting::Substeps(5), ALL),
    (Setting::Substeps(6), ALL),
    (
        Setting::Stiffer {
            substeps: 6,
            hertz: 45.0,
        },
        ALL,
    ),
    (Setting::Substeps(8), ALL),
    (
        Setting::Stiffer {
            substeps: 8,
            hertz: 60.0,
        },
        ALL,
    ),
];

/// The settings of [`SETTINGS`] aimed at any of `figures`, in order.
pub fn plan(figures: &[&str]) -> Vec<Setting> {
    SETTINGS
        .iter()
        .filter(|(_, aims)| aims.is_empty() || aims.iter().any(|a| figures.contains(a)))
        .map(|(s, _)| *s)
        .collect()
}

/// [`SETTINGS`] in words, with the figures each is aimed at.
pub fn settings_in_words() -> String {
    SETTINGS
        .iter()
        .map(|(s, aims)| {
            if aims.is_empty() {
                format!("{} (every figure)", s.label())
            } else {
                format!("{} ({})", s.label(), aims.join(", "))
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// How the target tables explain a missed quality target (the report's
/// paragraph): what the probe measures, with its constants.
pub fn explained(probed: bool) -> String {
    if !probed {
        return " A quality target not met is probed by `harness bench` (what would close it);                 this run did not probe."
            .into();
    }
    format!(
        " A quality target not met says how much worse the figure is; how far rounding alone \
         moves it: this engine's figure with every body (static ones too) shifted sideways by \
         {SHIFT_M} m, a translation the model does not see, so that only the rounding of the \
         coordinates differs, and the spread between Box2D's builds measured (when more than \
         one: the largest figure less the smallest); a miss within that spread cannot tell the \
         engines apart. Then the first of these settings, one changed at a time from the \
         scene's (Box2D's defaults), tried cheapest first, that meets the target: {}; with its \
         ms per step against the default's (minimum of {TIMED_REPEATS} runs each, the probe's \
         own runs among them, the shifted run standing for the default), and the settings \
         tried before it. A machine shared with other work makes that ratio the noisiest \
         number here. The benchmark's settings stay Box2D's.",
        settings_in_words()
    )
}

/// What one probe run measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbeRun {
    /// Its quality figures.
    pub figures: Figures,
    /// Its wall time per timed step (ms).
    pub ms_per_step: f64,
}

/// A figure in one build of Box2D.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BuildFigure {
    /// The build (its row's engine name).
    pub engine: String,
    /// The figure.
    pub value: f64,
}

/// A setting tried, and the figure it gave.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Tried {
    /// The setting, in words ([`Setting::label`]).
    pub setting: String,
    /// This engine's figure with it.
    pub value: f64,
}

/// The first setting that meets a target, and what it costs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Closing {
    /// The setting, in words.
    pub setting: String,
    /// This engine's figure with it.
    pub value: f64,
    /// Its ms per step (minimum of [`TIMED_REPEATS`] runs).
    pub ms_per_step: f64,
    /// The default settings' ms per step, timed alternately with it.
    pub default_ms_per_step: f64,
}

impl Closing {
    /// Its cost: its ms per step over the default's.
    pub fn ratio(&self) -> f64 {
        self.ms_per_step / self.default_ms_per_step
    }
}

/// One missed quality target, probed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MissProbe {
    /// The figure's name ([`super::figures`]).
    pub figure: String,
    /// The reference engine.
    pub reference: String,
    /// This engine's figure.
    pub ours: f64,
    /// The reference's figure.
    pub theirs: f64,
    /// This engine's figure with every body shifted by
    /// [`QualityProbe::shift_m`].
    pub shifted: f64,
    /// The figure in each build of Box2D measured at one thread.
    pub box2d_builds: Vec<BuildFigure>,
    /// The settings tried on the scene (aimed at any of its missed
    /// figures), in order, up to the one that closes this target.
    pub tried: Vec<Tried>,
    /// The first setting that meets the target, if one of the list does.
    pub closing: Option<Closing>,
}

impl MissProbe {
    /// How much worse this engine's figure is than the reference's.
    pub fn miss(&self) -> f64 {
        self.ours - self.theirs
    }

    /// How far this engine's figure moves under rounding (the shifted run).
    pub fn our_spread(&self) -> f64 {
        (self.shifted - self.ours).abs()
    }

    /// How far Box2D's builds disagree: the largest figure less the
    /// smallest; `None` with fewer than two builds.
    pub fn box2d_spread(&self) -> Option<f64> {
        if self.box2d_builds.len() < 2 {
            return None;
        }
        let values = self.box2d_builds.iter().map(|b| b.value);
        let max = values.clone().fold(f64::NEG_INFINITY, f64::max);
        let min = values.fold(f64::INFINITY, f64::min);
        Some(max - min)
    }

    /// In words, for the target table's "what would close it".
    pub fn describe(&self, shift_m: f64) -> String {
        let miss = self.miss();
        let mut out = format!(
            "worse by {miss:.2e} ({:.1} %). Rounding alone moves the figure by {:.2e} in this \
             engine (every body shifted {shift_m} m)",
            100.0 * miss / self.theirs.abs().max(f64::MIN_POSITIVE),
            self.our_spread()
        );
        let box2d = self.box2d_spread();
        if let Some(b) = box2d {
            out += &format!(
                " and by {b:.2e} between Box2D's {} builds",
                self.box2d_builds.len()
            );
        }
        let within: Vec<&str> = [
            (miss <= self.our_spread()).then_some("this engine's"),
            box2d.and_then(|b| (miss <= b).then_some("Box2D's")),
        ]
        .into_iter()
        .flatten()
        .collect();
        if within.is_empty() {
            out += ": the miss is larger. ";
        } else {
            out += &format!(
                ": the miss is within {}, so the figure cannot tell the engines apart here. ",
                within.join(" and ")
            );
        }
        let before: Vec<String> = self
            .tried
            .iter()
            .filter(|t| self.closing.as_ref().is_none_or(|c| c.setting != t.setting))
            .map(|t| format!("{} {:.3e}", t.setting, t.value))
            .collect();
        match &self.closing {
            Some(c) => {
                out += &format!(
                    "Closed by {}: {:.3e}, at {:.2}× the ms per step ({:.3} against {:.3} ms)",
                    c.setting,
                    c.value,
                    c.ratio(),
                    c.ms_per_step,
                    c.default_ms_per_step
                );
                if !before.is_empty() {
                    out += &format!("; not by {}", before.join(", "));
                }
            }
            None if before.is_empty() => out += "No setting of the list is aimed at it",
            None => out += &format!("No setting of the list closes it: {}", before.join(", ")),
        }
        out + "."
    }
}

/// Every missed quality target of a scene, probed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct QualityProbe {
    /// The sideways shift of the rounding run (m).
    pub shift_m: f64,
    /// One per missed target, in the targets' order.
    pub misses: Vec<MissProbe>,
}

impl QualityProbe {
    /// What would close the missed target on `figure` against `reference`,
    /// in words, if probed.
    pub fn describe(&self, figure: &str, reference: &str) -> Option<String> {
        self.misses
            .iter()
            .find(|m| m.figure == figure && m.reference == reference)
            .map(|m| m.describe(self.shift_m))
    }
}

/// The index in `tried` of the first run that meets `target`.
fn first_closing(tried: &[(Setting, ProbeRun)], target: &QualityTarget) -> Option<usize> {
    tried.iter().position(|(_, r)| {
        r.figures
            .get(target.figure)
            .is_some_and(|x| at_least_as_good(x, target.theirs))
    })
}

/// The probe of `misses` (missed targets of one scene), Box2D's one-thread
/// builds' figures `box2d`, running this engine through `run`: `run(None,
/// shift)` the default settings with every body shifted sideways by
/// `shift` (m), `run(Some(s), 0.0)` setting `s` changed. `None` when
/// nothing was missed (and nothing runs).
pub fn probe_with(
    misses: &[QualityTarget],
    box2d: &[(String, Figures)],
    mut run: impl FnMut(Option<Setting>, f64) -> Result<ProbeRun>,
) -> Result<Option<QualityProbe>> {
    if misses.is_empty() {
        return Ok(None);
    }
    let shifted = run(None, SHIFT_M)?;
    let figures: Vec<&str> = misses.iter().map(|m| m.figure).collect();
    let mut tried: Vec<(Setting, ProbeRun)> = Vec::new();
    for setting in plan(&figures) {
        if misses.iter().all(|m| first_closing(&tried, m).is_some()) {
            break;
        }
        tried.push((setting, run(Some(setting), 0.0)?));
    }
    // The settings that close a target, each timed once against the
    // default.
    let mut closers: Vec<Setting> = Vec::new();
    for m in misses {
        if let Some(i) = first_closing(&tried, m)
            && !closers.contains(&tried[i].0)
        {
            closers.push(tried[i].0);
        }
    }
    // Their first timed runs are the runs above: the shifted run for the
    // default settings (the same work, translated), each setting's own.
    let mut default_ms = shifted.ms_per_step;
    let mut closer_ms: Vec<f64> = closers
        .iter()
        .map(|c| {
            tried
                .iter()
                .find(|(s, _)| s == c)
                .map_or(f64::INFINITY, |(_, r)| r.ms_per_step)
        })
        .collect();
    if !closers.is_empty() {
        for _ in 1..TIMED_REPEATS {
            default_ms = default_ms.min(run(None, 0.0)?.ms_per_step);
            for (setting, ms) in closers.iter().zip(&mut closer_ms) {
                *ms = ms.min(run(Some(*setting), 0.0)?.ms_per_step);
            }
        }
    }
    let mut out = Vec::new();
    for m in misses {
        let value = |r: &ProbeRun| {
            r.figures
                .get(m.figure)
                .with_context(|| format!("the probe run has no {}", m.figure))
        };
        let closed = first_closing(&tried, m);
        let mut tried_here = Vec::new();
        for (setting, r) in &tried[..closed.map_or(tried.len(), |i| i + 1)] {
            tried_here.push(Tried {
                setting: setting.label(),
                value: value(r)?,
            });
        }
        let closing = match closed {
            Some(i) => {
                let setting = tried[i].0;
                let Some(k) = closers.iter().position(|c| *c == setting) else {
                    bail!("{} closes a target but was not timed", setting.label());
                };
                Some(Closing {
                    setting: setting.label(),
                    value: value(&tried[i].1)?,
                    ms_per_step: closer_ms[k],
                    default_ms_per_step: default_ms,
                })
            }
            None => None,
        };
        out.push(MissProbe {
            figure: m.figure.to_string(),
            reference: m.reference.clone(),
            ours: m.ours,
            theirs: m.theirs,
            shifted: value(&shifted)?,
            box2d_builds: box2d
                .iter()
                .filter_map(|(engine, f)| {
                    f.get(m.figure).map(|value| BuildFigure {
                        engine: engine.clone(),
                        value,
                    })
                })
                .collect(),
            tried: tried_here,
            closing,
        });
    }
    Ok(Some(QualityProbe {
        shift_m: SHIFT_M,
        misses: out,
    }))
}

/// The probe of `misses` on `scene` (its neutral form `neutral`, body
/// `top` watched, `steps` timed steps as the rows'), with the Box2D builds
/// of `rows` at one thread.
pub fn probe(
    scene: &Scene,
    neutral: &ManyBodyScene,
    top: Option<usize>,
    steps: usize,
    rows: &[BenchRow],
    misses: &[QualityTarget],
) -> Result<Option<QualityProbe>> {
    let box2d: Vec<(String, Figures)> = rows
        .iter()
        .filter(|b| b.threads == 1 && b.engine.starts_with("Box2D"))
        .map(|b| (b.engine.clone(), Figures::of_row(b)))
        .collect();
    probe_with(misses, &box2d, |setting, shift| {
        run_ours(scene, neutral, top, steps, setting, shift).with_context(|| {
            format!(
                "the quality probe with {}",
                setting.map_or(format!("every body shifted {shift} m"), |s| s.label())
            )
        })
    })
}

/// One run of this engine on `scene` at one thread: `setting` changed,
/// every body shifted sideways by `shift` (m) before the first step and
/// its final state shifted back; step 0 untimed, then `steps` timed.
fn run_ours(
    scene: &Scene,
    neutral: &ManyBodyScene,
    top: Option<usize>,
    steps: usize,
    setting: Option<Setting>,
    shift: f64,
) -> Result<ProbeRun> {
    let mut world = scene
        .build_world(None)
        .with_context(|| format!("building {}", scene.origin()))?;
    if shift != 0.0 {
        for id in 0..world.bodies().len() {
            let s = world.states()[id];
            world.set_pose(id, s.position + Vector2::new(shift, 0.0), s.angle)?;
        }
    }
    let Some(ContactModel::SoftStep(settings)) = world.contact_model() else {
        bail!("{} is not a soft-step scene", scene.origin());
    };
    let settings = SoftStepSettings {
        threads: 1,
        ..setting.map_or(settings, |s| s.apply(settings))
    };
    world.set_contact_model(ContactModel::SoftStep(settings))?;
    let mut engine = SoftStepEngine::from_world(world, scene.dt(), false)?;
    let mut run = run_engine(&mut engine, steps)?;
    for s in &mut run.samples {
        s.position[0] -= shift;
    }
    Ok(ProbeRun {
        figures: Figures::of(neutral, top, &run.samples),
        ms_per_step: 1e3 * run.per_step.as_secs_f64(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn figures(overlap: f64, fastest: f64) -> Figures {
        Figures {
            deepest_overlap: overlap,
            fastest_at_end: fastest,
            ..Figures::default()
        }
    }

    fn target(figure: &'static str, ours: f64, theirs: f64) -> QualityTarget {
        QualityTarget {
            figure,
            reference: "Box2D".into(),
            ours,
            theirs,
        }
    }

    #[test]
    fn the_plan_keeps_the_settings_aimed_at_the_figures_in_order() {
        let (six, eight) = (
            Setting::Stiffer {
                substeps: 6,
                hertz: 45.0,
            },
            Setting::Stiffer {
                substeps: 8,
                hertz: 60.0,
            },
        );
        assert_eq!(
            plan(&[DEEPEST_OVERLAP]),
            [
                Setting::PushOutSpeed(6.0),
                Setting::DampingRatio(5.0),
                Setting::Substeps(5),
                Setting::Substeps(6),
                six,
                Setting::Substeps(8),
                eight
            ]
        );
        assert_eq!(
            plan(&[FASTEST_AT_END]),
            [
                Setting::PushOutSpeed(1.5),
                Setting::Substeps(5),
                Setting::Substeps(6),
                six,
                Setting::Substeps(8),
                eight
            ]
        );
        assert_eq!(plan(&[DEEPEST_OVERLAP, FASTEST_AT_END]).len(), 8);
        // A figure no special setting aims at: the substeps alone.
        assert_eq!(plan(&["top sink (m)"]).len(), 5);
        // The caps by hand: 1/(8h) = substeps × 60 Hz / 8 at dt = 1/60 s.
        let cap = |n: usize| n as f64 * 60.0 / 8.0;
        assert_eq!((cap(6), cap(8)), (45.0, 60.0));
        assert_eq!(eight.apply(SoftStepSettings::default()).contact_hertz, 60.0);
        assert_eq!(six.label(), "6 substeps with 45 Hz contact springs");
        let s = Setting::Substeps(8).apply(SoftStepSettings::default());
        assert_eq!(s.substeps, 8);
        assert_eq!(
            Setting::PushOutSpeed(6.0)
                .apply(SoftStepSettings::default())
                .push_out_speed,
            6.0
        );
        assert_eq!(
            Setting::DampingRatio(5.0).label(),
            "contact damping ratio 5"
        );
        assert_eq!(Setting::PushOutSpeed(1.5).label(), "push-out speed 1.5 m/s");
    }

    /// A fake engine: each setting's figures (overlap, fastest) and ms per
    /// step; records the calls.
    fn fake(calls: &mut Vec<String>) -> impl FnMut(Option<Setting>, f64) -> Result<ProbeRun> + '_ {
        move |setting, shift| {
            let (overlap, fastest, ms) = match setting {
                None if shift != 0.0 => (1.10, 2.2, 1.0),
                None => (1.05, 2.0, 1.0),
                Some(Setting::PushOutSpeed(v)) if v > 3.0 => (1.04, 2.1, 1.0),
                Some(Setting::PushOutSpeed(_)) => (1.2, 1.9, 1.0),
                Some(Setting::DampingRatio(_)) => (1.03, 2.0, 1.0),
                Some(Setting::Substeps(5)) => (1.01, 1.95, 1.25),
                Some(Setting::Substeps(6)) => (0.99, 1.5, 1.5),
                Some(Setting::Stiffer { substeps: 6, .. }) => (0.95, 1.45, 1.6),
                Some(Setting::Stiffer { .. }) => (0.8, 1.3, 2.1),
                Some(Setting::Substeps(_)) => (0.9, 1.4, 2.0),
            };
            calls.push(setting.map_or(format!("shift {shift}"), |s| s.label()));
            Ok(ProbeRun {
                figures: figures(overlap, fastest),
                ms_per_step: ms,
            })
        }
    }

    #[test]
    fn each_miss_gets_the_first_setting_that_meets_it_and_the_list_stops_there() {
        // Overlap 1.05 against 1.0 (5 % worse); fastest 2.0 against 1.5.
        let misses = [
            target(DEEPEST_OVERLAP, 1.05, 1.0),
            target(FASTEST_AT_END, 2.0, 1.5),
        ];
        let box2d = [
            ("Box2D f32".to_string(), figures(1.0, 1.5)),
            ("Box2D f64".to_string(), figures(1.08, 1.6)),
        ];
        let mut calls = Vec::new();
        let p = probe_with(&misses, &box2d, fake(&mut calls))
            .unwrap()
            .unwrap();
        // Overlap: 6 m/s 1.04, 1.5 m/s (not aimed), ζ 5 1.03, 5 substeps
        // 1.01 (within 1 % of 1.0: met). Fastest: 6 substeps 1.5 (met);
        // the list stops there, 8 substeps never runs. Then the timed
        // rounds of the default, 5 and 6 substeps, but the first: the runs
        // above (the shifted one for the default).
        let mut want: Vec<String> = ["shift 0.0009765625", "push-out speed 6 m/s"]
            .map(String::from)
            .into();
        want.extend(
            [
                "push-out speed 1.5 m/s",
                "contact damping ratio 5",
                "5 substeps",
                "6 substeps",
            ]
            .map(String::from),
        );
        for _ in 1..TIMED_REPEATS {
            want.extend(["shift 0", "5 substeps", "6 substeps"].map(String::from));
        }
        assert_eq!(calls, want);
        let overlap = &p.misses[0];
        let tried: Vec<&str> = overlap.tried.iter().map(|t| t.setting.as_str()).collect();
        assert_eq!(
            tried,
            [
                "push-out speed 6 m/s",
                "push-out speed 1.5 m/s",
                "contact damping ratio 5",
                "5 substeps"
            ]
        );
        let c = overlap.closing.as_ref().unwrap();
        assert_eq!(
            (c.setting.as_str(), c.value, c.ratio()),
            ("5 substeps", 1.01, 1.25)
        );
        // By hand: |1.10 − 1.05| = 0.05; Box2D's builds 1.08 − 1.0 = 0.08;
        // the miss 0.05 is within both.
        assert!((overlap.our_spread() - 0.05).abs() < 1e-12);
        assert!((overlap.box2d_spread().unwrap() - 0.08).abs() < 1e-12);
        assert_eq!(
            p.describe(DEEPEST_OVERLAP, "Box2D").unwrap(),
            "worse by 5.00e-2 (5.0 %). Rounding alone moves the figure by 5.00e-2 in this \
             engine (every body shifted 0.0009765625 m) and by 8.00e-2 between Box2D's 2 \
             builds: the miss is within this engine's and Box2D's, so the figure cannot tell \
             the engines apart here. Closed by 5 substeps: 1.010e0, at 1.25× the ms per step \
             (1.250 against 1.000 ms); not by push-out speed 6 m/s 1.040e0, push-out speed \
             1.5 m/s 1.200e0, contact damping ratio 5 1.030e0."
        );
        let fastest = &p.misses[1];
        assert_eq!(fastest.closing.as_ref().unwrap().setting, "6 substeps");
        // 0.5 worse; spreads 0.2 and 0.1: larger.
        assert!(
            p.describe(FASTEST_AT_END, "Box2D")
                .unwrap()
                .contains("between Box2D's 2 builds: the miss is larger. Closed by 6 substeps")
        );
        // Another reference's target was not probed here.
        assert_eq!(p.describe(DEEPEST_OVERLAP, "rapier2d"), None);
    }

    #[test]
    fn a_miss_no_setting_closes_says_so_and_nothing_is_timed() {
        let misses = [target(DEEPEST_OVERLAP, 1.05, 0.5)];
        let mut calls = Vec::new();
        let p = probe_with(&misses, &[], fake(&mut calls)).unwrap().unwrap();
        // The shift, then every setting aimed at the overlap; no timing.
        assert_eq!(calls.len(), 1 + 7, "{calls:?}");
        let m = &p.misses[0];
        assert_eq!(m.closing, None);
        assert_eq!(m.box2d_spread(), None);
        let text = m.describe(p.shift_m);
        assert!(
            text.contains(
                "in this engine (every body shifted 0.0009765625 m): the miss is larger."
            ) && text.ends_with(
                "No setting of the list closes it: push-out speed 6 m/s 1.040e0, contact \
                     damping ratio 5 1.030e0, 5 substeps 1.010e0, 6 substeps 9.900e-1, 6 \
                     substeps with 45 Hz contact springs 9.500e-1, 8 substeps 9.000e-1, 8 \
                     substeps with 60 Hz contact springs 8.000e-1."
            ),
            "{text}"
        );
        // Nothing missed: nothing runs.
        let mut calls = Vec::new();
        assert_eq!(probe_with(&[], &[], fake(&mut calls)).unwrap(), None);
        assert!(calls.is_empty());
    }
}
