//! Ray traversal of a [`DynamicTree`]: the leaves whose box a ray segment
//! crosses, nearest box first, subtrees pruned by a shrinking maximum
//! distance (Box2D's `b2DynamicTree_RayCast` with its `maxFraction`, plus
//! the nearer child visited first).
//!
//! Each child's box is tested when its parent is opened, and it is pushed
//! with the distance at which the ray enters it; when popped, it is skipped
//! if that distance is now beyond the maximum (a hit found meanwhile). The
//! nearer child is pushed last, so popped first: the first leaves a
//! closest-hit query examines are the nearest, and the far subtrees are
//! then pruned by its hit. Whether a box is reached is exactly
//! [`ray_box`]'s answer at the current maximum (the entry distance does
//! not depend on the maximum), so the set of leaves reported for a given
//! sequence of maxima is the same as testing each box when popped.

use super::{DynamicTree, NULL, ProxyId, QUERY_STACK_CAPACITY};
use crate::collision::Aabb;
use nalgebra::Vector2;

/// The part `[lower, upper]` of the ray `origin + t dir`, `0 ≤ t ≤ max_t`,
/// inside `aabb` (closed), by the slab method; `None` when it misses.
/// `inverse` is `1 / dir` component-wise (an infinity for a zero
/// component). A NaN coordinate of the box leaves its slab out of the
/// clip (the comparisons below are false for NaN).
///
/// The clip is written with comparisons rather than `f64::max`/`f64::min`:
/// those must return the other operand for a NaN and compile to several
/// instructions each, where `a > b` selects in one; the two agree on every
/// non-NaN operand (up to the sign of a zero, which no comparison sees),
/// and on a NaN operand both keep the bound unchanged.
#[inline]
pub(crate) fn ray_box(
    aabb: &Aabb,
    origin: Vector2<f64>,
    inverse: Vector2<f64>,
    max_t: f64,
) -> Option<(f64, f64)> {
    // Written out per axis (a loop over the two axes was not unrolled and
    // cost a third of the test in its bookkeeping).
    let mut clip = (0.0f64, max_t);
    let inside = clip_slab(aabb.min.x, aabb.max.x, origin.x, inverse.x, &mut clip)
        && clip_slab(aabb.min.y, aabb.max.y, origin.y, inverse.y, &mut clip);
    (inside && clip.0 <= clip.1).then_some(clip)
}

/// Clips `[lower, upper]` (`clip`) to the part of the ray inside the slab
/// `min ≤ x ≤ max` of one axis, for the ray's origin coordinate `o` and
/// inverse direction `inv` on that axis; false when the ray is parallel to
/// the slab and outside it.
#[inline(always)]
fn clip_slab(min: f64, max: f64, o: f64, inv: f64, clip: &mut (f64, f64)) -> bool {
    if inv.is_infinite() {
        // Parallel to this slab: inside it or never.
        return min <= o && o <= max;
    }
    let (t1, t2) = ((min - o) * inv, (max - o) * inv);
    let (near, far) = if t1 <= t2 { (t1, t2) } else { (t2, t1) };
    if near > clip.0 {
        clip.0 = near;
    }
    if far < clip.1 {
        clip.1 = far;
    }
    true
}

/// One ray prepared for many box tests: [`ray_box`]'s answer and entry
/// distance, the two axes computed at once in SSE2 lanes on x86-64 (the
/// tree walk's box tests were most of a ray query's instructions). Same
/// operations per lane as [`ray_box`]: `minpd`/`maxpd` select as its
/// comparisons do (for a NaN too), so the answers are equal (tested). A
/// ray parallel to an axis takes [`ray_box`] itself.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RayBoxTest {
    origin: Vector2<f64>,
    /// `1 / dir`, component-wise.
    inverse: Vector2<f64>,
    /// A component of the direction is zero (an infinite inverse).
    #[cfg_attr(
        not(all(target_arch = "x86_64", target_feature = "sse2")),
        allow(dead_code)
    )]
    parallel: bool,
}

#[cfg(test)]
thread_local! {
    /// Test builds only: the number of [`RayBoxTest::entry`] calls (box
    /// tests of the ray walks) on this thread, for the tests' cost figures.
    pub(crate) static BOX_TESTS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

impl RayBoxTest {
    /// The test for the ray `origin + t dir`.
    pub(crate) fn new(origin: Vector2<f64>, dir: Vector2<f64>) -> Self {
        let inverse = dir.map(|c| 1.0 / c);
        Self {
            origin,
            inverse,
            parallel: inverse.x.is_infinite() || inverse.y.is_infinite(),
        }
    }

    /// Where the ray (`0 ≤ t ≤ max_t`) enters `aabb`, `None` when it
    /// misses: `ray_box(aabb, origin, 1 / dir, max_t)`'s lower end.
    #[inline(always)]
    pub(crate) fn entry(&self, aabb: &Aabb, max_t: f64) -> Option<f64> {
        #[cfg(test)]
        BOX_TESTS.with(|c| c.set(c.get() + 1));
        #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
        if !self.parallel {
            return self.entry_sse2(aabb, max_t);
        }
        ray_box(aabb, self.origin, self.inverse, max_t).map(|(lower, _)| lower)
    }

    /// [`RayBoxTest::entry`] for a ray with both inverse components
    /// finite, x in lane 0 and y in lane 1 (SSE2 is part of x86-64).
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    #[inline(always)]
    fn entry_sse2(&self, aabb: &Aabb, max_t: f64) -> Option<f64> {
        use std::arch::x86_64::{
            _mm_cvtsd_f64, _mm_max_pd, _mm_max_sd, _mm_min_pd, _mm_min_sd, _mm_mul_pd, _mm_set_pd,
            _mm_set_sd, _mm_sub_pd, _mm_unpackhi_pd,
        };
        // SAFETY: these intrinsics only need SSE2, which this function is
        // compiled with (the `cfg` above: every x86-64 target has it); they
        // read and write registers only.
        let (lower, upper) = unsafe {
            let o = _mm_set_pd(self.origin.y, self.origin.x);
            let inv = _mm_set_pd(self.inverse.y, self.inverse.x);
            let t1 = _mm_mul_pd(_mm_sub_pd(_mm_set_pd(aabb.min.y, aabb.min.x), o), inv);
            let t2 = _mm_mul_pd(_mm_sub_pd(_mm_set_pd(aabb.max.y, aabb.max.x), o), inv);
            // near = t1 < t2 ? t1 : t2 and far = t2 > t1 ? t2 : t1 per lane:
            // `if t1 <= t2 { (t1, t2) } else { (t2, t1) }` (equal values, or
            // a NaN, give the same choice up to the sign of a zero).
            let near = _mm_min_pd(t1, t2);
            let far = _mm_max_pd(t2, t1);
            // lower = near_y > (near_x > 0 ? near_x : 0) ? near_y : ..., as
            // ray_box clips x then y; upper likewise with `<` from max_t.
            let lower = _mm_max_sd(
                _mm_unpackhi_pd(near, near),
                _mm_max_sd(near, _mm_set_sd(0.0)),
            );
            let upper = _mm_min_sd(
                _mm_unpackhi_pd(far, far),
                _mm_min_sd(far, _mm_set_sd(max_t)),
            );
            (_mm_cvtsd_f64(lower), _mm_cvtsd_f64(upper))
        };
        (lower <= upper).then_some(lower)
    }
}

impl DynamicTree {
    /// Calls `callback(id, user_data, max_t)` for every proxy whose fat box
    /// the ray `origin + t dir` (0 ≤ t ≤ `max_t`, m when `dir` is a unit
    /// vector) crosses, roughly nearest first (see the module
    /// documentation). The callback returns the new maximum distance
    /// (`max_t` unchanged to see every crossed leaf, the distance of a hit
    /// to look only nearer), or `None` to stop. Subtrees whose box the
    /// shortened ray no longer reaches are skipped. Allocates nothing.
    pub fn ray_cast(
        &self,
        origin: Vector2<f64>,
        dir: Vector2<f64>,
        max_t: f64,
        mut callback: impl FnMut(ProxyId, u32, f64) -> Option<f64>,
    ) {
        self.ray_cast_with_stack::<QUERY_STACK_CAPACITY>(origin, dir, max_t, &mut callback);
    }

    /// [`DynamicTree::ray_cast`] with a stack of `N` entries (tests use a
    /// small one to reach the recursive fallback).
    fn ray_cast_with_stack<const N: usize>(
        &self,
        origin: Vector2<f64>,
        dir: Vector2<f64>,
        max_t: f64,
        callback: &mut impl FnMut(ProxyId, u32, f64) -> Option<f64>,
    ) {
        if self.root == NULL {
            return;
        }
        let ray = RayBoxTest::new(origin, dir);
        let mut max_t = max_t;
        let Some(root_lower) = ray.entry(&self.nodes[self.root as usize].aabb, max_t) else {
            return;
        };
        if N == 0 {
            self.ray_cast_recursive(self.root, &ray, &mut max_t, callback);
            return;
        }
        // (node, distance at which the ray enters its box)
        let mut stack = [(NULL, 0.0f64); N];
        stack[0] = (self.root, root_lower);
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let (i, lower) = stack[len];
            if lower > max_t {
                continue; // entered beyond a hit found since it was pushed
            }
            let node = &self.nodes[i as usize];
            if node.is_leaf() {
                match callback(ProxyId(i), node.user_data, max_t) {
                    Some(t) => max_t = max_t.min(t),
                    None => return,
                }
                continue;
            }
            let entry = |c: u32| {
                ray.entry(&self.nodes[c as usize].aabb, max_t)
                    .map(|l| (c, l))
            };
            let [a, b] = node.children;
            let (near, far) = match (entry(a), entry(b)) {
                (Some(x), Some(y)) if y.1 < x.1 => (Some(y), Some(x)),
                (x, y) => (x, y),
            };
            // The farther first, so that the nearer is popped next.
            for (child, lower) in [far, near].into_iter().flatten() {
                if len < N {
                    stack[len] = (child, lower);
                    len += 1;
                } else if !self.ray_cast_recursive(child, &ray, &mut max_t, callback) {
                    return;
                }
            }
        }
    }

    /// The fallback of [`DynamicTree::ray_cast`] past its stack's depth.
    /// Returns false if the callback stopped it.
    fn ray_cast_recursive(
        &self,
        i: u32,
        ray: &RayBoxTest,
        max_t: &mut f64,
        callback: &mut impl FnMut(ProxyId, u32, f64) -> Option<f64>,
    ) -> bool {
        let node = &self.nodes[i as usize];
        if ray.entry(&node.aabb, *max_t).is_none() {
            return true;
        }
        if node.is_leaf() {
            return match callback(ProxyId(i), node.user_data, *max_t) {
                Some(t) => {
                    *max_t = max_t.min(t);
                    true
                }
                None => false,
            };
        }
        node.children
            .iter()
            .all(|&c| self.ray_cast_recursive(c, ray, max_t, callback))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::test_rng::Rng;

    /// Every leaf the ray crosses, against a brute-force slab test.
    #[test]
    fn ray_finds_every_crossed_box() {
        let mut rng = Rng::new(17);
        let mut tree = DynamicTree::new();
        let mut boxes = Vec::new();
        for k in 0..300 {
            let c = Vector2::new(rng.range(-20.0, 20.0), rng.range(-20.0, 20.0));
            let e = Vector2::new(rng.range(0.1, 2.0), rng.range(0.1, 2.0));
            let b = Aabb::new(c - e, c + e);
            tree.create_proxy(b, k);
            boxes.push(b);
        }
        for _ in 0..200 {
            let o = Vector2::new(rng.range(-25.0, 25.0), rng.range(-25.0, 25.0));
            let angle = rng.range(0.0, std::f64::consts::TAU);
            let d = Vector2::new(angle.cos(), angle.sin());
            let inverse = d.map(|c| 1.0 / c);
            let mut found = Vec::new();
            tree.ray_cast(o, d, 30.0, |_, k, max| {
                found.push(k);
                Some(max)
            });
            found.sort();
            let expected: Vec<u32> = (0..boxes.len() as u32)
                .filter(|&k| ray_box(&boxes[k as usize], o, inverse, 30.0).is_some())
                .collect();
            assert_eq!(found, expected);
        }
    }

    /// The slab test as first written, with `f64::max`/`f64::min`: the
    /// specification [`ray_box`]'s comparisons must agree with.
    fn ray_box_with_max_min(
        aabb: &Aabb,
        origin: Vector2<f64>,
        inverse: Vector2<f64>,
        max_t: f64,
    ) -> Option<(f64, f64)> {
        let (mut lower, mut upper) = (0.0f64, max_t);
        for axis in 0..2 {
            let (o, inv) = (origin[axis], inverse[axis]);
            if inv.is_infinite() {
                if !(aabb.min[axis] <= o && o <= aabb.max[axis]) {
                    return None;
                }
                continue;
            }
            let (t1, t2) = ((aabb.min[axis] - o) * inv, (aabb.max[axis] - o) * inv);
            let (near, far) = if t1 <= t2 { (t1, t2) } else { (t2, t1) };
            lower = lower.max(near);
            upper = upper.min(far);
        }
        (lower <= upper).then_some((lower, upper))
    }

    /// Same answer, same interval (zeros compared as numbers), on random
    /// boxes and on the awkward ones: touching, inverted, infinite, NaN,
    /// axis-parallel rays, rays starting on a face.
    #[test]
    fn ray_box_agrees_with_the_max_min_form() {
        let mut rng = Rng::new(5);
        let inf = f64::INFINITY;
        let special = [
            Aabb::new(Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0)),
            Aabb::new(Vector2::new(1.0, 1.0), Vector2::new(0.0, 0.0)),
            Aabb::new(Vector2::new(-inf, -1.0), Vector2::new(inf, 0.0)),
            Aabb::new(Vector2::new(f64::NAN, 0.0), Vector2::new(1.0, 1.0)),
            Aabb::new(Vector2::repeat(f64::NAN), Vector2::repeat(f64::NAN)),
            Aabb::new(Vector2::new(2.0, 2.0), Vector2::new(2.0, 2.0)),
        ];
        let dirs = [
            Vector2::x(),
            -Vector2::y(),
            Vector2::new(-0.0, 1.0),
            Vector2::new(1.0, 1.0).normalize(),
        ];
        let origins = [
            Vector2::zeros(),
            Vector2::new(-3.0, 0.5),
            Vector2::new(2.0, -1.0),
        ];
        let mut checked = 0;
        let mut check = |b: &Aabb, o: Vector2<f64>, d: Vector2<f64>, max_t: f64| {
            let inverse = d.map(|c| 1.0 / c);
            let got = ray_box(b, o, inverse, max_t);
            let want = ray_box_with_max_min(b, o, inverse, max_t);
            assert_eq!(got.is_some(), want.is_some(), "{b:?} {o} {d} {max_t}");
            let entry = RayBoxTest::new(o, d).entry(b, max_t);
            assert_eq!(entry.is_some(), want.is_some(), "{b:?} {o} {d} {max_t}");
            if let (Some(e), Some(w)) = (entry, want) {
                assert!(e == w.0, "{e} {w:?}");
            }
            if let (Some(g), Some(w)) = (got, want) {
                assert!(g.0 == w.0 && g.1 == w.1, "{g:?} {w:?}");
            }
            checked += 1;
        };
        for b in &special {
            for &o in &origins {
                for &d in &dirs {
                    for max_t in [0.0, 3.0, inf] {
                        check(b, o, d, max_t);
                        check(b, o, -d, max_t);
                    }
                }
            }
        }
        for _ in 0..20_000 {
            let c = Vector2::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0));
            let e = Vector2::new(rng.range(0.0, 2.0), rng.range(0.0, 2.0));
            let o = Vector2::new(rng.range(-8.0, 8.0), rng.range(-8.0, 8.0));
            let a = rng.range(0.0, std::f64::consts::TAU);
            check(
                &Aabb::new(c - e, c + e),
                o,
                Vector2::new(a.cos(), a.sin()),
                rng.range(0.0, 12.0),
            );
        }
        assert!(checked > 20_000);
    }

    /// A closest-hit walk (each leaf's "hit" is where the ray enters its
    /// box, returned as the new maximum) finds the brute-force nearest
    /// entry, with the full stack and with stacks small enough that the
    /// recursive fallback runs; with the maximum unchanged every stack size
    /// reports every crossed leaf.
    #[test]
    fn closest_walk_finds_the_nearest_box_with_any_stack() {
        let mut rng = Rng::new(23);
        let mut tree = DynamicTree::new();
        let mut boxes = Vec::new();
        for k in 0..400 {
            let c = Vector2::new(rng.range(-30.0, 30.0), rng.range(-30.0, 30.0));
            let e = Vector2::new(rng.range(0.1, 2.0), rng.range(0.1, 2.0));
            let b = Aabb::new(c - e, c + e);
            tree.create_proxy(b, k);
            boxes.push(b);
        }
        fn walk<const N: usize>(
            tree: &DynamicTree,
            boxes: &[Aabb],
            o: Vector2<f64>,
            d: Vector2<f64>,
            closest: bool,
        ) -> Vec<(u32, f64)> {
            let inverse = d.map(|c| 1.0 / c);
            let mut seen = Vec::new();
            tree.ray_cast_with_stack::<N>(o, d, 40.0, &mut |_, k, max| {
                let (lower, _) = ray_box(&boxes[k as usize], o, inverse, max).expect("crossed");
                seen.push((k, lower));
                Some(if closest { lower } else { max })
            });
            seen
        }
        for _ in 0..300 {
            let o = Vector2::new(rng.range(-35.0, 35.0), rng.range(-35.0, 35.0));
            let angle = rng.range(0.0, std::f64::consts::TAU);
            let d = Vector2::new(angle.cos(), angle.sin());
            let inverse = d.map(|c| 1.0 / c);
            let nearest = (0..boxes.len())
                .filter_map(|k| ray_box(&boxes[k], o, inverse, 40.0).map(|(l, _)| l))
                .fold(f64::INFINITY, f64::min);
            let min_of =
                |seen: Vec<(u32, f64)>| seen.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
            assert_eq!(min_of(walk::<64>(&tree, &boxes, o, d, true)), nearest);
            assert_eq!(min_of(walk::<2>(&tree, &boxes, o, d, true)), nearest);
            assert_eq!(min_of(walk::<0>(&tree, &boxes, o, d, true)), nearest);
            let all = |mut seen: Vec<(u32, f64)>| {
                seen.sort_by_key(|s| s.0);
                seen
            };
            let full = all(walk::<64>(&tree, &boxes, o, d, false));
            assert_eq!(all(walk::<1>(&tree, &boxes, o, d, false)), full);
            assert_eq!(all(walk::<0>(&tree, &boxes, o, d, false)), full);
        }
    }
}
