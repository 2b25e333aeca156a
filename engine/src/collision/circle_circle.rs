//! Circle against circle: exact, in closed form.
//!
//! With centres c_a, c_b (m) and radii r_a, r_b (m), the signed distance is
//! `|c_b − c_a| − r_a − r_b` and the normal is `(c_b − c_a)/|c_b − c_a|`.
//! Concentric circles have no preferred direction; the normal is then A's
//! +y (the world's +y for the exact model, which takes the world's axes).
//! A circle's orientation does not matter: its centre is its body's
//! position.

use super::manifold::{LocalProximity, Manifold, Proximity};
use crate::shape::Circle;
use nalgebra::{Isometry2, Vector2};

/// Two circles of radii `ra`, `rb` (m), B's centre at `pb` in A's frame,
/// written once for both contact models: the signed distance |pb| − ra − rb
/// along the line of centres; concentric circles have no line of centres
/// and are pushed along A's y axis. `None` when the distance exceeds
/// `beyond` (m).
pub(crate) fn circle_circle_local(
    ra: f64,
    rb: f64,
    pb: Vector2<f64>,
    beyond: f64,
) -> Option<LocalProximity> {
    let length = pb.norm();
    let distance = length - ra - rb;
    if distance > beyond {
        return None;
    }
    let normal = if length > 0.0 {
        pb / length
    } else {
        Vector2::y()
    };
    Some(LocalProximity {
        distance,
        normal,
        point_a: normal * ra,
        point_b: pb - normal * rb,
    })
}

/// The contact manifold of two circles if their signed distance is ≤
/// `margin` (m): one point midway between the surfaces, depth = −distance
/// (`circle_circle_local` in a frame parallel to the world's at A's
/// centre: a circle has no orientation to matter).
pub fn collide_circle_circle_with_margin(
    a: &Circle,
    pose_a: &Isometry2<f64>,
    b: &Circle,
    pose_b: &Isometry2<f64>,
    margin: f64,
) -> Option<Manifold> {
    let (ca, cb) = (pose_a.translation.vector, pose_b.translation.vector);
    // Never `None` (no distance exceeds an infinite bound); a NaN distance
    // (non-finite input) fails the margin test below: no contact.
    let local = circle_circle_local(a.radius, b.radius, cb - ca, f64::INFINITY)?;
    let normal = local.normal;
    let surfaces = Proximity {
        distance: local.distance,
        normal,
        point_a: ca + a.radius * normal,
        point_b: cb - b.radius * normal,
    };
    (surfaces.distance <= margin).then(|| surfaces.one_point_manifold())
}

/// The contact manifold of two touching or overlapping circles, `None` if
/// they are apart.
pub fn collide_circle_circle(
    a: &Circle,
    pose_a: &Isometry2<f64>,
    b: &Circle,
    pose_b: &Isometry2<f64>,
) -> Option<Manifold> {
    collide_circle_circle_with_margin(a, pose_a, b, pose_b, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64, y: f64) -> Isometry2<f64> {
        Isometry2::new(Vector2::new(x, y), 0.7)
    }

    #[test]
    fn overlapping_circles_3_4_5() {
        // Centres 5 m apart along (3, 4)/5, radii 2 and 4: depth 1.
        let (a, b) = (Circle::new(2.0).unwrap(), Circle::new(4.0).unwrap());
        let m = collide_circle_circle(&a, &at(1.0, 1.0), &b, &at(4.0, 5.0)).unwrap();
        assert!((m.normal - Vector2::new(0.6, 0.8)).norm() < 1e-15);
        let p = m.points()[0];
        assert!((p.depth - 1.0).abs() < 1e-14);
        // Surface of A at (1,1) + 2n = (2.2, 2.6); of B at (4,5) − 4n =
        // (1.6, 1.8); midpoint (1.9, 2.2).
        assert!((p.point - Vector2::new(1.9, 2.2)).norm() < 1e-14);
    }

    #[test]
    fn apart_circles_give_no_contact_but_a_distance() {
        let (a, b) = (Circle::new(1.0).unwrap(), Circle::new(0.5).unwrap());
        assert!(collide_circle_circle(&a, &at(0.0, 0.0), &b, &at(0.0, 2.0)).is_none());
        // Within a 0.6 m margin, the gap is reported as a negative depth.
        let m = collide_circle_circle_with_margin(&a, &at(0.0, 0.0), &b, &at(0.0, 2.0), 0.6);
        assert!((m.unwrap().points()[0].depth + 0.5).abs() < 1e-15);
    }

    #[test]
    fn touching_circles_touch_and_concentric_circles_push_along_y() {
        let (a, b) = (Circle::new(1.0).unwrap(), Circle::new(1.0).unwrap());
        let m = collide_circle_circle(&a, &at(0.0, 0.0), &b, &at(2.0, 0.0)).unwrap();
        assert_eq!(m.points()[0].depth, 0.0);
        let c = collide_circle_circle(&a, &at(1.0, 1.0), &b, &at(1.0, 1.0)).unwrap();
        assert_eq!(c.normal, Vector2::y());
        assert_eq!(c.points()[0].depth, 2.0);
    }

    #[test]
    fn swapping_the_circles_flips_the_normal_only() {
        let (a, b) = (Circle::new(0.3).unwrap(), Circle::new(0.9).unwrap());
        let (pa, pb) = (at(0.1, -0.2), at(0.8, 0.4));
        let ab = collide_circle_circle(&a, &pa, &b, &pb).unwrap();
        let ba = collide_circle_circle(&b, &pb, &a, &pa).unwrap();
        assert!((ab.normal + ba.normal).norm() < 1e-15);
        assert!((ab.points()[0].point - ba.points()[0].point).norm() < 1e-15);
        assert!((ab.points()[0].depth - ba.points()[0].depth).abs() < 1e-15);
    }
}
