//! Ray traversal of a [`DynamicTree`]: the leaves whose box a ray segment
//! crosses, nearest subtrees pruned by a shrinking maximum distance.

use super::{DynamicTree, NULL, ProxyId, QUERY_STACK_CAPACITY};
use crate::collision::Aabb;
use nalgebra::Vector2;

/// The part `[lower, upper]` of the ray `origin + t dir`, `0 ≤ t ≤ max_t`,
/// inside `aabb` (closed), by the slab method; `None` when it misses (and
/// for a box holding a NaN). `inverse` is `1 / dir` component-wise (an
/// infinity for a zero component).
#[inline]
pub(crate) fn ray_box(
    aabb: &Aabb,
    origin: Vector2<f64>,
    inverse: Vector2<f64>,
    max_t: f64,
) -> Option<(f64, f64)> {
    let (mut lower, mut upper) = (0.0f64, max_t);
    for axis in 0..2 {
        let (o, inv) = (origin[axis], inverse[axis]);
        if inv.is_infinite() {
            // Parallel to this slab: inside it or never.
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

impl DynamicTree {
    /// Calls `callback(id, user_data, max_t)` for every proxy whose fat box
    /// the ray `origin + t dir` (0 ≤ t ≤ `max_t`, m when `dir` is a unit
    /// vector) crosses. The callback returns the new maximum distance
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
        if self.root == NULL {
            return;
        }
        let inverse = dir.map(|c| 1.0 / c);
        let mut max_t = max_t;
        let mut stack = [NULL; QUERY_STACK_CAPACITY];
        stack[0] = self.root;
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let i = stack[len];
            let node = &self.nodes[i as usize];
            if ray_box(&node.aabb, origin, inverse, max_t).is_none() {
                continue;
            }
            if node.is_leaf() {
                match callback(ProxyId(i), node.user_data, max_t) {
                    Some(t) => max_t = max_t.min(t),
                    None => return,
                }
                continue;
            }
            for child in node.children {
                if len < QUERY_STACK_CAPACITY {
                    stack[len] = child;
                    len += 1;
                } else if !self.ray_cast_recursive(
                    child,
                    origin,
                    inverse,
                    &mut max_t,
                    &mut callback,
                ) {
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
        origin: Vector2<f64>,
        inverse: Vector2<f64>,
        max_t: &mut f64,
        callback: &mut impl FnMut(ProxyId, u32, f64) -> Option<f64>,
    ) -> bool {
        let node = &self.nodes[i as usize];
        if ray_box(&node.aabb, origin, inverse, *max_t).is_none() {
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
            .all(|&c| self.ray_cast_recursive(c, origin, inverse, max_t, callback))
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
}
