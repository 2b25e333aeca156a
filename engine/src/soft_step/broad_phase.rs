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
//! fall or fly, one rebuild costs much less than a removal and a
//! reinsertion each, and gives a tighter tree to query.
//!
//! The new pairs are reported grouped by moved body, in the move buffer's
//! order, and within a group in the order the trees give them (spatially
//! coherent, deterministic). The contact order is the order the solver
//! colours and visits constraints in, and it matters: sorted by partner
//! id instead, the pairs of a pyramid built row by row were solved left to
//! right row after row, and the benchmark's 5050-box pyramid's top box
//! drifted 0.56 m sideways in 2 s instead of 0.010 m (and the 820-box one's
//! 3.5 cm instead of 0.6 mm).

use crate::body::{BodyId, BodyKind};
use crate::collision::{Aabb, DynamicTree, ProxyId};

/// Which tree a proxy lives in: its body's kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum Tree {
    Static,
    Kinematic,
    Dynamic,
}

/// The trees, the proxies of the bodies that have a shape, and the move
/// buffer.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct BroadPhase {
    static_tree: DynamicTree,
    kinematic_tree: DynamicTree,
    dynamic_tree: DynamicTree,
    /// Per body: its tree and proxy, `None` without a shape.
    proxies: Vec<Option<(Tree, ProxyId)>>,
    /// Bodies whose proxy was created or moved since pairs were last found.
    moved: Vec<BodyId>,
    /// Per body: its position in `moved`, [`NOT_MOVED`] if it is not
    /// there.
    move_position: Vec<u32>,
    /// Per body: its fat box (a copy of its leaf's box, read by the
    /// collide stage for every contact), [`NO_BOX`] without a shape.
    fat: Vec<Aabb>,
    /// Scratch of [`BroadPhase::find_pairs`]: the moved dynamic proxies,
    /// the pairs found as (position in `moved` of the body reporting it,
    /// other body), the start of each position's pairs, and the other
    /// bodies in reporting order.
    #[cfg_attr(feature = "serde", serde(skip))]
    moved_dynamic: Vec<ProxyId>,
    #[cfg_attr(feature = "serde", serde(skip))]
    found: Vec<(u32, u32)>,
    #[cfg_attr(feature = "serde", serde(skip))]
    starts: Vec<u32>,
    #[cfg_attr(feature = "serde", serde(skip))]
    ordered: Vec<u32>,
}

/// The move position of a body not in the move buffer.
const NOT_MOVED: u32 = u32::MAX;

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
        self.move_position.push(NOT_MOVED);
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
        if self.move_position[id] != NOT_MOVED {
            self.moved.retain(|&b| b != id);
            self.move_position[id] = NOT_MOVED;
            for (k, &b) in self.moved.iter().enumerate() {
                self.move_position[b] = k as u32;
            }
        }
    }

    /// Gives registered proxy `id` the fat box `fat` in the tree of
    /// `kind` (its body's kind changed, or it got its shape back), or none,
    /// and puts it in the move buffer so that its pairs are found again.
    pub(crate) fn replace(&mut self, id: BodyId, fat: Option<Aabb>, kind: BodyKind) {
        self.remove(id);
        if let Some(fat) = fat {
            let tree = match kind {
                BodyKind::Static => Tree::Static,
                BodyKind::Kinematic => Tree::Kinematic,
                BodyKind::Dynamic => Tree::Dynamic,
            };
            let proxy = self.tree_mut(tree).create_proxy(fat, id as u32);
            self.proxies[id] = Some((tree, proxy));
            self.fat[id] = fat;
            self.buffer_move(id);
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
        if self.move_position[id] == NOT_MOVED {
            self.move_position[id] = self.moved.len() as u32;
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

    /// Whether collider `id`'s fat box holds `aabb`: if so,
    /// [`BroadPhase::update`] with `aabb` does nothing.
    #[inline]
    pub(crate) fn fat_contains(&self, id: BodyId, aabb: &Aabb) -> bool {
        self.fat[id].contains(aabb)
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
    /// the move buffer whose fat boxes overlap (and one dynamic body), then
    /// empties the buffer. A pair of two moved bodies is reported by the
    /// lower id, as `new_pair(lower, higher)`; the callback decides whether
    /// a pair is new and wanted. The moved bodies are taken in the buffer's
    /// order, and the other bodies of each in the trees' order.
    ///
    /// The pairs of two dynamic bodies are found by one walk of the dynamic
    /// tree against itself ([`DynamicTree::moved_pairs`]), the others by
    /// querying the kinematic and static trees with each moved dynamic
    /// body, and the dynamic tree with each moved kinematic or static one.
    pub(crate) fn find_pairs(&mut self, mut new_pair: impl FnMut(BodyId, BodyId)) {
        self.dynamic_tree.rebuild();
        self.kinematic_tree.rebuild();
        if self.static_tree.leaves_changed() {
            self.static_tree.rebuild_all();
        }
        let position = &self.move_position;
        let found = &mut self.found;
        found.clear();
        // Who reports a pair: the moved one, or the lower of two moved.
        let mut add = |id: usize, other: usize| {
            let moved_other = position[other] != NOT_MOVED;
            if !(moved_other && other < id) {
                found.push((position[id], other as u32));
            }
        };
        self.moved_dynamic.clear();
        for &id in &self.moved {
            if let Some((Tree::Dynamic, proxy)) = self.proxies[id] {
                self.moved_dynamic.push(proxy);
            }
        }
        self.dynamic_tree.moved_pairs(&self.moved_dynamic, |x, y| {
            let (x, y) = (x as usize, y as usize);
            match (position[x] != NOT_MOVED, position[y] != NOT_MOVED) {
                (true, true) => add(x.min(y), x.max(y)),
                (true, false) => add(x, y),
                _ => add(y, x),
            }
        });
        for &id in &self.moved {
            let Some((tree, _)) = self.proxies[id] else {
                continue;
            };
            let mut visit = |_: ProxyId, other: u32| {
                add(id, other as usize);
                true
            };
            let fat = &self.fat[id];
            if tree == Tree::Dynamic {
                self.kinematic_tree.query(fat, &mut visit);
                self.static_tree.query(fat, &mut visit);
            } else {
                self.dynamic_tree.query(fat, &mut visit);
            }
        }
        // Group by reporting position (a stable counting sort).
        let n = self.moved.len();
        self.starts.clear();
        self.starts.resize(n + 1, 0);
        for &(k, _) in found.iter() {
            self.starts[k as usize + 1] += 1;
        }
        for k in 0..n {
            self.starts[k + 1] += self.starts[k];
        }
        self.ordered.clear();
        self.ordered.resize(found.len(), 0);
        for &(k, other) in found.iter() {
            let slot = &mut self.starts[k as usize];
            self.ordered[*slot as usize] = other;
            *slot += 1;
        }
        // `starts[k]` is now the end of group k, the start of group k + 1.
        let mut begin = 0;
        for k in 0..n {
            let end = self.starts[k] as usize;
            for &other in &self.ordered[begin..end] {
                new_pair(self.moved[k], other as usize);
            }
            begin = end;
        }
        for &id in &self.moved {
            self.move_position[id] = NOT_MOVED;
        }
        self.moved.clear();
    }

    /// The static, kinematic and dynamic trees, for world queries
    /// (module `query`); their leaves' user data are collider indices.
    pub(crate) fn trees(&self) -> [&DynamicTree; 3] {
        [&self.static_tree, &self.kinematic_tree, &self.dynamic_tree]
    }

    /// Whether any static shape is registered.
    pub(crate) fn has_static(&self) -> bool {
        self.static_tree.proxy_count() > 0
    }

    /// Calls `f(collider)` for every collider whose fat box overlaps `aabb`,
    /// in the static tree, then the kinematic tree, then the dynamic tree
    /// (each in its own order): a bullet's candidates (`bullets.rs`).
    pub(crate) fn query_all(&self, aabb: &Aabb, mut f: impl FnMut(BodyId)) {
        for tree in self.trees() {
            tree.query(aabb, |_, id| {
                f(id as usize);
                true
            });
        }
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
            // Each moved body's pairs come together.
            let mut done = BTreeSet::new();
            for w in raw.windows(2) {
                if w[0].0 != w[1].0 {
                    assert!(done.insert(w[0].0), "body {} reports twice", w[0].0);
                    assert!(!done.contains(&w[1].0), "body {} reports twice", w[1].0);
                }
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
