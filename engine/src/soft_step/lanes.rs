//! Four f64 lanes side by side: the arithmetic of the wide contact solver
//! ([`super::wide_solver`]), which works on four constraints at once.
//!
//! [`F64x4`] wraps the `wide` crate's `f64x4` (packed SSE2 instructions on
//! the x86-64 baseline, two lanes per instruction), with the few
//! operations the solver uses. It is the layout of the solver's records in
//! memory and the arithmetic of every CPU; [`Lanes`] is that arithmetic as
//! a trait, so that the passes also compile for AVX registers
//! ([`super::lanes_avx`]), which the solver uses when the CPU has AVX.
//! Each operation is, in every lane, exactly the IEEE operation the scalar
//! solver performs (no fused multiply-add, no reassociation), so a lane
//! gives the same bits as the scalar code on the same data; what the lanes
//! buy besides fewer instructions is four independent dependency chains,
//! where the scalar solver waits on one.
//!
//! A plain `[f64; 4]` with lane-by-lane loops was tried first: the
//! compiler vectorised only part of it (scalar moves and maxima between
//! packed operations), and the solve pass took more instructions than with
//! `wide`, whose operations are the SSE2 intrinsics themselves.

use super::bodies::SolverBody;
use super::wide_solver::{Bodies, FIXED};
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};
use wide::{CmpEq, CmpGt, f64x4};

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
        self.0.as_array_ref()[l]
    }

    /// Sets lane `l` (0 to 3) to `x`.
    #[inline(always)]
    pub fn set_lane(&mut self, l: usize, x: f64) {
        self.0.as_array_mut()[l] = x;
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

    /// Lanes where `self > other`.
    #[inline(always)]
    pub fn gt(self, other: Self) -> Mask4 {
        Mask4(self.0.cmp_gt(other.0))
    }

    /// Lanes where `self == other`.
    #[inline(always)]
    pub fn eq(self, other: Self) -> Mask4 {
        Mask4(self.0.cmp_eq(other.0))
    }
}

impl Mask4 {
    /// `yes` in the lanes where the condition holds, `no` elsewhere.
    #[inline(always)]
    pub fn select(self, yes: F64x4, no: F64x4) -> F64x4 {
        F64x4(self.0.blend(yes.0, no.0))
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

/// The lane arithmetic the wide solver's passes are written in, so that
/// they compile both for [`F64x4`] (SSE2, any x86-64 CPU) and for
/// [`super::lanes_avx::Avx4`] (AVX, chosen at run time when the CPU has it).
/// Every operation is lane by lane and is the scalar IEEE operation; both
/// implementations give the same bits. The records keep [`F64x4`] in
/// memory; a pass loads its fields into `Self` and stores them back.
pub(crate) trait Lanes:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
{
    /// A lane-wise condition.
    type Mask: Copy;
    /// Reads `x`.
    fn load(x: &F64x4) -> Self;
    /// Writes into `x`.
    fn store(self, x: &mut F64x4);
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// The lanes of `a`.
    fn from_array(a: [f64; LANES]) -> Self;
    /// The lanes as an array.
    fn to_array(self) -> [f64; LANES];
    /// `self > other ? self : other` per lane (x86's `maxpd`).
    fn max(self, other: Self) -> Self;
    /// `self < other ? self : other` per lane (x86's `minpd`).
    fn min(self, other: Self) -> Self;
    /// Lanes where `self > other`.
    fn gt(self, other: Self) -> Self::Mask;
    /// Lanes where `self == other`.
    fn eq(self, other: Self) -> Self::Mask;
    /// `yes` where `mask` holds, `no` elsewhere.
    fn select(mask: Self::Mask, yes: Self, no: Self) -> Self;
    /// Lanes where either condition holds.
    fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Whether the condition holds in every lane.
    fn all(mask: Self::Mask) -> bool;

    /// Each lane clamped to `[lo, hi]` (lo ≤ hi), as `f64::clamp`.
    #[inline(always)]
    fn clamp(self, lo: Self, hi: Self) -> Self {
        self.max(lo).min(hi)
    }

    /// Row `row` of four bodies' records ([`SolverBody::rows`]),
    /// transposed: `[v.x, v.y, ω, Δp.x]` (row 0) or `[Δp.y, Δθ, cos Δθ,
    /// sin Δθ]` (row 1) of every lane, lane `l` from `b[l]`. (Pure data
    /// movement: any implementation gives the same bits.)
    #[inline(always)]
    fn gather_row(b: &[&SolverBody; LANES], row: usize) -> [Self; 4] {
        let r = [0, 1, 2, 3].map(|l| &b[l].rows()[row]);
        [0, 1, 2, 3].map(|k| Self::from_array([r[0][k], r[1][k], r[2][k], r[3][k]]))
    }

    /// Writes each lane's `v.x`, `v.y`, `ω` (`head[0..3]`) into body
    /// `index[l]`, lane after lane; `head[3]` is the lanes' `Δp.x` as
    /// gathered, which an implementation may write back whole rows with. A
    /// body met in two lanes is static or kinematic, whose index carries
    /// [`FIXED`]: it is not written back (no lane changed it).
    #[inline(always)]
    fn scatter_head(head: [Self; 4], bodies: Bodies<'_>, index: &[u32; LANES]) {
        let [vx, vy, w, _] = head;
        let (vx, vy, w) = (vx.to_array(), vy.to_array(), w.to_array());
        for (l, &i) in index.iter().enumerate() {
            if i & FIXED != 0 {
                continue;
            }
            // SAFETY: a dynamic body of a lane is this thread's alone (the
            // colouring); no reference to it is alive.
            let b = unsafe { bodies.get_mut(i as usize) };
            b.v.x = vx[l];
            b.v.y = vy[l];
            b.w = w[l];
        }
    }
}

impl Lanes for F64x4 {
    type Mask = Mask4;
    #[inline(always)]
    fn load(x: &F64x4) -> Self {
        *x
    }
    #[inline(always)]
    fn store(self, x: &mut F64x4) {
        *x = self;
    }
    #[inline(always)]
    fn splat(x: f64) -> Self {
        F64x4::splat(x)
    }
    #[inline(always)]
    fn from_array(a: [f64; LANES]) -> Self {
        F64x4::new(a)
    }
    #[inline(always)]
    fn to_array(self) -> [f64; LANES] {
        self.0.to_array()
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        F64x4::max(self, other)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        F64x4::min(self, other)
    }
    #[inline(always)]
    fn gt(self, other: Self) -> Mask4 {
        F64x4::gt(self, other)
    }
    #[inline(always)]
    fn eq(self, other: Self) -> Mask4 {
        F64x4::eq(self, other)
    }
    #[inline(always)]
    fn select(mask: Mask4, yes: Self, no: Self) -> Self {
        mask.select(yes, no)
    }
    #[inline(always)]
    fn or(a: Mask4, b: Mask4) -> Mask4 {
        a.or(b)
    }
    #[inline(always)]
    fn all(mask: Mask4) -> bool {
        mask.all()
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

impl Div for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn div(self, other: F64x4) -> F64x4 {
        F64x4(self.0 / other.0)
    }
}

impl Neg for F64x4 {
    type Output = F64x4;
    /// Flips the sign bit, as the scalar `-x` (`wide`'s own negation is
    /// 0 − x, which gives +0 for +0).
    #[inline(always)]
    fn neg(self) -> F64x4 {
        F64x4(self.0 ^ f64x4::splat(-0.0))
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

/// Runs `$generic::<lane type>(args)` with AVX lanes when the CPU has AVX,
/// with SSE2 lanes otherwise; `$avx` is the AVX-compiled instance. (The
/// wide passes of the contacts, [`super::wide_solver`], and of the
/// revolute joints, `super::joints::wide_revolute`, are written once,
/// generic over [`Lanes`], and dispatched by this.)
macro_rules! dispatch {
    ($generic:ident, $avx:ident, ($($arg:ident: $ty:ty),*)) => {
        /// The AVX instance.
        ///
        /// # Safety
        /// The CPU must have AVX. (An `unsafe fn`, not a safe one with a
        /// target feature, which needs Rust 1.86: the workspace's minimum
        /// is 1.85.)
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx")]
        unsafe fn $avx($($arg: $ty),*) {
            $generic::<$crate::soft_step::lanes_avx::Avx4>($($arg),*)
        }

        #[cfg(target_arch = "x86_64")]
        if $crate::soft_step::lanes_avx::detected() {
            // SAFETY: the CPU has AVX (just checked), which is all `$avx`
            // requires.
            unsafe { $avx($($arg),*) };
            return;
        }
        $generic::<$crate::soft_step::lanes::F64x4>($($arg),*);
    };
}
pub(crate) use dispatch;

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
            assert_eq!((a / b).lane(i), x / y);
            assert_eq!((-a).lane(i), -x);
            assert_eq!(a.max(b).lane(i), x.max(y));
            assert_eq!(a.min(b).lane(i), x.min(y));
            let hi = y.abs();
            assert_eq!(a.clamp(-b.max(-b), b.max(-b)).lane(i), x.clamp(-hi, hi));
            assert_eq!(a.gt(b).select(a, b).lane(i), if x > y { x } else { y });
        }
        // Negation flips the sign bit, zeros included, as the scalar `-x`.
        assert_eq!((-F64x4::splat(0.0)).lane(0).to_bits(), (-0.0f64).to_bits());
        let mut c = a;
        c.set_lane(2, 7.0);
        assert_eq!(c.lane(2), 7.0);
        assert!(a.eq(a).all() && !a.eq(b).all());
        assert!(a.gt(b).or(b.gt(a)).all());
    }
}
