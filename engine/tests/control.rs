//! Driving a world from a program between steps: every control call of
//! [`World`] (engine/src/world/control.rs), its effect against the closed
//! form of one step of the soft step (symplectic Euler per substep), its
//! refusals (typed errors for NaN, unknown or removed bodies, kinds that
//! cannot take it, the exact model), and that a refused call leaves the
//! world as it was: the world after the error steps to the same bits as a
//! clone taken before the call.

use etalon2d::prelude::*;

const DT: f64 = 1.0 / 60.0;

/// A soft-step world without gravity, sleeping on.
fn soft_world() -> World {
    let settings = SoftStepSettings {
        sleeping: true,
        ..SoftStepSettings::default()
    };
    World::with_model(Method::SemiImplicitEuler, ContactModel::SoftStep(settings)).unwrap()
}

/// Ground (0), a 1 m box resting on it (1), a free particle far away (2),
/// a kinematic paddle far away (3), a static post (4), a removed box (5);
/// gravity −10.
fn scene() -> World {
    let mut world = soft_world();
    world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
    world
        .add_body(BodyDef::fixed(
            "ground",
            Vector2::new(0.0, -0.5),
            Some(Shape::rectangle(20.0, 1.0).unwrap()),
        ))
        .unwrap();
    world
        .add_body(
            BodyDef::rigid("box", 2.0, Shape::rectangle(1.0, 1.0).unwrap())
                .with_position(Vector2::new(0.0, 0.5)),
        )
        .unwrap();
    world
        .add_body(BodyDef::particle("dot", 0.5, Vector2::new(50.0, 50.0)))
        .unwrap();
    world
        .add_body(BodyDef::kinematic(
            "paddle",
            Vector2::new(-50.0, 10.0),
            Shape::rectangle(2.0, 0.2).unwrap(),
            Vector2::zeros(),
            0.0,
        ))
        .unwrap();
    world
        .add_body(BodyDef::fixed(
            "post",
            Vector2::new(30.0, 1.0),
            Some(Shape::rectangle(0.2, 2.0).unwrap()),
        ))
        .unwrap();
    let gone = world
        .add_body(
            BodyDef::rigid("gone", 1.0, Shape::rectangle(1.0, 1.0).unwrap())
                .with_position(Vector2::new(-30.0, 5.0)),
        )
        .unwrap();
    world.remove_body(gone).unwrap();
    world
}

const BOX: BodyId = 1;
const DOT: BodyId = 2;
const PADDLE: BodyId = 3;
const POST: BodyId = 4;
const GONE: BodyId = 5;

/// `after` (which refused a call) is `before` (a clone taken before it):
/// same bodies, states and time, and ten more steps of each give the same
/// bits.
fn assert_unchanged(before: &World, after: &World) {
    assert_eq!(before.bodies(), after.bodies());
    assert_eq!(before.states(), after.states());
    assert_eq!(before.time(), after.time());
    let (mut a, mut b) = (before.clone(), after.clone());
    for _ in 0..10 {
        a.step(DT).unwrap();
        b.step(DT).unwrap();
    }
    assert_eq!(
        a.state_hash(),
        b.state_hash(),
        "the refused call changed the world"
    );
    assert_eq!(a.states(), b.states());
}

/// Runs `call` on a clone of `world`, expects an error whose message
/// contains `says`, and checks the world is unchanged.
fn refused(world: &World, says: &str, call: impl FnOnce(&mut World) -> Result<()>) -> EngineError {
    let mut after = world.clone();
    let error = call(&mut after).expect_err("the call should be refused");
    assert!(
        error.to_string().contains(says),
        "error '{error}' should say '{says}'"
    );
    assert_unchanged(world, &after);
    error
}

/// Settles the scene for a second, so that the box rests (and sleeps).
fn settled() -> World {
    let mut world = scene();
    for _ in 0..60 {
        world.step(DT).unwrap();
    }
    world
}

#[test]
fn setting_a_pose_moves_the_body_and_wakes_it() {
    let mut world = settled();
    assert!(
        world.is_asleep(BOX),
        "the box sleeps after a second at rest"
    );
    world.set_pose(BOX, Vector2::new(3.0, 4.0), 0.25).unwrap();
    assert!(!world.is_asleep(BOX));
    let s = world.states()[BOX];
    assert_eq!((s.position, s.angle), (Vector2::new(3.0, 4.0), 0.25));
    // It falls from there: one step of g = −10 from rest, v = −10 dt.
    world.step(DT).unwrap();
    let v = world.states()[BOX].velocity.y;
    assert!((v + 10.0 * DT).abs() < 1e-12, "v = {v}");
    // Static bodies move too (a teleport), and the particle keeps angle 0.
    world.set_pose(POST, Vector2::new(31.0, 1.0), 0.0).unwrap();
    assert_eq!(world.states()[POST].position.x, 31.0);
    world.set_pose(DOT, Vector2::new(1.0, 60.0), 1.0).unwrap();
    assert_eq!(world.states()[DOT].angle, 0.0);

    let world = settled();
    let e = refused(&world, "must be finite", |w| {
        w.set_pose(BOX, Vector2::new(f64::NAN, 0.0), 0.0)
    });
    assert!(matches!(e, EngineError::InvalidParameter { .. }));
    refused(&world, "must be finite", |w| {
        w.set_pose(BOX, Vector2::zeros(), f64::INFINITY)
    });
    let e = refused(&world, "unknown body", |w| {
        w.set_pose(99, Vector2::zeros(), 0.0)
    });
    assert!(matches!(e, EngineError::UnknownBody { index: 99, .. }));
    let e = refused(&world, "removed", |w| {
        w.set_pose(GONE, Vector2::zeros(), 0.0)
    });
    assert!(matches!(e, EngineError::RemovedBody { index: GONE, .. }));
}

#[test]
fn setting_a_velocity_takes_effect_at_the_next_step() {
    let mut world = settled();
    world
        .set_velocity(BOX, Vector2::new(0.0, 5.0), 2.0)
        .unwrap();
    assert!(!world.is_asleep(BOX));
    let y0 = world.states()[BOX].position.y;
    world.step(DT).unwrap();
    let s = world.states()[BOX];
    // Leaving the ground: v = 5 − 10 dt after the step, and it rose.
    assert!(
        (s.velocity.y - (5.0 - 10.0 * DT)).abs() < 1e-9,
        "{}",
        s.velocity.y
    );
    assert!(s.position.y > y0);
    // A kinematic body keeps its velocity.
    world
        .set_velocity(PADDLE, Vector2::new(1.0, 0.0), 0.5)
        .unwrap();
    for _ in 0..3 {
        world.step(DT).unwrap();
    }
    let p = world.states()[PADDLE];
    assert_eq!((p.velocity.x, p.angular_velocity), (1.0, 0.5));
    assert!((p.position.x - (-50.0 + 3.0 * DT)).abs() < 1e-12);

    let world = settled();
    let e = refused(&world, "static body 'post'", |w| {
        w.set_velocity(POST, Vector2::new(1.0, 0.0), 0.0)
    });
    assert!(matches!(e, EngineError::Unsupported { .. }));
    refused(&world, "does not rotate", |w| {
        w.set_velocity(DOT, Vector2::zeros(), 1.0)
    });
    refused(&world, "must be finite", |w| {
        w.set_velocity(BOX, Vector2::new(0.0, f64::NEG_INFINITY), 0.0)
    });
    refused(&world, "removed", |w| {
        w.set_velocity(GONE, Vector2::zeros(), 0.0)
    });
}

#[test]
fn an_applied_force_acts_for_one_step_only() {
    let mut world = soft_world();
    let id = world
        .add_body(BodyDef::rigid(
            "box",
            2.0,
            Shape::rectangle(1.0, 2.0).unwrap(),
        ))
        .unwrap();
    let inertia = world.bodies()[id].inertia.unwrap();
    // 4 N along x at 1 m above the centre: torque r × F = (0, 1) × (4, 0)
    // = −4 N·m; twice (calls add up).
    for _ in 0..2 {
        world
            .apply_force(id, Vector2::new(4.0, 0.0), Vector2::new(0.0, 1.0))
            .unwrap();
    }
    world.step(DT).unwrap();
    let s = world.states()[id];
    // v = Σ h F/m over the substeps = dt·8/2; ω = dt·(−8)/I.
    assert!((s.velocity.x - 4.0 * DT).abs() < 1e-15, "{}", s.velocity.x);
    assert!((s.angular_velocity + 8.0 * DT / inertia).abs() < 1e-14);
    world.step(DT).unwrap();
    let t = world.states()[id];
    assert_eq!(t.velocity, s.velocity, "the force is gone after one step");
    assert_eq!(t.angular_velocity, s.angular_velocity);
    // A torque alone.
    world.apply_torque(id, 3.0).unwrap();
    world.step(DT).unwrap();
    let u = world.states()[id];
    assert!((u.angular_velocity - t.angular_velocity - 3.0 * DT / inertia).abs() < 1e-14);

    let world = scene();
    let e = refused(&world, "static body 'post'", |w| {
        w.apply_force(POST, Vector2::new(1.0, 0.0), Vector2::zeros())
    });
    assert!(matches!(e, EngineError::Unsupported { .. }));
    refused(&world, "kinematic body 'paddle'", |w| {
        w.apply_torque(PADDLE, 1.0)
    });
    refused(&world, "does not rotate", |w| w.apply_torque(DOT, 1.0));
    refused(&world, "must be finite", |w| {
        w.apply_force(BOX, Vector2::new(f64::NAN, 0.0), Vector2::zeros())
    });
    refused(&world, "must be finite", |w| {
        w.apply_force(
            BOX,
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, f64::INFINITY),
        )
    });
    // A sum that overflows is refused, the first force kept.
    let mut pushed = world.clone();
    pushed
        .apply_force(BOX, Vector2::new(1e308, 0.0), Vector2::zeros())
        .unwrap();
    refused(&pushed, "must be finite", |w| {
        w.apply_force(BOX, Vector2::new(1e308, 0.0), Vector2::zeros())
    });
    refused(&world, "removed", |w| w.apply_torque(GONE, 1.0));
}

#[test]
fn impulses_change_the_velocities_at_once() {
    let mut world = settled();
    let body = world.bodies()[BOX].clone();
    let (m, i) = (body.mass, body.inertia.unwrap());
    let s0 = world.states()[BOX];
    // 3 N·s up at 0.5 m right of the centre: Δv = J/m, Δω = (r × J)/I.
    let point = s0.position + Vector2::new(0.5, 0.0);
    world
        .apply_linear_impulse(BOX, Vector2::new(0.0, 3.0), point)
        .unwrap();
    let s = world.states()[BOX];
    assert_eq!(s.velocity.y, s0.velocity.y + 3.0 / m);
    assert_eq!(s.angular_velocity, s0.angular_velocity + 0.5 * 3.0 / i);
    assert!(!world.is_asleep(BOX));
    world.apply_angular_impulse(BOX, -1.5).unwrap();
    assert_eq!(
        world.states()[BOX].angular_velocity,
        s.angular_velocity - 1.5 / i
    );
    // A particle takes the linear part only.
    world
        .apply_linear_impulse(DOT, Vector2::new(1.0, 0.0), Vector2::new(0.0, 0.0))
        .unwrap();
    assert_eq!(world.states()[DOT].velocity.x, 1.0 / 0.5);
    assert_eq!(world.states()[DOT].angular_velocity, 0.0);

    let world = settled();
    refused(&world, "static body", |w| {
        w.apply_linear_impulse(POST, Vector2::new(1.0, 0.0), Vector2::zeros())
    });
    refused(&world, "does not rotate", |w| {
        w.apply_angular_impulse(DOT, 1.0)
    });
    refused(&world, "must be finite", |w| {
        w.apply_angular_impulse(BOX, f64::NAN)
    });
    // A velocity that overflows is refused, the first kick kept.
    let mut kicked = world.clone();
    kicked
        .apply_linear_impulse(BOX, Vector2::new(1e308, 0.0), Vector2::zeros())
        .unwrap();
    let after = kicked.clone();
    let e = kicked
        .apply_linear_impulse(BOX, Vector2::new(1e308, 0.0), Vector2::zeros())
        .unwrap_err();
    assert!(e.to_string().contains("after the impulse"), "{e}");
    assert_eq!(kicked.states(), after.states());
    refused(&world, "unknown body", |w| w.apply_angular_impulse(7, 1.0));
}

#[test]
fn a_kinematic_target_is_reached_in_one_step() {
    let mut world = scene();
    let target = Vector2::new(-49.0, 10.5);
    world.set_target_pose(PADDLE, target, 0.3, DT).unwrap();
    world.step(DT).unwrap();
    let p = world.states()[PADDLE];
    // Reached to the round-off of the substeps' sum (4 additions of
    // h·v, each within half an ulp of ~50 m: 4 × 3.6e-15 m; 1e-13 allows
    // for the velocity's own rounding).
    assert!((p.position - target).norm() < 1e-13, "{:?}", p.position);
    assert!((p.angle - 0.3).abs() < 1e-15, "{}", p.angle);
    // Box2D's semantics: the velocity stays until set again.
    assert_eq!(p.velocity, (target - Vector2::new(-50.0, 10.0)) / DT);

    let world = scene();
    refused(&world, "dynamic body 'box'", |w| {
        w.set_target_pose(BOX, Vector2::zeros(), 0.0, DT)
    });
    refused(&world, "must be finite and > 0", |w| {
        w.set_target_pose(PADDLE, Vector2::zeros(), 0.0, 0.0)
    });
    refused(&world, "must be finite", |w| {
        w.set_target_pose(PADDLE, Vector2::zeros(), f64::NAN, DT)
    });
    refused(&world, "must be finite", |w| {
        w.set_target_pose(PADDLE, Vector2::new(1e308, 0.0), 0.0, 1e-300)
    });
}

#[test]
fn a_body_changes_kind() {
    let mut world = settled();
    // The box made static stays where it is; made dynamic again it has
    // its mass back and falls when the ground is gone.
    world.set_body_kind(BOX, BodyKind::Static).unwrap();
    assert_eq!(world.bodies()[BOX].kind, BodyKind::Static);
    assert_eq!(world.bodies()[BOX].mass, f64::INFINITY);
    let y = world.states()[BOX].position.y;
    world.step(DT).unwrap();
    assert_eq!(world.states()[BOX].position.y, y);
    world.set_body_kind(BOX, BodyKind::Dynamic).unwrap();
    assert_eq!(world.bodies()[BOX].mass, 2.0);
    world.set_enabled(0, false).unwrap();
    world.step(DT).unwrap();
    assert!((world.states()[BOX].velocity.y + 10.0 * DT).abs() < 1e-12);
    // Kinematic: it keeps its velocity and pushes what it touches.
    world.set_body_kind(BOX, BodyKind::Kinematic).unwrap();
    let v = world.states()[BOX].velocity;
    world.step(DT).unwrap();
    assert_eq!(world.states()[BOX].velocity, v);
    // A body created static has no mass: refused until it gets one.
    let world2 = world.clone();
    let e = refused(&world2, "set_mass_properties", |w| {
        w.set_body_kind(POST, BodyKind::Dynamic)
    });
    assert!(matches!(e, EngineError::InvalidParameter { .. }));
    world.set_mass_properties(POST, 3.0, Some(1.0)).unwrap();
    world.set_body_kind(POST, BodyKind::Dynamic).unwrap();
    assert_eq!(world.bodies()[POST].mass, 3.0);
    assert_eq!(world.bodies()[POST].inertia, Some(1.0));
    world.step(DT).unwrap();
    assert!(world.states()[POST].velocity.y < 0.0, "the post falls");

    // A joint must keep a dynamic body.
    let mut world = scene();
    world
        .add_joint(JointDef::revolute(
            "pin",
            None,
            Some(BOX),
            Vector2::new(0.0, 1.0),
            Revolute::default(),
        ))
        .unwrap();
    let e = refused(&world, "joint 'pin'", |w| {
        w.set_body_kind(BOX, BodyKind::Static)
    });
    assert!(matches!(e, EngineError::Unsupported { .. }));
    refused(&world, "removed", |w| {
        w.set_body_kind(GONE, BodyKind::Static)
    });
    // Same kind: nothing to do.
    let mut same = world.clone();
    same.set_body_kind(BOX, BodyKind::Dynamic).unwrap();
    assert_unchanged(&world, &same);
}

#[test]
fn a_disabled_body_takes_no_part() {
    let mut world = settled();
    // The ground disabled: the box falls through where it was.
    world.set_enabled(0, false).unwrap();
    assert!(!world.is_enabled(0));
    assert!(world.bodies()[0].shape.is_none());
    for _ in 0..30 {
        world.step(DT).unwrap();
    }
    assert!(
        world.states()[BOX].position.y < -0.5,
        "the box fell through"
    );
    // Enabled again: its shape is back and it stops a box dropped on it.
    world.set_enabled(0, true).unwrap();
    assert!(world.bodies()[0].shape.is_some());
    world.set_pose(BOX, Vector2::new(0.0, 2.0), 0.0).unwrap();
    world.set_velocity(BOX, Vector2::zeros(), 0.0).unwrap();
    for _ in 0..120 {
        world.step(DT).unwrap();
    }
    let y = world.states()[BOX].position.y;
    assert!(
        (y - 0.5).abs() < 0.01,
        "the box rests on the ground again at {y}"
    );
    // A disabled dynamic body keeps its velocity for later.
    world
        .set_velocity(DOT, Vector2::new(1.0, 0.0), 0.0)
        .unwrap();
    world.set_enabled(DOT, false).unwrap();
    let x = world.states()[DOT].position.x;
    world.step(DT).unwrap();
    assert_eq!(world.states()[DOT].position.x, x);
    let refused_world = world.clone();
    refused(&refused_world, "disabled body 'dot'", |w| {
        w.set_velocity(DOT, Vector2::zeros(), 0.0)
    });
    world.set_enabled(DOT, true).unwrap();
    assert_eq!(world.states()[DOT].velocity.x, 1.0);
    // A jointed body cannot be disabled.
    let mut world = scene();
    world
        .add_joint(JointDef::revolute(
            "pin",
            None,
            Some(BOX),
            Vector2::new(0.0, 1.0),
            Revolute::default(),
        ))
        .unwrap();
    refused(&world, "joint 'pin'", |w| w.set_enabled(BOX, false));
    refused(&world, "removed", |w| w.set_enabled(GONE, false));
}

#[test]
fn gravity_scale_and_damping_act_in_the_velocity_stage() {
    let mut world = scene();
    world.set_pose(DOT, Vector2::new(50.0, 50.0), 0.0).unwrap();
    world.set_gravity_scale(DOT, 0.5).unwrap();
    assert_eq!(world.gravity_scale(DOT).unwrap(), 0.5);
    world.step(DT).unwrap();
    assert!((world.states()[DOT].velocity.y + 5.0 * DT).abs() < 1e-15);
    // Damping alone (scale 0): v_n = v0 / (1 + h c)^n over n = 4
    // substeps of h = dt/4.
    world.set_gravity_scale(DOT, 0.0).unwrap();
    world
        .set_velocity(DOT, Vector2::new(3.0, 0.0), 0.0)
        .unwrap();
    world.set_damping(DOT, 2.0, 0.0).unwrap();
    world.step(DT).unwrap();
    let h = DT / 4.0;
    let expected = 3.0 / (1.0 + h * 2.0f64).powi(4);
    let v = world.states()[DOT].velocity;
    assert!((v.x - expected).abs() < 1e-14, "{} vs {expected}", v.x);
    assert_eq!(v.y, 0.0);
    // Angular damping on the box in the air.
    world.set_pose(BOX, Vector2::new(0.0, 30.0), 0.0).unwrap();
    world.set_gravity_scale(BOX, 0.0).unwrap();
    world.set_velocity(BOX, Vector2::zeros(), 1.0).unwrap();
    world.set_damping(BOX, 0.0, 5.0).unwrap();
    world.step(DT).unwrap();
    let w = world.states()[BOX].angular_velocity;
    assert!((w - 1.0 / (1.0 + h * 5.0f64).powi(4)).abs() < 1e-14, "{w}");
    assert_eq!(world.damping(BOX).unwrap(), (0.0, 5.0));

    let world = scene();
    refused(&world, "must be finite", |w| {
        w.set_gravity_scale(DOT, f64::NAN)
    });
    refused(&world, "must be finite and >= 0", |w| {
        w.set_damping(DOT, -1.0, 0.0)
    });
    refused(&world, "must be finite and >= 0", |w| {
        w.set_damping(DOT, 0.0, f64::INFINITY)
    });
    refused(&world, "removed", |w| w.set_damping(GONE, 1.0, 1.0));
}

#[test]
fn a_locked_rotation_takes_no_spin() {
    let mut world = scene();
    world.set_pose(BOX, Vector2::new(0.0, 30.0), 0.0).unwrap();
    world.set_velocity(BOX, Vector2::zeros(), 2.0).unwrap();
    world.set_fixed_rotation(BOX, true).unwrap();
    assert!(world.has_fixed_rotation(BOX).unwrap());
    assert_eq!(world.bodies()[BOX].inertia, None);
    assert_eq!(world.states()[BOX].angular_velocity, 0.0);
    world
        .apply_linear_impulse(BOX, Vector2::new(0.0, 1.0), Vector2::new(0.5, 30.0))
        .unwrap();
    world.step(DT).unwrap();
    assert_eq!(world.states()[BOX].angular_velocity, 0.0);
    assert_eq!(world.states()[BOX].angle, 0.0);
    let before = world.clone();
    refused(&before, "does not rotate", |w| {
        w.apply_angular_impulse(BOX, 1.0)
    });
    world.set_fixed_rotation(BOX, false).unwrap();
    let inertia = world.bodies()[BOX].inertia.expect("its inertia is back");
    world.apply_angular_impulse(BOX, 1.0).unwrap();
    assert_eq!(world.states()[BOX].angular_velocity, 1.0 / inertia);
}

#[test]
fn mass_properties_are_replaced() {
    let mut world = scene();
    world.set_mass_properties(BOX, 8.0, Some(4.0)).unwrap();
    assert_eq!(world.bodies()[BOX].mass, 8.0);
    world
        .apply_linear_impulse(BOX, Vector2::new(8.0, 0.0), Vector2::new(0.0, 1.5))
        .unwrap();
    let s = world.states()[BOX];
    assert_eq!(s.velocity.x, 1.0);
    // r = (0, 1): r × J = −8, over I = 4.
    assert_eq!(s.angular_velocity, -2.0);
    refused(&world, "must be finite and > 0", |w| {
        w.set_mass_properties(BOX, 0.0, Some(1.0))
    });
    refused(&world, "must be finite and > 0", |w| {
        w.set_mass_properties(BOX, 1.0, Some(f64::NAN))
    });
    refused(&world, "needs an inertia", |w| {
        w.set_mass_properties(BOX, 1.0, None)
    });
    refused(&world, "removed", |w| {
        w.set_mass_properties(GONE, 1.0, Some(1.0))
    });
}

#[test]
fn user_values_and_forces_by_id() {
    let mut world = scene();
    world.set_user_value(BOX, 42).unwrap();
    assert_eq!(world.user_value(BOX).unwrap(), 42);
    assert_eq!(world.user_value(DOT).unwrap(), 0);
    assert!(matches!(
        world.set_user_value(99, 1),
        Err(EngineError::UnknownBody { .. })
    ));
    let joint = world
        .add_joint(JointDef::revolute(
            "pin",
            None,
            Some(BOX),
            Vector2::new(0.0, 1.0),
            Revolute::default(),
        ))
        .unwrap();
    world.set_joint_user_value(joint, 7).unwrap();
    assert_eq!(world.joint_user_value(joint).unwrap(), 7);
    assert!(matches!(
        world.set_joint_user_value(3, 1),
        Err(EngineError::UnknownJoint { .. })
    ));

    // A force removed by its id acts no more.
    let mut world = soft_world();
    let id = world
        .add_body(BodyDef::particle("p", 1.0, Vector2::zeros()))
        .unwrap();
    let push = world
        .add_force(PointForce {
            body: id,
            force: Vector2::new(1.0, 0.0),
            local_point: Vector2::zeros(),
        })
        .unwrap();
    world.step(DT).unwrap();
    let v = world.states()[id].velocity.x;
    assert!((v - DT).abs() < 1e-15);
    world.remove_force(push).unwrap();
    world.step(DT).unwrap();
    assert_eq!(world.states()[id].velocity.x, v);
    let before = world.clone();
    let e = refused(&before, "unknown force", |w| w.remove_force(push));
    assert!(matches!(e, EngineError::UnknownForce { .. }));
}

#[test]
fn under_the_exact_model_each_call_works_or_names_the_model() {
    let mut world = World::new(Method::Rk4).unwrap();
    world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
    let ball = world
        .add_body(
            BodyDef::rigid("ball", 1.0, Shape::circle(0.5).unwrap())
                .with_position(Vector2::new(0.0, 10.0)),
        )
        .unwrap();
    let post = world
        .add_body(BodyDef::fixed(
            "post",
            Vector2::new(5.0, 0.0),
            Some(Shape::rectangle(1.0, 1.0).unwrap()),
        ))
        .unwrap();
    // What works: pose, velocity, forces, impulses, kind (dynamic and
    // static), enabling, mass, user values.
    world.set_pose(ball, Vector2::new(1.0, 10.0), 0.5).unwrap();
    world
        .set_velocity(ball, Vector2::new(1.0, 0.0), 0.0)
        .unwrap();
    world
        .apply_force(ball, Vector2::new(2.0, 0.0), Vector2::new(1.0, 10.0))
        .unwrap();
    world
        .apply_linear_impulse(ball, Vector2::new(0.0, 1.0), Vector2::new(1.0, 10.0))
        .unwrap();
    world.apply_angular_impulse(ball, 0.1).unwrap();
    world.apply_torque(ball, 0.1).unwrap();
    world.step(0.01).unwrap();
    // RK4 with a constant force is exact for the velocity: v = 1 + 2·0.01.
    let v = world.states()[ball].velocity;
    assert!((v.x - 1.02).abs() < 1e-14, "{}", v.x);
    assert!((v.y - (1.0 - 0.1)).abs() < 1e-14, "{}", v.y);
    world.set_mass_properties(ball, 2.0, Some(0.5)).unwrap();
    world.set_body_kind(ball, BodyKind::Static).unwrap();
    world.set_body_kind(ball, BodyKind::Dynamic).unwrap();
    world.set_enabled(post, false).unwrap();
    world.set_enabled(post, true).unwrap();
    world.set_user_value(ball, 3).unwrap();
    world.set_gravity_scale(ball, 1.0).unwrap();
    world.set_damping(ball, 0.0, 0.0).unwrap();
    world.step(0.01).unwrap();
    // What it refuses, naming the model.
    refused(&world, "exact contact model", |w| {
        w.set_gravity_scale(ball, 0.5)
    });
    refused(&world, "exact contact model", |w| {
        w.set_damping(ball, 1.0, 0.0)
    });
    refused(&world, "exact contact model", |w| {
        w.set_fixed_rotation(ball, true)
    });
    refused(&world, "exact contact model", |w| {
        w.set_body_kind(ball, BodyKind::Kinematic)
    });
    // And a soft-step world whose controls need the soft step cannot
    // leave it.
    let mut soft = scene();
    soft.set_gravity_scale(DOT, 0.0).unwrap();
    let e = soft
        .set_contact_model(ContactModel::Exact(ContactSettings::default()))
        .unwrap_err();
    assert!(e.to_string().contains("exact contact model"), "{e}");
}
