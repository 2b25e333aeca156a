//! Tests of the dynamic tree: exact agreement with brute force under
//! random queries, moves, destroys and re-creates; the pair count of a
//! resting column; the height under ordered insertions; degenerate boxes;
//! the query's stack fallback; the node pool; determinism.

use super::*;
use crate::collision::brute_force_pairs;
use crate::collision::test_rng::Rng;
use nalgebra::Vector2;

fn aabb(min_x: f64, min_y: f64, max_x: f64, max_y: f64) -> Aabb {
    Aabb::new(Vector2::new(min_x, min_y), Vector2::new(max_x, max_y))
}

/// A box of half-size up to `size` (m) centred in [0, world]².
fn random_box(rng: &mut Rng, world: f64, size: f64) -> Aabb {
    let c = Vector2::new(rng.range(0.0, world), rng.range(0.0, world));
    let h = Vector2::new(rng.range(0.0, size), rng.range(0.0, size));
    Aabb::new(c - h, c + h)
}

/// The user data of the proxies the tree reports for `query`, sorted.
fn hits(tree: &DynamicTree, query: &Aabb) -> Vec<u32> {
    let mut found = Vec::new();
    tree.query(query, |id, data| {
        assert_eq!(tree.user_data(id), data);
        found.push(data);
        true
    });
    found.sort_unstable();
    found
}

/// The oracle: the user data of every live box overlapping `query`.
fn brute_hits(live: &[(u32, Aabb)], query: &Aabb) -> Vec<u32> {
    let mut found: Vec<u32> = live
        .iter()
        .filter(|(_, b)| b.overlaps(query))
        .map(|&(d, _)| d)
        .collect();
    found.sort_unstable();
    found
}

/// A tree of `boxes` inserted in order, user data = index, and the
/// proxy ids by index.
fn build(boxes: &[Aabb]) -> (DynamicTree, Vec<ProxyId>) {
    let mut tree = DynamicTree::new();
    let ids = boxes
        .iter()
        .enumerate()
        .map(|(i, b)| tree.create_proxy(*b, i as u32))
        .collect();
    (tree, ids)
}

/// The pairs `(i, j)`, `i < j` (user data), found by querying the tree
/// with the fat box of every proxy, sorted: the same form as
/// [`brute_force_pairs`].
fn pairs_by_query(tree: &DynamicTree, ids: &[ProxyId]) -> Vec<(usize, usize)> {
    let mut pairs = Vec::new();
    for &id in ids {
        let i = tree.user_data(id) as usize;
        tree.query(tree.fat_aabb(id), |_, j| {
            let j = j as usize;
            // Each pair is found from both ends; keep it once.
            if j > i {
                pairs.push((i, j));
            }
            true
        });
    }
    pairs.sort_unstable();
    pairs
}

/// [`build`] then [`pairs_by_query`].
fn tree_pairs(boxes: &[Aabb]) -> (DynamicTree, Vec<(usize, usize)>) {
    let (tree, ids) = build(boxes);
    let pairs = pairs_by_query(&tree, &ids);
    (tree, pairs)
}

/// A column of `n` unit boxes resting on each other, inserted
/// bottom-to-top with a fat margin of 0.1 m.
fn column(n: usize) -> Vec<Aabb> {
    (0..n)
        .map(|i| aabb(0.0, i as f64, 1.0, i as f64 + 1.0).loosened(0.1))
        .collect()
}

#[test]
fn random_queries_match_brute_force_exactly() {
    let mut rng = Rng::new(0x7EE_0001);
    let mut tree = DynamicTree::new();
    let mut live = Vec::new();
    for i in 0..400 {
        let size = if i % 4 == 0 { 4.0 } else { 1.0 };
        let b = random_box(&mut rng, 60.0, size);
        tree.create_proxy(b, i);
        live.push((i, b));
    }
    tree.validate().unwrap();
    assert_eq!(tree.proxy_count(), 400);
    let mut total = 0;
    for q in 0..500 {
        // Points, small and large query boxes.
        let size = [0.0, 0.5, 3.0, 20.0][q % 4];
        let query = random_box(&mut rng, 60.0, size);
        let expected = brute_hits(&live, &query);
        assert_eq!(hits(&tree, &query), expected, "query {q}");
        total += expected.len();
    }
    assert!(total > 2000, "the queries must hit something: {total}");
}

#[test]
fn moves_destroys_and_recreates_keep_the_tree_valid_and_exact() {
    let mut rng = Rng::new(0x7EE_0002);
    let mut tree = DynamicTree::new();
    // Slot k of the mirror: the proxy with user data k and its box.
    let mut mirror: Vec<Option<(ProxyId, Aabb)>> = Vec::new();
    for k in 0..200 {
        let b = random_box(&mut rng, 40.0, 1.5);
        mirror.push(Some((tree.create_proxy(b, k), b)));
    }
    let mut checked_hits = 0;
    for op in 0..3000 {
        let k = rng.int(0, mirror.len() - 1);
        match (rng.int(0, 9), mirror[k]) {
            (0..=5, Some((id, b))) => {
                // A small displacement, as between two steps, or a jump.
                let reach = if op % 10 == 0 { 20.0 } else { 0.5 };
                let d = Vector2::new(rng.range(-reach, reach), rng.range(-reach, reach));
                let moved = Aabb::new(b.min + d, b.max + d);
                tree.move_proxy(id, moved);
                assert_eq!(tree.user_data(id), k as u32);
                mirror[k] = Some((id, moved));
            }
            (6..=7, Some((id, _))) => {
                tree.destroy_proxy(id);
                mirror[k] = None;
            }
            (_, None) => {
                let b = random_box(&mut rng, 40.0, 1.5);
                mirror[k] = Some((tree.create_proxy(b, k as u32), b));
            }
            _ => {}
        }
        tree.validate()
            .unwrap_or_else(|e| panic!("after operation {op}: {e}"));
        let live: Vec<(u32, Aabb)> = mirror
            .iter()
            .enumerate()
            .filter_map(|(k, e)| e.map(|(_, b)| (k as u32, b)))
            .collect();
        assert_eq!(tree.proxy_count(), live.len());
        for &(k, b) in &live {
            assert_eq!(tree.fat_aabb(mirror[k as usize].unwrap().0), &b);
        }
        if op % 10 == 0 {
            for _ in 0..5 {
                let query = random_box(&mut rng, 40.0, 3.0);
                let expected = brute_hits(&live, &query);
                assert_eq!(hits(&tree, &query), expected, "operation {op}");
                checked_hits += expected.len();
            }
        }
    }
    assert!(checked_hits > 500, "{checked_hits} hits checked");
}

#[test]
fn querying_every_proxy_gives_the_brute_force_pairs() {
    let mut rng = Rng::new(0x7EE_0003);
    let mut total = 0;
    for trial in 0..40 {
        let n = rng.int(0, 150);
        let mut boxes: Vec<Aabb> = (0..n).map(|_| random_box(&mut rng, 25.0, 1.5)).collect();
        // Exact ties and boxes touching along an edge.
        if n > 4 {
            boxes[1] = boxes[0];
            boxes[3].min.x = boxes[2].max.x;
            boxes[3].min.y = boxes[2].min.y;
        }
        let expected = brute_force_pairs(&boxes);
        let (tree, pairs) = tree_pairs(&boxes);
        tree.validate().unwrap();
        assert_eq!(pairs, expected, "trial {trial}, n = {n}");
        total += expected.len();
    }
    assert!(total > 1000, "the sets must have pairs: {total}");
}

#[test]
fn a_resting_column_gives_one_pair_per_contact_and_a_logarithmic_height() {
    // Fat boxes [i − 0.1, i + 1.1]: each overlaps its two neighbours
    // (by 0.2 m) and nothing else, so a column of n boxes has n − 1
    // pairs.
    let boxes = column(1000);
    let (tree, pairs) = tree_pairs(&boxes);
    tree.validate().unwrap();
    assert_eq!(pairs.len(), 999);
    assert_eq!(pairs, brute_force_pairs(&boxes));
    assert!(pairs.iter().all(|&(i, j)| j == i + 1));
    // The bound of the task: 2.5·log2(n) (≈ 24.9). An AVL tree stays
    // under 1.44·log2(n + 2); a tree without rotations would be 999
    // deep here.
    let bound = 2.5 * (1000f64).log2();
    assert!((tree.height() as f64) <= bound, "height {}", tree.height());

    // Ten times more: checked against the known pairs instead of the
    // O(n²) oracle.
    let (tree, pairs) = tree_pairs(&column(10_000));
    assert_eq!(pairs.len(), 9999);
    assert!(pairs.iter().enumerate().all(|(k, &p)| p == (k, k + 1)));
    let bound = 2.5 * (10_000f64).log2();
    assert!((tree.height() as f64) <= bound, "height {}", tree.height());
}

#[test]
fn ordered_insertions_in_two_dimensions_stay_shallow() {
    // A pyramid of base 45 (1035 boxes) built row by row, and a 40 × 40
    // grid of boxes inserted row-major: the other orders a scene is
    // built in.
    let mut pyramid = Vec::new();
    for row in 0..45 {
        for k in 0..45 - row {
            let x = k as f64 + 0.5 * row as f64;
            pyramid.push(aabb(x, row as f64, x + 1.0, row as f64 + 1.0).loosened(0.1));
        }
    }
    let grid: Vec<Aabb> = (0..1600)
        .map(|i| {
            let (x, y) = ((i % 40) as f64, (i / 40) as f64);
            aabb(x, y, x + 1.0, y + 1.0).loosened(0.1)
        })
        .collect();
    for boxes in [pyramid, grid] {
        let (tree, pairs) = tree_pairs(&boxes);
        tree.validate().unwrap();
        assert_eq!(pairs, brute_force_pairs(&boxes));
        let bound = 2.5 * (boxes.len() as f64).log2();
        assert!((tree.height() as f64) <= bound, "height {}", tree.height());
    }
}

#[test]
fn degenerate_boxes_give_correct_answers() {
    let mut rng = Rng::new(0x7EE_0004);
    let point = |x: f64, y: f64| aabb(x, y, x, y);
    let big = 1e12;
    let sets: Vec<Vec<Aabb>> = vec![
        // Zero-size boxes, some coincident, some touching larger boxes.
        (0..60)
            .map(|i| point((i % 7) as f64, (i % 5) as f64))
            .chain((0..20).map(|i| aabb(i as f64, 0.0, i as f64 + 1.0, 1.0)))
            .collect(),
        // Identical boxes: every pair overlaps.
        vec![aabb(1.0, 2.0, 3.0, 4.0); 50],
        // Huge coordinates, unit boxes 1 m apart: still exact, since
        // 1e12 + k is exactly representable.
        (0..100)
            .map(|i| {
                let x = big + (i % 10) as f64 * 2.0;
                let y = -big + (i / 10) as f64 * 1.5;
                aabb(x, y, x + 1.0, y + 1.0)
            })
            .collect(),
        // Mixed scales, an infinite ground, an inverted box and NaN.
        (0..80)
            .map(|_| random_box(&mut rng, 10.0, 1.0))
            .chain([
                aabb(-big, -big, big, big),
                aabb(f64::NEG_INFINITY, -1.0, f64::INFINITY, 0.0),
                aabb(2.0, 2.0, 1.0, 1.0),
                aabb(f64::NAN, 0.0, 1.0, 1.0),
                aabb(f64::NAN, f64::NAN, f64::NAN, f64::NAN),
                point(5.0, 5.0),
            ])
            .collect(),
    ];
    for (s, boxes) in sets.iter().enumerate() {
        let (mut tree, ids) = build(boxes);
        tree.validate().unwrap();
        assert_eq!(
            pairs_by_query(&tree, &ids),
            brute_force_pairs(boxes),
            "set {s}"
        );
        let live: Vec<(u32, Aabb)> = boxes
            .iter()
            .enumerate()
            .map(|(i, b)| (i as u32, *b))
            .collect();
        for q in [
            point(0.0, 0.0),
            point(big + 1.0, -big + 1.0),
            aabb(-1.0, -1.0, 3.0, 3.0),
            aabb(
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::INFINITY,
            ),
            aabb(f64::NAN, 0.0, 1.0, 1.0),
        ] {
            assert_eq!(
                hits(&tree, &q),
                brute_hits(&live, &q),
                "set {s}, query {q:?}"
            );
        }
        // Tear it down through moves onto one point and destroys.
        for &id in &ids {
            tree.move_proxy(id, point(0.0, 0.0));
            tree.validate().unwrap();
        }
        for &id in &ids {
            tree.destroy_proxy(id);
            tree.validate().unwrap();
        }
        assert_eq!((tree.proxy_count(), tree.height()), (0, 0));
    }
}

#[test]
fn the_callback_can_stop_a_query() {
    let tree = tree_pairs(&vec![aabb(0.0, 0.0, 1.0, 1.0); 20]).0;
    let mut calls = 0;
    tree.query(&aabb(0.5, 0.5, 0.5, 0.5), |_, _| {
        calls += 1;
        calls < 3
    });
    assert_eq!(calls, 3);
    // An empty tree calls nothing.
    DynamicTree::new().query(&aabb(0.0, 0.0, 1.0, 1.0), |_, _| panic!("no proxy"));
}

/// The user data reported by a query with a stack of `N` entries,
/// stopped after `stop_after` hits, sorted.
fn hits_with_stack<const N: usize>(
    tree: &DynamicTree,
    query: &Aabb,
    stop_after: usize,
) -> Vec<u32> {
    let mut found = Vec::new();
    tree.query_with_stack::<N>(query, &mut |_, data| {
        found.push(data);
        found.len() < stop_after
    });
    found.sort_unstable();
    found
}

#[test]
fn a_full_query_stack_falls_back_to_recursion_with_the_same_hits() {
    let mut rng = Rng::new(0x7EE_0005);
    let boxes: Vec<Aabb> = (0..300).map(|_| random_box(&mut rng, 30.0, 2.0)).collect();
    let tree = tree_pairs(&boxes).0;
    // The walk needs about height + 1 entries: stacks of 0, 1 and 3
    // overflow.
    assert!(tree.height() > 3, "height {}", tree.height());
    let mut compared = 0;
    for q in 0..50 {
        let query = random_box(&mut rng, 30.0, 6.0);
        let full = hits(&tree, &query);
        for found in [
            hits_with_stack::<0>(&tree, &query, usize::MAX),
            hits_with_stack::<1>(&tree, &query, usize::MAX),
            hits_with_stack::<3>(&tree, &query, usize::MAX),
        ] {
            assert_eq!(found, full, "query {q}");
        }
        // Stopping still works from within the recursive walk.
        for found in [
            hits_with_stack::<0>(&tree, &query, 2),
            hits_with_stack::<1>(&tree, &query, 2),
            hits_with_stack::<3>(&tree, &query, 2),
        ] {
            assert_eq!(found.len(), full.len().min(2), "query {q}");
            assert!(found.iter().all(|d| full.contains(d)));
        }
        compared += full.len();
    }
    assert!(compared > 100, "{compared} hits compared");
}

#[test]
fn the_node_pool_stops_growing_after_warm_up() {
    let mut rng = Rng::new(0x7EE_0006);
    let mut tree = DynamicTree::new();
    let mut ids: Vec<ProxyId> = (0..200)
        .map(|k| tree.create_proxy(random_box(&mut rng, 40.0, 1.0), k))
        .collect();
    // 200 leaves and 199 internal nodes.
    assert_eq!(tree.nodes.len(), 399);
    let capacity = tree.nodes.capacity();
    for cycle in 0..2000 {
        let k = rng.int(0, ids.len() - 1);
        if cycle % 3 == 0 {
            tree.destroy_proxy(ids[k]);
            ids[k] = tree.create_proxy(random_box(&mut rng, 40.0, 1.0), k as u32);
        } else {
            tree.move_proxy(ids[k], random_box(&mut rng, 40.0, 1.0));
        }
        assert_eq!(tree.nodes.len(), 399, "cycle {cycle}");
    }
    assert_eq!(tree.nodes.capacity(), capacity);
    tree.validate().unwrap();
}

#[test]
fn the_same_operations_build_the_same_tree() {
    let build = || {
        let mut rng = Rng::new(0x7EE_0007);
        let mut tree = DynamicTree::new();
        let mut ids = Vec::new();
        for k in 0..300 {
            ids.push(tree.create_proxy(random_box(&mut rng, 30.0, 1.0), k));
            if k % 5 == 4 {
                tree.destroy_proxy(ids.swap_remove(rng.int(0, ids.len() - 1)));
            }
            if k % 3 == 2 {
                let id = ids[rng.int(0, ids.len() - 1)];
                tree.move_proxy(id, random_box(&mut rng, 30.0, 1.0));
            }
        }
        (tree, ids)
    };
    let (a, ids_a) = build();
    let (b, ids_b) = build();
    assert_eq!(ids_a, ids_b);
    assert_eq!((a.root, a.free_list), (b.root, b.free_list));
    assert!(a.nodes == b.nodes);
}

#[test]
#[should_panic(expected = "is not a live proxy")]
fn destroying_a_proxy_twice_is_refused() {
    let mut tree = DynamicTree::new();
    let a = tree.create_proxy(aabb(0.0, 0.0, 1.0, 1.0), 0);
    tree.create_proxy(aabb(2.0, 0.0, 3.0, 1.0), 1);
    tree.destroy_proxy(a);
    tree.destroy_proxy(a);
}

/// The tree's cost in the insertion heuristic's measure: the sum of its
/// internal nodes' perimeters (m).
fn internal_perimeter(tree: &DynamicTree) -> f64 {
    tree.nodes
        .iter()
        .filter(|n| n.in_use && !n.is_leaf())
        .map(|n| n.aabb.perimeter())
        .sum()
}

#[test]
fn enlarging_then_rebuilding_keeps_queries_exact_and_the_pool_fixed() {
    let mut rng = Rng::new(0x7EE_0008);
    let mut tree = DynamicTree::new();
    let mut live: Vec<(u32, Aabb)> = Vec::new();
    let mut ids = Vec::new();
    for k in 0..300 {
        let b = random_box(&mut rng, 40.0, 1.0);
        ids.push(tree.create_proxy(b, k));
        live.push((k, b));
    }
    let nodes = tree.nodes.len();
    let mut compared = 0;
    for round in 0..40 {
        // A share of the proxies (a few, or most) get new boxes that need
        // not contain their old ones, as bodies leaving their fat boxes.
        let share = [0.02, 0.3, 1.0][round % 3];
        for k in 0..ids.len() {
            if rng.unit() < share {
                let (x, y) = (live[k].1.min.x, live[k].1.min.y);
                let d = Vector2::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
                let b = aabb(x, y, x + rng.range(0.1, 2.0), y + rng.range(0.1, 2.0));
                let b = Aabb::new(b.min + d, b.max + d);
                tree.enlarge_proxy(ids[k], b);
                live[k].1 = b;
                assert_eq!(*tree.fat_aabb(ids[k]), b);
            }
        }
        tree.validate().unwrap();
        // Exact before the rebuild (marked boxes are only larger) and after.
        for pass in 0..2 {
            for _ in 0..20 {
                let query = random_box(&mut rng, 40.0, [0.0, 1.0, 6.0][pass]);
                let expected = brute_hits(&live, &query);
                compared += expected.len();
                assert_eq!(hits(&tree, &query), expected, "round {round}");
            }
            tree.rebuild();
            tree.validate().unwrap();
            assert!(tree.nodes.iter().all(|n| !n.enlarged), "marks left");
        }
        assert_eq!(tree.nodes.len(), nodes, "the pool grew");
        assert_eq!(tree.proxy_count(), 300);
        for (k, &id) in ids.iter().enumerate() {
            assert_eq!(tree.user_data(id), k as u32);
        }
    }
    assert!(compared > 300, "{compared} hits compared");
}

#[test]
fn a_rebuild_without_enlarged_proxies_changes_nothing() {
    let mut rng = Rng::new(0x7EE_0009);
    let boxes: Vec<Aabb> = (0..100).map(|_| random_box(&mut rng, 20.0, 1.0)).collect();
    let (mut tree, ids) = build(&boxes);
    tree.move_proxy(ids[3], aabb(5.0, 5.0, 6.0, 6.0));
    let before = tree.clone();
    tree.rebuild();
    assert!(tree.nodes == before.nodes && tree.root == before.root);
}

#[test]
fn rebuilding_a_column_inserted_in_order_gives_a_shallow_cheap_tree() {
    // Enlarging every proxy of a column by 1 mm and rebuilding regroups the
    // whole tree: the binned heuristic splits it near the middle each time.
    let n = 1024;
    let (mut tree, ids) = build(&column(n));
    let inserted = internal_perimeter(&tree);
    for (i, &id) in ids.iter().enumerate() {
        tree.enlarge_proxy(id, column(n)[i].loosened(1e-3));
    }
    tree.rebuild();
    tree.validate().unwrap();
    // A perfectly balanced tree of 1024 leaves has height 10; the slices
    // of 8 bins split 1:7 at worst, so allow a few levels more.
    assert!(tree.height() <= 14, "height {}", tree.height());
    let rebuilt = internal_perimeter(&tree);
    assert!(rebuilt <= inserted, "{rebuilt} vs {inserted}");
    let pairs = pairs_by_query(&tree, &ids);
    assert_eq!(
        pairs,
        brute_force_pairs(
            &column(n)
                .iter()
                .map(|b| b.loosened(1e-3))
                .collect::<Vec<_>>()
        )
    );
}

#[test]
fn a_rebuild_handles_coincident_and_nan_boxes() {
    let mut tree = DynamicTree::new();
    let same = aabb(0.0, 0.0, 1.0, 1.0);
    let ids: Vec<ProxyId> = (0..64).map(|k| tree.create_proxy(same, k)).collect();
    for &id in &ids[..40] {
        tree.enlarge_proxy(id, same.loosened(0.5));
    }
    let nan = Aabb::new(Vector2::new(f64::NAN, 0.0), Vector2::new(1.0, f64::NAN));
    tree.enlarge_proxy(ids[50], nan);
    tree.rebuild();
    tree.validate().unwrap();
    // Coincident centres are halved: a balanced tree of 64 leaves.
    assert!(tree.height() <= 8, "height {}", tree.height());
    let found = hits(&tree, &aabb(0.2, 0.2, 0.3, 0.3));
    let expected: Vec<u32> = (0..64).filter(|&k| k != 50).collect();
    assert_eq!(found, expected);
}

#[test]
fn the_same_enlargements_rebuild_the_same_tree() {
    let run = || {
        let mut rng = Rng::new(0x7EE_000A);
        let boxes: Vec<Aabb> = (0..200).map(|_| random_box(&mut rng, 30.0, 1.0)).collect();
        let (mut tree, ids) = build(&boxes);
        for round in 0..10 {
            for (k, &id) in ids.iter().enumerate() {
                if (k + round) % 3 == 0 {
                    tree.enlarge_proxy(id, random_box(&mut rng, 30.0, 1.0));
                }
            }
            tree.rebuild();
        }
        tree
    };
    let (a, b) = (run(), run());
    assert!(a.nodes == b.nodes && a.root == b.root && a.free_list == b.free_list);
}

#[test]
fn moved_pairs_are_the_brute_force_pairs_with_a_moved_proxy_each_once() {
    let mut rng = Rng::new(0x7EE_000B);
    for round in 0..12 {
        let n = 20 + 40 * round;
        let boxes: Vec<Aabb> = (0..n).map(|_| random_box(&mut rng, 30.0, 1.5)).collect();
        let (mut tree, ids) = build(&boxes);
        // None, a few, about half, or all of the proxies moved.
        let share = [0.0, 0.05, 0.5, 1.0][round % 4];
        let moved: Vec<bool> = (0..n).map(|_| rng.unit() < share).collect();
        let moved_ids: Vec<ProxyId> = (0..n).filter(|&k| moved[k]).map(|k| ids[k]).collect();
        let mut found = Vec::new();
        tree.moved_pairs(&moved_ids, |a, b| {
            found.push((a.min(b) as usize, a.max(b) as usize));
        });
        let count = found.len();
        found.sort_unstable();
        found.dedup();
        assert_eq!(found.len(), count, "a pair reported twice");
        let expected: Vec<(usize, usize)> = brute_force_pairs(&boxes)
            .into_iter()
            .map(|(a, b)| (a.min(b), a.max(b)))
            .filter(|&(a, b)| moved[a] || moved[b])
            .collect::<std::collections::BTreeSet<_>>()
            .into_iter()
            .collect();
        assert_eq!(found, expected, "round {round}");
    }
}

#[test]
fn the_pieces_of_the_moved_pairs_walk_joined_in_order_are_the_one_walk() {
    // Trees from 20 to 1400 proxies (deeper than the split depth, so that
    // the larger ones are cut below pairs of internal nodes), none, a few,
    // half or all moved: the pieces' reports, joined in the pieces' order,
    // equal the one walk's reports in its order.
    let mut rng = Rng::new(0x7EE_00C5);
    for round in 0..12 {
        let n = 20 + 115 * round;
        let boxes: Vec<Aabb> = (0..n).map(|_| random_box(&mut rng, 40.0, 1.5)).collect();
        let (mut tree, ids) = build(&boxes);
        let share = [0.0, 0.05, 0.5, 1.0][round % 4];
        let moved_ids: Vec<ProxyId> = (0..n)
            .filter(|_| rng.unit() < share)
            .map(|k| ids[k])
            .collect();
        let mut one_walk = Vec::new();
        tree.moved_pairs(&moved_ids, |a, b| one_walk.push((a, b)));
        let mut pieces = Vec::new();
        tree.split_moved_pairs(&moved_ids, &mut pieces);
        if n > 1000 && share > 0.0 {
            assert!(pieces.len() > 16, "round {round}: {} pieces", pieces.len());
        }
        let mut joined = Vec::new();
        let mut stack = Vec::new();
        for &piece in &pieces {
            tree.moved_pairs_of_piece(piece, &mut stack, |a, b| joined.push((a, b)));
        }
        assert_eq!(joined, one_walk, "round {round}");
        if share >= 0.5 {
            assert!(!one_walk.is_empty(), "round {round}: nothing to compare");
        }
    }
}

#[test]
fn a_full_rebuild_lays_the_internal_nodes_out_in_preorder() {
    // Every proxy enlarged: the rebuild regroups the whole tree, and its
    // internal nodes, visited in preorder (left child first), must take
    // ascending indices, so that a subtree's nodes lie together in memory.
    // Twice, because the second rebuild reuses the nodes the first laid out.
    let mut rng = Rng::new(7);
    let boxes: Vec<Aabb> = (0..300).map(|_| random_box(&mut rng, 50.0, 2.0)).collect();
    let (mut tree, ids) = build(&boxes);
    for round in 1..=2 {
        for (id, b) in ids.iter().zip(&boxes) {
            tree.enlarge_proxy(*id, b.loosened(1e-3 * round as f64));
        }
        tree.rebuild();
        tree.validate().unwrap();
        let mut preorder = Vec::new();
        let mut walk = vec![tree.root];
        while let Some(i) = walk.pop() {
            let node = &tree.nodes[i as usize];
            if !node.is_leaf() {
                preorder.push(i);
                walk.push(node.children[1]);
                walk.push(node.children[0]);
            }
        }
        assert_eq!(preorder.len(), boxes.len() - 1);
        assert!(
            preorder.windows(2).all(|w| w[0] < w[1]),
            "round {round}: internal nodes in preorder {preorder:?}"
        );
    }
}

/// Boxes like the ray benchmark's world (`harness bench`, 2000 static
/// shapes of 0.2–3 m in a 200 m square).
fn scattered_boxes(rng: &mut Rng, n: usize) -> Vec<Aabb> {
    (0..n)
        .map(|_| {
            let c = Vector2::new(rng.range(-100.0, 100.0), rng.range(-100.0, 100.0));
            let h = Vector2::new(rng.range(0.1, 1.5), rng.range(0.1, 1.5));
            Aabb::new(c - h, c + h)
        })
        .collect()
}

/// The user data of the leaves a ray of `length` crosses, sorted, and the
/// box tests the walk made.
fn ray_leaves(
    tree: &DynamicTree,
    o: Vector2<f64>,
    d: Vector2<f64>,
    length: f64,
) -> (Vec<u32>, u64) {
    let before = ray::BOX_TESTS.with(|c| c.get());
    let mut found = Vec::new();
    tree.ray_cast(o, d, length, |_, data, max| {
        found.push(data);
        Some(max)
    });
    found.sort_unstable();
    (found, ray::BOX_TESTS.with(|c| c.get()) - before)
}

/// The box tests of a closest-hit walk (each leaf's hit where the ray
/// enters its box) and the nearest entry found.
fn closest_ray(tree: &DynamicTree, boxes: &[Aabb], o: Vector2<f64>, d: Vector2<f64>) -> (f64, u64) {
    let before = ray::BOX_TESTS.with(|c| c.get());
    let inverse = d.map(|c| 1.0 / c);
    let mut nearest = f64::INFINITY;
    tree.ray_cast(o, d, 20.0, |_, k, max| {
        let (lower, _) = ray::ray_box(&boxes[k as usize], o, inverse, max).expect("crossed");
        nearest = nearest.min(lower);
        Some(lower)
    });
    (nearest, ray::BOX_TESTS.with(|c| c.get()) - before)
}

#[test]
fn a_full_rebuild_keeps_the_tree_valid_and_queries_exact() {
    let mut rng = Rng::new(41);
    let boxes = scattered_boxes(&mut rng, 600);
    let (mut tree, ids) = build(&boxes);
    // Destroy a few, so that the free list and the ids are not in order.
    let mut live: Vec<(u32, Aabb)> = Vec::new();
    for (k, b) in boxes.iter().enumerate() {
        if k % 7 == 3 {
            tree.destroy_proxy(ids[k]);
        } else {
            live.push((k as u32, *b));
        }
    }
    assert!(tree.leaves_changed());
    let nodes_before = tree.nodes.len();
    tree.rebuild_all();
    assert!(!tree.leaves_changed());
    tree.validate().unwrap();
    assert_eq!(tree.proxy_count(), live.len());
    assert_eq!(tree.nodes.len(), nodes_before, "the pool grew");
    for (k, b) in boxes.iter().enumerate() {
        if k % 7 != 3 {
            assert_eq!(tree.user_data(ids[k]), k as u32);
            assert_eq!(tree.fat_aabb(ids[k]), b);
        }
    }
    for _ in 0..300 {
        let q = random_box(&mut rng, 100.0, 8.0);
        let q = Aabb::new(q.min - Vector2::repeat(50.0), q.max - Vector2::repeat(50.0));
        assert_eq!(hits(&tree, &q), brute_hits(&live, &q));
    }
    for _ in 0..300 {
        let o = Vector2::new(rng.range(-100.0, 100.0), rng.range(-100.0, 100.0));
        let a = rng.range(0.0, std::f64::consts::TAU);
        let d = Vector2::new(a.cos(), a.sin());
        let inverse = d.map(|c| 1.0 / c);
        let expected: Vec<u32> = live
            .iter()
            .filter(|(_, b)| ray::ray_box(b, o, inverse, 20.0).is_some())
            .map(|&(k, _)| k)
            .collect();
        assert_eq!(ray_leaves(&tree, o, d, 20.0).0, expected);
    }
    // Changes after the rebuild, then a second rebuild.
    tree.move_proxy(ids[0], aabb(0.0, 0.0, 1.0, 1.0));
    assert!(tree.leaves_changed());
    tree.rebuild_all();
    tree.validate().unwrap();
    assert_eq!(tree.nodes.len(), nodes_before);
}

#[test]
fn a_full_rebuild_depends_only_on_the_leaves() {
    let mut rng = Rng::new(43);
    let boxes = scattered_boxes(&mut rng, 300);
    // The same boxes with the same ids: inserted in order, and inserted in
    // order then all moved in reverse order (another incremental shape).
    let (mut a, ids_a) = build(&boxes);
    let (mut b, ids_b) = build(&boxes);
    assert_eq!(ids_a, ids_b);
    for (k, id) in ids_b.iter().enumerate().rev() {
        b.move_proxy(*id, boxes[k]);
    }
    assert_ne!(a.nodes, b.nodes, "the incremental trees should differ");
    a.rebuild_all();
    b.rebuild_all();
    assert_eq!(a.root, b.root);
    let shape = |t: &DynamicTree| {
        let mut out = Vec::new();
        let mut stack = vec![t.root];
        while let Some(i) = stack.pop() {
            let n = &t.nodes[i as usize];
            out.push((n.is_leaf().then_some(i), n.aabb, n.height));
            if !n.is_leaf() {
                stack.extend(n.children);
            }
        }
        out
    };
    assert_eq!(shape(&a), shape(&b));
    // And a clone rebuilt again gives the same tree.
    let mut c = a.clone();
    c.rebuild_all();
    assert_eq!(c.nodes, a.nodes);
}

#[test]
fn a_full_rebuild_handles_small_coincident_and_nan_trees() {
    let mut empty = DynamicTree::new();
    empty.rebuild_all();
    empty.validate().unwrap();
    let mut one = DynamicTree::new();
    one.create_proxy(aabb(0.0, 0.0, 1.0, 1.0), 5);
    one.rebuild_all();
    one.validate().unwrap();
    assert_eq!(hits(&one, &aabb(0.5, 0.5, 0.6, 0.6)), vec![5]);
    let mut tree = DynamicTree::new();
    for k in 0..20 {
        tree.create_proxy(aabb(0.0, 0.0, 1.0, 1.0), k);
    }
    tree.create_proxy(aabb(f64::NAN, 0.0, 1.0, 1.0), 20);
    tree.create_proxy(
        Aabb::new(Vector2::repeat(f64::NAN), Vector2::repeat(f64::NAN)),
        21,
    );
    tree.rebuild_all();
    tree.validate().unwrap();
    assert!(tree.height() <= 6, "height {}", tree.height());
    assert_eq!(
        hits(&tree, &aabb(0.5, 0.5, 0.6, 0.6)),
        (0..20).collect::<Vec<_>>()
    );
}

/// The cost figure behind the soft step's rebuild of its static tree: a
/// closest-hit ray of 20 m through 2000 scattered boxes tests about 90
/// boxes in the incrementally built tree and about a third of that after
/// [`DynamicTree::rebuild_all`], with the same nearest hits. (Printed with
/// `--nocapture`; the bound checks the rebuild at least halves the tests.)
#[test]
fn a_full_rebuild_cuts_the_box_tests_of_closest_ray_casts() {
    let mut rng = Rng::new(47);
    let boxes = scattered_boxes(&mut rng, 2000);
    let (incremental, _) = build(&boxes);
    let mut rebuilt = incremental.clone();
    rebuilt.rebuild_all();
    let rays = 2000;
    let (mut tests_before, mut tests_after) = (0, 0);
    for _ in 0..rays {
        let o = Vector2::new(rng.range(-100.0, 100.0), rng.range(-100.0, 100.0));
        let a = rng.range(0.0, std::f64::consts::TAU);
        let d = Vector2::new(a.cos(), a.sin());
        let (near_before, before) = closest_ray(&incremental, &boxes, o, d);
        let (near_after, after) = closest_ray(&rebuilt, &boxes, o, d);
        assert_eq!(near_before, near_after);
        tests_before += before;
        tests_after += after;
    }
    let per_ray = |t: u64| t as f64 / rays as f64;
    println!(
        "box tests per ray: incremental {:.1}, rebuilt {:.1}",
        per_ray(tests_before),
        per_ray(tests_after)
    );
    assert!(
        2 * tests_after < tests_before,
        "{tests_after} vs {tests_before}"
    );
}
