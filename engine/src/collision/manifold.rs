//! What the narrow phase reports (seed §7.2, Fig. 7.9): the contact point P
//! and normal N the impulse of seed eq. 7.1–7.16 needs, and the depth by
//! which the bodies overlap.
//!
//! Conventions: the normal is a unit vector from shape A (the first
//! argument of a query) towards shape B; a depth is > 0 when the shapes
//! interpenetrate and < 0 for a gap (reported only within a caller's
//! margin). A contact point is the midpoint between the two surfaces along
//! the normal, so it is the same whichever shape is called A.

use nalgebra::Vector2;

/// One contact point with its normal: the input of an impulse (seed eq.
/// 7.9–7.15 use P for `r_ap`, `r_bp` and N for the impulse direction).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Contact point in the world frame (m), midway between the surfaces.
    pub point: Vector2<f64>,
    /// Unit normal from A to B.
    pub normal: Vector2<f64>,
    /// Penetration depth (m): > 0 when penetrating, < 0 for a gap.
    pub depth: f64,
}

/// A point of a [`Manifold`]; the normal is shared by the manifold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ManifoldPoint {
    /// Contact point in the world frame (m), midway between the surfaces.
    pub point: Vector2<f64>,
    /// Penetration depth along the manifold's normal (m): > 0 when
    /// penetrating, < 0 for a gap.
    pub depth: f64,
}

/// A contact manifold: one normal and one or two points. Two points arise
/// when an edge lies on an edge (a box resting on a box), one otherwise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Manifold {
    /// Unit normal from A to B.
    pub normal: Vector2<f64>,
    points: [ManifoldPoint; 2],
    count: usize,
}

impl Manifold {
    /// A manifold with a single point.
    pub fn one(normal: Vector2<f64>, point: ManifoldPoint) -> Self {
        Self {
            normal,
            points: [point; 2],
            count: 1,
        }
    }

    /// A manifold with two points.
    pub fn two(normal: Vector2<f64>, first: ManifoldPoint, second: ManifoldPoint) -> Self {
        Self {
            normal,
            points: [first, second],
            count: 2,
        }
    }

    /// The one or two points.
    pub fn points(&self) -> &[ManifoldPoint] {
        &self.points[..self.count]
    }

    /// The largest depth of its points (m).
    pub fn max_depth(&self) -> f64 {
        self.points()
            .iter()
            .map(|p| p.depth)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Each point as a [`Contact`] carrying the shared normal.
    pub fn contacts(&self) -> impl Iterator<Item = Contact> + '_ {
        self.points().iter().map(|p| Contact {
            point: p.point,
            normal: self.normal,
            depth: p.depth,
        })
    }

    /// The same manifold seen with A and B swapped: the normal reversed,
    /// points and depths unchanged (they are midway between the surfaces).
    pub fn flipped(&self) -> Self {
        Self {
            normal: -self.normal,
            ..*self
        }
    }
}

/// The closest points of two shapes in the frame of the first (A), as the
/// pair functions written once for both contact models compute them: each
/// model turns it into its own manifold (the exact model's [`Proximity`] in
/// the world frame, the soft step's speculative point midway between the
/// surfaces).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LocalProximity {
    /// Signed distance (m): > 0 apart, < 0 overlapping.
    pub distance: f64,
    /// Unit normal from A to B, A's frame.
    pub normal: Vector2<f64>,
    /// The point of A's surface nearest B (deepest in B when overlapping), A's frame (m).
    pub point_a: Vector2<f64>,
    /// The point of B's surface nearest A, A's frame (m).
    pub point_b: Vector2<f64>,
}

/// The signed distance between two shapes and where it is attained.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Proximity {
    /// Signed distance (m): the Euclidean gap when apart, 0 when touching,
    /// −(penetration depth) when they overlap.
    pub distance: f64,
    /// Unit normal from A to B: the direction of `point_b − point_a` when
    /// apart, the direction of least penetration when overlapping.
    pub normal: Vector2<f64>,
    /// Witness point on A's boundary (world, m).
    pub point_a: Vector2<f64>,
    /// Witness point on B's boundary (world, m); `point_b − point_a =
    /// distance · normal`.
    pub point_b: Vector2<f64>,
}

impl Proximity {
    /// The one-point manifold these witnesses make: the point midway between
    /// the surfaces, depth = −distance.
    pub fn one_point_manifold(&self) -> Manifold {
        Manifold::one(
            self.normal,
            ManifoldPoint {
                point: 0.5 * (self.point_a + self.point_b),
                depth: -self.distance,
            },
        )
    }

    /// The same proximity seen with A and B swapped.
    pub fn flipped(&self) -> Self {
        Self {
            distance: self.distance,
            normal: -self.normal,
            point_a: self.point_b,
            point_b: self.point_a,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn manifold_lists_only_its_points_and_flips_its_normal() {
        let n = Vector2::new(0.0, 1.0);
        let p = ManifoldPoint {
            point: Vector2::new(1.0, 2.0),
            depth: 0.25,
        };
        let q = ManifoldPoint {
            point: Vector2::new(-1.0, 2.0),
            depth: 0.5,
        };
        let one = Manifold::one(n, p);
        assert_eq!(one.points(), &[p]);
        let two = Manifold::two(n, p, q);
        assert_eq!(two.points().len(), 2);
        assert_eq!(two.max_depth(), 0.5);
        let f = two.flipped();
        assert_eq!(f.normal, -n);
        assert_eq!(f.points(), two.points());
        let c: Vec<Contact> = two.contacts().collect();
        assert_eq!(c[1].normal, n);
        assert_eq!(c[1].depth, 0.5);
    }
}
