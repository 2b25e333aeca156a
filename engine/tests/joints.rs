//! Joints under the soft step, each against what its rows must do, at the
//! soft step's defaults (dt = 1/60 s, 4 substeps: h = 1/240 s; the rigid
//! rows at Box2D's 60 Hz and ζ = 2, within the cap 1/(4h) = 60 Hz).
//!
//! The bounds come from the soft rows' equilibrium (docs/joints.md): a
//! soft row under a steady load sinks by a/ω_c², a the acceleration the
//! load would give the row's error without it, ω_c = 2π × 60 Hz; a row
//! whose anchors turn also drifts by ½ h² a_c per substep along a straight
//! path (a_c their centripetal acceleration), of which the bias removes
//! the fraction h² ω_c² a₃ per substep (a₃ = 1/(1 + a₂) of
//! `soft_step::Softness`), so the separation of a point row is at most
//!
//! δ ≤ (a_load + a_c (1 + 1/(2 a₃))) / ω_c².

use etalon2d::forces::Torque;
use etalon2d::prelude::*;
use std::f64::consts::PI;

const DT: f64 = 1.0 / 60.0;
/// The substep (s).
const H: f64 = DT / 4.0;
const G: f64 = 9.81;

/// ω_c (rad/s) and a₃ of the rigid rows at the defaults.
fn rigid_rows() -> (f64, f64) {
    let hertz = 60.0_f64.min(0.25 / H);
    let omega = 2.0 * PI * hertz;
    let a1 = 2.0 * 2.0 + H * omega;
    let a2 = H * omega * a1;
    (omega, 1.0 / (1.0 + a2))
}

/// The largest separation of a point row under `a_load` and the
/// centripetal `a_c` (m/s²), from the module docs.
fn separation_bound(a_load: f64, a_c: f64) -> f64 {
    let (omega, a3) = rigid_rows();
    (a_load + a_c * (1.0 + 1.0 / (2.0 * a3))) / (omega * omega)
}

fn world(g: f64) -> World {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap();
    world.set_gravity(Vector2::new(0.0, -g)).unwrap();
    world
}

/// The complete elliptic integral of the first kind K(k), by the
/// arithmetic-geometric mean: K = π / (2 AGM(1, √(1 − k²))), independent
/// of the engine.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, (1.0 - k * k).sqrt());
    while (a - b).abs() > 1e-16 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

/// Times (s) at which `values` changes sign, by linear interpolation
/// between samples.
fn sign_changes(times: &[f64], values: &[f64]) -> Vec<f64> {
    (1..values.len())
        .filter(|&i| (values[i - 1] < 0.0) != (values[i] < 0.0))
        .map(|i| {
            let f = values[i - 1] / (values[i - 1] - values[i]);
            times[i - 1] + f * (times[i] - times[i - 1])
        })
        .collect()
}

/// The mean period (s) of a signal from its sign changes.
fn period(times: &[f64], values: &[f64]) -> f64 {
    let c = sign_changes(times, values);
    assert!(c.len() >= 3, "too few oscillations: {c:?}");
    2.0 * (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64
}

#[test]
fn the_elliptic_integral_gives_the_literal_period() {
    let k = (10.0_f64.to_radians() / 2.0).sin();
    let t = 4.0 * (1.0 / G).sqrt() * elliptic_k(k);
    assert!((t - 2.009892627298601).abs() < 1e-14, "{t}");
}

/// A pendulum of length 1 m released at rest from 10°, held by `joint`
/// from the world at the origin: (period over 20 s, largest constraint
/// error).
fn swing(bob: BodyDef, joint: impl Fn(BodyId, Vector2<f64>) -> JointDef) -> (f64, f64) {
    let theta0 = 10.0_f64.to_radians();
    let start = Vector2::new(theta0.sin(), -theta0.cos());
    let mut world = world(G);
    let bob = world.add_body(bob.with_position(start)).unwrap();
    let j = world.add_joint(joint(bob, start)).unwrap();
    let (mut times, mut angles) = (vec![0.0], vec![theta0]);
    let mut worst: f64 = 0.0;
    for k in 1..=1200 {
        world.step(DT).unwrap();
        let p = world.states()[bob].position;
        times.push(k as f64 * DT);
        angles.push(p.x.atan2(-p.y));
        worst = worst.max(world.joint(j).unwrap().linear_error);
    }
    (period(&times, &angles), worst)
}

/// The pendulum's tolerances: (largest anchor separation, relative period
/// error) for an equivalent length `l_eq` (m).
///
/// - separation: δ of the module docs with a_load = g and a_c = ω_max² L,
///   the anchor's centripetal acceleration at the bottom (ω_max² =
///   2 g (1 − cos θ0) / l_eq);
/// - period: the softness lengthens the pendulum by at most δ (a relative
///   period change ½ δ/L); symplectic Euler, first order in its positions,
///   errs on a time-reversible oscillation's period only at second order:
///   on the linearised pendulum its phase per substep φ has cos φ = 1 −
///   (hΩ)²/2, a relative period error (hΩ)²/24 (Ω² = g/l_eq); plus 1e-6
///   for locating the zero crossings by linear interpolation between steps
///   (an error of O(Ω² dt³) ≈ 2e-6 s per crossing, over 20 s).
fn pendulum_tolerances(l_eq: f64) -> (f64, f64) {
    let theta0 = 10.0_f64.to_radians();
    let omega_max2 = 2.0 * G * (1.0 - theta0.cos()) / l_eq;
    let delta = separation_bound(G, omega_max2 * 1.0);
    let big_omega2 = G / l_eq;
    (delta, 0.5 * delta + H * H * big_omega2 / 24.0 + 1e-6)
}

#[test]
fn a_revolute_pendulum_keeps_its_anchor_and_its_period() {
    // A disc of radius 5 cm pivoted 1 m from its centre: a physical
    // pendulum of equivalent length l_eq = (L² + r²/2)/L.
    let r = 0.05;
    let bob = BodyDef::rigid("bob", 1.0, Shape::circle(r).unwrap());
    let (t, worst) = swing(bob, |bob, _| {
        JointDef::revolute(
            "pivot",
            None,
            Some(bob),
            Vector2::zeros(),
            Revolute::default(),
        )
    });
    let l_eq = 1.0 + r * r / 2.0;
    let expected = 4.0 * (l_eq / G).sqrt() * elliptic_k((10.0_f64.to_radians() / 2.0).sin());
    let (delta, rel) = pendulum_tolerances(l_eq);
    // Measured: 7.92e-5 m of 8.13e-5; period off by -7.8e-7 of 4.8e-5
    // (the revolute's sink is mostly vertical, a fixed offset of the pivot
    // that does not change the period).
    assert!(worst <= delta, "anchor separation {worst:e} m > {delta:e}");
    assert!(
        (t / expected - 1.0).abs() <= rel,
        "period {t} s, expected {expected} s ± {rel:e}"
    );
}

#[test]
fn a_distance_pendulum_keeps_its_length_and_its_period() {
    // A point mass on a massless rod of 1 m: the closed form's own case.
    let bob = BodyDef::particle("bob", 1.0, Vector2::zeros());
    let (t, worst) = swing(bob, |bob, at| {
        JointDef::distance(
            "rod",
            (None, Vector2::zeros()),
            (Some(bob), at),
            Distance::default(),
        )
    });
    let (delta, rel) = pendulum_tolerances(1.0);
    // Measured: 7.92e-5 m of 8.13e-5; period off by +3.36e-5 of 4.8e-5
    // (the rod stretches under the tension: its sink is along it).
    assert!(worst <= delta, "length error {worst:e} m > {delta:e}");
    assert!(
        (t / 2.009892627298601 - 1.0).abs() <= rel,
        "period {t} s, expected 2.009892627298601 s ± {rel:e}"
    );
}

#[test]
fn a_rope_lets_the_body_come_closer_but_not_farther() {
    // A bead 0.5 m under the anchor of a 1 m rope falls freely, exactly as
    // a free bead beside it does, until the rope is taut (after about
    // 0.32 s), then hangs at the rope's length.
    let mut world = world(G);
    let bead = world
        .add_body(BodyDef::particle("bead", 1.0, Vector2::new(0.0, -0.5)))
        .unwrap();
    let free = world
        .add_body(BodyDef::particle("free", 1.0, Vector2::new(5.0, -0.5)))
        .unwrap();
    let rope = world
        .add_joint(JointDef::distance(
            "rope",
            (None, Vector2::zeros()),
            (Some(bead), Vector2::new(0.0, -0.5)),
            Distance::rope(1.0),
        ))
        .unwrap();
    // The hanging bead's sink: the rope row's load is g (a_c = 0).
    let bound = separation_bound(G, 0.0) * (1.0 + 1e-9);
    let mut longest: f64 = 0.0;
    for _ in 0..300 {
        world.step(DT).unwrap();
        let s = world.joint(rope).unwrap();
        if s.translation < 1.0 - 0.01 {
            // Slack: no force at all.
            let (a, b) = (world.states()[bead], world.states()[free]);
            assert_eq!(a.position.y, b.position.y, "a slack rope pulled");
            assert_eq!(s.force, Vector2::zeros());
        }
        longest = longest.max(s.translation);
    }
    // Measured: 6.9025e-5 m, the sink g/ω_c² itself.
    assert!(
        longest - 1.0 <= bound,
        "rope longer by {:e} m",
        longest - 1.0
    );
    assert!(world.states()[bead].velocity.norm() < 1e-9);
}

#[test]
fn a_spring_distance_joint_oscillates_at_its_frequency() {
    // A 2 kg bead on a 2 Hz spring of rest length 1 m, undamped, pulled
    // 0.1 m along it, no gravity: a one-row oscillator. Per substep the
    // spring row, solved in both passes, maps (x, v) linearly with
    // eigenvalues of modulus 1/(1 + ε), ε = (hω)², and phase φ with cos φ
    // = (2 + ε)/(2 (1 + ε)) (docs/joints.md): the period 2πh/φ is
    // 1/f × (1 + 11/24 (hω)² + O(h⁴)) (1.26e-3 at 2 Hz).
    let f = 2.0;
    let mut world = world(0.0);
    let bead = world
        .add_body(BodyDef::particle("bead", 2.0, Vector2::new(1.1, 0.0)))
        .unwrap();
    world
        .add_joint(JointDef::distance(
            "spring",
            (None, Vector2::zeros()),
            (Some(bead), Vector2::new(1.1, 0.0)),
            Distance::Spring {
                length: Some(1.0),
                spring: JointSpring::new(f, 0.0),
                min_length: 0.0,
                max_length: f64::INFINITY,
            },
        ))
        .unwrap();
    let (mut times, mut stretch) = (vec![0.0], vec![0.1]);
    for k in 1..=120 {
        world.step(DT).unwrap();
        times.push(k as f64 * DT);
        stretch.push(world.states()[bead].position.x - 1.0);
        assert_eq!(world.states()[bead].position.y, 0.0);
    }
    let t = period(&times, &stretch);
    let eps = (H * 2.0 * PI * f).powi(2);
    let phi = ((2.0 + eps) / (2.0 * (1.0 + eps))).acos();
    let discrete = 2.0 * PI * H / phi;
    // The crossings are located to about 1e-6 of the period (linear
    // interpolation between steps); 1e-5 allows it.
    assert!(
        (t / discrete - 1.0).abs() < 1e-5,
        "period {t} s, discrete {discrete} s"
    );
    let tolerance = (discrete * f - 1.0).abs() + 1e-5;
    assert!(
        (t * f - 1.0).abs() <= tolerance,
        "period {t} s against 1/f = {} s ± {tolerance:e}",
        1.0 / f
    );
}

#[test]
fn a_prismatic_joint_keeps_the_body_on_its_axis_and_its_limit_holds() {
    // A slider on a rail tilted by 0.3 rad through (0, 1), limits ±1 m:
    // it slides down at g sin 0.3 (exactly symplectic Euler's discrete
    // slide, the rail's rows acting across it only), then rests on the
    // lower limit.
    let tilt = 0.3_f64;
    let axis = Vector2::new(tilt.cos(), tilt.sin());
    let mut world = world(G);
    let slider = world
        .add_body(
            BodyDef::rigid("slider", 1.0, Shape::rectangle(0.4, 0.2).unwrap())
                .with_position(Vector2::new(0.0, 1.0))
                .with_rotation(tilt, 0.0),
        )
        .unwrap();
    let rail = world
        .add_joint(JointDef::prismatic(
            "rail",
            None,
            Some(slider),
            Vector2::new(0.0, 1.0),
            Prismatic {
                axis,
                limits: Some((-1.0, 1.0)),
                ..Prismatic::default()
            },
        ))
        .unwrap();
    let (omega, _) = rigid_rows();
    // Static sinks: across the rail under g cos 0.3, past the limit under
    // g sin 0.3 (no centripetal load); 1 % for the approach.
    let across = 1.01 * G * tilt.cos() / (omega * omega);
    let past = 1.01 * G * tilt.sin() / (omega * omega);
    let (mut worst_across, mut lowest) = (0.0_f64, 0.0_f64);
    for k in 1..=300_u32 {
        world.step(DT).unwrap();
        let s = world.joint(rail).unwrap();
        if k == 20 {
            let n = f64::from(4 * k);
            let slide = -G * tilt.sin() * H * H * n * (n + 1.0) / 2.0;
            assert!(
                (s.translation - slide).abs() < 1e-12,
                "slid {} m, symplectic Euler {slide} m",
                s.translation
            );
        }
        worst_across = worst_across.max(s.linear_error);
        lowest = lowest.min(s.translation);
        assert!(s.angular_error < 1e-12, "turned by {}", s.angular_error);
    }
    // Measured: 6.594e-5 m across, 2.040e-5 m past the limit.
    assert!(worst_across <= across, "off the axis by {worst_across:e} m");
    assert!(
        -1.0 - lowest <= past,
        "past the limit by {:e} m",
        -1.0 - lowest
    );
    assert!(world.states()[slider].velocity.norm() < 1e-9);
}

/// A 2 kg disc of radius 0.5 m (I = 0.25 kg·m²) on an axle at the world
/// origin whose motor drives it at 3 rad/s with at most 10 N·m, against a
/// load torque of `load` N·m: (ω after 2 s, the motor's torque then, its
/// largest torque over the run).
fn motor_against(load: f64) -> (f64, f64, f64) {
    let mut world = world(0.0);
    let wheel = world
        .add_body(BodyDef::rigid("wheel", 2.0, Shape::circle(0.5).unwrap()))
        .unwrap();
    let motor = Some(RevoluteMotor {
        speed: 3.0,
        max_torque: 10.0,
    });
    let axle = world
        .add_joint(JointDef::revolute(
            "axle",
            None,
            Some(wheel),
            Vector2::zeros(),
            Revolute {
                motor,
                ..Revolute::default()
            },
        ))
        .unwrap();
    world
        .add_force(Torque {
            body: wheel,
            torque: -load,
        })
        .unwrap();
    let mut largest: f64 = 0.0;
    for _ in 0..120 {
        world.step(DT).unwrap();
        largest = largest.max(world.joint(axle).unwrap().motor.abs());
    }
    (
        world.states()[wheel].angular_velocity,
        world.joint(axle).unwrap().motor,
        largest,
    )
}

#[test]
fn a_revolute_motor_reaches_its_speed_within_its_torque_and_slips_beyond() {
    // |λ| ≤ h τ_max per substep: the torque never exceeds 10 N·m, to
    // round-off.
    let cap = 10.0 * (1.0 + 4.0 * f64::EPSILON);
    // 5 N·m: the motor holds 3 rad/s, balancing the load exactly.
    let (w, torque, largest) = motor_against(5.0);
    assert!((w - 3.0).abs() < 1e-12, "ω = {w}");
    assert!((torque - 5.0).abs() < 1e-9, "torque {torque}");
    assert!(largest <= cap, "torque {largest}");
    // 20 N·m: the motor gives its 10 N·m and slips; the wheel turns
    // backwards at (10 − 20)/0.25 = −40 rad/s² (symplectic Euler is exact
    // on a constant acceleration): −80 rad/s after 2 s.
    let (w, torque, largest) = motor_against(20.0);
    assert!((w + 80.0).abs() < 1e-9, "ω = {w}");
    assert!(
        (torque - 10.0).abs() <= 10.0 * 4.0 * f64::EPSILON,
        "{torque}"
    );
    assert!(largest <= cap, "torque {largest}");
}

#[test]
fn a_revolute_limit_holds() {
    // A 1 m × 0.1 m rod of 1 kg hinged at one end, released horizontal,
    // falls onto its lower limit at −0.5 rad (the upper one at 0.25).
    let (lower, upper) = (-0.5, 0.25);
    let mut world = world(G);
    let rod = world
        .add_body(
            BodyDef::rigid("rod", 1.0, Shape::rectangle(1.0, 0.1).unwrap())
                .with_position(Vector2::new(0.5, 0.0)),
        )
        .unwrap();
    let hinge = world
        .add_joint(JointDef::revolute(
            "hinge",
            None,
            Some(rod),
            Vector2::zeros(),
            Revolute {
                limits: Some((lower, upper)),
                ..Revolute::default()
            },
        ))
        .unwrap();
    // Slop: the speculative limit row stops the approach within the
    // substep, but the point row solved after it gives back part of the
    // angular velocity it removed: at most one substep's turn at the
    // impact speed, h ω_impact (ω_impact from energy: ½ I_p ω² =
    // m g (L/2) sin 0.5). At rest, the limit row sinks by its load
    // τ = m g (L/2) cos 0.5 over its mass I_cm: τ / (I_cm ω_c²).
    let (i_cm, i_p) = ((1.0 + 0.01) / 12.0, (1.0 + 0.01) / 12.0 + 0.25);
    let impact = (2.0 * G * 0.5 * 0.5_f64.sin() / i_p).sqrt();
    let (omega, _) = rigid_rows();
    let sink = G * 0.5 * 0.5_f64.cos() / (i_cm * omega * omega);
    let slop = H * impact + sink;
    let mut lowest: f64 = 0.0;
    for _ in 0..300 {
        world.step(DT).unwrap();
        let angle = world.joint(hinge).unwrap().angle;
        assert!(angle <= upper + slop, "angle {angle}");
        lowest = lowest.min(angle);
    }
    // Measured: 3.16e-3 rad past the limit at the impact (slop 1.60e-2);
    // at rest 3.5978e-4 rad past it (sink 3.5978e-4).
    assert!(
        lower - lowest <= slop,
        "past the limit by {}",
        lower - lowest
    );
    let rest = world.joint(hinge).unwrap().angle;
    assert!(
        (lower - rest - sink).abs() <= 0.01 * sink,
        "at rest {} rad past the limit, sink {sink}",
        lower - rest
    );
}

#[test]
fn a_weld_holds_two_boxes_as_one() {
    // A unit box welded by its left face to a static wall: a cantilever.
    // At rest each rigid row sinks by its load over ω_c²: the angle row by
    // the weight's moment about the centre over the box's inertia,
    // α = m g (1/2) / (1/6); the point row by the anchor's acceleration
    // under gravity and that turn, g + α/2. A load applied at once
    // deflects a linear spring-damper at most twice its static deflection.
    let mut world = world(G);
    let wall = world
        .add_body(BodyDef::fixed(
            "wall",
            Vector2::new(-0.5, 0.0),
            Some(Shape::rectangle(1.0, 1.0).unwrap()),
        ))
        .unwrap();
    let arm = world
        .add_body(
            BodyDef::rigid("arm", 1.0, Shape::rectangle(1.0, 1.0).unwrap())
                .with_position(Vector2::new(0.5, 0.0)),
        )
        .unwrap();
    let weld = world
        .add_joint(JointDef::weld(
            "glue",
            Some(wall),
            Some(arm),
            Vector2::zeros(),
            Weld::default(),
        ))
        .unwrap();
    let (omega, _) = rigid_rows();
    let alpha = G * 0.5 * 6.0;
    let (angle_sink, point_sink) = (alpha / (omega * omega), (G + 0.5 * alpha) / (omega * omega));
    let (mut worst_point, mut worst_angle) = (0.0_f64, 0.0_f64);
    for _ in 0..300 {
        world.step(DT).unwrap();
        let s = world.joint(weld).unwrap();
        worst_point = worst_point.max(s.linear_error);
        worst_angle = worst_angle.max(s.angular_error);
    }
    // Measured: at most 1.726e-4 m and 2.578e-4 rad; at rest 1.7256e-4 m
    // and 2.0708e-4 rad.
    assert!(worst_point <= 2.0 * point_sink, "{worst_point:e} m");
    assert!(worst_angle <= 2.0 * angle_sink, "{worst_angle:e} rad");
    let s = world.joint(weld).unwrap();
    assert!((s.linear_error / point_sink - 1.0).abs() < 0.01, "{s:?}");
    assert!((s.angular_error / angle_sink - 1.0).abs() < 0.01, "{s:?}");

    // Two free unit boxes welded face to face and spun at 2 rad/s about
    // their common centre in zero gravity turn as one body: the weld's
    // anchors see the centripetal a_c = ω² × 1 m.
    let mut world = world_without_gravity();
    let spin = 2.0;
    let half = |x: f64| {
        BodyDef::rigid("half", 1.0, Shape::rectangle(1.0, 1.0).unwrap())
            .with_position(Vector2::new(x, 0.0))
            .with_velocity(Vector2::new(1.0, spin * x))
            .with_rotation(0.0, spin)
    };
    let a = world.add_body(half(-0.5)).unwrap();
    let b = world.add_body(half(0.5)).unwrap();
    let weld = world
        .add_joint(JointDef::weld(
            "glue",
            Some(a),
            Some(b),
            Vector2::zeros(),
            Weld::default(),
        ))
        .unwrap();
    let bound = separation_bound(0.0, spin * spin * 1.0);
    for _ in 0..300 {
        world.step(DT).unwrap();
        let s = world.joint(weld).unwrap();
        // Measured: at most 1.37e-4 m of 1.65e-4.
        assert!(
            s.linear_error <= bound,
            "{:e} m > {bound:e}",
            s.linear_error
        );
        assert!(s.angular_error < 1e-12, "{}", s.angular_error);
        let (wa, wb) = (
            world.states()[a].angular_velocity,
            world.states()[b].angular_velocity,
        );
        assert_eq!(wa, wb);
    }
}

fn world_without_gravity() -> World {
    world(0.0)
}

#[test]
fn a_target_joint_pulls_with_a_bounded_force() {
    // A 1 kg box pulled from the origin toward (2, 0) with at most 5 N:
    // the 4 Hz spring would pull with m ω² d ≈ 1263 N, so the bound holds
    // it to 5 N, an acceleration of exactly 5 m/s² at first; it then
    // settles on the target, follows it when moved, and never pulls
    // harder than 5 N (the impulse is scaled onto |λ| ≤ h F_max each
    // solve).
    let mut world = world(0.0);
    let body = world
        .add_body(BodyDef::rigid(
            "box",
            1.0,
            Shape::rectangle(0.5, 0.5).unwrap(),
        ))
        .unwrap();
    let hand = world
        .add_joint(JointDef::target(
            "hand",
            body,
            Vector2::zeros(),
            Vector2::new(2.0, 0.0),
            Target::new(5.0),
        ))
        .unwrap();
    let cap = 5.0 * (1.0 + 4.0 * f64::EPSILON);
    world.step(DT).unwrap();
    assert!((world.states()[body].velocity.x - 5.0 * DT).abs() < 1e-15);
    for _ in 0..600 {
        world.step(DT).unwrap();
        assert!(world.joint(hand).unwrap().force.norm() <= cap);
    }
    assert!(world.joint(hand).unwrap().linear_error < 1e-9);
    world
        .set_joint_target(hand, Vector2::new(2.0, 3.0))
        .unwrap();
    for _ in 0..600 {
        world.step(DT).unwrap();
        assert!(world.joint(hand).unwrap().force.norm() <= cap);
    }
    let s = world.joint(hand).unwrap();
    assert_eq!(s.anchor_a, Vector2::new(2.0, 3.0));
    assert!(s.linear_error < 1e-9, "{s:?}");
}
