//! Four f64 lanes side by side: the arithmetic of the wide contact solver
//! ([`super::wide_solver`]), which works on four constraints at once.
//!
//! [`F64x4`] wraps the `wide` crate's `f64x4` (packed SSE2 instructions on
//! the x86-64 baseline, two lanes per instruction; one AVX instruction when
//! the build enables AVX), with the few operations the solver uses. Each
//! operation is, in every lane, exactly the IEEE operation the scalar
//! solver performs (no fused multiply-add, no reassociation), so a lane
//! gives the same bits as the scalar code on the same data; what the lanes
//! buy besides fewer instructions is four independent dependency chains,
//! where the scalar solver waits on one.
//!
//! A plain `[f64; 4]` with lane-by-lane loops was tried first: the
//! compiler vectorised only part of it (scalar moves and maxima between
//! packed operations), and the solve pass took more instructions than with
//! `wide`, whose operations are the SSE2 intrinsics themselves.

use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};
use wide::f64x4;

/// Number of lanes: constraints solved at once.
pub(crate) const LANES: usize = 4;

/// Four f64 lanes (the unit is each use's).
#[derive(Clone, Copy, PartialEq, Default)]
pub(crate) struct F64x4(f64x4);

/// A lane-wise condition, from a comparison of two [`F64x4`] (all bits set
/// in a lane where it holds).
#[derive(Clone, Copy, PartialEq)]
pub(crate) struct Mask4(f64x4);

impl std::fmt::Debug for F64x4 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.to_array().fmt(f)
    }
}

impl std::fmt::Debug for Mask4 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.to_array().map(|m| m.to_bits() != 0).fmt(f)
    }
}

impl F64x4 {
    /// Every lane zero.
    pub const ZERO: F64x4 = F64x4(f64x4::ZERO);

    /// The lanes of `a`.
    #[inline(always)]
    pub fn new(a: [f64; LANES]) -> Self {
        F64x4(f64x4::new(a))
    }

    /// `x` in every lane.
    #[inline(always)]
    pub fn splat(x: f64) -> Self {
        F64x4(f64x4::splat(x))
    }

    /// Lane `l` (0 to 3).
    #[inline(always)]
    pub fn lane(&self, l: usize) -> f64 {
        self.0.as_array()[l]
    }

    /// Sets lane `l` (0 to 3) to `x`.
    #[inline(always)]
    pub fn set_lane(&mut self, l: usize, x: f64) {
        self.0.as_mut_array()[l] = x;
    }

    /// The larger of each pair of lanes: `self > other ? self : other`
    /// (x86's `maxpd`; the solver's values are finite).
    #[inline(always)]
    pub fn max(self, other: Self) -> Self {
        F64x4(self.0.fast_max(other.0))
    }

    /// The smaller of each pair of lanes: `self < other ? self : other`.
    #[inline(always)]
    pub fn min(self, other: Self) -> Self {
        F64x4(self.0.fast_min(other.0))
    }

    /// Each lane clamped to `[lo, hi]` (lo ≤ hi), as `f64::clamp`.
    #[inline(always)]
    pub fn clamp(self, lo: Self, hi: Self) -> Self {
        self.max(lo).min(hi)
    }

    /// Lanes where `self > other`.
    #[inline(always)]
    pub fn gt(self, other: Self) -> Mask4 {
        Mask4(self.0.simd_gt(other.0))
    }

    /// Lanes where `self == other`.
    #[inline(always)]
    pub fn eq(self, other: Self) -> Mask4 {
        Mask4(self.0.simd_eq(other.0))
    }
}

impl Mask4 {
    /// `yes` in the lanes where the condition holds, `no` elsewhere.
    #[inline(always)]
    pub fn select(self, yes: F64x4, no: F64x4) -> F64x4 {
        F64x4(self.0.bitselect(yes.0, no.0))
    }

    /// Lanes where either condition holds.
    #[inline(always)]
    pub fn or(self, other: Mask4) -> Mask4 {
        Mask4(self.0 | other.0)
    }

    /// Whether the condition holds in every lane.
    #[inline(always)]
    pub fn all(self) -> bool {
        self.0.all()
    }
}

impl Add for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn add(self, other: F64x4) -> F64x4 {
        F64x4(self.0 + other.0)
    }
}

impl Sub for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn sub(self, other: F64x4) -> F64x4 {
        F64x4(self.0 - other.0)
    }
}

impl Mul for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn mul(self, other: F64x4) -> F64x4 {
        F64x4(self.0 * other.0)
    }
}

impl Neg for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn neg(self) -> F64x4 {
        F64x4(-self.0)
    }
}

impl AddAssign for F64x4 {
    #[inline(always)]
    fn add_assign(&mut self, other: F64x4) {
        *self = *self + other;
    }
}

impl SubAssign for F64x4 {
    #[inline(always)]
    fn sub_assign(&mut self, other: F64x4) {
        *self = *self - other;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_are_the_scalar_operations() {
        let a = F64x4::new([1.5, -2.0, 0.1, 3.0]);
        let b = F64x4::new([0.5, 4.0, 0.2, -1.0]);
        for i in 0..4 {
            let (x, y) = (a.lane(i), b.lane(i));
            assert_eq!((a + b).lane(i), x + y);
            assert_eq!((a - b).lane(i), x - y);
            assert_eq!((a * b).lane(i), x * y);
            assert_eq!((-a).lane(i), -x);
            assert_eq!(a.max(b).lane(i), x.max(y));
            assert_eq!(a.min(b).lane(i), x.min(y));
            let hi = y.abs();
            assert_eq!(a.clamp(-b.max(-b), b.max(-b)).lane(i), x.clamp(-hi, hi));
            assert_eq!(a.gt(b).select(a, b).lane(i), if x > y { x } else { y });
        }
        let mut c = a;
        c.set_lane(2, 7.0);
        assert_eq!(c.lane(2), 7.0);
        assert!(a.eq(a).all() && !a.eq(b).all());
        assert!(a.gt(b).or(b.gt(a)).all());
    }
}
