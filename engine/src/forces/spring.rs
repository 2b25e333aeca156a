//! A linear spring (seed §5.2, eq. 5.2: `F = −k ψ`, `ψ = x − l0`), between a
//! fixed anchor and a body or between two bodies.

use super::{Force, ForceContext, Wrench};
use crate::body::{BodyId, BodyState};
use crate::error::{Result, require_finite, require_non_negative};
use crate::shape::cross;
use nalgebra::Vector2;

/// Where a spring end is attached.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Attachment {
    /// A fixed point of the world (m).
    World(Vector2<f64>),
    /// A point of a body, in the body frame (m) relative to its centre of mass.
    Body {
        /// The body.
        body: BodyId,
        /// Attachment point in the body frame (m).
        local_point: Vector2<f64>,
    },
}

impl Attachment {
    /// The centre of mass of `body`.
    pub fn center_of(body: BodyId) -> Self {
        Attachment::Body {
            body,
            local_point: Vector2::zeros(),
        }
    }

    fn world_point(&self, states: &[BodyState]) -> Vector2<f64> {
        match *self {
            Attachment::World(p) => p,
            Attachment::Body { body, local_point } => {
                let s = &states[body];
                s.position + s.to_world_offset(local_point)
            }
        }
    }
}

/// A spring of stiffness `k` (N/m) and rest length `l0` (m) between two
/// attachments.
///
/// - Without an axis (a distance spring), the force on end `b` is
///   `−k (L − l0) d̂` with `d = p_b − p_a`, `L = |d|`; end `a` gets the
///   opposite. At `L = 0` the direction is undefined and the spring exerts no
///   force.
/// - With a unit `axis` u (the seed's one-dimensional spring, §5.2 eq. 5.2:
///   `F = −k ψ`, `ψ = x − l0`), the extension is signed, `ψ = d·u − l0`, and
///   the force on `b` is `−k ψ u`. The seed's mass swings from x = 100 m down
///   to x = 0, the anchor itself: a distance spring would flip its direction
///   there, the axial one is the seed's model.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Spring {
    /// First end.
    pub a: Attachment,
    /// Second end.
    pub b: Attachment,
    /// Stiffness (N/m).
    pub stiffness: f64,
    /// Rest length (m).
    pub rest_length: f64,
    /// Unit direction of a one-dimensional spring; `None` for a distance
    /// spring.
    pub axis: Option<Vector2<f64>>,
}

impl Spring {
    /// The force on end `b` (N) and the extension `ψ` (m).
    fn force_on_b(&self, states: &[BodyState]) -> (Vector2<f64>, f64) {
        let d = self.b.world_point(states) - self.a.world_point(states);
        match self.axis {
            Some(u) => {
                let psi = d.dot(&u) - self.rest_length;
                (-self.stiffness * psi * u, psi)
            }
            None => {
                let length = d.norm();
                let psi = length - self.rest_length;
                if length == 0.0 {
                    (Vector2::zeros(), psi)
                } else {
                    (-self.stiffness * psi / length * d, psi)
                }
            }
        }
    }
}

fn add_at(
    attachment: &Attachment,
    force: Vector2<f64>,
    states: &[BodyState],
    wrenches: &mut [Wrench],
) {
    if let Attachment::Body { body, local_point } = *attachment {
        let r = states[body].to_world_offset(local_point);
        wrenches[body].force += force;
        wrenches[body].torque += cross(r, force);
    }
}

impl Force for Spring {
    fn builtin(&self) -> Option<super::BuiltinForce> {
        Some(super::BuiltinForce::Spring(*self))
    }

    fn name(&self) -> &str {
        "spring"
    }
    fn bodies(&self) -> Vec<BodyId> {
        [self.a, self.b]
            .iter()
            .filter_map(|a| match a {
                Attachment::Body { body, .. } => Some(*body),
                Attachment::World(_) => None,
            })
            .collect()
    }
    fn validate(&self) -> Result<()> {
        require_non_negative("spring stiffness", self.stiffness)?;
        require_non_negative("spring rest length", self.rest_length)?;
        for end in [self.a, self.b] {
            let p = match end {
                Attachment::World(p) => p,
                Attachment::Body { local_point, .. } => local_point,
            };
            require_finite("spring attachment x", p.x)?;
            require_finite("spring attachment y", p.y)?;
        }
        // A unit vector to round-off: |u| − 1 within a few ulps of 1.
        let is_unit = |u: Vector2<f64>| (u.norm() - 1.0).abs() <= 1e-12;
        if let Some(u) = self.axis.filter(|&u| !is_unit(u)) {
            return Err(crate::error::EngineError::InvalidParameter {
                what: "spring axis length".into(),
                value: u.norm(),
                reason: "the axis must be a finite unit vector",
            });
        }
        Ok(())
    }
    fn apply(&self, ctx: &ForceContext<'_>, wrenches: &mut [Wrench]) {
        let (on_b, _) = self.force_on_b(ctx.states);
        add_at(&self.b, on_b, ctx.states, wrenches);
        add_at(&self.a, -on_b, ctx.states, wrenches);
    }
    /// `½ k ψ²` (J).
    fn potential_energy(&self, ctx: &ForceContext<'_>) -> Option<f64> {
        let (_, psi) = self.force_on_b(ctx.states);
        Some(0.5 * self.stiffness * psi * psi)
    }
}
