//! The lane arithmetic of the wide solvers ([`super::wide_solver`] for the
//! contacts, `super::joints::wide_revolute` for the revolute joints), which
//! work on eight constraints at once: their records hold eight lanes per
//! field ([`F64x8`], 64 bytes aligned to 64, Box2D's `B2_SIMD_WIDTH` 8).
//!
//! [`Lanes`] is that arithmetic as a trait, so the passes are written once
//! and compiled for three register types, one chosen at run time
//! ([`dispatch`]): [`F64x4`] (the `wide` crate's `f64x4`: packed SSE2, the
//! x86-64 baseline every CPU has), [`super::lanes_avx::Avx4`] (one AVX
//! register) and [`super::lanes_avx512::Avx8`] (one AVX-512 register). A
//! value of four lanes covers half a record: the passes visit a record as
//! [`Lanes::GROUPS`] groups of [`Lanes::WIDTH`] lanes, group after group
//! (the lanes of a record are constraints of one colour, independent, so
//! the order does not matter).
//!
//! Each operation is, in every lane, exactly the IEEE operation the scalar
//! solver performs (no fused multiply-add: the scalar code does not fuse,
//! so a fused lane would round differently; no reassociation), so a lane
//! gives the same bits as the scalar code on the same data, whichever type
//! runs; what the lanes buy besides fewer instructions is independent
//! dependency chains, where the scalar solver waits on one.
//!
//! A plain `[f64; 4]` with lane-by-lane loops was tried first: the
//! compiler vectorised only part of it (scalar moves and maxima between
//! packed operations), and the solve pass took more instructions than with
//! `wide`, whose operations are the SSE2 intrinsics themselves.

use super::bodies::SolverBody;
use super::wide_solver::{Bodies, FIXED, INDEX};
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};
use wide::{CmpEq, CmpGt, f64x4};

/// Number of lanes of a record: constraints solved at once.
pub(crate) const LANES: usize = 8;

/// Eight f64 lanes in memory, a field of a solver record (the unit is each
/// use's): two halves of four, 64 bytes aligned to 64, so that a half is
/// an aligned AVX load and the whole an aligned AVX-512 load.
#[derive(Clone, Copy, PartialEq, Default)]
#[repr(C, align(64))]
pub(crate) struct F64x8([F64x4; 2]);

impl std::fmt::Debug for F64x8 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        [0, 1, 2, 3, 4, 5, 6, 7].map(|l| self.lane(l)).fmt(f)
    }
}

impl F64x8 {
    /// Lane `l` (0 to 7; taken modulo 8).
    #[inline(always)]
    pub fn lane(&self, l: usize) -> f64 {
        self.half(l / 4).lane(l % 4)
    }

    /// Sets lane `l` (0 to 7; taken modulo 8) to `x`.
    #[inline(always)]
    pub fn set_lane(&mut self, l: usize, x: f64) {
        self.half_mut(l / 4).set_lane(l % 4, x);
    }

    /// Half `group` (0: lanes 0–3, 1: lanes 4–7; taken modulo 2, which
    /// spares the passes a bounds check per load where their loop over the
    /// groups is not unrolled).
    #[inline(always)]
    pub(crate) fn half(&self, group: usize) -> &F64x4 {
        &self.0[group & 1]
    }

    /// Half `group`, writable (taken modulo 2).
    #[inline(always)]
    pub(crate) fn half_mut(&mut self, group: usize) -> &mut F64x4 {
        &mut self.0[group & 1]
    }
}

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
    pub fn new(a: [f64; 4]) -> Self {
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

    /// The lanes as an array.
    #[inline(always)]
    pub fn to_array(self) -> [f64; 4] {
        self.0.to_array()
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

/// The body indices of group `group` (0 or 1, taken modulo 2) of a
/// record's lanes, for lanes of four.
#[inline(always)]
pub(crate) fn group_of(index: &[u32; LANES], group: usize) -> &[u32; 4] {
    &index.as_chunks::<4>().0[group & 1]
}

/// The record of the body of lane `index` (its flags ignored).
#[inline(always)]
pub(crate) fn body_of(bodies: Bodies<'_>, index: u32) -> &SolverBody {
    // SAFETY: a dynamic body of a lane is written only by this thread
    // (the colouring; the reference is dropped before the scatter), a
    // fixed one by no thread.
    unsafe { bodies.get((index & INDEX) as usize) }
}

/// The lane arithmetic the wide solvers' passes are written in, so that
/// they compile for [`F64x4`] (SSE2, any x86-64 CPU),
/// [`super::lanes_avx::Avx4`] (AVX) and [`super::lanes_avx512::Avx8`]
/// (AVX-512), chosen at run time. Every operation is lane by lane and is
/// the scalar IEEE operation; all implementations give the same bits. The
/// records keep [`F64x8`] in memory; a pass loads the fields of one group
/// of lanes into `Self` and stores them back.
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
    /// Lanes in a value: 4 or 8.
    const WIDTH: usize;
    /// Groups of `WIDTH` lanes in a record: `LANES / WIDTH`.
    const GROUPS: usize = LANES / Self::WIDTH;
    /// A lane-wise condition.
    type Mask: Copy;
    /// Reads group `group` of `x`.
    fn load(x: &F64x8, group: usize) -> Self;
    /// Writes into group `group` of `x`.
    fn store(self, x: &mut F64x8, group: usize);
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// `f` applied to each lane.
    fn map(self, f: impl Fn(f64) -> f64) -> Self;
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

    /// Row `row` of the bodies of group `group` of a record's lanes
    /// (`index`: the record's body indices; [`SolverBody::rows`]),
    /// transposed: `[v.x, v.y, ω, Δp.x]` (row 0) or `[Δp.y, Δθ, cos Δθ,
    /// sin Δθ]` (row 1) of every lane. (Pure data movement: any
    /// implementation gives the same bits.)
    fn gather_row(bodies: Bodies<'_>, index: &[u32; LANES], group: usize, row: usize) -> [Self; 4];

    /// Writes each lane's `v.x`, `v.y`, `ω` (`head[0..3]`) into the body of
    /// that lane of group `group`, lane after lane; `head[3]` is the
    /// lanes' `Δp.x` as gathered, which an implementation may write back
    /// whole rows with. A body met in two lanes is static or kinematic,
    /// whose index carries [`FIXED`]: it is not written back (no lane
    /// changed it).
    fn scatter_head(head: [Self; 4], bodies: Bodies<'_>, index: &[u32; LANES], group: usize);

    /// The inverse masses and inverse inertias (`[m, i]` of
    /// [`super::wide_solver::BodyMasses`]) of the bodies of group `group`
    /// of a record's lanes (`index`: the record's body indices), transposed
    /// into two values. (Pure data movement.)
    fn gather_masses(masses: &[[f64; 2]], index: &[u32; LANES], group: usize) -> [Self; 2];

    /// The lanes of group `group` whose index word (of `index`, a record's
    /// body indices) has `flag` set.
    fn flagged(index: &[u32; LANES], group: usize, flag: u32) -> Self::Mask;
}

impl Lanes for F64x4 {
    const WIDTH: usize = 4;
    type Mask = Mask4;
    #[inline(always)]
    fn load(x: &F64x8, group: usize) -> Self {
        *x.half(group)
    }
    #[inline(always)]
    fn store(self, x: &mut F64x8, group: usize) {
        *x.half_mut(group) = self;
    }
    #[inline(always)]
    fn splat(x: f64) -> Self {
        F64x4::splat(x)
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        F64x4::new(self.to_array().map(f))
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

    #[inline(always)]
    fn gather_row(bodies: Bodies<'_>, index: &[u32; LANES], group: usize, row: usize) -> [Self; 4] {
        let index = group_of(index, group);
        let r = [0, 1, 2, 3].map(|l| &body_of(bodies, index[l]).rows()[row]);
        [0, 1, 2, 3].map(|k| F64x4::new([r[0][k], r[1][k], r[2][k], r[3][k]]))
    }

    #[inline(always)]
    fn scatter_head(head: [Self; 4], bodies: Bodies<'_>, index: &[u32; LANES], group: usize) {
        let [vx, vy, w, _] = head;
        let (vx, vy, w) = (vx.to_array(), vy.to_array(), w.to_array());
        for (l, &i) in group_of(index, group).iter().enumerate() {
            if i & FIXED != 0 {
                continue;
            }
            // SAFETY: a dynamic body of a lane is this thread's alone (the
            // colouring); no reference to it is alive.
            let b = unsafe { bodies.get_mut((i & INDEX) as usize) };
            b.v.x = vx[l];
            b.v.y = vy[l];
            b.w = w[l];
        }
    }

    #[inline(always)]
    fn gather_masses(masses: &[[f64; 2]], index: &[u32; LANES], group: usize) -> [Self; 2] {
        let m = group_of(index, group).map(|i| masses[(i & INDEX) as usize]);
        [F64x4::new(m.map(|x| x[0])), F64x4::new(m.map(|x| x[1]))]
    }

    #[inline(always)]
    fn flagged(index: &[u32; LANES], group: usize, flag: u32) -> Mask4 {
        let set = |i: u32| f64::from_bits(if i & flag != 0 { u64::MAX } else { 0 });
        Mask4(f64x4::new(group_of(index, group).map(set)))
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

/// Runs `$generic::<lane type>(args)` with AVX-512 lanes when the CPU has
/// AVX-512F, with AVX lanes when it has AVX, with SSE2 lanes otherwise;
/// `$avx512` and `$avx` are the instances compiled for those instruction
/// sets. (The wide passes of the contacts, [`super::wide_solver`], and of
/// the revolute joints, `super::joints::wide_revolute`, are written once,
/// generic over [`Lanes`], and dispatched by this.)
macro_rules! dispatch {
    ($generic:ident, $avx512:ident, $avx:ident, ($($arg:ident: $ty:ty),*)) => {
        /// The AVX-512 instance.
        ///
        /// # Safety
        /// The CPU must have AVX-512F.
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx512f")]
        unsafe fn $avx512($($arg: $ty),*) {
            $generic::<$crate::soft_step::lanes_avx512::Avx8>($($arg),*)
        }

        /// The AVX instance.
        ///
        /// # Safety
        /// The CPU must have AVX.
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx")]
        unsafe fn $avx($($arg: $ty),*) {
            $generic::<$crate::soft_step::lanes_avx::Avx4>($($arg),*)
        }

        #[cfg(target_arch = "x86_64")]
        if $crate::soft_step::lanes_avx512::detected() {
            // SAFETY: the CPU has AVX-512F (just checked), which is all
            // `$avx512` requires.
            unsafe { $avx512($($arg),*) };
            return;
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
pub(crate) mod tests {
    use super::*;

    /// Eight lanes as a record field.
    fn record(a: [f64; 8]) -> F64x8 {
        let mut x = F64x8::default();
        for (l, &v) in a.iter().enumerate() {
            x.set_lane(l, v);
        }
        x
    }

    /// Every operation of the lanes `L` against the SSE2 lanes (the type
    /// every x86-64 CPU runs, itself tested against the scalar operations
    /// below) on the same records, bit for bit: signed zeros, equal lanes,
    /// both orders of each comparison; and the transposed gather and
    /// scatter of body records. The caller checks that the CPU runs `L`.
    pub(crate) fn lanes_give_the_bits_of_the_sse2_lanes<L: Lanes>() {
        let x = record([1.5, -2.0, 0.1, -0.0, 3.0, 0.0, -7.25, 1e-300]);
        let y = record([0.5, 4.0, 0.1, 0.0, -3.0, -0.0, 2.0, -1e300]);
        // A divisor without zeros: 0/0's NaN has no defined sign bit (the
        // CPU gives -NaN, a constant-folded one +NaN).
        let z = record([0.5, 4.0, 0.1, 2.0, -3.0, 7.0, 1e-3, 3.0]);
        // `f` on each group of `L`, and on each half in SSE2: same bits.
        let same = |wide: &dyn Fn(L, L, L) -> L, sse: &dyn Fn(F64x4, F64x4, F64x4) -> F64x4| {
            let (mut out, mut expected) = (F64x8::default(), F64x8::default());
            for g in 0..L::GROUPS {
                wide(L::load(&x, g), L::load(&y, g), L::load(&z, g)).store(&mut out, g);
            }
            for g in 0..2 {
                let (a, b, c) = (F64x4::load(&x, g), F64x4::load(&y, g), F64x4::load(&z, g));
                sse(a, b, c).store(&mut expected, g);
            }
            for l in 0..LANES {
                assert_eq!(
                    out.lane(l).to_bits(),
                    expected.lane(l).to_bits(),
                    "lane {l}"
                );
            }
        };
        same(&|a, b, _| a + b, &|a, b, _| a + b);
        same(&|a, b, _| a - b, &|a, b, _| a - b);
        same(&|a, b, _| a * b, &|a, b, _| a * b);
        same(&|a, _, c| a / c, &|a, _, c| a / c);
        same(&|a, _, _| -a, &|a, _, _| -a);
        same(&|a, b, _| a.max(b), &|a, b, _| Lanes::max(a, b));
        same(&|a, b, _| b.max(a), &|a, b, _| Lanes::max(b, a));
        same(&|a, b, _| a.min(b), &|a, b, _| Lanes::min(a, b));
        same(&|a, b, _| b.min(a), &|a, b, _| Lanes::min(b, a));
        same(&|a, b, _| a.clamp(-b.max(-b), b.max(-b)), &|a, b, _| {
            a.clamp(-Lanes::max(b, -b), Lanes::max(b, -b))
        });
        same(&|a, b, _| L::select(a.gt(b), a, b), &|a, b, _| {
            F64x4::select(a.gt(b), a, b)
        });
        same(&|a, b, _| L::select(b.gt(a), a, b), &|a, b, _| {
            F64x4::select(b.gt(a), a, b)
        });
        same(&|a, b, c| L::select(a.eq(b), a, c), &|a, b, c| {
            F64x4::select(a.eq(b), a, c)
        });
        same(
            &|a, b, c| L::select(L::or(a.gt(b), c.eq(b)), a, c),
            &|a, b, c| F64x4::select(F64x4::or(a.gt(b), c.eq(b)), a, c),
        );
        same(&|a, _, _| a.map(|v| 2.0 * v + 1.0), &|a, _, _| {
            a.map(|v| 2.0 * v + 1.0)
        });
        same(&|_, _, _| L::splat(3.0), &|_, _, _| F64x4::splat(3.0));
        let all = |m: &dyn Fn(&F64x8, &F64x8, usize) -> bool, groups: usize| {
            (0..groups).all(|g| m(&x, &y, g))
        };
        for (p, q) in [(&x, &y), (&x, &x)] {
            let wide = (0..L::GROUPS).all(|g| {
                let (a, b) = (L::load(p, g), L::load(q, g));
                L::all(L::or(a.gt(b), b.gt(a)))
            });
            let sse = (0..2).all(|g| {
                let (a, b) = (F64x4::load(p, g), F64x4::load(q, g));
                F64x4::all(F64x4::or(a.gt(b), b.gt(a)))
            });
            assert_eq!(wide, sse);
        }
        assert!(all(
            &|p, _, g| L::all(L::load(p, g).eq(L::load(p, g))),
            L::GROUPS
        ));
        assert!(!all(
            &|p, q, g| L::all(L::load(p, g).eq(L::load(q, g))),
            L::GROUPS
        ));

        // The transposed gather and scatter of body records (ten bodies,
        // the static dummy twice among the lanes, fixed).
        let mut bodies: Vec<SolverBody> = (0..10)
            .map(|i| {
                let f = |k: usize| (8 * i + k) as f64 - 0.5;
                SolverBody {
                    v: nalgebra::Vector2::new(f(0), f(1)),
                    w: f(2),
                    dp: nalgebra::Vector2::new(f(3), f(4)),
                    dtheta: f(5),
                    dq: [f(6), f(7)],
                }
            })
            .collect();
        let index = [3, FIXED, 9, 1, 4, FIXED, 7, 2];
        for row in 0..2 {
            let (mut out, mut expected) = ([F64x8::default(); 4], [F64x8::default(); 4]);
            for g in 0..L::GROUPS {
                let wide = L::gather_row(Bodies::new(&mut bodies), &index, g, row);
                for k in 0..4 {
                    wide[k].store(&mut out[k], g);
                }
            }
            for g in 0..2 {
                let sse = F64x4::gather_row(Bodies::new(&mut bodies), &index, g, row);
                for k in 0..4 {
                    sse[k].store(&mut expected[k], g);
                }
            }
            assert_eq!(out, expected, "row {row}");
        }
        // New velocities for the dynamic bodies, with their Δp.x as
        // gathered: the same bodies after either scatter.
        let lanes = |v: f64| record([v, -v, 10.0 * v, -10.0 * v, 0.5 * v, -0.0, 3.0 * v, -3.0 * v]);
        let head = [1.0, 2.0, 3.0].map(lanes);
        let mut expected = bodies.clone();
        for g in 0..2 {
            let dpx = F64x4::gather_row(Bodies::new(&mut expected), &index, g, 0)[3];
            let h = head.map(|r| F64x4::load(&r, g));
            F64x4::scatter_head(
                [h[0], h[1], h[2], dpx],
                Bodies::new(&mut expected),
                &index,
                g,
            );
        }
        for g in 0..L::GROUPS {
            let dpx = L::gather_row(Bodies::new(&mut bodies), &index, g, 0)[3];
            let h = [
                L::load(&head[0], g),
                L::load(&head[1], g),
                L::load(&head[2], g),
            ];
            L::scatter_head([h[0], h[1], h[2], dpx], Bodies::new(&mut bodies), &index, g);
        }
        assert_eq!(bodies, expected);
        // Body 9 is lane 2: v.x, v.y, ω = 10, 20, 30; body 0 unchanged.
        assert_eq!(
            (bodies[9].v.x, bodies[9].v.y, bodies[9].w),
            (10.0, 20.0, 30.0)
        );
        assert_eq!(bodies[0].v.x, -0.5);
    }

    /// Whether the lane type `path` ("SSE2", "AVX", "AVX-512"; anything
    /// else: the dispatched passes) can run on this CPU; says so when not.
    pub(crate) fn lane_type_runs(path: &str) -> bool {
        let runs = match path {
            "AVX" => crate::soft_step::lanes_avx::detected(),
            "AVX-512" => crate::soft_step::lanes_avx512::detected(),
            _ => true,
        };
        if !runs {
            eprintln!("skipped the {path} lanes: this CPU does not have {path}");
        }
        runs
    }

    #[test]
    fn sse2_lanes_give_their_own_bits() {
        // The comparison's own check: SSE2 against itself must hold.
        lanes_give_the_bits_of_the_sse2_lanes::<F64x4>();
    }

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
