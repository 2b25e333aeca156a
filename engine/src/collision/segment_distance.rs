//! The closest points of two segments (Ericson, Real-Time Collision
//! Detection §5.1.9): where they lie along each segment and how far apart
//! they are.

use nalgebra::Vector2;

/// The closest points of segments p1–q1 and p2–q2: their parameters in
/// [0, 1] along each and the squared distance between them (m²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SegmentDistance {
    /// Parameter of the closest point along p1–q1 (0 at p1, 1 at q1).
    pub fraction_a: f64,
    /// Parameter of the closest point along p2–q2.
    pub fraction_b: f64,
    /// Squared distance between the closest points (m²).
    pub distance_squared: f64,
}

/// The closest points of segments p1–q1 and p2–q2 (m, any common frame).
/// A segment shorter than machine epsilon is its first point; parallel
/// segments take the first parameter 0 where any would do.
pub(crate) fn segment_distance(
    p1: Vector2<f64>,
    q1: Vector2<f64>,
    p2: Vector2<f64>,
    q2: Vector2<f64>,
) -> SegmentDistance {
    let (d1, d2) = (q1 - p1, q2 - p2);
    let r = p1 - p2;
    let (dd1, dd2, rd1, rd2) = (d1.dot(&d1), d2.dot(&d2), r.dot(&d1), r.dot(&d2));
    let eps_sqr = f64::EPSILON * f64::EPSILON;
    let (f1, f2) = if dd1 < eps_sqr || dd2 < eps_sqr {
        if dd1 >= eps_sqr {
            ((-rd1 / dd1).clamp(0.0, 1.0), 0.0)
        } else if dd2 >= eps_sqr {
            (0.0, (rd2 / dd2).clamp(0.0, 1.0))
        } else {
            (0.0, 0.0)
        }
    } else {
        let d12 = d1.dot(&d2);
        let denominator = dd1 * dd2 - d12 * d12;
        // Parallel segments: any f1 will do; take 0.
        let mut f1 = if denominator != 0.0 {
            ((d12 * rd2 - rd1 * dd2) / denominator).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let mut f2 = (d12 * f1 + rd2) / dd2;
        if f2 < 0.0 {
            f2 = 0.0;
            f1 = (-rd1 / dd1).clamp(0.0, 1.0);
        } else if f2 > 1.0 {
            f2 = 1.0;
            f1 = ((d12 - rd1) / dd1).clamp(0.0, 1.0);
        }
        (f1, f2)
    };
    let c1 = p1 + f1 * d1;
    let c2 = p2 + f2 * d2;
    SegmentDistance {
        fraction_a: f1,
        fraction_b: f2,
        distance_squared: (c1 - c2).norm_squared(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_parallel_and_end_to_end_segments() {
        let v = Vector2::new;
        // Crossing at their middles: distance 0 at fractions ½.
        let x = segment_distance(v(-1.0, 0.0), v(1.0, 0.0), v(0.0, -1.0), v(0.0, 1.0));
        assert_eq!(
            (x.fraction_a, x.fraction_b, x.distance_squared),
            (0.5, 0.5, 0.0)
        );
        // Parallel, 0.5 m apart, overlapping in x: f1 = 0 first, which puts
        // f2 before p2, so f2 = 0 and f1 is p2's foot on the first, ½.
        let p = segment_distance(v(0.0, 0.0), v(1.0, 0.0), v(0.5, 0.5), v(2.0, 0.5));
        assert_eq!(
            (p.fraction_a, p.fraction_b, p.distance_squared),
            (0.5, 0.0, 0.25)
        );
        // End to end along a line, 1 m gap between q1 and p2.
        let e = segment_distance(v(0.0, 0.0), v(1.0, 0.0), v(2.0, 0.0), v(3.0, 0.0));
        assert_eq!(
            (e.fraction_a, e.fraction_b, e.distance_squared),
            (1.0, 0.0, 1.0)
        );
    }
}
