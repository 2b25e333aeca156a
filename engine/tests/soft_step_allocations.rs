//! The soft step allocates nothing per step in steady state: once a pile
//! has settled (its contacts, constraints and broad-phase pairs have
//! reached their counts), 100 more steps of a 210-body pyramid make no
//! heap allocation, nor 100 steps of a swinging chain and one joint of
//! every type. Counted by a global allocator in this test binary
//! only, per thread; and on two threads, the pile again counted over
//! every thread of the process (the pool's worker included).

use etalon2d::{BodyDef, ContactModel, Method, Shape, SoftStepSettings, World};
use nalgebra::Vector2;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator, counting the allocations of each thread.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// Allocations by every thread of the process.
static ALL_THREADS: AtomicUsize = AtomicUsize::new(0);

/// The tests of this binary one at a time, so that the count over every
/// thread sees only the test that reads it.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

// SAFETY: every call is forwarded unchanged to the system allocator; the
// counters are a const-initialised thread-local `Cell` and a static
// atomic, which allocate nothing and cannot re-enter the allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
        ALL_THREADS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: the caller's contract is passed on as is.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is passed on as is.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|n| n.set(n.get() + 1));
        ALL_THREADS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: the caller's contract is passed on as is.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn a_settled_pile_steps_without_allocating() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    settled_pile_allocations(1, || ALLOCATIONS.with(Cell::get));
}

#[test]
fn a_settled_pile_steps_without_allocating_on_two_threads() {
    // Every thread's allocations: the pool's worker must not allocate
    // either (the pool is made on the first step, before the count).
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    settled_pile_allocations(2, || ALL_THREADS.load(Ordering::SeqCst));
}

/// The pyramid settled on `threads` threads, then 100 steps counted by
/// `count`.
fn settled_pile_allocations(threads: usize, count: fn() -> usize) {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings {
            threads,
            // On the threads however small the pile: what is counted.
            min_work_per_thread: 0,
            ..SoftStepSettings::default()
        }),
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
    let before = count();
    for _ in 0..100 {
        world.step(dt).unwrap();
    }
    let made = count() - before;
    assert_eq!(
        made, 0,
        "{made} allocations in 100 steady steps on {threads} threads"
    );
    // The pile is still standing: the counting did not change the physics.
    let top = world.states().last().unwrap().position.y;
    assert!((top - 19.5).abs() < 0.05, "top box at {top}");
}

#[test]
fn jointed_bodies_step_without_allocating() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    // A chain of 20 boxes hanging from a static bar by revolute joints
    // (with limits, a motor and a spring on every other one), a distance
    // pendulum, a rope, a spring, a prismatic slider, a weld and a target
    // joint: every joint type, with sleeping on (the islands hold the
    // jointed bodies).
    use etalon2d::{
        Distance, JointDef, JointSpring, Prismatic, Revolute, RevoluteMotor, Target, Weld,
    };
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings {
            sleeping: true,
            ..SoftStepSettings::default()
        }),
    )
    .unwrap();
    world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
    let bar = world
        .add_body(BodyDef::fixed(
            "bar",
            Vector2::new(0.0, 10.0),
            Some(Shape::rectangle(4.0, 0.2).unwrap()),
        ))
        .unwrap();
    let mut above = Some(bar);
    for k in 0..20 {
        let y = 9.75 - 0.5 * k as f64;
        let link = world
            .add_body(
                BodyDef::rigid("link", 0.5, Shape::rectangle(0.1, 0.5).unwrap())
                    .with_position(Vector2::new(0.0, y)),
            )
            .unwrap();
        let mut hinge = Revolute::default();
        if k % 2 == 1 {
            hinge.limits = Some((-0.5, 0.5));
            hinge.motor = Some(RevoluteMotor {
                speed: 0.0,
                max_torque: 0.1,
            });
            hinge.spring = Some(JointSpring::new(2.0, 0.5));
        }
        let at = Vector2::new(0.0, y + 0.25);
        world
            .add_joint(JointDef::revolute("hinge", above, Some(link), at, hinge))
            .unwrap();
        above = Some(link);
    }
    // Kick the chain so that it swings.
    let last = world.bodies().len() - 1;
    world
        .add_force_during(
            Box::new(etalon2d::forces::PointForce {
                body: last,
                force: Vector2::new(20.0, 0.0),
                local_point: Vector2::zeros(),
            }),
            etalon2d::TimeWindow::new(0.0, 0.2).unwrap(),
        )
        .unwrap();
    let bead = |x: f64| BodyDef::particle("bead", 1.0, Vector2::new(x, 8.0));
    for (x, joint) in [
        (3.0, Distance::default()),
        (5.0, Distance::rope(2.5)),
        (7.0, Distance::spring(1.0, 0.1)),
    ] {
        let b = world.add_body(bead(x)).unwrap();
        world
            .add_joint(JointDef::distance(
                "distance",
                (None, Vector2::new(x - 1.5, 9.0)),
                (Some(b), Vector2::new(x, 8.0)),
                joint,
            ))
            .unwrap();
    }
    let slider = world
        .add_body(
            BodyDef::rigid("slider", 1.0, Shape::rectangle(0.4, 0.2).unwrap())
                .with_position(Vector2::new(-4.0, 8.0)),
        )
        .unwrap();
    world
        .add_joint(JointDef::prismatic(
            "rail",
            None,
            Some(slider),
            Vector2::new(-4.0, 8.0),
            Prismatic {
                axis: Vector2::new(1.0, -1.0),
                limits: Some((-1.0, 1.0)),
                ..Prismatic::default()
            },
        ))
        .unwrap();
    let left = world
        .add_body(
            BodyDef::rigid("left", 1.0, Shape::rectangle(0.5, 0.5).unwrap())
                .with_position(Vector2::new(-6.0, 8.0))
                .with_rotation(0.0, 1.0),
        )
        .unwrap();
    let right = world
        .add_body(
            BodyDef::rigid("right", 1.0, Shape::rectangle(0.5, 0.5).unwrap())
                .with_position(Vector2::new(-5.5, 8.0)),
        )
        .unwrap();
    world
        .add_joint(JointDef::weld(
            "glue",
            Some(left),
            Some(right),
            Vector2::new(-5.75, 8.0),
            Weld::default(),
        ))
        .unwrap();
    world
        .add_joint(JointDef::target(
            "hand",
            right,
            Vector2::new(-5.5, 8.0),
            Vector2::new(-5.5, 9.0),
            Target::new(100.0),
        ))
        .unwrap();
    let dt = 1.0 / 60.0;
    for _ in 0..120 {
        world.step(dt).unwrap();
    }
    let before = ALLOCATIONS.with(Cell::get);
    for _ in 0..100 {
        world.step(dt).unwrap();
    }
    let made = ALLOCATIONS.with(Cell::get) - before;
    assert_eq!(made, 0, "{made} allocations in 100 steps with joints");
    // Still moving: the chain swings (no sleeping through the test).
    let swing = world.states()[last].velocity.norm();
    assert!(swing > 1e-3, "the chain stopped ({swing} m/s)");
    assert!(!world.is_asleep(last));
}

#[test]
fn events_hooks_and_contact_data_step_without_allocating() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    // Balls bouncing (restitution 0.9) on a ground, each through a static
    // sensor band above it: every bounce begins and ends touching, hits,
    // and enters and leaves the sensor; a pre-solve hook sees every
    // touching pair and a pair filter every new one; the contact data is
    // read after every step. Once the event lists have grown (the first
    // 240 steps), 240 more steps allocate nothing.
    use etalon2d::{ContactHooks, Filter, JointDef, PreSolveContact, Revolute, ShapeId};
    #[derive(Clone)]
    struct Counter {
        pre_solved: usize,
        filtered: usize,
    }
    impl ContactHooks for Counter {
        fn should_collide(&mut self, _: ShapeId, _: ShapeId) -> bool {
            self.filtered += 1;
            true
        }
        fn pre_solve(&mut self, _: &PreSolveContact) -> bool {
            self.pre_solved += 1;
            true
        }
    }
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
            Some(Shape::rectangle(40.0, 1.0).unwrap()),
        ))
        .unwrap();
    world
        .add_body(
            BodyDef::fixed(
                "band",
                Vector2::new(0.0, 1.0),
                Some(Shape::rectangle(40.0, 0.5).unwrap()),
            )
            .as_sensor(),
        )
        .unwrap();
    for k in 0..10 {
        world
            .add_body(
                BodyDef::rigid("ball", 1.0, Shape::circle(0.25).unwrap())
                    .with_position(Vector2::new(2.0 * k as f64 - 9.0, 2.0 + 0.1 * k as f64))
                    .with_material(0.6, 0.9)
                    .with_filter(Filter {
                        category: 2,
                        ..Filter::DEFAULT
                    }),
            )
            .unwrap();
    }
    // A box hanging from a hinge whose 1 N force threshold its 10 N weight
    // exceeds: a joint event every step.
    let hung = world
        .add_body(
            BodyDef::rigid("hung", 1.0, Shape::rectangle(0.5, 0.5).unwrap())
                .with_position(Vector2::new(0.0, 8.0)),
        )
        .unwrap();
    world
        .add_joint(
            JointDef::revolute(
                "hinge",
                None,
                Some(hung),
                Vector2::new(0.0, 8.0),
                Revolute::default(),
            )
            .with_thresholds(Some(1.0), None),
        )
        .unwrap();
    world
        .set_contact_hooks(Counter {
            pre_solved: 0,
            filtered: 0,
        })
        .unwrap();
    let dt = 1.0 / 60.0;
    let mut seen = [0usize; 6];
    let read = |world: &World, seen: &mut [usize; 6]| {
        let e = world.step_events().unwrap();
        seen[0] += e.touch_began.len();
        seen[1] += e.touch_ended.len();
        seen[2] += e.hits.len();
        seen[3] += e.sensor_began.len();
        seen[4] += e.sensor_ended.len();
        seen[5] += e.joints_exceeded.len();
        world
            .contact_data()
            .unwrap()
            .map(|c| {
                c.points()
                    .iter()
                    .map(|p| p.total_normal_impulse)
                    .sum::<f64>()
            })
            .sum::<f64>()
    };
    for _ in 0..240 {
        world.step(dt).unwrap();
        read(&world, &mut seen);
    }
    let warm = seen;
    let before = ALLOCATIONS.with(Cell::get);
    let mut impulse = 0.0;
    for _ in 0..240 {
        world.step(dt).unwrap();
        impulse += read(&world, &mut seen);
    }
    let made = ALLOCATIONS.with(Cell::get) - before;
    assert_eq!(made, 0, "{made} allocations in 240 steps with events");
    // Events did happen while counting: the balls still bounce through
    // the band and push on the ground.
    for k in 0..6 {
        assert!(seen[k] > warm[k], "event kind {k}: {seen:?} after {warm:?}");
    }
    assert!(impulse > 0.0);
}

#[test]
fn a_circling_bullet_steps_without_allocating() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    // A bullet on a revolute joint to the world at the origin, circling at
    // r = 1 m and 60 rad/s (1 m per step at 60 Hz, twenty times half its
    // 0.1 m side: swept every step), around a dynamic box at the centre
    // that its chords' boxes overlap now and then (the bullet pass lists
    // it, queries the trees and sweeps it against the box every step).
    use etalon2d::{JointDef, Revolute};
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap();
    world
        .add_body(BodyDef::rigid(
            "centre",
            1.0,
            Shape::rectangle(0.3, 0.3).unwrap(),
        ))
        .unwrap();
    let bullet = world
        .add_body(
            BodyDef::rigid("bullet", 0.1, Shape::rectangle(0.1, 0.1).unwrap())
                .with_position(Vector2::new(1.0, 0.0))
                .with_velocity(Vector2::new(0.0, 60.0))
                .with_rotation(0.0, 60.0)
                .as_bullet(),
        )
        .unwrap();
    world
        .add_joint(JointDef::revolute(
            "pivot",
            None,
            Some(bullet),
            Vector2::zeros(),
            Revolute::default(),
        ))
        .unwrap();
    let dt = 1.0 / 60.0;
    for _ in 0..120 {
        world.step(dt).unwrap();
    }
    let before = ALLOCATIONS.with(Cell::get);
    for _ in 0..100 {
        world.step(dt).unwrap();
    }
    let made = ALLOCATIONS.with(Cell::get) - before;
    assert_eq!(made, 0, "{made} allocations in 100 steps with a bullet");
    // Still swept at the end (the joint's soft rows slow the orbit): it
    // moves more than FAST_FRACTION (0.5) of its smallest extent (0.05 m)
    // per step, and still about the origin.
    let s = world.states()[bullet];
    assert!(
        s.velocity.norm() * dt > 0.5 * 0.05,
        "bullet at {} m/s",
        s.velocity.norm()
    );
    assert!(
        (s.position.norm() - 1.0).abs() < 0.1,
        "radius {}",
        s.position.norm()
    );
}
