//! The scene file format: the serde structures a TOML scene deserializes
//! into, one per table, every field with its unit and default.
//!
//! These structures hold what the file says, checked only for form (types,
//! known keys, `[x, y]` of exactly two numbers). Values are checked by
//! [`crate::Scene::parse_str`] / [`crate::Scene::load`], which refuse NaN and
//! infinities, out-of-domain numbers, bad polygons and dangling body names
//! with a line-numbered [`crate::SceneError`].
//!
//! Units are SI: m, s, kg, rad. A file describes either a world of bodies
//! (`[[bodies]]`, `[[forces]]`, `[[events]]`, `[[joints]]`, `[contact]`) or
//! the scalar stiff test (`[linear_test]`), with `[simulation]` in both. A
//! complete example is in the crate documentation; every table and key,
//! with an example each, in `docs/scene_format.md`, which the test
//! `scene/tests/scene_format_doc.rs` keeps in step with these structures
//! (a key added here without its line there fails it, naming the key).

use serde::Deserialize;
use serde::de::{self, Deserializer, IgnoredAny, SeqAccess, Visitor};
use std::fmt;

/// A whole scene file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// `[simulation]`: method, step and duration. Required.
    pub simulation: SimulationSpec,
    /// `[[bodies]]`, in order: the body with index `i` here has
    /// [`engine::BodyId`] `i` in the built world. Default: none.
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// `[[forces]]`, applied in this order. Default: none.
    #[serde(default)]
    pub forces: Vec<ForceSpec>,
    /// `[[events]]` to locate during the run. Default: none.
    #[serde(default)]
    pub events: Vec<EventEntry>,
    /// `[[joints]]`, added in this order after the bodies (the joint
    /// `joints[i]` has [`engine::JointId`] `i`, before the generators'
    /// joints). Under `[contact] model = "exact"` only the revolute,
    /// prismatic, rigid distance and weld joints without limits, motors or
    /// springs. Default: none.
    #[serde(default)]
    pub joints: Vec<JointSpec>,
    /// `[contact]`: collision response settings. Optional.
    pub contact: Option<ContactSpec>,
    /// `[[generate]]` blocks: many bodies from a few numbers (a pyramid, a
    /// stack, a grid or rain of shapes), appended after `[[bodies]]` in
    /// order. Default: none.
    #[serde(default)]
    pub generate: Vec<crate::generate::GenerateSpec>,
    /// `[linear_test]`: the scalar stiff test instead of bodies. Optional;
    /// excludes bodies, forces, events and contact.
    pub linear_test: Option<LinearTestSpec>,
}

/// `[simulation]`: how the scene is integrated.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimulationSpec {
    /// Integration method, an [`engine::Method::id`]: `"explicit_euler"`,
    /// `"semi_implicit_euler"`, `"rk2_midpoint"` (or `"midpoint"`), `"rk4"`,
    /// `"velocity_verlet"`, `"implicit_euler"` or `"dormand_prince"`.
    /// Default `"rk4"` (the seed's method, §4.3), or
    /// `"semi_implicit_euler"` under the soft-step contact model (also a
    /// scene with joints and no `[contact]`), which integrates by itself
    /// and accepts no other.
    pub method: Option<String>,
    /// Time step h (s), > 0. Required. For `dormand_prince` it is the output
    /// interval, the largest step the controller may take.
    pub dt: f64,
    /// Length of the run (s), > 0. Required. The run takes
    /// `ceil(duration / dt)` steps (an exact count when `dt` divides it to
    /// within round-off), at most 1e8.
    pub duration: f64,
    /// Relative and absolute error tolerance of `dormand_prince`
    /// (dimensionless / state units), > 0. Default 1e-9; ignored by the
    /// fixed-step methods.
    pub tolerance: Option<f64>,
    /// Uniform gravity on every dynamic body (m/s²), the world's setting
    /// (`[[forces]] type = "gravity"` also works, with a window). Default:
    /// none.
    pub gravity: Option<Xy>,
    /// Threads of the soft step's parallel stages, 1 to 256 (the results
    /// do not depend on it, only the time). Default 1. Refused under the
    /// exact contact model.
    pub threads: Option<i64>,
}

/// The default method of a scene without the soft-step contact model.
pub const DEFAULT_METHOD: &str = "rk4";

/// Default tolerance of `dormand_prince` when `[simulation]` gives none.
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

/// Whether a body moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BodyKindSpec {
    /// Moves under forces (default).
    #[default]
    Dynamic,
    /// Never moves (an anchor, the ground); takes no mass or velocity.
    Static,
    /// Moves at its `velocity` and `angular_velocity` forever, pushed by
    /// nothing (a conveyor, a stirring paddle, a turning container); takes
    /// no mass. Soft-step contact model only.
    Kinematic,
}

/// `[[bodies]]`: one body.
///
/// A dynamic body needs `mass`, or `density` with a `shape`. A body with
/// neither `shape` nor `inertia` is a particle: no rotation, so `angle` and
/// `angular_velocity` must stay 0 and no torque may act on it.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Unique, non-empty name; forces and events refer to the body by it.
    pub name: String,
    /// `"dynamic"` (default), `"static"` or `"kinematic"` (soft-step
    /// contact model only): [`BodyKindSpec`].
    #[serde(default)]
    pub kind: BodyKindSpec,
    /// Mass (kg), > 0. Give this or `density`, not both.
    pub mass: Option<f64>,
    /// Areal density (kg/m²), > 0; mass = density × shape area. Needs a
    /// `shape`.
    pub density: Option<f64>,
    /// Moment of inertia about the centre of mass (kg·m²), > 0. Default:
    /// from the shape (a box b × h: m(b² + h²)/12); none for a particle.
    pub inertia: Option<f64>,
    /// Geometry. Default: none (a particle, unless `inertia` is given).
    pub shape: Option<ShapeSpec>,
    /// Initial position of the centre of mass (m). Default `[0, 0]`.
    #[serde(default)]
    pub position: Xy,
    /// Initial orientation (rad), counter-clockwise. Default 0.
    #[serde(default)]
    pub angle: f64,
    /// Initial velocity of the centre of mass (m/s). Default `[0, 0]`.
    #[serde(default)]
    pub velocity: Xy,
    /// Initial angular velocity (rad/s), counter-clockwise. Default 0.
    #[serde(default)]
    pub angular_velocity: f64,
    /// Coulomb friction coefficient of this body (≥ 0), combined with the
    /// other body's by `[contact] friction_mixing` (√(μa μb) by default).
    /// Default: `[contact] friction`. Soft-step contact model only.
    pub friction: Option<f64>,
    /// Restitution of this body (in [0, 1]), combined by `[contact]
    /// restitution_mixing` (the larger of the two by default). Default:
    /// `[contact] restitution`. Soft-step contact model only.
    pub restitution: Option<f64>,
    /// Rolling resistance coefficient of this body's shape (≥ 0,
    /// dimensionless; Box2D v3's: the largest rolling torque is this times
    /// the larger circle radius of the pair times the normal force; a
    /// polygon has radius 0). Default: `[contact] rolling_resistance`.
    /// Soft-step contact model only.
    pub rolling_resistance: Option<f64>,
    /// Speed (m/s, finite) of this body's surface along the contact
    /// tangent, a conveyor belt's: friction drives what touches it toward
    /// this relative speed (Box2D v3's tangent speed). Default 0. Soft-step
    /// contact model only.
    pub tangent_speed: Option<f64>,
    /// Collision filter `{ category, mask, group }` (Box2D's): shapes
    /// collide when each one's category meets the other's mask, except that
    /// a shared positive group always collides and a shared negative group
    /// never does. Default `{ category = 1, mask = all bits, group = 0 }`.
    /// Soft-step contact model only.
    pub filter: Option<FilterSpec>,
    /// Whether this body's shape is a sensor: it reports overlaps as
    /// sensor events and neither pushes nor is pushed. Default false.
    /// Soft-step contact model only.
    pub sensor: Option<bool>,
    /// Whether this body is a bullet (Box2D's `isBullet`): moving fast
    /// under the soft step, it is swept against the other dynamic bodies'
    /// end poses too, not only the static ones, so it cannot pass through
    /// a thin moving body in one step. Default false. No effect on a
    /// static or kinematic body, nor under the exact model (whose swept
    /// contact search covers every pair).
    pub bullet: Option<bool>,
    /// Colour for pictures, `"#rrggbb"` (also accepted as `color`).
    /// Default: grey ([`crate::Colour::STATIC`]) for a static body; for the
    /// others the next colour of the matplotlib "tab10" cycle without its
    /// grey ([`crate::Colour::PALETTE`]), counting only the bodies that are
    /// not static. The engine ignores it.
    #[serde(alias = "color")]
    pub colour: Option<String>,
}

/// `shape = { type = ..., ... }`: a body's geometry, in the body frame (m).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ShapeSpec {
    /// `{ type = "box", width, height }`: an axis-aligned rectangle
    /// centred on the body's position; width and height (m) > 0. With
    /// `radius = r` (m, ≥ 0) the rectangle is the core of a rounded box,
    /// every point within r of it: outer size `width + 2r` by
    /// `height + 2r`, corners rounded (not collided yet by either contact
    /// model).
    Box {
        /// Extent along the body's x axis (m), > 0.
        width: f64,
        /// Extent along the body's y axis (m), > 0.
        height: f64,
        /// Rounding radius (m), ≥ 0; 0 or absent: a sharp box.
        #[serde(default)]
        radius: f64,
    },
    /// `{ type = "polygon", vertices = [[x, y], ...] }`: a simple polygon,
    /// at least 3 vertices, counter-clockwise (m), no edges crossing or
    /// touching, no point twice, no vertex on the line through its
    /// neighbours. A convex one is one shape; a concave one is cut into
    /// convex parts ([`engine::shape::decompose`]): one rigid body of
    /// several shapes, soft-step contact model only. The engine re-centres
    /// it on its centroid, so `position` is the centre of mass.
    ///
    /// With `radius = r` (m, ≥ 0) a convex polygon is the core of a
    /// rounded polygon, every point within r of it (not collided yet by
    /// either contact model); a concave one cannot be rounded.
    Polygon {
        /// Vertices counter-clockwise (m).
        vertices: Vec<Xy>,
        /// Rounding radius (m), ≥ 0; 0 or absent: sharp corners.
        #[serde(default)]
        radius: f64,
    },
    /// `{ type = "capsule", length, radius }`: two half discs of `radius`
    /// whose centres are `length` apart on the body's x axis, joined by
    /// their tangents; centred on the body (m), both > 0. Not collided
    /// yet by either contact model.
    Capsule {
        /// Distance between the two cap centres (m), > 0.
        length: f64,
        /// Radius (m), > 0.
        radius: f64,
    },
    /// `{ type = "segment", a = [x, y], b = [x, y] }`: the line segment
    /// from `a` to `b` (m, distinct). It has no area, hence no mass (as in
    /// Box2D): on a static or kinematic body, or on a dynamic body given
    /// both `mass` and `inertia`. Re-centred on its midpoint like any
    /// shape on its centroid. Not collided yet by either contact model.
    Segment {
        /// First end (m).
        a: Xy,
        /// Second end (m).
        b: Xy,
    },
    /// `{ type = "circle", radius }`: a disc centred on the body (m), > 0.
    Circle {
        /// Radius (m), > 0.
        radius: f64,
    },
    /// `{ type = "hollow_box", width, height, wall }`: four walls of
    /// thickness `wall` around an inside of `width × height` (m), centred
    /// on the body (a container, a tumbler). One rigid body of four
    /// shapes; soft-step contact model only.
    HollowBox {
        /// Inside extent along the body's x axis (m), > 0.
        width: f64,
        /// Inside extent along the body's y axis (m), > 0.
        height: f64,
        /// Wall thickness (m), > 0.
        wall: f64,
    },
    /// `{ type = "compound", parts = [{ shape = {...}, offset = [x, y],
    /// angle = a }, ...] }`: one rigid body of several shapes placed in
    /// its frame, of uniform density; soft-step contact model only. The
    /// engine re-centres it on its centroid.
    Compound {
        /// The parts, at least one.
        parts: Vec<PartSpec>,
    },
    /// `{ type = "chain", points = [[x, y], ...], loop = false }`: a
    /// one-sided polyline ([`engine::Chain`]) on a static body: each
    /// segment pushes shapes to the right of its direction (a ground listed
    /// right to left is solid from above, a loop listed clockwise holds
    /// shapes inside). At least 4 points, consecutive ones at least 5 mm
    /// apart; in an open chain the first and last points only guide the
    /// end segments. Soft-step contact model only.
    Chain {
        /// The points in order (m, body frame).
        points: Vec<Xy>,
        /// Whether the last point joins the first. Default false.
        #[serde(default, rename = "loop")]
        is_loop: bool,
    },
}

/// One part of a `compound` shape.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PartSpec {
    /// The part in its own frame: a box, circle, polygon (a concave one
    /// adds each of its convex parts) or hollow_box (its four walls); not
    /// a compound.
    pub shape: ShapeSpec,
    /// Where the part's origin sits in the body frame (m). Default `[0, 0]`.
    #[serde(default)]
    pub offset: Xy,
    /// The part's orientation in the body frame (rad), counter-clockwise.
    /// Default 0.
    #[serde(default)]
    pub angle: f64,
}

/// `[[forces]]`: a force generator, tagged by `type`. Every force takes an
/// optional `window = [start, end]` (s): it acts for `start ≤ t < end`
/// (finite, `end > start`), and the engine splits its steps at both edges.
/// Default: always on. Bodies are named, never numbered.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ForceSpec {
    /// `{ type = "gravity", g = [gx, gy] }`: uniform field on every dynamic
    /// body, F = m g. The seed's cases use g = [0, −9.80655] m/s².
    Gravity {
        /// Acceleration (m/s²). Required.
        g: Xy,
        /// Active window (s). Default: always.
        window: Option<Window>,
    },
    /// A linear spring, F = −k ψ (seed §5.2, eq. 5.2), from `body` to a
    /// fixed `anchor` or to `other_body` (exactly one of the two).
    Spring {
        /// The body at one end.
        body: String,
        /// Attachment point on `body`, in its frame (m). Default `[0, 0]`,
        /// the centre of mass.
        point: Option<Xy>,
        /// Fixed world point at the other end (m).
        anchor: Option<Xy>,
        /// Body at the other end, instead of an anchor.
        other_body: Option<String>,
        /// Attachment point on `other_body`, in its frame (m). Default
        /// `[0, 0]`.
        other_point: Option<Xy>,
        /// Stiffness k (N/m), ≥ 0. Required.
        stiffness: f64,
        /// Rest length l0 (m), ≥ 0. Default 0.
        #[serde(default)]
        rest_length: f64,
        /// Direction of a one-dimensional spring (normalised; not zero):
        /// the extension is signed, ψ = (p_body − p_other)·u − l0, so the
        /// spring may pass through its anchor (the seed's model). Default:
        /// none, a distance spring ψ = |p_body − p_other| − l0.
        axis: Option<Xy>,
        /// Active window (s). Default: always.
        window: Option<Window>,
    },
    /// Quadratic air drag at the centre of mass, F = −D |v| v (seed
    /// Table 6.2).
    Drag {
        /// The body.
        body: String,
        /// D = ρ C A / 2 (kg/m), ≥ 0. Required.
        coefficient: f64,
        /// Active window (s). Default: always.
        window: Option<Window>,
    },
    /// Angular drag, τ = −D ω |ω| (the seed's angular friction, §6.2), on a
    /// rotating body.
    AngularDrag {
        /// The body (not a particle).
        body: String,
        /// D (N·m·s²), ≥ 0. Required.
        coefficient: f64,
        /// Active window (s). Default: always.
        window: Option<Window>,
    },
    /// A constant world-frame force at a point fixed in the body: pushes
    /// the centre of mass and turns the body by r × F.
    PointForce {
        /// The body.
        body: String,
        /// Force in the world frame (N). Required.
        force: Xy,
        /// Application point in the body frame (m), from the centre of mass.
        /// Default `[0, 0]`; must be 0 on a particle.
        point: Option<Xy>,
        /// Active window (s). Default: always.
        window: Option<Window>,
    },
    /// A pure couple (no net force), counter-clockwise positive, on a
    /// rotating body: either `torque` (N·m), or `lever` (m) and `force` (N)
    /// giving τ = lever × force (seed eq. 6.16–6.20).
    Torque {
        /// The body (not a particle).
        body: String,
        /// Torque (N·m).
        torque: Option<f64>,
        /// Lever arm R (m), with `force`.
        lever: Option<Xy>,
        /// Force F (N), with `lever`.
        force: Option<Xy>,
        /// Active window (s). Default: always.
        window: Option<Window>,
    },
}

/// `[[events]]`: an event located by root finding inside the step.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum EventEntry {
    /// The body's centre comes down through `y = level`; ends the run.
    Landing {
        /// The body watched.
        body: String,
        /// Height (m). Default 0.
        #[serde(default)]
        level: f64,
    },
    /// The top of the trajectory, `vy` from > 0 to ≤ 0; the run goes on.
    Apex {
        /// The body watched.
        body: String,
    },
}

/// `[contact]`: collision response. Its presence turns the world's
/// contacts on; without it, shapes pass through each other (except in a
/// scene with joints, which runs the soft step at its defaults: joints
/// need it). Two models
/// (`docs/design.md#contact-models`):
///
/// - `model = "soft_step"` (the default): Box2D v3's soft step, for many
///   bodies; it integrates by itself (semi-implicit Euler per substep), so
///   `[simulation] method` must be absent or `"semi_implicit_euler"`;
/// - `model = "exact"`: the event-driven model after Baraff, exact to
///   round-off on a few bodies, integrated by `[simulation] method`.
///
/// Keys of the other model are refused, with the reason.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// `"soft_step"` (default) or `"exact"`.
    #[serde(default)]
    pub model: ContactModelSpec,
    /// Coefficient of restitution e, in [0, 1] (seed eq. 7.1–7.16): the
    /// whole world's under the exact model, the default of bodies without
    /// their own under the soft step. Default: 1 under the exact model (no
    /// loss the scene did not ask for), 0 under the soft step (Box2D's).
    pub restitution: Option<f64>,
    /// Coulomb friction coefficient μ, ≥ 0, in the same way. Default: 0
    /// under the exact model, 0.6 under the soft step (Box2D's).
    pub friction: Option<f64>,
    /// Soft step: substeps per step, 1 to 1024. Default 4.
    pub substeps: Option<i64>,
    /// Soft step: contact stiffness as a natural frequency (Hz, > 0).
    /// Default 30.
    pub contact_hertz: Option<f64>,
    /// Soft step: damping ratio of the contact spring (≥ 0). Default 10.
    pub damping_ratio: Option<f64>,
    /// Soft step: largest push-out speed of overlapping bodies (m/s, > 0).
    /// Default 3.
    pub push_out_speed: Option<f64>,
    /// Soft step: approach speed below which nothing bounces (m/s, ≥ 0).
    /// Default 1.
    pub restitution_threshold: Option<f64>,
    /// Soft step: distance within which contacts are speculative (m, ≥ 0).
    /// Default 0.02.
    pub speculative_distance: Option<f64>,
    /// Soft step: largest margin of the broad phase's boxes (m, > 0), at
    /// most 1/8 of each shape's extent. Default 0.1.
    pub aabb_margin: Option<f64>,
    /// Soft step: relative motion under which a manifold is recycled (m,
    /// ≥ 0; 0 recomputes every manifold every step). Default 0.05.
    pub recycle_distance: Option<f64>,
    /// Soft step: sweep fast bodies against static ones. Default true.
    pub continuous: Option<bool>,
    /// Soft step: islands at rest fall asleep. Default false.
    pub sleeping: Option<bool>,
    /// Soft step: how a pair mixes its bodies' friction. Default
    /// `"geometric_mean"` (Box2D's); also `"max"`, `"min"`, `"average"`,
    /// `"product"`.
    pub friction_mixing: Option<MixingSpec>,
    /// Soft step: how a pair mixes its bodies' restitution. Default
    /// `"max"` (Box2D's); the same choices.
    pub restitution_mixing: Option<MixingSpec>,
    /// Soft step: rolling resistance of bodies without their own (≥ 0).
    /// Default 0.
    pub rolling_resistance: Option<f64>,
    /// Soft step: approach speed above which a pair that begins touching
    /// reports a hit event (m/s, ≥ 0). Default 1.
    pub hit_event_threshold: Option<f64>,
    /// Exact model: how the first contact inside a step is found:
    /// `"swept"` (the default: the seed's bisection where a pair overlaps at
    /// the step's end, conservative advancement where its motion could have
    /// touched inside the step, so a fast body does not pass through a
    /// thin one), `"bisection"` (the seed's alone: looks at the step's end
    /// only) or `"conservative_advancement"` (for every pair apart at the
    /// step's start).
    pub toi_method: Option<ToiMethodSpec>,
}

/// `filter = { category = 2, mask = 0xFFFF, group = -1 }` on a body: each
/// key optional. TOML integers are signed 64-bit, so a mask written as a
/// number holds bits 0 to 62; leave `mask` out for every bit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FilterSpec {
    /// The categories the shape belongs to, a bit set (> 0). Default 1.
    pub category: Option<i64>,
    /// The categories it collides with, a bit set (≥ 0). Default every
    /// bit.
    pub mask: Option<i64>,
    /// Group index: shapes sharing a positive group always collide, a
    /// negative one never; 0 (default) none.
    pub group: Option<i64>,
}

/// `[contact] friction_mixing` and `restitution_mixing`: how a pair
/// combines its two bodies' values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MixingSpec {
    /// √(a b) (Box2D's friction rule).
    GeometricMean,
    /// max(a, b) (Box2D's restitution rule).
    Max,
    /// min(a, b).
    Min,
    /// (a + b) / 2.
    Average,
    /// a b.
    Product,
}

/// `[contact] model`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactModelSpec {
    /// Box2D v3's soft step.
    #[default]
    SoftStep,
    /// The exact, event-driven model.
    Exact,
}

/// `[contact] toi_method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ToiMethodSpec {
    /// The seed's bisection, and conservative advancement where a pair
    /// could have touched inside the step.
    Swept,
    /// The seed's bisection of the step.
    Bisection,
    /// Conservative advancement.
    ConservativeAdvancement,
}

/// `[[joints]]`: a joint, tagged by `type`, holding two bodies together or
/// one body to the world (engine module `joints`: the rows each type
/// solves, Box2D's defaults).
///
/// Common keys:
///
/// - `name`: unique among the joints, for messages. Default `joints[i]`.
/// - `body_a`, `body_b`: the bodies by name; `"world"` or an absent key is
///   the world (a fixed anchor). At least one must be a dynamic body, and
///   they differ.
/// - Anchors, in **world coordinates at t = 0** (`anchor = [x, y]`, m; a
///   distance joint has `anchor_a` and `anchor_b`), or in the **bodies'
///   frames** from each centre of mass (`local_anchor_a`, `local_anchor_b`,
///   m; on the world side a world point). Give one form or the other.
/// - `collide_connected`: whether the two bodies still collide. Default
///   false (Box2D's).
/// - `constraint_hertz` (Hz, > 0) and `constraint_damping_ratio` (≥ 0):
///   the stiffness of the joint's rigid rows (capped at a quarter of the
///   substep rate). Default 60 Hz and 2 (Box2D's).
///
/// A scene with joints and no `[contact]` table runs under the soft step
/// at its defaults (its bodies then collide). Under `model = "exact"` the
/// revolute, prismatic, rigid distance and weld joints are constraints of
/// the equations of motion, integrated by `[simulation] method`
/// (`docs/joints.md`), with a wheel's spring and a motor joint as force
/// laws; a limit, motor, other spring, rope or target joint there is
/// refused at the joint, and so is a ragdoll generator.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum JointSpec {
    /// A shared point about which the bodies turn freely.
    Revolute {
        /// Name. Default `joints[i]`.
        name: Option<String>,
        /// First body, or `"world"` (default).
        body_a: Option<String>,
        /// Second body, or `"world"` (default).
        body_b: Option<String>,
        /// The shared point, world coordinates at t = 0 (m).
        anchor: Option<Xy>,
        /// The point in A's frame (m), with `local_anchor_b`.
        local_anchor_a: Option<Xy>,
        /// The point in B's frame (m), with `local_anchor_a`.
        local_anchor_b: Option<Xy>,
        /// θB − θA at which the joint angle is 0 (rad). Default: the
        /// bodies' relative angle at t = 0.
        reference_angle: Option<f64>,
        /// `[lower, upper]` joint angle (rad), lower ≤ upper, within
        /// ±0.99π. Default: none.
        limits: Option<Range>,
        /// A motor. Default: none.
        motor: Option<RevoluteMotorSpec>,
        /// A rotational spring. Default: none.
        spring: Option<TargetSpringSpec>,
        /// Default false.
        collide_connected: Option<bool>,
        /// Default 60 Hz.
        constraint_hertz: Option<f64>,
        /// Default 2.
        constraint_damping_ratio: Option<f64>,
    },
    /// B slides along an axis fixed in A, without turning relative to it.
    Prismatic {
        /// Name. Default `joints[i]`.
        name: Option<String>,
        /// First body, or `"world"` (default).
        body_a: Option<String>,
        /// Second body, or `"world"` (default).
        body_b: Option<String>,
        /// A point of the axis, world coordinates at t = 0 (m).
        anchor: Option<Xy>,
        /// The point in A's frame (m), with `local_anchor_b`.
        local_anchor_a: Option<Xy>,
        /// The point in B's frame (m), with `local_anchor_a`.
        local_anchor_b: Option<Xy>,
        /// The sliding direction, world frame at t = 0 (any length but
        /// zero). Required.
        axis: Xy,
        /// θB − θA held (rad). Default: the relative angle at t = 0.
        reference_angle: Option<f64>,
        /// `[lower, upper]` translation of B's anchor from A's along the
        /// axis (m), lower ≤ upper. Default: none.
        limits: Option<Range>,
        /// A motor. Default: none.
        motor: Option<PrismaticMotorSpec>,
        /// A linear spring along the axis. Default: none.
        spring: Option<TargetSpringSpec>,
        /// Default false.
        collide_connected: Option<bool>,
        /// Default 60 Hz.
        constraint_hertz: Option<f64>,
        /// Default 2.
        constraint_damping_ratio: Option<f64>,
    },
    /// The distance between a point of A and a point of B: rigid (a
    /// massless rod) by default; with `min_length` or `max_length` and no
    /// `spring`, free between them (a rope); with a `spring`, sprung about
    /// `length`, within the limits if given.
    Distance {
        /// Name. Default `joints[i]`.
        name: Option<String>,
        /// First body, or `"world"` (default).
        body_a: Option<String>,
        /// Second body, or `"world"` (default).
        body_b: Option<String>,
        /// A's point, world coordinates at t = 0 (m); or `local_anchor_a`.
        anchor_a: Option<Xy>,
        /// B's point, world coordinates at t = 0 (m); or `local_anchor_b`.
        anchor_b: Option<Xy>,
        /// A's point in A's frame (m).
        local_anchor_a: Option<Xy>,
        /// B's point in B's frame (m).
        local_anchor_b: Option<Xy>,
        /// The rigid or rest length (m), > 0. Default: the anchors'
        /// distance at t = 0. Not for a rope.
        length: Option<f64>,
        /// Shortest length (m), ≥ 0. Default 0.
        min_length: Option<f64>,
        /// Longest length (m), > 0, ≥ `min_length`. Default: none.
        max_length: Option<f64>,
        /// A spring. Default: none (rigid, or a rope with limits).
        spring: Option<SpringSpec>,
        /// Default false.
        collide_connected: Option<bool>,
        /// Default 60 Hz.
        constraint_hertz: Option<f64>,
        /// Default 2.
        constraint_damping_ratio: Option<f64>,
    },
    /// The bodies held at their relative pose, rigidly or by springs.
    Weld {
        /// Name. Default `joints[i]`.
        name: Option<String>,
        /// First body, or `"world"` (default).
        body_a: Option<String>,
        /// Second body, or `"world"` (default).
        body_b: Option<String>,
        /// The weld point, world coordinates at t = 0 (m).
        anchor: Option<Xy>,
        /// The point in A's frame (m), with `local_anchor_b`.
        local_anchor_a: Option<Xy>,
        /// The point in B's frame (m), with `local_anchor_a`.
        local_anchor_b: Option<Xy>,
        /// θB − θA held (rad). Default: the relative angle at t = 0.
        reference_angle: Option<f64>,
        /// A spring on the point instead of the rigid rows. Default: none.
        linear_spring: Option<SpringSpec>,
        /// A spring on the angle instead of the rigid row. Default: none.
        angular_spring: Option<SpringSpec>,
        /// Default false.
        collide_connected: Option<bool>,
        /// Default 60 Hz.
        constraint_hertz: Option<f64>,
        /// Default 2.
        constraint_damping_ratio: Option<f64>,
    },
    /// A point of one body pulled toward a world point by a spring of
    /// bounded force (Box2D's mouse joint).
    Target {
        /// Name. Default `joints[i]`.
        name: Option<String>,
        /// The body pulled (dynamic). Required.
        body: String,
        /// The point pulled, world coordinates at t = 0 (m). Default: the
        /// body's centre of mass.
        anchor: Option<Xy>,
        /// The point pulled, in the body's frame (m), instead of `anchor`.
        local_anchor: Option<Xy>,
        /// Where it is pulled (m). Default: the anchor (the body is held
        /// where it is).
        target: Option<Xy>,
        /// Largest force (N), > 0. Required.
        max_force: f64,
        /// Stiffness (Hz), > 0. Default 4 (Box2D's).
        hertz: Option<f64>,
        /// Damping ratio, ≥ 0. Default 1 (Box2D's).
        damping_ratio: Option<f64>,
    },
    /// B's anchor (the axle) on a line fixed in A (the chassis), B turning
    /// freely about it, with a suspension spring along the line (Box2D's
    /// wheel joint).
    Wheel {
        /// Name. Default `joints[i]`.
        name: Option<String>,
        /// The chassis, or `"world"` (default).
        body_a: Option<String>,
        /// The wheel, or `"world"` (default).
        body_b: Option<String>,
        /// The axle, world coordinates at t = 0 (m).
        anchor: Option<Xy>,
        /// The point in A's frame (m), with `local_anchor_b`.
        local_anchor_a: Option<Xy>,
        /// The point in B's frame (m), with `local_anchor_a`.
        local_anchor_b: Option<Xy>,
        /// The suspension's direction, world frame at t = 0 (any length
        /// but zero). Default [0, 1].
        axis: Option<Xy>,
        /// The suspension spring along the axis (rest: the anchors level).
        /// Default: none (the axis is free).
        spring: Option<SpringSpec>,
        /// `[lower, upper]` translation along the axis (m). Default: none.
        limits: Option<Range>,
        /// A motor on the wheel's rotation. Default: none.
        motor: Option<RevoluteMotorSpec>,
        /// Default false.
        collide_connected: Option<bool>,
        /// Default 60 Hz.
        constraint_hertz: Option<f64>,
        /// Default 2.
        constraint_damping_ratio: Option<f64>,
    },
    /// B's centre and angle driven to an offset from A's by a linear and
    /// an angular spring of bounded force and torque (Box2D v3.2's motor
    /// joint).
    MotorJoint {
        /// Name. Default `joints[i]`.
        name: Option<String>,
        /// The reference body, or `"world"` (default: its origin).
        body_a: Option<String>,
        /// The body driven, or `"world"` (default).
        body_b: Option<String>,
        /// Target of B's centre from A's, in A's frame (m). Default [0, 0].
        linear_offset: Option<Xy>,
        /// Target θB − θA (rad). Default 0.
        angular_offset: Option<f64>,
        /// Largest force (N), > 0. Required.
        max_force: f64,
        /// Largest torque (N·m), > 0. Required.
        max_torque: f64,
        /// The linear spring. Default 4 Hz, ζ = 1.
        linear_spring: Option<SpringSpec>,
        /// The angular spring. Default 4 Hz, ζ = 1.
        angular_spring: Option<SpringSpec>,
        /// Default false.
        collide_connected: Option<bool>,
    },
}

impl JointSpec {
    /// The type, as written.
    pub fn kind(&self) -> &'static str {
        match self {
            JointSpec::Revolute { .. } => "revolute",
            JointSpec::Prismatic { .. } => "prismatic",
            JointSpec::Distance { .. } => "distance",
            JointSpec::Weld { .. } => "weld",
            JointSpec::Target { .. } => "target",
            JointSpec::Wheel { .. } => "wheel",
            JointSpec::MotorJoint { .. } => "motor_joint",
        }
    }

    /// The name, as written.
    pub fn name(&self) -> Option<&str> {
        match self {
            JointSpec::Revolute { name, .. }
            | JointSpec::Prismatic { name, .. }
            | JointSpec::Distance { name, .. }
            | JointSpec::Weld { name, .. }
            | JointSpec::Target { name, .. }
            | JointSpec::Wheel { name, .. }
            | JointSpec::MotorJoint { name, .. } => name.as_deref(),
        }
    }
}

/// `motor = { speed, max_torque }` of a revolute joint.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RevoluteMotorSpec {
    /// Target ω_B − ω_A (rad/s), any sign. Default 0 (joint friction).
    #[serde(default)]
    pub speed: f64,
    /// Largest torque (N·m), > 0. Required.
    pub max_torque: f64,
}

/// `motor = { speed, max_force }` of a prismatic joint.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrismaticMotorSpec {
    /// Target speed along the axis (m/s), any sign. Default 0.
    #[serde(default)]
    pub speed: f64,
    /// Largest force (N), > 0. Required.
    pub max_force: f64,
}

/// `{ hertz, damping_ratio }`: a joint spring, mass-independent.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringSpec {
    /// Natural frequency (Hz), > 0. Required.
    pub hertz: f64,
    /// Damping ratio, ≥ 0 (1 is critical). Default 0.
    #[serde(default)]
    pub damping_ratio: f64,
}

/// `{ hertz, damping_ratio, target }`: a revolute's or prismatic's spring.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TargetSpringSpec {
    /// Natural frequency (Hz), > 0. Required.
    pub hertz: f64,
    /// Damping ratio, ≥ 0. Default 0.
    #[serde(default)]
    pub damping_ratio: f64,
    /// Rest angle (rad) or translation (m). Default 0.
    #[serde(default)]
    pub target: f64,
}

/// `[linear_test]`: Hoffman's scalar stiff test (seed §4.3), generalised to a
/// linear forcing g(t) = `forcing_offset` + `forcing_slope`·t:
///
/// y' = λ (y − g(t)) + g'(t),  y(0) = y0,
///
/// with exact solution y = g(t) + (y0 − g(0)) e^(λt). The defaults give the
/// seed's y' = λ(y − (t + 2)) + 1. Time in s, y dimensionless.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinearTestSpec {
    /// λ (s⁻¹), finite; < 0 for a decaying (stiff) transient. Required.
    pub lambda: f64,
    /// y(0). Required.
    pub y0: f64,
    /// g(0), the forcing's value at t = 0. Default 2.
    #[serde(default = "two")]
    pub forcing_offset: f64,
    /// g'(t), the forcing's slope (s⁻¹). Default 1.
    #[serde(default = "one")]
    pub forcing_slope: f64,
}

fn one() -> f64 {
    1.0
}

fn two() -> f64 {
    2.0
}

/// A 2D vector written `[x, y]`: exactly two numbers (integers are
/// accepted). Units are those of the field.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Xy {
    /// First component.
    pub x: f64,
    /// Second component.
    pub y: f64,
}

impl Xy {
    /// As an nalgebra vector.
    pub fn vector(&self) -> nalgebra::Vector2<f64> {
        nalgebra::Vector2::new(self.x, self.y)
    }
}

/// Limits written `[lower, upper]`, in the field's unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Lower limit.
    pub lower: f64,
    /// Upper limit.
    pub upper: f64,
}

impl<'de> Deserialize<'de> for Range {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let (lower, upper) = deserializer.deserialize_seq(PairVisitor("[lower, upper]"))?;
        Ok(Self { lower, upper })
    }
}

/// A force's active window `[start, end]` (s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// Start of activity (s).
    pub start: f64,
    /// End of activity (s), excluded.
    pub end: f64,
}

/// Reads exactly two numbers: toml's deserializer lets `[f64; 2]` silently
/// drop a third element, so `[1, 2, 3]` must be refused here.
struct PairVisitor(&'static str);

impl<'de> Visitor<'de> for PairVisitor {
    type Value = (f64, f64);

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "an array of exactly two numbers {}", self.0)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let a = seq
            .next_element::<f64>()?
            .ok_or_else(|| de::Error::invalid_length(0, &self))?;
        let b = seq
            .next_element::<f64>()?
            .ok_or_else(|| de::Error::invalid_length(1, &self))?;
        let mut len = 2;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            len += 1;
        }
        if len != 2 {
            return Err(de::Error::invalid_length(len, &self));
        }
        Ok((a, b))
    }
}

impl<'de> Deserialize<'de> for Xy {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let (x, y) = deserializer.deserialize_seq(PairVisitor("[x, y]"))?;
        Ok(Self { x, y })
    }
}

impl<'de> Deserialize<'de> for Window {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let (start, end) = deserializer.deserialize_seq(PairVisitor("[start, end]"))?;
        Ok(Self { start, end })
    }
}
