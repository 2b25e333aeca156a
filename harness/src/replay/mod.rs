//! The interactive replay: one self-contained HTML page (`simulate
//! --html out.html`, and `reports/replays/<case>.html` for every case)
//! that plays a run back in any browser, offline, with no build step: the
//! page's script and style are inline (`replay.html`, `replay.js`,
//! `replay.css` beside this file, included at compile time) and the trace
//! is embedded as compact JSON ([`encode`] documents the format).
//!
//! What the page does: play, pause, step forward and back (by the
//! recorded sample spacing), a scrub bar with the events marked on it, a
//! speed control, zoom (mouse wheel, about the cursor) and pan (drag),
//! each body's path up to the current time (toggleable), each body at its
//! true size in its scene colour (static bodies without a colour of their
//! own in grey), springs, the ground lines of landing events, event
//! markers, the time, and a body's state (position, angle, velocities,
//! kinetic energy, and the world's energy when the run has it) on hover or,
//! pinned, in the side panel. With several runs (`--compare`) the engines
//! are shown side by side or overlaid, in sync, each labelled.
//!
//! The URL fragment sets the start: `#t=1.25` shows t = 1.25 s paused,
//! `#play=1.25` plays from 0 and stops at 1.25 s, `speed=2`, `body=NAME`
//! pins a body, `mode=overlay`, `traces=0`; joined with `&`.
//!
//! # View transform (what the browser test relies on)
//!
//! The page is laid out in fixed boxes (CSS pixels): a header of
//! [`HEADER_PX`], a side panel of [`SIDE_PX`] on the right, a control bar
//! of [`FOOTER_PX`] at the bottom; the canvas fills the rest, from
//! (0, [`HEADER_PX`]). With `n` runs side by side it is split into `n`
//! panels of equal width (one panel when overlaid). The world box
//! `data.view` = [x0, y0, x1, y1] (m) is fitted into each panel:
//! scale s = [`FILL`] × min(panel width / (x1 − x0), panel height /
//! (y1 − y0)) px/m, the box centre at the panel centre, y up. Zoom z and
//! pan (dx, dy) px then map a world point (x, y) to (cx + dx + z s (x −
//! xc), cy + dy − z s (y − yc)). The page writes the transform it uses on
//! the canvas as `data-*` attributes.
//!
//! # Size
//!
//! A run keeps only the samples that linear interpolation cannot replace
//! within a tolerance ([`thin`]): first 1/2000 of the view's size (half a
//! pixel on a 1000-pixel view), doubled until the page fits
//! [`BUDGET_BYTES`] (2 MiB), up to 1/25 of the view; past that the page is
//! written larger and says so. A body that never moves is stored once.

mod encode;
mod thin;

use crate::pictures::film::{fit_statics, grounds, shape_radius, springs};
use anyhow::Result;
use engine::{Body, BodyKind, BodyState, EventRecord, Shape};
use nalgebra::Vector2;
use scene::format::EventEntry;
use scene::{Colour, Scene};

/// Height of the page's header (CSS px).
pub const HEADER_PX: f64 = 48.0;
/// Width of the side panel (CSS px).
pub const SIDE_PX: f64 = 320.0;
/// Height of the control bar (CSS px).
pub const FOOTER_PX: f64 = 96.0;
/// Share of a panel the world box fills along its tighter axis.
pub const FILL: f64 = 0.92;
/// The size a page aims at (bytes): 2 MiB.
pub const BUDGET_BYTES: usize = 2 << 20;
/// First interpolation tolerance, as a share of the view's size.
pub const FIRST_TOLERANCE: f64 = 1.0 / 2000.0;
/// Coarsest interpolation tolerance, as a share of the view's size.
pub const LAST_TOLERANCE: f64 = 1.0 / 25.0;
/// Colour of a static body whose scene gives it none.
pub const STATIC_GREY: Colour = Colour::rgb(0x9e, 0x9e, 0x9e);

const TEMPLATE: &str = include_str!("replay.html");
const SCRIPT: &str = include_str!("replay.js");
const STYLE: &str = include_str!("replay.css");

/// How one body is drawn and what the readout needs of it.
#[derive(Debug, Clone)]
pub struct ReplayBody {
    /// Its name in the scene.
    pub name: String,
    /// Fill colour.
    pub colour: Colour,
    /// `"dynamic"`, `"static"` or `"kinematic"`.
    pub kind: &'static str,
    /// Mass (kg) of a dynamic body.
    pub mass: Option<f64>,
    /// Moment of inertia (kg·m²) of a dynamic body that rotates.
    pub inertia: Option<f64>,
    /// Largest distance from the centre of mass to the outline (m); 0 for
    /// a particle.
    pub radius: f64,
    /// Shape, centred on the centre of mass; `None` for a particle (a dot).
    pub shape: Option<Shape>,
}

pub use crate::pictures::film::SpringEnd;

/// A located event, marked once its time has passed.
#[derive(Debug, Clone, PartialEq)]
pub struct ReplayEvent {
    /// Its name (`apex`, `landing`).
    pub name: String,
    /// When (s).
    pub t: f64,
    /// The body the scene's event watches.
    pub body: Option<usize>,
    /// Where that body's centre was (m).
    pub position: Option<Vector2<f64>>,
}

impl ReplayEvent {
    /// The events of a run of `scene`, each at the body its scene event
    /// watches.
    pub fn from_records(scene: &Scene, records: &[EventRecord]) -> Vec<Self> {
        records
            .iter()
            .map(|record| {
                let body = scene.file().events.iter().find_map(|e| match e {
                    EventEntry::Landing { body, .. } if record.name == "landing" => {
                        scene.body_id(body)
                    }
                    EventEntry::Apex { body } if record.name == "apex" => scene.body_id(body),
                    _ => None,
                });
                Self {
                    name: record.name.clone(),
                    t: record.t,
                    body,
                    position: body.and_then(|b| record.states.get(b)).map(|s| s.position),
                }
            })
            .collect()
    }
}

/// One engine's run, sampled.
#[derive(Debug, Clone, Default)]
pub struct ReplayRun {
    /// The label shown over its panel (engine, method, step).
    pub label: String,
    /// A short name for table headers (`engine`, `rapier2d`, `Box2D`).
    pub short: String,
    /// Sample times (s), increasing.
    pub times: Vec<f64>,
    /// Every body's state at each sample (unwrapped angles).
    pub states: Vec<Vec<BodyState>>,
    /// The world's total energy at each sample (J), when known.
    pub energies: Option<Vec<f64>>,
    /// Located events.
    pub events: Vec<ReplayEvent>,
}

/// A replay page in the making: the scene's bodies, the runs, notes.
#[derive(Debug, Clone)]
pub struct Replay {
    /// First title line.
    pub title: String,
    /// Second title line.
    pub subtitle: String,
    /// Every body, in scene order.
    pub bodies: Vec<ReplayBody>,
    /// Springs.
    pub springs: Vec<(SpringEnd, SpringEnd)>,
    /// Levels of landing events (m).
    pub grounds: Vec<f64>,
    /// The runs; the first is the engine's.
    pub runs: Vec<ReplayRun>,
    /// Lines shown in the side panel.
    pub notes: Vec<String>,
    /// What the step buttons move (s): the recorded sample spacing.
    pub step: f64,
    view: (Vector2<f64>, Vector2<f64>),
}

/// A written page and what it holds.
#[derive(Debug, Clone)]
pub struct Page {
    /// The HTML text.
    pub html: String,
    /// Frames kept per run.
    pub frames: Vec<usize>,
    /// The interpolation tolerance used (m).
    pub tolerance: f64,
}

impl Replay {
    /// A replay of `scene`, whose world has `bodies` (as `World::bodies`
    /// gives them: shapes centred on the centre of mass), with no run yet.
    /// `step` (s) is what the step buttons move.
    pub fn new(scene: &Scene, bodies: &[Body], title: String, subtitle: String, step: f64) -> Self {
        let colours = scene.colours();
        let given = |i: usize| {
            scene
                .file()
                .bodies
                .get(i)
                .is_some_and(|b| b.colour.is_some())
        };
        let looks = bodies
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let palette = colours.get(i).copied().unwrap_or(Colour::default_for(i));
                let dynamic = b.is_dynamic();
                ReplayBody {
                    name: b.name.clone(),
                    colour: if dynamic || given(i) {
                        palette
                    } else {
                        STATIC_GREY
                    },
                    kind: match b.kind {
                        BodyKind::Dynamic => "dynamic",
                        BodyKind::Static => "static",
                        BodyKind::Kinematic => "kinematic",
                    },
                    mass: dynamic.then_some(b.mass),
                    inertia: if dynamic { b.inertia } else { None },
                    radius: b.shape.as_ref().map_or(0.0, shape_radius),
                    shape: b.shape.clone(),
                }
            })
            .collect();
        Self {
            title,
            subtitle,
            bodies: looks,
            springs: springs(scene),
            grounds: grounds(scene),
            runs: Vec::new(),
            notes: Vec::new(),
            step,
            view: (Vector2::zeros(), Vector2::repeat(1.0)),
        }
    }

    /// The larger side of the view box (m).
    fn view_size(&self) -> f64 {
        let d = self.view.1 - self.view.0;
        d.x.max(d.y)
    }

    /// The world box shown at load: every moving body at its true size
    /// over every run, the spring anchors, the ground lines, and the
    /// static bodies where they come near the moving part (a 20 m floor
    /// under a ball is cut to half the moving part's size around it).
    fn compute_view(&mut self) {
        let mut lo = Vector2::repeat(f64::INFINITY);
        let mut hi = Vector2::repeat(f64::NEG_INFINITY);
        let mut add = |p: Vector2<f64>, r: f64| {
            if p.x.is_finite() && p.y.is_finite() {
                lo = lo.inf(&(p - Vector2::repeat(r)));
                hi = hi.sup(&(p + Vector2::repeat(r)));
            }
        };
        for run in &self.runs {
            for states in &run.states {
                for (body, s) in self.bodies.iter().zip(states) {
                    if body.kind != "static" {
                        add(s.position, body.radius);
                    }
                }
            }
        }
        for (a, b) in &self.springs {
            for end in [a, b] {
                if let SpringEnd::World(p) = end {
                    add(*p, 0.0);
                }
            }
        }
        let first = self.runs.first().and_then(|r| r.states.first());
        let statics: Vec<(Vector2<f64>, Vector2<f64>)> = first
            .map(|states| {
                self.bodies
                    .iter()
                    .zip(states)
                    .filter(|(b, _)| b.kind == "static")
                    .map(|(b, s)| {
                        let r = Vector2::repeat(b.radius);
                        (s.position - r, s.position + r)
                    })
                    .collect()
            })
            .unwrap_or_default();
        (lo, hi) = fit_statics((lo, hi), statics, &self.grounds);
        if !(lo.x.is_finite() && lo.y.is_finite() && hi.x.is_finite() && hi.y.is_finite()) {
            lo = Vector2::repeat(-1.0);
            hi = Vector2::repeat(1.0);
        }
        // A box flat along one axis gets a twentieth of the other's size
        // (at least a millimetre), so the fit stays finite.
        let size = hi - lo;
        let least = (0.05 * size.x.max(size.y)).max(1e-3);
        for axis in 0..2 {
            if size[axis] < least {
                let c = 0.5 * (lo[axis] + hi[axis]);
                lo[axis] = c - 0.5 * least;
                hi[axis] = c + 0.5 * least;
            }
        }
        self.view = (lo, hi);
    }

    /// The page: the runs thinned at the first tolerance that fits the
    /// budget (see the module documentation).
    pub fn page(&mut self) -> Result<Page> {
        anyhow::ensure!(!self.runs.is_empty(), "a replay needs a run");
        self.compute_view();
        let size = self.view_size();
        let radii: Vec<Option<f64>> = self
            .bodies
            .iter()
            .map(|b| (b.kind != "static").then_some(b.radius))
            .collect();
        let mut share = FIRST_TOLERANCE;
        loop {
            let tolerance = share * size;
            let kept: Vec<Vec<usize>> = self
                .runs
                .iter()
                .map(|r| thin::keep(&r.times, &r.states, &radii, tolerance))
                .collect();
            let mut notes = self.notes.clone();
            for (run, kept) in self.runs.iter().zip(&kept) {
                notes.push(format!(
                    "{}: {} of {} samples kept; between them the page interpolates linearly, \
                     within {} m of every sample.",
                    run.label,
                    kept.len(),
                    run.times.len(),
                    crate::pictures::sig(tolerance)
                ));
            }
            let data = encode::data_json(self, &kept, tolerance, &notes);
            let fits = data.len() <= BUDGET_BYTES;
            if fits || share * 2.0 > LAST_TOLERANCE {
                let data = if fits {
                    data
                } else {
                    notes.push(format!(
                        "This page holds {:.1} MB of data, over the {} MB aimed at: the scene \
                         has too many moving bodies for a coarser thinning to help.",
                        data.len() as f64 / 1e6,
                        BUDGET_BYTES >> 20
                    ));
                    encode::data_json(self, &kept, tolerance, &notes)
                };
                return Ok(Page {
                    html: assemble(&self.title, &data),
                    frames: kept.iter().map(Vec::len).collect(),
                    tolerance,
                });
            }
            share *= 2.0;
        }
    }
}

/// The page from the template: the title escaped for HTML, the data for a
/// `<script>` element (every `<` written `\u003c`, so no `</script>` can
/// close it early), the script and the style inline.
fn assemble(title: &str, data: &str) -> String {
    let title = title
        .replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    let data = data.replace('<', "\\u003c");
    TEMPLATE
        .replace("{{TITLE}}", &title)
        .replace("/*{{STYLE}}*/", STYLE)
        .replace("/*{{SCRIPT}}*/", SCRIPT)
        .replace("{{DATA}}", &data)
}

/// Angles read as principal values (−π, π] made continuous: each change
/// taken on the branch nearest zero (right while a body turns by less than
/// half a turn between samples).
pub fn unwrap_angles(states: &mut [Vec<BodyState>]) {
    for k in 1..states.len() {
        let (done, rest) = states.split_at_mut(k);
        let previous = &done[k - 1];
        for (s, p) in rest[0].iter_mut().zip(previous) {
            let turn = s.angle - p.angle;
            s.angle =
                p.angle + (turn - std::f64::consts::TAU * (turn / std::f64::consts::TAU).round());
        }
    }
}

#[cfg(test)]
mod tests;
