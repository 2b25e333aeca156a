//! What the soft step reports about its contacts, and the hooks a program
//! can give it (Box2D v3's contact events, sensor events, `b2ContactData`,
//! custom filter and pre-solve callbacks).
//!
//! **Events** ([`StepEvents`], read with [`crate::World::step_events`]
//! after a step; each call of [`crate::World::step`] clears them first):
//!
//! - *touch began / ended*, per pair of shapes, when a pair's manifold gets
//!   its first point (touching, or within the speculative distance) or
//!   loses its last one, or the pair is destroyed while touching (the
//!   shapes' boxes parted, a body was removed, a joint now keeps them
//!   apart);
//! - *hit*, for a pair that began touching this step and whose point
//!   approached faster than [`crate::SoftStepSettings::hit_event_threshold`]
//!   and pushed (Box2D's rule: the point of largest approach speed among
//!   those with a non-zero total normal impulse);
//! - *sensor began / ended*, when a shape overlaps a sensor shape or stops
//!   overlapping it (overlap: a manifold point with separation ≤ 0).
//!   Sensors do not detect other sensors (Box2D v3's rule), and detect the
//!   shapes of static, kinematic and dynamic bodies as long as one of the
//!   two bodies moves (two static bodies are never paired).
//!
//! The event lists are vectors kept by the model and cleared, not freed,
//! each step: once they have grown to a scene's largest step, collecting
//! them allocates nothing.
//!
//! **Contact data** ([`crate::World::contact_data`]): every touching pair
//! of non-sensor shapes with its normal and points, each with the impulses
//! of the last step. A point's `total_normal_impulse` is the normal impulse
//! it delivered over the whole step (the sum over the substeps, restitution
//! included): divided by the step it is the average contact force (N).
//! `normal_impulse` is the accumulated impulse of the last substep (what
//! warm-starts the next step).
//!
//! **Hooks** ([`ContactHooks`], set with [`crate::World::set_contact_hooks`]):
//! `should_collide` is asked once when two shapes that passed their
//! filters first come near each other (their enlarged boxes overlap): false
//! and the pair gets no contact until they part and meet again;
//! `pre_solve` is asked every step for every touching non-sensor pair
//! before the solver sees it: false and the pair has no points this step
//! (Box2D's rule: its impulses are dropped, and touch events follow). Both
//! are called from inside the step; they must not allocate per call to keep
//! the step allocation-free.

use crate::body::BodyId;
use nalgebra::Vector2;

/// A shape of the world: a body's shape, or one part of a compound shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ShapeId {
    /// The body.
    pub body: BodyId,
    /// The part of its compound shape (0 for a simple shape).
    pub part: usize,
}

/// Two shapes that began or ended touching. `a` is the pair's reference
/// shape (the normal of [`ContactData`] points from `a` to `b`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TouchEvent {
    /// The first shape.
    pub a: ShapeId,
    /// The second shape.
    pub b: ShapeId,
}

/// A pair that began touching fast.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct HitEvent {
    /// The first shape.
    pub a: ShapeId,
    /// The second shape.
    pub b: ShapeId,
    /// The point of the hit (world frame, m), where the manifold was
    /// computed at the start of the step.
    pub point: Vector2<f64>,
    /// Unit normal from `a` to `b`.
    pub normal: Vector2<f64>,
    /// Approach speed along the normal before the solve (m/s, > 0).
    pub approach_speed: f64,
}

/// A shape that began or ended overlapping a sensor.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SensorEvent {
    /// The sensor shape.
    pub sensor: ShapeId,
    /// The shape that entered or left it.
    pub visitor: ShapeId,
}

/// The events of the last [`crate::World::step`] (see the module docs).
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct StepEvents {
    /// Pairs that began touching.
    pub touch_began: Vec<TouchEvent>,
    /// Pairs that stopped touching.
    pub touch_ended: Vec<TouchEvent>,
    /// Pairs that began touching faster than the hit threshold.
    pub hits: Vec<HitEvent>,
    /// Shapes that began overlapping a sensor.
    pub sensor_began: Vec<SensorEvent>,
    /// Shapes that stopped overlapping a sensor.
    pub sensor_ended: Vec<SensorEvent>,
    /// Joints whose force or torque reached their threshold
    /// ([`crate::JointDef::force_threshold`]) in the step's last substep.
    pub joints_exceeded: Vec<JointEvent>,
}

/// A joint whose force or torque reached its threshold (Box2D v3's
/// `b2JointEvent`): a breakable joint is one the program then removes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointEvent {
    /// The joint.
    pub joint: crate::JointId,
    /// Its force on body B in the last substep (N), world frame.
    pub force: Vector2<f64>,
    /// Its torque on body B in the last substep (N·m).
    pub torque: f64,
}

impl StepEvents {
    /// Empties every list, keeping their memory.
    pub(crate) fn clear(&mut self) {
        self.touch_began.clear();
        self.touch_ended.clear();
        self.hits.clear();
        self.sensor_began.clear();
        self.sensor_ended.clear();
        self.joints_exceeded.clear();
    }
}

/// A point of a touching pair, after the last step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactPointData {
    /// The point (world frame, m), where the manifold was computed (at the
    /// start of the step, or up to the recycle distance earlier).
    pub point: Vector2<f64>,
    /// Signed distance along the normal when the step began (m): < 0
    /// overlapping, > 0 a speculative point.
    pub separation: f64,
    /// Accumulated normal impulse of the last substep (N·s).
    pub normal_impulse: f64,
    /// Accumulated friction impulse of the last substep (N·s), along the
    /// tangent (n.y, −n.x).
    pub tangent_impulse: f64,
    /// Normal impulse delivered over the whole step (N·s): ÷ dt gives the
    /// mean normal force (N).
    pub total_normal_impulse: f64,
    /// Relative normal velocity before the solve (m/s, < 0 approaching).
    pub normal_velocity: f64,
}

/// A touching pair of shapes and its manifold after the last step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactData {
    /// The reference shape.
    pub a: ShapeId,
    /// The other shape.
    pub b: ShapeId,
    /// Unit normal from `a` to `b`.
    pub normal: Vector2<f64>,
    /// Number of points (1 or 2).
    pub count: usize,
    /// The points; the first `count` are valid.
    pub points: [ContactPointData; 2],
    /// Accumulated rolling-resistance angular impulse of the last substep
    /// (N·m·s), on `b` (−, on `a`).
    pub rolling_impulse: f64,
}

impl ContactData {
    /// The valid points.
    pub fn points(&self) -> &[ContactPointData] {
        &self.points[..self.count]
    }
}

/// A touching pair as the pre-solve hook sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreSolveContact {
    /// The reference shape.
    pub a: ShapeId,
    /// The other shape.
    pub b: ShapeId,
    /// Unit normal from `a` to `b` (world frame).
    pub normal: Vector2<f64>,
    /// Number of points (1 or 2).
    pub count: usize,
    /// The points (world frame, m) and their separations (m); the first
    /// `count` are valid.
    pub points: [(Vector2<f64>, f64); 2],
}

/// A program's say in which pairs collide (see the module docs). Both
/// methods default to "yes".
///
/// Hooks are code, not state: a cloned world gets its own copy of them
/// (hence `Clone`), and a world written to bytes leaves them out, so a
/// restored world has none until the program sets them again
/// ([`crate::World::set_contact_hooks`]). `Send`, as the world is: a
/// program may step it on another thread.
pub trait ContactHooks: ContactHooksClone + Send {
    /// Whether shapes `a` and `b`, whose filters let them collide, get a
    /// contact. Asked when their enlarged boxes begin to overlap.
    fn should_collide(&mut self, a: ShapeId, b: ShapeId) -> bool {
        let _ = (a, b);
        true
    }

    /// Whether the touching pair `contact` is solved this step; false
    /// disables it for the step (a one-way platform: false while the
    /// normal points the wrong way).
    fn pre_solve(&mut self, contact: &PreSolveContact) -> bool {
        let _ = contact;
        true
    }
}

/// Clones a boxed [`ContactHooks`]; implemented for every hooks type that
/// is `Clone`.
pub trait ContactHooksClone {
    /// A boxed copy of these hooks.
    fn clone_box(&self) -> Box<dyn ContactHooks>;
}

impl<T: ContactHooks + Clone + 'static> ContactHooksClone for T {
    fn clone_box(&self) -> Box<dyn ContactHooks> {
        Box::new(self.clone())
    }
}

/// The hooks a model holds, if any (a `Debug` wrapper). A clone copies
/// them; bytes leave them out (see [`ContactHooks`]).
#[derive(Default)]
pub(crate) struct Hooks(pub Option<Box<dyn ContactHooks>>);

impl Clone for Hooks {
    fn clone(&self) -> Self {
        Self(self.0.as_ref().map(|h| h.clone_box()))
    }
}

impl std::fmt::Debug for Hooks {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.is_some() {
            "Hooks(set)"
        } else {
            "Hooks(none)"
        })
    }
}
