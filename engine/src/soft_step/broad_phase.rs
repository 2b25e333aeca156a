//! The soft step's broad phase: two dynamic AABB trees (static bodies in
//! one, moving bodies in the other) of enlarged ("fat") boxes, and a move
//! buffer of the bodies whose box left its fat box.
//!
//! A body that moves less than the margin stays inside its fat box and costs
//! nothing here; only bodies in the move buffer are re-inserted and queried
//! for new pairs (seed §7.2–7.3 ask the collision system to keep few
//! candidates; Box2D's `broad_phase.c` and rapier's BVH do the same). Pairs
//! persist as [`super::contacts::Contact`]s until their fat boxes part, so
//! the cost of a resting pile is O(1) per body per step.

use crate::body::BodyId;
use crate::collision::{Aabb, DynamicTree, ProxyId};

/// Which tree a proxy lives in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Tree {
    Static,
    Moving,
}

/// The trees, the proxies of the bodies that have a shape, and the move
/// buffer.
#[derive(Debug, Default)]
pub(crate) struct BroadPhase {
    static_tree: DynamicTree,
    moving_tree: DynamicTree,
    /// Per body: its tree and proxy, `None` without a shape.
    proxies: Vec<Option<(Tree, ProxyId)>>,
    /// Bodies whose proxy was created or moved since pairs were last found.
    moved: Vec<BodyId>,
    /// Per body: whether it is in `moved`.
    in_move_buffer: Vec<bool>,
}

impl BroadPhase {
    /// Registers body `id` (the next one) with its fat box, or none
    /// without a shape.
    pub(crate) fn add(&mut self, id: BodyId, fat: Option<Aabb>, is_static: bool) {
        debug_assert_eq!(id, self.proxies.len());
        let proxy = fat.map(|fat| {
            let tree = if is_static {
                Tree::Static
            } else {
                Tree::Moving
            };
            let proxy = self.tree_mut(tree).create_proxy(fat, id as u32);
            (tree, proxy)
        });
        self.proxies.push(proxy);
        self.in_move_buffer.push(false);
        if proxy.is_some() {
            self.buffer_move(id);
        }
    }

    /// Removes body `id`'s proxy (the body stays registered, without one).
    pub(crate) fn remove(&mut self, id: BodyId) {
        if let Some((tree, proxy)) = self.proxies[id].take() {
            self.tree_mut(tree).destroy_proxy(proxy);
        }
        if self.in_move_buffer[id] {
            self.moved.retain(|&b| b != id);
            self.in_move_buffer[id] = false;
        }
    }

    fn tree_mut(&mut self, tree: Tree) -> &mut DynamicTree {
        match tree {
            Tree::Static => &mut self.static_tree,
            Tree::Moving => &mut self.moving_tree,
        }
    }

    fn buffer_move(&mut self, id: BodyId) {
        if !self.in_move_buffer[id] {
            self.in_move_buffer[id] = true;
            self.moved.push(id);
        }
    }

    /// Puts proxy `id` in the move buffer, so that the next pair search
    /// looks at its overlaps again (a filter between it and another body
    /// was lifted).
    pub(crate) fn refresh(&mut self, id: BodyId) {
        if self.proxies[id].is_some() {
            self.buffer_move(id);
        }
    }

    /// Body `id`'s fat box, if it has a shape.
    pub(crate) fn fat_aabb(&self, id: BodyId) -> Option<&Aabb> {
        self.proxies[id].map(|(tree, proxy)| match tree {
            Tree::Static => self.static_tree.fat_aabb(proxy),
            Tree::Moving => self.moving_tree.fat_aabb(proxy),
        })
    }

    /// Whether two bodies' fat boxes overlap.
    pub(crate) fn fat_overlap(&self, a: BodyId, b: BodyId) -> bool {
        match (self.fat_aabb(a), self.fat_aabb(b)) {
            (Some(a), Some(b)) => a.overlaps(b),
            _ => false,
        }
    }

    /// Body `id` now has the (speculatively grown) box `aabb`: if it left
    /// its fat box, the proxy moves to `aabb` grown by `margin` (m) and the
    /// body joins the move buffer.
    pub(crate) fn update(&mut self, id: BodyId, aabb: &Aabb, margin: f64) {
        let Some((tree, proxy)) = self.proxies[id] else {
            return;
        };
        let tree_ref = self.tree_mut(tree);
        if tree_ref.fat_aabb(proxy).contains(aabb) {
            return;
        }
        tree_ref.move_proxy(proxy, aabb.loosened(margin));
        self.buffer_move(id);
    }

    /// Calls `new_pair(a, b)` once for every pair with at least one body in
    /// the move buffer whose fat boxes overlap, then empties the buffer.
    /// Pairs of two moved bodies are reported once; the callback decides
    /// whether a pair is new and wanted.
    pub(crate) fn find_pairs(&mut self, mut new_pair: impl FnMut(BodyId, BodyId)) {
        for i in 0..self.moved.len() {
            let id = self.moved[i];
            let Some((tree, proxy)) = self.proxies[id] else {
                continue;
            };
            let fat = match tree {
                Tree::Static => *self.static_tree.fat_aabb(proxy),
                Tree::Moving => *self.moving_tree.fat_aabb(proxy),
            };
            let in_buffer = &self.in_move_buffer;
            let mut visit = |_: ProxyId, other: u32| {
                let other = other as usize;
                // A pair of two moved bodies is reported by the lower id.
                if other != id && !(in_buffer[other] && other < id) {
                    new_pair(id, other);
                }
                true
            };
            self.moving_tree.query(&fat, &mut visit);
            if tree == Tree::Moving {
                self.static_tree.query(&fat, &mut visit);
            }
        }
        for &id in &self.moved {
            self.in_move_buffer[id] = false;
        }
        self.moved.clear();
    }

    /// Calls `f(body)` for every body whose shape's fat box overlaps
    /// `aabb` in the static tree.
    pub(crate) fn query_static(&self, aabb: &Aabb, mut f: impl FnMut(BodyId)) {
        self.static_tree.query(aabb, |_, id| {
            f(id as usize);
            true
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::brute_force_pairs;
    use crate::collision::test_rng::Rng;
    use nalgebra::Vector2;
    use std::collections::BTreeSet;

    fn random_box(rng: &mut Rng) -> Aabb {
        let c = Vector2::new(rng.range(-20.0, 20.0), rng.range(-20.0, 20.0));
        let e = Vector2::new(rng.range(0.1, 2.0), rng.range(0.1, 2.0));
        Aabb::new(c - e, c + e)
    }

    /// Pairs (lo, hi) with at least one moving body whose boxes overlap.
    fn oracle(boxes: &[Aabb], is_static: &[bool], involving: &[bool]) -> BTreeSet<(usize, usize)> {
        brute_force_pairs(boxes)
            .into_iter()
            .filter(|&(a, b)| !(is_static[a] && is_static[b]))
            .filter(|&(a, b)| involving[a] || involving[b])
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect()
    }

    #[test]
    fn new_pairs_are_exactly_the_brute_force_ones_each_once() {
        let mut rng = Rng::new(11);
        for round in 0..20 {
            let n = 50 + round * 10;
            let mut broad = BroadPhase::default();
            let mut boxes = Vec::new();
            let mut is_static = Vec::new();
            for id in 0..n {
                let b = random_box(&mut rng);
                let s = rng.unit() < 0.2;
                broad.add(id, Some(b), s);
                boxes.push(b);
                is_static.push(s);
            }
            let mut found = Vec::new();
            broad.find_pairs(|a, b| found.push((a.min(b), a.max(b))));
            let unique: BTreeSet<_> = found.iter().copied().collect();
            assert_eq!(unique.len(), found.len(), "a pair reported twice");
            assert_eq!(unique, oracle(&boxes, &is_static, &vec![true; n]));
            // Give a third of the moving bodies a new box; those that left
            // their fat box move (margin 0: to exactly the new box).
            let mut moved = vec![false; n];
            for id in 0..n {
                if !is_static[id] && rng.unit() < 0.33 {
                    let b = random_box(&mut rng);
                    moved[id] = !broad.fat_aabb(id).unwrap().contains(&b);
                    broad.update(id, &b, 0.0);
                }
            }
            let mut found = Vec::new();
            broad.find_pairs(|a, b| found.push((a.min(b), a.max(b))));
            let unique: BTreeSet<_> = found.iter().copied().collect();
            assert_eq!(unique.len(), found.len(), "a pair reported twice");
            // Every overlapping pair of the stored fat boxes that involves a
            // moved body, once.
            let fat: Vec<Aabb> = (0..n).map(|id| *broad.fat_aabb(id).unwrap()).collect();
            assert_eq!(unique, oracle(&fat, &is_static, &moved));
        }
    }

    #[test]
    fn a_column_of_a_thousand_boxes_has_a_pair_per_neighbour() {
        let mut broad = BroadPhase::default();
        broad.add(
            0,
            Some(Aabb::new(
                Vector2::new(-50.0, -1.0),
                Vector2::new(50.0, 0.0),
            )),
            true,
        );
        for i in 0..1000 {
            let y = i as f64;
            let b = Aabb::new(Vector2::new(-0.5, y), Vector2::new(0.5, y + 1.0)).loosened(0.02);
            broad.add(i + 1, Some(b.loosened(0.1)), false);
        }
        let mut count = 0;
        broad.find_pairs(|_, _| count += 1);
        // 999 neighbour pairs plus the bottom box on the ground: O(n).
        assert_eq!(count, 1000);
    }
}
