//! Dynamic AABB tree: the incremental broad phase for scenes of thousands of
//! bodies (after the dynamic trees of Box2D and rapier; own code).
//!
//! Each proxy (one shape of one body) is a leaf holding a *fat* box: its
//! tight box enlarged by a margin (m) chosen by the caller. While the shape
//! stays inside its fat box nothing in the tree changes; only a proxy whose
//! tight box left its fat box is moved (removed and reinserted with a new
//! fat box) and re-queried. Each internal node holds the union of its two
//! children's boxes, so a query descends only into subtrees whose box
//! overlaps the query box.
//!
//! **Insertion** picks the sibling of the new leaf by the surface-area
//! heuristic, whose 2D form is the perimeter: the cost of a tree is the sum
//! of the perimeters of its internal nodes, and the new leaf goes where the
//! added cost (the new parent's perimeter plus the growth of every
//! ancestor) is smallest. The search descends greedily and stops when a
//! lower bound on everything below exceeds the best cost found so far.
//!
//! **Balancing**: walking from the new (or removed) leaf up to the root,
//! every node whose children's heights differ by more than one is rotated:
//! its taller child moves up and takes its place, keeping its own taller
//! child and handing the shorter one down (one AVL-like rotation). Bodies
//! inserted in order, as in a column or a pyramid built row by row, would
//! otherwise give a tree of height O(n); with the rotations the height stays
//! O(log n) (tested: a column of 1000 boxes inserted bottom-to-top).
//!
//! **Enlarging in place**: when many proxies move every step, removing and
//! reinserting each is the dominant cost. [`DynamicTree::enlarge_proxy`]
//! instead gives the leaf its new box and only grows its ancestors
//! (marking them); [`DynamicTree::rebuild`] then regroups the marked part
//! of the tree once, top-down (the private module `rebuild` has the
//! method). Between the two, queries are exact but visit more nodes.
//!
//! **Memory**: the nodes live in one `Vec` with a free list. A tree of n
//! proxies uses 2n − 1 nodes, and a destroyed node is reused first, so once
//! the proxy count has peaked, creating, destroying and moving proxies
//! allocates nothing. A query allocates nothing either: it walks the tree
//! with a fixed stack array ([`QUERY_STACK_CAPACITY`] entries, far above
//! the depth of a balanced tree) and continues recursively if that were
//! ever exceeded, so the answer is always complete.
//!
//! **Determinism**: no hashing and no randomness; the same sequence of
//! operations gives the same tree, the same [`ProxyId`]s and the same order
//! of query callbacks.
//!
//! Boxes follow [`Aabb`]'s conventions: closed (touching boxes overlap),
//! and a box holding a NaN overlaps nothing, so such a proxy is stored but
//! never reported (unions ignore NaN coordinates, see [`Aabb::merged`]).
//!
//! The candidate pairs of a step are found by querying the tree with the
//! fat box of each proxy that moved; a pair of two moved proxies is found
//! twice and is kept once, e.g. from the proxy with the smaller id.
//!
//! ```
//! use etalon2d::validation::collision::{Aabb, DynamicTree};
//! use nalgebra::Vector2;
//! let unit = |x: f64, y: f64| Aabb::new(Vector2::new(x, y), Vector2::new(x + 1.0, y + 1.0));
//! let margin = 0.1; // m
//! let mut tree = DynamicTree::new();
//! let a = tree.create_proxy(unit(0.0, 0.0).loosened(margin), 7);
//! let _b = tree.create_proxy(unit(5.0, 0.0).loosened(margin), 8);
//! let mut hits = Vec::new();
//! tree.query(&unit(0.5, 0.5), |_, data| {
//!     hits.push(data);
//!     true // keep going
//! });
//! assert_eq!(hits, vec![7]);
//! // Body 7 moved out of its fat box: give it a new one.
//! tree.move_proxy(a, unit(4.5, 0.0).loosened(margin));
//! assert_eq!(tree.fat_aabb(a).min.x, 4.4);
//! ```

use super::aabb::Aabb;

/// The depth of the fixed stack a query walks the tree with: a walk holds
/// at most one entry per level plus one, and a balanced tree of a billion
/// proxies is about 45 levels deep; a deeper walk continues recursively
/// rather than failing. (256 entries cost 12 % of the soft step's queries
/// in filling the array.)
pub const QUERY_STACK_CAPACITY: usize = 64;

/// Marks "no node": the root's parent, a leaf's children, the free list's
/// end, the empty tree's root.
const NULL: u32 = u32::MAX;

/// The handle of one proxy (a leaf of a [`DynamicTree`]). It stays valid
/// until the proxy is destroyed; after that the tree may hand out the same
/// id to a new proxy.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ProxyId(u32);

impl ProxyId {
    /// A small integer identifying the proxy, below twice the largest number
    /// of proxies the tree has held at once: usable to index a side table.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// One node of the tree: a leaf (a proxy), an internal node, or a free slot.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Node {
    /// Leaf: the proxy's fat box; internal node: the union of its two
    /// children's boxes (m).
    aabb: Aabb,
    /// The parent node, `NULL` at the root. In a free node: the next free
    /// node, `NULL` at the end of the free list.
    parent: u32,
    /// The two children of an internal node; both `NULL` in a leaf or a
    /// free node.
    children: [u32; 2],
    /// The number of edges from this node down to its deepest leaf (0 for
    /// a leaf).
    height: u32,
    /// The caller's tag of a leaf (unused elsewhere).
    user_data: u32,
    /// False while the node is in the free list.
    in_use: bool,
    /// Internal node: a leaf below it was enlarged in place
    /// ([`DynamicTree::enlarge_proxy`]) since the last
    /// [`DynamicTree::rebuild`], so its box may be larger than its
    /// children's union and its subtree is rebuilt. Never set on a leaf.
    enlarged: bool,
}

impl Node {
    fn is_leaf(&self) -> bool {
        self.children[0] == NULL
    }
}

/// A dynamic bounding-volume tree over fat boxes (m); see the [module
/// documentation](self) for the method.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DynamicTree {
    /// The node pool: leaves, internal nodes and free slots.
    nodes: Vec<Node>,
    /// The root node, `NULL` when the tree is empty.
    root: u32,
    /// The first free node, `NULL` when the pool is full.
    free_list: u32,
    /// The number of leaves.
    proxy_count: usize,
    /// A proxy was created, destroyed, moved or enlarged since the last
    /// [`DynamicTree::rebuild_all`] (or since the tree was made). Written
    /// with the tree, so a restored tree rebuilds when the original does.
    #[cfg_attr(feature = "serde", serde(default))]
    leaves_changed: bool,
    /// Reused buffers of [`DynamicTree::rebuild`].
    #[cfg_attr(feature = "serde", serde(skip))]
    scratch: rebuild::Scratch,
    /// Reused buffers of [`DynamicTree::moved_pairs`].
    #[cfg_attr(feature = "serde", serde(skip))]
    pair_scratch: pairs::Scratch,
}

impl Default for DynamicTree {
    fn default() -> Self {
        Self::new()
    }
}

impl DynamicTree {
    /// An empty tree. It allocates nothing until the first proxy.
    pub fn new() -> Self {
        Self {
            nodes: Vec::new(),
            root: NULL,
            free_list: NULL,
            proxy_count: 0,
            leaves_changed: false,
            scratch: rebuild::Scratch::default(),
            pair_scratch: pairs::Scratch::default(),
        }
    }

    /// Inserts a proxy with the box `fat_aabb` (m), already enlarged by the
    /// caller's margin, tagged with `user_data` (e.g. a collider index).
    /// O(log n) for a balanced tree.
    pub fn create_proxy(&mut self, fat_aabb: Aabb, user_data: u32) -> ProxyId {
        let leaf = self.allocate_node();
        let node = &mut self.nodes[leaf as usize];
        node.aabb = fat_aabb;
        node.user_data = user_data;
        self.insert_leaf(leaf);
        self.proxy_count += 1;
        self.leaves_changed = true;
        ProxyId(leaf)
    }

    /// Removes a proxy; its id may later be reused.
    ///
    /// # Panics
    /// If `id` is not a live proxy of this tree (a programming error, such
    /// as destroying a proxy twice).
    pub fn destroy_proxy(&mut self, id: ProxyId) {
        let leaf = self.checked_leaf(id);
        self.remove_leaf(leaf);
        self.free_node(leaf);
        self.proxy_count -= 1;
        self.leaves_changed = true;
    }

    /// Gives a proxy the new fat box `fat_aabb` (m): the leaf is removed and
    /// reinserted where the heuristic now places it. Its id and user data
    /// are kept. Call it only for a proxy whose shape left its fat box; a
    /// proxy that stays inside costs nothing.
    ///
    /// # Panics
    /// If `id` is not a live proxy of this tree.
    pub fn move_proxy(&mut self, id: ProxyId, fat_aabb: Aabb) {
        let leaf = self.checked_leaf(id);
        self.remove_leaf(leaf);
        self.nodes[leaf as usize].aabb = fat_aabb;
        self.insert_leaf(leaf);
        self.leaves_changed = true;
    }

    /// Gives a proxy the new fat box `fat_aabb` (m) in place, without
    /// moving its leaf: every ancestor grows to contain the new box and is
    /// marked for the next [`DynamicTree::rebuild`], which restructures the
    /// marked part of the tree once for all the proxies enlarged since
    /// (Box2D v3's scheme: cheaper than a removal and reinsertion per
    /// proxy when many move). Until then queries stay exact (a marked box
    /// only contains more) but visit more nodes. O(depth).
    ///
    /// # Panics
    /// If `id` is not a live proxy of this tree.
    pub fn enlarge_proxy(&mut self, id: ProxyId, fat_aabb: Aabb) {
        let leaf = self.checked_leaf(id);
        self.nodes[leaf as usize].aabb = fat_aabb;
        self.leaves_changed = true;
        let mut i = self.nodes[leaf as usize].parent;
        // Grow the ancestors until one already holds the box; above it only
        // the marks are missing, up to the first ancestor already marked
        // (whose own ancestors are marked too).
        let mut growing = true;
        while i != NULL {
            let node = &mut self.nodes[i as usize];
            if growing {
                let grown = node.aabb.merged(&fat_aabb);
                growing = grown != node.aabb;
                node.aabb = grown;
            } else if node.enlarged {
                break;
            }
            node.enlarged = true;
            i = node.parent;
        }
    }

    /// Rebuilds the part of the tree marked by [`DynamicTree::enlarge_proxy`]
    /// since the last rebuild: the unmarked subtrees and the leaves under
    /// the marked nodes are regrouped top-down, each group split at the
    /// middle of its box centres along their longer side (Box2D v3's median
    /// split), and every box is exact again. Proxy
    /// ids and user data are kept. Nothing to do, and O(1), when no proxy
    /// was enlarged; allocates nothing once its buffers have grown to the
    /// tree's size.
    pub fn rebuild(&mut self) {
        rebuild::rebuild(self);
    }

    /// Rebuilds the whole tree top-down by the surface-area heuristic, for
    /// a tree queried much more often than it changes (the soft step's
    /// static tree, rebuilt before the pairs of a step in which it
    /// changed; its world queries test about a third of the boxes of the
    /// incrementally built tree). Each range of leaves is sorted by box
    /// centre along x and along y, and split where the sum of the two
    /// parts' perimeters, each times its leaf count, is least. The shape
    /// depends only on the leaves (boxes and proxy ids), not on the order
    /// they were inserted in: ties are broken by proxy id. Proxy ids and
    /// user data are kept, the node pool does not grow, and every box is
    /// exact. O(n log² n); allocates nothing once its buffers have grown to
    /// the tree's size. Clears [`DynamicTree::leaves_changed`].
    pub fn rebuild_all(&mut self) {
        rebuild::rebuild_all(self);
    }

    /// Whether a proxy was created, destroyed, moved or enlarged since the
    /// last [`DynamicTree::rebuild_all`] (true for a new tree that has had
    /// proxies created and not yet been rebuilt).
    pub fn leaves_changed(&self) -> bool {
        self.leaves_changed
    }

    /// The fat box (m) of a proxy, as last given to
    /// [`DynamicTree::create_proxy`], [`DynamicTree::move_proxy`] or
    /// [`DynamicTree::enlarge_proxy`].
    ///
    /// # Panics
    /// If `id` is not a live proxy of this tree.
    pub fn fat_aabb(&self, id: ProxyId) -> &Aabb {
        &self.nodes[self.checked_leaf(id) as usize].aabb
    }

    /// The user data a proxy was created with.
    ///
    /// # Panics
    /// If `id` is not a live proxy of this tree.
    pub fn user_data(&self, id: ProxyId) -> u32 {
        self.nodes[self.checked_leaf(id) as usize].user_data
    }

    /// The number of proxies (leaves).
    pub fn proxy_count(&self) -> usize {
        self.proxy_count
    }

    /// The number of edges from the root to the deepest leaf: 0 for an
    /// empty tree or a single proxy, about log2(n) for a balanced tree.
    pub fn height(&self) -> usize {
        if self.root == NULL {
            0
        } else {
            self.nodes[self.root as usize].height as usize
        }
    }

    /// Calls `callback(id, user_data)` for every proxy whose fat box
    /// overlaps `aabb` (closed boxes: touching counts), in an order fixed by
    /// the tree's shape. The callback returns `false` to stop the query
    /// early. Allocates nothing.
    pub fn query(&self, aabb: &Aabb, mut callback: impl FnMut(ProxyId, u32) -> bool) {
        self.query_with_stack::<QUERY_STACK_CAPACITY>(aabb, &mut callback);
    }

    /// Checks the tree's invariants and describes the first one broken:
    /// parent and child links agree, every node is reached once from the
    /// root or sits in the free list (no leak, no cycle), free nodes are
    /// marked free, a leaf has height 0 and an internal node one more than
    /// its taller child, each internal box is exactly the union of its
    /// children's boxes (contains it, for a node marked by
    /// [`DynamicTree::enlarge_proxy`]), no leaf is marked, and the leaf
    /// count matches
    /// [`DynamicTree::proxy_count`]. O(n) and allocating: for tests.
    pub fn validate(&self) -> Result<(), String> {
        let n = self.nodes.len();
        let mut seen = vec![false; n];
        let mut free_count = 0;
        let mut i = self.free_list;
        while i != NULL {
            let node = self
                .nodes
                .get(i as usize)
                .ok_or(format!("free list points outside the pool: {i}"))?;
            if seen[i as usize] {
                return Err(format!("free list cycles at node {i}"));
            }
            seen[i as usize] = true;
            if node.in_use {
                return Err(format!("node {i} is in the free list but in use"));
            }
            free_count += 1;
            i = node.parent;
        }

        let mut leaves = 0;
        let mut stack = Vec::new();
        if self.root != NULL {
            let root = self
                .nodes
                .get(self.root as usize)
                .ok_or(format!("root outside the pool: {}", self.root))?;
            if root.parent != NULL {
                return Err(format!("root {} has parent {}", self.root, root.parent));
            }
            stack.push(self.root);
        }
        while let Some(i) = stack.pop() {
            let node = &self.nodes[i as usize];
            if seen[i as usize] {
                return Err(format!("node {i} is reached twice"));
            }
            seen[i as usize] = true;
            if !node.in_use {
                return Err(format!("free node {i} is in the tree"));
            }
            let [c0, c1] = node.children;
            if c0 == NULL && c1 == NULL {
                if node.height != 0 {
                    return Err(format!("leaf {i} has height {}", node.height));
                }
                if node.enlarged {
                    return Err(format!("leaf {i} is marked enlarged"));
                }
                leaves += 1;
                continue;
            }
            if c0 == NULL || c1 == NULL || c0 as usize >= n || c1 as usize >= n {
                return Err(format!("node {i} has children {c0}, {c1}"));
            }
            let (a, b) = (&self.nodes[c0 as usize], &self.nodes[c1 as usize]);
            if a.parent != i || b.parent != i {
                return Err(format!("a child of node {i} has another parent"));
            }
            if node.height != 1 + a.height.max(b.height) {
                return Err(format!("node {i} has a wrong height {}", node.height));
            }
            let union = a.aabb.merged(&b.aabb);
            if node.enlarged {
                if !node.aabb.contains(&union) && !same_box(&node.aabb, &union) {
                    return Err(format!("the box of node {i} does not hold its children's"));
                }
            } else if !same_box(&node.aabb, &union) {
                return Err(format!("the box of node {i} is not its children's union"));
            }
            stack.push(c0);
            stack.push(c1);
        }
        if leaves != self.proxy_count {
            return Err(format!(
                "{leaves} leaves but a proxy count of {}",
                self.proxy_count
            ));
        }
        let reached = seen.iter().filter(|&&s| s).count();
        if reached != n {
            return Err(format!(
                "{} nodes are neither in the tree nor free ({free_count} free)",
                n - reached
            ));
        }
        Ok(())
    }

    /// The query with a stack of `N` entries; a child that does not fit is
    /// searched recursively. Returns false if the callback stopped it.
    fn query_with_stack<const N: usize>(
        &self,
        aabb: &Aabb,
        callback: &mut impl FnMut(ProxyId, u32) -> bool,
    ) -> bool {
        if self.root == NULL || N == 0 {
            return self.root == NULL || self.query_recursive(self.root, aabb, callback);
        }
        if !self.nodes[self.root as usize].aabb.overlaps(aabb) {
            return true;
        }
        // The stack holds nodes whose box overlaps the query. Each child is
        // written on top of the stack and kept there only if it overlaps
        // (the test's result moves the top, without a branch: whether a
        // box overlaps is what a processor predicts worst, and the
        // mispredictions were most of the queries' time).
        let mut stack = [NULL; N];
        stack[0] = self.root;
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let i = stack[len];
            let node = &self.nodes[i as usize];
            if node.is_leaf() {
                if !callback(ProxyId(i), node.user_data) {
                    return false;
                }
                continue;
            }
            for child in node.children {
                let overlaps = overlap(&self.nodes[child as usize].aabb, aabb);
                if len < N {
                    stack[len] = child;
                    len += usize::from(overlaps);
                } else if overlaps && !self.query_recursive(child, aabb, callback) {
                    return false;
                }
            }
        }
        true
    }

    /// The fallback of [`DynamicTree::query_with_stack`]: a recursive walk
    /// of the subtree at `i`. Returns false if the callback stopped it.
    fn query_recursive(
        &self,
        i: u32,
        aabb: &Aabb,
        callback: &mut impl FnMut(ProxyId, u32) -> bool,
    ) -> bool {
        let node = &self.nodes[i as usize];
        if !node.aabb.overlaps(aabb) {
            true
        } else if node.is_leaf() {
            callback(ProxyId(i), node.user_data)
        } else {
            self.query_recursive(node.children[0], aabb, callback)
                && self.query_recursive(node.children[1], aabb, callback)
        }
    }

    /// The node of a live proxy, or a panic naming the misuse.
    fn checked_leaf(&self, id: ProxyId) -> u32 {
        match self.nodes.get(id.index()) {
            Some(node) if node.in_use && node.is_leaf() => id.0,
            _ => panic!("{id:?} is not a live proxy of this tree"),
        }
    }

    /// A detached node from the free list, or a new one at the pool's end.
    fn allocate_node(&mut self) -> u32 {
        let fresh = Node {
            aabb: Aabb::new(Default::default(), Default::default()),
            parent: NULL,
            children: [NULL, NULL],
            height: 0,
            user_data: 0,
            in_use: true,
            enlarged: false,
        };
        if self.free_list != NULL {
            let i = self.free_list;
            self.free_list = self.nodes[i as usize].parent;
            self.nodes[i as usize] = fresh;
            i
        } else {
            let i = u32::try_from(self.nodes.len())
                .ok()
                .filter(|&i| i != NULL)
                .expect("a dynamic tree holds at most 2^32 - 1 nodes");
            self.nodes.push(fresh);
            i
        }
    }

    /// Puts a detached node at the head of the free list.
    fn free_node(&mut self, i: u32) {
        let node = &mut self.nodes[i as usize];
        node.in_use = false;
        node.children = [NULL, NULL];
        node.height = 0;
        node.enlarged = false;
        node.parent = self.free_list;
        self.free_list = i;
    }

    /// Links the detached leaf `leaf` into the tree next to the best
    /// sibling, then refits and balances its ancestors.
    fn insert_leaf(&mut self, leaf: u32) {
        if self.root == NULL {
            self.root = leaf;
            self.nodes[leaf as usize].parent = NULL;
            return;
        }
        let leaf_box = self.nodes[leaf as usize].aabb;
        let sibling = self.best_sibling(&leaf_box);
        let old_parent = self.nodes[sibling as usize].parent;

        let new_parent = self.allocate_node();
        let sibling_node = &self.nodes[sibling as usize];
        let node = Node {
            aabb: sibling_node.aabb.merged(&leaf_box),
            parent: old_parent,
            children: [sibling, leaf],
            height: sibling_node.height + 1,
            user_data: 0,
            in_use: true,
            enlarged: false,
        };
        self.nodes[new_parent as usize] = node;
        self.replace_child(old_parent, sibling, new_parent);
        self.nodes[sibling as usize].parent = new_parent;
        self.nodes[leaf as usize].parent = new_parent;

        // From the new parent: it is unbalanced if the sibling is tall.
        self.refit_to_root(new_parent);
    }

    /// The node the new leaf should be paired with: the one minimising the
    /// perimeter of the new parent plus the perimeter growth of all its
    /// ancestors. Descends greedily into the child with the lower bound,
    /// and stops when no child's lower bound beats the best cost so far.
    fn best_sibling(&self, leaf_box: &Aabb) -> u32 {
        let leaf_perimeter = leaf_box.perimeter();
        let mut best = self.root;
        let mut best_cost = self.nodes[best as usize].aabb.merged(leaf_box).perimeter();
        // The perimeter growth of the current node and all its ancestors if
        // the leaf is placed below the current node.
        let mut inherited = 0.0;
        let mut index = self.root;
        while !self.nodes[index as usize].is_leaf() {
            let node = &self.nodes[index as usize];
            inherited += node.aabb.merged(leaf_box).perimeter() - node.aabb.perimeter();
            let mut lower_bound = [f64::INFINITY; 2];
            for (k, &c) in node.children.iter().enumerate() {
                let child = &self.nodes[c as usize];
                let combined = child.aabb.merged(leaf_box).perimeter();
                // Pairing with this child: a new parent of perimeter
                // `combined`, plus the growth above it.
                let direct = combined + inherited;
                if direct < best_cost {
                    best_cost = direct;
                    best = c;
                }
                if !child.is_leaf() {
                    // Anywhere below it: the child grows, and the new parent
                    // is at least as long as the leaf's perimeter.
                    lower_bound[k] =
                        inherited + (combined - child.aabb.perimeter()) + leaf_perimeter;
                }
            }
            let k = usize::from(lower_bound[1] < lower_bound[0]);
            // A NaN bound (from infinite boxes) compares false and stops
            // the descent, as a bound no better than the best does.
            let may_improve = lower_bound[k] < best_cost;
            if !may_improve {
                break;
            }
            index = node.children[k];
        }
        best
    }

    /// Unlinks `leaf` (left detached, not freed): its parent is freed and its
    /// sibling takes the parent's place; the ancestors are refitted and
    /// balanced.
    fn remove_leaf(&mut self, leaf: u32) {
        if leaf == self.root {
            self.root = NULL;
            return;
        }
        let parent = self.nodes[leaf as usize].parent;
        let [c0, c1] = self.nodes[parent as usize].children;
        let sibling = if c0 == leaf { c1 } else { c0 };
        let grandparent = self.nodes[parent as usize].parent;
        self.replace_child(grandparent, parent, sibling);
        self.nodes[sibling as usize].parent = grandparent;
        self.nodes[leaf as usize].parent = NULL;
        self.free_node(parent);
        self.refit_to_root(grandparent);
    }

    /// Makes `new` the child of `parent` in place of `old`, or the root if
    /// `parent` is `NULL`. The caller sets `new`'s parent link.
    fn replace_child(&mut self, parent: u32, old: u32, new: u32) {
        if parent == NULL {
            self.root = new;
        } else {
            let children = &mut self.nodes[parent as usize].children;
            let k = usize::from(children[1] == old);
            children[k] = new;
        }
    }

    /// Walks from `i` to the root, balancing each node and recomputing its
    /// height and box from its children.
    fn refit_to_root(&mut self, mut i: u32) {
        while i != NULL {
            i = self.balance(i);
            self.refit(i);
            i = self.nodes[i as usize].parent;
        }
    }

    /// Recomputes the height and box of the internal node `i` from its
    /// children; it stays marked for the rebuild if it or a child was (so
    /// the marks still reach the root after a rotation).
    fn refit(&mut self, i: u32) {
        let [c0, c1] = self.nodes[i as usize].children;
        let (a, b) = (&self.nodes[c0 as usize], &self.nodes[c1 as usize]);
        let height = 1 + a.height.max(b.height);
        let aabb = a.aabb.merged(&b.aabb);
        let enlarged = a.enlarged || b.enlarged;
        let node = &mut self.nodes[i as usize];
        node.height = height;
        node.aabb = aabb;
        node.enlarged |= enlarged;
    }

    /// If the children of the internal node `a` differ in height by more
    /// than one, rotates the taller one up into `a`'s place and returns it;
    /// otherwise returns `a`. The rotated nodes are refitted; `a`'s
    /// children are up to date, its own height and box may not be.
    fn balance(&mut self, a: u32) -> u32 {
        let [c0, c1] = self.nodes[a as usize].children;
        let h0 = self.nodes[c0 as usize].height;
        let h1 = self.nodes[c1 as usize].height;
        if h1 > h0 + 1 {
            self.rotate_up(a, 1)
        } else if h0 > h1 + 1 {
            self.rotate_up(a, 0)
        } else {
            a
        }
    }

    /// Rotation at `a` promoting its child on side `side` (taller by at
    /// least two, hence internal), called `p`: `p` takes `a`'s place, keeps
    /// its taller child and gives its shorter one to `a` in place of itself;
    /// `a` becomes `p`'s child. Returns `p`.
    ///
    /// ```text
    ///        a                 p
    ///      /   \             /   \
    ///   other   p    →     a    taller
    ///          / \        / \
    ///     taller shorter other shorter
    /// ```
    fn rotate_up(&mut self, a: u32, side: usize) -> u32 {
        let p = self.nodes[a as usize].children[side];
        let [g0, g1] = self.nodes[p as usize].children;
        let (taller, shorter) = if self.nodes[g0 as usize].height >= self.nodes[g1 as usize].height
        {
            (g0, g1)
        } else {
            (g1, g0)
        };
        let grandparent = self.nodes[a as usize].parent;
        self.replace_child(grandparent, a, p);
        self.nodes[p as usize].parent = grandparent;

        self.nodes[a as usize].children[side] = shorter;
        self.nodes[shorter as usize].parent = a;
        self.nodes[a as usize].parent = p;

        self.nodes[p as usize].children[1 - side] = a;
        self.nodes[p as usize].children[side] = taller;

        self.refit(a);
        self.refit(p);
        p
    }
}

/// [`Aabb::overlaps`] computed without branches (all four comparisons).
#[inline(always)]
fn overlap(a: &Aabb, b: &Aabb) -> bool {
    (a.min.x <= b.max.x) & (b.min.x <= a.max.x) & (a.min.y <= b.max.y) & (b.min.y <= a.max.y)
}

/// Box equality for [`DynamicTree::validate`], with NaN equal to NaN.
fn same_box(a: &Aabb, b: &Aabb) -> bool {
    let same = |x: f64, y: f64| x == y || (x.is_nan() && y.is_nan());
    same(a.min.x, b.min.x)
        && same(a.min.y, b.min.y)
        && same(a.max.x, b.max.x)
        && same(a.max.y, b.max.y)
}

mod pairs;
pub(crate) mod ray;
mod rebuild;
#[cfg(test)]
mod tests;
