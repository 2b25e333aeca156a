//! Quadratic air drag at the centre of mass (seed §6.2, Table 6.2):
//! `F = −D |v| v` with `D = ρ C A / 2` (kg/m).

use super::{Force, ForceContext, Wrench};
use crate::body::BodyId;
use crate::error::{Result, require_non_negative};

/// Quadratic drag `F = −D |v| v` (N) on one body. The seed's box has
/// D = 1.2 · 0.5 · 0.01 / 2 = 0.003 kg/m.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct QuadraticDrag {
    /// The body.
    pub body: BodyId,
    /// Drag coefficient D (kg/m).
    pub coefficient: f64,
}

impl Force for QuadraticDrag {
    fn builtin(&self) -> Option<super::BuiltinForce> {
        Some(super::BuiltinForce::QuadraticDrag(*self))
    }

    fn name(&self) -> &str {
        "quadratic drag"
    }
    fn bodies(&self) -> Vec<BodyId> {
        vec![self.body]
    }
    fn validate(&self) -> Result<()> {
        require_non_negative("drag coefficient", self.coefficient).map(|_| ())
    }
    fn apply(&self, ctx: &ForceContext<'_>, wrenches: &mut [Wrench]) {
        let v = ctx.states[self.body].velocity;
        wrenches[self.body].force -= self.coefficient * v.norm() * v;
    }
}
