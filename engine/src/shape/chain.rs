//! Chains: one-sided polylines for static ground and walls (Box2D's chain
//! shape, written anew).
//!
//! A chain is a list of points; each pair of consecutive points is a
//! **segment** that collides only on its **right**: the direction
//! `p2 − p1` turned clockwise by 90° is the segment's normal, and shapes
//! are pushed that way. So a ground listed right to left is solid from
//! above, and a loop listed clockwise holds shapes inside it (listed
//! counter-clockwise, it is solid outside).
//!
//! Each segment knows its neighbours' far points, the **ghost** points:
//! a shape sliding across a join reads the neighbour's direction and
//! refuses contact normals the smooth surface cannot have (no ghost
//! collision at the joins; `collision/chain_segment.rs`). In an open chain
//! the first and last points are ghosts only: they guide the end segments
//! but are not solid, so `n` points give `n − 3` solid segments. A loop of
//! `n` points has `n` segments, the last from the last point back to the
//! first. Box2D's conventions (`b2CreateChain`): at least 4 points, and
//! consecutive points at least the linear slop (5 mm) apart.
//!
//! A chain has no area and no mass: it goes on static bodies only.

use crate::error::{EngineError, Result};
use nalgebra::{Isometry2, Vector2};

/// Read from `engine/src/tunables.rs` (unit, value and source there): the
/// shortest segment a chain accepts (m).
use crate::tunables::LINEAR_SLOP;

/// A one-sided polyline, open or closed, in its body's frame (m).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Chain {
    points: Vec<Vector2<f64>>,
    is_loop: bool,
}

/// One solid segment of a chain with its two ghost points, in the body
/// frame (m): `ghost1 → point1 → point2 → ghost2` are four consecutive
/// points of the chain. The segment collides on the right of
/// `point2 − point1`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ChainSegment {
    /// The point before `point1` (m): the previous segment starts there.
    pub ghost1: Vector2<f64>,
    /// The segment's first point (m).
    pub point1: Vector2<f64>,
    /// The segment's second point (m).
    pub point2: Vector2<f64>,
    /// The point after `point2` (m): the next segment ends there.
    pub ghost2: Vector2<f64>,
}

impl Chain {
    /// A chain through `points` (m, body frame); `is_loop` joins the last
    /// point back to the first. Refuses fewer than 4 points, a non-finite
    /// coordinate, and two consecutive points (the last and the first in a
    /// loop) closer than the linear slop (5 mm), naming the first bad
    /// point.
    pub fn new(points: Vec<Vector2<f64>>, is_loop: bool) -> Result<Self> {
        let n = points.len();
        if n < 4 {
            return Err(EngineError::InvalidChain {
                point: n,
                reason: "a chain needs at least 4 points",
            });
        }
        if let Some(i) = super::first_non_finite(&points) {
            return Err(EngineError::InvalidChain {
                point: i,
                reason: "non-finite coordinate",
            });
        }
        let joins = if is_loop { n } else { n - 1 };
        for i in 0..joins {
            let j = (i + 1) % n;
            if (points[j] - points[i]).norm() < LINEAR_SLOP {
                return Err(EngineError::InvalidChain {
                    point: j,
                    reason: "closer than 5 mm (the linear slop) to the point before it",
                });
            }
        }
        Ok(Self { points, is_loop })
    }

    /// The tightest axis-aligned bounds of the chain placed at `pose` (m,
    /// world frame): the extremes of its points (ghosts included).
    pub fn bounds(&self, pose: &Isometry2<f64>) -> (Vector2<f64>, Vector2<f64>) {
        super::placed_bounds(&self.points, pose)
    }

    /// The largest distance from the frame's origin to a point of the
    /// chain (m).
    pub fn max_extent(&self) -> f64 {
        self.points.iter().map(|v| v.norm()).fold(0.0, f64::max)
    }

    /// The points, as given (m, body frame).
    pub fn points(&self) -> &[Vector2<f64>] {
        &self.points
    }

    /// Whether the last point joins the first.
    pub fn is_loop(&self) -> bool {
        self.is_loop
    }

    /// How many solid segments the chain has: `n − 3` for an open chain of
    /// `n` points, `n` for a loop.
    pub fn segment_count(&self) -> usize {
        let n = self.points.len();
        if self.is_loop { n } else { n - 3 }
    }

    /// Solid segment `i` (in [0, [`Chain::segment_count`])) with its ghost
    /// points, `None` past the last.
    pub fn segment(&self, i: usize) -> Option<ChainSegment> {
        if i >= self.segment_count() {
            return None;
        }
        let p = &self.points;
        let n = p.len();
        // An open chain's first point is a ghost only: its segment i starts
        // at point i + 1.
        let first = if self.is_loop { i + n } else { i + 1 };
        Some(ChainSegment {
            ghost1: p[(first - 1) % n],
            point1: p[first % n],
            point2: p[(first + 1) % n],
            ghost2: p[(first + 2) % n],
        })
    }

    /// The solid segments with their ghost points: `n − 3` for an open
    /// chain of `n` points, `n` for a loop.
    pub fn segments(&self) -> Vec<ChainSegment> {
        (0..self.segment_count())
            .map(|i| self.segment(i).expect("i < segment count"))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(xy: &[[f64; 2]]) -> Vec<Vector2<f64>> {
        xy.iter().map(|p| Vector2::new(p[0], p[1])).collect()
    }

    #[test]
    fn an_open_chain_of_n_points_has_n_minus_3_segments_with_its_ghosts() {
        let chain = Chain::new(
            points(&[[3.0, 0.0], [2.0, 0.0], [1.0, 0.0], [0.0, 0.0]]),
            false,
        )
        .unwrap();
        let segments = chain.segments();
        assert_eq!(segments.len(), 1);
        let s = segments[0];
        assert_eq!(s.ghost1, Vector2::new(3.0, 0.0));
        assert_eq!(s.point1, Vector2::new(2.0, 0.0));
        assert_eq!(s.point2, Vector2::new(1.0, 0.0));
        assert_eq!(s.ghost2, Vector2::new(0.0, 0.0));
    }

    #[test]
    fn a_loop_of_n_points_has_n_segments_wrapping_around() {
        let square = points(&[[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]);
        let segments = Chain::new(square.clone(), true).unwrap().segments();
        assert_eq!(segments.len(), 4);
        let last = segments[3];
        assert_eq!(
            (last.ghost1, last.point1, last.point2, last.ghost2),
            (square[2], square[3], square[0], square[1])
        );
    }

    #[test]
    fn bad_chains_name_the_point() {
        let err = |xy: &[[f64; 2]], is_loop| match Chain::new(points(xy), is_loop).unwrap_err() {
            EngineError::InvalidChain { point, reason } => (point, reason),
            e => panic!("unexpected {e}"),
        };
        assert_eq!(err(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], false).0, 3);
        let (i, why) = err(
            &[[0.0, 0.0], [1.0, 0.0], [f64::NAN, 0.0], [3.0, 0.0]],
            false,
        );
        assert_eq!((i, why), (2, "non-finite coordinate"));
        let close = [[0.0, 0.0], [1.0, 0.0], [1.004, 0.0], [3.0, 0.0]];
        assert_eq!(err(&close, false).0, 2);
        // In a loop the last point must also be apart from the first.
        let closing = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.001, 0.0]];
        assert!(Chain::new(points(&closing), false).is_ok());
        assert_eq!(err(&closing, true).0, 0);
    }
}
