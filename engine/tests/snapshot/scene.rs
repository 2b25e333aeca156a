// The world of the snapshot tests, in one place: included (`include!`) by
// engine/tests/snapshot.rs and the harness's `snapshot_restore` case
// (harness/src/cases/snapshot_restore.rs), so that both restore the same
// world.

/// Steps of 1/60 s before the snapshot (the pendulum is swinging down
/// toward the pyramid, whose contacts carry warm-starting impulses) and
/// after it (the pendulum hits the pyramid).
const SNAPSHOT_STEP: usize = 40;
const STEPS_AFTER: usize = 80;

/// Bodies 1 to 10: the pyramid's boxes.
const PYRAMID: std::ops::RangeInclusive<usize> = 1..=10;

/// A pyramid of 10 boxes (base 4) on the ground, sleeping on, hit by a
/// pendulum of three boxes hinged to the world and to each other
/// (revolute joints with limits and a spring, one weld), with a spring
/// force, one body's gravity scaled and damped: contacts, joints, islands,
/// sleep, forces and controls, all of which a snapshot must carry.
fn pyramid_with_joints() -> engine::World {
    use engine::prelude::*;
    let settings = SoftStepSettings {
        sleeping: true,
        ..SoftStepSettings::default()
    };
    let mut world =
        World::with_model(Method::SemiImplicitEuler, ContactModel::SoftStep(settings)).unwrap();
    world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(40.0, 1.0).unwrap()),
        ))
        .unwrap();
    let size = 0.5;
    let base = 4;
    for row in 0..base {
        for k in 0..base - row {
            let x = (k as f64 - 0.5 * (base - row - 1) as f64) * size * 1.05;
            let y = 0.5 * size + row as f64 * size;
            world
                .add_body(
                    BodyDef::rigid(
                        &format!("box {row}.{k}"),
                        1.0,
                        Shape::rectangle(size, size).unwrap(),
                    )
                    .with_position(Vector2::new(x, y)),
                )
                .unwrap();
        }
    }
    // The pendulum: three links of 0.8 m and 5 kg from the pivot
    // (-1.2, 2.6), released horizontally away from the pyramid: it swings
    // down into the pyramid's lower rows (its tip's circle, radius 2.4 m,
    // passes 0.5 m left of the centre 0.3 m high) between steps 40 and 50,
    // just after the snapshot, and every box moves.
    let pivot = Vector2::new(-1.2, 2.6);
    let mut previous: Option<BodyId> = None;
    for k in 0..3 {
        let center = pivot - Vector2::new(0.4 + 0.8 * k as f64, 0.0);
        let link = world
            .add_body(
                BodyDef::rigid(&format!("link {k}"), 5.0, Shape::rectangle(0.8, 0.2).unwrap())
                    .with_position(center),
            )
            .unwrap();
        let anchor = center + Vector2::new(0.4, 0.0);
        let joint = if k == 2 {
            JointDef::weld(&format!("weld {k}"), previous, Some(link), anchor, Weld::default())
        } else {
            let hinge = Revolute {
                limits: Some((-2.5, 2.5)),
                spring: Some(JointSpring {
                    hertz: 1.0,
                    damping_ratio: 0.2,
                }),
                ..Revolute::default()
            };
            JointDef::revolute(&format!("hinge {k}"), previous, Some(link), anchor, hinge)
        };
        world.add_joint(joint).unwrap();
        previous = Some(link);
    }
    let last = previous.unwrap();
    world
        .add_force(Spring {
            a: Attachment::World(Vector2::new(4.0, 4.0)),
            b: Attachment::center_of(last),
            stiffness: 5.0,
            rest_length: 2.0,
            axis: None,
        })
        .unwrap();
    world.set_gravity_scale(last, 0.8).unwrap();
    world.set_damping(last, 0.1, 0.2).unwrap();
    world
}
