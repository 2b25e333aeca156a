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
//! # Faithfulness and size
//!
//! Each moving body keeps only the samples that linear interpolation
//! cannot replace within the page's bound ([`thin`], body by body): 1 % of
//! the smallest moving body's width (`pictures::film::shape_width`), or,
//! when no moving body has a shape (particles), 1/2000 of the view's size
//! (half a pixel on a 1000-pixel view). The bound is on what the page
//! shows: the stored values' rounding is inside it, and the quanta are
//! chosen at least ten times finer than the bound. The page states its bound
//! ("within X m of every sample") and its size; it is never coarsened to
//! fit a size, so a scene of many moving bodies makes a large page. A body
//! that never moves is stored once.

mod encode;
pub(crate) mod thin;

use crate::pictures::film::{fit_statics, grounds, shape_radius, shape_width, springs};
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
/// The page's bound, as a share of the smallest moving body's width.
pub const BODY_SHARE: f64 = 0.01;
/// The page's bound when no moving body has a shape, as a share of the
/// view's size (half a pixel on a 1000-pixel view).
pub const VIEW_SHARE: f64 = 1.0 / 2000.0;
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
    /// Smallest width (m, `shape_width`); `None` for a particle.
    pub width: Option<f64>,
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
    /// Samples recorded, per run.
    pub samples: Vec<usize>,
    /// The most samples any one body keeps, per run.
    pub frames: Vec<usize>,
    /// The page's bound (m): every body, as shown, is within it of every
    /// recorded sample.
    pub tolerance: f64,
    /// The largest error (m) of what the page shows against the recorded
    /// samples, over every body and run (at most `tolerance`).
    pub max_error: f64,
    /// The smallest moving body's width (m), when a moving body has a
    /// shape.
    pub smallest_width: Option<f64>,
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
                    width: b.shape.as_ref().map(shape_width),
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

    /// The smallest width (m) of a moving body with a shape.
    fn smallest_width(&self) -> Option<f64> {
        self.bodies
            .iter()
            .filter(|b| b.kind != "static")
            .filter_map(|b| b.width)
            .filter(|w| w.is_finite() && *w > 0.0)
            .reduce(f64::min)
    }

    /// The page: every moving body's samples thinned to the page's bound
    /// (see the module documentation).
    pub fn page(&mut self) -> Result<Page> {
        anyhow::ensure!(!self.runs.is_empty(), "a replay needs a run");
        self.compute_view();
        let smallest = self.smallest_width();
        let tolerance = match smallest {
            Some(w) => BODY_SHARE * w,
            None => VIEW_SHARE * self.view_size(),
        };
        let mut notes = self.notes.clone();
        let mut kept_all = Vec::new();
        let mut quanta = Vec::new();
        let mut worst = 0.0_f64;
        for run in &self.runs {
            let q = encode::quanta(self, run, tolerance);
            let q_thin = thin::Quanta {
                t: q.t,
                p: q.p,
                a: q.a,
            };
            let kept: Vec<Vec<usize>> = (0..self.bodies.len())
                .map(|b| {
                    if run.states.is_empty() || encode::fixed(&run.states, b) {
                        return Vec::new();
                    }
                    let r = self.bodies[b].radius;
                    let kept = thin::keep_body(&run.times, &run.states, b, r, q_thin, tolerance);
                    // A body whose samples are not finite (a blown-up run) cannot
                    // be shown; the bound holds for every other body.
                    let e = thin::max_error(&run.times, &run.states, b, r, q_thin, &kept);
                    if e.is_finite() {
                        worst = worst.max(e);
                    }
                    kept
                })
                .collect();
            let most = kept.iter().map(Vec::len).max().unwrap_or(0);
            let moving = kept.iter().filter(|k| !k.is_empty()).count();
            let stored: usize = kept.iter().map(Vec::len).sum();
            notes.push(format!(
                "{}: {} samples; each of its {moving} moving bodies keeps only those the page \
                 cannot interpolate (up to {most}, {stored} in all); between them the page \
                 interpolates linearly, within {} m of every sample.",
                run.label,
                run.times.len(),
                crate::pictures::sig(tolerance)
            ));
            kept_all.push(kept);
            quanta.push(q);
        }
        let bound_note = match smallest {
            Some(w) => format!(
                "The bound, {} m, is 1 % of the smallest moving body's width ({} m); the \
                 largest error of what the page shows is {} m.",
                crate::pictures::sig(tolerance),
                crate::pictures::sig(w),
                crate::pictures::sig(worst)
            ),
            None => format!(
                "No moving body has a shape: the bound, {} m, is 1/2000 of the view; the largest \
                 error of what the page shows is {} m.",
                crate::pictures::sig(tolerance),
                crate::pictures::sig(worst)
            ),
        };
        anyhow::ensure!(
            worst <= tolerance,
            "the replay page would be {worst} m off a sample, over its bound {tolerance} m"
        );
        notes.push(bound_note);
        // The size note states the size of the page without it; the note
        // adds a few dozen bytes.
        let data = encode::data_json(self, &kept_all, &quanta, tolerance, &notes);
        let size = data.len() as f64;
        notes.push(if size < 1e6 {
            format!("This page holds {:.0} kB of data.", size / 1e3)
        } else {
            format!("This page holds {:.2} MB of data.", size / 1e6)
        });
        let data = encode::data_json(self, &kept_all, &quanta, tolerance, &notes);
        Ok(Page {
            html: assemble(&self.title, &data),
            samples: self.runs.iter().map(|r| r.times.len()).collect(),
            frames: kept_all
                .iter()
                .map(|k| k.iter().map(Vec::len).max().unwrap_or(0))
                .collect(),
            tolerance,
            max_error: worst,
            smallest_width: smallest,
        })
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
