//! The soft step's broad phase: three dynamic AABB trees of enlarged
//! ("fat") boxes, one per kind of body (static, kinematic, dynamic; as
//! Box2D v3), and a move buffer of the bodies whose box left its fat box.
//! A moved dynamic body queries all three trees, a moved kinematic one the
//! dynamic tree only (static and kinematic bodies do not collide with each
//! other), so a few large kinematic bodies, such as the walls of a turning
//! container, do not bloat the boxes of the dynamic tree's nodes that
//! every query descends through.
//!
//! A body that moves less than the margin stays inside its fat box and costs
//! nothing here; only bodies in the move buffer are queried for new pairs
//! (seed §7.2–7.3 ask the collision system to keep few candidates; Box2D's
//! `broad_phase.c` and rapier's BVH do the same). Pairs persist as
//! [`super::contacts::Contact`]s until their fat boxes part, so the cost of
//! a resting pile is O(1) per body per step.
//!
//! A moving proxy that left its fat box is not reinserted: its leaf gets
//! the new fat box in place ([`DynamicTree::enlarge_proxy`]), and the
//! enlarged part of the dynamic and kinematic trees is rebuilt once before
//! the next queries
//! ([`DynamicTree::rebuild`]; Box2D v3's scheme). When hundreds of bodies
//! fall or fly, one binned-SAH rebuild costs much less than a removal and
//! a reinsertion each, and gives a tighter tree to query.
//!
//! The new pairs of one moved proxy are reported in increasing order of
//! the other proxy (not in the tree's order), so contacts are created in
//! an order that depends on the bodies' boxes only, never on the trees'
//! internal shape.

use crate::body::{BodyId, BodyKind};
use crate::collision::{Aabb, DynamicTree, ProxyId};

/// Which tree a proxy lives in: its body's kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Tree {
    Static,
    Kinematic,
    Dynamic,
}

/// The trees, the proxies of the bodies that have a shape, and the move
/// buffer.
#[derive(Debug, Default)]
pub(crate) struct BroadPhase {
    static_tree: DynamicTree,
    kinematic_tree: DynamicTree,
    dynamic_tree: DynamicTree,
    /// Per body: its tree and proxy, `None` without a shape.
    proxies: Vec<Option<(Tree, ProxyId)>>,
    /// Bodies whose proxy was created or moved since pairs were last found.
    moved: Vec<BodyId>,
    /// Per body: whether it is in `moved`.
    in_move_buffer: Vec<bool>,
    /// Per body: its fat box (a copy of its leaf's box, read by the
    /// collide stage for every contact), [`NO_BOX`] without a shape.
    fat: Vec<Aabb>,
    /// The overlaps found by one query, sorted before they are reported.
    hits: Vec<u32>,
}

/// The box of a body without a shape: it overlaps nothing.
const NO_BOX: Aabb = Aabb {
    min: nalgebra::Vector2::new(f64::INFINITY, f64::INFINITY),
    max: nalgebra::Vector2::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
};

impl BroadPhase {
    /// Registers body `id` (the next one), of kind `kind`, with its fat
    /// box, or none without a shape.
    pub(crate) fn add(&mut self, id: BodyId, fat: Option<Aabb>, kind: BodyKind) {
        debug_assert_eq!(id, self.proxies.len());
        let proxy = fat.map(|fat| {
            let tree = match kind {
                BodyKind::Static => Tree::Static,
                BodyKind::Kinematic => Tree::Kinematic,
                BodyKind::Dynamic => Tree::Dynamic,
            };
            let proxy = self.tree_mut(tree).create_proxy(fat, id as u32);
            (tree, proxy)
        });
        self.proxies.push(proxy);
        self.fat.push(fat.unwrap_or(NO_BOX));
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
        self.fat[id] = NO_BOX;
        if self.in_move_buffer[id] {
            self.moved.retain(|&b| b != id);
            self.in_move_buffer[id] = false;
        }
    }

    fn tree_mut(&mut self, tree: Tree) -> &mut DynamicTree {
        match tree {
            Tree::Static => &mut self.static_tree,
            Tree::Kinematic => &mut self.kinematic_tree,
            Tree::Dynamic => &mut self.dynamic_tree,
        }
    }

    fn buffer_move(&mut self, id: BodyId) {
        if !self.in_move_buffer[id] {
            self.in_move_buffer[id] = true;
            self.moved.push(id);
        }
    }

    /// Body `id`'s fat box, if it has a shape.
    #[cfg(test)]
    pub(crate) fn fat_aabb(&self, id: BodyId) -> Option<&Aabb> {
        self.proxies[id].map(|_| &self.fat[id])
    }

    /// Whether two bodies' fat boxes overlap (false if either has no
    /// shape).
    #[inline]
    pub(crate) fn fat_overlap(&self, a: BodyId, b: BodyId) -> bool {
        self.fat[a].overlaps(&self.fat[b])
    }

    /// Body `id` now has the (speculatively grown) box `aabb`: if it left
    /// its fat box, its fat box becomes `aabb` grown by `margin` (m) and the
    /// body joins the move buffer.
    pub(crate) fn update(&mut self, id: BodyId, aabb: &Aabb, margin: f64) {
        if self.fat[id].contains(aabb) {
            return;
        }
        let Some((tree, proxy)) = self.proxies[id] else {
            return;
        };
        let fat = aabb.loosened(margin);
        self.fat[id] = fat;
        match tree {
            Tree::Static => self.static_tree.move_proxy(proxy, fat),
            moving => self.tree_mut(moving).enlarge_proxy(proxy, fat),
        }
        self.buffer_move(id);
    }

    /// Calls `new_pair(a, b)` once for every pair with at least one body in
    /// the move buffer whose fat boxes overlap, then empties the buffer.
    /// Pairs of two moved bodies are reported once; the callback decides
    /// whether a pair is new and wanted. The moved bodies are taken in the
    /// buffer's order, and the other bodies of each in increasing order.
    pub(crate) fn find_pairs(&mut self, mut new_pair: impl FnMut(BodyId, BodyId)) {
        self.dynamic_tree.rebuild();
        self.kinematic_tree.rebuild();
        for i in 0..self.moved.len() {
            let id = self.moved[i];
            let Some((tree, _)) = self.proxies[id] else {
                continue;
            };
            let fat = self.fat[id];
            let in_buffer = &self.in_move_buffer;
            let hits = &mut self.hits;
            hits.clear();
            let mut visit = |_: ProxyId, other: u32| {
                let o = other as usize;
                // A pair of two moved bodies is reported by the lower id.
                if o != id && !(in_buffer[o] && o < id) {
                    hits.push(other);
                }
                true
            };
            self.dynamic_tree.query(&fat, &mut visit);
            if tree == Tree::Dynamic {
                self.kinematic_tree.query(&fat, &mut visit);
                self.static_tree.query(&fat, &mut visit);
            }
            hits.sort_unstable();
            for &other in hits.iter() {
                new_pair(id, other as usize);
            }
        }
        for &id in &self.moved {
            self.in_move_buffer[id] = false;
        }
        self.moved.clear();
    }

    /// Whether any static shape is registered.
    pub(crate) fn has_static(&self) -> bool {
        self.static_tree.proxy_count() > 0
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

    /// Pairs (lo, hi) with at least one dynamic body whose boxes overlap.
    fn oracle(boxes: &[Aabb], kinds: &[BodyKind], involving: &[bool]) -> BTreeSet<(usize, usize)> {
        let dynamic = |i: usize| kinds[i] == BodyKind::Dynamic;
        brute_force_pairs(boxes)
            .into_iter()
            .filter(|&(a, b)| dynamic(a) || dynamic(b))
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
            let mut kinds = Vec::new();
            for id in 0..n {
                let b = random_box(&mut rng);
                let kind = match rng.unit() {
                    u if u < 0.2 => BodyKind::Static,
                    u if u < 0.3 => BodyKind::Kinematic,
                    _ => BodyKind::Dynamic,
                };
                broad.add(id, Some(b), kind);
                boxes.push(b);
                kinds.push(kind);
            }
            let mut found = Vec::new();
            broad.find_pairs(|a, b| found.push((a.min(b), a.max(b))));
            let unique: BTreeSet<_> = found.iter().copied().collect();
            assert_eq!(unique.len(), found.len(), "a pair reported twice");
            assert_eq!(unique, oracle(&boxes, &kinds, &vec![true; n]));
            // Give a third of the moving bodies a new box; those that left
            // their fat box move (margin 0: to exactly the new box).
            let mut moved = vec![false; n];
            for id in 0..n {
                if kinds[id] != BodyKind::Static && rng.unit() < 0.33 {
                    let b = random_box(&mut rng);
                    moved[id] = !broad.fat_aabb(id).unwrap().contains(&b);
                    broad.update(id, &b, 0.0);
                }
            }
            let mut raw = Vec::new();
            broad.find_pairs(|a, b| raw.push((a, b)));
            // Each moved body's partners come in increasing order.
            for w in raw.windows(2) {
                assert!(w[0].0 != w[1].0 || w[0].1 < w[1].1, "{w:?} out of order");
            }
            let found: Vec<_> = raw.iter().map(|&(a, b)| (a.min(b), a.max(b))).collect();
            let unique: BTreeSet<_> = found.iter().copied().collect();
            assert_eq!(unique.len(), found.len(), "a pair reported twice");
            // Every overlapping pair of the stored fat boxes that involves a
            // moved body and a dynamic one, once.
            let fat: Vec<Aabb> = (0..n).map(|id| *broad.fat_aabb(id).unwrap()).collect();
            assert_eq!(unique, oracle(&fat, &kinds, &moved));
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
            BodyKind::Static,
        );
        for i in 0..1000 {
            let y = i as f64;
            let b = Aabb::new(Vector2::new(-0.5, y), Vector2::new(0.5, y + 1.0)).loosened(0.02);
            broad.add(i + 1, Some(b.loosened(0.1)), BodyKind::Dynamic);
        }
        let mut count = 0;
        broad.find_pairs(|_, _| count += 1);
        // 999 neighbour pairs plus the bottom box on the ground: O(n).
        assert_eq!(count, 1000);
    }
}
