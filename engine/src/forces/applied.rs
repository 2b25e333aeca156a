//! Applied loads: a constant force at a body point, and a pure torque
//! (seed §6.2, eq. 6.16–6.20: `τ = R × F`).

use super::{Force, ForceContext, Wrench};
use crate::body::BodyId;
use crate::error::{Result, require_finite};
use crate::shape::cross;
use nalgebra::Vector2;

/// A constant world-frame force `F` (N) applied at a point fixed in the
/// body (m, body frame): it pushes the centre of mass and adds the torque
/// `r × F`, where `r` turns with the body.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct PointForce {
    /// The body.
    pub body: BodyId,
    /// Force in the world frame (N).
    pub force: Vector2<f64>,
    /// Application point in the body frame (m), from the centre of mass.
    pub local_point: Vector2<f64>,
}

impl Force for PointForce {
    fn builtin(&self) -> Option<super::BuiltinForce> {
        Some(super::BuiltinForce::PointForce(*self))
    }

    fn name(&self) -> &str {
        "point force"
    }
    fn bodies(&self) -> Vec<BodyId> {
        vec![self.body]
    }
    fn validate(&self) -> Result<()> {
        for (what, v) in [
            ("point force x", self.force.x),
            ("point force y", self.force.y),
            ("point force application x", self.local_point.x),
            ("point force application y", self.local_point.y),
        ] {
            require_finite(what, v)?;
        }
        Ok(())
    }
    fn apply(&self, ctx: &ForceContext<'_>, wrenches: &mut [Wrench]) {
        let r = ctx.states[self.body].to_world_offset(self.local_point);
        wrenches[self.body].force += self.force;
        wrenches[self.body].torque += cross(r, self.force);
    }
}

/// A pure couple τ (N·m), counter-clockwise positive: no net force. The
/// seed's case II uses τ = R × F with R = (0.05, 0.05) m, F = (0.3, 0.4) N,
/// so τ = 0.005 N·m.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Torque {
    /// The body.
    pub body: BodyId,
    /// Torque (N·m).
    pub torque: f64,
}

impl Torque {
    /// The couple `R × F` of a force F (N) at lever arm R (m).
    pub fn from_lever(body: BodyId, lever: Vector2<f64>, force: Vector2<f64>) -> Self {
        Self {
            body,
            torque: cross(lever, force),
        }
    }
}

impl Force for Torque {
    fn builtin(&self) -> Option<super::BuiltinForce> {
        Some(super::BuiltinForce::Torque(*self))
    }

    fn name(&self) -> &str {
        "torque"
    }
    fn bodies(&self) -> Vec<BodyId> {
        vec![self.body]
    }
    fn validate(&self) -> Result<()> {
        require_finite("torque", self.torque).map(|_| ())
    }
    fn apply(&self, _ctx: &ForceContext<'_>, wrenches: &mut [Wrench]) {
        wrenches[self.body].torque += self.torque;
    }
}
