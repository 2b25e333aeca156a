//! The integration stages of each substep: velocities from gravity and
//! the force generators, then positions from velocities (symplectic Euler),
//! on the solver's records of the moving bodies ([`super::bodies`]).

use super::SoftStep;
use super::bodies;
use crate::body::BodyKind;
use crate::forces::{ForceContext, Wrench};
use crate::world_core::WorldCore;
use nalgebra::Vector2;

impl SoftStep {
    /// v += h (g + F/m), ω += h τ/I for every awake dynamic body (with its
    /// gravity scale s and damping rates c, c_ω when a program set them:
    /// v ← v/(1 + h c) + h (s g + F/m), ω ← ω/(1 + h c_ω) + h τ/I); the force
    /// generators (other than uniform fields) see the state at the
    /// substep's start, at time `t_sub`, active as at `middle`.
    #[inline(never)]
    pub(super) fn integrate_velocities(
        &mut self,
        core: &WorldCore,
        h: f64,
        gravity: Vector2<f64>,
        general: Option<(f64, f64)>,
    ) {
        if let Some((t_sub, middle)) = general {
            self.force_states.clone_from(&core.states);
            for (id, sim) in self.sims.iter().enumerate() {
                if sim.moving() {
                    let r = &self.bodies[id + 1];
                    let s = &mut self.force_states[id];
                    s.position += r.dp;
                    s.angle += r.dtheta;
                    s.velocity = r.v;
                    s.angular_velocity = r.w;
                }
            }
            self.wrenches.clear();
            self.wrenches.resize(core.bodies.len(), Wrench::default());
            let ctx = ForceContext {
                t: t_sub,
                bodies: &core.bodies,
                states: &self.force_states,
            };
            for f in &core.forces {
                if f.window.contains(middle) && f.force.uniform_acceleration().is_none() {
                    f.force.apply(&ctx, &mut self.wrenches);
                }
            }
        }
        let controls = core.controls_act.then_some(core.controls.as_slice());
        let wrenches = general.is_some().then_some(self.wrenches.as_slice());
        for (id, sim) in self.sims.iter().enumerate() {
            integrate_velocity(
                id,
                sim,
                &mut self.bodies[id + 1],
                (controls, wrenches),
                h,
                gravity,
            );
        }
    }

    /// x += h v, θ += h ω (symplectic Euler) for every awake moving body.
    #[inline(never)]
    pub(super) fn integrate_positions(&mut self, h: f64) {
        for (sim, r) in self.sims.iter().zip(&mut self.bodies[1..]) {
            integrate_position(sim, r, h);
        }
    }
}

/// The velocity update of body `id` (see
/// [`SoftStep::integrate_velocities`]): nothing unless it is awake and
/// dynamic; `wrenches` when force generators act.
#[inline(always)]
pub(super) fn integrate_velocity(
    id: usize,
    sim: &bodies::BodySim,
    r: &mut bodies::SolverBody,
    (controls, wrenches): (Option<&[crate::world_core::BodyControl]>, Option<&[Wrench]>),
    h: f64,
    gravity: Vector2<f64>,
) {
    if sim.kind != BodyKind::Dynamic || sim.asleep {
        return;
    }
    if let Some(controls) = controls {
        // Box2D's implicit damping, v ← v / (1 + h c), on the velocity
        // before this substep's forces; then the body's share of gravity.
        let c = &controls[id];
        r.v *= 1.0 / (1.0 + h * c.linear_damping);
        r.w *= 1.0 / (1.0 + h * c.angular_damping);
        r.v += h * (c.gravity_scale * gravity);
    } else {
        r.v += h * gravity;
    }
    if let Some(wrenches) = wrenches {
        let w = &wrenches[id];
        r.v += (h * sim.inv_mass) * w.force;
        r.w += h * sim.inv_inertia * w.torque;
    }
}

/// x += h v, θ += h ω for one body, when it is awake and moving.
#[inline(always)]
pub(super) fn integrate_position(sim: &bodies::BodySim, r: &mut bodies::SolverBody, h: f64) {
    if !sim.moving() {
        return;
    }
    r.dp += h * r.v;
    if r.w != 0.0 {
        r.dtheta += h * r.w;
        let (s, c) = bodies::small_sin_cos(r.dtheta);
        r.dq = [c, s];
    }
}
