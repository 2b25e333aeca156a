//! Persistent contacts: a resting pair's contact followed through a piece of
//! step by the features it was found with (seed §7.1 after Baraff: the set
//! of contacts is fixed between events, and their forces are computed from
//! the state at every evaluation of the right-hand side).
//!
//! At a settle the narrow phase gives each resting pair a manifold and the
//! features behind it ([`ContactFeatures`]: incident points against a
//! reference face, or two round features), fixed in the bodies' frames.
//! During the piece every evaluation re-measures those features at the
//! current poses ([`follow`]), whatever the distance: an integrator stage
//! whose extrapolated pose lifts a pivoting corner by more than ε keeps its
//! contact force (asking the narrow phase with a margin of ε there dropped
//! the force for that stage, and the body sank by O(h²) every step, which
//! cut the step into thousands of pieces). A point that really separates
//! gets no force (the complementarity problem gives it λ = 0), and the next
//! settle drops it.
//!
//! **The separation's second derivative.** A contact row holds the relative
//! normal acceleration of the contact at zero or above. For two material
//! points that is `n · (a_B(P) − a_A(P))` (module `rows`), which is exact
//! only for a vertex on a face that does not turn. In general, with d the
//! separation, n the normal from A to B, v_rel = v_B(Q_B) − v_A(Q_A) the
//! relative velocity of the feature points Q (material points), ω_R the
//! angular velocity of the body holding the reference face and ρ the
//! incident shape's radius:
//!
//! ```text
//! face:  d'' = n·(a_B(Q_B) − a_A(Q_A)) + 2 ω_R (n⊥ · v_rel) − ω_R² (d + ρ)
//! round: d'' = n·(a_B(Q_B) − a_A(Q_A)) + (|v_rel|² − (n·v_rel)²) / L
//! ```
//!
//! (n⊥ = n turned by +90°; L the distance between the round features'
//! points; Q is a circle's centre, the incident point, or the reference
//! body's material point under it). The first line is d = n·(Q_inc − X) − ρ
//! differentiated twice with n turning at ω_R; the second d = L − ρ_A − ρ_B.
//! A circle rolling on the ground is the case that matters: its material
//! point at the contact accelerates towards the centre by ω² r, while the
//! separation's d'' is the centre's normal acceleration; a row at the
//! material point pulled a rolling disc into the ground at ω² r (770 m/s²
//! at 39 rad/s and r = 0.5 m). [`FollowedPoint::correction`] is the
//! difference, added to the row's material-point acceleration.

use super::rows::{BodyView, perp};
use crate::collision::features::ContactFeatures;
use crate::collision::{Manifold, ManifoldPoint};
use nalgebra::{Isometry2, Point2, Vector2};

/// One point of a followed contact at the current poses, with what the
/// separation's second derivative needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FollowedPoint {
    /// The feature point on A (world, m): a vertex, a circle's centre, or
    /// A's material point under B's incident point.
    pub on_a: Vector2<f64>,
    /// The same on B.
    pub on_b: Vector2<f64>,
    /// The separation d (m): > 0 for a gap.
    pub separation: f64,
    /// The geometry's own term of d''.
    pub geometry: Geometry,
}

/// Which formula of the module docs a point follows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Geometry {
    /// Against a reference face on A (`true`) or B, incident radius ρ (m).
    Face { reference_is_a: bool, radius: f64 },
    /// Two round features `length` (m) apart.
    Round { length: f64 },
}

impl FollowedPoint {
    /// What `n · (a_B(P) − a_A(P))` at the manifold point `p` misses of the
    /// separation's second derivative (m/s²), given the bodies' velocities
    /// (`views`, indexed by body) for the pair `(a, b)` and the normal `n`
    /// from A to B.
    pub(crate) fn correction(
        &self,
        views: &[BodyView],
        (a, b): (usize, usize),
        p: Vector2<f64>,
        n: Vector2<f64>,
    ) -> f64 {
        let (va, vb) = (&views[a], &views[b]);
        // The centripetal terms at the feature points instead of at P.
        let mut c = va.omega * va.omega * n.dot(&(self.on_a - p))
            - vb.omega * vb.omega * n.dot(&(self.on_b - p));
        let v_rel =
            vb.point_velocity(self.on_b - vb.position) - va.point_velocity(self.on_a - va.position);
        match self.geometry {
            Geometry::Face {
                reference_is_a,
                radius,
            } => {
                let omega = if reference_is_a { va.omega } else { vb.omega };
                c += 2.0 * omega * perp(n).dot(&v_rel) - omega * omega * (self.separation + radius);
            }
            Geometry::Round { length } => {
                if length > 0.0 {
                    let normal = n.dot(&v_rel);
                    c += (v_rel.norm_squared() - normal * normal) / length;
                }
            }
        }
        c
    }
}

/// The manifold of `features` at the poses `pose_a`, `pose_b` (A's and B's,
/// world), whatever the separation, and each point's followed geometry.
pub(crate) fn follow(
    features: &ContactFeatures,
    pose_a: &Isometry2<f64>,
    pose_b: &Isometry2<f64>,
) -> (Manifold, [FollowedPoint; 2]) {
    let world =
        |pose: &Isometry2<f64>, p: Vector2<f64>| pose.transform_point(&Point2::from(p)).coords;
    match *features {
        ContactFeatures::Face {
            reference_is_a,
            normal,
            face_point,
            points,
            count,
            radius,
            ..
        } => {
            let (reference, incident) = if reference_is_a {
                (pose_a, pose_b)
            } else {
                (pose_b, pose_a)
            };
            let n_face = reference.rotation * normal;
            let on_face = world(reference, face_point);
            let n = if reference_is_a { n_face } else { -n_face };
            let point = |local: Vector2<f64>| {
                let q = world(incident, local);
                let d = n_face.dot(&(q - on_face)) - radius;
                let under = q - (d + radius) * n_face;
                let (on_a, on_b) = if reference_is_a {
                    (under, q)
                } else {
                    (q, under)
                };
                (
                    ManifoldPoint {
                        point: q - (radius + 0.5 * d) * n_face,
                        depth: -d,
                    },
                    FollowedPoint {
                        on_a,
                        on_b,
                        separation: d,
                        geometry: Geometry::Face {
                            reference_is_a,
                            radius,
                        },
                    },
                )
            };
            let (m0, f0) = point(points[0]);
            if count == 2 {
                let (m1, f1) = point(points[1]);
                (Manifold::two(n, m0, m1), [f0, f1])
            } else {
                (Manifold::one(n, m0), [f0, f0])
            }
        }
        ContactFeatures::Round {
            point_a,
            radius_a,
            point_b,
            radius_b,
            ..
        } => {
            let (qa, qb) = (world(pose_a, point_a), world(pose_b, point_b));
            let between = qb - qa;
            let length = between.norm();
            let n = if length > 0.0 {
                between / length
            } else {
                Vector2::x()
            };
            let d = length - radius_a - radius_b;
            let f = FollowedPoint {
                on_a: qa,
                on_b: qb,
                separation: d,
                geometry: Geometry::Round { length },
            };
            (
                Manifold::one(
                    n,
                    ManifoldPoint {
                        point: qa + (radius_a + 0.5 * d) * n,
                        depth: -d,
                    },
                ),
                [f, f],
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision::narrow_phase::collide_with_features;
    use crate::collision::{collide, proximity};
    use crate::shape::{Circle, Shape};

    /// The followed manifold at the poses it was found at is the narrow
    /// phase's own.
    #[test]
    fn followed_at_the_same_poses_is_the_narrow_phase_manifold() {
        let square = Shape::rectangle(1.0, 1.0).unwrap();
        let ground = Shape::rectangle(10.0, 1.0).unwrap();
        let ball = Shape::Circle(Circle::new(0.5).unwrap());
        // A plank of core 10 × 0.5 rounded by 0.25 (its top surface 0.5
        // above its centre), a capsule of cap radius 0.3.
        let plank = Shape::rounded_box(10.0, 0.5, 0.25).unwrap();
        let pill = Shape::capsule(1.0, 0.3).unwrap();
        // The capsule's first cap centre 0.3 − 1e-12 from the square's
        // corner (0.5, 0.5), along a direction 0.1 rad past the diagonal,
        // the capsule pointing away along it.
        let diagonal = Vector2::new(
            (std::f64::consts::FRAC_PI_4 + 0.1).cos(),
            (std::f64::consts::FRAC_PI_4 + 0.1).sin(),
        );
        let cap = Vector2::new(0.5, 0.5) + (0.3 - 1e-12) * diagonal;
        let cases = [
            (
                &ground,
                Isometry2::new(Vector2::new(0.0, -0.5), 0.0),
                &square,
                Isometry2::new(Vector2::new(0.3, 0.5 - 1e-12), 0.0),
            ),
            (
                &square,
                Isometry2::new(Vector2::new(0.3, 0.5), 0.0),
                &ground,
                Isometry2::new(Vector2::new(0.0, -0.5 + 1e-12), 0.0),
            ),
            (
                &ground,
                Isometry2::new(Vector2::new(0.0, -0.5), 0.1),
                &ball,
                Isometry2::new(Vector2::new(0.2, 0.4), 0.7),
            ),
            (
                &ball,
                Isometry2::new(Vector2::new(0.2, 0.4), 0.7),
                &ground,
                Isometry2::new(Vector2::new(0.0, -0.5), 0.1),
            ),
            (
                &square,
                Isometry2::new(Vector2::zeros(), 0.0),
                &ball,
                Isometry2::new(Vector2::new(0.85, 0.85), 0.0),
            ),
            (
                &ball,
                Isometry2::new(Vector2::zeros(), 0.0),
                &ball,
                Isometry2::new(Vector2::new(0.6, 0.8), 0.0),
            ),
            (
                &square,
                Isometry2::new(Vector2::zeros(), 0.0),
                &square,
                Isometry2::new(Vector2::new(0.4, 0.99), 0.05),
            ),
            // Rounded shapes: a capsule lying on a rounded plank (a face of
            // a rounded reference), on a box (the capsule as A, the box's
            // face the reference), its cap on a box's corner (a vertex
            // pair), a disc at a rounded box's corner and on a capsule.
            (
                &plank,
                Isometry2::new(Vector2::new(0.0, -0.5), 0.0),
                &pill,
                Isometry2::new(Vector2::new(0.3, 0.3 - 1e-12), 0.0),
            ),
            (
                &pill,
                Isometry2::new(Vector2::new(0.3, 0.3 - 1e-12), 0.0),
                &square,
                Isometry2::new(Vector2::new(0.2, -0.5), 0.0),
            ),
            (
                &square,
                Isometry2::new(Vector2::zeros(), 0.0),
                &pill,
                Isometry2::new(cap + 0.5 * diagonal, std::f64::consts::FRAC_PI_4 + 0.1),
            ),
            (
                &plank,
                Isometry2::new(Vector2::new(0.0, -0.5), 0.0),
                &ball,
                Isometry2::new(Vector2::new(5.0, -0.75) + (0.75 - 1e-12) * diagonal, 0.0),
            ),
            (
                &ball,
                Isometry2::new(Vector2::new(0.2, 0.8 - 1e-12), 0.0),
                &pill,
                Isometry2::new(Vector2::zeros(), 0.0),
            ),
        ];
        for (sa, pa, sb, pb) in cases {
            let (m, features) = collide_with_features(sa, &pa, sb, &pb, 1e-6).expect("touching");
            assert_eq!(Some(m), collide(sa, &pa, sb, &pb, 1e-6));
            let (followed, _) = follow(&features, &pa, &pb);
            assert!(
                (followed.normal - m.normal).norm() < 1e-15,
                "{followed:?} {m:?}"
            );
            assert_eq!(followed.points().len(), m.points().len());
            for (f, e) in followed.points().iter().zip(m.points()) {
                assert!((f.point - e.point).norm() < 1e-14, "{f:?} {e:?}");
                assert!((f.depth - e.depth).abs() < 1e-14, "{f:?} {e:?}");
            }
            let d = proximity(sa, &pa, sb, &pb).distance;
            assert!((-followed.max_depth() - d).abs() < 1e-14 || m.points().len() == 2);
        }
    }

    /// The separation of followed features, differentiated twice by finite
    /// differences along a motion with constant accelerations, against the
    /// material-point acceleration plus the correction.
    #[test]
    fn the_correction_gives_the_second_derivative_of_the_separation() {
        let square = Shape::rectangle(1.0, 1.0).unwrap();
        let ground = Shape::rectangle(10.0, 1.0).unwrap();
        let ball = Shape::Circle(Circle::new(0.5).unwrap());
        // (shape, pose, velocity, omega, acceleration, alpha) per body.
        type Motion = (Vector2<f64>, f64, Vector2<f64>, f64, Vector2<f64>, f64);
        let plank = Shape::rounded_box(10.0, 0.5, 0.25).unwrap();
        let pill = Shape::capsule(1.0, 0.25).unwrap();
        // The direction of the box's corner (0.5, 0.5) at its angle 0.2.
        let corner = std::f64::consts::FRAC_PI_4 + 0.2;
        let cases: [(&Shape, Motion, &Shape, Motion); 7] = [
            // A tilted capsule spinning on a turning rounded plank: its
            // core's end against the plank's core face moved out by 0.25.
            (
                &plank,
                (
                    Vector2::new(0.0, -0.5),
                    -0.05,
                    Vector2::new(0.0, 0.3),
                    -1.5,
                    Vector2::new(0.2, 0.1),
                    0.3,
                ),
                &pill,
                (
                    Vector2::new(0.2, 0.42),
                    0.3,
                    Vector2::new(1.0, 0.5),
                    4.0,
                    Vector2::new(0.1, -3.0),
                    -2.0,
                ),
            ),
            // A capsule's cap at a turning box's corner: a vertex pair.
            (
                &square,
                (
                    Vector2::zeros(),
                    0.2,
                    Vector2::new(0.3, -0.1),
                    2.0,
                    Vector2::new(0.1, 0.2),
                    0.5,
                ),
                &pill,
                (
                    (0.5f64.hypot(0.5) + 0.3 + 0.5) * Vector2::new(corner.cos(), corner.sin()),
                    corner,
                    Vector2::new(0.2, 0.3),
                    3.0,
                    Vector2::new(0.2, 0.0),
                    -1.0,
                ),
            ),
            // A disc rolling and spinning on a turning plank.
            (
                &ground,
                (
                    Vector2::new(0.0, -0.5),
                    0.1,
                    Vector2::new(0.1, 0.2),
                    0.7,
                    Vector2::new(0.3, -0.2),
                    0.4,
                ),
                &ball,
                (
                    Vector2::new(0.05, 0.0),
                    0.3,
                    Vector2::new(2.0, -0.4),
                    -6.0,
                    Vector2::new(-1.0, 0.5),
                    2.0,
                ),
            ),
            // The same, the disc as A.
            (
                &ball,
                (
                    Vector2::new(0.05, 0.0),
                    0.3,
                    Vector2::new(2.0, -0.4),
                    -6.0,
                    Vector2::new(-1.0, 0.5),
                    2.0,
                ),
                &ground,
                (
                    Vector2::new(0.0, -0.5),
                    0.1,
                    Vector2::new(0.1, 0.2),
                    0.7,
                    Vector2::new(0.3, -0.2),
                    0.4,
                ),
            ),
            // A box on one corner on a turning plank.
            (
                &ground,
                (
                    Vector2::new(0.0, -0.5),
                    -0.05,
                    Vector2::new(0.0, 0.3),
                    -1.5,
                    Vector2::new(0.2, 0.1),
                    0.3,
                ),
                &square,
                (
                    Vector2::new(0.2, 0.69),
                    0.3,
                    Vector2::new(1.0, 0.5),
                    4.0,
                    Vector2::new(0.1, -3.0),
                    -2.0,
                ),
            ),
            // Two discs rolling on each other.
            (
                &ball,
                (
                    Vector2::zeros(),
                    0.0,
                    Vector2::new(0.5, 0.0),
                    3.0,
                    Vector2::new(0.0, 1.0),
                    -1.0,
                ),
                &ball,
                (
                    Vector2::new(0.6, 0.8),
                    0.0,
                    Vector2::new(-1.0, 2.0),
                    -4.0,
                    Vector2::new(0.5, 0.0),
                    1.0,
                ),
            ),
            // A disc at a box's corner.
            (
                &square,
                (
                    Vector2::zeros(),
                    0.2,
                    Vector2::new(0.3, -0.1),
                    2.0,
                    Vector2::new(0.1, 0.2),
                    0.5,
                ),
                &ball,
                (
                    Vector2::new(0.75, 0.85),
                    0.0,
                    Vector2::new(-0.5, 1.0),
                    5.0,
                    Vector2::new(0.2, 0.0),
                    -1.0,
                ),
            ),
        ];
        for (sa, ma, sb, mb) in cases {
            let pose = |m: &Motion, t: f64| {
                Isometry2::new(
                    m.0 + m.2 * t + 0.5 * m.4 * t * t,
                    m.1 + m.3 * t + 0.5 * m.5 * t * t,
                )
            };
            let (_, features) =
                collide_with_features(sa, &pose(&ma, 0.0), sb, &pose(&mb, 0.0), 0.2)
                    .expect("close");
            let d = |t: f64| follow(&features, &pose(&ma, t), &pose(&mb, t)).1[0].separation;
            let h = 1e-4;
            let fd = (d(h) - 2.0 * d(0.0) + d(-h)) / (h * h);
            let view = |m: &Motion| BodyView {
                inv_mass: 1.0,
                inv_inertia: 1.0,
                position: m.0,
                velocity: m.2,
                omega: m.3,
            };
            let views = [view(&ma), view(&mb)];
            let (manifold, followed) = follow(&features, &pose(&ma, 0.0), &pose(&mb, 0.0));
            let (p, n) = (manifold.points()[0].point, manifold.normal);
            let material = |v: &BodyView, m: &Motion| {
                let r = p - v.position;
                m.4 + m.5 * perp(r) - v.omega * v.omega * r
            };
            let rows = n.dot(&(material(&views[1], &mb) - material(&views[0], &ma)));
            let exact = rows + followed[0].correction(&views, (0, 1), p, n);
            // Central differences: O(h²) truncation (~1e-7 here) and
            // round-off 4 ulp(d)/h² (~1e-8).
            // Each case turns a face, rolls a circle or both: the material
            // points' acceleration alone is off by metres per second².
            assert!(
                (rows - fd).abs() > 1.0,
                "{features:?}: rows alone {rows} vs {fd}"
            );
            assert!(
                (exact - fd).abs() < 1e-5,
                "{features:?}: {exact} vs {fd} (rows alone {rows})"
            );
        }
    }
}
