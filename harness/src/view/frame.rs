//! What one picture of the view shows, copied out of the world: the
//! simulation thread fills a [`Frame`] after its steps and hands it to the
//! window, which draws it while the next steps run. Nothing in a frame
//! refers back to the world.

use super::canvas::{Rgb, rgb};
use engine::{Body, BodyKind, BodyState, JointType, Shape};
use nalgebra::{Rotation2, Vector2};
use std::sync::Arc;

/// How a body is drawn: its pieces in the body frame (m, from its centre
/// of mass), its colour and kind. Built once per body.
#[derive(Debug, Clone)]
pub struct BodyLook {
    /// The body's name.
    pub name: String,
    /// Dynamic, static or kinematic.
    pub kind: BodyKind,
    /// Fill colour.
    pub colour: Rgb,
    /// Convex polygons, vertices counter-clockwise (m, body frame).
    pub polygons: Vec<Vec<Vector2<f64>>>,
    /// Circles: centre (m, body frame) and radius (m).
    pub circles: Vec<(Vector2<f64>, f64)>,
    /// The largest distance of the shape from the centre of mass (m); 0
    /// for a particle.
    pub radius: f64,
}

impl BodyLook {
    /// The look of `body`, filled with `colour`.
    pub fn of(body: &Body, colour: Rgb) -> Self {
        let mut look = Self {
            name: body.name.clone(),
            kind: body.kind,
            colour,
            polygons: Vec::new(),
            circles: Vec::new(),
            radius: 0.0,
        };
        if let Some(shape) = &body.shape {
            for (offset, angle, piece) in shape.pieces() {
                let rotation = Rotation2::new(angle);
                match piece {
                    Shape::Polygon(p) => look
                        .polygons
                        .push(p.vertices().iter().map(|v| offset + rotation * v).collect()),
                    Shape::Circle(c) => look.circles.push((offset, c.radius)),
                    // Drawn as its inscribed outline (48 chords a turn).
                    Shape::Rounded(r) => look.polygons.push(
                        r.outline(48)
                            .iter()
                            .map(|v| offset + rotation * v)
                            .collect(),
                    ),
                    // A chain is a line: each solid segment a polygon of
                    // its two ends, drawn as its outline.
                    Shape::Chain(c) => {
                        for segment in c.segments() {
                            look.polygons.push(vec![
                                offset + rotation * segment.point1,
                                offset + rotation * segment.point2,
                            ]);
                        }
                    }
                    // A compound's parts are polygons and circles.
                    Shape::Compound(_) => {}
                }
            }
        }
        let far_vertex = look.polygons.iter().flatten().map(|v| v.norm());
        let far_circle = look.circles.iter().map(|(c, r)| c.norm() + r);
        look.radius = far_vertex.chain(far_circle).fold(0.0, f64::max);
        look
    }

    /// The axis-aligned box of the shape at `state` (m): lower and upper
    /// corners; the centre twice for a particle.
    pub fn aabb(&self, state: &BodyState) -> (Vector2<f64>, Vector2<f64>) {
        if self.is_particle() {
            return (state.position, state.position);
        }
        let rotation = Rotation2::new(state.angle);
        let mut lo = Vector2::repeat(f64::INFINITY);
        let mut hi = Vector2::repeat(f64::NEG_INFINITY);
        for v in self.polygons.iter().flatten() {
            let p = state.position + rotation * v;
            lo = lo.inf(&p);
            hi = hi.sup(&p);
        }
        for (c, r) in &self.circles {
            let p = state.position + rotation * c;
            lo = lo.inf(&(p - Vector2::repeat(*r)));
            hi = hi.sup(&(p + Vector2::repeat(*r)));
        }
        (lo, hi)
    }

    /// Whether the body has no shape (a point mass, drawn as a dot).
    pub fn is_particle(&self) -> bool {
        self.polygons.is_empty() && self.circles.is_empty()
    }
}

/// A joint as drawn: its anchors now and the centres of its bodies.
#[derive(Debug, Clone, Copy)]
pub struct JointLine {
    /// The joint's type.
    pub joint_type: JointType,
    /// Body A's centre of mass, `None` for the world.
    pub centre_a: Option<Vector2<f64>>,
    /// Anchor on A (m, world frame).
    pub anchor_a: Vector2<f64>,
    /// Anchor on B (m, world frame).
    pub anchor_b: Vector2<f64>,
    /// Body B's centre of mass, `None` for the world.
    pub centre_b: Option<Vector2<f64>>,
}

/// A contact point with its unit normal (from the first body to the
/// second) and, under the soft step, the impulses the solver gave it.
#[derive(Debug, Clone, Copy)]
pub struct ContactMark {
    /// World point (m).
    pub point: Vector2<f64>,
    /// Unit normal.
    pub normal: Vector2<f64>,
    /// Normal impulse delivered over the last step (N·s; ÷ dt is the mean
    /// normal force), `None` where the engine gives none (exact model).
    pub normal_impulse: Option<f64>,
    /// Friction impulse of the last substep along (n.y, −n.x) (N·s).
    pub tangent_impulse: Option<f64>,
}

/// How contact normals are drawn: a length proportional to the normal
/// impulse.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpulseScale {
    /// Pixels per N·s (a round 1, 2, 5 × 10ⁿ).
    pub px_per_newton_second: f64,
    /// The largest normal impulse of the frame (N·s).
    pub largest: f64,
}

/// An island of the soft step (`World::islands`): its id, the box around
/// its bodies and whether it sleeps.
#[derive(Debug, Clone, Copy)]
pub struct IslandMark {
    /// The engine's island id (its colour is picked from it).
    pub id: usize,
    /// Lower corner of the union of its bodies' boxes (m).
    pub lo: Vector2<f64>,
    /// Upper corner (m).
    pub hi: Vector2<f64>,
    /// Its bodies.
    pub bodies: usize,
    /// Whether it sleeps.
    pub asleep: bool,
}

/// No island (a static, kinematic or removed body, or no islands kept).
pub const NO_ISLAND: u32 = u32::MAX;

/// The live numbers shown in the corner.
#[derive(Debug, Clone, Default)]
pub struct Status {
    /// The engine and its build, the panel's title.
    pub label: String,
    /// Simulated time (s).
    pub time: f64,
    /// Steps taken since the start or the last reset.
    pub steps: u64,
    /// The scene's step (s).
    pub dt: f64,
    /// Whether the simulation runs (false: paused).
    pub running: bool,
    /// Simulated seconds per wall second asked for.
    pub speed: f64,
    /// Simulated seconds per wall second achieved over the last half
    /// second (`None` before the first half second, and headless).
    pub achieved_speed: Option<f64>,
    /// The contact model, as the engine names it (`soft_step`, `exact`,
    /// `off`), and the integration method.
    pub model: String,
    /// Bodies in the world (static ones included).
    pub bodies: usize,
    /// Dynamic bodies asleep.
    pub asleep: usize,
    /// Joints acting (the drag's included).
    pub joints: usize,
    /// Wall time of one step, averaged over the last half second (ms;
    /// `None` before it, or over all steps taken headless).
    pub step_ms: Option<f64>,
    /// The step profile over the last half second: per-phase ms per step, the
    /// phases that took any time (when profiling is on).
    pub phases: Vec<(&'static str, f64)>,
    /// Counters per step over the last half second: candidate pairs, contacts,
    /// touching contacts, contact points.
    pub counters: Vec<(&'static str, f64)>,
    /// The last thing the simulation has to say (a refusal, a switch, an
    /// error), empty when none.
    pub message: String,
    /// The contact normals' scale, when they show impulses.
    pub impulse_scale: Option<ImpulseScale>,
}

/// One picture's worth of simulation.
#[derive(Debug, Clone, Default)]
pub struct Frame {
    /// Every body's look, by id (shared between frames; replaced when a
    /// body is added).
    pub looks: Arc<Vec<BodyLook>>,
    /// Every body's state, by id.
    pub states: Vec<BodyState>,
    /// Whether each body was removed (drawn as nothing).
    pub removed: Vec<bool>,
    /// Whether each body sleeps.
    pub asleep: Vec<bool>,
    /// Joints acting (when the joints overlay is on).
    pub joints: Vec<JointLine>,
    /// Contact points (when the contacts overlay is on).
    pub contacts: Vec<ContactMark>,
    /// Each body's island, by id, [`NO_ISLAND`] for none (when the
    /// sleeping overlay is on and the engine keeps islands).
    pub island_of: Vec<u32>,
    /// The islands (as `island_of`).
    pub islands: Vec<IslandMark>,
    /// Why islands are not shown, if they are not (the exact model,
    /// sleeping off).
    pub islands_missing: Option<String>,
    /// Recent paths of the first dynamic bodies (when the paths overlay is
    /// on), oldest point first.
    pub paths: Vec<(usize, Vec<Vector2<f64>>)>,
    /// The drag: the grabbed point now and the cursor's target (m).
    pub drag: Option<(Vector2<f64>, Vector2<f64>)>,
    /// The numbers.
    pub status: Status,
    /// The reference engine's side, with `--compare`.
    pub reference: Option<Box<Frame>>,
}

/// The colour of a scene colour.
pub fn colour_of(c: scene::Colour) -> Rgb {
    rgb(c.r, c.g, c.b)
}
