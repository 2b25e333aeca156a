//! Wheel and motor joints (`engine/src/soft_step/joints/wheel.rs`,
//! `motor_joint.rs`, `engine/src/exact/joint_forces.rs`) at a small size:
//! the closed forms the harness's `wheel_suspension` and `motor_joint`
//! cases hold them to, at looser bounds written next to each, and the
//! refusals.

use etalon2d::prelude::*;

/// A 2 kg disc whose centre rides a vertical wheel joint to the world at
/// the origin, released 0.1 m above it, no gravity.
fn suspended(world: &mut World, hertz: f64, zeta: f64) -> (usize, usize) {
    let mut def = BodyDef::rigid("chassis", 2.0, Shape::circle(0.2).unwrap());
    def.state.position = Vector2::new(0.0, 0.1);
    let body = world.add_body(def).unwrap();
    // The axle's anchor: the origin on the world's side, the chassis'
    // centre on its own; the spring's rest is the two level (y = 0).
    let joint = world
        .add_joint(
            JointDef::wheel(
                "axle",
                None,
                Some(body),
                Vector2::zeros(),
                Wheel::suspension(Vector2::y(), hertz, zeta),
            )
            .with_local_anchors(Vector2::zeros(), Vector2::zeros()),
        )
        .unwrap();
    (body, joint)
}

/// y(t) of the damped oscillator from (y0, 0): ω, ζ < 1.
fn damped(y0: f64, omega: f64, zeta: f64, t: f64) -> f64 {
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    y0 * (-zeta * omega * t).exp() * ((wd * t).cos() + zeta * omega / wd * (wd * t).sin())
}

#[test]
fn an_exact_wheel_suspension_is_the_damped_oscillator() {
    // RK4 at h = 1e-3 s on ω = 4π rad/s: a global error of order
    // (hω)⁴ ωt y0 ≈ 2.5e-8 × 12.6 × 0.1 ≈ 3e-8 m after 1 s; held to 1e-6 m.
    let mut w = World::new(Method::Rk4).unwrap();
    let (body, joint) = suspended(&mut w, 2.0, 0.2);
    let omega = 4.0 * std::f64::consts::PI;
    for k in 1..=1000 {
        w.step(1e-3).unwrap();
        let y = w.states()[body].position.y;
        let t = k as f64 * 1e-3;
        assert!((y - damped(0.1, omega, 0.2, t)).abs() < 1e-6, "t {t}: {y}");
    }
    let s = w.joint(joint).unwrap();
    assert!(s.linear_error < 1e-12, "{}", s.linear_error);
    // The spring force on the chassis is −m(ω² y + 2ζω ẏ) along y.
    let st = w.states()[body];
    let expected = -2.0 * (omega * omega * st.position.y + 0.4 * omega * st.velocity.y);
    // Read at the last right-hand side RK4 evaluated, its fourth stage at
    // y_n + h k₃, which differs from y_{n+1} by O(h²): measured 8e-8
    // relative; held to 1e-5.
    assert!(
        (s.force.y - expected).abs() < 1e-5 * expected.abs(),
        "{s:?}"
    );
}

#[test]
fn a_soft_wheel_suspension_oscillates_at_its_frequency() {
    // The soft spring's period 2π/ω (1 + 11/24 (hω)²) at h = 1/240 s is
    // within 1.3e-3 of 2π/ω; the first upward crossing of an underdamped
    // oscillator from rest at y0 > 0 comes at 3T/4 + O(ζ): measured against
    // the closed form's crossing with a 2 % bound (the soft spring's
    // added damping hω/2 ≈ 0.026 shifts it by ζ-order terms).
    let mut w = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap();
    let (body, joint) = suspended(&mut w, 2.0, 0.0);
    let mut last = 0.1;
    let mut crossings = Vec::new();
    for k in 1..=120 {
        w.step(1.0 / 60.0).unwrap();
        let y = w.states()[body].position.y;
        if (y < 0.0) != (last < 0.0) {
            let f = last / (last - y);
            crossings.push((k as f64 - 1.0 + f) / 60.0);
        }
        last = y;
    }
    assert!(crossings.len() >= 3, "{crossings:?}");
    let period = crossings[2] - crossings[0];
    assert!((period - 0.5).abs() < 0.01, "period {period}");
    assert!(w.joint(joint).unwrap().linear_error < 1e-9);
}

#[test]
fn a_motor_joint_reaches_its_target_within_its_bounds() {
    for method in [Method::Rk4, Method::SemiImplicitEuler] {
        let mut w = if method == Method::Rk4 {
            World::new(method).unwrap()
        } else {
            World::with_model(method, ContactModel::SoftStep(SoftStepSettings::default())).unwrap()
        };
        let body = w
            .add_body(BodyDef::rigid(
                "box",
                1.0,
                Shape::rectangle(0.5, 0.5).unwrap(),
            ))
            .unwrap();
        let target = Vector2::new(0.4, 0.3);
        let joint = w
            .add_joint(JointDef::motor(
                "drive",
                None,
                Some(body),
                MotorJoint {
                    linear_spring: JointSpring::new(2.0, 1.0),
                    angular_spring: JointSpring::new(2.0, 1.0),
                    ..MotorJoint::new(target, 0.6, 20.0, 1.0)
                },
            ))
            .unwrap();
        let dt = if method == Method::Rk4 {
            1e-3
        } else {
            1.0 / 60.0
        };
        let steps = (3.0 / dt) as usize;
        for _ in 0..steps {
            w.step(dt).unwrap();
            let s = w.joint(joint).unwrap();
            // Bounds to round-off (the impulse is scaled onto the disc).
            assert!(s.force.norm() <= 20.0 * (1.0 + 1e-12), "{s:?}");
            assert!(s.torque.abs() <= 1.0 * (1.0 + 1e-12), "{s:?}");
        }
        let st = w.states()[body];
        // 2 Hz critically damped, out of its bounds within 0.3 s: after
        // 3 s the offset (1 + ωt) e^{−ωt} of 0.5 m is below 1e-12 m.
        assert!((st.position - target).norm() < 1e-6, "{method:?} {st:?}");
        assert!((st.angle - 0.6).abs() < 1e-6, "{method:?} {st:?}");
    }
}

#[test]
fn bad_wheel_and_motor_joints_are_refused_by_name() {
    let mut w = World::new(Method::Rk4).unwrap();
    let body = w
        .add_body(BodyDef::rigid(
            "box",
            1.0,
            Shape::rectangle(0.5, 0.5).unwrap(),
        ))
        .unwrap();
    let bad_axis = Wheel::suspension(Vector2::zeros(), 1.0, 0.5);
    let e = w
        .add_joint(JointDef::wheel(
            "w",
            None,
            Some(body),
            Vector2::zeros(),
            bad_axis,
        ))
        .unwrap_err();
    assert!(matches!(e, EngineError::InvalidJoint { .. }), "{e}");
    let motorized = Wheel {
        motor: Some(WheelMotor {
            speed: 1.0,
            max_torque: 1.0,
        }),
        ..Wheel::default()
    };
    let e = w
        .add_joint(JointDef::wheel(
            "w",
            None,
            Some(body),
            Vector2::zeros(),
            motorized,
        ))
        .unwrap_err();
    assert!(
        e.to_string().contains("joint 'w' (wheel) with a motor"),
        "{e}"
    );
    let e = w
        .add_joint(JointDef::motor(
            "m",
            None,
            Some(body),
            MotorJoint::new(Vector2::zeros(), 0.0, -1.0, 1.0),
        ))
        .unwrap_err();
    assert!(e.to_string().contains("largest force"), "{e}");
    assert_eq!(w.joint_count(), 0);
}
