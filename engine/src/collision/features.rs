//! The features a contact is made of, in the shapes' own frames: what a
//! contact that persists over a stretch of time needs in order to be
//! followed as the bodies move, without asking the narrow phase again.
//!
//! The narrow phase ([`super::collide`]) answers "do these shapes touch, and
//! where?" for one pair of poses. A resting contact of the exact model is
//! held by forces computed at every evaluation of the right-hand side, at
//! poses that an integrator's stages extrapolate (an RK4 stage is off the
//! true path by O(h²)); asking the narrow phase there, with a margin of ε,
//! loses a contact whose stage pose lifts its point by more than ε, and the
//! contact force vanishes for that stage. Instead, the features found when
//! the contact was classified are kept, fixed in each body's frame, and
//! re-evaluated exactly at every pose:
//!
//! - [`ContactFeatures::Face`]: points of the *incident* shape (polygon
//!   vertices or clip points, or a circle's centre with its radius) against
//!   the *reference* face of the other polygon, as the SAT found them
//!   (seed §7.2, Fig. 7.2–7.4);
//! - [`ContactFeatures::Round`]: two round features (circle centres with
//!   their radii, or a polygon vertex with radius 0), the normal along the
//!   line between them.
//!
//! Frames: a shape's frame is its body's (origin at the centre of mass); a
//! circle is centred on it.

use super::feature_id::{Feature, FeatureId};
use super::manifold::Manifold;
use super::polygon_circle::{PolygonFeature, closest_polygon_circle, edge_normal};
use super::polygon_polygon::{Face, clip_polygon_polygon_on};
use crate::shape::{Circle, ConvexPolygon};
use nalgebra::{Isometry2, Point2, Vector2};

/// The features of one contact manifold, in the shapes' frames (m).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) enum ContactFeatures {
    /// Points of the incident shape against a face of the reference one.
    Face {
        /// Whether the reference face is on shape A (else on B).
        reference_is_a: bool,
        /// The reference face's outward unit normal, reference frame.
        normal: Vector2<f64>,
        /// A point of the reference face (its first vertex), reference
        /// frame (m).
        face_point: Vector2<f64>,
        /// The incident shape's points, incident frame (m); `count` of them.
        points: [Vector2<f64>; 2],
        /// 1 or 2.
        count: usize,
        /// The incident shape's radius (m): a circle's, 0 for a polygon.
        radius: f64,
        /// Which features these are ([`FeatureId::face`]), for telling a
        /// change of contact topology from a motion of the same contact.
        id: FeatureId,
    },
    /// Two round features, the normal along the line between them.
    Round {
        /// A's feature point (a vertex, or the circle's centre), A's frame.
        point_a: Vector2<f64>,
        /// A's radius (m): a circle's, 0 for a vertex.
        radius_a: f64,
        /// B's feature point, B's frame.
        point_b: Vector2<f64>,
        /// B's radius (m).
        radius_b: f64,
        /// Which features these are.
        id: FeatureId,
    },
}

impl ContactFeatures {
    /// The identity of the features.
    pub(crate) fn id(&self) -> FeatureId {
        match self {
            ContactFeatures::Face { id, .. } | ContactFeatures::Round { id, .. } => *id,
        }
    }

    /// The number of points (1 or 2), in the manifold's order.
    pub(crate) fn count(&self) -> usize {
        match self {
            ContactFeatures::Face { count, .. } => *count,
            ContactFeatures::Round { .. } => 1,
        }
    }

    /// The features of the points whose `keep` flag is set (in the
    /// manifold's order), `None` if none is.
    pub(crate) fn retain(&self, keep: [bool; 2]) -> Option<ContactFeatures> {
        let count = self.count();
        let kept: Vec<usize> = (0..count).filter(|&k| keep[k]).collect();
        if kept.is_empty() {
            return None;
        }
        if kept.len() == count {
            return Some(*self);
        }
        match *self {
            ContactFeatures::Face {
                reference_is_a,
                normal,
                face_point,
                points,
                radius,
                id,
                ..
            } => Some(ContactFeatures::Face {
                reference_is_a,
                normal,
                face_point,
                points: [points[kept[0]]; 2],
                count: 1,
                radius,
                // Which of the two points is left is part of the identity.
                id: id.retained(kept[0]),
            }),
            round @ ContactFeatures::Round { .. } => Some(round),
        }
    }
}

/// The features of two polygons' manifold clipped on reference face
/// `face` (the SAT's best when `None`), as `polygon_polygon.rs` finds it.
pub(crate) fn polygon_polygon_features(
    pa: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    pb: &ConvexPolygon,
    pose_b: &Isometry2<f64>,
    margin: f64,
    face: Option<Face>,
) -> Option<(Manifold, ContactFeatures)> {
    let (m, f) = clip_polygon_polygon_on(pa, pose_a, pb, pose_b, margin, face)?;
    let (reference, incident_pose) = if f.reference_is_a {
        (pa, pose_b)
    } else {
        (pb, pose_a)
    };
    let v = reference.vertices();
    let (v1, v2) = (v[f.edge], v[(f.edge + 1) % v.len()]);
    // The points are in A's frame: to the incident frame.
    let to_incident = |p: Vector2<f64>| {
        if f.reference_is_a {
            let world = pose_a.transform_point(&Point2::from(p));
            incident_pose.inverse_transform_point(&world).coords
        } else {
            p
        }
    };
    Some((
        m,
        ContactFeatures::Face {
            reference_is_a: f.reference_is_a,
            normal: edge_normal(v1, v2),
            face_point: v1,
            points: [to_incident(f.points[0]), to_incident(f.points[1])],
            count: f.count,
            radius: 0.0,
            id: FeatureId::face(
                f.reference_is_a,
                f.edge,
                f.ids[0].into(),
                f.ids[f.count - 1].into(),
            ),
        },
    ))
}

/// The features of a polygon (A) and a circle (B) within `margin` (m).
pub(crate) fn polygon_circle_contact(
    p: &ConvexPolygon,
    pose_a: &Isometry2<f64>,
    c: &Circle,
    pose_b: &Isometry2<f64>,
    margin: f64,
) -> Option<(Manifold, ContactFeatures)> {
    let (proximity, feature) = closest_polygon_circle(p, pose_a, c, pose_b);
    // A NaN distance (non-finite input) reports no contact.
    (proximity.distance <= margin).then_some(())?;
    Some((
        proximity.one_point_manifold(),
        polygon_circle_features(p.vertices(), 0.0, feature, c.radius, true),
    ))
}

/// The features of two circles within `margin` (m).
pub(crate) fn circle_circle_contact(
    ca: &Circle,
    pose_a: &Isometry2<f64>,
    cb: &Circle,
    pose_b: &Isometry2<f64>,
    margin: f64,
) -> Option<(Manifold, ContactFeatures)> {
    let m = super::collide_circle_circle_with_margin(ca, pose_a, cb, pose_b, margin)?;
    Some((
        m,
        ContactFeatures::Round {
            point_a: Vector2::zeros(),
            radius_a: ca.radius,
            point_b: Vector2::zeros(),
            radius_b: cb.radius,
            id: FeatureId::ONE_POINT,
        },
    ))
}

/// The features flipped to the pair seen with A and B swapped (the same
/// id: a pair is always asked in one order).
pub(crate) fn flipped(features: ContactFeatures) -> ContactFeatures {
    match features {
        ContactFeatures::Face {
            reference_is_a,
            normal,
            face_point,
            points,
            count,
            radius,
            id,
        } => ContactFeatures::Face {
            reference_is_a: !reference_is_a,
            normal,
            face_point,
            points,
            count,
            radius,
            id,
        },
        ContactFeatures::Round {
            point_a,
            radius_a,
            point_b,
            radius_b,
            id,
        } => ContactFeatures::Round {
            point_a: point_b,
            radius_a: radius_b,
            point_b: point_a,
            radius_b: radius_a,
            id,
        },
    }
}

/// The features of a polygon (or a rounded core of `core_radius`, m)
/// touching a circle of `radius` (m) at `feature`; `polygon_is_a` says
/// which of the pair the polygon is. A rounded core's face is its edge
/// moved out by its radius.
pub(crate) fn polygon_circle_features(
    vertices: &[Vector2<f64>],
    core_radius: f64,
    feature: PolygonFeature,
    radius: f64,
    polygon_is_a: bool,
) -> ContactFeatures {
    // The polygon's feature and the circle's centre, whichever is A: a
    // pair is always asked in one order.
    let id = FeatureId::pair(Feature::from(feature), Feature::Centre);
    match feature {
        PolygonFeature::Edge(i) => {
            let (v1, v2) = (vertices[i], vertices[(i + 1) % vertices.len()]);
            let normal = edge_normal(v1, v2);
            ContactFeatures::Face {
                reference_is_a: polygon_is_a,
                normal,
                face_point: v1 + core_radius * normal,
                points: [Vector2::zeros(); 2],
                count: 1,
                radius,
                id,
            }
        }
        PolygonFeature::Vertex(i) => {
            let (vertex, centre) = ((vertices[i], core_radius), (Vector2::zeros(), radius));
            let ((point_a, radius_a), (point_b, radius_b)) = if polygon_is_a {
                (vertex, centre)
            } else {
                (centre, vertex)
            };
            ContactFeatures::Round {
                point_a,
                radius_a,
                point_b,
                radius_b,
                id,
            }
        }
    }
}
