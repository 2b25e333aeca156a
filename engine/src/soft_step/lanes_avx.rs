//! Four f64 lanes in one AVX register, for the wide solver's passes on CPUs
//! that have AVX (checked at run time: the build targets the x86-64
//! baseline, SSE2, so [`super::lanes::F64x4`] is what every CPU runs
//! otherwise).
//!
//! Why: with SSE2 a four-lane value takes two registers and each operation
//! two instructions, and the two-operand SSE2 forms need register copies;
//! AVX does four lanes per instruction in three-operand form. Only plain
//! IEEE adds, subtractions, multiplications, divisions, comparisons, `maxpd`/`minpd`
//! and blends are used (no fused multiply-add), so the results are the
//! same bits as the SSE2 path and the scalar solver: which path runs does
//! not change the simulation.
//!
//! Safety: an [`Avx4`] executes AVX instructions in its operations. Values
//! of it exist only inside the functions of [`super::wide_solver`] and of
//! the revolute joints' wide passes (`super::joints::wide_revolute`) marked
//! `#[target_feature(enable = "avx")]` by [`super::lanes::dispatch`], which
//! are entered only after [`detected`] returned true; that is the
//! invariant every `unsafe` block here relies on. The type is private to
//! the soft step.

use super::lanes::{F64x4, F64x8, LANES, Lanes, body_of, group_of};
use super::wide_solver::{Bodies, FIXED, INDEX};
use std::arch::x86_64::{
    __m256d, _CMP_EQ_OQ, _CMP_GT_OQ, _mm_loadu_pd, _mm256_add_pd, _mm256_blendv_pd,
    _mm256_castpd128_pd256, _mm256_cmp_pd, _mm256_div_pd, _mm256_insertf128_pd, _mm256_load_pd,
    _mm256_loadu_pd, _mm256_max_pd, _mm256_min_pd, _mm256_movemask_pd, _mm256_mul_pd, _mm256_or_pd,
    _mm256_permute2f128_pd, _mm256_set1_pd, _mm256_store_pd, _mm256_storeu_pd, _mm256_sub_pd,
    _mm256_unpackhi_pd, _mm256_unpacklo_pd, _mm256_xor_pd,
};
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// Whether this CPU has AVX (cached by the standard library after the
/// first call).
#[inline]
pub(crate) fn detected() -> bool {
    std::is_x86_feature_detected!("avx")
}

/// Four f64 lanes in an AVX register (see the module's safety note).
#[derive(Clone, Copy)]
pub(crate) struct Avx4(__m256d);

/// A lane-wise condition: all bits set in the lanes where it holds.
#[derive(Clone, Copy)]
pub(crate) struct AvxMask(__m256d);

// `F64x8` is 64 bytes aligned to 64, two halves of four lanes: the
// address of a half is valid for an aligned 256-bit load or store.
const _: () = assert!(
    std::mem::size_of::<F64x8>() == 64 && std::mem::align_of::<F64x8>() == 64 && LANES == 8
);

impl Avx4 {
    /// The lanes of `a`.
    #[inline(always)]
    pub(crate) fn from_array(a: [f64; 4]) -> Self {
        // SAFETY: AVX is available (module invariant); `a` is 32 readable
        // bytes (an unaligned load).
        Avx4(unsafe { _mm256_loadu_pd(a.as_ptr()) })
    }

    /// The lanes as an array.
    #[inline(always)]
    pub(crate) fn to_array(self) -> [f64; 4] {
        let mut a = [0.0; 4];
        // SAFETY: AVX is available (module invariant); `a` is 32 writable
        // bytes (an unaligned store).
        unsafe { _mm256_storeu_pd(a.as_mut_ptr(), self.0) };
        a
    }
}

macro_rules! binary {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for Avx4 {
            type Output = Avx4;
            #[inline(always)]
            fn $method(self, other: Avx4) -> Avx4 {
                // SAFETY: AVX is available (module invariant).
                Avx4(unsafe { $intrinsic(self.0, other.0) })
            }
        }
    };
}

binary!(Add, add, _mm256_add_pd);
binary!(Sub, sub, _mm256_sub_pd);
binary!(Mul, mul, _mm256_mul_pd);
binary!(Div, div, _mm256_div_pd);

impl Neg for Avx4 {
    type Output = Avx4;
    /// Flips the sign bit, as the scalar `-x`.
    #[inline(always)]
    fn neg(self) -> Avx4 {
        // SAFETY: AVX is available (module invariant).
        Avx4(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
    }
}

impl AddAssign for Avx4 {
    #[inline(always)]
    fn add_assign(&mut self, other: Avx4) {
        *self = *self + other;
    }
}

impl SubAssign for Avx4 {
    #[inline(always)]
    fn sub_assign(&mut self, other: Avx4) {
        *self = *self - other;
    }
}

impl Lanes for Avx4 {
    const WIDTH: usize = 4;
    type Mask = AvxMask;

    #[inline(always)]
    fn load(x: &F64x8, group: usize) -> Self {
        // SAFETY: AVX is available (module invariant); the half is 32
        // readable bytes aligned to 32 (checked above).
        Avx4(unsafe { _mm256_load_pd((x.half(group) as *const F64x4).cast::<f64>()) })
    }

    #[inline(always)]
    fn store(self, x: &mut F64x8, group: usize) {
        // SAFETY: as `load`, for 32 writable bytes.
        unsafe { _mm256_store_pd((x.half_mut(group) as *mut F64x4).cast::<f64>(), self.0) }
    }

    #[inline(always)]
    fn splat(x: f64) -> Self {
        // SAFETY: AVX is available (module invariant).
        Avx4(unsafe { _mm256_set1_pd(x) })
    }

    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        Avx4::from_array(self.to_array().map(f))
    }

    #[inline(always)]
    fn max(self, other: Self) -> Self {
        // SAFETY: AVX is available (module invariant).
        Avx4(unsafe { _mm256_max_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn min(self, other: Self) -> Self {
        // SAFETY: AVX is available (module invariant).
        Avx4(unsafe { _mm256_min_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn gt(self, other: Self) -> AvxMask {
        // SAFETY: AVX is available (module invariant).
        AvxMask(unsafe { _mm256_cmp_pd::<_CMP_GT_OQ>(self.0, other.0) })
    }

    #[inline(always)]
    fn eq(self, other: Self) -> AvxMask {
        // SAFETY: AVX is available (module invariant).
        AvxMask(unsafe { _mm256_cmp_pd::<_CMP_EQ_OQ>(self.0, other.0) })
    }

    #[inline(always)]
    fn select(mask: AvxMask, yes: Self, no: Self) -> Self {
        // SAFETY: AVX is available (module invariant).
        Avx4(unsafe { _mm256_blendv_pd(no.0, yes.0, mask.0) })
    }

    #[inline(always)]
    fn or(a: AvxMask, b: AvxMask) -> AvxMask {
        // SAFETY: AVX is available (module invariant).
        AvxMask(unsafe { _mm256_or_pd(a.0, b.0) })
    }

    #[inline(always)]
    fn all(mask: AvxMask) -> bool {
        // SAFETY: AVX is available (module invariant).
        unsafe { _mm256_movemask_pd(mask.0) == 0b1111 }
    }

    /// Four aligned 32-byte loads and a 4 × 4 transpose (eight shuffles),
    /// instead of sixteen scalar loads and inserts.
    #[inline(always)]
    fn gather_row(bodies: Bodies<'_>, index: &[u32; LANES], group: usize, row: usize) -> [Self; 4] {
        let load = |l: usize| -> __m256d {
            let b = body_of(bodies, group_of(index, group)[l]);
            // SAFETY: AVX is available (module invariant); the row is 32
            // readable bytes of a `SolverBody`, aligned to 32 (its rows
            // start at 0 and 32 of a 64-aligned record).
            unsafe { _mm256_load_pd(b.rows()[row].as_ptr()) }
        };
        transpose([load(0), load(1), load(2), load(3)]).map(Avx4)
    }

    /// The 4 × 4 transpose back to rows and four aligned 32-byte stores of
    /// `[v.x, v.y, ω, Δp.x]` (`Δp.x` as gathered: unchanged).
    #[inline(always)]
    fn scatter_head(head: [Self; 4], bodies: Bodies<'_>, index: &[u32; LANES], group: usize) {
        let rows = transpose(head.map(|x| x.0));
        for (l, &i) in group_of(index, group).iter().enumerate() {
            if i & FIXED != 0 {
                continue;
            }
            // SAFETY: a dynamic body of a lane is this thread's alone (the
            // colouring); no reference to it is alive.
            let row = unsafe { bodies.get_mut((i & INDEX) as usize) }.head_mut();
            // SAFETY: AVX is available (module invariant); `row` is 32
            // writable bytes aligned to 32 (the start of a 64-aligned
            // record).
            unsafe { _mm256_store_pd(row.as_mut_ptr(), rows[l]) };
        }
    }

    /// Four 16-byte loads, paired and unpacked.
    #[inline(always)]
    fn gather_masses(masses: &[[f64; 2]], index: &[u32; LANES], group: usize) -> [Self; 2] {
        let index = group_of(index, group);
        let at = |l: usize| masses[(index[l] & INDEX) as usize].as_ptr();
        // SAFETY: AVX is available (module invariant); each pointer is 16
        // readable bytes (unaligned loads).
        unsafe {
            // [m0, i0, m2, i2] and [m1, i1, m3, i3].
            let even = _mm256_insertf128_pd::<1>(
                _mm256_castpd128_pd256(_mm_loadu_pd(at(0))),
                _mm_loadu_pd(at(2)),
            );
            let odd = _mm256_insertf128_pd::<1>(
                _mm256_castpd128_pd256(_mm_loadu_pd(at(1))),
                _mm_loadu_pd(at(3)),
            );
            [
                Avx4(_mm256_unpacklo_pd(even, odd)),
                Avx4(_mm256_unpackhi_pd(even, odd)),
            ]
        }
    }

    #[inline(always)]
    fn flagged(index: &[u32; LANES], group: usize, flag: u32) -> AvxMask {
        let set = |i: u32| f64::from_bits(if i & flag != 0 { u64::MAX } else { 0 });
        // SAFETY: AVX is available (module invariant); the array is 32
        // readable bytes (an unaligned load).
        AvxMask(unsafe { _mm256_loadu_pd(group_of(index, group).map(set).as_ptr()) })
    }
}

/// The 4 × 4 transpose of `m` (rows to columns).
#[inline(always)]
fn transpose(m: [__m256d; 4]) -> [__m256d; 4] {
    // SAFETY: AVX is available (module invariant); shuffles only.
    unsafe {
        // (m0[0], m1[0], m0[2], m1[2]), (m0[1], m1[1], m0[3], m1[3]), ...
        let t0 = _mm256_unpacklo_pd(m[0], m[1]);
        let t1 = _mm256_unpackhi_pd(m[0], m[1]);
        let t2 = _mm256_unpacklo_pd(m[2], m[3]);
        let t3 = _mm256_unpackhi_pd(m[2], m[3]);
        [
            _mm256_permute2f128_pd::<0x20>(t0, t2),
            _mm256_permute2f128_pd::<0x20>(t1, t3),
            _mm256_permute2f128_pd::<0x31>(t0, t2),
            _mm256_permute2f128_pd::<0x31>(t1, t3),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn avx_lanes_give_the_bits_of_the_sse2_lanes() {
        if !detected() {
            eprintln!("skipped: this CPU has no AVX, the AVX lanes cannot run");
            return;
        }
        // The CPU has AVX (checked above): Avx4 values may exist.
        crate::soft_step::lanes::tests::lanes_give_the_bits_of_the_sse2_lanes::<Avx4>();
    }
}
