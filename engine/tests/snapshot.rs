//! Snapshots (engine/src/world/snapshot.rs): a world cloned in memory, or
//! written as bytes (CBOR through ciborium, which keeps every f64's bits)
//! and read back, steps to the same bits as the uninterrupted run: every
//! body's state at every later step, exactly (a restored trajectory that
//! differed in one bit would show it: the soft step is deterministic, so
//! the tolerance is zero). Tested on a settling pyramid hit by a jointed
//! pendulum (engine/tests/snapshot/scene.rs), whose contacts, joints,
//! islands, sleep timers, forces and controls the snapshot must carry.
//! And the refusals: a force of the program's own type, the exact model,
//! bytes of another format.

use etalon2d as engine;
use etalon2d::prelude::*;

include!("snapshot/scene.rs");

const DT: f64 = 1.0 / 60.0;

fn to_bytes(world: &World) -> Vec<u8> {
    let mut bytes = Vec::new();
    ciborium::into_writer(world, &mut bytes).expect("a soft-step world with built-in forces");
    bytes
}

fn from_bytes(bytes: &[u8]) -> World {
    ciborium::from_reader(bytes).expect("bytes written by the same engine")
}

/// Steps `a` and `b` alike `steps` times and checks that every state is
/// the same, bit for bit, after every step.
fn assert_same_trajectory(a: &mut World, b: &mut World, steps: usize) {
    for step in 0..steps {
        a.step(DT).unwrap();
        b.step(DT).unwrap();
        assert_eq!(
            a.state_hash(),
            b.state_hash(),
            "hashes differ after step {step}"
        );
        for (id, (sa, sb)) in a.states().iter().zip(b.states()).enumerate() {
            for (x, y) in [
                (sa.position.x, sb.position.x),
                (sa.position.y, sb.position.y),
                (sa.angle, sb.angle),
                (sa.velocity.x, sb.velocity.x),
                (sa.velocity.y, sb.velocity.y),
                (sa.angular_velocity, sb.angular_velocity),
            ] {
                assert_eq!(x.to_bits(), y.to_bits(), "body {id} after step {step}");
            }
        }
    }
    assert_eq!(a.time(), b.time());
}

/// The world stepped to the snapshot, with a force and a kick pending for
/// the next step (they must be carried too).
fn at_snapshot() -> World {
    let mut world = pyramid_with_joints();
    for _ in 0..SNAPSHOT_STEP {
        world.step(DT).unwrap();
    }
    let top = 10;
    world
        .apply_force(top, Vector2::new(3.0, 0.0), world.states()[top].position)
        .unwrap();
    world
}

#[test]
fn a_clone_steps_to_the_same_bits() {
    let mut original = at_snapshot();
    let mut copy = original.clone();
    assert_eq!(copy.state_hash(), original.state_hash());
    assert_same_trajectory(&mut original, &mut copy, STEPS_AFTER);
}

#[test]
fn a_world_restored_from_bytes_steps_to_the_same_bits() {
    let mut original = at_snapshot();
    let bytes = to_bytes(&original);
    let mut restored = from_bytes(&bytes);
    assert_eq!(restored.state_hash(), original.state_hash());
    assert_eq!(restored.bodies(), original.bodies());
    assert_eq!(restored.joint_count(), original.joint_count());
    assert_same_trajectory(&mut original, &mut restored, STEPS_AFTER);
    // Something happened after the snapshot: the pendulum hit the pyramid
    // and its boxes moved (contacts made and broken after the restore).
    let before = at_snapshot();
    let moved = PYRAMID
        .filter(|&id| (original.states()[id].position - before.states()[id].position).norm() > 0.01)
        .count();
    println!("{moved} pyramid boxes moved more than 1 cm after the snapshot");
    assert!(
        moved >= 5,
        "only {moved} pyramid boxes moved after the snapshot"
    );
    // Written again after the run, it is the same world again.
    let again = from_bytes(&to_bytes(&original));
    assert_eq!(again.state_hash(), original.state_hash());
}

#[test]
fn poses_and_velocities_alone_are_not_a_snapshot() {
    // The control for the tests above: a new world set to the same poses
    // and velocities, without the contacts' and joints' impulses, islands
    // and broad-phase order, leaves the original's trajectory: what the
    // snapshot carries beyond the states matters, and the comparison sees
    // it.
    let mut original = at_snapshot();
    let mut rebuilt = pyramid_with_joints();
    for (id, s) in original.states().to_vec().into_iter().enumerate().skip(1) {
        rebuilt.set_pose(id, s.position, s.angle).unwrap();
        rebuilt
            .set_velocity(id, s.velocity, s.angular_velocity)
            .unwrap();
    }
    let top = 10;
    rebuilt
        .apply_force(top, Vector2::new(3.0, 0.0), rebuilt.states()[top].position)
        .unwrap();
    assert_eq!(rebuilt.state_hash(), original.state_hash());
    let mut differed = false;
    for _ in 0..STEPS_AFTER {
        original.step(DT).unwrap();
        rebuilt.step(DT).unwrap();
        differed |= original.state_hash() != rebuilt.state_hash();
    }
    assert!(
        differed,
        "a world without the step's caches should not follow to the bit"
    );
}

#[test]
fn the_state_hash_tells_poses_apart() {
    let world = at_snapshot();
    let mut moved = world.clone();
    let s = moved.states()[1];
    moved
        .set_pose(1, s.position + Vector2::new(f64::EPSILON, 0.0), s.angle)
        .unwrap();
    assert_ne!(moved.state_hash(), world.state_hash());
}

/// A force of the program's own type.
#[derive(Debug)]
struct Wind;

impl Force for Wind {
    fn name(&self) -> &str {
        "wind"
    }
    fn bodies(&self) -> Vec<BodyId> {
        Vec::new()
    }
    fn apply(&self, ctx: &etalon2d::ForceContext<'_>, wrenches: &mut [etalon2d::Wrench]) {
        for (w, b) in wrenches.iter_mut().zip(ctx.bodies) {
            if b.is_dynamic() {
                w.force.x += 0.1;
            }
        }
    }
}

#[test]
fn what_cannot_be_written_is_refused_with_a_typed_error() {
    let mut world = at_snapshot();
    let wind = world.add_force(Wind).unwrap();
    let e = world.check_serializable().unwrap_err();
    assert!(matches!(e, EngineError::NotSerializable { .. }), "{e}");
    assert!(e.to_string().contains("force 'wind'"), "{e}");
    let mut bytes = Vec::new();
    let written = ciborium::into_writer(&world, &mut bytes).unwrap_err();
    assert!(written.to_string().contains("force 'wind'"), "{written}");
    // A clone keeps the user's force; removed, the world can be written.
    let mut copy = world.clone();
    assert_same_trajectory(&mut world, &mut copy, 5);
    world.remove_force(wind).unwrap();
    world.check_serializable().unwrap();

    // The exact model: clone only.
    let mut exact = World::new(Method::Rk4).unwrap();
    exact
        .add_body(BodyDef::particle("p", 1.0, Vector2::zeros()))
        .unwrap();
    let e = exact.check_serializable().unwrap_err();
    assert!(e.to_string().contains("exact contact model"), "{e}");
    let _ = exact.clone();

    // Bytes of another format number, and bytes that are not a world.
    let mut value: ciborium::Value = ciborium::from_reader(&to_bytes(&world)[..]).unwrap();
    if let ciborium::Value::Map(fields) = &mut value {
        fields[0].1 = ciborium::Value::Integer(99.into());
    }
    let mut changed = Vec::new();
    ciborium::into_writer(&value, &mut changed).unwrap();
    let e = ciborium::from_reader::<World, _>(&changed[..]).unwrap_err();
    assert!(e.to_string().contains("format 99"), "{e}");
    assert!(ciborium::from_reader::<World, _>(&b"not a world"[..]).is_err());
}

/// A world can be moved to another thread (the live view steps it on one;
/// a program may too): every part of it, hooks included, is `Send`.
#[test]
fn a_world_is_send() {
    fn send<T: Send>(_: &T) {}
    send(&pyramid_with_joints());
}
