//! The same small scenes in both adapters (Box2D through boxdd, rapier),
//! checked against what the soft-step contact model predicts. Box2D runs in
//! f32, rapier in f64: each tolerance below says which rounding it covers.

use super::*;
use crate::box2d_world::Box2dWorld;
use crate::rapier_many::RapierManyWorld;
use crate::test_support::assert_close;
use engine::{Circle, ConvexPolygon};
use nalgebra::Vector2;
use scenes::{BENCHMARK_DT, BENCHMARK_SUBSTEPS, pyramid};
use std::f64::consts::TAU;

/// Unit roundoff of f32 (2⁻²⁴): the relative error of one rounding.
const EPS32: f64 = f32::EPSILON as f64 / 2.0;
/// Unit roundoff of f64 (2⁻⁵³).
const EPS64: f64 = f64::EPSILON / 2.0;

/// Both adapters on `scene`, with the unit roundoff of their precision.
fn engines(scene: &ManyBodyScene) -> Vec<(Box<dyn ManyBodyEngine>, f64)> {
    vec![
        (Box::new(Box2dWorld::new(scene).unwrap()), EPS32),
        (Box::new(RapierManyWorld::new(scene).unwrap()), EPS64),
    ]
}

fn run(engine: &mut dyn ManyBodyEngine, steps: usize) -> Vec<BodySample> {
    for _ in 0..steps {
        engine.step().unwrap();
    }
    let mut out = Vec::new();
    engine.samples(&mut out).unwrap();
    out
}

/// Angular frequency (rad/s) of the soft contacts against a static body at
/// the benchmark step: both engines use 2 × 30 Hz (Box2D's contact hertz
/// min(30, 0.125/h) = 30 Hz at h = 1/240 s, doubled for static contacts;
/// rapier's `static_contact_softness` 60 Hz).
const OMEGA_STATIC: f64 = TAU * 60.0;
/// The same for contacts between two dynamic bodies (30 Hz in both).
const OMEGA_DYNAMIC: f64 = TAU * 30.0;

/// Steady overlap of one contact point carrying a normal force `force`
/// (N) through a soft contact of angular frequency `omega` and effective
/// normal mass `normal_mass` (kg).
///
/// The soft step solves Δλ = −m_n (s_m v_n + s_m b s) − s_i λ per point
/// and substep (Box2D `contact_solver.c`; rapier's kernel is the same
/// model). With a = hω(2ζ + hω) (Box2D's `b2MakeSoft`), the bias rate is
/// b = ω/(2ζ + hω), the mass scale s_m = a/(1 + a) and the impulse scale
/// s_i = 1/(1 + a) = s_m/a. At rest the warm-started impulse λ = F h
/// already holds the body (v_n = 0), so Δλ = 0 gives
/// s = −s_i F h/(m_n s_m b) = −F h/(m_n a b) = −F/(m_n ω²): a spring of
/// stiffness m_n ω², independent of ζ and h.
fn soft_overlap(force: f64, normal_mass: f64, omega: f64) -> f64 {
    force / (normal_mass * omega * omega)
}

fn unit_box() -> Shape {
    Shape::rectangle(1.0, 1.0).unwrap()
}

/// A 1 m box (1 kg) placed 0.5 m above the benchmark ground, whose top
/// face is y = 0.
fn dropped_box() -> ManyBodyScene {
    let mut scene = pyramid(0);
    scene
        .bodies
        .push(SceneBody::dynamic(unit_box(), [0.0, 1.0], 1.0));
    scene
}

/// Rest overlap of the dropped box: it stands on two corner points, each
/// carrying m g/2, of effective mass m_n = 1/(1/m + r_t²/I) with the
/// tangential lever r_t = 0.5 m and I = m/6: m_n = 0.4 m.
fn box_rest_overlap() -> f64 {
    let (m, g) = (1.0, 10.0);
    soft_overlap(0.5 * m * g, 0.4 * m, OMEGA_STATIC)
}

#[test]
fn dropped_box_rests_at_the_soft_contact_overlap() {
    let scene = dropped_box();
    let expected = 0.5 - box_rest_overlap(); // 0.49991205 m
    for (mut e, eps) in engines(&scene) {
        // 120 steps = 2 s: it lands after 0.32 s; the slow (overdamped,
        // ζ = 10) contact mode decays as exp(−ω t/(2ζ)), about e^(−30) of
        // the initial 8 mm by then (e^(−27) at the 10 % slower rate
        // measured on the 30 Hz case below), far below either tolerance.
        let s = run(e.as_mut(), 120);
        // Box2D: the height is an f32 near 0.5 m, whose spacing is
        // 2·eps·0.5; the overlap is computed from f32 positions and anchors:
        // 4 spacings. Rapier: f64, the same 4 spacings (≈ 2e-16 m) would be
        // below the settling residual after 2 s, so 1e-12 m covers both.
        let tol = (4.0 * 2.0 * eps * 0.5).max(1e-12);
        assert_close(s[1].position[1], expected, tol, e.name());
        // Resting flat: two equal corner forces, equal overlaps, level to
        // the same rounding. (Sideways it may have slid a little at impact:
        // Box2D solves the two points one after the other, rapier as a
        // block, so x is not checked.)
        assert_close(s[1].angle, 0.0, tol, e.name());
        // At rest: the velocity Box2D leaves after the relax pass is f32
        // noise of the substep's gravity increment g h = 0.042 m/s.
        assert!(s[1].speed() < 1e-6, "{} {:?}", e.name(), s[1]);
        let c = e.contact_counts().unwrap();
        assert_eq!((c.touching_pairs, c.points), (1, 2), "{}", e.name());
    }
}

#[test]
fn box2d_reports_the_rest_overlap_and_rapier_keeps_the_impact_one_while_recycling() {
    let scene = dropped_box();
    let mut b = Box2dWorld::new(&scene).unwrap();
    run(&mut b, 120);
    let c = b.contact_counts().unwrap();
    assert_eq!(c.penetrating_points, 2);
    // Box2D updates a recycled pair's separations from the body motion:
    // f32 separations near 0.5 m positions, 4 spacings of 0.5 m.
    assert_close(
        c.deepest_penetration,
        box_rest_overlap(),
        4.0 * 2.0 * EPS32 * 0.5,
        "Box2D overlap",
    );

    // rapier keeps the dist of the pair's last full update: here the first
    // contact, at impact (8 mm, about 90 times the rest overlap).
    let mut r = RapierManyWorld::new(&scene).unwrap();
    run(&mut r, 120);
    let stale = r.contact_counts().unwrap().deepest_penetration;
    assert!(stale > 10.0 * box_rest_overlap(), "{stale}");
    // Without recycling every step recomputes it; it then reads the overlap
    // at the start of the last step, the rest overlap (f64, settled).
    let mut r = RapierManyWorld::new(&scene).unwrap();
    r.disable_contact_recycling();
    run(&mut r, 120);
    let c = r.contact_counts().unwrap();
    assert_close(
        c.deepest_penetration,
        box_rest_overlap(),
        1e-12,
        "rapier overlap without recycling",
    );
    // The geometric measure agrees with both.
    let mut out = Vec::new();
    r.samples(&mut out).unwrap();
    let o = deepest_overlap(&scene.bodies, &out).unwrap();
    assert_close(o.depth, box_rest_overlap(), 1e-12, "overlap from poses");
}

/// Bound on how far the top of a standing pyramid of `base` boxes (1 m,
/// 1 kg) can sink by soft compression alone.
///
/// A box `r` rows from the top carries at most the boxes of the triangle
/// above it, r(r + 1)/2 including itself, through the points under it;
/// each point overlaps by [`soft_overlap`] of its force, largest for the
/// smallest effective mass: 1/(2/m + 2·0.5²/I) = m/5 between two boxes
/// (lever at most half a box on each), m/2.5 on the ground. The top box's
/// drop is at most the sum over the rows of the deepest point under each
/// (its centre lies between its supports). Sideways, to first order in the
/// tilts, each row tilts by at most its compression over the 1 m span of
/// its supports and shifts the rows above by that angle times ≤ 1 m per
/// row: the same sum bounds it.
fn pyramid_sink_bound(base: usize) -> f64 {
    let (m, g) = (1.0, 10.0);
    let load = |r: usize| (r * (r + 1) / 2) as f64 * m * g;
    let between: f64 = (1..base)
        .map(|r| soft_overlap(load(r), m / 5.0, OMEGA_DYNAMIC))
        .sum();
    between + soft_overlap(load(base), m / 2.5, OMEGA_STATIC)
}

#[test]
fn base_5_pyramid_stands_for_120_steps() {
    let scene = pyramid(5);
    let bound = pyramid_sink_bound(5); // 0.031 m
    for (mut e, _) in engines(&scene) {
        let s = run(e.as_mut(), 120);
        let top = scene.bodies.len() - 1;
        let sink = scene.bodies[top].position[1] - s[top].position[1];
        assert!(sink > 0.0 && sink < bound, "{}: sink {sink}", e.name());
        for (i, (b, q)) in scene.bodies.iter().zip(&s).enumerate().skip(1) {
            let dx = (q.position[0] - b.position[0]).abs();
            let dy = (q.position[1] - b.position[1]).abs();
            assert!(dx < bound && dy < bound, "{} box {i}: {q:?}", e.name());
            // A toppling or sliding box moves at ~ sqrt(g·0.5 m) > 1 m/s;
            // a standing pile has settled (overdamped contacts, e^(−19) of
            // the landing transient after 2 s at 30 Hz, ζ = 10).
            assert!(q.speed() < 1e-3, "{} box {i}: {q:?}", e.name());
        }
        let c = e.contact_counts().unwrap();
        // 15 boxes: 5 on the ground, 4 + 3 + 2 + 1 boxes on two each, and
        // 4 + 3 + 2 + 1 side-by-side neighbours touching: 35 pairs, each
        // face contact with two points.
        assert_eq!((c.touching_pairs, c.points), (35, 70), "{}", e.name());
        let o = deepest_overlap(&scene.bodies, &s).unwrap();
        assert!(o.depth < bound, "{}: {o:?}", e.name());
    }
}

#[test]
fn stack_of_5_stands_for_120_steps() {
    // Solver2D's vertical stack, shortened: μ 0.3, boxes offset ±1 cm.
    // Box k from the top carries k boxes: the bound of
    // pyramid_sink_bound with loads k m g instead of k(k + 1)/2 m g.
    let scene = scenes::vertical_stack(5, 0.3, 0.01);
    let (m, g) = (1.0, 10.0);
    let bound: f64 = (1..5)
        .map(|k| soft_overlap(k as f64 * m * g, m / 5.0, OMEGA_DYNAMIC))
        .sum::<f64>()
        + soft_overlap(5.0 * m * g, m / 2.5, OMEGA_STATIC); // 0.0079 m
    for (mut e, _) in engines(&scene) {
        let s = run(e.as_mut(), 120);
        for (i, (b, q)) in scene.bodies.iter().zip(&s).enumerate().skip(1) {
            let dx = (q.position[0] - b.position[0]).abs();
            let dy = b.position[1] - q.position[1];
            assert!(
                dx < bound && dy > 0.0 && dy < bound,
                "{} box {i}: {q:?}",
                e.name()
            );
            assert!(q.speed() < 1e-3, "{} box {i}: {q:?}", e.name());
        }
    }
}

#[test]
fn kinematic_body_moves_at_its_velocity() {
    let mut scene = pyramid(0);
    let (v, w) = ([1.5, -0.5], 0.7);
    scene.bodies.push(SceneBody::kinematic(
        Shape::rectangle(1.0, 0.5).unwrap(),
        [0.0, 5.0],
        v,
        w,
    ));
    let steps = 60;
    let n_sub = (steps * BENCHMARK_SUBSTEPS) as f64;
    let h = BENCHMARK_DT / BENCHMARK_SUBSTEPS as f64;
    let t = steps as f64 * BENCHMARK_DT;
    for (mut e, eps) in engines(&scene) {
        let s = run(e.as_mut(), steps)[1];
        // Each substep adds v·h to the position (gravity does not act on
        // a kinematic body): one rounding of a value ≤ 5 m per substep.
        let tol = n_sub * eps * 5.0;
        assert_close(s.position[0], v[0] * t, tol, e.name());
        assert_close(s.position[1], 5.0 + v[1] * t, tol, e.name());
        // Both engines turn the rotation (cos, sin) by the linearised
        // increment and renormalise, which advances the angle by
        // atan(ω h) per substep (2.8e-6 rad short of ω t over 1 s): one
        // rounding of a value ≤ 1 per substep.
        let expected = n_sub * (w * h).atan();
        assert_close(s.angle, expected, n_sub * eps * 1.0, e.name());
        // The velocity is kept as given, rounded once to f32 for Box2D.
        assert_close(s.velocity[0], v[0], eps * 1.5, e.name());
        assert_close(s.velocity[1], v[1], eps * 0.5, e.name());
        assert_close(s.angular_velocity, w, eps * 0.7, e.name());
    }
}

/// A right triangle with legs 1.2 and 0.9 m, re-centred on its centroid.
fn triangle() -> Shape {
    let p = ConvexPolygon::new(vec![
        Vector2::new(0.0, 0.0),
        Vector2::new(1.2, 0.0),
        Vector2::new(0.0, 0.9),
    ])
    .unwrap();
    Shape::Polygon(p.centered())
}

#[test]
fn circle_box_and_triangle_get_density_times_area() {
    let mut scene = pyramid(0);
    let density = 2.5;
    let shapes = [
        Shape::Circle(Circle::new(0.3).unwrap()),
        Shape::rectangle(0.8, 0.4).unwrap(),
        triangle(),
    ];
    for (k, shape) in shapes.iter().enumerate() {
        let b = SceneBody::dynamic(shape.clone(), [3.0 * k as f64, 2.0], density);
        scene.bodies.push(b);
    }
    for (mut e, eps) in engines(&scene) {
        let m = e.mass_properties().unwrap();
        assert_eq!(m[0], BodyMass::default(), "static ground has no mass");
        for (k, b) in scene.bodies.iter().enumerate().skip(1) {
            // Box2D computes area and second moment in f32 from the f32
            // vertices (a fan of ≤ 3 triangles, a few roundings each, and
            // the density rounded once): 16 roundings. rapier: the same in
            // f64.
            let tol = 16.0 * eps;
            assert_close(m[k].mass, b.mass(), tol * b.mass(), e.name());
            assert_close(m[k].inertia, b.inertia(), tol * b.inertia(), e.name());
        }
    }
}

#[test]
fn friction_mixes_as_the_geometric_mean() {
    // A box sliding at 3 m/s on the ground, μ 0.5 on the box and 0.2 on
    // the ground: Box2D's √(μa μb) = √0.1. Sliding friction removes
    // μ_eff g h of speed per substep from the first one on (the box
    // starts touching; the relax pass holds the full normal impulse m g h
    // before friction is solved), so after 0.5 s v = 3 − μ_eff g t.
    let mut scene = pyramid(0);
    scene.bodies[0].friction = 0.2;
    let mut slider = SceneBody::dynamic(unit_box(), [-20.0, 0.5], 1.0);
    slider.velocity = [3.0, 0.0];
    slider.friction = 0.5;
    scene.bodies.push(slider);
    let expected = 3.0 - 0.1_f64.sqrt() * 10.0 * 0.5;
    let substeps = (30 * BENCHMARK_SUBSTEPS) as f64;
    for (mut e, eps) in engines(&scene) {
        let s = run(e.as_mut(), 30)[1];
        // One rounding of a speed ≤ 3 m/s per substep.
        assert_close(s.velocity[0], expected, substeps * eps * 3.0, e.name());
    }
}

#[test]
fn restitution_mixes_as_the_maximum() {
    // A ball (e 0.5) dropped onto the ground (e 0) from 1 m: max(0.5, 0)
    // = 0.5. The rebound speed is e times the approach speed at the start
    // of the contact step, which is within one step's gain g·dt = 0.17 m/s
    // of the impact speed √(2 g h) = 4.47 m/s (above Box2D's 1 m/s
    // threshold): |v_up − e √(2 g h)| ≤ e g dt.
    let mut scene = pyramid(0);
    let mut ball = SceneBody::dynamic(Shape::Circle(Circle::new(0.25).unwrap()), [0.0, 1.25], 1.0);
    ball.restitution = 0.5;
    scene.bodies.push(ball);
    let impact = (2.0_f64 * 10.0 * 1.0).sqrt();
    for (mut e, _) in engines(&scene) {
        let mut up = 0.0_f64;
        let mut out = Vec::new();
        for _ in 0..60 {
            e.step().unwrap();
            e.samples(&mut out).unwrap();
            up = up.max(out[1].velocity[1]);
        }
        assert_close(up, 0.5 * impact, 0.5 * 10.0 * BENCHMARK_DT, e.name());
    }
}

#[test]
fn invalid_scenes_are_refused_with_the_body_and_field() {
    let good = dropped_box();
    let cases: Vec<(ManyBodyScene, &str)> = vec![
        {
            let mut s = good.clone();
            s.bodies[1].position[1] = f64::NAN;
            (s, "body 1: position y = NaN must be finite")
        },
        {
            let mut s = good.clone();
            s.bodies[1].density = 0.0;
            (
                s,
                "body 1: density = 0 must be finite and > 0 for a dynamic body",
            )
        },
        {
            let mut s = good.clone();
            s.bodies[0].velocity = [1.0, 0.0];
            (s, "body 0: velocity of a static body = 1")
        },
        {
            let mut s = good.clone();
            s.bodies[1].friction = -0.1;
            (s, "body 1: friction = -0.1 must be finite and >= 0")
        },
        {
            let mut s = good.clone();
            let off = ConvexPolygon::rectangle(1.0, 1.0).unwrap();
            let moved = off
                .vertices()
                .iter()
                .map(|v| v + Vector2::new(0.2, 0.0))
                .collect();
            s.bodies[1].shape = Shape::Polygon(ConvexPolygon::new(moved).unwrap());
            (s, "body 1: shape centroid distance from the origin = 0.2")
        },
        {
            let mut s = good.clone();
            s.bodies[1].shape = Shape::rectangle(2.0, 2.0).unwrap();
            s.bodies[1].density = f64::MAX;
            (
                s,
                "body 1: mass (density × area) = inf must be finite and > 0",
            )
        },
        {
            let mut s = good.clone();
            s.substeps = 0;
            (s, "substeps = 0 must be between 1 and 1000")
        },
        {
            let mut s = good.clone();
            s.dt = -0.01;
            (s, "dt = -0.01 must be finite and > 0")
        },
    ];
    for (scene, message) in cases {
        let b = Box2dWorld::new(&scene).err().expect("Box2D refuses");
        let r = RapierManyWorld::new(&scene).err().expect("rapier refuses");
        assert_eq!(b.to_string(), r.to_string());
        assert!(b.to_string().contains(message), "{b}");
    }
}

#[test]
fn an_off_centre_wall_on_a_kinematic_body_is_accepted_and_turns_about_the_origin() {
    // The tumbler's construction: a wall polygon 10 m off the axis, on a
    // kinematic body at the axis turning at 25°/s.
    let wall = ConvexPolygon::new(vec![
        Vector2::new(9.5, -10.0),
        Vector2::new(10.5, -10.0),
        Vector2::new(10.5, 10.0),
        Vector2::new(9.5, 10.0),
    ])
    .unwrap();
    let w = 25f64.to_radians();
    let scene = ManyBodyScene {
        gravity: [0.0, -10.0],
        dt: BENCHMARK_DT,
        substeps: BENCHMARK_SUBSTEPS,
        bodies: vec![SceneBody::kinematic(
            Shape::Polygon(wall),
            [0.0, 10.0],
            [0.0, 0.0],
            w,
        )],
        joints: Vec::new(),
    };
    for (mut e, eps) in engines(&scene) {
        let s = run(e.as_mut(), 60)[0];
        // The origin stays on the axis; only the angle moves (see
        // kinematic_body_moves_at_its_velocity for the atan increments).
        assert_eq!(s.position, [0.0, 10.0], "{}", e.name());
        let n = (60 * BENCHMARK_SUBSTEPS) as f64;
        let h = BENCHMARK_DT / BENCHMARK_SUBSTEPS as f64;
        assert_close(s.angle, n * (w * h).atan(), n * eps, e.name());
        assert_eq!(e.mass_properties().unwrap()[0], BodyMass::default());
    }
}

#[test]
fn smash_conserves_momentum() {
    // Zero gravity, no static body: contact impulses act in equal and
    // opposite pairs, so the total momentum stays 512 kg × 40 m/s.
    let scene = scenes::smash(4, 4);
    let p0 = 8.0 * 64.0 * 40.0;
    for (mut e, eps) in engines(&scene) {
        // Contact starts after (30 − 0.2 − (−20 + 4))/40 s = 69 steps.
        let s = run(e.as_mut(), 90);
        let m = e.mass_properties().unwrap();
        let p = s.iter().zip(&m).fold([0.0, 0.0], |acc, (q, mm)| {
            [
                acc[0] + mm.mass * q.velocity[0],
                acc[1] + mm.mass * q.velocity[1],
            ]
        });
        // Each application of an impulse rounds the velocities it changes:
        // at most 21 contact steps × 4 substeps × 2 passes × 12 points ≈ 2000
        // roundings of the big box's velocity, which carries the momentum.
        let tol = 2000.0 * eps * p0;
        assert_close(p[0], p0, tol, e.name());
        assert_close(p[1], 0.0, tol, e.name());
        // It hit, and no more than physics allows. Had the whole block
        // (16 boxes, 2.56 kg) been swept along at its speed (perfectly
        // inelastic) it would be at p0/(512 + 2.56) = 39.80 m/s; v < 39.9
        // says the block took at least half that momentum. It cannot give
        // them more than an elastic push (twice its speed each):
        // v ≥ 40 − 2·2.56·40/512 = 39.6 m/s.
        let v = s[0].velocity[0];
        assert!(v > 39.6 && v < 39.9, "{}: {v}", e.name());
    }
}

#[test]
fn tumbler_keeps_its_boxes_inside() {
    // The kinematic walls turn about (0, 10) m; every box centre stays
    // inside the walls' inner faces (±9.5 m in the turning frame): a box
    // escaping would have to cross one. (Boxes do overlap a wall for a
    // while when it strikes them: at the corners it moves at
    // 25°/s × 13.4 m = 5.9 m/s, and a soft contact with a kinematic body
    // (30 Hz) gives way by up to about v/ω = 3 cm before it pushes back.)
    let scene = scenes::tumbler(3);
    for (mut e, _) in engines(&scene) {
        let s = run(e.as_mut(), 120);
        let theta = s[0].angle;
        for (i, q) in s.iter().enumerate().skip(4) {
            let (dx, dy) = (q.position[0], q.position[1] - 10.0);
            let (c, sn) = (theta.cos(), theta.sin());
            let local = [c * dx + sn * dy, -sn * dx + c * dy];
            let limit = 9.5;
            assert!(
                local[0].abs() < limit && local[1].abs() < limit,
                "{} box {i} at {local:?}",
                e.name()
            );
        }
        // They fell: from at most 0.6 m below the axis, free fall would
        // take them 20 m down in 2 s; the turned floor (at least 9.5 m
        // below the axis) stops them more than 5 m down.
        let lowest = s[4..]
            .iter()
            .map(|q| q.position[1])
            .fold(f64::INFINITY, f64::min);
        assert!(lowest < 10.0 - 5.0, "{}: {lowest}", e.name());
    }
}

#[test]
fn contacts_with_a_kinematic_body_are_as_soft_as_between_dynamic_ones() {
    // A box resting on a motionless kinematic slab: both engines use the
    // 30 Hz softness of dynamic pairs (Box2D keeps the doubled static
    // hertz for bodies outside its awake set, rapier for world-attached
    // solver sides: static bodies only), so it rests 4 times deeper than
    // on static ground: F/(m_n ω²) with ω = 2π·30.
    let mut scene = pyramid(0);
    scene.bodies[0] = SceneBody::kinematic(
        Shape::rectangle(200.0, 2.0).unwrap(),
        [0.0, -1.0],
        [0.0, 0.0],
        0.0,
    );
    scene
        .bodies
        .push(SceneBody::dynamic(unit_box(), [0.0, 0.5], 1.0));
    let overlap = soft_overlap(0.5 * 10.0, 0.4, OMEGA_DYNAMIC);
    for (mut e, eps) in engines(&scene) {
        // As in dropped_box_rests_at_the_soft_contact_overlap, but settling
        // is twice as slow at 30 Hz (the overdamped mode decays at about
        // ω/(2ζ) = 9.4 s⁻¹, a little slower in the discrete solver): 240
        // steps (4 s) bring the residual below 1e-12 m.
        let s = run(e.as_mut(), 240);
        let tol = (4.0 * 2.0 * eps * 0.5).max(1e-12);
        assert_close(s[1].position[1], 0.5 - overlap, tol, e.name());
    }
}
