//! Dragging a body with the mouse: a target joint (Box2D's mouse joint,
//! `engine::Target`, docs/joints.md) from the world to the grabbed point,
//! whose target follows the cursor. It pulls like Box2D's samples do: a
//! spring of [`DRAG_HERTZ`] and [`DRAG_DAMPING`] with a largest force of
//! [`FORCE_PER_WEIGHT`] times the body's weight, so a dragged body
//! follows the cursor within a fraction of a second and still pushes the
//! others like a body, not like a wall.
//!
//! Joints need the soft step: under the exact model a grab is refused with
//! the engine's reason and the remedy (switch the model with M).

use engine::{BodyId, JointDef, JointId, JointSpring, Target, World};
use nalgebra::Vector2;

/// The pull's natural frequency (Hz; Box2D's samples use 5 Hz).
pub const DRAG_HERTZ: f64 = 5.0;
/// The pull's damping ratio (Box2D's samples: 0.7).
pub const DRAG_DAMPING: f64 = 0.7;
/// Largest pull, in weights of the body (Box2D's samples: 1000).
pub const FORCE_PER_WEIGHT: f64 = 1000.0;
/// The acceleration that sets a weight when the world has no gravity
/// (m/s²).
const REFERENCE_GRAVITY: f64 = 10.0;

/// A drag in progress.
#[derive(Debug, Clone, Copy)]
pub struct Drag {
    /// The target joint.
    pub joint: JointId,
    /// The body pulled.
    pub body: BodyId,
    /// Where the cursor is (m).
    pub target: Vector2<f64>,
}

impl Drag {
    /// Grabs `body` at world point `at` (m): adds the target joint.
    pub fn grab(world: &mut World, body: BodyId, at: Vector2<f64>) -> engine::Result<Self> {
        let mass = world.bodies()[body].mass;
        let g = world.gravity().norm();
        let g = if g > 0.0 { g } else { REFERENCE_GRAVITY };
        let pull = Target {
            max_force: FORCE_PER_WEIGHT * mass * g,
            spring: JointSpring::new(DRAG_HERTZ, DRAG_DAMPING),
        };
        let joint = world.add_joint(JointDef::target("mouse drag", body, at, at, pull))?;
        Ok(Self {
            joint,
            body,
            target: at,
        })
    }

    /// Moves the target to `to` (m).
    pub fn move_to(&mut self, world: &mut World, to: Vector2<f64>) -> engine::Result<()> {
        self.target = to;
        world.set_joint_target(self.joint, to)
    }

    /// Lets go: removes the joint.
    pub fn release(self, world: &mut World) -> engine::Result<()> {
        world.remove_joint(self.joint)
    }
}
