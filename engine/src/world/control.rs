//! Driving a world from a program between steps (Box2D's `b2Body_*`
//! calls): poses and velocities, forces and impulses, a kinematic body's
//! target, its kind, enabling, gravity scale, damping, locked rotation,
//! mass properties and the program's own values.
//!
//! Every call checks all its input first (finite numbers, a body that
//! exists and was not removed, a kind that can take it, what the contact
//! model supports) and changes nothing when it refuses: the world after an
//! error is the world before the call. The exact model supports the pose,
//! velocity, force, impulse, kind (dynamic and static), enabling, mass and
//! user-value calls; it refuses gravity scales, damping and a locked
//! rotation on a body with a shape with [`EngineError::Unsupported`]
//! naming it (its right-hand side has no term for them), and kinematic
//! bodies as it always did.

use super::Dynamics;
use super::World;
use crate::body::{Body, BodyId, BodyKind, chain_on_moving_body};
use crate::error::{EngineError, Result, require_finite, require_non_negative, require_positive};
use crate::forces::{Force, ForceContext, Wrench};
use crate::soft_step::joints::JointId;
use nalgebra::Vector2;

/// Why the exact model refuses a gravity scale, damping or a locked
/// rotation.
const EXACT_HAS_NO_CONTROL: &str = "the exact contact model integrates Newton-Euler with the \
     world's forces only (no per-body gravity scale, damping or locked rotation of a shape); \
     use the soft_step contact model, or a force (QuadraticDrag, AngularDrag, Gravity)";

/// The forces and torques applied with [`World::apply_force`] and
/// [`World::apply_torque`], acting during the next step only.
#[derive(Debug)]
pub(super) struct AppliedWrenches(pub Vec<Wrench>);

impl Force for AppliedWrenches {
    fn name(&self) -> &str {
        "forces applied for one step"
    }

    fn bodies(&self) -> Vec<BodyId> {
        Vec::new()
    }

    fn apply(&self, _ctx: &ForceContext<'_>, wrenches: &mut [Wrench]) {
        for (w, a) in wrenches.iter_mut().zip(&self.0) {
            w.force += a.force;
            w.torque += a.torque;
        }
    }
}

/// `(x, y)` of `v`, checked finite, for a message naming `what`.
fn require_finite_vector(what: &str, v: Vector2<f64>) -> Result<()> {
    require_finite(format!("{what} x"), v.x)?;
    require_finite(format!("{what} y"), v.y)?;
    Ok(())
}

/// The 2D cross product r × f (the torque of `f` applied at `r`).
fn cross(r: Vector2<f64>, f: Vector2<f64>) -> f64 {
    r.x * f.y - r.y * f.x
}

impl World {
    /// Body `id`, checked to exist and not to be removed.
    fn live_body(&self, id: BodyId) -> Result<&Body> {
        self.check_body(id)?;
        let body = &self.core.bodies[id];
        if self.core.removed[id] {
            return Err(EngineError::RemovedBody {
                index: id,
                name: body.name.clone(),
            });
        }
        Ok(body)
    }

    /// Body `id`, live and enabled, for a call described by `what`.
    fn enabled_body(&self, id: BodyId, what: &str) -> Result<&Body> {
        let body = self.live_body(id)?;
        if self.core.controls[id].disabled.is_some() {
            return Err(EngineError::Unsupported {
                what: format!("{what} of disabled body '{}'", body.name),
                reason: "a disabled body takes no part in the simulation: enable it first \
                         (World::set_enabled)",
            });
        }
        Ok(body)
    }

    /// Body `id`, live, enabled and dynamic, for a call described by
    /// `what`.
    fn dynamic_body(&self, id: BodyId, what: &str) -> Result<&Body> {
        let body = self.enabled_body(id, what)?;
        if !body.is_dynamic() {
            return Err(EngineError::Unsupported {
                what: format!("{what} of {} body '{}'", kind_name(body.kind), body.name),
                reason: "only a dynamic body responds to forces and impulses; change its \
                         kind first (World::set_body_kind)",
            });
        }
        Ok(body)
    }

    /// Refuses what the exact model cannot do.
    fn refuse_under_exact(&self, what: impl FnOnce() -> String) -> Result<()> {
        match self.model {
            Dynamics::Exact(_) => Err(EngineError::Unsupported {
                what: what(),
                reason: EXACT_HAS_NO_CONTROL,
            }),
            Dynamics::SoftStep(_) => Ok(()),
        }
    }

    /// Refuses leaving the soft step while some body's control needs it.
    pub(super) fn refuse_controls_leaving_soft_step(&self) -> Result<()> {
        for (id, c) in self.core.controls.iter().enumerate() {
            let body = &self.core.bodies[id];
            let locked_shape = c.fixed_rotation && body.shape.is_some();
            if c.acts() || locked_shape {
                return Err(EngineError::Unsupported {
                    what: format!(
                        "the exact contact model with body '{}' (gravity scale {}, damping {} \
                         and {} 1/s, rotation locked: {})",
                        body.name,
                        c.gravity_scale,
                        c.linear_damping,
                        c.angular_damping,
                        c.fixed_rotation
                    ),
                    reason: EXACT_HAS_NO_CONTROL,
                });
            }
        }
        Ok(())
    }

    /// Moves body `id` to `position` (m, its centre of mass) at `angle`
    /// (rad), at once (a teleport: nothing in between is swept), and wakes
    /// it and the bodies it touches. Its velocity is kept. Any kind of
    /// body; a particle keeps its angle.
    pub fn set_pose(&mut self, id: BodyId, position: Vector2<f64>, angle: f64) -> Result<()> {
        let body = self.enabled_body(id, "the pose")?;
        let name = format!("position of body '{}'", body.name);
        require_finite_vector(&name, position)?;
        require_finite(format!("angle of body '{}'", body.name), angle)?;
        let rotates = body.inertia.is_some() || body.shape.is_some();
        let state = &mut self.core.states[id];
        state.position = position;
        if rotates {
            state.angle = angle;
        }
        self.model.pose_changed(&self.core, id);
        Ok(())
    }

    /// Sets body `id`'s velocity (m/s, of its centre of mass) and angular
    /// velocity (rad/s), and wakes it. A dynamic or kinematic body (a
    /// kinematic one keeps it until changed); a body that does not rotate
    /// (a particle, or its rotation locked) takes angular velocity 0 only.
    pub fn set_velocity(
        &mut self,
        id: BodyId,
        velocity: Vector2<f64>,
        angular_velocity: f64,
    ) -> Result<()> {
        let body = self.enabled_body(id, "the velocity")?;
        require_finite_vector(&format!("velocity of body '{}'", body.name), velocity)?;
        require_finite(
            format!("angular velocity of body '{}'", body.name),
            angular_velocity,
        )?;
        if body.kind == BodyKind::Static {
            return Err(EngineError::Unsupported {
                what: format!("a velocity of static body '{}'", body.name),
                reason: "a static body never moves; make it kinematic or dynamic first \
                         (World::set_body_kind)",
            });
        }
        if body.is_dynamic() && body.inertia.is_none() && angular_velocity != 0.0 {
            return Err(EngineError::InvalidParameter {
                what: format!("angular velocity of body '{}'", body.name),
                value: angular_velocity,
                reason: "the body does not rotate (a particle, or its rotation is locked)",
            });
        }
        self.write_velocity(id, velocity, angular_velocity);
        Ok(())
    }

    /// Applies `force` (N) at the world point `point` (m) on dynamic body
    /// `id` during the next step only (the next [`World::step`] or
    /// [`World::step_to`]), as Box2D's `b2Body_ApplyForce`: calls add up,
    /// the sum acts through the whole step and is then cleared. Off the
    /// centre of mass it also gives the torque r × F (a body that does not
    /// rotate takes the force only). Wakes the body.
    pub fn apply_force(
        &mut self,
        id: BodyId,
        force: Vector2<f64>,
        point: Vector2<f64>,
    ) -> Result<()> {
        let body = self.dynamic_body(id, "a force")?;
        require_finite_vector(&format!("force on body '{}'", body.name), force)?;
        require_finite_vector(
            &format!("point of the force on body '{}'", body.name),
            point,
        )?;
        let torque = if body.inertia.is_some() {
            cross(point - self.core.states[id].position, force)
        } else {
            0.0
        };
        self.accumulate(id, Wrench { force, torque })
    }

    /// Applies `torque` (N·m, counter-clockwise) on dynamic body `id`
    /// during the next step only, as [`World::apply_force`]. The body must
    /// rotate.
    pub fn apply_torque(&mut self, id: BodyId, torque: f64) -> Result<()> {
        let body = self.dynamic_body(id, "a torque")?;
        require_finite(format!("torque on body '{}'", body.name), torque)?;
        if body.inertia.is_none() {
            return Err(EngineError::InvalidParameter {
                what: format!("torque on body '{}'", body.name),
                value: torque,
                reason: "the body does not rotate (a particle, or its rotation is locked)",
            });
        }
        let force = Vector2::zeros();
        self.accumulate(id, Wrench { force, torque })
    }

    fn accumulate(&mut self, id: BodyId, wrench: Wrench) -> Result<()> {
        let n = self.core.bodies.len();
        let applied = &mut self.core.applied;
        if applied.len() < n {
            applied.resize(n, Wrench::default());
        }
        let sum = Wrench {
            force: applied[id].force + wrench.force,
            torque: applied[id].torque + wrench.torque,
        };
        if !(sum.force.x.is_finite() && sum.force.y.is_finite() && sum.torque.is_finite()) {
            return Err(EngineError::InvalidParameter {
                what: format!(
                    "sum of the forces applied on body '{}'",
                    self.core.bodies[id].name
                ),
                value: sum.force.norm() + sum.torque.abs(),
                reason: "must be finite",
            });
        }
        applied[id] = sum;
        self.model.wake(id);
        Ok(())
    }

    /// Applies the impulse `impulse` (N·s) at the world point `point` (m)
    /// on dynamic body `id` now: v += J/m and, if it rotates,
    /// ω += (r × J)/I. Wakes the body.
    pub fn apply_linear_impulse(
        &mut self,
        id: BodyId,
        impulse: Vector2<f64>,
        point: Vector2<f64>,
    ) -> Result<()> {
        let body = self.dynamic_body(id, "an impulse")?;
        require_finite_vector(&format!("impulse on body '{}'", body.name), impulse)?;
        require_finite_vector(
            &format!("point of the impulse on body '{}'", body.name),
            point,
        )?;
        let state = self.core.states[id];
        let velocity = state.velocity + impulse / body.mass;
        let angular_velocity = match body.inertia {
            Some(i) => state.angular_velocity + cross(point - state.position, impulse) / i,
            None => state.angular_velocity,
        };
        self.kick(id, velocity, angular_velocity)
    }

    /// Applies the angular impulse `impulse` (N·m·s) on dynamic body `id`
    /// now: ω += L/I. The body must rotate. Wakes it.
    pub fn apply_angular_impulse(&mut self, id: BodyId, impulse: f64) -> Result<()> {
        let body = self.dynamic_body(id, "an angular impulse")?;
        require_finite(format!("angular impulse on body '{}'", body.name), impulse)?;
        let Some(inertia) = body.inertia else {
            return Err(EngineError::InvalidParameter {
                what: format!("angular impulse on body '{}'", body.name),
                value: impulse,
                reason: "the body does not rotate (a particle, or its rotation is locked)",
            });
        };
        let state = self.core.states[id];
        self.kick(
            id,
            state.velocity,
            state.angular_velocity + impulse / inertia,
        )
    }

    /// Sets a kicked body's velocities, refusing a non-finite result.
    fn kick(&mut self, id: BodyId, velocity: Vector2<f64>, angular_velocity: f64) -> Result<()> {
        let name = &self.core.bodies[id].name;
        require_finite_vector(
            &format!("velocity of body '{name}' after the impulse"),
            velocity,
        )?;
        require_finite(
            format!("angular velocity of body '{name}' after the impulse"),
            angular_velocity,
        )?;
        self.write_velocity(id, velocity, angular_velocity);
        Ok(())
    }

    /// Sets body `id`'s velocity (m/s) and angular velocity (rad/s),
    /// already validated, and tells the contact model (which wakes it).
    fn write_velocity(&mut self, id: BodyId, velocity: Vector2<f64>, angular_velocity: f64) {
        let state = &mut self.core.states[id];
        state.velocity = velocity;
        state.angular_velocity = angular_velocity;
        self.model.velocity_changed(id);
    }

    /// Gives kinematic body `id` the velocity that brings it to `position`
    /// (m) and `angle` (rad) in `dt` (s), Box2D's
    /// `b2Body_SetTargetTransform`: v = (target − x)/dt, ω = (angle −
    /// θ)/dt; a step of `dt` then ends there (to the round-off of the
    /// substeps' sum). The body keeps that velocity afterwards until it is
    /// set again (call this before every step to follow a path). Wakes
    /// it. Kinematic bodies only (the soft-step contact model).
    pub fn set_target_pose(
        &mut self,
        id: BodyId,
        position: Vector2<f64>,
        angle: f64,
        dt: f64,
    ) -> Result<()> {
        let body = self.enabled_body(id, "a target pose")?;
        require_finite_vector(
            &format!("target position of body '{}'", body.name),
            position,
        )?;
        require_finite(format!("target angle of body '{}'", body.name), angle)?;
        require_positive(format!("time to the target of body '{}'", body.name), dt)?;
        if body.kind != BodyKind::Kinematic {
            return Err(EngineError::Unsupported {
                what: format!(
                    "a target pose of {} body '{}'",
                    kind_name(body.kind),
                    body.name
                ),
                reason: "a target pose drives a kinematic body; make it kinematic first \
                         (World::set_body_kind), or set a dynamic body's pose or velocity",
            });
        }
        let state = self.core.states[id];
        let velocity = (position - state.position) / dt;
        let angular_velocity = (angle - state.angle) / dt;
        let name = &body.name;
        require_finite_vector(
            &format!("velocity to the target of body '{name}'"),
            velocity,
        )?;
        require_finite(
            format!("angular velocity to the target of body '{name}'"),
            angular_velocity,
        )?;
        self.write_velocity(id, velocity, angular_velocity);
        Ok(())
    }

    /// Changes body `id`'s kind. Static → its velocity is zeroed; dynamic
    /// → it takes its mass and inertia as a dynamic body (from its
    /// definition, or [`World::set_mass_properties`]; a body created
    /// static or kinematic without them is refused) and starts at rest
    /// from static, at its velocity from kinematic; kinematic → it keeps
    /// its velocity. Its contacts end and are found again at the next step;
    /// it and the bodies it touched or is jointed to wake. Refused when a
    /// joint would be left without a dynamic body, and for kinematic under
    /// the exact model.
    pub fn set_body_kind(&mut self, id: BodyId, kind: BodyKind) -> Result<()> {
        let body = self.enabled_body(id, "the kind")?;
        if body.kind == kind {
            return Ok(());
        }
        if let Some(crate::shape::Shape::Chain(_)) = &body.shape {
            return Err(chain_on_moving_body(&body.name));
        }
        let control = &self.core.controls[id];
        let mut changed = body.clone();
        changed.kind = kind;
        if kind == BodyKind::Dynamic {
            let Some((mass, inertia)) = control.dynamic_mass else {
                return Err(EngineError::InvalidParameter {
                    what: format!("mass of body '{}'", body.name),
                    value: f64::NAN,
                    reason: "a body created static or kinematic has no mass: give it one with \
                             World::set_mass_properties before making it dynamic",
                });
            };
            changed.mass = mass;
            changed.inertia = if control.fixed_rotation {
                None
            } else {
                inertia
            };
        } else {
            changed.mass = f64::INFINITY;
            changed.inertia = Some(f64::INFINITY);
        }
        self.model.check_body(&changed)?;
        if changed.inertia.is_none() && changed.shape.is_some() {
            self.refuse_under_exact(|| {
                format!(
                    "making body '{}' with its rotation locked dynamic",
                    body.name
                )
            })?;
        }
        self.check_joints_keep_a_dynamic_body(id, kind, "changing the kind of")?;
        let state = &mut self.core.states[id];
        let from = self.core.bodies[id].kind;
        if kind == BodyKind::Static || from == BodyKind::Static {
            state.velocity = Vector2::zeros();
            state.angular_velocity = 0.0;
        }
        if changed.is_dynamic() && changed.inertia.is_none() {
            state.angular_velocity = 0.0;
        }
        self.core.bodies[id] = changed;
        self.model.body_changed(&self.core, id);
        Ok(())
    }

    /// Refuses a change that would leave a joint of body `id` (now of kind
    /// `kind`) with no dynamic body.
    fn check_joints_keep_a_dynamic_body(
        &self,
        id: BodyId,
        kind: BodyKind,
        what: &str,
    ) -> Result<()> {
        if kind == BodyKind::Dynamic {
            return Ok(());
        }
        for (joint, other) in self.model.joints_of(id) {
            let other_dynamic = other.is_some_and(|b| self.core.bodies[b].is_dynamic());
            if !other_dynamic {
                let joint = self.model.joint(&self.core, joint)?;
                return Err(EngineError::Unsupported {
                    what: format!(
                        "{what} body '{}' while joint '{}' holds it to no other dynamic body",
                        self.core.bodies[id].name, joint.name
                    ),
                    reason: "a joint needs a dynamic body; remove the joint first \
                             (World::remove_joint)",
                });
            }
        }
        Ok(())
    }

    /// Enables or disables body `id` (Box2D's `b2Body_Enable` and
    /// `b2Body_Disable`). A disabled body takes no part in the simulation:
    /// it is neither moved nor collided (its contacts end), forces leave
    /// it alone, and [`World::bodies`] shows it as an inert static body
    /// without a shape at its pose until it is enabled again with its
    /// kind, shape, mass and velocity. A body held by a joint cannot be
    /// disabled (remove the joint first). Doing it twice does nothing.
    pub fn set_enabled(&mut self, id: BodyId, enabled: bool) -> Result<()> {
        let body = self.live_body(id)?.clone();
        let disabled = &self.core.controls[id].disabled;
        if disabled.is_none() == enabled {
            return Ok(());
        }
        if enabled {
            let (stored, velocity, angular_velocity) = disabled.clone().expect("disabled");
            self.model.check_body(&stored)?;
            self.core.bodies[id] = stored;
            let state = &mut self.core.states[id];
            state.velocity = velocity;
            state.angular_velocity = angular_velocity;
            self.core.controls[id].disabled = None;
        } else {
            if let Some((joint, _)) = self.model.joints_of(id).first() {
                let joint = self.model.joint(&self.core, *joint)?;
                return Err(EngineError::Unsupported {
                    what: format!(
                        "disabling body '{}' held by joint '{}'",
                        body.name, joint.name
                    ),
                    reason: "a disabled body takes no part in the simulation; remove its \
                             joints first (World::remove_joint)",
                });
            }
            let inert = Body {
                kind: BodyKind::Static,
                mass: f64::INFINITY,
                inertia: Some(f64::INFINITY),
                shape: None,
                ..body.clone()
            };
            let state = &mut self.core.states[id];
            let stored = (body.clone(), state.velocity, state.angular_velocity);
            state.velocity = Vector2::zeros();
            state.angular_velocity = 0.0;
            self.core.controls[id].disabled = Some(stored);
            self.core.bodies[id] = inert;
        }
        self.model.body_changed(&self.core, id);
        Ok(())
    }

    /// Whether body `id` is enabled (it exists and is not disabled).
    pub fn is_enabled(&self, id: BodyId) -> bool {
        self.core
            .controls
            .get(id)
            .is_some_and(|c| c.disabled.is_none())
    }

    /// Scales the world's uniform gravity for body `id` by `scale` (any
    /// finite number; 0 floats, −1 falls up; 1 by default), Box2D's
    /// `b2Body_SetGravityScale`. The soft step only: the exact model
    /// refuses a scale other than 1. [`World::energy`] counts the gravity
    /// potential unscaled.
    pub fn set_gravity_scale(&mut self, id: BodyId, scale: f64) -> Result<()> {
        let body = self.live_body(id)?;
        require_finite(format!("gravity scale of body '{}'", body.name), scale)?;
        if scale != 1.0 {
            self.refuse_under_exact(|| format!("a gravity scale of body '{}'", body.name))?;
        }
        self.core.controls[id].gravity_scale = scale;
        self.controls_changed(id);
        Ok(())
    }

    /// Body `id`'s gravity scale.
    pub fn gravity_scale(&self, id: BodyId) -> Result<f64> {
        self.check_body(id)?;
        Ok(self.core.controls[id].gravity_scale)
    }

    /// Damps body `id`'s velocity at `linear` (1/s) and its angular
    /// velocity at `angular` (1/s), both ≥ 0 (0 by default), in Box2D's
    /// implicit form: every substep of length h, before the forces act,
    /// v ← v / (1 + h·c) and ω ← ω / (1 + h·c_ω) (stable for any rate;
    /// for small h·c the velocity decays as e^(−c t)). Dynamic bodies only
    /// feel it; the soft step only (the exact model refuses rates other
    /// than 0).
    pub fn set_damping(&mut self, id: BodyId, linear: f64, angular: f64) -> Result<()> {
        let body = self.live_body(id)?;
        require_non_negative(format!("linear damping of body '{}'", body.name), linear)?;
        require_non_negative(format!("angular damping of body '{}'", body.name), angular)?;
        if linear != 0.0 || angular != 0.0 {
            self.refuse_under_exact(|| format!("damping of body '{}'", body.name))?;
        }
        let control = &mut self.core.controls[id];
        control.linear_damping = linear;
        control.angular_damping = angular;
        self.controls_changed(id);
        Ok(())
    }

    /// Body `id`'s linear and angular damping rates (1/s).
    pub fn damping(&self, id: BodyId) -> Result<(f64, f64)> {
        self.check_body(id)?;
        let c = &self.core.controls[id];
        Ok((c.linear_damping, c.angular_damping))
    }

    fn controls_changed(&mut self, id: BodyId) {
        self.core.controls_act = self.core.controls.iter().any(|c| c.acts());
        self.model.velocity_changed(id);
    }

    /// Locks (or frees) body `id`'s rotation, Box2D's
    /// `b2Body_SetFixedRotation`: a locked dynamic body keeps its angle,
    /// its angular velocity is zeroed and nothing turns it (its inertia
    /// reads `None`); freed, it takes its inertia back. On a static or
    /// kinematic body the lock waits until it is made dynamic. The exact
    /// model refuses locking a body with a shape.
    pub fn set_fixed_rotation(&mut self, id: BodyId, fixed: bool) -> Result<()> {
        let body = self.enabled_body(id, "locking the rotation")?.clone();
        if self.core.controls[id].fixed_rotation == fixed {
            return Ok(());
        }
        if fixed && body.shape.is_some() {
            self.refuse_under_exact(|| format!("locking the rotation of body '{}'", body.name))?;
        }
        let control = &mut self.core.controls[id];
        control.fixed_rotation = fixed;
        if !body.is_dynamic() {
            return Ok(());
        }
        let inertia = control.dynamic_mass.and_then(|(_, i)| i);
        self.core.bodies[id].inertia = if fixed { None } else { inertia };
        if fixed {
            self.core.states[id].angular_velocity = 0.0;
        }
        self.model.body_changed(&self.core, id);
        Ok(())
    }

    /// Whether body `id`'s rotation is locked.
    pub fn has_fixed_rotation(&self, id: BodyId) -> Result<bool> {
        self.check_body(id)?;
        Ok(self.core.controls[id].fixed_rotation)
    }

    /// Makes body `id` a bullet (or not), Box2D's `b2Body_SetBullet`
    /// ([`crate::BodyDef::bullet`]): under the soft step a fast dynamic
    /// bullet is also swept against the other dynamic bodies' end poses.
    /// Kept on a static or kinematic body for when it is made dynamic;
    /// accepted and without effect under the exact model, whose swept
    /// contact search already covers every pair. Refused (typed error,
    /// world unchanged) for an unknown, removed or disabled body.
    pub fn set_bullet(&mut self, id: BodyId, bullet: bool) -> Result<()> {
        self.enabled_body(id, "the bullet flag")?;
        if self.core.bodies[id].bullet == bullet {
            return Ok(());
        }
        self.core.bodies[id].bullet = bullet;
        self.model.bullet_changed(&self.core, id);
        Ok(())
    }

    /// Whether body `id` is a bullet ([`World::set_bullet`]).
    pub fn is_bullet(&self, id: BodyId) -> Result<bool> {
        self.check_body(id)?;
        let c = &self.core.controls[id];
        Ok(c.disabled
            .as_ref()
            .map_or(self.core.bodies[id].bullet, |(body, _, _)| body.bullet))
    }

    /// Replaces body `id`'s mass (kg, > 0) and moment of inertia about its
    /// centre of mass (kg·m², > 0; `None` only for a body without a shape:
    /// a particle, with no rotation), Box2D's `b2Body_SetMassData` (the
    /// centre of mass stays the body's position, its shape's centroid).
    /// Its velocity is kept (not its momentum). On a static or kinematic
    /// body they are kept for when it is made dynamic.
    pub fn set_mass_properties(
        &mut self,
        id: BodyId,
        mass: f64,
        inertia: Option<f64>,
    ) -> Result<()> {
        let body = self.enabled_body(id, "the mass properties")?.clone();
        require_positive(format!("mass of body '{}'", body.name), mass)?;
        if let Some(i) = inertia {
            require_positive(format!("inertia of body '{}'", body.name), i)?;
        } else if body.shape.is_some() {
            return Err(EngineError::InvalidParameter {
                what: format!("inertia of body '{}'", body.name),
                value: f64::NAN,
                reason: "a body with a shape needs an inertia (lock its rotation with \
                         World::set_fixed_rotation instead)",
            });
        }
        let control = &mut self.core.controls[id];
        control.dynamic_mass = Some((mass, inertia));
        if !body.is_dynamic() {
            return Ok(());
        }
        let fixed = control.fixed_rotation;
        let b = &mut self.core.bodies[id];
        b.mass = mass;
        b.inertia = if fixed { None } else { inertia };
        if b.inertia.is_none() {
            self.core.states[id].angular_velocity = 0.0;
        }
        self.model.body_changed(&self.core, id);
        Ok(())
    }

    /// Attaches the program's own value to body `id` (0 by default), e.g.
    /// an index into its own tables; the engine never reads it.
    pub fn set_user_value(&mut self, id: BodyId, value: u64) -> Result<()> {
        self.check_body(id)?;
        self.core.controls[id].user_value = value;
        Ok(())
    }

    /// Body `id`'s user value.
    pub fn user_value(&self, id: BodyId) -> Result<u64> {
        self.check_body(id)?;
        Ok(self.core.controls[id].user_value)
    }

    /// Attaches the program's own value to joint `id` (0 by default).
    pub fn set_joint_user_value(&mut self, id: JointId, value: u64) -> Result<()> {
        self.model.joint(&self.core, id)?;
        let values = &mut self.core.joint_user_values;
        if values.len() <= id {
            values.resize(id + 1, 0);
        }
        values[id] = value;
        Ok(())
    }

    /// Joint `id`'s user value.
    pub fn joint_user_value(&self, id: JointId) -> Result<u64> {
        self.model.joint(&self.core, id)?;
        Ok(self.core.joint_user_values.get(id).copied().unwrap_or(0))
    }
}

/// "dynamic", "static" or "kinematic".
fn kind_name(kind: BodyKind) -> &'static str {
    match kind {
        BodyKind::Dynamic => "dynamic",
        BodyKind::Static => "static",
        BodyKind::Kinematic => "kinematic",
    }
}
