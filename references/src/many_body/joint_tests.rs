//! Joints in both adapters (Box2D through boxdd, rapier) against closed
//! forms and derived bounds: pendulum periods (revolute and rod) and
//! anchor separations, a motor's ramp, a limit's rest angle, the reference
//! angle and a spring's target, the slider's period and rest, a weld's
//! sag, a joint grid and a ragdoll that stay connected, Falling Hinges
//! closing their gaps. Box2D runs in f32, rapier in f64.

use super::*;
use crate::box2d_world::Box2dWorld;
use crate::pendulum::PhysicalPendulum;
use crate::rapier_many::RapierManyWorld;
use std::f64::consts::{PI, TAU};

/// Both adapters on `scene`.
pub(super) fn engines(scene: &ManyBodyScene) -> Vec<Box<dyn ManyBodyEngine>> {
    vec![
        Box::new(Box2dWorld::new(scene).unwrap()),
        Box::new(RapierManyWorld::new(scene).unwrap()),
    ]
}

const G: f64 = 9.81;
/// Radius of the pendulum bob, m: small against L = 1 m, its own inertia
/// counted exactly through the physical-pendulum length.
const BOB: f64 = 0.05;

/// A bob of radius [`BOB`] (density 1) hanging at distance `length` from
/// the world pivot at the origin, released at rest at `amplitude` rad from
/// the downward vertical, g = 9.81, dt 1/60 s with `substeps`; the
/// joint is a revolute at the origin or a rigid rod to the bob's centre.
pub(super) fn pendulum(length: f64, amplitude: f64, substeps: usize, rod: bool) -> ManyBodyScene {
    let (s, c) = amplitude.sin_cos();
    let centre = [length * s, -length * c];
    let bob = SceneBody::dynamic(Shape::circle(BOB).unwrap(), centre, 1.0);
    let joint = if rod {
        SceneJoint::rod(None, Some(0), [0.0, 0.0], centre)
    } else {
        SceneJoint::revolute(None, Some(0), [0.0, 0.0], 0.0)
    };
    ManyBodyScene {
        gravity: [0.0, -G],
        dt: 1.0 / 60.0,
        substeps,
        bodies: vec![bob],
        joints: vec![joint],
    }
}

/// The pendulum angle of body 0 about the origin, from the downward
/// vertical.
fn swing_angle(s: &BodySample) -> f64 {
    s.position[0].atan2(-s.position[1])
}

/// What [`measure`] reads over a pendulum run.
struct Swing {
    /// Mean period between upward zero crossings of the swing angle, s.
    period: f64,
    /// Largest joint separation, m.
    separation: f64,
    /// Largest |swing angle| after the first period, rad.
    amplitude: f64,
    /// Largest bob speed, m/s.
    speed: f64,
}

/// Runs `engine` for `periods` expected periods (`period` s), locating
/// each upward zero crossing of the swing angle by linear interpolation
/// between steps.
fn measure(
    scene: &ManyBodyScene,
    engine: &mut dyn ManyBodyEngine,
    period: f64,
    periods: usize,
) -> Swing {
    let steps = (period * periods as f64 / scene.dt).ceil() as usize + 2;
    let mut out = Vec::new();
    let mut crossings = Vec::new();
    let (mut prev, mut worst, mut amp, mut speed) = (f64::NAN, 0.0_f64, 0.0_f64, 0.0_f64);
    for i in 1..=steps {
        engine.step().unwrap();
        engine.samples(&mut out).unwrap();
        let a = swing_angle(&out[0]);
        if prev < 0.0 && a >= 0.0 {
            let t = scene.dt * ((i - 1) as f64 + prev / (prev - a));
            crossings.push(t);
        }
        worst = worst.max(scene.joint_states(&out)[0].separation);
        speed = speed.max(out[0].speed());
        if i as f64 * scene.dt > period {
            amp = amp.max(a.abs());
        }
        prev = a;
    }
    let n = crossings.len() - 1;
    Swing {
        period: (crossings[n] - crossings[0]) / n as f64,
        separation: worst,
        amplitude: amp,
        speed,
    }
}

/// The a-priori bound on the relative period error of a first-order
/// method (symplectic Euler per substep h) on a pendulum of amplitude θ0:
/// its local error per substep is at most (h²/2)|θ''| ≤ (h²/2) ω² θ0;
/// summed without cancellation over the T/h substeps of a period it shifts
/// the phase by at most (T h/2) ω² θ0 = π ω h θ0 rad, i.e. the zero
/// crossing, passed at the peak angular speed ω θ0, by π h s: relative to
/// T = 2π/ω, ω h/2. (At dt 1/60 s, 4 substeps and ω = 3.13 rad/s:
/// 6.5e-3.) Both engines' own effects of the joint's softness (Box2D's
/// 60 Hz joint stretches by g/ω_c² = 6.9e-5 m, lengthening T by 3.5e-5)
/// are far inside it.
fn first_order_period_bound(omega: f64, h: f64) -> f64 {
    0.5 * omega * h
}

/// The largest joint separation of the pendulum in `engine`, derived from
/// the step: each substep moves the bob along its tangent by h v, off the
/// circle by δ = (h v)²/(2L) ≤ (h v_max)²/(2L), v_max the largest speed
/// of the run. (`v_max` is read at the ends of steps; the speed peaks at
/// the bottom, where v'' = −ω² v, so between two samples dt apart it
/// exceeds the largest sample by at most a factor 1 + (ω dt)²/8, which
/// the caller applies.) Rapier removes the
/// error within the next substep (joint softness 1e6 Hz: erp = 1 − 8e-5),
/// so its separation after a step is the last substep's δ. Box2D's joint
/// is a 60 Hz, ζ = 2 soft constraint (min(60, 0.25/h) Hz): under the rod
/// tension F ≤ m g (3 − 2 cos θ0) it stretches by F/(m ω_c²) (its effective
/// mass along the rod is m), and it removes a fraction h b s_m of the drift
/// per substep (bias rate b = ω_c/(2ζ + hω_c), mass scale s_m =
/// a/(1 + a), a = hω_c(2ζ + hω_c)), so the drift stands at δ/(h b s_m);
/// the two add at most at the bottom of the swing.
fn separation_bound(box2d: bool, h: f64, length: f64, v_max: f64, theta0: f64) -> f64 {
    let delta = (h * v_max).powi(2) / (2.0 * length);
    if box2d {
        let omega = TAU * 60f64.min(0.25 / h);
        let zeta = 2.0;
        let b = omega / (2.0 * zeta + h * omega);
        let a = h * omega * (2.0 * zeta + h * omega);
        let tension = G * (3.0 - 2.0 * theta0.cos());
        // f32: 16 spacings of the 1 m positions the anchors come from.
        tension / (omega * omega) + delta / (h * b * a / (1.0 + a)) + 16.0 * f32::EPSILON as f64
    } else {
        // erp = hω/(hω + 2ζ) at 1e6 Hz, ζ = 1; f64 round-off.
        let w = TAU * 1e6;
        delta * (h * w + 2.0) / (h * w) + 1e-12
    }
}

#[test]
fn pendulum_periods_are_within_the_first_order_bound() {
    // Released from 10° at dt = 1/60 s, 4 substeps (the benchmark step),
    // measured over 10 periods. On a revolute joint the bob turns with the
    // arm: a physical pendulum (L_eq = L + r²/(2L)); on a rod fixed at
    // the bob's centre it does not turn: a simple pendulum of length L.
    let theta0 = 10f64.to_radians();
    let h = 1.0 / 240.0;
    for rod in [false, true] {
        let exact = if rod {
            crate::pendulum::Pendulum::new(1.0, G, theta0)
        } else {
            PhysicalPendulum::disc(BOB, 1.0).pendulum(G, theta0)
        };
        let scene = pendulum(1.0, theta0, 4, rod);
        for mut e in engines(&scene) {
            let box2d = e.name().starts_with("Box2D");
            let m = measure(&scene, e.as_mut(), exact.period(), 10);
            let v_max = m.speed * (1.0 + (exact.omega() * scene.dt).powi(2) / 8.0);
            let (t, sep, amp) = (m.period, m.separation, m.amplitude);
            let rel = t / exact.period() - 1.0;
            eprintln!(
                "{} {}: T = {t:.9} s (exact {:.9} s, relative {rel:+.3e}, bound {:.2e}); \
                 separation {sep:.3e} m (bound {:.3e}); amplitude {:.5} deg",
                e.name(),
                if rod { "rod" } else { "revolute" },
                exact.period(),
                first_order_period_bound(exact.omega(), h),
                separation_bound(box2d, h, 1.0, v_max, theta0),
                amp.to_degrees()
            );
            assert!(
                rel.abs() <= first_order_period_bound(exact.omega(), h),
                "{}: relative period error {rel:e}",
                e.name()
            );
            assert!(
                sep <= separation_bound(box2d, h, 1.0, v_max, theta0),
                "{}: separation {sep:e}",
                e.name()
            );
        }
    }
}

/// A disc of radius 0.5 m (density 1) on a revolute joint at its centre to
/// the world, under gravity, driven by a motor of `speed` rad/s and
/// `max_torque` N·m.
fn motor_scene(speed: f64, max_torque: f64) -> ManyBodyScene {
    let disc = SceneBody::dynamic(Shape::circle(0.5).unwrap(), [0.0, 2.0], 1.0);
    let mut joint = SceneJoint::revolute(None, Some(0), [0.0, 2.0], 0.0);
    if let JointKind::Revolute(r) = &mut joint.kind {
        r.motor = Some(Motor {
            speed,
            max_force: max_torque,
        });
    }
    ManyBodyScene {
        gravity: [0.0, -G],
        dt: 1.0 / 60.0,
        substeps: 4,
        bodies: vec![disc],
        joints: vec![joint],
    }
}

#[test]
fn motor_ramps_at_its_maximum_torque_then_holds_its_speed() {
    // The disc's inertia (I = m r²/2 = π/32 kg·m²) is the load. While the
    // motor is saturated each substep adds exactly h τ/I to ω (the
    // impulse is clamped at h τ), so ω = τ t/I until it reaches the
    // target at t* = I ω*/τ = 0.96 s; then the rigid velocity row holds ω*.
    let (target, torque) = (2.0, 0.2);
    let scene = motor_scene(target, torque);
    let inertia = scene.bodies[0].inertia();
    let t_star = inertia * target / torque;
    for mut e in engines(&scene) {
        let box2d = e.name().starts_with("Box2D");
        let mut out = Vec::new();
        for step in 1..=120 {
            e.step().unwrap();
            let t = step as f64 * scene.dt;
            e.samples(&mut out).unwrap();
            let w = out[0].angular_velocity;
            if t < t_star - scene.dt {
                // Box2D: f32 sums of 4 per step increments h τ/I (< 0.01
                // rad/s), one rounding of ω ≤ 2 each: ≤ 4 × step × 2⁻²⁴ × 2.
                // rapier: f64, the same count of roundings of 2⁻⁵³.
                let eps = if box2d {
                    0.5 * f32::EPSILON as f64
                } else {
                    0.5 * f64::EPSILON
                };
                let tol = 4.0 * step as f64 * eps * 2.0 + if box2d { 4.0 * eps } else { 0.0 };
                crate::test_support::assert_close(
                    w,
                    torque * t / inertia,
                    tol,
                    &format!("{} omega at t = {t:.3} s", e.name()),
                );
            }
            if t > t_star + scene.dt {
                // Box2D's row is exactly rigid: ω* to f32 rounding. rapier's
                // compliance 1/(h c) = 2.4e-13 leaves ω* (1 − 2.4e-13).
                let tol = if box2d {
                    2.0 * f32::EPSILON as f64
                } else {
                    1e-11
                };
                crate::test_support::assert_close(
                    w,
                    target,
                    tol,
                    &format!("{} omega at t = {t:.3} s", e.name()),
                );
            }
            // The pivot holds the disc's weight at its centre.
            assert!(
                scene.joint_states(&out)[0].separation < 1e-4,
                "{}: {:?}",
                e.name(),
                scene.joint_states(&out)[0]
            );
        }
    }
}

/// A bar `length` × 0.1 m (density 1) pivoted at its left end at the
/// origin, horizontal at t = 0, with angle limits `limits` rad.
fn limited_bar(length: f64, limits: [f64; 2]) -> ManyBodyScene {
    let bar = SceneBody::dynamic(
        Shape::rectangle(length, 0.1).unwrap(),
        [0.5 * length, 0.0],
        1.0,
    );
    let mut joint = SceneJoint::revolute(None, Some(0), [0.0, 0.0], 0.0);
    if let JointKind::Revolute(r) = &mut joint.kind {
        r.limits = Some(limits);
    }
    ManyBodyScene {
        gravity: [0.0, -G],
        dt: 1.0 / 60.0,
        substeps: 4,
        bodies: vec![bar],
        joints: vec![joint],
    }
}

/// Box2D's `b2Atan2` (`math_functions.c`), the approximation with which it
/// measures joint angles (`b2Rot_GetAngle`, `b2RelativeAngle`): a minimax
/// polynomial for atan on [0, 1], mapped to the circle. Its largest error
/// is 2.8e-5 rad. Evaluated here in f64 to predict where Box2D's limits
/// and springs hold the true angle.
fn box2d_atan2(y: f64, x: f64) -> f64 {
    let (ax, ay) = (x.abs(), y.abs());
    let a = ay.min(ax) / ay.max(ax);
    let s = a * a;
    let (c, q) = (s * a, s * s);
    let r = 0.024840285 * q + 0.18681418;
    let t = -0.094097948 * q - 0.33213072;
    let mut r = (r * s + t) * c + a;
    if ay > ax {
        r = std::f64::consts::FRAC_PI_2 - r;
    }
    if x < 0.0 {
        r = PI - r;
    }
    if y < 0.0 { -r } else { r }
}

#[test]
fn limit_stops_a_falling_bar_and_holds_it() {
    // The bar falls from horizontal, is stopped at its lower limit −0.5
    // rad and rests there. The limit is a soft row (Box2D: 60 Hz, ζ = 2 in
    // the biased pass; rapier: its joint softness, 1e6 Hz, ζ = 1); at rest
    // the warm-started impulses hold the bar, every row's increment is 0,
    // and the limit row's −s_m m_ax b C − s_i λ = 0 gives the violation
    // C = τ/(m_ax ω_c²): the gravity torque about the pivot
    // τ = m g (L/2) cos θ over the row's axial mass m_ax = I_c (the world
    // adds no inertia) times ω_c². Box2D measures the angle with
    // `b2Atan2` (see [`box2d_atan2`]), which reads |θ| = 0.5 rad as
    // 0.5 − 1.74e-5 rad: the true angle rests that much further out.
    let (length, lower) = (1.0, -0.5);
    let scene = limited_bar(length, [lower, 0.5]);
    let b = &scene.bodies[0];
    let torque = b.mass() * G * 0.5 * length * lower.cos();
    for mut e in engines(&scene) {
        let box2d = e.name().starts_with("Box2D");
        let hertz: f64 = if box2d { 60.0 } else { 1e6 };
        let sag = torque / (b.inertia() * (TAU * hertz).powi(2));
        let mut out = Vec::new();
        // 3 s: the limit's mode (stiffness I_c ω_c², damping 2ζ I_c ω_c on
        // the bar's inertia about the pivot, 4 I_c) is critically damped at
        // ω_c/2 = 188 rad/s, settled within 0.1 s of the impact at 0.35 s.
        for _ in 0..180 {
            e.step().unwrap();
        }
        e.samples(&mut out).unwrap();
        let s = scene.joint_states(&out)[0];
        eprintln!(
            "{}: rest angle {:.15} rad, violation {:.4e} (soft-row sag {sag:.4e}), omega {:.1e}",
            e.name(),
            s.coordinate,
            s.limit_violation,
            out[0].angular_velocity
        );
        if box2d {
            let read = -box2d_atan2(lower.sin().abs(), lower.cos());
            // f32: rotations, the polynomial and the masses to 2⁻²⁴ on
            // values ≤ 1: a few 1e-8 rad; 5e-7 rad allows 10 times that.
            crate::test_support::assert_close(
                s.limit_violation,
                sag + (read - lower).abs(),
                5e-7,
                "Box2D violation",
            );
        } else {
            // rapier's row at 1e6 Hz sags by at most 1.3e-12 rad (it holds
            // the angle exactly at the limit, to round-off); f64 round-off
            // of a 0.5 rad angle over the run: 1e-14.
            crate::test_support::assert_close(
                s.coordinate,
                lower,
                sag + 1e-14,
                "rapier rest angle",
            );
        }
        assert!(
            out[0].angular_velocity.abs() < 1e-5,
            "{}: still moving",
            e.name()
        );
    }
}

/// Largest joint separation (m) over `steps` steps of `scene` in `engine`,
/// and the states at the end.
fn worst_separation(
    scene: &ManyBodyScene,
    engine: &mut dyn ManyBodyEngine,
    steps: usize,
) -> (f64, Vec<JointState>, Vec<BodySample>) {
    let mut out = Vec::new();
    let mut worst = 0.0_f64;
    for _ in 0..steps {
        engine.step().unwrap();
        engine.samples(&mut out).unwrap();
        for s in scene.joint_states(&out) {
            worst = worst.max(s.separation);
        }
    }
    let states = scene.joint_states(&out);
    (worst, states, out)
}

#[test]
fn joint_grid_stays_connected() {
    // 3 × 3: the top row static, 6 circles hanging by 10 joints. A joint
    // carries at most the weight W of the 6 dynamic circles; the stiffness
    // of Box2D's 60 Hz joint row is m_eff ω_c², smallest for a joint
    // between two circles pulled across its anchor lever (0.5 m on each
    // side, I = m r²/2): m_eff = 1/(2/m + 2 · 0.5²/I) = m/8.25. The grid
    // starts with unloaded joints, so the load is a step: a damped
    // response overshoots its static value by less than 2×. rapier's
    // joints (1e6 Hz) are stiffer; the same bound covers them.
    let scene = joint_grid(3);
    let m = scene.bodies[1].mass();
    let weight = 6.0 * m * 10.0;
    let omega = TAU * 60.0;
    let bound = 2.0 * weight / (m / 8.25 * omega * omega); // 7.0e-3 m
    for mut e in engines(&scene) {
        let (worst, _, out) = worst_separation(&scene, e.as_mut(), 120);
        eprintln!(
            "{}: joint grid 3x3, worst separation {worst:.3e} m (bound {bound:.3e})",
            e.name()
        );
        assert!(worst < bound, "{}: {worst}", e.name());
        // Still hanging in place: no circle has moved by a joint length.
        for (b, s) in scene.bodies.iter().zip(&out) {
            let d = (s.position[0] - b.position[0]).hypot(s.position[1] - b.position[1]);
            assert!(d < 0.1, "{}: moved {d} m", e.name());
        }
    }
}

/// One ragdoll ([`scenes::ragdoll`], the `rain` parameters) standing with
/// its feet 0.3 m above a static ground box whose top is y = 0.
pub(super) fn dropped_ragdoll() -> ManyBodyScene {
    let mut bodies = vec![SceneBody::fixed(
        Shape::rectangle(20.0, 2.0).unwrap(),
        [0.0, -1.0],
    )];
    let mut joints = Vec::new();
    scenes::ragdoll(
        &scenes::RagdollParams::rain([0.0, 0.5], 1),
        &mut bodies,
        &mut joints,
    );
    ManyBodyScene {
        gravity: [0.0, -10.0],
        dt: 1.0 / 60.0,
        substeps: 4,
        bodies,
        joints,
    }
}

#[test]
fn ragdoll_lands_and_stays_in_one_piece() {
    // It falls, lands at 0.4 s and collapses. "In one piece": every anchor
    // pair stays closer than the thinnest bone's half-width (0.03 m: the
    // lower arm's radius), through the impact and at rest; at rest after
    // 3 s every bone lies above the ground (its centre above y = 0).
    let scene = dropped_ragdoll();
    scene.validate().unwrap();
    for mut e in engines(&scene) {
        let (worst, states, out) = worst_separation(&scene, e.as_mut(), 180);
        let at_rest = states.iter().map(|s| s.separation).fold(0.0, f64::max);
        let limit = states.iter().map(|s| s.limit_violation).fold(0.0, f64::max);
        eprintln!(
            "{}: ragdoll worst separation {worst:.3e} m, at rest {at_rest:.3e} m, \
             largest limit violation at rest {limit:.3e} rad",
            e.name()
        );
        assert!(at_rest < 0.03, "{}: {at_rest}", e.name());
        assert!(out[1..].iter().all(|s| s.position[1] > 0.0), "{}", e.name());
        if e.name().starts_with("Box2D") {
            // Box2D's limits are speculative (a row engages before the
            // angle reaches it) and hold at rest to their soft sag and its
            // atan2 approximation (< 1e-3 rad here, see the bar test).
            assert!(limit < 1e-3, "Box2D: {limit}");
        }
        // rapier's angular limit rows engage only once an angle is past
        // its limit and recover at most at its corrective speed: at the
        // landing its hip–torso joint overshoots by 0.7–1.7 rad and stays
        // pinned there by the ground contacts (measured, reported, not a
        // bound; the isolated torso holds its limit in rapier).
    }
}

#[test]
fn falling_hinges_pull_their_anchors_together() {
    // Box2D's hinges start with their anchors 0.11 m apart: from the
    // poses, (0.4h, 2h) + R(0.1)(−h, −h) − R(−0.1)(−h, h) =
    // (0.4h, 2h − 2h(sin 0.1 + cos 0.1)) = (0.1, −0.0474) m. Each joint
    // pulls its pair together as it falls: after 1 s both engines have
    // closed every gap to below 2 cm (Box2D's soft 60 Hz row closes a gap
    // e-fold in 1/(b s_m) ≈ 16 ms, rapier's in a substep; what remains is
    // the load of the landing pairs).
    let scene = falling_hinges();
    scene.validate().unwrap();
    let start: Vec<BodySample> = scene
        .bodies
        .iter()
        .map(|b| BodySample {
            position: b.position,
            angle: b.angle,
            ..Default::default()
        })
        .collect();
    let h = scenes::HINGE_HALF_EXTENT;
    let (c, s) = (0.1f64.cos(), 0.1f64.sin());
    let gap = [0.4 * h, 2.0 * h - 2.0 * h * (s + c)];
    for j in scene.joint_states(&start) {
        crate::test_support::assert_close(j.separation, gap[0].hypot(gap[1]), 1e-12, "gap");
    }
    for mut e in engines(&scene) {
        let (_, states, _) = worst_separation(&scene, e.as_mut(), 60);
        let worst = states.iter().map(|s| s.separation).fold(0.0, f64::max);
        eprintln!("{}: hinges' largest gap after 1 s {worst:.3e} m", e.name());
        assert!(worst < 0.02, "{}: {worst}", e.name());
    }
}

/// The `slider` case: a 0.5 m box of 2 kg on a prismatic joint to the
/// world at its centre, along 30° above the horizontal, with a spring of
/// the box's own frequency √(k/m)/(2π) (k = 50 N/m) toward the anchor,
/// released at rest at the anchor.
fn slider_scene(s: &crate::slider::Slider) -> ManyBodyScene {
    let body = SceneBody::dynamic(Shape::rectangle(0.5, 0.5).unwrap(), [0.0, 1.0], 8.0);
    let axis = [s.angle.cos(), s.angle.sin()];
    let mut joint = SceneJoint::prismatic(None, Some(0), [0.0, 1.0], axis);
    if let JointKind::Prismatic(p) = &mut joint.kind {
        p.spring = Some(Spring {
            hertz: s.spring_hertz(),
            damping_ratio: s.damping_ratio,
            target: 0.0,
        });
    }
    ManyBodyScene {
        gravity: [0.0, -s.gravity],
        dt: 1.0 / 60.0,
        substeps: 4,
        bodies: vec![body],
        joints: vec![joint],
    }
}

#[test]
fn slider_oscillates_at_its_frequency_and_rests_at_its_equilibrium() {
    // The prismatic spring maps exactly (Hz on the box's mass, see
    // `rapier_many::joints`), so at rest both engines hold it where
    // k x = −m g sin θ, to round-off (a soft spring at rest sags by
    // λ/(m_eff h ω²) = g sin θ/ω², which is that x). Undamped, the period
    // is within the first-order bound ω h/2 (both engines integrate the
    // spring implicitly, as a soft constraint, which also damps it: the
    // swing shrinks by a few per cent per period, not checked here). The
    // perpendicular row carries m g cos θ through the box's centre
    // (K = 1/m): it sags by g cos θ/ω_c²; the box does not turn (no torque
    // about its centre).
    let mut s = crate::slider::Slider {
        mass: 2.0,
        stiffness: 50.0,
        damping_ratio: 0.0,
        angle: 30f64.to_radians(),
        gravity: 9.81,
        x0: 0.0,
        v0: 0.0,
    };
    let scene = slider_scene(&s);
    assert_eq!(scene.bodies[0].mass(), s.mass);
    let (eq, period) = (s.equilibrium(), s.period());
    let h = scene.dt / scene.substeps as f64;
    for mut e in engines(&scene) {
        let box2d = e.name().starts_with("Box2D");
        let mut out = Vec::new();
        let (mut prev, mut crossings) = (f64::NAN, Vec::new());
        let (mut off_axis, mut turned) = (0.0_f64, 0.0_f64);
        let steps = (10.0 * period / scene.dt) as usize;
        for i in 1..=steps {
            e.step().unwrap();
            e.samples(&mut out).unwrap();
            let j = scene.joint_states(&out)[0];
            let y = j.coordinate - eq;
            if prev < 0.0 && y >= 0.0 {
                crossings.push(scene.dt * ((i - 1) as f64 + prev / (prev - y)));
            }
            prev = y;
            (off_axis, turned) = (off_axis.max(j.separation), turned.max(j.angular_error));
        }
        let n = crossings.len() - 1;
        let t = (crossings[n] - crossings[0]) / n as f64;
        let rel = t / period - 1.0;
        let w_c = TAU * if box2d { 60.0 } else { 1e6 };
        let sag = s.gravity * s.angle.cos() / (w_c * w_c);
        eprintln!(
            "{}: slider period {t:.6} s (exact {period:.6}, relative {rel:+.2e}), off axis \
             {off_axis:.3e} m (sag {sag:.3e}), turned {turned:.1e} rad",
            e.name()
        );
        assert!(rel.abs() < 0.5 * s.omega() * h, "{}: {rel}", e.name());
        // f32 (Box2D): a few spacings of the 1 m coordinates; f64: 1e-12.
        let round = if box2d { 1e-6 } else { 1e-12 };
        assert!(off_axis <= sag + round, "{}: {off_axis}", e.name());
        assert!(turned <= round, "{}: {turned}", e.name());
    }
    // Critically damped, it settles: after 5 s (e^(−ω t)(1 + ω t) ≈ 4e-10
    // of the initial 0.2 m) it rests at x_eq.
    s.damping_ratio = 1.0 - 1e-9;
    let scene = slider_scene(&s);
    for mut e in engines(&scene) {
        let box2d = e.name().starts_with("Box2D");
        let mut out = Vec::new();
        for _ in 0..300 {
            e.step().unwrap();
        }
        e.samples(&mut out).unwrap();
        let x = scene.joint_states(&out)[0].coordinate;
        // Box2D: f32 positions near 1 m (4 spacings) and the f32 spring
        // constants; rapier: the settling residual 1e-10 m.
        let tol = if box2d {
            4.0 * f32::EPSILON as f64
        } else {
            1e-9
        };
        crate::test_support::assert_close(x, eq, tol, &format!("{} rest", e.name()));
    }
}

#[test]
fn weld_holds_a_cantilever_at_its_soft_sag() {
    // A 1 m × 0.2 m bar (1 kg/m²) welded to the world at its left end,
    // horizontal under gravity. At rest every row's increment is 0: the
    // angular row, holding the torque d m g (d = 0.5 m, the anchor's
    // lever), sags by d m g/(I_c ω_c²); the linear row, holding m g at the
    // anchor with compliance K_yy = 1/m + d²/I_c, by m g K_yy/ω_c². Box2D:
    // ω_c = 2π 60 rad/s (rigid weld: the joint's constraint softness);
    // rapier: 2π 1e6 rad/s.
    let bar = SceneBody::dynamic(Shape::rectangle(1.0, 0.2).unwrap(), [0.5, 0.0], 1.0);
    let scene = ManyBodyScene {
        gravity: [0.0, -G],
        dt: 1.0 / 60.0,
        substeps: 4,
        bodies: vec![bar],
        joints: vec![SceneJoint::weld(None, Some(0), [0.0, 0.0])],
    };
    let (m, ic, d) = (scene.bodies[0].mass(), scene.bodies[0].inertia(), 0.5);
    for mut e in engines(&scene) {
        let box2d = e.name().starts_with("Box2D");
        let w = TAU * if box2d { 60.0 } else { 1e6 };
        let mut out = Vec::new();
        for _ in 0..120 {
            e.step().unwrap();
        }
        e.samples(&mut out).unwrap();
        let j = scene.joint_states(&out)[0];
        let (angle, drop) = (
            d * m * G / (ic * w * w),
            m * G * (1.0 / m + d * d / ic) / (w * w),
        );
        eprintln!(
            "{}: weld angular error {:.4e} (predicted {angle:.4e}), separation {:.4e} (predicted {drop:.4e})",
            e.name(),
            j.angular_error,
            j.separation
        );
        if box2d {
            // f32: rotations and positions near 1 m, a few spacings
            // (1e-7); the sags are 4e-4 and 2.7e-4.
            crate::test_support::assert_close(j.angular_error, angle, 2e-7, "Box2D angle");
            crate::test_support::assert_close(j.separation, drop, 2e-7, "Box2D drop");
        } else {
            // rapier removes its (1e-12-sized) sag through its bias: at
            // most the prediction, plus f64 round-off of 1 m coordinates.
            assert!(j.angular_error <= angle + 1e-15, "{j:?}");
            assert!(j.separation <= drop + 1e-15, "{j:?}");
        }
    }
}

#[test]
fn reference_angle_shifts_the_limits_in_both_engines() {
    // The same falling bar, its joint angle measured from a reference of
    // 0.2 rad, limits [−0.3, 0.3]: it rests where θ − 0.2 = −0.3, at a
    // body angle of −0.1 rad (not −0.3: an engine ignoring the reference;
    // not −0.5: one subtracting it the other way). Within Box2D's sag and
    // atan2 offset (< 1e-3 rad, see the bar above).
    let mut scene = limited_bar(1.0, [-0.3, 0.3]);
    if let JointKind::Revolute(r) = &mut scene.joints[0].kind {
        r.reference_angle = 0.2;
    }
    for mut e in engines(&scene) {
        let mut out = Vec::new();
        for _ in 0..180 {
            e.step().unwrap();
        }
        e.samples(&mut out).unwrap();
        crate::test_support::assert_close(out[0].angle, -0.1, 1e-3, e.name());
        crate::test_support::assert_close(
            scene.joint_states(&out)[0].coordinate,
            -0.3,
            1e-3,
            e.name(),
        );
    }
}

#[test]
fn revolute_spring_pulls_toward_its_target_in_the_joint_angle() {
    // Without gravity, a bar pivoted at its centre on a critically damped
    // 2 Hz spring toward a joint angle of 0.4 rad, reference 0.1 rad:
    // it settles at a body angle of 0.5 rad (e^(−ω t)(1 + ω t) ≈ 1e-15
    // after 3 s). Box2D reads the angle through its atan2 (error ≤ 2.8e-5
    // rad); rapier's is exact, its settling residual 1e-12.
    let bar = SceneBody::dynamic(Shape::rectangle(1.0, 0.1).unwrap(), [0.0, 0.0], 1.0);
    let mut joint = SceneJoint::revolute(None, Some(0), [0.0, 0.0], 0.1);
    if let JointKind::Revolute(r) = &mut joint.kind {
        r.spring = Some(Spring {
            hertz: 2.0,
            damping_ratio: 1.0,
            target: 0.4,
        });
    }
    let scene = ManyBodyScene {
        gravity: [0.0, 0.0],
        dt: 1.0 / 60.0,
        substeps: 4,
        bodies: vec![bar],
        joints: vec![joint],
    };
    for mut e in engines(&scene) {
        let tol = if e.name().starts_with("Box2D") {
            3e-5
        } else {
            1e-10
        };
        let mut out = Vec::new();
        for _ in 0..180 {
            e.step().unwrap();
        }
        e.samples(&mut out).unwrap();
        crate::test_support::assert_close(out[0].angle, 0.5, tol, e.name());
    }
}
