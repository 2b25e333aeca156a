//! Joints under the exact model (`engine/src/exact/joints.rs`): each
//! jointed system against the one-degree-of-freedom ODE it reduces to,
//! integrated by the engine's own integrator on its own coordinates (no
//! constraint code involved), at a step a tenth of the world's.
//!
//! Bounds: RK4's global error at h = 1e-3 s over 1 s on these pendulums
//! (ω ≈ 3.1 rad/s) is of order (hω)⁴ ω t ≈ 1e-11 of the amplitude; both
//! runs are held within 1e-9 m (two orders of margin for the constants of
//! the error expansion, which a fourth-order method's leading term does
//! not give), while a wrong constraint force (a missing centripetal term,
//! a wrong arm) errs by 1e-3 m or more within the second.

use etalon2d::prelude::*;
use etalon2d::{FnSystem, integrate_fixed};

const G: f64 = 9.81;
const H: f64 = 1e-3;

/// θ(t) of θ'' = −(g/L_eq) sin θ from rest at `theta0`, `steps` steps of
/// `h`, RK4 on (θ, θ'), returned at every step.
fn reduced_pendulum(l_eq: f64, theta0: f64, h: f64, steps: usize) -> Vec<f64> {
    let mut sys = FnSystem::new(2, |_t, y: &[f64], d: &mut [f64]| {
        d[0] = y[1];
        d[1] = -G / l_eq * y[0].sin();
    });
    let solution = integrate_fixed(&mut sys, Method::Rk4, 0.0, &[theta0, 0.0], h, steps).unwrap();
    solution.y.iter().map(|y| y[0]).collect()
}

/// A world under gravity integrated by `method`, contacts off.
fn world(method: Method) -> World {
    let mut w = World::new(method).unwrap();
    w.set_gravity(Vector2::new(0.0, -G)).unwrap();
    w
}

/// A disc of radius 0.1 m, 1 kg, at the angle `theta` (from straight
/// down) 1 m from the origin.
fn disc_at(name: &str, theta: f64) -> BodyDef {
    let mut def = BodyDef::rigid(name, 1.0, Shape::circle(0.1).unwrap());
    def.state.position = Vector2::new(theta.sin(), -theta.cos());
    def
}

fn angle_about_origin(p: Vector2<f64>) -> f64 {
    p.x.atan2(-p.y)
}

#[test]
fn a_rod_pendulum_follows_its_reduced_equation() {
    let theta0 = 2.0_f64; // rad, beyond 90°
    let mut w = world(Method::Rk4);
    let bob = w.add_body(disc_at("bob", theta0)).unwrap();
    let pos = w.states()[bob].position;
    w.add_joint(JointDef::distance(
        "rod",
        (None, Vector2::zeros()),
        (Some(bob), pos),
        Distance::default(),
    ))
    .unwrap();
    let reduced = reduced_pendulum(1.0, theta0, H / 10.0, 10_000);
    for k in 1..=1000 {
        w.step(H).unwrap();
        if k % 100 == 0 {
            let p = w.states()[bob].position;
            let theta = angle_about_origin(p);
            assert!(
                (theta - reduced[10 * k]).abs() < 1e-9,
                "t = {}: {theta} vs {}",
                w.time(),
                reduced[10 * k]
            );
            assert!((p.norm() - 1.0).abs() < 1e-13, "length {}", p.norm());
        }
    }
    // The drift the projection removed after a step is RK4's local error:
    // (hω)⁵-small, far above round-off and far below a millimetre.
    let drift = w.joint_drift().unwrap();
    assert!(drift > 0.0 && drift < 1e-10, "drift {drift}");
    let state = w.joint(0).unwrap();
    assert!(state.linear_error < 1e-13);
    // The rod's force on the bob points to the pivot (tension) and carries
    // at least the weight's component along it.
    assert!(state.force.dot(&w.states()[bob].position) < 0.0);
}

#[test]
fn a_pinned_disc_is_a_physical_pendulum() {
    // Pinned 1 m from its centre: I_pivot = m r²/2 + m L², L_eq = 1.005 m.
    let theta0 = 1.0_f64;
    let mut w = world(Method::Rk4);
    let disc = w.add_body(disc_at("disc", theta0)).unwrap();
    w.add_joint(JointDef::revolute(
        "pin",
        None,
        Some(disc),
        Vector2::zeros(),
        Revolute::default(),
    ))
    .unwrap();
    let reduced = reduced_pendulum(1.0 + 0.01 / 2.0, theta0, H / 10.0, 10_000);
    w.run(1.0, H).unwrap();
    let s = w.states()[disc];
    let theta = angle_about_origin(s.position);
    assert!(
        (theta - reduced[10_000]).abs() < 1e-9,
        "{theta} vs {}",
        reduced[10_000]
    );
    // It turns with its arm.
    assert!((s.angle - (theta - theta0)).abs() < 1e-9);
    assert!(w.joint(0).unwrap().linear_error < 1e-13);
}

#[test]
fn a_welded_pair_swings_as_one_body() {
    // Two discs welded 0.5 m apart on a pin at the origin: one rigid body
    // of 2 kg, centre 0.75 m from the pivot, I_pivot = 2 (0.005) + 0.25 + 1.
    let theta0 = 0.8_f64;
    let mut w = world(Method::Rk4);
    let near = {
        let mut d = disc_at("near", theta0);
        d.state.position *= 0.5;
        w.add_body(d).unwrap()
    };
    let far = w.add_body(disc_at("far", theta0)).unwrap();
    w.add_joint(JointDef::revolute(
        "pin",
        None,
        Some(near),
        Vector2::zeros(),
        Revolute::default(),
    ))
    .unwrap();
    let mid = w.states()[near].position;
    w.add_joint(JointDef::weld(
        "weld",
        Some(near),
        Some(far),
        mid,
        Weld::default(),
    ))
    .unwrap();
    let l_eq = (2.0 * 0.005 + 0.25 + 1.0) / (2.0 * 0.75);
    let reduced = reduced_pendulum(l_eq, theta0, H / 10.0, 10_000);
    w.run(1.0, H).unwrap();
    let theta = angle_about_origin(w.states()[far].position);
    assert!(
        (theta - reduced[10_000]).abs() < 1e-9,
        "{theta} vs {}",
        reduced[10_000]
    );
    let weld = w.joint(1).unwrap();
    assert!(weld.linear_error < 1e-13 && weld.angular_error < 1e-13);
}

#[test]
fn a_slider_on_an_incline_falls_at_g_sin_alpha() {
    // A box on a prismatic joint along a line 30° below the horizontal:
    // s = ½ g sin α t², a quadratic RK4 integrates exactly.
    let alpha = 30.0_f64.to_radians();
    let axis = Vector2::new(alpha.cos(), -alpha.sin());
    let mut w = world(Method::Rk4);
    let block = w
        .add_body(BodyDef::rigid(
            "block",
            2.0,
            Shape::rectangle(0.2, 0.1).unwrap(),
        ))
        .unwrap();
    w.add_joint(JointDef::prismatic(
        "rail",
        None,
        Some(block),
        Vector2::zeros(),
        Prismatic::along(axis),
    ))
    .unwrap();
    w.run(1.0, H).unwrap();
    let s = w.states()[block];
    let along = 0.5 * G * alpha.sin();
    assert!((s.position - along * axis).norm() < 1e-12, "{}", s.position);
    assert!(s.angle.abs() < 1e-15);
}

#[test]
fn options_the_exact_model_does_not_solve_are_refused_by_name() {
    let mut w = world(Method::Rk4);
    let bob = w.add_body(disc_at("bob", 0.5)).unwrap();
    let limited = Revolute {
        limits: Some((-0.5, 0.5)),
        ..Revolute::default()
    };
    let error = w
        .add_joint(JointDef::revolute(
            "hinge",
            None,
            Some(bob),
            Vector2::zeros(),
            limited,
        ))
        .unwrap_err();
    assert!(matches!(error, EngineError::Unsupported { .. }), "{error}");
    let message = error.to_string();
    assert!(
        message.contains("joint 'hinge' (revolute) with angle limits"),
        "{message}"
    );
    let error = w
        .add_joint(JointDef::distance(
            "rope",
            (None, Vector2::zeros()),
            (Some(bob), w.states()[bob].position),
            Distance::rope(2.0),
        ))
        .unwrap_err();
    assert!(
        error
            .to_string()
            .contains("joint 'rope' (distance) as a rope"),
        "{error}"
    );
    // Nothing was added; the world still steps.
    assert_eq!(w.joint_count(), 0);
    w.step(H).unwrap();
    // A supported joint then leaves the model only by refusal.
    w.add_joint(JointDef::revolute(
        "pin",
        None,
        Some(bob),
        Vector2::zeros(),
        Revolute::default(),
    ))
    .unwrap();
    let error = w
        .set_contact_model(ContactModel::SoftStep(SoftStepSettings::default()))
        .unwrap_err();
    assert!(error.to_string().contains("joint 'pin'"), "{error}");
    // Contact settings of the exact model itself are still accepted.
    w.set_contact_settings(ContactSettings::default()).unwrap();
    assert!(matches!(
        w.set_motor_speed(0, 1.0),
        Err(EngineError::InvalidJoint { .. })
    ));
    assert!(matches!(
        w.joint(3),
        Err(EngineError::UnknownJoint { index: 3, count: 1 })
    ));
}

#[test]
fn a_cradle_of_five_sends_one_ball_out_for_one_in() {
    // Five balls of radius 0.1 m on rods of 1 m, hung 0.2 m + 1e-9 m apart
    // (touching to 1e-9 m), e = 1; the first released from 30°.
    let mut w = world(Method::Rk4);
    w.set_contact_settings(ContactSettings {
        restitution: 1.0,
        ..ContactSettings::default()
    })
    .unwrap();
    let gap = 1e-9;
    let mut balls = Vec::new();
    for i in 0..5 {
        let pivot = Vector2::new(i as f64 * (0.2 + gap), 0.0);
        let theta = if i == 0 { -30.0_f64.to_radians() } else { 0.0 };
        let mut def = BodyDef::rigid(&format!("ball_{i}"), 1.0, Shape::circle(0.1).unwrap());
        def.state.position = pivot + Vector2::new(theta.sin(), -theta.cos());
        let b = w.add_body(def).unwrap();
        let at = w.states()[b].position;
        w.add_joint(JointDef::distance(
            &format!("rod_{i}"),
            (None, pivot),
            (Some(b), at),
            Distance::default(),
        ))
        .unwrap();
        balls.push(b);
    }
    let e0 = w.energy();
    // A quarter period (0.5 s) brings ball 0 to the bottom; 0.3 s more
    // sends ball 4 up.
    w.run(0.8, H).unwrap();
    // Ball 4 swings out; the others stay within 1e-8 m/s of rest (each
    // was left within 4e-9 m of its bottom by the gaps: ω × 4e-9 m).
    let s = w.states();
    assert!(s[balls[4]].velocity.norm() > 0.5);
    for b in &balls[..4] {
        assert!(s[*b].velocity.norm() < 1e-8, "{:?}", s[*b].velocity);
    }
    assert_eq!(w.contact_events().len(), 4);
    // e = 1 impulses keep the energy; RK4 over 800 steps to 1e-12.
    assert!(((w.energy() - e0) / e0).abs() < 1e-12);
}

/// A disc pinned 1 m above its centre strikes a static wall at its lowest
/// point, the normal along its motion (docs/joints.md, "Impacts on jointed
/// bodies"): the impulse solved with the joint held maps θ' to −e θ'
/// exactly (one degree of freedom), where a free impulse projected onto
/// the joint afterwards gives (I_cm − e m L²)/(I_cm + m L²) θ'.
#[test]
fn an_impact_on_a_pinned_disc_reverses_its_angular_velocity_by_e() {
    for e in [0.0, 0.5, 1.0] {
        let mut w = world(Method::Rk4);
        w.set_contact_settings(ContactSettings {
            restitution: e,
            ..ContactSettings::default()
        })
        .unwrap();
        let theta0 = -0.6_f64;
        let bob = w.add_body(disc_at("bob", theta0)).unwrap();
        w.add_body(BodyDef::fixed(
            "wall",
            Vector2::new(0.3, -1.0),
            Some(Shape::rectangle(0.4, 1.0).unwrap()),
        ))
        .unwrap();
        w.add_joint(JointDef::revolute(
            "pin",
            None,
            Some(bob),
            Vector2::zeros(),
            Revolute::default(),
        ))
        .unwrap();
        // Energies above the hanging disc (its centre at y = −1 m).
        let above_bottom = |w: &World| w.energy() + w.bodies()[bob].mass * G;
        let e0 = above_bottom(&w);
        // The quarter period of a 0.6 rad swing is about 0.51 s: the
        // impact is inside the first 0.6 s, and nothing else happens.
        w.run(0.6, H).unwrap();
        // θ' → −e θ' at the bottom keeps e² of the energy (RK4's error
        // over 600 steps is far below 1e-10); a free impulse projected
        // afterwards keeps ((I_cm − e m L²)/(I_cm + m L²))², 0.980 at e = 1.
        let kept = above_bottom(&w) / e0;
        assert!((kept - e * e).abs() < 1e-10, "e = {e}: {kept}");
        let impacts: Vec<_> = w
            .contact_events()
            .into_iter()
            .filter(|c| c.kind == etalon2d::ContactEventKind::Impact)
            .collect();
        assert_eq!(impacts.len(), 1, "e = {e}: {impacts:?}");
        let c = &impacts[0];
        assert!(
            (c.normal_velocity_after + e * c.normal_velocity_before).abs() < 1e-14,
            "e = {e}: {c:?}"
        );
        // The joint holds the pivot's velocity at zero after the impact:
        // the disc turns about the pivot at ω = vx / L.
        let s = w.states()[bob];
        let arm = -s.position;
        let pivot_velocity = s.velocity + s.angular_velocity * Vector2::new(-arm.y, arm.x);
        assert!(pivot_velocity.norm() < 1e-13, "e = {e}: {pivot_velocity:?}");
        if e > 0.0 {
            // Rebound to the left and up.
            assert!(s.velocity.x < 0.0, "e = {e}: {s:?}");
        }
    }
}
