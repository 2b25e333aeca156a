//! Where a query's candidate pieces come from: the soft step's broad-phase
//! trees when the soft step runs, else a linear scan over the bodies (the
//! exact model keeps no tree: it is made for a few bodies). Either way a
//! candidate is a [`ShapeRef`] the query's filter accepts, then tested on
//! the exact geometry by the caller.

use super::ShapeRef;
use crate::collision::Aabb;
use crate::collision::convex::{ConvexProxy, piece_count, piece_proxy};
use crate::collision::dynamic_tree::ray::ray_box;
use crate::filter::{Filter, QueryFilter};
use crate::shape::Shape;
use crate::soft_step::SoftStep;
use crate::world_core::WorldCore;
use nalgebra::{Isometry2, Vector2};

/// The world as a query reads it.
pub(crate) struct Source<'w> {
    pub core: &'w WorldCore,
    pub soft: Option<&'w SoftStep>,
    pub filter: QueryFilter,
}

/// The collision filter of a piece: its compound part's own, else its
/// body's (the soft step resolves a collider's filter the same way). The
/// one place queries read a shape's filter.
fn shape_filter(core: &WorldCore, shape: ShapeRef) -> Filter {
    let body = &core.bodies[shape.body];
    match &body.shape {
        Some(Shape::Compound(c)) => c
            .parts()
            .get(shape.part)
            .and_then(|p| p.overrides.filter)
            .unwrap_or(body.filter),
        _ => body.filter,
    }
}

impl Source<'_> {
    /// Whether the query's filter accepts the piece.
    fn accepts(&self, shape: ShapeRef) -> bool {
        self.filter.accepts(&shape_filter(self.core, shape))
    }

    /// Whether the piece is a chain's segment (one-sided: see
    /// [`World::cast_ray`](crate::World::cast_ray)).
    pub(crate) fn is_chain_segment(&self, shape: ShapeRef) -> bool {
        matches!(self.core.bodies[shape.body].shape, Some(Shape::Chain(_)))
    }

    /// The piece's proxy at its body's current pose.
    pub(crate) fn proxy(&self, shape: ShapeRef) -> ConvexProxy {
        let body = &self.core.bodies[shape.body];
        let state = &self.core.states[shape.body];
        let whole = body.shape.as_ref().expect("a candidate has a shape");
        let pose = Isometry2::new(state.position, state.angle);
        piece_proxy(whole, shape.part, &pose).expect("a candidate's part exists")
    }

    /// Every piece of every body with a shape, for the linear scan.
    fn all_pieces(&self) -> impl Iterator<Item = ShapeRef> + '_ {
        self.core
            .bodies
            .iter()
            .enumerate()
            .filter_map(|(body, b)| b.shape.as_ref().map(|s| (body, piece_count(s))))
            .flat_map(|(body, count)| (0..count).map(move |part| ShapeRef { body, part }))
    }

    /// Calls `f` for every accepted piece whose box (fat box under the
    /// soft step, tight box in the scan) overlaps `aabb`.
    pub(crate) fn overlapping(&self, aabb: &Aabb, mut f: impl FnMut(ShapeRef)) {
        match self.soft {
            Some(soft) => {
                for tree in soft.query_trees() {
                    tree.query(aabb, |_, c| {
                        let (body, part) = soft.collider_owner(c as usize);
                        let shape = ShapeRef { body, part };
                        if self.accepts(shape) {
                            f(shape);
                        }
                        true
                    });
                }
            }
            None => {
                for shape in self.all_pieces() {
                    if self.accepts(shape) && self.proxy(shape).aabb().overlaps(aabb) {
                        f(shape);
                    }
                }
            }
        }
    }

    /// Calls `f(piece, max_t)` for every accepted piece whose box the ray
    /// `origin + t dir` (unit `dir`, 0 ≤ t ≤ max_t, m) crosses; `f`
    /// returns the new maximum distance (the nearest hit so far, for a
    /// closest-hit query), and pieces beyond it are skipped where the tree
    /// allows.
    pub(crate) fn along_ray(
        &self,
        origin: Vector2<f64>,
        dir: Vector2<f64>,
        max_t: f64,
        mut f: impl FnMut(ShapeRef, f64) -> f64,
    ) {
        let mut max_t = max_t;
        match self.soft {
            Some(soft) => {
                for tree in soft.query_trees() {
                    tree.ray_cast(origin, dir, max_t, |_, c, limit| {
                        let (body, part) = soft.collider_owner(c as usize);
                        let shape = ShapeRef { body, part };
                        if self.accepts(shape) {
                            max_t = max_t.min(f(shape, limit));
                        }
                        Some(max_t)
                    });
                }
            }
            None => {
                let inverse = dir.map(|c| 1.0 / c);
                for shape in self.all_pieces() {
                    if self.accepts(shape)
                        && ray_box(&self.proxy(shape).aabb(), origin, inverse, max_t).is_some()
                    {
                        max_t = max_t.min(f(shape, max_t));
                    }
                }
            }
        }
    }
}
