//! The dynamic tree's memory promises, counted by a global allocator (this
//! test binary only): a query allocates nothing, and once the proxy count
//! has peaked, creating, destroying, moving and enlarging proxies,
//! rebuilding the tree and listing the moved proxies' pairs allocate
//! nothing.
//!
//! The count is kept per thread, so the test harness's own threads and
//! other tests running in parallel do not disturb it.

use etalon2d::validation::collision::{Aabb, DynamicTree, ProxyId};
use nalgebra::Vector2;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// The system allocator, counting the allocations of each thread.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: every call is forwarded unchanged to the system allocator; the
// counter is a const-initialised thread-local `Cell`, which allocates
// nothing and cannot re-enter the allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
        // SAFETY: the caller's contract is passed on as is.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is passed on as is.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
        // SAFETY: the caller's contract is passed on as is.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The allocations `f` made on this thread.
fn allocations_in(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

/// A unit box at (x, y) (m), fattened by 0.1 m.
fn fat_unit_box(x: f64, y: f64) -> Aabb {
    Aabb::new(Vector2::new(x, y), Vector2::new(x + 1.0, y + 1.0)).loosened(0.1)
}

#[test]
fn queries_and_steady_state_updates_allocate_nothing() {
    // A 30 × 30 grid of boxes, each touching its neighbours.
    let mut tree = DynamicTree::new();
    let mut ids: Vec<ProxyId> = (0..900)
        .map(|i| tree.create_proxy(fat_unit_box((i % 30) as f64, (i / 30) as f64), i))
        .collect();

    // Every proxy queried against the tree: the pair count of a grid with
    // diagonal neighbours, found without allocating.
    let mut pairs = 0;
    let queried = allocations_in(|| {
        for &id in &ids {
            let i = tree.user_data(id);
            tree.query(tree.fat_aabb(id), |_, j| {
                pairs += usize::from(j > i);
                true
            });
        }
    });
    assert_eq!(queried, 0);
    // 30 × 29 horizontal, as many vertical, 2 × 29 × 29 diagonal.
    assert_eq!(pairs, 2 * 30 * 29 + 2 * 29 * 29);

    // Steady state: the proxy count never exceeds its peak of 900, so the
    // freed nodes are reused and the pool never grows.
    let updated = allocations_in(|| {
        for step in 0..3000usize {
            let k = (step * 7919) % ids.len();
            let (x, y) = ((step % 37) as f64, (step % 23) as f64);
            if step % 4 == 0 {
                tree.destroy_proxy(ids[k]);
                ids[k] = tree.create_proxy(fat_unit_box(x, y), k as u32);
            } else {
                tree.move_proxy(ids[k], fat_unit_box(x, y));
            }
        }
    });
    assert_eq!(updated, 0);
    assert_eq!(tree.proxy_count(), 900);
    tree.validate().unwrap();

    // Enlarging in place and rebuilding: the first rebuild grows its work
    // lists, later ones (of as many proxies or fewer) allocate nothing.
    let enlarge_all = |tree: &mut DynamicTree, shift: f64| {
        for (k, &id) in ids.iter().enumerate() {
            tree.enlarge_proxy(id, fat_unit_box((k % 30) as f64 + shift, (k / 30) as f64));
        }
        tree.rebuild();
    };
    enlarge_all(&mut tree, 0.5);
    let rebuilt = allocations_in(|| {
        for round in 0..20 {
            enlarge_all(&mut tree, 0.05 * round as f64);
        }
    });
    assert_eq!(rebuilt, 0);
    tree.validate().unwrap();

    // The pairs of the moved proxies, by the tree's walk against itself.
    let half: Vec<ProxyId> = ids.iter().copied().step_by(2).collect();
    let mut walked = 0;
    tree.moved_pairs(&half, |_, _| walked += 1);
    let walking = allocations_in(|| {
        for _ in 0..5 {
            tree.moved_pairs(&half, |_, _| walked += 1);
        }
    });
    assert_eq!(walking, 0);
    assert!(walked > 0);

    // The counter does see allocations: growing past the peak allocates.
    let grown = allocations_in(|| {
        for i in 0..2000 {
            tree.create_proxy(fat_unit_box(0.0, -(i as f64)), 900 + i);
        }
    });
    assert!(grown > 0);
}
