//! Uniform gravity on every dynamic body (seed §6.2: `F = m g`).

use super::{Force, ForceContext, Wrench};
use crate::body::BodyId;
use crate::error::{Result, require_finite};
use nalgebra::Vector2;

/// Uniform gravitational field `g` (m/s²) acting on every dynamic body.
/// The seed's cases use |g| = 9.80655 m/s² (its value; standard gravity is
/// 9.80665).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Gravity {
    /// Acceleration (m/s²), e.g. `(0, −9.80655)`.
    pub g: Vector2<f64>,
}

impl Force for Gravity {
    fn builtin(&self) -> Option<super::BuiltinForce> {
        Some(super::BuiltinForce::Gravity(*self))
    }

    fn name(&self) -> &str {
        "gravity"
    }
    fn bodies(&self) -> Vec<BodyId> {
        Vec::new()
    }
    fn validate(&self) -> Result<()> {
        require_finite("gravity x", self.g.x)?;
        require_finite("gravity y", self.g.y).map(|_| ())
    }
    fn apply(&self, ctx: &ForceContext<'_>, wrenches: &mut [Wrench]) {
        for (body, w) in ctx.bodies.iter().zip(wrenches.iter_mut()) {
            if body.is_dynamic() {
                w.force += body.mass * self.g;
            }
        }
    }
    fn uniform_acceleration(&self) -> Option<Vector2<f64>> {
        Some(self.g)
    }
    /// `U = −Σ m g·x` (J), zero at the origin.
    fn potential_energy(&self, ctx: &ForceContext<'_>) -> Option<f64> {
        Some(
            ctx.bodies
                .iter()
                .zip(ctx.states)
                .filter(|(b, _)| b.is_dynamic())
                .map(|(b, s)| -b.mass * self.g.dot(&s.position))
                .sum(),
        )
    }
}
