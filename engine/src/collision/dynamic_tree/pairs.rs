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
//!
//! For several threads the walk is cut into pieces
//! ([`DynamicTree::split_moved_pairs`]): the top of the walk, down to a
//! fixed depth, is done once and leaves a list of node pairs whose walks,
//! joined in the list's order, report the pairs of the one walk in its
//! order, whoever walks each piece.

use super::{DynamicTree, NULL, ProxyId, overlap};

/// The walk's reused buffers.
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    /// Per node: a moved leaf is at or below it.
    marked: Vec<bool>,
    /// Pairs of nodes still to visit; `(n, n)` means "inside node n".
    stack: Vec<(u32, u32)>,
    /// The same for [`DynamicTree::split_moved_pairs`], with each pair's
    /// depth below the root pair.
    split_stack: Vec<(u32, u32, u32)>,
}

/// The depth (in node pairs below the root pair) at which
/// [`DynamicTree::split_moved_pairs`] stops descending and hands out a
/// piece: a constant, so the pieces do not depend on the thread count.
/// Seven levels give a few hundred pieces on a tree of thousands of
/// proxies, enough for any likely thread count to share evenly, for a
/// serial pre-walk of a few hundred node pairs.
const PIECE_DEPTH: u32 = 7;

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
        self.mark(moved, &mut s.marked);
        walk(
            self,
            &s.marked,
            (self.root, self.root),
            &mut s.stack,
            &mut report,
        );
        self.pair_scratch = s;
    }

    /// The walk of [`DynamicTree::moved_pairs`] cut into pieces, for
    /// several threads: marks the nodes above the `moved` proxies and
    /// fills `pieces` with pairs of nodes such that walking each piece with
    /// [`DynamicTree::moved_pairs_of_piece`], in the order of `pieces`,
    /// reports exactly the pairs of [`DynamicTree::moved_pairs`] in its
    /// order. The pieces depend only on the tree and `moved`.
    ///
    /// The split is the walk itself (depth first, a stack of node pairs)
    /// down to a fixed depth: a node pair popped there, or a pair of
    /// leaves above it, becomes the next piece instead of being walked.
    /// The walk reports everything below a popped pair before popping the
    /// next one, so the pieces' reports, joined in the order they were
    /// popped, are the walk's.
    ///
    /// # Panics
    /// If a proxy of `moved` is not a live proxy of this tree.
    pub fn split_moved_pairs(&mut self, moved: &[ProxyId], pieces: &mut Vec<(u32, u32)>) {
        pieces.clear();
        if self.root == NULL || moved.is_empty() {
            return;
        }
        let mut s = std::mem::take(&mut self.pair_scratch);
        self.mark(moved, &mut s.marked);
        let mut stack = std::mem::take(&mut s.split_stack);
        stack.clear();
        stack.push((self.root, self.root, 0));
        while let Some((a, b, depth)) = stack.pop() {
            if depth >= PIECE_DEPTH {
                pieces.push((a, b));
                continue;
            }
            match step(self, &s.marked, (a, b)) {
                Step::Skip => {}
                Step::Report => pieces.push((a, b)),
                Step::Inside([c0, c1]) => {
                    stack.push((c0, c1, depth + 1));
                    stack.push((c1, c1, depth + 1));
                    stack.push((c0, c0, depth + 1));
                }
                Step::SplitA([c0, c1]) => {
                    stack.push((c1, b, depth + 1));
                    stack.push((c0, b, depth + 1));
                }
                Step::SplitB([c0, c1]) => {
                    stack.push((a, c1, depth + 1));
                    stack.push((a, c0, depth + 1));
                }
            }
        }
        s.split_stack = stack;
        self.pair_scratch = s;
    }

    /// Reports the pairs below one piece of
    /// [`DynamicTree::split_moved_pairs`] (called last on this tree, which
    /// has not changed since), in the walk's order; `stack` is the
    /// caller's (one per thread), reused. Reads the tree only, so several
    /// threads can walk their pieces at once.
    pub fn moved_pairs_of_piece(
        &self,
        piece: (u32, u32),
        stack: &mut Vec<(u32, u32)>,
        mut report: impl FnMut(u32, u32),
    ) {
        walk(self, &self.pair_scratch.marked, piece, stack, &mut report);
    }

    /// Marks in `marked` every node with a `moved` leaf at or below it.
    fn mark(&self, moved: &[ProxyId], marked: &mut Vec<bool>) {
        marked.clear();
        marked.resize(self.nodes.len(), false);
        for &id in moved {
            let mut i = self.checked_leaf(id);
            while i != NULL && !marked[i as usize] {
                marked[i as usize] = true;
                i = self.nodes[i as usize].parent;
            }
        }
    }
}

/// What the walk does with a pair of nodes.
enum Step {
    /// Nothing below it to report.
    Skip,
    /// A pair of overlapping leaves, one moved: report it.
    Report,
    /// Inside one node: its children, each alone, and the two against
    /// each other.
    Inside([u32; 2]),
    /// Node `a`'s children against `b`.
    SplitA([u32; 2]),
    /// `a` against node `b`'s children.
    SplitB([u32; 2]),
}

/// The walk's rule for the node pair `(a, b)` (`a == b`: inside node a).
#[inline(always)]
fn step(tree: &DynamicTree, marked: &[bool], (a, b): (u32, u32)) -> Step {
    let (na, nb) = (&tree.nodes[a as usize], &tree.nodes[b as usize]);
    if a == b {
        if na.is_leaf() || !marked[a as usize] {
            return Step::Skip;
        }
        return Step::Inside(na.children);
    }
    if !(marked[a as usize] || marked[b as usize]) || !overlap(&na.aabb, &nb.aabb) {
        return Step::Skip;
    }
    match (na.is_leaf(), nb.is_leaf()) {
        (true, true) => Step::Report,
        // Split the internal one, or the larger of two.
        (true, false) => Step::SplitB(nb.children),
        (false, true) => Step::SplitA(na.children),
        (false, false) => {
            if na.aabb.perimeter() >= nb.aabb.perimeter() {
                Step::SplitA(na.children)
            } else {
                Step::SplitB(nb.children)
            }
        }
    }
}

/// Walks everything below the node pair `start`, depth first, reporting
/// the pairs of overlapping leaves with a marked one.
fn walk(
    tree: &DynamicTree,
    marked: &[bool],
    start: (u32, u32),
    stack: &mut Vec<(u32, u32)>,
    report: &mut impl FnMut(u32, u32),
) {
    stack.clear();
    stack.push(start);
    while let Some((a, b)) = stack.pop() {
        match step(tree, marked, (a, b)) {
            Step::Skip => {}
            Step::Report => report(
                tree.nodes[a as usize].user_data,
                tree.nodes[b as usize].user_data,
            ),
            Step::Inside([c0, c1]) => {
                stack.push((c0, c1));
                stack.push((c1, c1));
                stack.push((c0, c0));
            }
            Step::SplitA([c0, c1]) => {
                stack.push((c1, b));
                stack.push((c0, b));
            }
            Step::SplitB([c0, c1]) => {
                stack.push((a, c1));
                stack.push((a, c0));
            }
        }
    }
}
