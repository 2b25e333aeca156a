//! `shape_mass`: the area, centre of mass and polar second moment of area
//! the engine computes for each kind of shape, against closed forms.
//!
//! The circle and the box against their textbook formulas; a convex
//! polygon and the concave outlines (an L, a five-pointed star, random
//! simple polygons) against the shoelace formulas of the *undecomposed*
//! outline, written here apart from the engine's code (the engine sums
//! its convex parts, each about its own centroid by fanned triangles, then
//! the parallel axis theorem; these formulas take the outline's edges
//! about the origin in one pass); a compound of a disc and a turned box
//! against the parallel axis theorem on the two closed forms; a capsule and
//! a rounded box against their textbook decompositions into rectangles,
//! half or quarter discs and the parallel axis theorem (the engine sums
//! its core, one rectangle per edge and one sector per vertex instead).
//!
//! Tolerances are worst-case round-off bounds, not fitted: each side sums
//! at most m terms of a few rounded operations, so its error is at most
//! γ_(m+6) Σ|terms| (Higham, *Accuracy and Stability of Numerical
//! Algorithms*, §4.2, recursive summation), γ_k = k u/(1 − k u) ≤ k ε/2 for
//! the unit round-off u = ε/2. Both sides together: (m + 8) ε Σ|terms|.
//! With R the largest distance of a vertex from the origin and A the
//! area, Σ|terms| ≤ m R² for the area, 17 m R³ / A for a coordinate of the
//! centroid (the engine's fan terms are at most 16 R³/3 per triangle, and
//! the division by A carries the area's error times |c| ≤ R), and 5 m R⁴
//! for the polar moment (terms about the centroid at most 4 R⁴, plus the
//! parallel-axis term A R²). m counts the outline's vertices plus two for
//! each diagonal the cut adds. A rounded shape's engine side sums a
//! rectangle and a sector per core vertex besides its core (each term at
//! most 5 R⁴ with R the farthest boundary point, through libm's sin, cos,
//! atan2 within an ulp): m = 2 n + 4 for a core of n vertices.

use super::{Case, CaseReport};
use crate::row::{RowKind, RowSink};
use anyhow::{Context, Result, ensure};
use engine::shape::decompose::convex_parts;
use engine::{Compound, CompoundPart, ConvexPolygon, Shape};
use nalgebra::Vector2;
use references::parry_queries::exact::Rng;
use std::f64::consts::PI;

/// Mass properties of every shape kind against closed forms.
pub const CASE: Case = Case::new(
    "shape_mass",
    "Area, centre of mass and polar inertia of every shape kind, concave polygons cut into convex parts, against closed forms",
    run,
);

/// Area (m²), centroid (m) and polar second moment of area about the
/// centroid (m⁴): times a density, the mass, centre of mass and moment of
/// inertia.
#[derive(Debug, Clone, Copy)]
struct MassProperties {
    area: f64,
    centroid: Vector2<f64>,
    polar_moment: f64,
}

/// Round-off scales of one comparison: how many terms each side sums and
/// the size of the shape.
#[derive(Debug, Clone, Copy)]
struct Scale {
    /// Terms summed by the side that sums more.
    terms: usize,
    /// Largest distance of the shape's boundary from the origin (m).
    radius: f64,
}

/// The shoelace formulas of a simple polygon listed counter-clockwise:
/// A = ½ Σ cᵢ, C = Σ (pᵢ + pᵢ₊₁) cᵢ / (6A), J_O = Σ cᵢ (xᵢ² + xᵢxᵢ₊₁ +
/// xᵢ₊₁² + yᵢ² + yᵢyᵢ₊₁ + yᵢ₊₁²) / 12 about the origin, then J = J_O − A|C|²
/// (cᵢ = xᵢ yᵢ₊₁ − xᵢ₊₁ yᵢ).
fn shoelace(outline: &[Vector2<f64>]) -> MassProperties {
    let n = outline.len();
    let (mut twice_area, mut first, mut twelve_j) = (0.0, Vector2::zeros(), 0.0);
    for i in 0..n {
        let (p, q) = (outline[i], outline[(i + 1) % n]);
        let c = p.x * q.y - q.x * p.y;
        twice_area += c;
        first += (p + q) * c;
        twelve_j += c * (p.x * p.x + p.x * q.x + q.x * q.x + p.y * p.y + p.y * q.y + q.y * q.y);
    }
    let area = twice_area / 2.0;
    let centroid = first / (3.0 * twice_area);
    MassProperties {
        area,
        centroid,
        polar_moment: twelve_j / 12.0 - area * centroid.norm_squared(),
    }
}

/// What the engine computes for `shape`, in the frame it was given in.
fn engine_properties(shape: &Shape) -> MassProperties {
    let area = shape.area();
    let centroid = match shape {
        Shape::Polygon(p) => p.centroid(),
        Shape::Compound(c) => c.centroid(),
        Shape::Circle(_) | Shape::Chain(_) => Vector2::zeros(),
        Shape::Rounded(r) => r.centroid(),
    };
    MassProperties {
        area,
        centroid,
        polar_moment: area * shape.inertia_per_unit_mass(),
    }
}

/// Rows of one shape: area, centroid x and y, polar moment.
fn compare(
    sink: &mut RowSink,
    name: &str,
    engine: MassProperties,
    exact: MassProperties,
    scale: Scale,
    what: &str,
) {
    let (m, r) = (scale.terms as f64, scale.radius);
    let gamma = (m + 8.0) * f64::EPSILON;
    let reason = |quantity: &str| {
        format!(
            "{what}; round-off bound (m + 8) ε Σ|terms| with m = {} terms, R = {} m: {quantity}",
            scale.terms,
            crate::simulate::fmt_short(r)
        )
    };
    sink.within(
        RowKind::Validation,
        &format!("{name}.area"),
        engine.area,
        exact.area,
        gamma * m * r * r,
        reason("Σ|terms| ≤ m R²"),
    );
    let centroid_tol = gamma * 17.0 * m * r.powi(3) / exact.area;
    for (axis, e, x) in [
        ("x", engine.centroid.x, exact.centroid.x),
        ("y", engine.centroid.y, exact.centroid.y),
    ] {
        sink.within(
            RowKind::Validation,
            &format!("{name}.centroid_{axis}"),
            e,
            x,
            centroid_tol,
            reason("Σ|terms| ≤ 17 m R³ / A"),
        );
    }
    sink.within(
        RowKind::Validation,
        &format!("{name}.polar_moment"),
        engine.polar_moment,
        exact.polar_moment,
        gamma * 5.0 * m * r.powi(4),
        reason("Σ|terms| ≤ 5 m R⁴"),
    );
}

fn points(xy: &[[f64; 2]]) -> Vec<Vector2<f64>> {
    xy.iter().map(|p| Vector2::new(p[0], p[1])).collect()
}

/// A star of `tips` points, radii `outer` and `inner` (m), about `centre`.
fn star(tips: usize, outer: f64, inner: f64, centre: Vector2<f64>) -> Vec<Vector2<f64>> {
    (0..2 * tips)
        .map(|k| {
            let r = if k % 2 == 0 { outer } else { inner };
            let a = PI / 2.0 + PI * k as f64 / tips as f64;
            centre + Vector2::new(r * a.cos(), r * a.sin())
        })
        .collect()
}

/// A random simple polygon of `n` vertices about `centre`: angles drawn
/// uniformly and sorted, each with a radius drawn in [0.2, 1.5] m, so the
/// outline is star-shaped about the centre (hence simple) and concave
/// wherever a radius dips.
fn random_outline(rng: &mut Rng, n: usize, centre: Vector2<f64>) -> Vec<Vector2<f64>> {
    let mut angles: Vec<f64> = (0..n).map(|_| rng.range(0.0, 2.0 * PI)).collect();
    angles.sort_by(f64::total_cmp);
    angles
        .iter()
        .map(|a| centre + rng.range(0.2, 1.5) * Vector2::new(a.cos(), a.sin()))
        .collect()
}

fn radius_of(outline: &[Vector2<f64>]) -> f64 {
    outline.iter().map(|p| p.norm()).fold(0.0, f64::max)
}

/// The rows of one outline cut by the engine, against its shoelace
/// formulas; returns the number of parts.
fn outline_rows(sink: &mut RowSink, name: &str, outline: &[Vector2<f64>]) -> Result<usize> {
    let parts = convex_parts(outline).with_context(|| format!("cutting {name}"))?.len();
    let shape = Shape::simple_polygon(outline).with_context(|| format!("shape of {name}"))?;
    let scale = Scale {
        terms: outline.len() + 2 * (parts - 1) + 2,
        radius: radius_of(outline),
    };
    compare(
        sink,
        name,
        engine_properties(&shape),
        shoelace(outline),
        scale,
        &format!(
            "{} vertices cut into {parts} convex parts, against the shoelace formulas of the whole outline",
            outline.len()
        ),
    );
    Ok(parts)
}

/// Runs the case.
pub fn run() -> Result<CaseReport> {
    let mut report = CaseReport::default();
    let mut sink = RowSink {
        case: "shape_mass",
        method: "geometry",
        dt: 0.0,
        rows: &mut report.rows,
    };

    // Circle of radius r: A = π r², centroid at its centre, J = π r⁴ / 2.
    let r = 0.7;
    let circle = Shape::circle(r)?;
    compare(
        &mut sink,
        "circle",
        engine_properties(&circle),
        MassProperties {
            area: PI * r * r,
            centroid: Vector2::zeros(),
            polar_moment: PI * r.powi(4) / 2.0,
        },
        Scale {
            terms: 1,
            radius: r,
        },
        "π r², 0, π r⁴/2",
    );

    // Box b × h: A = b h, J = b h (b² + h²) / 12.
    let (b, h) = (2.0, 0.5);
    compare(
        &mut sink,
        "box",
        engine_properties(&Shape::rectangle(b, h)?),
        MassProperties {
            area: b * h,
            centroid: Vector2::zeros(),
            polar_moment: b * h * (b * b + h * h) / 12.0,
        },
        Scale {
            terms: 4,
            radius: 0.5 * (b * b + h * h).sqrt(),
        },
        "b h, 0, b h (b² + h²)/12",
    );

    // A convex pentagon off the origin.
    let pentagon = points(&[[0.2, -0.3], [1.4, 0.1], [1.6, 1.0], [0.7, 1.5], [-0.1, 0.6]]);
    compare(
        &mut sink,
        "convex_polygon",
        engine_properties(&Shape::polygon(pentagon.clone())?),
        shoelace(&pentagon),
        Scale {
            terms: pentagon.len() + 2,
            radius: radius_of(&pentagon),
        },
        "shoelace formulas",
    );

    // A compound: a disc at (−0.8, 0.3) and a 1 × 0.4 box at (0.6, −0.2)
    // turned by 0.7 rad. Parallel axis theorem on the closed forms.
    let (rd, disc_at) = (0.35, Vector2::new(-0.8, 0.3));
    let (bw, bh, box_at) = (1.0, 0.4, Vector2::new(0.6, -0.2));
    let compound = Shape::Compound(Compound::new(vec![
        CompoundPart::new(disc_at, 0.0, Shape::circle(rd)?),
        CompoundPart::new(box_at, 0.7, Shape::rectangle(bw, bh)?),
    ])?);
    let (a1, a2) = (PI * rd * rd, bw * bh);
    let centre = (a1 * disc_at + a2 * box_at) / (a1 + a2);
    let j = a1 * rd * rd / 2.0
        + a1 * (disc_at - centre).norm_squared()
        + a2 * (bw * bw + bh * bh) / 12.0
        + a2 * (box_at - centre).norm_squared();
    compare(
        &mut sink,
        "compound",
        engine_properties(&compound),
        MassProperties {
            area: a1 + a2,
            centroid: centre,
            polar_moment: j,
        },
        Scale {
            terms: 8,
            radius: disc_at.norm() + rd,
        },
        "disc and turned box: the parallel axis theorem on π r², b h and their moments",
    );

    // Capsule, cap centres L apart, radius r: the rectangle L × 2r plus two
    // half discs. A half disc (area πr²/2) has its centroid 4r/(3π) from
    // its flat side and the moment πr⁴/4 about the flat side's midpoint,
    // so πr⁴/4 − (πr²/2)(4r/3π)² about its centroid; moved to the
    // capsule's centre, (L/2 + 4r/3π) away (parallel axis theorem).
    let (length, r) = (1.5, 0.4);
    let half_disc = PI * r * r / 2.0;
    let bulge = 4.0 * r / (3.0 * PI);
    let own = PI * r.powi(4) / 4.0 - half_disc * bulge * bulge;
    let rect = 2.0 * r * length;
    compare(
        &mut sink,
        "capsule",
        engine_properties(&Shape::capsule(length, r)?),
        MassProperties {
            area: rect + 2.0 * half_disc,
            centroid: Vector2::zeros(),
            polar_moment: rect * (length * length + 4.0 * r * r) / 12.0
                + 2.0 * (own + half_disc * (length / 2.0 + bulge).powi(2)),
        },
        Scale {
            terms: 2 * 2 + 4,
            radius: length / 2.0 + r,
        },
        "rectangle L × 2r and two half discs by the parallel axis theorem",
    );

    // Rounded box, core w × h, radius r: the rectangle (w + 2r) × h, two
    // rectangles w × r above and below, and four quarter discs (area πr²/4,
    // centroid 4r/(3π) from both straight sides, moment πr⁴/8 about the
    // corner, so πr⁴/8 − (πr²/4)·2(4r/3π)² about its centroid) at the
    // corners (±w/2, ±h/2).
    let (w, h, r) = (1.2, 0.6, 0.15);
    let middle = (w + 2.0 * r) * h;
    let band = w * r;
    let quarter = PI * r * r / 4.0;
    let bulge = 4.0 * r / (3.0 * PI);
    let quarter_own = PI * r.powi(4) / 8.0 - quarter * 2.0 * bulge * bulge;
    let quarter_at = Vector2::new(w / 2.0 + bulge, h / 2.0 + bulge);
    compare(
        &mut sink,
        "rounded_box",
        engine_properties(&Shape::rounded_box(w, h, r)?),
        MassProperties {
            area: middle + 2.0 * band + 4.0 * quarter,
            centroid: Vector2::zeros(),
            polar_moment: middle * ((w + 2.0 * r).powi(2) + h * h) / 12.0
                + 2.0 * (band * (w * w + r * r) / 12.0 + band * (h / 2.0 + r / 2.0).powi(2))
                + 4.0 * (quarter_own + quarter * quarter_at.norm_squared()),
        },
        Scale {
            terms: 2 * 4 + 4,
            radius: 0.5 * (w * w + h * h).sqrt() + r,
        },
        "rectangles and four quarter discs by the parallel axis theorem",
    );

    // Concave outlines, cut into convex parts.
    let l = points(&[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]);
    let l_parts = outline_rows(&mut sink, "l_shape", &l)?;
    ensure!(l_parts == 2, "an L is cut into 2 convex parts, got {l_parts}");
    outline_rows(&mut sink, "star", &star(5, 1.0, 0.4, Vector2::new(0.3, -0.2)))?;
    let mut rng = Rng(0x5eed_0019);
    for n in [12, 50, 200] {
        let outline = random_outline(&mut rng, n, Vector2::new(0.4, 0.25));
        outline_rows(&mut sink, &format!("random_{n}"), &outline)?;
    }

    // The same L as a polygon part of a compound, beside a disc: the
    // compound's properties are those of the L and the disc together.
    let disc_at = Vector2::new(3.0, 0.5);
    let mut parts: Vec<CompoundPart> = convex_parts(&l)?
        .into_iter()
        .map(|p: ConvexPolygon| CompoundPart::new(Vector2::zeros(), 0.0, Shape::Polygon(p)))
        .collect();
    parts.push(CompoundPart::new(disc_at, 0.0, Shape::circle(0.5)?));
    let with_disc = Shape::Compound(Compound::new(parts)?);
    let l_exact = shoelace(&l);
    let a_disc = PI * 0.25;
    let centre = (l_exact.area * l_exact.centroid + a_disc * disc_at) / (l_exact.area + a_disc);
    compare(
        &mut sink,
        "compound_with_l",
        engine_properties(&with_disc),
        MassProperties {
            area: l_exact.area + a_disc,
            centroid: centre,
            polar_moment: l_exact.polar_moment
                + l_exact.area * (l_exact.centroid - centre).norm_squared()
                + a_disc * 0.125
                + a_disc * (disc_at - centre).norm_squared(),
        },
        Scale {
            terms: l.len() + 2 + 4,
            radius: disc_at.norm() + 0.5,
        },
        "an L (shoelace) and a disc (π r², π r⁴/2) joined by the parallel axis theorem",
    );
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shoelace_formulas_give_a_unit_square() {
        // Unit square at [1, 2]²: A = 1, C = (1.5, 1.5), J = 1/6 exactly.
        let p = shoelace(&points(&[[1.0, 1.0], [2.0, 1.0], [2.0, 2.0], [1.0, 2.0]]));
        assert_eq!(p.area, 1.0);
        assert_eq!(p.centroid, Vector2::new(1.5, 1.5));
        assert!((p.polar_moment - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn a_missing_part_would_fail_the_rows() {
        // Half the L dropped: the area row must fail, so the rows can fail.
        let l = points(&[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]]);
        let first = convex_parts(&l).unwrap().remove(0);
        let mut rows = Vec::new();
        let mut sink = RowSink {
            case: "shape_mass",
            method: "geometry",
            dt: 0.0,
            rows: &mut rows,
        };
        compare(
            &mut sink,
            "l_half",
            engine_properties(&Shape::Polygon(first)),
            shoelace(&l),
            Scale {
                terms: 10,
                radius: radius_of(&l),
            },
            "test",
        );
        assert!(!rows[0].pass);
    }
}
