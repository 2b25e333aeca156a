//! The engine's collision detection against parry2d (docs/cases.md case III,
//! "Reference checks"): verdicts, penetration depths and normals on random
//! convex pairs, and the two time-of-impact values.
//!
//! Run with `--nocapture` to see the measured agreement.

use super::exact::{Hull, Rng, overlap_along, signed_distance_to_polygon, world_vertices};
use super::*;
use engine::validation::collision::{
    Motion, ToiOptions, collide, proximity, separation_polygon_polygon, toi_bisection,
    toi_conservative_advancement,
};
use engine::{Circle, ConvexPolygon};

#[derive(Default, Debug)]
struct Agreement {
    pairs: usize,
    overlapping: usize,
    near_touching: usize,
    verdict_disagreements: usize,
    /// Of those, where an exact check proves the engine right: a vertex
    /// of one polygon inside the other proves an overlap, a positive
    /// separation along an edge normal (the SAT's, far above its rounding)
    /// proves a gap.
    verdict_engine_right: usize,
    max_depth_diff: f64,
    max_normal_diff: f64,
    max_distance_diff: f64,
    /// Pairs whose SAT depth/normal differ from parry's by more than 1e-9
    /// but where an exact check shows the engine is right (or they tie).
    parry_worse: usize,
    engine_worse: usize,
    clipped_manifolds: usize,
    vertex_counts: [usize; 13],
}

fn compare_polygon_pair(
    a: &ConvexPolygon,
    pa: &Isometry2<f64>,
    b: &ConvexPolygon,
    pb: &Isometry2<f64>,
    stats: &mut Agreement,
) {
    const BAND: f64 = 1e-9;
    let (sa, sb) = (Shape::Polygon(a.clone()), Shape::Polygon(b.clone()));
    stats.pairs += 1;
    stats.vertex_counts[a.vertices().len()] += 1;
    stats.vertex_counts[b.vertices().len()] += 1;

    let exact = proximity(&sa, pa, &sb, pb);
    let sat = separation_polygon_polygon(a, pa, b, pb);
    let engine_manifold = collide(&sa, pa, &sb, pb, 0.0);
    let engine_verdict = engine_manifold.is_some();
    let parry_verdict = parry_intersects(&sa, pa, &sb, pb);

    if exact.distance.abs() <= BAND {
        stats.near_touching += 1;
        return;
    }
    if engine_verdict != parry_verdict {
        stats.verdict_disagreements += 1;
        let (wa, wb) = (world_vertices(a, pa), world_vertices(b, pb));
        // Exact check: is a vertex of one inside the other, or do the
        // witness points of the engine's distance lie on the boundaries?
        let deepest_b = wb
            .iter()
            .map(|v| signed_distance_to_polygon(&wa, v))
            .fold(f64::INFINITY, f64::min);
        let deepest_a = wa
            .iter()
            .map(|v| signed_distance_to_polygon(&wb, v))
            .fold(f64::INFINITY, f64::min);
        println!(
            "VERDICT: engine {engine_verdict}, parry {parry_verdict}, engine distance {:e}, \
             SAT {:e}, parry distance {:e}, deepest vertex of B in A {:e}, of A in B {:e}\n  \
             A = {:?} at {pa:?}\n  B = {:?} at {pb:?}",
            exact.distance,
            sat.separation,
            parry_distance(&sa, pa, &sb, pb),
            deepest_b,
            deepest_a,
            a.vertices(),
            b.vertices(),
        );
        let engine_right = if engine_verdict {
            deepest_a.min(deepest_b) < 0.0
        } else {
            sat.separation > 0.0
        };
        stats.verdict_engine_right += usize::from(engine_right);
        return;
    }
    if !engine_verdict {
        let d = parry_distance(&sa, pa, &sb, pb);
        stats.max_distance_diff = stats.max_distance_diff.max((d - exact.distance).abs());
        return;
    }
    stats.overlapping += 1;
    let contact =
        parry_contact(&sa, pa, &sb, pb, 0.0).expect("parry: overlapping pair has a contact");
    let depth = -sat.separation;
    let depth_diff = (depth - contact.depth).abs();
    let normal_diff = (sat.normal - contact.normal).norm();
    let manifold = engine_manifold.unwrap();
    if manifold.max_depth() < depth - 1e-12 {
        stats.clipped_manifolds += 1;
    }
    if depth_diff > BAND || normal_diff > BAND {
        // Which is right? The depth is the smallest projection overlap over
        // all axes: compare the overlaps along both normals, and check that
        // parry's witness points lie on the boundaries.
        let (wa, wb) = (world_vertices(a, pa), world_vertices(b, pb));
        let along_engine = overlap_along(&wa, &wb, &sat.normal);
        let along_parry = overlap_along(&wa, &wb, &contact.normal);
        let witness_a = signed_distance_to_polygon(&wa, &contact.point_a);
        let witness_b = signed_distance_to_polygon(&wb, &contact.point_b);
        println!(
            "DEPTH/NORMAL: engine depth {depth:.15e} normal {:?}, parry depth {:.15e} normal {:?}\n  \
             overlap along engine normal {along_engine:.15e}, along parry normal {along_parry:.15e}; \
             parry witnesses off the boundaries by {witness_a:e}, {witness_b:e}",
            sat.normal, contact.depth, contact.normal,
        );
        if along_engine <= along_parry + 1e-12 {
            stats.parry_worse += 1;
        } else {
            stats.engine_worse += 1;
        }
        return;
    }
    stats.max_depth_diff = stats.max_depth_diff.max(depth_diff);
    stats.max_normal_diff = stats.max_normal_diff.max(normal_diff);
}

/// Random pairs moved to within 1e-8 to 1e-3 m of touching (apart or
/// overlapping): the regime where a tolerance inside GJK/EPA or SAT shows.
#[test]
fn engine_detection_agrees_with_parry_near_touching() {
    let mut rng = Rng(0x70C4);
    let mut stats = Agreement::default();
    for i in 0..2000 {
        let (a, b) = (rng.polygon(Hull::AsDrawn), rng.polygon(Hull::AsDrawn));
        let (pa, pb) = (rng.pose(0.5), rng.pose(2.0));
        let (sa, sb) = (Shape::Polygon(a.clone()), Shape::Polygon(b.clone()));
        let p = proximity(&sa, &pa, &sb, &pb);
        // Target signed distance ±10^u m, u ∈ [−8, −3].
        let target = 10f64.powf(rng.range(-8.0, -3.0)) * if i % 2 == 0 { 1.0 } else { -1.0 };
        let shift = (target - p.distance) * p.normal;
        let pb = Isometry2::from_parts((pb.translation.vector + shift).into(), pb.rotation);
        compare_polygon_pair(&a, &pa, &b, &pb, &mut stats);
    }
    println!("near-touching polygon pairs vs parry: {stats:?}");
    // Within 1e-8 m of touching parry's intersection test may err (its
    // GJK tolerance); every disagreement must be one the exact check
    // proves the engine right on.
    assert_eq!(stats.verdict_disagreements, stats.verdict_engine_right);
    assert_eq!(stats.engine_worse, 0);
    assert!(stats.max_depth_diff <= 1e-9 && stats.max_normal_diff <= 1e-9);
    assert!(stats.max_distance_diff <= 1e-9);
}

#[test]
fn engine_detection_agrees_with_parry_on_random_convex_pairs() {
    let mut rng = Rng(0xC0111DE);
    let mut stats = Agreement::default();
    for _ in 0..2000 {
        let (a, b) = (rng.polygon(Hull::AsDrawn), rng.polygon(Hull::AsDrawn));
        let (pa, pb) = (rng.pose(0.5), rng.pose(2.0));
        compare_polygon_pair(&a, &pa, &b, &pb, &mut stats);
    }
    println!("polygon pairs vs parry: {stats:?}");
    let compared = stats.pairs - stats.near_touching;
    println!(
        "verdict agreement {}/{} outside 1e-9 of touching; overlapping {}; max |depth diff| {:e} m, \
         max |normal diff| {:e}, max |distance diff| {:e} m (apart)",
        compared - stats.verdict_disagreements,
        compared,
        stats.overlapping,
        stats.max_depth_diff,
        stats.max_normal_diff,
        stats.max_distance_diff,
    );
    assert_eq!(stats.verdict_disagreements, 0);
    assert_eq!(
        stats.engine_worse, 0,
        "the engine's depth is worse than parry's"
    );
    assert!(stats.max_depth_diff <= 1e-9 && stats.max_normal_diff <= 1e-9);
    assert!(stats.max_distance_diff <= 1e-9);
    // Both verdicts well represented, and every vertex count 3..=12.
    assert!(
        stats.overlapping > 600 && stats.overlapping < 1400,
        "{}",
        stats.overlapping
    );
    assert!(
        stats.vertex_counts[3..].iter().all(|&c| c > 0),
        "{:?}",
        stats.vertex_counts
    );
}

/// Boxes face to face are a degenerate case for GJK/EPA (parallel edges,
/// ties between axes); compare on axis-aligned boxes too.
#[test]
fn engine_detection_agrees_with_parry_on_boxes_resting_on_boxes() {
    let mut rng = Rng(0xB0C5);
    let mut stats = Agreement::default();
    for _ in 0..300 {
        let (w, h) = (rng.range(0.2, 2.0), rng.range(0.2, 2.0));
        let a = ConvexPolygon::rectangle(w, h).unwrap();
        let b = ConvexPolygon::rectangle(rng.range(0.2, 2.0), rng.range(0.2, 2.0)).unwrap();
        let hb = b.vertices()[2].y;
        let pa = Isometry2::identity();
        let pb = Isometry2::translation(
            rng.range(-0.5, 0.5) * w,
            0.5 * h + hb - rng.range(0.001, 0.1),
        );
        compare_polygon_pair(&a, &pa, &b, &pb, &mut stats);
    }
    println!("resting boxes vs parry: {stats:?}");
    assert_eq!(stats.verdict_disagreements, 0);
    assert_eq!(stats.engine_worse, 0);
    assert!(stats.max_depth_diff <= 1e-9 && stats.max_normal_diff <= 1e-9);
}

#[test]
fn engine_circle_queries_agree_with_parry() {
    let mut rng = Rng(0xC1C1E);
    let (mut max_depth, mut max_normal, mut max_distance, mut overlapping) =
        (0.0f64, 0.0f64, 0.0f64, 0);
    for i in 0..2000 {
        let a = if i % 2 == 0 {
            Shape::Polygon(rng.polygon(Hull::AsDrawn))
        } else {
            Shape::Circle(Circle::new(rng.range(0.1, 1.0)).unwrap())
        };
        let b = Shape::Circle(Circle::new(rng.range(0.1, 1.0)).unwrap());
        let (pa, pb) = (rng.pose(0.5), rng.pose(2.0));
        let p = proximity(&a, &pa, &b, &pb);
        if p.distance.abs() <= 1e-9 {
            continue;
        }
        assert_eq!(
            p.distance <= 0.0,
            parry_intersects(&a, &pa, &b, &pb),
            "pair {i}"
        );
        if p.distance > 0.0 {
            max_distance = max_distance.max((p.distance - parry_distance(&a, &pa, &b, &pb)).abs());
        } else {
            overlapping += 1;
            let c = parry_contact(&a, &pa, &b, &pb, 0.0).unwrap();
            max_depth = max_depth.max((-p.distance - c.depth).abs());
            max_normal = max_normal.max((p.normal - c.normal).norm());
        }
    }
    println!(
        "circle pairs vs parry: {overlapping} overlapping, max |depth diff| {max_depth:e}, \
         max |normal diff| {max_normal:e}, max |distance diff| {max_distance:e}"
    );
    assert!(max_depth <= 1e-9 && max_normal <= 1e-9 && max_distance <= 1e-9);
}

fn unit_box() -> Shape {
    Shape::rectangle(1.0, 1.0).unwrap()
}

/// docs/cases.md case III: a 1 m box at x = −3 moving at +1 m/s toward a fixed
/// 1 m box at the origin touches at t = 2.0 s; with ω = 1 rad/s on the
/// moving box, 1.8736370117 s. parry's casts against the engine's two
/// methods.
#[test]
fn time_of_impact_matches_parry_casts() {
    let fixed = ParryMotion {
        pose: Isometry2::identity(),
        linear_velocity: Vector2::zeros(),
        angular_velocity: 0.0,
    };
    for (omega, expected) in [(0.0, 2.0), (1.0, 1.8736370117)] {
        let moving = ParryMotion {
            pose: Isometry2::translation(-3.0, 0.0),
            linear_velocity: Vector2::new(1.0, 0.0),
            angular_velocity: omega,
        };
        let parry = parry_time_of_impact(&unit_box(), &moving, &unit_box(), &fixed, 3.0).unwrap();
        let m = Motion::new(moving.pose, moving.linear_velocity, omega);
        let f = Motion::fixed(fixed.pose);
        let options = ToiOptions::default();
        let bisection = toi_bisection(&unit_box(), &m, &unit_box(), &f, 3.0, &options)
            .unwrap()
            .unwrap();
        let advancement =
            toi_conservative_advancement(&unit_box(), &m, &unit_box(), &f, 3.0, &options)
                .unwrap()
                .unwrap();
        println!(
            "TOI ω = {omega}: parry {} ({:?}) {:.15}, engine bisection {:.15} ({} it.), \
             conservative advancement {:.15} ({} it.), normal parry {:?}",
            parry.method,
            parry.status,
            parry.time,
            bisection.time,
            bisection.iterations,
            advancement.time,
            advancement.iterations,
            parry.normal,
        );
        assert!((parry.time - expected).abs() < 1e-9, "parry {}", parry.time);
        assert!((bisection.time - expected).abs() < 1e-6);
        assert!((advancement.time - expected).abs() < 1e-6);
        assert!((bisection.time - parry.time).abs() < 2.0 * options.tolerance);
        // parry's nonlinear cast ends with status `Failed` here (its last
        // closest-point query finds the shapes closer than f64::EPSILON) and
        // then reports the normal of an earlier iterate: compare normals
        // only for a converged cast.
        if parry.status == ShapeCastStatus::Converged {
            assert!((parry.normal - bisection.manifold.normal).norm() < 1e-9);
        }
    }
}
