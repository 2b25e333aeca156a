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

use super::pool::{Pool, SharedSlice, Worker};
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
    /// the pieces of the dynamic tree's walk (on several threads), each
    /// thread's pairs found, the start of each position's pairs, and the
    /// other bodies in reporting order.
    #[cfg_attr(feature = "serde", serde(skip))]
    moved_dynamic: Vec<ProxyId>,
    #[cfg_attr(feature = "serde", serde(skip))]
    pieces: Vec<(u32, u32)>,
    #[cfg_attr(feature = "serde", serde(skip))]
    found: Vec<Found>,
    #[cfg_attr(feature = "serde", serde(skip))]
    starts: Vec<u32>,
    #[cfg_attr(feature = "serde", serde(skip))]
    ordered: Vec<u32>,
}

/// A body's tree and proxy, `None` without a shape.
type Proxy = Option<(Tree, ProxyId)>;

/// One thread's pairs of [`BroadPhase::find_pairs`], each as (position in
/// `moved` of the body reporting it, other body): those of the dynamic
/// tree's walk (its pieces, in order), then those of the queries of the
/// kinematic and static trees (its moved bodies, in order); and its walk
/// stack.
#[derive(Debug, Clone, Default)]
struct Found {
    walk: Vec<(u32, u32)>,
    query: Vec<(u32, u32)>,
    stack: Vec<(u32, u32)>,
}

/// Below this many moved bodies the pairs are found on the calling thread
/// alone (the same pairs in the same order): a job on the pool costs
/// about as much as walking and querying a few dozen bodies.
const MIN_MOVED_FOR_THREADS: usize = 64;

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
    ///
    /// With `pool` (and enough moved bodies), the walk is cut into pieces
    /// ([`DynamicTree::split_moved_pairs`]) and the moved bodies' queries
    /// into shares, each thread a contiguous share of both; each thread
    /// lists its pairs, and the lists are read in thread order, which is
    /// the pieces' and the moved bodies' order: the pairs found and their
    /// order are those of one thread, whatever the thread count. Only
    /// `new_pair` runs on the calling thread alone, in that order.
    pub(crate) fn find_pairs(
        &mut self,
        pool: Option<&Pool>,
        mut new_pair: impl FnMut(BodyId, BodyId),
    ) {
        self.dynamic_tree.rebuild();
        self.kinematic_tree.rebuild();
        if self.static_tree.leaves_changed() {
            self.static_tree.rebuild_all();
        }
        let pool = pool.filter(|_| self.moved.len() >= MIN_MOVED_FOR_THREADS);
        let threads = pool.map_or(1, Pool::threads);
        if self.found.len() < threads {
            self.found.resize_with(threads, Found::default);
        }
        self.moved_dynamic.clear();
        for &id in &self.moved {
            if let Some((Tree::Dynamic, proxy)) = self.proxies[id] {
                self.moved_dynamic.push(proxy);
            }
        }
        if let Some(pool) = pool {
            self.dynamic_tree
                .split_moved_pairs(&self.moved_dynamic, &mut self.pieces);
            // Out of `self` for the job, which reads the rest of it.
            let mut found = std::mem::take(&mut self.found);
            let lists = SharedSlice::new(&mut found[..threads]);
            let this = &*self;
            pool.run(&|w: &Worker<'_>| {
                // SAFETY: each thread its own list.
                let found = unsafe { lists.get_mut(w.index) };
                found.walk.clear();
                let (walk, stack) = (&mut found.walk, &mut found.stack);
                for &piece in &this.pieces[w.share(this.pieces.len())] {
                    this.dynamic_tree
                        .moved_pairs_of_piece(piece, stack, |x, y| this.walk_pair(walk, x, y));
                }
                found.query.clear();
                for &id in &this.moved[w.share(this.moved.len())] {
                    this.query_pairs(&mut found.query, id);
                }
            });
            self.found = found;
        } else {
            let found = &mut self.found[0];
            found.walk.clear();
            found.query.clear();
            let position = &self.move_position;
            let walk = &mut found.walk;
            self.dynamic_tree.moved_pairs(&self.moved_dynamic, |x, y| {
                pair_of_walk(position, walk, x, y);
            });
            for &id in &self.moved {
                Self::query_pairs_of(
                    (&self.proxies, &self.fat, position),
                    [&self.kinematic_tree, &self.static_tree, &self.dynamic_tree],
                    &mut found.query,
                    id,
                );
            }
        }
        // Every pair, in the one-thread order: the walk's, then the
        // queries'.
        let lists = &self.found[..threads];
        let all = || {
            let walk = lists.iter().flat_map(|f| f.walk.iter());
            walk.chain(lists.iter().flat_map(|f| f.query.iter()))
        };
        // Group by reporting position (a stable counting sort).
        let n = self.moved.len();
        self.starts.clear();
        self.starts.resize(n + 1, 0);
        for &(k, _) in all() {
            self.starts[k as usize + 1] += 1;
        }
        for k in 0..n {
            self.starts[k + 1] += self.starts[k];
        }
        self.ordered.clear();
        self.ordered.resize(self.starts[n] as usize, 0);
        for &(k, other) in all() {
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

    /// A pair `(x, y)` of the dynamic tree's walk into `found`.
    #[inline]
    fn walk_pair(&self, found: &mut Vec<(u32, u32)>, x: u32, y: u32) {
        pair_of_walk(&self.move_position, found, x, y);
    }

    /// The pairs of moved body `id` with the other trees into `found`.
    #[inline]
    fn query_pairs(&self, found: &mut Vec<(u32, u32)>, id: BodyId) {
        Self::query_pairs_of(
            (&self.proxies, &self.fat, &self.move_position),
            [&self.kinematic_tree, &self.static_tree, &self.dynamic_tree],
            found,
            id,
        );
    }

    /// The pairs of moved body `id` found by querying the trees other than
    /// its own: a dynamic body the kinematic and static trees, the others
    /// the dynamic tree.
    #[inline]
    fn query_pairs_of(
        (proxies, fat, position): (&[Proxy], &[Aabb], &[u32]),
        [kinematic, fixed, dynamic]: [&DynamicTree; 3],
        found: &mut Vec<(u32, u32)>,
        id: BodyId,
    ) {
        let Some((tree, _)) = proxies[id] else {
            return;
        };
        let mut visit = |_: ProxyId, other: u32| {
            add(position, found, id, other as usize);
            true
        };
        let fat = &fat[id];
        if tree == Tree::Dynamic {
            kinematic.query(fat, &mut visit);
            fixed.query(fat, &mut visit);
        } else {
            dynamic.query(fat, &mut visit);
        }
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

/// Lists the pair of moved body `id` and `other` unless `other` moved too
/// and has the lower id (then it reports the pair), as (position of the
/// reporting body in the move buffer, other body).
#[inline(always)]
fn add(position: &[u32], found: &mut Vec<(u32, u32)>, id: usize, other: usize) {
    let moved_other = position[other] != NOT_MOVED;
    if !(moved_other && other < id) {
        found.push((position[id], other as u32));
    }
}

/// Lists a pair of the dynamic tree's walk (user data `x`, `y`, at least
/// one moved), reported by the moved one, or the lower of two moved.
#[inline(always)]
fn pair_of_walk(position: &[u32], found: &mut Vec<(u32, u32)>, x: u32, y: u32) {
    let (x, y) = (x as usize, y as usize);
    match (position[x] != NOT_MOVED, position[y] != NOT_MOVED) {
        (true, true) => add(position, found, x.min(y), x.max(y)),
        (true, false) => add(position, found, x, y),
        _ => add(position, found, y, x),
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
            broad.find_pairs(None, |a, b| found.push((a.min(b), a.max(b))));
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
            broad.find_pairs(None, |a, b| raw.push((a, b)));
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
    fn the_pairs_and_their_order_are_the_same_on_one_two_and_three_threads() {
        // 600 bodies (a tenth static, a tenth kinematic), every one in the
        // move buffer at first, then a third of the moving ones moved: the
        // pairs, in order, of the calling thread alone and of pools of 1,
        // 2 and 3 threads (both above MIN_MOVED_FOR_THREADS moved bodies).
        let mut rng = Rng::new(0x21C);
        let n = 600;
        let mut broad = BroadPhase::default();
        let mut kinds = Vec::new();
        for id in 0..n {
            let kind = match rng.unit() {
                u if u < 0.1 => BodyKind::Static,
                u if u < 0.2 => BodyKind::Kinematic,
                _ => BodyKind::Dynamic,
            };
            broad.add(id, Some(random_box(&mut rng)), kind);
            kinds.push(kind);
        }
        let pools: Vec<Pool> = (1..=3).map(Pool::new).collect();
        for round in 0..3 {
            assert!(broad.moved.len() >= MIN_MOVED_FOR_THREADS, "round {round}");
            let mut alone = Vec::new();
            broad.clone().find_pairs(None, |a, b| alone.push((a, b)));
            assert!(alone.len() > 100, "round {round}: {} pairs", alone.len());
            for pool in &pools {
                let mut threaded = Vec::new();
                broad
                    .clone()
                    .find_pairs(Some(pool), |a, b| threaded.push((a, b)));
                assert_eq!(threaded, alone, "round {round}, {} threads", pool.threads());
            }
            broad.find_pairs(None, |_, _| {});
            for (id, &kind) in kinds.iter().enumerate() {
                if kind != BodyKind::Static && rng.unit() < 0.33 {
                    broad.update(id, &random_box(&mut rng), 0.0);
                }
            }
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
        broad.find_pairs(None, |_, _| count += 1);
        // 999 neighbour pairs plus the bottom box on the ground: O(n).
        assert_eq!(count, 1000);
    }
}
