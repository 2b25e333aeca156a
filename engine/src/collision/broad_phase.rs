//! Broad phase: the candidate pairs, those whose bounding boxes overlap
//! (seed §7.2, Fig. 7.1).
//!
//! The seed replaces the O(n²) all-pairs test by a sweep in O(n log n) after
//! Fortune. Its modern form, used here, is *sort and sweep* (also called
//! sweep and prune): sort the boxes by the left end of their x-interval,
//! then sweep left to right; a box can only overlap the boxes that start
//! before its own x-interval ends, so the inner loop stops at the first box
//! starting to its right. The cost is the sort plus the number of
//! x-overlapping pairs.
//!
//! Between steps the bodies move a little, so the order of the previous call
//! is nearly right: [`SweepAndPrune`] keeps it and repairs it by insertion
//! sort, O(n + swaps), which is O(n) for coherent motion.
//!
//! [`brute_force_pairs`] is the O(n²) oracle the sweep is tested against.

use super::aabb::Aabb;

/// Sort-and-sweep broad phase that remembers the order of its last call.
///
/// ```
/// use etalon2d::validation::collision::{Aabb, SweepAndPrune};
/// use nalgebra::Vector2;
/// let boxes = [
///     Aabb::new(Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0)),
///     Aabb::new(Vector2::new(5.0, 0.0), Vector2::new(6.0, 1.0)),
///     Aabb::new(Vector2::new(0.5, 0.5), Vector2::new(2.0, 2.0)),
/// ];
/// let mut sap = SweepAndPrune::new();
/// assert_eq!(sap.pairs(&boxes), vec![(0, 2)]);
/// ```
#[derive(Debug, Clone, Default)]
pub struct SweepAndPrune {
    /// Box indices sorted by `min.x` (ties by index), as left by the last call.
    order: Vec<usize>,
    /// Adjacent swaps the insertion sort made in the last call.
    swaps: usize,
}

impl SweepAndPrune {
    /// An empty broad phase; the first call sorts from scratch.
    pub fn new() -> Self {
        Self::default()
    }

    /// The pairs `(i, j)`, `i < j`, of boxes that overlap (closed boxes:
    /// touching counts), sorted. Indices refer to `aabbs`.
    ///
    /// If `aabbs` has the same length as in the last call, the previous
    /// order is repaired by insertion sort; otherwise it is rebuilt by a full
    /// O(n log n) sort. A box holding a NaN overlaps nothing.
    pub fn pairs(&mut self, aabbs: &[Aabb]) -> Vec<(usize, usize)> {
        let key = |i: usize| aabbs[i].min.x;
        let before = |i: usize, j: usize| key(i).total_cmp(&key(j)).then(i.cmp(&j));
        self.swaps = 0;
        if self.order.len() == aabbs.len() {
            // Insertion sort: each element walks left past the ones that
            // should follow it. Nearly sorted input makes few swaps.
            for k in 1..self.order.len() {
                let mut m = k;
                while m > 0 && before(self.order[m], self.order[m - 1]).is_lt() {
                    self.order.swap(m, m - 1);
                    self.swaps += 1;
                    m -= 1;
                }
            }
        } else {
            self.order = (0..aabbs.len()).collect();
            self.order.sort_unstable_by(|&i, &j| before(i, j));
        }

        let mut pairs = Vec::new();
        for (p, &i) in self.order.iter().enumerate() {
            let a = &aabbs[i];
            for &j in &self.order[p + 1..] {
                let b = &aabbs[j];
                // Sorted by min.x: every later box starts at or after b does.
                if b.min.x > a.max.x {
                    break;
                }
                if a.overlaps(b) {
                    pairs.push((i.min(j), i.max(j)));
                }
            }
        }
        pairs.sort_unstable();
        pairs
    }

    /// Adjacent swaps the insertion sort made in the last call to
    /// [`SweepAndPrune::pairs`] (0 after a rebuild or for unchanged order):
    /// a measure of how coherent the motion was.
    pub fn last_swap_count(&self) -> usize {
        self.swaps
    }

    /// Forgets the stored order; the next call sorts from scratch.
    pub fn clear(&mut self) {
        self.order.clear();
        self.swaps = 0;
    }
}

/// The pairs `(i, j)`, `i < j`, of overlapping boxes by testing all
/// n(n − 1)/2 pairs (seed §7.2: "O(n²) comparaisons"). Sorted. The oracle of
/// [`SweepAndPrune`].
pub fn brute_force_pairs(aabbs: &[Aabb]) -> Vec<(usize, usize)> {
    let mut pairs = Vec::new();
    for i in 0..aabbs.len() {
        for j in i + 1..aabbs.len() {
            if aabbs[i].overlaps(&aabbs[j]) {
                pairs.push((i, j));
            }
        }
    }
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::test_rng::Rng;
    use nalgebra::Vector2;

    fn random_box(rng: &mut Rng, world: f64, size: f64) -> Aabb {
        let c = Vector2::new(rng.range(0.0, world), rng.range(0.0, world));
        let h = Vector2::new(rng.range(0.0, size), rng.range(0.0, size));
        Aabb::new(c - h, c + h)
    }

    #[test]
    fn sweep_matches_brute_force_on_random_sets() {
        let mut rng = Rng::new(0x5EED_0001);
        let mut total_pairs = 0;
        for trial in 0..300 {
            let n = rng.int(0, 80);
            let size = if trial % 3 == 0 { 0.5 } else { 3.0 };
            let mut boxes: Vec<Aabb> = (0..n).map(|_| random_box(&mut rng, 20.0, size)).collect();
            // Exact ties and touching boxes, the cases a strict/closed mix-up
            // would get wrong.
            if n > 4 {
                boxes[1].min.x = boxes[0].min.x;
                boxes[3].min.x = boxes[2].max.x;
                boxes[3].min.y = boxes[2].min.y;
            }
            let mut sap = SweepAndPrune::new();
            let expected = brute_force_pairs(&boxes);
            assert_eq!(sap.pairs(&boxes), expected, "trial {trial}, n = {n}");
            total_pairs += expected.len();
        }
        assert!(
            total_pairs > 1000,
            "the sets must have pairs: {total_pairs}"
        );
    }

    #[test]
    fn sweep_matches_brute_force_on_moving_sets_across_calls() {
        let mut rng = Rng::new(0x5EED_0002);
        let n = 120;
        let mut boxes: Vec<Aabb> = (0..n).map(|_| random_box(&mut rng, 30.0, 1.5)).collect();
        let velocities: Vec<Vector2<f64>> = (0..n)
            .map(|_| Vector2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)))
            .collect();
        let mut sap = SweepAndPrune::new();
        let mut swaps = 0;
        for step in 0..200 {
            for (b, v) in boxes.iter_mut().zip(&velocities) {
                let d = 0.05 * v;
                b.min += d;
                b.max += d;
            }
            assert_eq!(sap.pairs(&boxes), brute_force_pairs(&boxes), "step {step}");
            swaps += sap.last_swap_count();
        }
        // Coherent motion: a few swaps per step, far from the n²/4 of a
        // random permutation.
        assert!(swaps < 200 * n, "{swaps} swaps");
        // A repeated call on the same boxes swaps nothing.
        sap.pairs(&boxes);
        assert_eq!(sap.last_swap_count(), 0);
    }

    #[test]
    fn changing_the_count_rebuilds_the_order() {
        let mut rng = Rng::new(7);
        let mut sap = SweepAndPrune::new();
        let mut boxes: Vec<Aabb> = (0..30).map(|_| random_box(&mut rng, 10.0, 1.0)).collect();
        assert_eq!(sap.pairs(&boxes), brute_force_pairs(&boxes));
        boxes.truncate(17);
        assert_eq!(sap.pairs(&boxes), brute_force_pairs(&boxes));
        boxes.extend((0..40).map(|_| random_box(&mut rng, 10.0, 1.0)));
        assert_eq!(sap.pairs(&boxes), brute_force_pairs(&boxes));
        sap.clear();
        assert_eq!(sap.pairs(&boxes), brute_force_pairs(&boxes));
    }

    #[test]
    fn nan_boxes_pair_with_nothing() {
        let mut boxes = vec![
            Aabb::new(Vector2::new(0.0, 0.0), Vector2::new(1.0, 1.0)),
            Aabb::new(Vector2::new(f64::NAN, 0.0), Vector2::new(1.0, 1.0)),
            Aabb::new(Vector2::new(0.5, 0.5), Vector2::new(f64::NAN, 2.0)),
            Aabb::new(Vector2::new(0.5, 0.5), Vector2::new(2.0, 2.0)),
        ];
        let mut sap = SweepAndPrune::new();
        assert_eq!(sap.pairs(&boxes), vec![(0, 3)]);
        boxes.swap(0, 1);
        assert_eq!(sap.pairs(&boxes), brute_force_pairs(&boxes));
    }
}
