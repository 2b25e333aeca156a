//! The one feature-id scheme of both contact models: which features of the
//! two shapes made a contact point (the soft step, per point) or a contact
//! manifold (the exact model, per manifold), so that a contact computed
//! again from the same features is recognised as the same contact (the
//! soft step's warm starting carries its impulses over; the exact model's
//! resting classification keeps its persistent contact).
//!
//! Only equality is read: two ids of the same pair of shapes are equal
//! exactly when they name the same features. Ids of different pairs of
//! shape kinds are never compared (a contact keeps its two shapes).
//!
//! # Features
//!
//! A [`Feature`] of one shape is a 20-bit code, its kind in bits 18–19 and
//! its index in bits 0–17:
//!
//! | kind | code | names |
//! |---|---|---|
//! | [`Feature::Vertex`]`(i)` | `i` | vertex `i` of a polygon or core (a segment's ends are vertices 0 and 1) |
//! | [`Feature::Edge`]`(i)` | `1 << 18 \| i` | the edge from vertex `i` to vertex `i + 1` (a segment's inside, and its side as a reference face, are its edge 0) |
//! | [`Feature::Clip`]`(k)` | `2 << 18 \| k` | an incident point made by clipping at end `k` (0 or 1) of the reference edge |
//! | [`Feature::Centre`] | `3 << 18` | a circle's centre |
//!
//! # Layout of a [`FeatureId`] (64 bits)
//!
//! | bits | field |
//! |---|---|
//! | 63 | the reference face is A's ([`FeatureId::face`]; else B's, or not a face contact) |
//! | 62, 61 | a two-point face manifold cut to its last (62) or first (61) point ([`FeatureId::retained`]) |
//! | 60 | a vertex–vertex contact of two cores ([`FeatureId::vertex_pair`]) |
//! | 40–59 | the reference edge's index ([`FeatureId::face`]) |
//! | 20–39 | the first feature |
//! | 0–19 | the second feature |
//!
//! The two features are read by how the id was made:
//!
//! - [`FeatureId::pair`] (a point of the soft step; the exact model's
//!   vertex pairs and polygon–circle contacts): A's feature first, B's
//!   second. The soft step's clipped points of two polygons are the
//!   vertices behind them (the reference edge's end on the point's side
//!   and the incident vertex), as Box2D v3's `B2_MAKE_ID`; its vertex–vertex
//!   point of two polygons apart is the pair of those vertices, so it keeps
//!   the impulse of the clipped point it replaces. A capsule pair's point
//!   between closest points is each segment's end (vertex 0 or 1) or
//!   inside (edge 0); its clipped points are the reference segment's edge 0
//!   and the incident end as a clip. A chain segment's points are its edge
//!   0 and the incident vertex when it is the reference, its end (a vertex)
//!   and the polygon's reference edge when the polygon is.
//! - [`FeatureId::face`] (the exact model's face manifolds): the reference
//!   side (bit 63) and edge, the first and last incident points (a vertex
//!   of the incident shape, or a clip).
//!
//! A manifold of one point with nothing to tell apart (every circle pair
//! of the soft step, as Box2D's circle manifolds; two circles in the exact
//! model) is [`FeatureId::ONE_POINT`].
//!
//! This file depends on no shape: the pair files name their own features
//! as [`Feature`]s (`polygon_polygon_local.rs`'s incident points,
//! `polygon_circle.rs`'s polygon features).
//!
//! The soft step stores an id in each of its contact points: a `u64` there
//! takes the padding a `u32` left beside the `f64`s (the records keep their
//! size, checked by a test in `soft_step/contacts.rs`).

/// One feature of one shape (see the module documentation for its code).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Feature {
    /// Vertex `i` of a polygon or core.
    Vertex(usize),
    /// The edge from vertex `i` to vertex `i + 1`.
    Edge(usize),
    /// An incident point made by clipping at end `k` (0 or 1) of the
    /// reference edge.
    Clip(usize),
    /// A circle's centre.
    Centre,
}

/// Bits of a feature's code.
const FEATURE_BITS: u32 = 20;
/// Bits of a feature's index.
const INDEX_BITS: u32 = 18;

impl Feature {
    /// The 20-bit code.
    #[inline(always)]
    const fn code(self) -> u64 {
        let (kind, index) = match self {
            Feature::Vertex(i) => (0, i),
            Feature::Edge(i) => (1, i),
            Feature::Clip(k) => (2, k),
            Feature::Centre => (3, 0),
        };
        debug_assert!(index < 1 << INDEX_BITS);
        (kind << INDEX_BITS) | index as u64
    }
}

/// Which features of a pair of shapes a contact point or manifold comes
/// from (layout in the module documentation). Compared for equality only.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(transparent))]
pub(crate) struct FeatureId(u64);

/// Bit 63: the reference face is A's.
const REFERENCE_ON_A: u64 = 1 << 63;
/// Bit 61 + k: a face manifold cut to its point k.
const RETAINED_SHIFT: u32 = 61;
/// Bit 60: a vertex–vertex contact of two cores.
const VERTEX_PAIR: u64 = 1 << 60;
/// Bits 40–59: the reference edge.
const EDGE_SHIFT: u32 = 2 * FEATURE_BITS;

impl FeatureId {
    /// A one-point manifold with nothing to tell apart.
    pub(crate) const ONE_POINT: FeatureId = FeatureId(0);

    /// A's feature `a` and B's feature `b`.
    #[inline(always)]
    pub(crate) const fn pair(a: Feature, b: Feature) -> Self {
        FeatureId((a.code() << FEATURE_BITS) | b.code())
    }

    /// Vertex `a` of A's core and vertex `b` of B's, nearest each other
    /// (the exact model's round contact of two cores).
    pub(crate) const fn vertex_pair(a: usize, b: usize) -> Self {
        FeatureId(VERTEX_PAIR | Self::pair(Feature::Vertex(a), Feature::Vertex(b)).0)
    }

    /// Incident points `first` and `last` (the same for one point; a vertex
    /// of the incident shape or a clip) against reference edge `edge` of A
    /// (`reference_is_a`) or B.
    pub(crate) fn face(reference_is_a: bool, edge: usize, first: Feature, last: Feature) -> Self {
        debug_assert!(edge < 1 << FEATURE_BITS);
        let side = if reference_is_a { REFERENCE_ON_A } else { 0 };
        FeatureId(side | ((edge as u64) << EDGE_SHIFT) | Self::pair(first, last).0)
    }

    /// A two-point face manifold's id cut to its point `k` (0 or 1): which
    /// point is left is part of the identity.
    pub(crate) fn retained(self, k: usize) -> Self {
        FeatureId(self.0 | (1 << (RETAINED_SHIFT + k as u32)))
    }

    /// Whether this is a vertex–vertex contact of two cores.
    #[cfg(test)]
    pub(crate) fn is_vertex_pair(self) -> bool {
        self.0 & VERTEX_PAIR != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_and_fields_do_not_overlap() {
        let features = [
            Feature::Vertex(0),
            Feature::Vertex(1),
            Feature::Edge(0),
            Feature::Edge(1),
            Feature::Clip(0),
            Feature::Clip(1),
            Feature::Centre,
        ];
        // Every pair (pair(Vertex(0), Vertex(0)) is ONE_POINT's code).
        let mut ids = Vec::new();
        for a in features {
            for b in features {
                ids.push(FeatureId::pair(a, b));
            }
        }
        assert!(ids.contains(&FeatureId::ONE_POINT));
        let incident = [Feature::Vertex(0), Feature::Clip(0)];
        for side in [false, true] {
            for first in incident {
                for last in incident {
                    let face = FeatureId::face(side, 1, first, last);
                    ids.extend([face, face.retained(0), face.retained(1)]);
                }
            }
        }
        ids.push(FeatureId::vertex_pair(0, 1));
        let n = ids.len();
        ids.sort_by_key(|id| id.0);
        ids.dedup();
        assert_eq!(ids.len(), n);
        assert!(FeatureId::vertex_pair(0, 1).is_vertex_pair());
        assert!(!FeatureId::face(true, 1, incident[0], incident[1]).is_vertex_pair());
    }
}
