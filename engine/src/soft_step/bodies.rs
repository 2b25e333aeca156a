//! The bodies as the soft step's substeps see them: velocities and the
//! motion since the step began, in one compact record per body that the
//! contact solver reads and writes, and the per-body constants (inverse
//! mass and inertia, shape, extents) that it only reads.
//!
//! Solver index 0 is a body that never moves (zero velocity, infinite
//! mass): every contact with a static body points there, so the solver
//! needs no branch for them. The body with world id `i` has solver index
//! `i + 1`.

use super::geometry::Collider;
use crate::body::{Body, BodyKind, BodyState};
use nalgebra::{UnitComplex, Vector2};
use std::ops::Range;

/// A body's velocity and its motion since the start of the step: what one
/// substep reads and writes (64 bytes, one cache line: its eight f64 in
/// this order, which the wide passes load as two rows of four,
/// [`SolverBody::rows`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct SolverBody {
    /// Linear velocity of the centre of mass (m/s).
    pub v: Vector2<f64>,
    /// Angular velocity (rad/s).
    pub w: f64,
    /// Displacement of the centre of mass since the step began (m).
    pub dp: Vector2<f64>,
    /// Rotation since the step began (rad).
    pub dtheta: f64,
    /// cos and sin of `dtheta`.
    pub dq: [f64; 2],
}

// The layout `rows` relies on: eight f64 without padding (a `Vector2<f64>`
// is nalgebra's `repr(C)` matrix over a `repr(transparent)` `[[f64; 2];
// 1]`: x then y).
const _: () = {
    use std::mem::{offset_of, size_of};
    assert!(size_of::<SolverBody>() == 64);
    assert!(offset_of!(SolverBody, v) == 0 && size_of::<Vector2<f64>>() == 16);
    assert!(offset_of!(SolverBody, w) == 16);
    assert!(offset_of!(SolverBody, dp) == 24);
    assert!(offset_of!(SolverBody, dtheta) == 40);
    assert!(offset_of!(SolverBody, dq) == 48);
};

impl SolverBody {
    /// A body at rest that has not moved.
    pub const AT_REST: SolverBody = SolverBody {
        v: Vector2::new(0.0, 0.0),
        w: 0.0,
        dp: Vector2::new(0.0, 0.0),
        dtheta: 0.0,
        dq: [1.0, 0.0],
    };

    /// `r` turned by this body's rotation since the step began.
    #[inline(always)]
    pub fn rotate(&self, r: Vector2<f64>) -> Vector2<f64> {
        let [c, s] = self.dq;
        Vector2::new(c * r.x - s * r.y, s * r.x + c * r.y)
    }

    /// The record as two rows of four f64: `[v.x, v.y, ω, Δp.x]` and
    /// `[Δp.y, Δθ, cos Δθ, sin Δθ]`.
    #[inline(always)]
    pub fn rows(&self) -> &[[f64; 4]; 2] {
        // SAFETY: `SolverBody` is `repr(C)`, eight f64 at offsets 0 to 56
        // without padding (asserted above), so it is a valid `[[f64; 4];
        // 2]`, whose alignment (8) is below its own (64).
        unsafe { &*(self as *const SolverBody).cast::<[[f64; 4]; 2]>() }
    }

    /// The first row of [`SolverBody::rows`], `[v.x, v.y, ω, Δp.x]`, to
    /// write.
    #[inline(always)]
    pub fn head_mut(&mut self) -> &mut [f64; 4] {
        // SAFETY: as `rows`; the first 32 bytes are `v`, `w` and `dp.x`,
        // f64 for which any bits are valid.
        unsafe { &mut *(self as *mut SolverBody).cast::<[f64; 4]>() }
    }
}

use crate::tunables::SMALL_ANGLE;

/// (sin x, cos x), x in rad: the Taylor polynomials for |x| ≤ 1/4 (a
/// body's rotation since the step began is almost always that small),
/// `f64::sin_cos` beyond.
///
/// Error bound for |x| ≤ 1/4: the truncation remainders are at most
/// |x|¹³/13! ≤ 2.4e-18 for the sine (up to x¹¹; relative to sin x at most
/// (1/4)¹²/13! · (x/sin x) ≤ 1.0e-17, a tenth of a half-ulp) and
/// |x|¹⁴/14! ≤ 4.3e-20 for the cosine (up to x¹²); Horner's evaluation,
/// whose terms shrink by x²/((2k)(2k+1)) ≤ 1/96, adds about one rounding of
/// the result. So both are within about 1 ulp of the exact values (0.58
/// ulp for the sine and 0.53 for the cosine at most, measured on 20 000
/// points of [0, 1/4] against 120-bit values), like libm's (tested against
/// it). About a fifth of the cost of `sin_cos`.
#[inline]
pub(crate) fn small_sin_cos(x: f64) -> (f64, f64) {
    if x.abs() > SMALL_ANGLE {
        return x.sin_cos();
    }
    let x2 = x * x;
    // sin x = x − x³/3! + … − x¹¹/11!, cos x = 1 − x²/2! + … + x¹²/12!,
    // both by Horner's rule in x².
    let s = x + x
        * x2
        * (-1.0 / 6.0
            + x2 * (1.0 / 120.0
                + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362_880.0 + x2 * (-1.0 / 39_916_800.0)))));
    let c = 1.0
        + x2 * (-0.5
            + x2 * (1.0 / 24.0
                + x2 * (-1.0 / 720.0
                    + x2 * (1.0 / 40_320.0
                        + x2 * (-1.0 / 3_628_800.0 + x2 * (1.0 / 479_001_600.0))))));
    (s, c)
}

/// What the prepare stage reads of a body, copied from its [`BodySim`]
/// at the start of each step into a compact array (24 bytes a body instead
/// of the whole record), since prepare reads two bodies per contact in no
/// particular order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BodyMass {
    /// 1/m (1/kg); 0 for static and kinematic bodies.
    pub inv_mass: f64,
    /// 1/I (1/(kg·m²)).
    pub inv_inertia: f64,
    pub kind: BodyKind,
    /// Whether the solver moves it ([`BodySim::moving`]).
    pub moving: bool,
    /// Its word in a wide record's lane ([`super::wide_solver::lane_index`]
    /// of its solver index): computed once per body and step rather than
    /// twice per constraint; its solver index is `lane &`
    /// [`super::wide_solver::INDEX`].
    pub lane: u32,
}

impl BodyMass {
    /// The prepare stage's view of `sim`, whose lane word is `lane`.
    pub(crate) fn of(sim: &BodySim, lane: u32) -> Self {
        BodyMass {
            inv_mass: sim.inv_mass,
            inv_inertia: sim.inv_inertia,
            kind: sim.kind,
            moving: sim.moving(),
            lane,
        }
    }
}

/// What the soft step keeps about a body besides its velocity.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct BodySim {
    pub kind: BodyKind,
    /// 1/m (1/kg); 0 for static and kinematic bodies.
    pub inv_mass: f64,
    /// 1/I (1/(kg·m²)); 0 for static, kinematic and non-rotating bodies.
    pub inv_inertia: f64,
    /// Its colliders (indices into the model's collider list); empty
    /// without a shape.
    pub colliders: Range<usize>,
    /// Largest distance from the centre of mass to a point of its shapes
    /// (m).
    pub max_extent: f64,
    /// Smallest distance from the centre of a shape to its boundary (m):
    /// moving less than a fraction of it, the body cannot jump over a
    /// thin wall.
    pub min_extent: f64,
    /// Its rotation at the end of the last step (cos θ, sin θ).
    pub rotation: UnitComplex<f64>,
    /// Whether the body sleeps (its island is at rest).
    pub asleep: bool,
    /// Whether it is a dynamic bullet ([`Body::bullet`]): its sweep waits
    /// for the other bodies' end poses (`bullets.rs`).
    pub bullet: bool,
    /// How long (s) the body has been slower than the sleep threshold.
    pub sleep_time: f64,
}

impl BodySim {
    /// The solver's view of `body` at angle `angle` (rad), whose colliders
    /// are `colliders` (at indices `range`).
    pub(crate) fn new(
        body: &Body,
        angle: f64,
        (colliders, range): (&[Collider], Range<usize>),
    ) -> Self {
        let max_extent = colliders
            .iter()
            .map(|c| c.offset.map_or(0.0, |o| o.translation.vector.norm()) + c.max_extent)
            .fold(0.0, f64::max);
        let min_extent = colliders
            .iter()
            .map(|c| c.shape.min_extent())
            .fold(f64::INFINITY, f64::min);
        let min_extent = if min_extent.is_finite() {
            min_extent
        } else {
            0.0
        };
        let dynamic = body.kind == BodyKind::Dynamic;
        Self {
            kind: body.kind,
            inv_mass: if dynamic { 1.0 / body.mass } else { 0.0 },
            inv_inertia: match (dynamic, body.inertia) {
                (true, Some(i)) => 1.0 / i,
                _ => 0.0,
            },
            colliders: range,
            max_extent,
            min_extent,
            rotation: UnitComplex::new(angle),
            asleep: false,
            bullet: dynamic && body.bullet,
            sleep_time: 0.0,
        }
    }

    /// Whether the solver moves this body (dynamic or kinematic, awake).
    pub(crate) fn moving(&self) -> bool {
        self.kind != BodyKind::Static && !self.asleep
    }
}

/// The solver index of world body `id` of kind `kind`: 0 for a static one.
pub(crate) fn solver_index(id: usize, kind: BodyKind) -> usize {
    if kind == BodyKind::Static { 0 } else { id + 1 }
}

/// The solver record of a body whose state is `s`.
pub(crate) fn solver_body(s: &BodyState, kind: BodyKind) -> SolverBody {
    if kind == BodyKind::Static {
        return SolverBody::AT_REST;
    }
    SolverBody {
        v: s.velocity,
        w: s.angular_velocity,
        ..SolverBody::AT_REST
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_solver_body_reads_as_its_fields_in_order() {
        let mut b = SolverBody {
            v: Vector2::new(1.0, 2.0),
            w: 3.0,
            dp: Vector2::new(4.0, 5.0),
            dtheta: 6.0,
            dq: [7.0, 8.0],
        };
        assert_eq!(b.rows(), &[[1.0, 2.0, 3.0, 4.0], [5.0, 6.0, 7.0, 8.0]]);
        *b.head_mut() = [-1.0, -2.0, -3.0, -4.0];
        assert_eq!((b.v, b.w, b.dp.x), (Vector2::new(-1.0, -2.0), -3.0, -4.0));
        assert_eq!((b.dp.y, b.dtheta, b.dq), (5.0, 6.0, [7.0, 8.0]));
    }

    #[test]
    fn the_small_angle_sine_and_cosine_agree_with_libm_to_round_off() {
        // Both are within about 1 ulp of the exact value (see
        // small_sin_cos), so they differ by at most about 2 ulp: 2 × 2⁻⁵²
        // relative, 4.5e-16; the bound allows 3 ulp.
        let ulp3 = 3.0 * f64::EPSILON;
        for k in -2000..=2000 {
            let x = SMALL_ANGLE * k as f64 / 2000.0 * 1.001;
            let (s, c) = small_sin_cos(x);
            let (s0, c0) = x.sin_cos();
            assert!((s - s0).abs() <= ulp3 * s0.abs(), "sin {x}: {s} vs {s0}");
            assert!((c - c0).abs() <= ulp3 * c0.abs(), "cos {x}: {c} vs {c0}");
        }
        assert_eq!(small_sin_cos(0.0), (0.0, 1.0));
    }
}
