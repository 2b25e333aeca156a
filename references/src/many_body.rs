//! An engine-agnostic description of a many-body scene (boxes, circles and
//! convex polygons on static ground, walls or kinematic movers) and the
//! interface every many-body engine of the benchmark implements: Box2D v3
//! ([`crate::box2d_world`]), rapier2d ([`crate::rapier_many`]), and the
//! project's own soft-step solver (in the harness).
//!
//! A [`ManyBodyScene`] says *what* is simulated (bodies, shapes, materials,
//! gravity, the step and the substep count); each adapter builds it in its
//! engine and documents *how* (every setting it changes from the engine's
//! defaults). The harness times [`ManyBodyEngine::step`] alone; reading the
//! state back ([`ManyBodyEngine::samples`], [`ManyBodyEngine::contact_counts`])
//! is separate and never timed.
//!
//! Conventions shared by every engine:
//! - one shape per body. A dynamic body's shape is centred on the body
//!   origin, which is then its centre of mass (a polygon's centroid at the
//!   origin, checked by [`ManyBodyScene::validate`]). A static or kinematic
//!   body's polygon may sit anywhere in its frame (a tumbler's wall is a
//!   kinematic body at the tumbler's axis with an off-centre wall polygon),
//!   since such bodies have no mass;
//! - mass = density × area, inertia = density × ∫ r² dA about the origin
//!   (each engine computes them from the shape and the density);
//! - materials are per body and mixed per pair by Box2D's rules: friction
//!   √(μa μb), restitution max(ea, eb) (rapier is set to the same rules);
//! - angles read back are principal values in (−π, π]: samples may be taken
//!   at any interval, so no adapter unwraps them;
//! - bodies sharing a `collision_group` never collide with each other
//!   (Box2D's negative group index; a ragdoll's bones, the joint grid's
//!   circles);
//! - joints ([`SceneJoint`], in [`joints`]) connect two bodies or a body and
//!   the world, anchors given in world coordinates at t = 0; their state is
//!   read from the bodies' poses by [`ManyBodyScene::joint_states`], the
//!   same computation for every engine.
//!
//! Units: SI throughout (m, s, kg, rad; density in kg/m²).

use engine::{ConvexPolygon, Shape};
use thiserror::Error;

#[cfg(test)]
mod joint_checks;
#[cfg(test)]
mod joint_tests;
pub mod joints;
pub mod overlap;
pub mod scenes;
#[cfg(test)]
mod tests;

pub use joints::{
    DistanceJoint, DistanceMode, JointKind, JointState, Motor, Pose, PrismaticJoint, RevoluteJoint,
    SceneJoint, Softness, Spring, WeldJoint,
};
pub use overlap::{Overlap, deepest_overlap};
pub use scenes::{
    falling_hinges, joint_grid, pyramid, ragdoll, rain, smash, tumbler, vertical_stack,
};

/// How a body moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BodyKind {
    /// Moved by gravity and contacts; needs a density > 0.
    Dynamic,
    /// Never moves; its velocity must be zero.
    Static,
    /// Moves at its own constant velocity and angular velocity, whatever it
    /// touches (infinite mass).
    Kinematic,
}

/// A body of a [`ManyBodyScene`], at t = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneBody {
    /// Dynamic, static or kinematic.
    pub kind: BodyKind,
    /// The body's shape in its own frame (m). For a dynamic body, centred on
    /// the origin (the centre of mass).
    pub shape: Shape,
    /// Position of the body origin, m.
    pub position: [f64; 2],
    /// Orientation, rad (counter-clockwise).
    pub angle: f64,
    /// Linear velocity of the origin, m/s (zero for a static body).
    pub velocity: [f64; 2],
    /// Angular velocity, rad/s (zero for a static body).
    pub angular_velocity: f64,
    /// Areal density, kg/m² (> 0 for a dynamic body; ignored otherwise).
    pub density: f64,
    /// Coulomb friction coefficient μ (≥ 0); a pair uses √(μa μb).
    pub friction: f64,
    /// Coefficient of restitution e (≥ 0); a pair uses max(ea, eb).
    pub restitution: f64,
    /// Bodies with the same `Some(group)` never collide with each other
    /// (default `None`: collides with everything).
    pub collision_group: Option<u32>,
}

impl SceneBody {
    /// A dynamic body at rest at `position`, angle 0, with `density`
    /// (kg/m²), friction 0.6 and restitution 0 (Box2D's default material).
    pub fn dynamic(shape: Shape, position: [f64; 2], density: f64) -> Self {
        Self {
            kind: BodyKind::Dynamic,
            shape,
            position,
            angle: 0.0,
            velocity: [0.0, 0.0],
            angular_velocity: 0.0,
            density,
            friction: DEFAULT_FRICTION,
            restitution: 0.0,
            collision_group: None,
        }
    }

    /// A static body at `position`, angle 0, friction 0.6, restitution 0.
    pub fn fixed(shape: Shape, position: [f64; 2]) -> Self {
        Self {
            kind: BodyKind::Static,
            density: 0.0,
            ..Self::dynamic(shape, position, 0.0)
        }
    }

    /// A kinematic body at `position` moving at `velocity` (m/s) and
    /// `angular_velocity` (rad/s), friction 0.6, restitution 0.
    pub fn kinematic(
        shape: Shape,
        position: [f64; 2],
        velocity: [f64; 2],
        angular_velocity: f64,
    ) -> Self {
        Self {
            kind: BodyKind::Kinematic,
            velocity,
            angular_velocity,
            ..Self::fixed(shape, position)
        }
    }

    /// Mass (kg): density × area for a dynamic body, 0 otherwise.
    pub fn mass(&self) -> f64 {
        match self.kind {
            BodyKind::Dynamic => self.density * self.shape.area(),
            BodyKind::Static | BodyKind::Kinematic => 0.0,
        }
    }

    /// Moment of inertia about the centre of mass (kg·m²) of a dynamic body,
    /// 0 otherwise.
    pub fn inertia(&self) -> f64 {
        self.mass() * self.shape.inertia_per_unit_mass()
    }
}

/// Box2D's default friction coefficient (`b2DefaultShapeDef`), used by its
/// benchmark scenes.
pub const DEFAULT_FRICTION: f64 = 0.6;

/// A many-body scene: what every engine simulates.
#[derive(Debug, Clone, PartialEq)]
pub struct ManyBodyScene {
    /// Uniform gravitational acceleration, m/s².
    pub gravity: [f64; 2],
    /// Step length, s (> 0).
    pub dt: f64,
    /// Substeps per step (≥ 1): Box2D's `subStepCount`, rapier's
    /// `num_solver_iterations`, the soft step's substeps.
    pub substeps: usize,
    /// The bodies; samples and errors refer to bodies by their index here.
    pub bodies: Vec<SceneBody>,
    /// The joints; errors and joint states refer to them by their index
    /// here.
    pub joints: Vec<SceneJoint>,
}

/// Largest substep count accepted (Box2D takes an `int`; beyond this the
/// benchmark would be meaningless anyway).
pub const MAX_SUBSTEPS: usize = 1000;

/// How far (relative to the shape's size) a dynamic body's polygon centroid
/// may sit from its origin: the engine's own centroid of a centred polygon
/// is exact to a few ulps of the vertex coordinates, so 1e-9 of the size
/// accepts round-off and refuses any real offset.
const CENTROID_TOLERANCE: f64 = 1e-9;

impl ManyBodyScene {
    /// Checks every number of the scene: finite values, dt > 0,
    /// 1 ≤ substeps ≤ [`MAX_SUBSTEPS`], density > 0 for dynamic bodies
    /// (≥ 0 otherwise), friction and restitution ≥ 0, zero velocity for
    /// static bodies, and dynamic shapes centred on their origin; and every
    /// joint (see [`joints`]: existing distinct bodies, one of them
    /// dynamic, finite anchors, ordered limits, positive lengths, axes and
    /// spring frequencies, non-negative motor forces and damping ratios).
    /// The first problem found is returned, naming the body or joint (by
    /// index) and the field.
    pub fn validate(&self) -> Result<(), ManyBodyError> {
        for (field, v) in [
            ("gravity x", self.gravity[0]),
            ("gravity y", self.gravity[1]),
        ] {
            if !v.is_finite() {
                return Err(ManyBodyError::scene(field, v, "must be finite"));
            }
        }
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(ManyBodyError::scene(
                "dt",
                self.dt,
                "must be finite and > 0",
            ));
        }
        if !(1..=MAX_SUBSTEPS).contains(&self.substeps) {
            return Err(ManyBodyError::scene(
                "substeps",
                self.substeps as f64,
                "must be between 1 and 1000",
            ));
        }
        for (i, b) in self.bodies.iter().enumerate() {
            validate_body(i, b)?;
        }
        for (i, j) in self.joints.iter().enumerate() {
            joints::validate_joint(i, j, &self.bodies)?;
        }
        Ok(())
    }

    /// The state of every joint (in scene order) when the bodies are at
    /// `samples` (in scene order, as [`ManyBodyEngine::samples`] gives
    /// them): the coordinate, the anchor separation, the angular error and
    /// the limit violation, computed from the poses alone, the same way for
    /// every engine. The scene must be valid and `samples` complete.
    pub fn joint_states(&self, samples: &[BodySample]) -> Vec<JointState> {
        joints::joint_states(&self.bodies, &self.joints, samples)
    }

    /// The deepest overlap at the poses of `samples` of the pairs that can
    /// collide: [`deepest_overlap`] without the pairs of two bodies held by
    /// a joint that keeps them apart (`collide_connected` false).
    pub fn deepest_overlap(&self, samples: &[BodySample]) -> Option<Overlap> {
        let apart: std::collections::HashSet<(usize, usize)> = self
            .joints
            .iter()
            .filter(|j| !j.collide_connected)
            .filter_map(|j| Some((j.body_a?, j.body_b?)))
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect();
        overlap::deepest_overlap_except(&self.bodies, samples, |i, j| apart.contains(&(i, j)))
    }

    /// Total mass of the dynamic bodies, kg.
    pub fn dynamic_mass(&self) -> f64 {
        self.bodies.iter().map(SceneBody::mass).sum()
    }
}

fn validate_body(i: usize, b: &SceneBody) -> Result<(), ManyBodyError> {
    let finite = [
        ("position x", b.position[0]),
        ("position y", b.position[1]),
        ("angle", b.angle),
        ("velocity x", b.velocity[0]),
        ("velocity y", b.velocity[1]),
        ("angular velocity", b.angular_velocity),
    ];
    for (field, v) in finite {
        if !v.is_finite() {
            return Err(ManyBodyError::body(i, field, v, "must be finite"));
        }
    }
    for (field, v) in [("friction", b.friction), ("restitution", b.restitution)] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(ManyBodyError::body(i, field, v, "must be finite and >= 0"));
        }
    }
    match b.kind {
        BodyKind::Dynamic => {
            if !(b.density.is_finite() && b.density > 0.0) {
                return Err(ManyBodyError::body(
                    i,
                    "density",
                    b.density,
                    "must be finite and > 0 for a dynamic body",
                ));
            }
            for (field, v) in [
                ("mass (density × area)", b.mass()),
                ("moment of inertia", b.inertia()),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(ManyBodyError::body(i, field, v, "must be finite and > 0"));
                }
            }
            if let Shape::Polygon(p) = &b.shape {
                let c = p.centroid();
                let size = p
                    .vertices()
                    .iter()
                    .map(|v| v.norm())
                    .fold(0.0_f64, f64::max);
                if c.norm() > CENTROID_TOLERANCE * size {
                    return Err(ManyBodyError::body(
                        i,
                        "shape centroid distance from the origin",
                        c.norm(),
                        "a dynamic body's polygon must be centred on its origin \
                         (the centre of mass): use ConvexPolygon::centered",
                    ));
                }
            }
        }
        BodyKind::Static | BodyKind::Kinematic => {
            if !(b.density.is_finite() && b.density >= 0.0) {
                return Err(ManyBodyError::body(
                    i,
                    "density",
                    b.density,
                    "must be finite and >= 0",
                ));
            }
        }
    }
    if b.kind == BodyKind::Static {
        let speed = b.velocity[0].hypot(b.velocity[1]);
        if speed != 0.0 || b.angular_velocity != 0.0 {
            return Err(ManyBodyError::body(
                i,
                "velocity of a static body",
                speed.max(b.angular_velocity.abs()),
                "must be zero (a moving body without mass is kinematic)",
            ));
        }
    }
    Ok(())
}

/// A body's state as an engine reports it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BodySample {
    /// Position of the body origin (the centre of mass of a dynamic body), m.
    pub position: [f64; 2],
    /// Orientation, rad, principal value in (−π, π].
    pub angle: f64,
    /// Linear velocity, m/s.
    pub velocity: [f64; 2],
    /// Angular velocity, rad/s.
    pub angular_velocity: f64,
}

impl BodySample {
    /// |v|, m/s.
    pub fn speed(&self) -> f64 {
        self.velocity[0].hypot(self.velocity[1])
    }
}

/// A body's mass properties as an engine holds them (what it computed from
/// the shape and the density).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BodyMass {
    /// Mass, kg (0 for static and kinematic bodies).
    pub mass: f64,
    /// Moment of inertia about the centre of mass, kg·m² (0 for static and
    /// kinematic bodies).
    pub inertia: f64,
}

/// The contacts an engine holds after its last step, as its own narrow
/// phase reports them.
///
/// Both engines keep speculative points (separation up to 0.02 m in both,
/// by default) in their manifolds, so `touching_pairs` and `points` include
/// pairs about to touch. Separations are those of the engine's last
/// collision pass, which runs at the *start* of a step (before the solver
/// moves the bodies). With contact recycling (on by default in both), a
/// pair that moved little skips that pass: Box2D then updates its
/// separations from the bodies' motion, rapier keeps the `dist` of the
/// pair's last full update, possibly from the impact that created it, so
/// rapier's `penetrating_points` and `deepest_penetration` are stale (see
/// [`crate::rapier_many::RapierManyWorld::disable_contact_recycling`]).
/// For a comparison on equal terms use [`deepest_overlap`], computed from
/// the poses.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactCounts {
    /// Shape pairs with at least one manifold point.
    pub touching_pairs: usize,
    /// Manifold points over all pairs.
    pub points: usize,
    /// Points with a negative separation (overlap).
    pub penetrating_points: usize,
    /// The largest overlap, −(most negative separation), m; 0 if none.
    pub deepest_penetration: f64,
}

/// What the benchmark needs of a many-body engine.
///
/// Reading back takes `&mut self` because Box2D's safe bindings lend body
/// access only through a mutable borrow of the world; nothing is changed.
pub trait ManyBodyEngine {
    /// Engine and version, e.g. `"Box2D 3.2 (boxdd 0.6)"`.
    fn name(&self) -> &'static str;

    /// One paragraph for the report: precision, substeps, contact
    /// stiffness, damping, push-out speed, restitution threshold, CCD,
    /// sleeping, threads, and every setting changed from the engine's
    /// defaults.
    fn configuration(&self) -> String;

    /// Number of bodies (the scene's, in its order).
    fn body_count(&self) -> usize;

    /// Steps completed since construction.
    fn steps_taken(&self) -> usize;

    /// Advances the world by one step of the scene's dt with its substeps.
    /// This is the only method the benchmark times.
    fn step(&mut self) -> Result<(), ManyBodyError>;

    /// Every body's state, in scene order, written into `out` (cleared
    /// first). Refuses a non-finite state.
    fn samples(&mut self, out: &mut Vec<BodySample>) -> Result<(), ManyBodyError>;

    /// The mass properties the engine computed, in scene order.
    fn mass_properties(&mut self) -> Result<Vec<BodyMass>, ManyBodyError>;

    /// The engine's contacts after the last step.
    fn contact_counts(&mut self) -> Result<ContactCounts, ManyBodyError>;
}

/// Why a many-body scene could not be built or advanced.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ManyBodyError {
    /// A scene-wide value is out of its domain.
    #[error("many-body scene: {field} = {value} {reason}")]
    InvalidScene {
        /// Which value.
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },
    /// A body's value is out of its domain.
    #[error("many-body scene, body {body}: {field} = {value} {reason}")]
    InvalidBody {
        /// Index of the body in the scene.
        body: usize,
        /// Which value.
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },
    /// A joint's value is out of its domain.
    #[error("many-body scene, joint {joint}: {field} = {value} {reason}")]
    InvalidJoint {
        /// Index of the joint in the scene.
        joint: usize,
        /// Which value.
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },
    /// The engine cannot represent a joint as described.
    #[error("{engine} cannot represent joint {joint}: {message}")]
    JointRefused {
        /// Engine name.
        engine: &'static str,
        /// Index of the joint in the scene.
        joint: usize,
        /// Why, in the engine's terms.
        message: String,
    },
    /// The engine refused a body (e.g. a polygon it cannot represent).
    #[error("{engine} cannot represent body {body}: {message}")]
    BodyRefused {
        /// Engine name.
        engine: &'static str,
        /// Index of the body in the scene.
        body: usize,
        /// The engine's reason, in its words.
        message: String,
    },
    /// The engine reported a failure.
    #[error("{engine} failed: {message}")]
    Engine {
        /// Engine name.
        engine: &'static str,
        /// The engine's message.
        message: String,
    },
    /// A body's state stopped being finite.
    #[error("{engine}: body {body} has a non-finite state after {steps} steps")]
    NonFinite {
        /// Engine name.
        engine: &'static str,
        /// Index of the body in the scene.
        body: usize,
        /// Steps completed when it was seen.
        steps: usize,
    },
}

impl ManyBodyError {
    pub(crate) fn scene(field: &'static str, value: f64, reason: &'static str) -> Self {
        Self::InvalidScene {
            field,
            value,
            reason,
        }
    }

    pub(crate) fn body(body: usize, field: &'static str, value: f64, reason: &'static str) -> Self {
        Self::InvalidBody {
            body,
            field,
            value,
            reason,
        }
    }
}

/// `Some((centre, half_width, half_height))` if `polygon` is an axis-aligned
/// rectangle (four vertices, edges exactly horizontal or vertical), which
/// both engines have a dedicated box shape for.
pub(crate) fn axis_aligned_box(polygon: &ConvexPolygon) -> Option<([f64; 2], f64, f64)> {
    let v = polygon.vertices();
    if v.len() != 4 {
        return None;
    }
    let aligned = (0..4).all(|i| {
        let (a, b) = (v[i], v[(i + 1) % 4]);
        a.x == b.x || a.y == b.y
    });
    if !aligned {
        return None;
    }
    let (min_x, max_x) = (v.iter().map(|q| q.x).fold(f64::INFINITY, f64::min), {
        v.iter().map(|q| q.x).fold(f64::NEG_INFINITY, f64::max)
    });
    let (min_y, max_y) = (v.iter().map(|q| q.y).fold(f64::INFINITY, f64::min), {
        v.iter().map(|q| q.y).fold(f64::NEG_INFINITY, f64::max)
    });
    Some((
        [0.5 * (min_x + max_x), 0.5 * (min_y + max_y)],
        0.5 * (max_x - min_x),
        0.5 * (max_y - min_y),
    ))
}

/// What differs between the Box2D and rapier adapters once both are set up
/// as the adapters document (same scene, same substeps, same mixing rules,
/// sleeping off, one thread), for the report.
pub const ENGINE_DIFFERENCES: &[&str] = &[
    "precision: Box2D 3.2 stores positions, velocities and impulses in f32 \
     (its double-precision build only its absolute positions in f64; each \
     row's build is in the builds table); rapier2d-f64 in f64",
    "friction: Box2D solves friction only in the relax pass of each substep; \
     rapier 0.36 does the same by default (friction_in_bias_pass = false)",
    "contact softness: both 30 Hz with damping ratio 10, 60 Hz against static \
     bodies (Box2D doubles the contact hertz, rapier has its own 60 Hz \
     static_contact_softness), 30 Hz against kinematic ones in both; Box2D caps \
     the contact hertz at a quarter of the substep Nyquist rate (0.125/h = 30 Hz \
     at 4 substeps of 1/60 s), rapier does not cap it",
    "penetration: Box2D has no slop in the contact bias (it pushes out to zero \
     separation); rapier neither (allowed_linear_error is only the CCD standoff)",
    "restitution: Box2D applies it when the pre-solve approach speed exceeds 1 m/s \
     (restitution threshold); rapier has no threshold but bounces only contacts \
     that are new this step (a persisting contact rests unless e >= 1)",
    "CCD: both sweep fast dynamic bodies against static geometry only (Box2D \
     enableContinuous, rapier max_ccd_substeps = 1 with its automatic tier); \
     neither treats bodies as bullets",
    "contact recycling: both on by default (Box2D 0.05 m, rapier 0.05 m of \
     relative motion); Box2D updates a recycled pair's separations from the body \
     motion, rapier keeps them from the last full update",
    "speed limits: both clamp |v| to 400 m/s and |omega| to (pi/4)/dt per step",
    "polygons: Box2D at most 8 vertices, built through its hull (which welds \
     points closer than 0.005 m); rapier any count, vertices kept as given",
    "joint softness: Box2D's joints are soft rows of 60 Hz, damping ratio 2 \
     (min(60, 0.25/h) Hz) in the biased pass and rigid in the relax pass; rapier's \
     locked axes and limits 1e6 Hz, ratio 1 (rigid), their bias removed in the relax \
     pass; rapier does not warm-start joints (warmstart_joints false), Box2D does",
    "joint limits: Box2D's are speculative (a limit row acts before the angle \
     reaches it); rapier's angular limit rows engage only once the angle is past \
     the limit and recover at most at the corrective speed cap",
    "joint angles: Box2D measures them with b2Atan2, a polynomial of error up to \
     2.8e-5 rad, so its limits and springs act on that approximate angle; rapier \
     uses the exact angle",
    "joint springs and motors: the same soft spring in both (rapier's \
     AccelerationBased motor with stiffness (2 pi f)^2 and damping 2 zeta (2 pi f) \
     is Box2D's spring of f Hz and ratio zeta exactly); a spring and a motor on one \
     joint are two rows in Box2D, a second impulse joint carrying the motor in rapier",
    "rigid distance joints: Box2D's soft row (as above); rapier has none, here a \
     position motor along the coupled linear axes at rapier's joint softness, kept \
     in the relax pass",
];

/// Whether `shape` is or holds a rounded shape of `kind`: the adapters
/// give some of them their exact mass properties explicitly (parry gives a
/// round polygon its core's and a capsule an inertia built on the 3D
/// hemisphere's centroid offset 3r/8 instead of the half disc's 4r/3π;
/// Box2D approximates a rounded polygon's).
pub fn holds_rounded(shape: &Shape, kind: engine::RoundedKind) -> bool {
    shape
        .pieces()
        .into_iter()
        .any(|(_, _, piece)| matches!(piece, Shape::Rounded(r) if r.kind() == kind))
}
