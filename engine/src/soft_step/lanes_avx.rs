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

use super::bodies::SolverBody;
use super::lanes::{F64x4, LANES, Lanes};
use super::wide_solver::{Bodies, FIXED};
use std::arch::x86_64::{
    __m256d, _CMP_EQ_OQ, _CMP_GT_OQ, _mm256_add_pd, _mm256_blendv_pd, _mm256_cmp_pd, _mm256_div_pd,
    _mm256_load_pd, _mm256_loadu_pd, _mm256_max_pd, _mm256_min_pd, _mm256_movemask_pd,
    _mm256_mul_pd, _mm256_or_pd, _mm256_permute2f128_pd, _mm256_set1_pd, _mm256_store_pd,
    _mm256_storeu_pd, _mm256_sub_pd, _mm256_unpackhi_pd, _mm256_unpacklo_pd, _mm256_xor_pd,
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

// `F64x4` is 32 bytes aligned to 32 (the `wide` crate's layout), so its
// address is valid for an aligned 256-bit load or store.
const _: () = assert!(
    std::mem::size_of::<F64x4>() == 32 && std::mem::align_of::<F64x4>() == 32 && LANES == 4
);

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
    type Mask = AvxMask;

    #[inline(always)]
    fn load(x: &F64x4) -> Self {
        // SAFETY: AVX is available (module invariant); `x` is 32 readable
        // bytes aligned to 32 (checked above).
        Avx4(unsafe { _mm256_load_pd((x as *const F64x4).cast::<f64>()) })
    }

    #[inline(always)]
    fn store(self, x: &mut F64x4) {
        // SAFETY: as `load`, for 32 writable bytes.
        unsafe { _mm256_store_pd((x as *mut F64x4).cast::<f64>(), self.0) }
    }

    #[inline(always)]
    fn splat(x: f64) -> Self {
        // SAFETY: AVX is available (module invariant).
        Avx4(unsafe { _mm256_set1_pd(x) })
    }

    #[inline(always)]
    fn from_array(a: [f64; LANES]) -> Self {
        // SAFETY: AVX is available (module invariant); `a` is 32 readable
        // bytes (an unaligned load).
        Avx4(unsafe { _mm256_loadu_pd(a.as_ptr()) })
    }

    #[inline(always)]
    fn to_array(self) -> [f64; LANES] {
        let mut a = [0.0; LANES];
        // SAFETY: AVX is available (module invariant); `a` is 32 writable
        // bytes (an unaligned store).
        unsafe { _mm256_storeu_pd(a.as_mut_ptr(), self.0) };
        a
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
    fn gather_row(b: &[&SolverBody; LANES], row: usize) -> [Self; 4] {
        let load = |l: usize| -> __m256d {
            // SAFETY: AVX is available (module invariant); the row is 32
            // readable bytes of a `SolverBody`, aligned to 32 (its rows
            // start at 0 and 32 of a 64-aligned record).
            unsafe { _mm256_load_pd(b[l].rows()[row].as_ptr()) }
        };
        transpose([load(0), load(1), load(2), load(3)]).map(Avx4)
    }

    /// The 4 × 4 transpose back to rows and four aligned 32-byte stores of
    /// `[v.x, v.y, ω, Δp.x]` (`Δp.x` as gathered: unchanged).
    #[inline(always)]
    fn scatter_head(head: [Self; 4], bodies: Bodies<'_>, index: &[u32; LANES]) {
        let rows = transpose(head.map(|x| x.0));
        for (l, &i) in index.iter().enumerate() {
            if i & FIXED != 0 {
                continue;
            }
            // SAFETY: a dynamic body of a lane is this thread's alone (the
            // colouring); no reference to it is alive.
            let row = unsafe { bodies.get_mut(i as usize) }.head_mut();
            // SAFETY: AVX is available (module invariant); `row` is 32
            // writable bytes aligned to 32 (the start of a 64-aligned
            // record).
            unsafe { _mm256_store_pd(row.as_mut_ptr(), rows[l]) };
        }
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
            return; // Nothing to compare on this CPU.
        }
        let (x, y) = ([1.5, -2.0, 0.1, -0.0], [0.5, 4.0, 0.1, 0.0]);
        let (a, b) = (F64x4::new(x), F64x4::new(y));
        // The CPU has AVX (checked above): Avx4 values may exist.
        let (p, q) = (Avx4::from_array(x), Avx4::from_array(y));
        let same = |avx: Avx4, sse: F64x4| {
            let bits = |v: [f64; 4]| v.map(f64::to_bits);
            assert_eq!(bits(avx.to_array()), bits(sse.to_array()));
        };
        same(p + q, a + b);
        same(p - q, a - b);
        same(p * q, a * b);
        // Division by a divisor without zeros: 0/0's NaN has no defined
        // sign bit (the CPU gives -NaN, a constant-folded one +NaN).
        let z = [0.5, 4.0, 0.1, 2.0];
        same(p / Avx4::from_array(z), a / F64x4::new(z));
        same(-p, -a);
        same(p.max(q), Lanes::max(a, b));
        same(p.min(q), Lanes::min(a, b));
        same(p.clamp(-q, q), a.clamp(-b, b));
        same(Avx4::select(p.gt(q), p, q), F64x4::select(a.gt(b), a, b));
        same(Avx4::select(p.eq(q), p, q), F64x4::select(a.eq(b), a, b));
        assert_eq!(
            Avx4::all(Avx4::or(p.gt(q), q.gt(p))),
            F64x4::all(F64x4::or(a.gt(b), b.gt(a)))
        );
        let mut stored = F64x4::default();
        Avx4::load(&a).store(&mut stored);
        assert_eq!(stored, a);
        same(Avx4::splat(3.0), Lanes::splat(3.0));
        // The transposed gather and scatter of body records.
        let mut bodies: Vec<SolverBody> = (0..5)
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
        let index = [3, 0, 4, 0];
        let refs = index.map(|i| &bodies[i as usize]);
        for row in 0..2 {
            let (avx, sse) = (
                Avx4::gather_row(&refs, row),
                <F64x4 as Lanes>::gather_row(&refs, row),
            );
            for k in 0..4 {
                same(avx[k], sse[k]);
            }
        }
        // New velocities for bodies 3, 1, 4, 2, with their Δp.x as gathered.
        let index = [3, 1, 4, 2];
        let dpx = Avx4::gather_row(&index.map(|i| &bodies[i as usize]), 0)[3];
        let lanes = |x: f64| [x, -x, 10.0 * x, -10.0 * x];
        let head = [1.0, 2.0, 3.0].map(|x| Avx4::from_array(lanes(x)));
        let sse_head = [1.0, 2.0, 3.0].map(|x| F64x4::new(lanes(x)));
        let mut expected = bodies.clone();
        <F64x4 as Lanes>::scatter_head(
            [
                sse_head[0],
                sse_head[1],
                sse_head[2],
                F64x4::new(dpx.to_array()),
            ],
            Bodies::new(&mut expected),
            &index,
        );
        Avx4::scatter_head(
            [head[0], head[1], head[2], dpx],
            Bodies::new(&mut bodies),
            &index,
        );
        assert_eq!(bodies, expected);
        // Body 4 is lane 2: v.x, v.y, ω = 10, 20, 30.
        assert_eq!(
            (bodies[4].v.x, bodies[4].v.y, bodies[4].w),
            (10.0, 20.0, 30.0)
        );
    }
}
