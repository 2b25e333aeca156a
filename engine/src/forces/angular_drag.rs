//! Angular drag (the seed's "friction angulaire", §6.2): a torque
//! `τ = −D ω |ω|` opposing the rotation.

use super::{Force, ForceContext, Wrench};
use crate::body::BodyId;
use crate::error::{Result, require_non_negative};

/// Angular drag torque `−D ω |ω|` (N·m) on one rotating body; D in
/// kg·m²/rad² (N·m·s²). On a particle it does nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AngularDrag {
    /// The body.
    pub body: BodyId,
    /// Coefficient D (N·m·s²).
    pub coefficient: f64,
}

impl Force for AngularDrag {
    fn builtin(&self) -> Option<super::BuiltinForce> {
        Some(super::BuiltinForce::AngularDrag(*self))
    }

    fn name(&self) -> &str {
        "angular drag"
    }
    fn bodies(&self) -> Vec<BodyId> {
        vec![self.body]
    }
    fn validate(&self) -> Result<()> {
        require_non_negative("angular drag coefficient", self.coefficient).map(|_| ())
    }
    fn apply(&self, ctx: &ForceContext<'_>, wrenches: &mut [Wrench]) {
        let w = ctx.states[self.body].angular_velocity;
        wrenches[self.body].torque -= self.coefficient * w * w.abs();
    }
}
