//! The overlapping pairs of a [`DynamicTree`]'s own proxies that involve
//! at least one given ("moved") proxy, each pair once, by one descent of
//! the tree against itself (own code; the classic self-collision walk of a
//! bounding-volume hierarchy).
//!
//! Querying the tree once per moved proxy finds a pair of two moved
//! proxies twice (once from each) and walks the top of the tree again for
//! every query. The walk here visits pairs of nodes instead: a node's two
//! children are tested against each other, and against a node they
//! overlap the larger of the two is split, down to pairs of leaves. Nodes
//! are marked when a moved leaf lies below them, and a pair of unmarked
//! nodes is skipped: only pairs with a moved proxy are reported. When most
//! proxies moved (a tumbling or exploding pile), this does about half the
//! work of the queries; when few did, about the same.

use super::{DynamicTree, NULL, ProxyId, overlap};

/// The walk's reused buffers.
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    /// Per node: a moved leaf is at or below it.
    marked: Vec<bool>,
    /// Pairs of nodes still to visit; `(n, n)` means "inside node n".
    stack: Vec<(u32, u32)>,
}

impl DynamicTree {
    /// Calls `report(a, b)` (user data) once for every unordered pair of
    /// distinct proxies of this tree whose fat boxes overlap and of which
    /// at least one is in `moved`, in an order fixed by the tree's shape.
    /// Allocates nothing once its buffers have grown to the tree's size.
    ///
    /// # Panics
    /// If a proxy of `moved` is not a live proxy of this tree.
    pub fn moved_pairs(&mut self, moved: &[ProxyId], mut report: impl FnMut(u32, u32)) {
        if self.root == NULL || moved.is_empty() {
            return;
        }
        let mut s = std::mem::take(&mut self.pair_scratch);
        s.marked.clear();
        s.marked.resize(self.nodes.len(), false);
        for &id in moved {
            let mut i = self.checked_leaf(id);
            while i != NULL && !s.marked[i as usize] {
                s.marked[i as usize] = true;
                i = self.nodes[i as usize].parent;
            }
        }
        s.stack.clear();
        s.stack.push((self.root, self.root));
        while let Some((a, b)) = s.stack.pop() {
            let (na, nb) = (&self.nodes[a as usize], &self.nodes[b as usize]);
            if a == b {
                // Inside one node: each child, and the two against each
                // other.
                if na.is_leaf() || !s.marked[a as usize] {
                    continue;
                }
                let [c0, c1] = na.children;
                s.stack.push((c0, c1));
                s.stack.push((c1, c1));
                s.stack.push((c0, c0));
                continue;
            }
            if !(s.marked[a as usize] || s.marked[b as usize]) || !overlap(&na.aabb, &nb.aabb) {
                continue;
            }
            match (na.is_leaf(), nb.is_leaf()) {
                (true, true) => report(na.user_data, nb.user_data),
                // Split the internal one, or the larger of two.
                (true, false) => {
                    let [c0, c1] = nb.children;
                    s.stack.push((a, c1));
                    s.stack.push((a, c0));
                }
                (false, true) => {
                    let [c0, c1] = na.children;
                    s.stack.push((c1, b));
                    s.stack.push((c0, b));
                }
                (false, false) => {
                    if na.aabb.perimeter() >= nb.aabb.perimeter() {
                        let [c0, c1] = na.children;
                        s.stack.push((c1, b));
                        s.stack.push((c0, b));
                    } else {
                        let [c0, c1] = nb.children;
                        s.stack.push((a, c1));
                        s.stack.push((a, c0));
                    }
                }
            }
        }
        self.pair_scratch = s;
    }
}
