//! Signed distance and contact of every pair of convex shape kinds
//! (circle, polygon, box, capsule, segment, rounded polygon) against
//! parry2d-f64 (docs/cases.md "shape_parry"): on random pairs of each of
//! the 21 pairs of kinds, the engine's public
//! [`proximity`](engine::validation::collision::proximity) (touching or
//! not, signed distance: the gap, or minus the penetration depth; normal)
//! against parry's `query::contact` with a prediction distance larger than
//! any gap of the sample (its GJK distance and normal when apart, its EPA
//! depth and normal when overlapping) and its intersection test.
//!
//! **Tolerances**, from parry's termination criteria (parry2d-f64 0.31,
//! `query/gjk/gjk.rs` and `query/epa/epa2.rs`; the engine's answer is
//! exact up to rounding, brute force over the cores or closed forms):
//!
//! - a **length** (distance or depth): parry's GJK stops when its lower
//!   and upper bounds on the distance agree within `eps_tol` = 10 ε
//!   (ε = 2.2e-16) relative to the distance, and its EPA when its
//!   polytope's support gap is below 100 ε; on shapes of metres and
//!   coordinates up to [`SPAN`] m, these are below 1e-13 m. The sample's
//!   rounding is of the same order (a few ulps of coordinates up to 4 m:
//!   4 · 4 m · ε ≈ 3.6e-15 m per operation, a few dozen operations). The
//!   tolerance is [`LENGTH_TOL`] = 1e-9 m, the band of `collision_parry`
//!   (docs/cases.md): four orders above both, so a row fails only on a
//!   real difference, not on rounding, and pairs closer than it to
//!   touching have their verdicts left uncompared (either is right).
//! - a **normal** on flat features (polygon, box and segment cores): a
//!   face normal is computed from the vertices by both, so within the
//!   length tolerance divided by the shortest edge: [`FLAT_NORMAL_TOL`].
//! - a **normal** where a round feature decides (a circle, a capsule's or
//!   a rounded polygon's arc): parry finds it by iterating on the
//!   curve, and a support gap δ on an arc of radius r means a direction
//!   error θ with r (1 − cos θ) = δ, θ = √(2 δ / r); with δ the length
//!   tolerance and r ≥ [`MIN_RADIUS`] that is [`ROUND_NORMAL_TOL`].
//!   Normals of pairs within [`LENGTH_TOL`] of touching are not compared
//!   (there, the normal of a vanishing gap is ill-defined).

use super::{Case, CaseReport, Headline, Snapshots};
use crate::row::{RowKind, RowSink};
use anyhow::Result;
use engine::Shape;
use engine::validation::collision::proximity;
use engine::validation::collision::Proximity;
use nalgebra::{Isometry2, Point2, Vector2};
use references::parry_queries::exact::{Hull, Rng, overlap_along, signed_distance_to_polygon};
use references::parry_queries::{parry_contact, parry_intersects};

/// Signed distance and contact against parry2d on every pair of kinds.
pub const CASE: Case = Case {
    snapshots: Snapshots::HarnessOnly(
        "42 000 pairs; `tests/shape_parry.rs` checks its rows on 40 pairs of each pair of kinds",
    ),
    headline: &[Headline::new("verdict_agreement_rate", "engine_vs_parry2d")],
    ..Case::new(
        "shape_parry",
        "Signed distance and contact of every pair of convex shape kinds against parry2d (2 000 random pairs each)",
        run,
    )
};

/// Random pairs of each pair of kinds in the full run.
pub const PAIRS_PER_KIND_PAIR: usize = 2_000;

/// Length tolerance (m): distances and depths; pairs closer than it to
/// touching have their verdicts and normals left uncompared (module docs).
pub const LENGTH_TOL: f64 = 1e-9;

/// The shortest core edge of the sample (m): a polygon's hull on an
/// annulus of outer radius ≥ 0.2 m can have edges much shorter, so its
/// normals are compared through the length tolerance over this edge; the
/// generator's boxes, segments and capsules have sides ≥ 0.2 m.
pub const MIN_EDGE: f64 = 1e-3;

/// Normal tolerance on flat features: [`LENGTH_TOL`] / [`MIN_EDGE`].
pub const FLAT_NORMAL_TOL: f64 = LENGTH_TOL / MIN_EDGE;

/// The smallest radius of a round feature in the sample (m).
pub const MIN_RADIUS: f64 = 0.02;

/// Normal tolerance where an arc decides: √(2 · [`LENGTH_TOL`] /
/// [`MIN_RADIUS`]) (module docs).
pub fn round_normal_tol() -> f64 {
    (2.0 * LENGTH_TOL / MIN_RADIUS).sqrt()
}

/// See [`round_normal_tol`] (for the docs' links).
pub const ROUND_NORMAL_TOL: &str = "√(2 · 1e-9 m / 0.02 m) ≈ 3.2e-4";

/// Poses: A within 0.5 m of the origin, B within this (m).
pub const SPAN: f64 = 2.0;

/// The prediction distance given to parry's contact (m): more than any gap
/// of the sample (two shapes of at most 1.5 m + 0.3 m extent within
/// [`SPAN`] + 0.5 m), so that parry answers every pair.
const PREDICTION: f64 = 100.0;

/// Disagreements listed in the notes, at most.
const LISTED: usize = 30;

/// The convex shape kinds compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A circle of radius 0.1 to 1 m.
    Circle,
    /// The hull of 3 to 12 random points (outer radius 0.2 to 1.5 m).
    Polygon,
    /// A box of sides 0.2 to 2 m.
    Box,
    /// A capsule: cap centres 0.2 to 2 m apart, radius 0.02 to 0.5 m.
    Capsule,
    /// A segment of length 0.2 to 2 m.
    Segment,
    /// A random polygon (as above, up to 1 m) rounded by 0.02 to 0.3 m.
    RoundedPolygon,
}

/// Every kind, in the order of the rows.
pub const KINDS: [Kind; 6] = [
    Kind::Circle,
    Kind::Polygon,
    Kind::Box,
    Kind::Capsule,
    Kind::Segment,
    Kind::RoundedPolygon,
];

impl Kind {
    /// The kind's name in row ids.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Circle => "circle",
            Kind::Polygon => "polygon",
            Kind::Box => "box",
            Kind::Capsule => "capsule",
            Kind::Segment => "segment",
            Kind::RoundedPolygon => "rounded_polygon",
        }
    }

    /// Whether the shape has a round feature (a circle, a radius > 0).
    fn is_round(self) -> bool {
        matches!(self, Kind::Circle | Kind::Capsule | Kind::RoundedPolygon)
    }

    /// A random shape of this kind, centred on its centre of mass (or on
    /// its middle, for a segment).
    fn random(self, rng: &mut Rng) -> Shape {
        match self {
            Kind::Circle => Shape::circle(rng.range(0.1, 1.0)),
            Kind::Polygon => Ok(Shape::Polygon(rng.polygon(Hull::AsDrawn))),
            Kind::Box => Shape::rectangle(rng.range(0.2, 2.0), rng.range(0.2, 2.0)),
            Kind::Capsule => Shape::capsule(rng.range(0.2, 2.0), rng.range(MIN_RADIUS, 0.5)),
            Kind::Segment => {
                let half = 0.5 * rng.range(0.2, 2.0);
                Shape::segment(Vector2::new(-half, 0.0), Vector2::new(half, 0.0))
            }
            Kind::RoundedPolygon => {
                let core = rng.polygon(Hull::AsDrawn);
                let shrink = 1.0 / core.vertices().iter().map(|v| v.norm()).fold(1.0, f64::max);
                let vertices = core.vertices().iter().map(|v| v * shrink).collect();
                Shape::rounded_polygon(vertices, rng.range(MIN_RADIUS, 0.3))
            }
        }
        .expect("the generator's dimensions are valid")
    }
}

/// What the comparison found on one pair of kinds.
#[derive(Debug, Default, Clone)]
pub struct Agreement {
    /// Pairs generated.
    pub pairs: usize,
    /// Pairs within [`LENGTH_TOL`] of touching (verdicts and normals not
    /// compared).
    pub near_touching: usize,
    /// Overlapping pairs (by the engine).
    pub overlapping: usize,
    /// Pairs whose verdicts (touching or not) differ.
    pub verdict_disagreements: usize,
    /// Largest |engine signed distance − parry's| (m).
    pub max_distance_diff: f64,
    /// Largest |engine normal − parry's| outside [`LENGTH_TOL`] of touching.
    pub max_normal_diff: f64,
    /// Pairs whose distance or normal differ beyond the tolerances.
    pub beyond: usize,
    /// Of those, where the exact check finds the engine right (parry
    /// worse).
    pub parry_worse: usize,
    /// Of those, where the exact check finds the engine wrong.
    pub engine_worse: usize,
    /// Pairs parry gave no contact for (it should, within the
    /// prediction distance).
    pub parry_missing: usize,
    /// Descriptions of the worst disagreements, at most [`LISTED`].
    pub listed: Vec<String>,
}

/// Whether a round feature can decide the pair's normal: either kind is
/// round.
fn round_decides(a: Kind, b: Kind) -> bool {
    a.is_round() || b.is_round()
}

/// The normal tolerance of a pair of kinds (module docs).
pub fn normal_tol(a: Kind, b: Kind) -> f64 {
    if round_decides(a, b) {
        round_normal_tol()
    } else {
        FLAT_NORMAL_TOL
    }
}

/// Rounding allowed in the exact check (m): a few operations on
/// coordinates up to 4 m, 4 m · ε ≈ 1e-15 each; 1e-12 as `collision_parry`.
const EXACT_ROUNDING: f64 = 1e-12;

/// A shape's core (world vertices, m) and radius (m): the representation,
/// not an algorithm under test.
fn world_core(shape: &Shape, pose: &Isometry2<f64>) -> (Vec<Vector2<f64>>, f64) {
    let core = shape.convex_core().expect("convex kinds only");
    let vertices = core
        .vertices
        .iter()
        .map(|v| pose.transform_point(&Point2::from(*v)).coords)
        .collect();
    (vertices, core.radius)
}

/// The signed distance (m) of `p` from the surface of the core inflated by
/// the radius: the distance to the core (a point, a segment, a polygon,
/// negative inside a polygon) less the radius.
fn surface_offset(core: &[Vector2<f64>], radius: f64, p: &Vector2<f64>) -> f64 {
    let to_core = match core.len() {
        1 => (p - core[0]).norm(),
        2 => {
            let (a, e) = (core[0], core[1] - core[0]);
            let t = ((p - a).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
            (p - (a + t * e)).norm()
        }
        _ => signed_distance_to_polygon(core, p),
    };
    to_core - radius
}

/// Overlap (m) of the projections of the two inflated cores on unit axis
/// `n` (from A to B): the shapes' supports, `max_A n·x + r_A − (min_B n·x
/// − r_B)`. The penetration depth is the least overlap over all axes.
fn overlap_of(a: &(Vec<Vector2<f64>>, f64), b: &(Vec<Vector2<f64>>, f64), n: &Vector2<f64>) -> f64 {
    overlap_along(&a.0, &b.0, n) + a.1 + b.1
}

/// Whether the exact check finds the engine's answer right where it
/// differs from parry's beyond the tolerances: apart, the engine's two
/// witness points lie on the two surfaces (so the true distance is at
/// most theirs) and its distance is no larger than parry's; overlapping,
/// the engine's depth is the projections' overlap along its normal and
/// that overlap is no larger than along parry's normal.
fn engine_right(
    a: &Shape,
    pa: &Isometry2<f64>,
    b: &Shape,
    pb: &Isometry2<f64>,
    engine: &Proximity,
    parry_distance: f64,
    parry_normal: &Vector2<f64>,
) -> bool {
    let (ca, cb) = (world_core(a, pa), world_core(b, pb));
    if engine.distance > 0.0 {
        let on_a = surface_offset(&ca.0, ca.1, &engine.point_a).abs() <= EXACT_ROUNDING;
        let on_b = surface_offset(&cb.0, cb.1, &engine.point_b).abs() <= EXACT_ROUNDING;
        let attained = ((engine.point_b - engine.point_a).norm() - engine.distance).abs()
            <= EXACT_ROUNDING;
        on_a && on_b && attained && engine.distance <= parry_distance + EXACT_ROUNDING
    } else {
        let along_engine = overlap_of(&ca, &cb, &engine.normal);
        let along_parry = overlap_of(&ca, &cb, parry_normal);
        (along_engine + engine.distance).abs() <= EXACT_ROUNDING
            && along_engine <= along_parry + EXACT_ROUNDING
    }
}

fn compare(
    ka: Kind,
    a: &Shape,
    pa: &Isometry2<f64>,
    kb: Kind,
    b: &Shape,
    pb: &Isometry2<f64>,
    s: &mut Agreement,
) {
    s.pairs += 1;
    let engine = proximity(a, pa, b, pb);
    let Some(parry) = parry_contact(a, pa, b, pb, PREDICTION) else {
        s.parry_missing += 1;
        return;
    };
    let parry_distance = -parry.depth;
    let dd = (engine.distance - parry_distance).abs();
    s.max_distance_diff = s.max_distance_diff.max(dd);
    if engine.distance < 0.0 {
        s.overlapping += 1;
    }
    if engine.distance.abs() <= LENGTH_TOL {
        s.near_touching += 1;
        return;
    }
    let engine_verdict = engine.distance <= 0.0;
    let parry_verdict = parry_intersects(a, pa, b, pb);
    if engine_verdict != parry_verdict {
        s.verdict_disagreements += 1;
        if s.listed.len() < LISTED {
            s.listed.push(format!(
                "pair {}: verdict: engine {engine_verdict} (distance {:.3e} m), parry {parry_verdict}",
                s.pairs, engine.distance
            ));
        }
    }
    let nd = (engine.normal - parry.normal).norm();
    s.max_normal_diff = s.max_normal_diff.max(nd);
    if dd <= LENGTH_TOL && nd <= normal_tol(ka, kb) {
        return;
    }
    s.beyond += 1;
    let right = engine_right(a, pa, b, pb, &engine, parry_distance, &parry.normal);
    if right {
        s.parry_worse += 1;
    } else {
        s.engine_worse += 1;
    }
    if (!right || s.listed.len() < LISTED / 3) && s.listed.len() < LISTED {
        s.listed.push(format!(
            "pair {}: engine distance {:.15e} m normal ({:.12}, {:.12}); parry {:.15e} m \
             normal ({:.12}, {:.12}): the exact check finds {} right; A at ({:.6}, {:.6}) m, \
             {:.6} rad; B at ({:.6}, {:.6}) m, {:.6} rad",
            s.pairs,
            engine.distance,
            engine.normal.x,
            engine.normal.y,
            parry_distance,
            parry.normal.x,
            parry.normal.y,
            if right { "the engine" } else { "parry" },
            pa.translation.x,
            pa.translation.y,
            pa.rotation.angle(),
            pb.translation.x,
            pb.translation.y,
            pb.rotation.angle(),
        ));
    }
}

/// Compares the engine with parry on `pairs` random pairs of each of the
/// 21 pairs of kinds: (kind A, kind B, what was found), A ≤ B in
/// [`KINDS`]' order.
pub fn agreement(pairs: usize) -> Vec<(Kind, Kind, Agreement)> {
    let mut out = Vec::new();
    for (i, &ka) in KINDS.iter().enumerate() {
        for &kb in &KINDS[i..] {
            // One seed per pair of kinds: a pair's sample does not depend
            // on how many pairs the others drew.
            let mut rng = Rng(0x5A4E_0000 + 16 * out.len() as u64 + 1);
            let mut s = Agreement::default();
            for _ in 0..pairs {
                let (a, b) = (ka.random(&mut rng), kb.random(&mut rng));
                let (pa, pb) = (rng.pose(0.5), rng.pose(SPAN));
                compare(ka, &a, &pa, kb, &b, &pb, &mut s);
            }
            out.push((ka, kb, s));
        }
    }
    out
}

/// The rows and notes of an agreement run.
pub fn report(found: &[(Kind, Kind, Agreement)]) -> CaseReport {
    let mut report = CaseReport::default();
    let mut sink = RowSink {
        case: "shape_parry",
        method: "engine_vs_parry2d",
        dt: 0.0,
        rows: &mut report.rows,
    };
    let (mut compared, mut disagreements) = (0, 0);
    for (ka, kb, s) in found {
        let tag = format!("{}_{}", ka.name(), kb.name());
        compared += s.pairs - s.near_touching;
        disagreements += s.verdict_disagreements;
        sink.within(
            RowKind::Validation,
            &format!("parry_missing_{tag}"),
            s.parry_missing as f64,
            0.0,
            0.0,
            format!(
                "pairs of {} parry gave no contact for within its {PREDICTION} m prediction \
                 distance (more than any gap of the sample): none",
                s.pairs
            ),
        );
        sink.within(
            RowKind::Validation,
            &format!("verdict_disagreements_{tag}"),
            s.verdict_disagreements as f64,
            0.0,
            0.0,
            format!(
                "pairs outside {LENGTH_TOL} m of touching ({} of {}, {} overlapping) where the \
                 engine's touching-or-not and parry's intersection test differ: none",
                s.pairs - s.near_touching,
                s.pairs,
                s.overlapping
            ),
        );
        sink.within(
            RowKind::Validation,
            &format!("pairs_engine_worse_{tag}"),
            s.engine_worse as f64,
            0.0,
            0.0,
            format!(
                "pairs whose signed distance differs from parry's by more than {LENGTH_TOL} m or \
                 whose normal differs by more than {:.1e} ({} of {}) where the exact check \
                 (apart: the engine's witness points on both surfaces, its distance no larger \
                 than parry's; overlapping: the projections' overlap along the engine's normal \
                 equal to its depth and no larger than along parry's) finds the engine wrong: none",
                normal_tol(*ka, *kb),
                s.beyond,
                s.pairs
            ),
        );
        sink.at_least(
            RowKind::Criterion,
            &format!("pairs_parry_worse_{tag}"),
            s.parry_worse as f64,
            0.0,
            0.0,
            format!(
                "of those pairs, where the exact check finds the engine right and parry off: \
                 reported, not judged (largest |distance difference| {:.2e} m, largest |normal \
                 difference| {:.2e} over the sample)",
                s.max_distance_diff, s.max_normal_diff
            ),
        );
        report.notes.push(format!(
            "{} against {}: {} pairs, {} overlapping, {} within {LENGTH_TOL} m of touching; \
             verdict disagreements {}; max |distance diff| {:.2e} m; max |normal diff| {:.2e}; \
             beyond the tolerances {} (engine right on {}, parry right on {}).",
            ka.name(),
            kb.name(),
            s.pairs,
            s.overlapping,
            s.near_touching,
            s.verdict_disagreements,
            s.max_distance_diff,
            s.max_normal_diff,
            s.beyond,
            s.parry_worse,
            s.engine_worse,
        ));
        for l in &s.listed {
            report
                .notes
                .push(format!("{} against {}, {l}", ka.name(), kb.name()));
        }
    }
    sink.at_least(
        RowKind::Validation,
        "verdict_agreement_rate",
        1.0 - disagreements as f64 / compared.max(1) as f64,
        1.0,
        0.0,
        "share of all pairs outside 1e-9 m of touching on which the engine and parry agree \
         whether the shapes touch: all",
    );
    report
}

/// Runs `shape_parry` on [`PAIRS_PER_KIND_PAIR`] pairs of each pair of
/// kinds.
pub fn run() -> Result<CaseReport> {
    Ok(report(&agreement(PAIRS_PER_KIND_PAIR)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact check can fail: an engine answer moved off the truth (a
    /// gap shortened by 1 µm, witnesses unchanged; a depth along a turned
    /// normal) is judged wrong against parry's.
    #[test]
    fn the_exact_check_refuses_a_wrong_answer() {
        let a = Shape::capsule(1.0, 0.25).unwrap();
        let b = Shape::rectangle(1.0, 1.0).unwrap();
        let (pa, pb) = (Isometry2::identity(), Isometry2::translation(0.0, 1.5));
        let truth = proximity(&a, &pa, &b, &pb);
        // The capsule's top at y = 0.25, the box's bottom at y = 1.
        assert!((truth.distance - 0.75).abs() < 1e-15);
        assert!(engine_right(&a, &pa, &b, &pb, &truth, 0.75, &truth.normal));
        let short = Proximity {
            distance: truth.distance - 1e-6,
            ..truth
        };
        assert!(!engine_right(&a, &pa, &b, &pb, &short, 0.75, &truth.normal));
        let pb = Isometry2::translation(0.0, 0.7);
        let truth = proximity(&a, &pa, &b, &pb);
        assert!(truth.distance < 0.0);
        let turned = Proximity {
            normal: Vector2::new(0.1, 1.0).normalize(),
            ..truth
        };
        assert!(!engine_right(&a, &pa, &b, &pb, &turned, truth.distance, &truth.normal));
        assert!(engine_right(&a, &pa, &b, &pb, &truth, truth.distance, &turned.normal));
    }
}
