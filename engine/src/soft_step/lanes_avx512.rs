//! Eight f64 lanes in one AVX-512 register: a whole record of the wide
//! solvers at once, for their passes on CPUs that have AVX-512F (checked
//! at run time, like AVX: [`super::lanes::dispatch`]).
//!
//! Why: a record ([`super::lanes::F64x8`]) is eight constraints of one
//! colour; with AVX the passes visit it as two groups of four, with
//! AVX-512 as one group of eight, so each operation is one instruction
//! for eight lanes, and the 32 registers hold a pass's values without
//! spilling. Only plain IEEE adds, subtractions, multiplications,
//! divisions, comparisons, `vmaxpd`/`vminpd` (the same rule as `maxpd`:
//! the second operand when the lanes compare unordered or equal) and
//! blends are used; no fused multiply-add (the scalar solver does not
//! fuse: a fused lane would round once where the scalar code rounds
//! twice). So the results are the bits of the AVX and SSE2 paths and of
//! the scalar solver: which path runs does not change the simulation
//! (tested below and in the solvers' tests).
//!
//! Safety: an [`Avx8`] executes AVX-512F instructions in its operations.
//! Values of it exist only inside the functions that
//! [`super::lanes::dispatch`] marks `#[target_feature(enable =
//! "avx512f")]`, entered only after [`detected`] returned true, and in
//! tests after that check; that is the invariant every `unsafe` block here
//! relies on. The type is private to the soft step.

use super::lanes::{F64x8, LANES, Lanes, body_of};
use super::wide_solver::{Bodies, FIXED, INDEX};
use std::arch::x86_64::{
    __m256i, __m512d, __m512i, __mmask8, _CMP_EQ_OQ, _CMP_GT_OQ, _mm_loadu_pd,
    _mm256_castpd128_pd256, _mm256_insertf128_pd, _mm256_load_pd, _mm256_loadu_si256,
    _mm256_store_pd, _mm512_add_pd, _mm512_castpd_si512, _mm512_castpd256_pd512,
    _mm512_castpd512_pd256, _mm512_castsi256_si512, _mm512_castsi512_pd, _mm512_cmp_pd_mask,
    _mm512_div_pd, _mm512_extractf64x4_pd, _mm512_insertf64x4, _mm512_load_pd, _mm512_loadu_pd,
    _mm512_mask_blend_pd, _mm512_max_pd, _mm512_min_pd, _mm512_mul_pd, _mm512_permutex2var_pd,
    _mm512_set1_epi32, _mm512_set1_epi64, _mm512_set1_pd, _mm512_setr_epi64, _mm512_store_pd,
    _mm512_storeu_pd, _mm512_sub_pd, _mm512_test_epi32_mask, _mm512_unpackhi_pd,
    _mm512_unpacklo_pd, _mm512_xor_si512,
};
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// Whether this CPU has AVX-512F (cached by the standard library after
/// the first call).
#[inline]
pub(crate) fn detected() -> bool {
    std::is_x86_feature_detected!("avx512f")
}

/// Eight f64 lanes in an AVX-512 register (see the module's safety note).
#[derive(Clone, Copy)]
pub(crate) struct Avx8(__m512d);

// `F64x8` is 64 bytes aligned to 64: its address is valid for an aligned
// 512-bit load or store.
const _: () = assert!(
    std::mem::size_of::<F64x8>() == 64 && std::mem::align_of::<F64x8>() == 64 && LANES == 8
);

impl Avx8 {
    /// The lanes of `a`.
    #[inline(always)]
    pub(crate) fn from_array(a: [f64; 8]) -> Self {
        // SAFETY: AVX-512F is available (module invariant); `a` is 64
        // readable bytes (an unaligned load).
        Avx8(unsafe { _mm512_loadu_pd(a.as_ptr()) })
    }

    /// The lanes as an array.
    #[inline(always)]
    pub(crate) fn to_array(self) -> [f64; 8] {
        let mut a = [0.0; 8];
        // SAFETY: AVX-512F is available (module invariant); `a` is 64
        // writable bytes (an unaligned store).
        unsafe { _mm512_storeu_pd(a.as_mut_ptr(), self.0) };
        a
    }
}

macro_rules! binary {
    ($trait:ident, $method:ident, $intrinsic:ident) => {
        impl $trait for Avx8 {
            type Output = Avx8;
            #[inline(always)]
            fn $method(self, other: Avx8) -> Avx8 {
                // SAFETY: AVX-512F is available (module invariant).
                Avx8(unsafe { $intrinsic(self.0, other.0) })
            }
        }
    };
}

binary!(Add, add, _mm512_add_pd);
binary!(Sub, sub, _mm512_sub_pd);
binary!(Mul, mul, _mm512_mul_pd);
binary!(Div, div, _mm512_div_pd);

impl Neg for Avx8 {
    type Output = Avx8;
    /// Flips the sign bit, as the scalar `-x` (an integer xor: the
    /// floating-point `vxorpd` of 512 bits is AVX-512DQ).
    #[inline(always)]
    fn neg(self) -> Avx8 {
        // SAFETY: AVX-512F is available (module invariant).
        Avx8(unsafe {
            let sign: __m512i = _mm512_set1_epi64(i64::MIN);
            _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(self.0), sign))
        })
    }
}

impl AddAssign for Avx8 {
    #[inline(always)]
    fn add_assign(&mut self, other: Avx8) {
        *self = *self + other;
    }
}

impl SubAssign for Avx8 {
    #[inline(always)]
    fn sub_assign(&mut self, other: Avx8) {
        *self = *self - other;
    }
}

impl Lanes for Avx8 {
    const WIDTH: usize = 8;
    type Mask = __mmask8;

    #[inline(always)]
    fn load(x: &F64x8, _group: usize) -> Self {
        // SAFETY: AVX-512F is available (module invariant); `x` is 64
        // readable bytes aligned to 64 (checked above).
        Avx8(unsafe { _mm512_load_pd((x as *const F64x8).cast::<f64>()) })
    }

    #[inline(always)]
    fn store(self, x: &mut F64x8, _group: usize) {
        // SAFETY: as `load`, for 64 writable bytes.
        unsafe { _mm512_store_pd((x as *mut F64x8).cast::<f64>(), self.0) }
    }

    #[inline(always)]
    fn splat(x: f64) -> Self {
        // SAFETY: AVX-512F is available (module invariant).
        Avx8(unsafe { _mm512_set1_pd(x) })
    }

    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        Avx8::from_array(self.to_array().map(f))
    }

    #[inline(always)]
    fn max(self, other: Self) -> Self {
        // SAFETY: AVX-512F is available (module invariant).
        Avx8(unsafe { _mm512_max_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn min(self, other: Self) -> Self {
        // SAFETY: AVX-512F is available (module invariant).
        Avx8(unsafe { _mm512_min_pd(self.0, other.0) })
    }

    #[inline(always)]
    fn gt(self, other: Self) -> __mmask8 {
        // SAFETY: AVX-512F is available (module invariant).
        unsafe { _mm512_cmp_pd_mask::<_CMP_GT_OQ>(self.0, other.0) }
    }

    #[inline(always)]
    fn eq(self, other: Self) -> __mmask8 {
        // SAFETY: AVX-512F is available (module invariant).
        unsafe { _mm512_cmp_pd_mask::<_CMP_EQ_OQ>(self.0, other.0) }
    }

    #[inline(always)]
    fn select(mask: __mmask8, yes: Self, no: Self) -> Self {
        // SAFETY: AVX-512F is available (module invariant); the blend
        // takes its second operand where the mask bit is set.
        Avx8(unsafe { _mm512_mask_blend_pd(mask, no.0, yes.0) })
    }

    #[inline(always)]
    fn or(a: __mmask8, b: __mmask8) -> __mmask8 {
        a | b
    }

    #[inline(always)]
    fn all(mask: __mmask8) -> bool {
        mask == 0xff
    }

    /// Eight aligned 32-byte loads, paired into four registers (bodies l
    /// and l + 4), and an 8 × 4 transpose: four in-lane unpacks and four
    /// two-source permutes, instead of 32 scalar loads and inserts.
    #[inline(always)]
    fn gather_row(
        bodies: Bodies<'_>,
        index: &[u32; LANES],
        _group: usize,
        row: usize,
    ) -> [Self; 4] {
        // The row of the body of lane `l`: 32 readable bytes of a
        // `SolverBody`, aligned to 32 (its rows start at 0 and 32 of a
        // 64-aligned record). (A closure of pointers: one returning AVX
        // values was not inlined into the AVX-512 passes, a call per load.)
        let at = |l: usize| body_of(bodies, index[l]).rows()[row].as_ptr();
        // SAFETY: AVX-512F (so AVX) is available (module invariant); each
        // row is as said above.
        let [m0, m1, m2, m3] = unsafe {
            [
                _mm512_insertf64x4::<1>(
                    _mm512_castpd256_pd512(_mm256_load_pd(at(0))),
                    _mm256_load_pd(at(4)),
                ),
                _mm512_insertf64x4::<1>(
                    _mm512_castpd256_pd512(_mm256_load_pd(at(1))),
                    _mm256_load_pd(at(5)),
                ),
                _mm512_insertf64x4::<1>(
                    _mm512_castpd256_pd512(_mm256_load_pd(at(2))),
                    _mm256_load_pd(at(6)),
                ),
                _mm512_insertf64x4::<1>(
                    _mm512_castpd256_pd512(_mm256_load_pd(at(3))),
                    _mm256_load_pd(at(7)),
                ),
            ]
        };
        let [f0, f1, f2, f3] = transpose([m0, m1, m2, m3]);
        [Avx8(f0), Avx8(f1), Avx8(f2), Avx8(f3)]
    }

    /// The transpose back to rows (bodies l and l + 4 in register l) and
    /// eight aligned 32-byte stores of `[v.x, v.y, ω, Δp.x]` (`Δp.x` as
    /// gathered: unchanged).
    #[inline(always)]
    fn scatter_head(head: [Self; 4], bodies: Bodies<'_>, index: &[u32; LANES], _group: usize) {
        let [vx, vy, w, dpx] = head;
        let rows = transpose([vx.0, vy.0, w.0, dpx.0]);
        for (l, &i) in index.iter().enumerate() {
            if i & FIXED != 0 {
                continue;
            }
            // SAFETY: AVX-512F is available (module invariant); shuffles
            // only.
            let half = unsafe {
                if l < 4 {
                    _mm512_castpd512_pd256(rows[l])
                } else {
                    _mm512_extractf64x4_pd::<1>(rows[l - 4])
                }
            };
            // SAFETY: a dynamic body of a lane is this thread's alone (the
            // colouring); no reference to it is alive.
            let row = unsafe { bodies.get_mut((i & INDEX) as usize) }.head_mut();
            // SAFETY: AVX is available (AVX-512F implies it); `row` is 32
            // writable bytes aligned to 32 (the start of a 64-aligned
            // record).
            unsafe { _mm256_store_pd(row.as_mut_ptr(), half) };
        }
    }

    /// Eight 16-byte loads, paired into two registers and unpacked.
    #[inline(always)]
    fn gather_masses(masses: &[[f64; 2]], index: &[u32; LANES], _group: usize) -> [Self; 2] {
        let at = |l: usize| masses[(index[l] & INDEX) as usize].as_ptr();
        // SAFETY: AVX-512F (so AVX) is available (module invariant); each
        // pointer is 16 readable bytes (unaligned loads).
        unsafe {
            let pair = |l: usize, k: usize| {
                _mm256_insertf128_pd::<1>(
                    _mm256_castpd128_pd256(_mm_loadu_pd(at(l))),
                    _mm_loadu_pd(at(k)),
                )
            };
            // [m0, i0, m2, i2, m4, i4, m6, i6] and the odd lanes likewise.
            let even = _mm512_insertf64x4::<1>(_mm512_castpd256_pd512(pair(0, 2)), pair(4, 6));
            let odd = _mm512_insertf64x4::<1>(_mm512_castpd256_pd512(pair(1, 3)), pair(5, 7));
            [
                Avx8(_mm512_unpacklo_pd(even, odd)),
                Avx8(_mm512_unpackhi_pd(even, odd)),
            ]
        }
    }

    /// One 32-byte load of the eight indices and a `vptestmd`.
    #[inline(always)]
    fn flagged(index: &[u32; LANES], _group: usize, flag: u32) -> __mmask8 {
        // SAFETY: AVX-512F (so AVX) is available (module invariant);
        // `index` is 32 readable bytes (an unaligned load); the upper half
        // of the widened register is undefined, its bits of the mask are
        // dropped.
        unsafe {
            let words =
                _mm512_castsi256_si512(_mm256_loadu_si256(index.as_ptr().cast::<__m256i>()));
            _mm512_test_epi32_mask(words, _mm512_set1_epi32(flag as i32)) as __mmask8
        }
    }
}

/// The transpose between four registers of two rows each (register l:
/// the rows of bodies l and l + 4, four fields each) and four registers of
/// one field each (eight bodies). It is its own inverse: applied to the
/// four fields it gives the rows back, paired the same way.
#[inline(always)]
fn transpose(m: [__m512d; 4]) -> [__m512d; 4] {
    // SAFETY: AVX-512F is available (module invariant); shuffles only.
    unsafe {
        // Per 128-bit lane: (m0[0], m1[0]), (m0[2], m1[2]), (m0[4], m1[4]),
        // (m0[6], m1[6]) and the odd elements likewise.
        let t0 = _mm512_unpacklo_pd(m[0], m[1]);
        let t1 = _mm512_unpackhi_pd(m[0], m[1]);
        let t2 = _mm512_unpacklo_pd(m[2], m[3]);
        let t3 = _mm512_unpackhi_pd(m[2], m[3]);
        // Elements 0–7 of the first source, 8–15 of the second.
        let even = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13);
        let odd = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
        [
            _mm512_permutex2var_pd(t0, even, t2),
            _mm512_permutex2var_pd(t1, even, t3),
            _mm512_permutex2var_pd(t0, odd, t2),
            _mm512_permutex2var_pd(t1, odd, t3),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn avx512_lanes_give_the_bits_of_the_sse2_lanes() {
        if !detected() {
            eprintln!("skipped: this CPU has no AVX-512F, the AVX-512 lanes cannot run");
            return;
        }
        // The CPU has AVX-512F (checked above): Avx8 values may exist.
        crate::soft_step::lanes::tests::lanes_give_the_bits_of_the_sse2_lanes::<Avx8>();
    }
}
