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

/// A static floor (top at y = 0) and a bar of 1 m × 0.1 m hinged to it at
/// (0, 0.1), its far end 0.05 m above the floor: the bar falls about the
/// hinge. A joint's `collide_connected` off (Box2D's default) keeps its
/// two bodies out of contact under the exact model as under the soft
/// step: the bar swings through the floor. On, the bar strikes the floor
/// (e = 0) with its far corner and stays on it.
#[test]
fn a_joint_keeps_its_bodies_out_of_contact_unless_collide_connected() {
    for collide in [false, true] {
        let mut w = world(Method::Rk4);
        w.set_contact_settings(ContactSettings::new(0.0, 0.0))
            .unwrap();
        let floor = w
            .add_body(BodyDef::fixed(
                "floor",
                Vector2::new(0.5, -0.1),
                Some(Shape::rectangle(2.0, 0.2).unwrap()),
            ))
            .unwrap();
        let mut def = BodyDef::rigid("bar", 1.0, Shape::rectangle(1.0, 0.1).unwrap());
        def.state.position = Vector2::new(0.5, 0.1);
        let bar = w.add_body(def).unwrap();
        w.add_joint(
            JointDef::revolute(
                "hinge",
                Some(floor),
                Some(bar),
                Vector2::new(0.0, 0.1),
                Revolute::default(),
            )
            .with_collide_connected(collide),
        )
        .unwrap();
        w.run(0.5, H).unwrap();
        let s = w.states()[bar];
        assert!(s.position.iter().all(|x| x.is_finite()), "{s:?}");
        let impacts = w
            .contact_events()
            .iter()
            .filter(|c| c.kind == etalon2d::ContactEventKind::Impact)
            .count();
        // The far bottom corner, (0.5, −0.05) in the bar's frame.
        let (sin, cos) = s.angle.sin_cos();
        let corner_y = s.position.y + sin * 0.5 - cos * 0.05;
        if collide {
            // The corner reaches the floor at sin φ + 0.05 cos φ = 0.1
            // (φ ≈ 0.0501 rad) and rests there, within the contact
            // tolerance ε = 1e-10 m (2ε: a resting point is released
            // beyond it).
            assert!(impacts >= 1, "collide_connected: {impacts} impacts");
            assert!(corner_y.abs() < 2e-10, "corner at {corner_y} m");
        } else {
            // Swung through the floor: a quarter period of this
            // physical pendulum from horizontal is about 0.45 s.
            assert!(w.contact_events().is_empty(), "{:?}", w.contact_events());
            assert!(corner_y < -0.5, "corner at {corner_y} m");
        }
    }
}

/// Two boxes of 1 m × 0.1 m overlapping over half their length, the first
/// hinged to the world at its end, the second to the first at (0.75, 0),
/// inside both (a double pendulum whose links overlap, as a crank and its
/// rod do): with contacts on, the joint keeps them out of contact, so
/// the run equals the one without contacts (no contact code acts; the
/// same integrator steps) and nothing goes non-finite.
#[test]
fn overlapping_jointed_boxes_run_as_without_contacts() {
    let run = |contacts: bool| {
        let mut w = world(Method::Rk4);
        if contacts {
            w.set_contact_settings(ContactSettings::default()).unwrap();
        }
        let mut upper = BodyDef::rigid("upper", 1.0, Shape::rectangle(1.0, 0.1).unwrap());
        upper.state.position = Vector2::new(0.5, 0.0);
        let upper = w.add_body(upper).unwrap();
        let mut lower = BodyDef::rigid("lower", 1.0, Shape::rectangle(1.0, 0.1).unwrap());
        lower.state.position = Vector2::new(1.0, 0.0);
        let lower = w.add_body(lower).unwrap();
        w.add_joint(JointDef::revolute(
            "shoulder",
            None,
            Some(upper),
            Vector2::zeros(),
            Revolute::default(),
        ))
        .unwrap();
        w.add_joint(JointDef::revolute(
            "elbow",
            Some(upper),
            Some(lower),
            Vector2::new(0.75, 0.0),
            Revolute::default(),
        ))
        .unwrap();
        w.run(1.0, H).unwrap();
        (w.states().to_vec(), w.contact_events())
    };
    let (free, _) = run(false);
    let (with_contacts, events) = run(true);
    assert!(events.is_empty(), "{events:?}");
    for (a, b) in free.iter().zip(&with_contacts) {
        assert!(b.position.iter().all(|x| x.is_finite()), "{b:?}");
        // The same steps of the same integrator, projected alike.
        assert!((a.position - b.position).norm() < 1e-12, "{a:?} vs {b:?}");
        assert!((a.angle - b.angle).abs() < 1e-12, "{a:?} vs {b:?}");
    }
    // And they did swing, the lower link turning about the elbow across
    // the upper one.
    assert!(
        free[0].angle.abs() > 1.0 && free[1].angle.abs() > 1.0,
        "{free:?}"
    );
}

/// A uniform bar of 1 m × 0.1 m, 1 kg, hinged to the world at its left
/// end, at rest on a static disc under it at s = 0.95 m from the hinge
/// (docs/joints.md, "Resting contact on jointed bodies"). Statics, the
/// closed form: the support holds N = m g x_c / s (x_c = 0.5 m the
/// centre's distance; m g / 2 for a support at the end), the hinge the
/// rest of the weight, m g (1 − x_c / s), vertical. The contact force
/// solved before the joints (with the free bar's mass) would give
/// N = m g / (1 + m s_c² / I) ≈ 0.27 m g and let the bar sink and turn.
#[test]
fn a_hinged_bar_on_a_support_shares_its_weight_with_the_hinge() {
    let mut w = world(Method::Rk4);
    w.set_contact_settings(ContactSettings::new(0.0, 0.0))
        .unwrap();
    let mut def = BodyDef::rigid("bar", 1.0, Shape::rectangle(1.0, 0.1).unwrap());
    def.state.position = Vector2::new(0.5, 0.1);
    let bar = w.add_body(def).unwrap();
    let s = 0.95;
    w.add_body(BodyDef::fixed(
        "support",
        Vector2::new(s, 0.0),
        Some(Shape::circle(0.05).unwrap()),
    ))
    .unwrap();
    w.add_joint(JointDef::revolute(
        "hinge",
        None,
        Some(bar),
        Vector2::new(0.0, 0.1),
        Revolute::default(),
    ))
    .unwrap();
    let start = w.states()[bar];
    w.run(1.0, H).unwrap();
    let end = w.states()[bar];
    // At rest: the accelerations are zero to round-off (the bar's
    // coordinates are of order 1: 1e-12 is a few thousand ulps over the
    // 1000 steps).
    assert!((end.position - start.position).norm() < 1e-12, "{end:?}");
    assert!(end.angle.abs() < 1e-12, "{end:?}");
    let m_g = G;
    let hinge = w.joint(0).unwrap().force;
    let expected = m_g * (1.0 - 0.5 / s);
    // The force of the last right-hand side, at a state at rest to 1e-12:
    // the closed form to round-off of the 10 N load.
    assert!(
        (hinge - Vector2::new(0.0, expected)).norm() < 1e-9,
        "hinge {hinge:?}, expected (0, {expected})"
    );
    // The support carries the rest of the weight (the bar at rest).
    let support = m_g - hinge.y;
    assert!(
        (support - m_g * 0.5 / s).abs() < 1e-9,
        "support {support} N"
    );
    assert!(
        w.contact_events()
            .iter()
            .all(|c| c.kind == etalon2d::ContactEventKind::Rest),
        "{:?}",
        w.contact_events()
    );
}

/// A disc of 1 kg on a rod of 1 m at θ = 0.3 rad from the vertical,
/// resting against a static wall on the side it would swing to
/// (frictionless): the closed form of its statics is the wall's push
/// N = m g tan θ, horizontal, and the rod's tension T = m g / cos θ.
/// Solved before the joint the contact would take no force (gravity has no
/// horizontal part) and the rod would pull the disc into the wall.
#[test]
fn a_pendulum_resting_against_a_wall_pulls_its_rod_with_m_g_over_cos_theta() {
    let theta = 0.3_f64;
    let mut w = world(Method::Rk4);
    w.set_contact_settings(ContactSettings::new(0.0, 0.0))
        .unwrap();
    let bob = w.add_body(disc_at("bob", theta)).unwrap();
    let centre = w.states()[bob].position;
    // The wall's right face touches the disc's leftmost point.
    w.add_body(BodyDef::fixed(
        "wall",
        Vector2::new(centre.x - 0.1 - 0.2, centre.y),
        Some(Shape::rectangle(0.4, 1.0).unwrap()),
    ))
    .unwrap();
    w.add_joint(JointDef::distance(
        "rod",
        (None, Vector2::zeros()),
        (Some(bob), centre),
        Distance::default(),
    ))
    .unwrap();
    w.run(1.0, H).unwrap();
    let end = w.states()[bob];
    assert!((end.position - centre).norm() < 1e-12, "{end:?}");
    let rod = w.joint(0).unwrap().force;
    let expected = -G / theta.cos() * centre / centre.norm();
    assert!(
        (rod - expected).norm() < 1e-9,
        "rod {rod:?}, expected {expected:?}"
    );
    // The wall's push is what the rod and the weight leave: m g tan θ.
    let wall = -(rod + Vector2::new(0.0, -G));
    assert!(
        (wall - Vector2::new(G * theta.tan(), 0.0)).norm() < 1e-9,
        "wall {wall:?}"
    );
}
