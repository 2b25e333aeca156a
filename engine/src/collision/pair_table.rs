//! The narrow phase's one pair table: shape kind × shape kind → the
//! functions of that pair (as Box2D v3's contact registers). Every question
//! the narrow phase answers about a pair of single shapes goes through
//! [`pair`]:
//!
//! - `manifold`: the exact contact manifold within a margin
//!   ([`super::collide`]);
//! - `features`: the same manifold with the features the exact model's
//!   persistent contacts follow (`features.rs`), optionally clipped on a
//!   given reference face.
//!
//! The signed distance is not here: it is written once for every pair of
//! convex shapes, on their convex proxies ([`super::proximity`]).
//!
//! Kinds, in table order: polygon, circle, rounded (segment, capsule,
//! rounded polygon), chain. A compound is not a kind here: the narrow
//! phase splits it into its parts before asking the table. A chain is
//! one-sided and collided by the soft step only: its row reports no
//! contact.
//!
//! Adding a shape kind is one row and one column here, and its pair
//! functions in their own file (as `rounded_pair.rs` for the rounded
//! kinds). A pair whose first shape is the later kind in table order is
//! the mirrored pair with its result flipped.

use super::circle_circle::collide_circle_circle_with_margin;
use super::features::{
    ContactFeatures, circle_circle_contact, flipped, polygon_circle_contact,
    polygon_polygon_features,
};
use super::manifold::Manifold;
use super::polygon_circle::collide_polygon_circle_with_margin;
use super::polygon_polygon::{Face, collide_polygon_polygon_with_margin};
use super::rounded_pair::{Core, core_circle, core_pair};
use crate::shape::{Circle, Shape};
use nalgebra::Isometry2;

/// The contact manifold of a pair within a margin (m), `None` when apart.
pub(crate) type ManifoldFn =
    fn(&Shape, &Isometry2<f64>, &Shape, &Isometry2<f64>, f64) -> Option<Manifold>;

/// The manifold with its features, clipped on a given reference face when
/// one is given (polygon pairs; others ignore it).
pub(crate) type FeaturesFn = fn(
    &Shape,
    &Isometry2<f64>,
    &Shape,
    &Isometry2<f64>,
    f64,
    Option<Face>,
) -> Option<(Manifold, ContactFeatures)>;

/// The functions of one pair of shape kinds.
#[derive(Clone, Copy)]
pub(crate) struct PairFunctions {
    /// The exact manifold.
    pub manifold: ManifoldFn,
    /// The manifold and its features.
    pub features: FeaturesFn,
}

/// The table's index of a shape's kind; `None` for a compound.
fn kind(shape: &Shape) -> Option<usize> {
    match shape {
        Shape::Polygon(_) => Some(0),
        Shape::Circle(_) => Some(1),
        Shape::Rounded(_) => Some(2),
        Shape::Chain(_) => Some(3),
        Shape::Compound(_) => None,
    }
}

/// The functions of the pair `(a, b)`; `None` when either is a compound
/// (split it into its parts first).
pub(crate) fn pair(a: &Shape, b: &Shape) -> Option<&'static PairFunctions> {
    Some(&TABLE[kind(a)?][kind(b)?])
}

const POLYGON_POLYGON: PairFunctions = PairFunctions {
    manifold: |a, pa, b, pb, margin| {
        let (Shape::Polygon(a), Shape::Polygon(b)) = (a, b) else {
            unreachable!("the table's polygon–polygon cell")
        };
        collide_polygon_polygon_with_margin(a, pa, b, pb, margin)
    },
    features: |a, pa, b, pb, margin, face| {
        let (Shape::Polygon(a), Shape::Polygon(b)) = (a, b) else {
            unreachable!("the table's polygon–polygon cell")
        };
        polygon_polygon_features(a, pa, b, pb, margin, face)
    },
};

const POLYGON_CIRCLE: PairFunctions = PairFunctions {
    manifold: |a, pa, b, pb, margin| {
        let (Shape::Polygon(a), Shape::Circle(b)) = (a, b) else {
            unreachable!("the table's polygon–circle cell")
        };
        collide_polygon_circle_with_margin(a, pa, b, pb, margin)
    },
    features: |a, pa, b, pb, margin, _| {
        let (Shape::Polygon(a), Shape::Circle(b)) = (a, b) else {
            unreachable!("the table's polygon–circle cell")
        };
        polygon_circle_contact(a, pa, b, pb, margin)
    },
};

const CIRCLE_CIRCLE: PairFunctions = PairFunctions {
    manifold: |a, pa, b, pb, margin| {
        let (Shape::Circle(a), Shape::Circle(b)) = (a, b) else {
            unreachable!("the table's circle–circle cell")
        };
        collide_circle_circle_with_margin(a, pa, b, pb, margin)
    },
    features: |a, pa, b, pb, margin, _| {
        let (Shape::Circle(a), Shape::Circle(b)) = (a, b) else {
            unreachable!("the table's circle–circle cell")
        };
        circle_circle_contact(a, pa, b, pb, margin)
    },
};

/// A polygon or rounded shape as a core (the table's cells call it only
/// with these).
fn core_of(shape: &Shape) -> Core<'_> {
    match shape {
        Shape::Polygon(p) => Core {
            vertices: p.vertices(),
            radius: 0.0,
        },
        Shape::Rounded(r) => Core {
            vertices: r.core(),
            radius: r.radius(),
        },
        _ => unreachable!("a core is a polygon's or a rounded shape's"),
    }
}

/// A circle's radius (the table's cells call it only with circles).
fn circle_of(shape: &Shape) -> &Circle {
    match shape {
        Shape::Circle(c) => c,
        _ => unreachable!("the table's circle column"),
    }
}

/// A core (polygon or rounded) against a core, one of them rounded.
const CORE_CORE: PairFunctions = PairFunctions {
    manifold: |a, pa, b, pb, margin| {
        core_pair(core_of(a), pa, core_of(b), pb, margin, None).map(|(m, _)| m)
    },
    features: |a, pa, b, pb, margin, face| core_pair(core_of(a), pa, core_of(b), pb, margin, face),
};

/// A rounded shape against a circle.
const ROUNDED_CIRCLE: PairFunctions = PairFunctions {
    manifold: |a, pa, b, pb, margin| {
        core_circle(core_of(a), pa, circle_of(b).radius, pb, margin).map(|(m, _)| m)
    },
    features: |a, pa, b, pb, margin, _| {
        core_circle(core_of(a), pa, circle_of(b).radius, pb, margin)
    },
};

/// A chain against anything: the exact model refuses chains (the soft
/// step collides their segments, `chain_segment.rs`); a chain bounds no
/// region (it is one-sided), so it reports no contact.
const CHAIN: PairFunctions = PairFunctions {
    manifold: |_, _, _, _, _| None,
    features: |_, _, _, _, _, _| None,
};

/// The pair `(b, a)` of a cell, flipped: circle against polygon, circle
/// and polygon against rounded.
macro_rules! mirrored {
    ($cell:expr) => {
        PairFunctions {
            manifold: |a, pa, b, pb, margin| {
                ($cell.manifold)(b, pb, a, pa, margin).map(|m| m.flipped())
            },
            features: |a, pa, b, pb, margin, face| {
                let face = face.map(|(reference_is_a, edge)| (!reference_is_a, edge));
                ($cell.features)(b, pb, a, pa, margin, face).map(|(m, f)| (m.flipped(), flipped(f)))
            },
        }
    };
}

/// Rows: A's kind; columns: B's (polygon, circle, rounded, chain).
static TABLE: [[PairFunctions; 4]; 4] = [
    [POLYGON_POLYGON, POLYGON_CIRCLE, CORE_CORE, CHAIN],
    [
        mirrored!(POLYGON_CIRCLE),
        CIRCLE_CIRCLE,
        mirrored!(ROUNDED_CIRCLE),
        CHAIN,
    ],
    [CORE_CORE, ROUNDED_CIRCLE, CORE_CORE, CHAIN],
    [CHAIN, CHAIN, CHAIN, CHAIN],
];
