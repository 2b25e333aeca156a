//! Convex polygons: counter-clockwise, checked convex on construction,
//! with their mass properties (area, centroid, second moment) from the
//! geometry (seed §4.1.1, §4.2.5) and their bounds and convex core.

use super::{Turn, cross, rescaled, turn};
use crate::error::{EngineError, Result, require_positive};
use nalgebra::{Isometry2, Vector2};

/// A convex polygon, counter-clockwise, in its body's frame (m).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ConvexPolygon {
    pub(super) vertices: Vec<Vector2<f64>>,
}

impl ConvexPolygon {
    /// A polygon from vertices listed counter-clockwise. Refuses fewer than
    /// three vertices, non-finite coordinates, repeated or collinear vertices,
    /// a clockwise order and a non-convex outline, naming the first bad vertex.
    pub fn new(vertices: Vec<Vector2<f64>>) -> Result<Self> {
        let n = vertices.len();
        if n < 3 {
            return Err(EngineError::InvalidPolygon {
                vertex: n,
                reason: "a polygon needs at least 3 vertices",
            });
        }
        if let Some(i) = super::first_non_finite(&vertices) {
            return Err(EngineError::InvalidPolygon {
                vertex: i,
                reason: "non-finite coordinate",
            });
        }
        for i in 0..n {
            if vertices[i] == vertices[(i + n - 1) % n] {
                return Err(EngineError::InvalidPolygon {
                    vertex: i,
                    reason: "repeated vertex",
                });
            }
        }
        let vertices_in = vertices;
        let vertices = rescaled(&vertices_in);
        let signed_area: f64 = (0..n)
            .map(|i| cross(vertices[i], vertices[(i + 1) % n]))
            .sum();
        for i in 0..n {
            let prev = vertices[(i + n - 1) % n];
            let next = vertices[(i + 1) % n];
            let turn = turn(prev, vertices[i], next);
            if turn == Turn::Straight {
                return Err(EngineError::InvalidPolygon {
                    vertex: i,
                    reason: "collinear vertex",
                });
            }
            if turn == Turn::Right {
                return Err(EngineError::InvalidPolygon {
                    vertex: i,
                    reason: if signed_area < 0.0 {
                        "vertices are clockwise (list them counter-clockwise)"
                    } else {
                        "polygon is not convex"
                    },
                });
            }
        }
        // All turns left is not enough: a star winds twice. A convex CCW
        // polygon's edge directions turn by exactly 2π in total.
        let winding: f64 = (0..n)
            .map(|i| {
                let a = vertices[(i + 1) % n] - vertices[i];
                let b = vertices[(i + 2) % n] - vertices[(i + 1) % n];
                cross(a, b).atan2(a.dot(&b))
            })
            .sum();
        if winding > 2.0 * std::f64::consts::PI + 1e-6 {
            return Err(EngineError::InvalidPolygon {
                vertex: 0,
                reason: "polygon is not convex (self-intersecting)",
            });
        }
        Ok(Self {
            vertices: vertices_in,
        })
    }

    /// The axis-aligned rectangle `width × height` (m) centred on the origin.
    pub fn rectangle(width: f64, height: f64) -> Result<Self> {
        let hw = 0.5 * require_positive("box width", width)?;
        let hh = 0.5 * require_positive("box height", height)?;
        Self::new(vec![
            Vector2::new(-hw, -hh),
            Vector2::new(hw, -hh),
            Vector2::new(hw, hh),
            Vector2::new(-hw, hh),
        ])
    }

    /// The convex hull of a point cloud (Andrew's monotone chain), CCW,
    /// collinear points dropped.
    pub fn convex_hull(points: &[Vector2<f64>]) -> Result<Self> {
        let mut pts: Vec<Vector2<f64>> = points.to_vec();
        if let Some(i) = super::first_non_finite(&pts) {
            return Err(EngineError::InvalidPolygon {
                vertex: i,
                reason: "non-finite coordinate",
            });
        }
        pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        pts.dedup();
        if pts.len() < 3 {
            return Err(EngineError::InvalidPolygon {
                vertex: pts.len(),
                reason: "a hull needs at least 3 distinct points",
            });
        }
        let mut hull: Vec<Vector2<f64>> = Vec::with_capacity(2 * pts.len());
        for pass in 0..2 {
            let start = hull.len();
            let iter: Box<dyn Iterator<Item = &Vector2<f64>>> = if pass == 0 {
                Box::new(pts.iter())
            } else {
                Box::new(pts.iter().rev())
            };
            for p in iter {
                while hull.len() >= start + 2
                    && cross(
                        hull[hull.len() - 1] - hull[hull.len() - 2],
                        p - hull[hull.len() - 2],
                    ) <= 0.0
                {
                    hull.pop();
                }
                hull.push(*p);
            }
            hull.pop();
        }
        Self::new(hull)
    }

    /// The vertices, counter-clockwise, in the body frame (m).
    pub fn vertices(&self) -> &[Vector2<f64>] {
        &self.vertices
    }

    /// Area (m²).
    pub fn area(&self) -> f64 {
        let n = self.vertices.len();
        0.5 * (0..n)
            .map(|i| cross(self.vertices[i], self.vertices[(i + 1) % n]))
            .sum::<f64>()
    }

    /// Centroid (m), in the polygon's frame.
    pub fn centroid(&self) -> Vector2<f64> {
        let n = self.vertices.len();
        let mut c = Vector2::zeros();
        let mut area2 = 0.0;
        // Triangles fanned from vertex 0 keep the sums well conditioned.
        let o = self.vertices[0];
        for i in 1..n - 1 {
            let (a, b) = (self.vertices[i] - o, self.vertices[i + 1] - o);
            let w = cross(a, b);
            area2 += w;
            c += w * (a + b) / 3.0;
        }
        o + c / area2
    }

    /// Second moment of area about the centroid, `∫ |r − c|² dA` (m⁴).
    /// Times the density it is the moment of inertia.
    pub fn polar_moment_about_centroid(&self) -> f64 {
        let n = self.vertices.len();
        let c = self.centroid();
        (0..n)
            .map(|i| {
                let (a, b) = (self.vertices[i] - c, self.vertices[(i + 1) % n] - c);
                cross(a, b) * (a.dot(&a) + a.dot(&b) + b.dot(&b)) / 12.0
            })
            .sum()
    }

    /// The tightest axis-aligned bounds of the polygon placed at `pose`
    /// (m, world frame): the lower and upper corners, the extremes of its
    /// vertices.
    pub fn bounds(&self, pose: &Isometry2<f64>) -> (Vector2<f64>, Vector2<f64>) {
        super::placed_bounds(&self.vertices, pose)
    }

    /// Its convex core placed at `pose` (m, world frame): the vertices,
    /// counter-clockwise (radius 0).
    pub(crate) fn core_at<'a>(
        &'a self,
        pose: &'a Isometry2<f64>,
    ) -> impl Iterator<Item = Vector2<f64>> + 'a {
        super::placed(&self.vertices, pose)
    }

    /// The radius (m) of the largest circle about the frame's origin inside
    /// the polygon: the least distance from the origin to an edge's line,
    /// 0 when the origin is outside.
    pub fn inner_radius(&self) -> f64 {
        inner_radius_of(&self.vertices)
    }

    /// The largest distance from the frame's origin to the polygon (m):
    /// its farthest vertex.
    pub fn max_extent(&self) -> f64 {
        self.vertices.iter().map(|v| v.norm()).fold(0.0, f64::max)
    }

    /// The same polygon translated so that its centroid is the origin.
    pub fn centered(&self) -> Self {
        let c = self.centroid();
        Self {
            vertices: self.vertices.iter().map(|v| v - c).collect(),
        }
    }
}

/// The inner radius (m) of a convex core with vertices `v` (≥ 3,
/// counter-clockwise): the least distance from the frame's origin to an
/// edge's line (outward unit normal `(e.y, −e.x)/|e|` of edge `e`), 0 when
/// the origin is outside.
pub(crate) fn inner_radius_of(v: &[Vector2<f64>]) -> f64 {
    (0..v.len())
        .map(|i| {
            let e = v[(i + 1) % v.len()] - v[i];
            (Vector2::new(e.y, -e.x) / e.norm()).dot(&v[i])
        })
        .fold(f64::INFINITY, f64::min)
        .max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clockwise_polygon_is_refused() {
        let cw = vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(1.0, 0.0),
        ];
        let err = ConvexPolygon::new(cw).unwrap_err();
        assert!(err.to_string().contains("clockwise"), "{err}");
    }

    #[test]
    fn non_convex_polygon_names_the_vertex() {
        let dart = vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(2.0, 0.0),
            Vector2::new(1.0, 0.5),
            Vector2::new(2.0, 2.0),
            Vector2::new(0.0, 2.0),
        ];
        match ConvexPolygon::new(dart).unwrap_err() {
            EngineError::InvalidPolygon { vertex, .. } => assert_eq!(vertex, 2),
            e => panic!("unexpected {e}"),
        }
    }

    #[test]
    fn hull_of_a_square_with_inner_points_is_the_square() {
        let pts = [
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.5, 0.5),
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(0.5, 0.0),
        ];
        let hull = ConvexPolygon::convex_hull(&pts).unwrap();
        assert_eq!(hull.vertices().len(), 4);
        assert!((hull.area() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn off_centre_triangle_centroid_and_inertia() {
        // Right triangle legs 3 and 6: centroid (1, 2); I_c/A = (a² + b²)/18.
        let t = ConvexPolygon::new(vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(3.0, 0.0),
            Vector2::new(0.0, 6.0),
        ])
        .unwrap();
        assert!((t.centroid() - Vector2::new(1.0, 2.0)).norm() < 1e-14);
        let per_area = t.polar_moment_about_centroid() / t.area();
        assert!((per_area - 45.0 / 18.0).abs() < 1e-13, "{per_area}");
    }

    fn polygon(points: &[[f64; 2]]) -> Result<ConvexPolygon> {
        ConvexPolygon::new(points.iter().map(|p| Vector2::new(p[0], p[1])).collect())
    }

    fn reason(points: &[[f64; 2]]) -> (usize, &'static str) {
        match polygon(points).unwrap_err() {
            EngineError::InvalidPolygon { vertex, reason } => (vertex, reason),
            e => panic!("unexpected {e}"),
        }
    }

    #[test]
    fn thin_boxes_are_valid() {
        for (w, h) in [(1.0, 1e-7), (1000.0, 0.001), (1e-7, 1.0), (1e6, 1e-9)] {
            let b = ConvexPolygon::rectangle(w, h).unwrap();
            assert!((b.area() - w * h).abs() <= 1e-15 * w * h, "{w} x {h}");
        }
    }

    #[test]
    fn huge_and_tiny_coordinates_are_judged_by_their_shape() {
        let huge = polygon(&[[-1e300, -1e300], [1e300, -1e300], [0.0, 1e300]]);
        assert!(huge.is_ok(), "{huge:?}");
        let tiny = polygon(&[[-1e-300, -1e-300], [1e-300, -1e-300], [0.0, 1e-300]]);
        assert!(tiny.is_ok(), "{tiny:?}");
        let far = polygon(&[[1e6, 1e6], [1e6 + 1e-3, 1e6], [1e6, 1e6 + 1e-3]]);
        assert!(far.is_ok(), "{far:?}");
    }

    #[test]
    fn a_duplicated_vertex_is_a_repeated_vertex() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(reason(&square), (2, "repeated vertex"));
        assert_eq!(
            reason(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]).1,
            "repeated vertex"
        );
    }

    #[test]
    fn collinear_vertices_are_refused_at_any_scale() {
        for s in [1.0, 1e-300, 1e300] {
            let points = [[0.0, 0.0], [s, 0.0], [2.0 * s, 0.0], [s, s]];
            assert_eq!(reason(&points), (1, "collinear vertex"), "scale {s}");
        }
        // The vertices are exact: a dent of 1e-17 m in a 1 m edge is a real
        // dent, far above the turn's rounding (about 1e-32 m² here).
        let points = [[0.0, 0.0], [0.5, 1e-17], [1.0, 0.0], [0.5, 1.0]];
        assert_eq!(reason(&points), (1, "polygon is not convex"));
    }
}
