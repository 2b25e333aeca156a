//! The soft step allocates nothing per step in steady state: once a pile
//! has settled (its contacts, constraints and broad-phase pairs have
//! reached their counts), 100 more steps of a 210-body pyramid make no
//! heap allocation. Counted by a global allocator in this test binary
//! only, per thread.

use engine::{BodyDef, ContactModel, Method, Shape, SoftStepSettings, World};
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

#[test]
fn a_settled_pile_steps_without_allocating() {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap();
    world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(60.0, 1.0).unwrap()),
        ))
        .unwrap();
    let base = 20;
    for row in 0..base {
        for col in 0..base - row {
            let x = col as f64 - (base - row) as f64 / 2.0 + 0.5;
            world
                .add_body(
                    BodyDef::rigid("box", 1.0, Shape::rectangle(1.0, 1.0).unwrap())
                        .with_position(Vector2::new(x, 0.5 + row as f64)),
                )
                .unwrap();
        }
    }
    assert_eq!(world.bodies().len(), 211);
    let dt = 1.0 / 60.0;
    for _ in 0..120 {
        world.step(dt).unwrap();
    }
    let before = ALLOCATIONS.with(Cell::get);
    for _ in 0..100 {
        world.step(dt).unwrap();
    }
    let made = ALLOCATIONS.with(Cell::get) - before;
    assert_eq!(made, 0, "{made} allocations in 100 steady steps");
    // The pile is still standing: the counting did not change the physics.
    let top = world.states().last().unwrap().position.y;
    assert!((top - 19.5).abs() < 0.05, "top box at {top}");
}
