//! [`Film`]: what a picture of a run needs, independent of how it is drawn:
//! each body's look (name, colour, shape, kind), the springs between
//! bodies and anchors, the joints' anchors, the ground lines of landing
//! events, the sampled states, and the located events.

use engine::{Body, BodyState, EventRecord, Shape};
use nalgebra::Vector2;
use scene::format::{EventEntry, ForceSpec};
use scene::{Colour, Scene};

/// How one body is drawn.
#[derive(Debug, Clone)]
pub struct BodyLook {
    /// The body's name in the scene file.
    pub name: String,
    /// Its colour (the file's `colour`, or the palette's).
    pub colour: Colour,
    /// Its shape, centred on the centre of mass; `None` for a particle
    /// (drawn as a dot) or a shapeless static anchor.
    pub shape: Option<Shape>,
    /// Whether it moves.
    pub dynamic: bool,
    /// Whether it carries rotational state (shows θ and ω in labels).
    pub rotates: bool,
}

impl BodyLook {
    /// The largest distance from the centre of mass to the outline (m); 0
    /// for a particle.
    pub fn radius(&self) -> f64 {
        self.shape.as_ref().map_or(0.0, shape_radius)
    }
}

/// The largest distance from the centre of mass to the outline of `shape`
/// (m): [`Shape::max_extent`].
pub fn shape_radius(shape: &Shape) -> f64 {
    shape.max_extent()
}

/// The smallest width of `shape` (m): a circle's diameter, a polygon's
/// least distance between parallel supporting lines (the least extent
/// across one of its edges), a compound's smallest piece's. The size a
/// picture's error is measured against.
pub fn shape_width(shape: &Shape) -> f64 {
    match shape {
        Shape::Circle(c) => 2.0 * c.radius,
        Shape::Polygon(p) => {
            let v = p.vertices();
            (0..v.len())
                .filter_map(|i| {
                    let edge = v[(i + 1) % v.len()] - v[i];
                    let n = Vector2::new(-edge.y, edge.x);
                    let len = n.norm();
                    (len > 0.0).then(|| {
                        let proj = v.iter().map(|p| (p - v[i]).dot(&n) / len);
                        let (lo, hi) =
                            proj.fold((0.0_f64, 0.0_f64), |(lo, hi), x| (lo.min(x), hi.max(x)));
                        hi - lo
                    })
                })
                .fold(f64::INFINITY, f64::min)
        }
        // The core's width plus the two roundings (a segment's is 0).
        Shape::Rounded(r) => {
            let core = match r.core_polygon() {
                Some(p) => shape_width(&Shape::Polygon(p)),
                None => 0.0,
            };
            core + 2.0 * r.radius()
        }
        Shape::Compound(_) => shape
            .pieces()
            .into_iter()
            .map(|(_, _, piece)| match piece {
                Shape::Compound(_) => f64::INFINITY,
                other => shape_width(other),
            })
            .fold(f64::INFINITY, f64::min),
        // A line has no width: none to measure a picture's error against.
        Shape::Chain(_) => f64::INFINITY,
    }
}

/// The springs of `scene`, as pairs of ends (the anchor or other body's
/// end first).
pub fn springs(scene: &Scene) -> Vec<(SpringEnd, SpringEnd)> {
    let zero = Vector2::zeros();
    let end = |name: &str, point: Option<&scene::format::Xy>| -> Option<SpringEnd> {
        Some(SpringEnd::Body {
            body: scene.body_id(name)?,
            local: point.map_or(zero, |p| p.vector()),
        })
    };
    scene
        .file()
        .forces
        .iter()
        .filter_map(|f| match f {
            ForceSpec::Spring {
                body,
                point,
                anchor,
                other_body,
                other_point,
                ..
            } => {
                let b = end(body, point.as_ref())?;
                let a = match (anchor, other_body) {
                    (Some(p), _) => SpringEnd::World(p.vector()),
                    (None, Some(other)) => end(other, other_point.as_ref())?,
                    (None, None) => return None,
                };
                Some((a, b))
            }
            _ => None,
        })
        .collect()
}

/// The levels of the landing events of `scene` (m), sorted, each once.
pub fn grounds(scene: &Scene) -> Vec<f64> {
    let mut levels: Vec<f64> = scene
        .file()
        .events
        .iter()
        .filter_map(|e| match e {
            EventEntry::Landing { level, .. } => Some(*level),
            EventEntry::Apex { .. } => None,
        })
        .collect();
    levels.sort_by(f64::total_cmp);
    levels.dedup();
    levels
}

/// Widens the view `(lo, hi)` (m) by the static bodies' boxes `statics`,
/// each cut to half the view's size around it when the view has a size
/// (a 20 m floor under a ball), and by the ground lines' heights `grounds`
/// (they span the width already there).
pub fn fit_statics(
    (mut lo, mut hi): (Vector2<f64>, Vector2<f64>),
    statics: Vec<(Vector2<f64>, Vector2<f64>)>,
    grounds: &[f64],
) -> (Vector2<f64>, Vector2<f64>) {
    if lo.x.is_finite() {
        let size = hi - lo;
        let reach = Vector2::repeat(0.5 * size.x.max(size.y).max(1e-3));
        let (near_lo, near_hi) = (lo - reach, hi + reach);
        for (a, b) in statics {
            let (a, b) = (a.sup(&near_lo), b.inf(&near_hi));
            if a.x <= b.x && a.y <= b.y {
                lo = lo.inf(&a);
                hi = hi.sup(&b);
            }
        }
    } else {
        for (a, b) in statics {
            lo = lo.inf(&a);
            hi = hi.sup(&b);
        }
    }
    for &level in grounds {
        lo.y = lo.y.min(level);
        hi.y = hi.y.max(level);
    }
    (lo, hi)
}

/// One end of a drawn spring.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpringEnd {
    /// A fixed world point (m).
    World(Vector2<f64>),
    /// A point of a body, in its frame relative to its centre of mass (m).
    Body {
        /// Index of the body.
        body: usize,
        /// Point in the body frame (m).
        local: Vector2<f64>,
    },
}

impl SpringEnd {
    /// Where this end is, given every body's state (m).
    pub fn at(&self, states: &[BodyState]) -> Vector2<f64> {
        match *self {
            SpringEnd::World(p) => p,
            SpringEnd::Body { body, local } => {
                let s = &states[body];
                s.position + s.to_world_offset(local)
            }
        }
    }
}

/// A located event, drawn as a marker once its time has passed.
#[derive(Debug, Clone, PartialEq)]
pub struct Mark {
    /// Event name (`landing`, `apex`).
    pub name: String,
    /// Time (s).
    pub t: f64,
    /// Where the watched body's centre was (m).
    pub position: Vector2<f64>,
}

/// A run ready to draw.
#[derive(Debug, Clone)]
pub struct Film {
    /// First title line (e.g. the scene file's name).
    pub title: String,
    /// Second title line (method, step, ...).
    pub subtitle: String,
    /// Every body, in scene order.
    pub bodies: Vec<BodyLook>,
    /// Springs, drawn as zigzags.
    pub springs: Vec<(SpringEnd, SpringEnd)>,
    /// Joints, by their two anchors: drawn as a thin line between them
    /// with a dot at each end (a revolute's coincide: its pivot).
    pub joints: Vec<(SpringEnd, SpringEnd)>,
    /// Heights of ground lines (m): the levels of landing events.
    pub grounds: Vec<f64>,
    /// Sample times (s), increasing.
    pub times: Vec<f64>,
    /// Every body's state at each sample.
    pub states: Vec<Vec<BodyState>>,
    /// Located events.
    pub marks: Vec<Mark>,
}

impl Film {
    /// An empty film of `scene`, whose world has `bodies` (as
    /// `World::bodies` returns them: shapes centred on the centre of mass).
    pub fn new(scene: &Scene, bodies: &[Body], title: String, subtitle: String) -> Self {
        let colours = scene.colours();
        let looks = bodies
            .iter()
            .enumerate()
            .map(|(i, b)| BodyLook {
                name: b.name.clone(),
                colour: colours.get(i).copied().unwrap_or(Colour::default_for(i)),
                shape: b.shape.clone(),
                dynamic: b.is_dynamic(),
                rotates: b.rotates(),
            })
            .collect();
        let springs = springs(scene);
        // The joints' anchors in the bodies' frames, resolved at t = 0.
        let initial: Vec<BodyState> = scene.bodies().iter().map(|b| b.state).collect();
        let joint_end = |body: Option<usize>, local: Vector2<f64>| match body {
            None => SpringEnd::World(local),
            Some(body) => SpringEnd::Body { body, local },
        };
        let joints = scene
            .joints()
            .map(|j| {
                let (a, b) = j.local_anchors(&initial);
                (joint_end(j.body_a, a), joint_end(j.body_b, b))
            })
            .collect();
        let grounds = grounds(scene);
        Self {
            title,
            subtitle,
            bodies: looks,
            springs,
            joints,
            grounds,
            times: Vec::new(),
            states: Vec::new(),
            marks: Vec::new(),
        }
    }

    /// Appends a sample.
    pub fn push(&mut self, t: f64, states: &[BodyState]) {
        self.times.push(t);
        self.states.push(states.to_vec());
    }

    /// Adds the events of a run as marks, each at the position of the body
    /// its scene event watches.
    pub fn mark_events(&mut self, scene: &Scene, events: &[EventRecord]) {
        for record in events {
            let body = scene.file().events.iter().find_map(|e| match e {
                EventEntry::Landing { body, .. } if record.name == "landing" => Some(body),
                EventEntry::Apex { body } if record.name == "apex" => Some(body),
                _ => None,
            });
            let Some(id) = body.and_then(|b| scene.body_id(b)) else {
                continue;
            };
            if let Some(state) = record.states.get(id) {
                self.marks.push(Mark {
                    name: record.name.clone(),
                    t: record.t,
                    position: state.position,
                });
            }
        }
    }

    /// The index of the first dynamic body, whose state the labels show.
    pub fn lead_body(&self) -> Option<usize> {
        self.bodies.iter().position(|b| b.dynamic)
    }

    /// The sample nearest to time `t` (s).
    pub fn sample_near(&self, t: f64) -> usize {
        let i = self.times.partition_point(|&s| s < t);
        if i == 0 {
            return 0;
        }
        if i >= self.times.len() {
            return self.times.len().saturating_sub(1);
        }
        if (self.times[i] - t) < (t - self.times[i - 1]) {
            i
        } else {
            i - 1
        }
    }

    /// `count` sample indices evenly spaced in time from the first sample
    /// to the last, without repeats.
    pub fn evenly_spaced(&self, count: usize) -> Vec<usize> {
        let (Some(&t0), Some(&t1)) = (self.times.first(), self.times.last()) else {
            return Vec::new();
        };
        let count = count.max(1);
        let mut out: Vec<usize> = (0..count)
            .map(|k| {
                let f = if count == 1 {
                    1.0
                } else {
                    k as f64 / (count - 1) as f64
                };
                self.sample_near(t0 + f * (t1 - t0))
            })
            .collect();
        out.dedup();
        out
    }

    /// The world box to show (min corner, max corner), m: every moving
    /// body at its true size over the run, the spring anchors and the
    /// ground lines, and the static bodies where they come near (a 20 m
    /// floor under a bouncing ball is cut to the ball's surroundings: half
    /// the moving part's size around it). `None` when a coordinate is not
    /// finite (a blown-up run).
    pub fn bounds(&self) -> Option<(Vector2<f64>, Vector2<f64>)> {
        let mut lo = Vector2::repeat(f64::INFINITY);
        let mut hi = Vector2::repeat(f64::NEG_INFINITY);
        let mut add = |p: Vector2<f64>, r: f64| {
            lo = lo.inf(&(p - Vector2::repeat(r)));
            hi = hi.sup(&(p + Vector2::repeat(r)));
        };
        for states in &self.states {
            for (look, s) in self.bodies.iter().zip(states) {
                if look.dynamic {
                    add(s.position, look.radius());
                }
            }
        }
        for (a, b) in self.springs.iter().chain(&self.joints) {
            for end in [a, b] {
                if let SpringEnd::World(p) = end {
                    add(*p, 0.0);
                }
            }
        }
        let statics: Vec<(Vector2<f64>, Vector2<f64>)> = self
            .states
            .first()
            .map(|states| {
                self.bodies
                    .iter()
                    .zip(states)
                    .filter(|(look, _)| !look.dynamic)
                    .map(|(look, s)| {
                        let r = Vector2::repeat(look.radius());
                        (s.position - r, s.position + r)
                    })
                    .collect()
            })
            .unwrap_or_default();
        let (lo, hi) = fit_statics((lo, hi), statics, &self.grounds);
        (lo.iter().chain(hi.iter()).all(|v| v.is_finite())).then_some((lo, hi))
    }
}
