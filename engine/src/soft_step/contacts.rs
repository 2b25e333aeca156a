//! The persistent contacts of the soft step: one [`Contact`] per pair of
//! bodies whose enlarged bounding boxes overlap, created by the broad phase
//! and destroyed when the boxes part; each step its manifold is recomputed
//! (the **collide** stage), and every new point whose feature id matches a
//! point of the last manifold inherits that point's impulses, which the
//! solver then applies first (warm starting).
//!
//! A pair that barely moved relative to itself since its manifold was
//! computed keeps that manifold (contact recycling, after Box2D v3.2): its
//! anchors and normal stay, its separations are updated from the bodies'
//! motion exactly as the substeps do. See
//! [`super::SoftStepSettings::recycle_distance`].

use super::geometry::SolverShape;
use super::manifold::{self, LocalManifold, Scratch};
use super::shape_data::PairMaterial;
use crate::body::BodyId;
use crate::collision::feature_id::FeatureId;
use nalgebra::{Isometry2, UnitComplex, Vector2};
use rustc_hash::FxHashMap;

use crate::tunables::RECYCLE_COS_ANGLE;

/// A point of a contact's manifold, in the world frame at the time the
/// manifold was computed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ContactPoint {
    /// From A's centre of mass to the point (m).
    pub anchor_a: Vector2<f64>,
    /// From B's centre of mass to the point (m).
    pub anchor_b: Vector2<f64>,
    /// Signed distance along the normal now (m): < 0 overlapping.
    pub separation: f64,
    /// Signed distance when the manifold was computed (m).
    pub computed_separation: f64,
    /// Feature id ([`manifold::LocalPoint::id`]).
    pub id: FeatureId,
    /// Normal impulse accumulated over the last step (N·s).
    pub normal_impulse: f64,
    /// Friction impulse accumulated over the last step (N·s), along the
    /// tangent `(n.y, −n.x)`.
    pub tangent_impulse: f64,
    /// Sum of every normal impulse applied in the last step (N·s): zero
    /// for a speculative point that never pushed.
    pub total_normal_impulse: f64,
    /// Relative normal velocity before the last step's solve (m/s).
    pub normal_velocity: f64,
    /// The point in the world frame when the manifold was computed (m).
    pub point: Vector2<f64>,
}

/// What a recycled manifold is compared against.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Computed {
    /// Collider B's pose in collider A's frame when the manifold was
    /// computed.
    relative: Isometry2<f64>,
    /// The bodies' rotations then.
    rotation_a: UnitComplex<f64>,
    rotation_b: UnitComplex<f64>,
}

/// A pair of colliders whose enlarged boxes overlap.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Contact {
    /// The reference collider (the polygon of a polygon–circle pair, else
    /// the lower id).
    pub a: usize,
    /// The other collider.
    pub b: usize,
    /// Their bodies.
    pub body_a: BodyId,
    pub body_b: BodyId,
    /// Unit normal from A to B (world, at computation time).
    pub normal: Vector2<f64>,
    pub count: usize,
    pub points: [ContactPoint; 2],
    /// Mixed friction coefficient √(μa μb).
    pub friction: f64,
    /// Mixed restitution (by default max(ea, eb)).
    pub restitution: f64,
    /// Mixed rolling resistance (m: coefficient × radius).
    pub rolling_resistance: f64,
    /// Mixed tangent speed (m/s).
    pub tangent_speed: f64,
    /// Rolling-resistance angular impulse accumulated over the last step
    /// (N·m·s).
    pub rolling_impulse: f64,
    /// When collider A (B) is a circle, the distance (m) along the normal
    /// from the manifold's point to the circle's centre (towards A's
    /// centre for A, along the normal for B); 0 for any other shape.
    /// The point of a circle facing the other shape is the one along the
    /// normal from its centre whatever the circle's turn, so the
    /// separation follows the centre, not the point turning with the body
    /// ([`super::contact_solver`]'s current separation).
    pub centre_depth: [f64; 2],
    /// Whether one of the two colliders is a sensor: the pair is never
    /// solved, and "touching" means overlapping.
    pub sensor: bool,
    /// Whether the manifold has points (touching or within the
    /// speculative distance); for a sensor pair, whether a point overlaps.
    pub touching: bool,
    computed: Option<Computed>,
}

/// What the collide stage reads of one side of a pair: the collider's
/// shape and pose, and its body's pose (centre of mass and rotation).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Side<'a> {
    pub shape: &'a SolverShape,
    pub collider: Isometry2<f64>,
    pub body: Isometry2<f64>,
}

/// Touching changes found by the collide stage ([`ContactSet::record_change`]), for the islands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TouchChange {
    Began(usize),
    Ended(usize),
}

/// Every contact of the world, with the pair index.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ContactSet {
    pub contacts: Vec<Contact>,
    pairs: FxHashMap<(BodyId, BodyId), usize>,
    /// Reused list of touching changes of the last update.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub changes: Vec<TouchChange>,
}

/// The key of an unordered pair.
fn key(a: BodyId, b: BodyId) -> (BodyId, BodyId) {
    (a.min(b), a.max(b))
}

/// Whether `(a, b)` must be swapped so that a polygon–circle pair has the
/// polygon first and a pair with a chain segment the segment first;
/// otherwise the lower id comes first.
pub(crate) fn ordered(
    (a, shape_a): (BodyId, &SolverShape),
    (b, shape_b): (BodyId, &SolverShape),
) -> (BodyId, BodyId) {
    match (shape_a, shape_b) {
        (SolverShape::Circle { .. }, SolverShape::Polygon(_)) => (b, a),
        (SolverShape::Polygon(_), SolverShape::Circle { .. }) => (a, b),
        (SolverShape::ChainSegment(_), SolverShape::ChainSegment(_)) => (a.min(b), a.max(b)),
        (_, SolverShape::ChainSegment(_)) => (b, a),
        (SolverShape::ChainSegment(_), _) => (a, b),
        _ => (a.min(b), a.max(b)),
    }
}

impl ContactSet {
    /// Whether the pair of colliders already has a contact.
    pub(crate) fn contains(&self, a: usize, b: usize) -> bool {
        self.pairs.contains_key(&key(a, b))
    }

    /// Creates the contact of an ordered pair of colliders (see
    /// [`ordered`]) on `bodies`, with its mixed material; `sensor` when
    /// one of them is a sensor.
    pub(crate) fn create(
        &mut self,
        (a, b): (usize, usize),
        bodies: (BodyId, BodyId),
        material: PairMaterial,
        sensor: bool,
    ) {
        let index = self.contacts.len();
        self.pairs.insert(key(a, b), index);
        self.contacts.push(Contact {
            a,
            b,
            body_a: bodies.0,
            body_b: bodies.1,
            normal: Vector2::zeros(),
            count: 0,
            points: [ContactPoint::default(); 2],
            friction: material.friction,
            restitution: material.restitution,
            rolling_resistance: material.rolling_resistance,
            tangent_speed: material.tangent_speed,
            rolling_impulse: 0.0,
            centre_depth: [0.0; 2],
            sensor,
            touching: false,
            computed: None,
        });
    }

    /// Destroys contact `index` (the last contact takes its place).
    pub(crate) fn destroy(&mut self, index: usize) {
        let c = self.contacts.swap_remove(index);
        self.pairs.remove(&key(c.a, c.b));
        if let Some(moved) = self.contacts.get(index) {
            self.pairs.insert(key(moved.a, moved.b), index);
        }
    }

    /// Destroys every contact of `body`.
    pub(crate) fn destroy_body(&mut self, body: BodyId) {
        let mut i = 0;
        while i < self.contacts.len() {
            let c = &self.contacts[i];
            if c.body_a == body || c.body_b == body {
                self.destroy(i);
            } else {
                i += 1;
            }
        }
    }

    /// Records contact `index`'s [`TouchChange`] after an update that found
    /// it `was_touching` before.
    pub(crate) fn record_change(&mut self, index: usize, was_touching: bool) {
        let touching = self.contacts[index].touching;
        if touching && !was_touching {
            self.changes.push(TouchChange::Began(index));
        } else if !touching && was_touching {
            self.changes.push(TouchChange::Ended(index));
        }
    }

    /// Disables contact `index` for this step (the pre-solve hook said
    /// so), right after its update ([`update_contact`]): no points, not
    /// touching, its touching change corrected (a beginning undone, or an
    /// end recorded).
    pub(crate) fn disable(&mut self, index: usize) {
        let contact = &mut self.contacts[index];
        if !contact.touching {
            return;
        }
        contact.count = 0;
        contact.touching = false;
        contact.computed = None;
        if self.changes.last() == Some(&TouchChange::Began(index)) {
            self.changes.pop();
        } else {
            self.changes.push(TouchChange::Ended(index));
        }
    }
}

/// Recomputes `contact`'s manifold at the colliders' poses, keeping the
/// impulses of points whose feature ids persist, or recycles it (see the
/// module docs), and sets its touching flag; `scratch` is the caller's
/// (one per thread). The distances (m): `max_extent` bounds the distance
/// of the colliders' points from their origins, then the speculative and
/// the recycle distance. Returns whether the contact was touching before,
/// for [`ContactSet::record_change`]. Touches nothing but `contact` and
/// `scratch`, so contacts can be updated on several threads. Inlined into
/// the collide stage's loop (a call per contact, its sides passed by
/// value, cost some 90 instructions a contact).
#[inline(always)]
pub(crate) fn update_contact(
    contact: &mut Contact,
    (a, b): (Side<'_>, Side<'_>),
    (max_extent, speculative, recycle_distance): (f64, f64, f64),
    scratch: &mut Scratch,
) -> bool {
    let was_touching = contact.touching;
    let relative = a.collider.inv_mul(&b.collider);
    if let Some(computed) = contact.computed
        && recycle(
            contact,
            computed,
            &relative,
            (&a.body, &b.body),
            max_extent,
            speculative,
            recycle_distance,
        )
    {
        if contact.sensor {
            set_touching(contact);
        }
        return was_touching;
    }
    let local = manifold::collide(a.shape, b.shape, &relative, speculative, scratch);
    store_manifold(contact, &local, &a.collider, (&a.body, &b.body));
    contact.centre_depth = centre_depth(contact, (&a, &b));
    contact.computed = Some(Computed {
        relative,
        rotation_a: a.body.rotation,
        rotation_b: b.body.rotation,
    });
    set_touching(contact);
    was_touching
}

/// [`Contact::centre_depth`] of a freshly stored manifold: for each side
/// that is a circle (centred at its collider's origin), the distance along
/// the normal between the point and the centre. Circle manifolds have one
/// point.
#[inline(always)]
fn centre_depth(contact: &Contact, (a, b): (&Side<'_>, &Side<'_>)) -> [f64; 2] {
    if contact.count == 0 {
        return [0.0; 2];
    }
    let point = a.body.translation.vector + contact.points[0].anchor_a;
    let depth = |side: &Side<'_>, sign: f64| match side.shape {
        SolverShape::Circle { .. } => {
            sign * (side.collider.translation.vector - point).dot(&contact.normal)
        }
        _ => 0.0,
    };
    [depth(a, -1.0), depth(b, 1.0)]
}

/// Sets `contact`'s touching flag from its manifold: any point for a
/// solved pair, an overlapping one for a sensor pair.
fn set_touching(contact: &mut Contact) {
    contact.touching = if contact.sensor {
        contact.points[..contact.count]
            .iter()
            .any(|p| p.separation <= 0.0)
    } else {
        contact.count > 0
    };
}

/// Keeps the manifold when the pair's relative pose moved by less than the
/// recycle distance (a bound on any point's displacement: the translation
/// plus the largest extent times the sine of the turn), updating its
/// separations from the motion. Returns whether it did. Inlined into the
/// collide stage's loop, as [`update_contact`].
#[inline(always)]
fn recycle(
    contact: &mut Contact,
    computed: Computed,
    relative: &Isometry2<f64>,
    (body_a, body_b): (&Isometry2<f64>, &Isometry2<f64>),
    max_extent: f64,
    speculative: f64,
    recycle_distance: f64,
) -> bool {
    if recycle_distance <= 0.0 {
        return false;
    }
    // Turns since the manifold was computed, as unit complex numbers: their
    // real part is the cosine, their imaginary part the sine.
    let turn_a = body_a.rotation * computed.rotation_a.conjugate();
    let turn_b = body_b.rotation * computed.rotation_b.conjugate();
    if turn_a.re.min(turn_b.re) <= RECYCLE_COS_ANGLE {
        return false;
    }
    let moved = (relative.translation.vector - computed.relative.translation.vector).norm();
    let turned = (relative.rotation * computed.relative.rotation.conjugate())
        .im
        .abs();
    // A pair that is not touching may come within reach of new features:
    // hold it to the tighter of the two distances.
    let tolerance = if contact.touching {
        recycle_distance
    } else {
        recycle_distance.min(speculative)
    };
    if moved + max_extent * turned >= tolerance {
        return false;
    }
    let dc = body_b.translation.vector - body_a.translation.vector;
    for p in &mut contact.points[..contact.count] {
        // B's point relative to A's point; zero when the manifold was
        // computed (anchor_b − anchor_a = pose_a − pose_b then).
        let d = dc + turn_b * p.anchor_b - turn_a * p.anchor_a;
        // A circle's facing point does not turn with it (Contact::centre_depth).
        let [ka, kb] = contact.centre_depth;
        let unturned = kb * (1.0 - turn_b.re) + ka * (1.0 - turn_a.re);
        p.separation = p.computed_separation + d.dot(&contact.normal) - unturned;
    }
    true
}

/// Stores a freshly computed manifold (in collider A's frame) in world
/// terms, anchors from the bodies' centres of mass, carrying over the
/// impulses of points with the same feature id. Inlined, as
/// [`update_contact`].
#[inline(always)]
fn store_manifold(
    contact: &mut Contact,
    local: &LocalManifold,
    collider_a: &Isometry2<f64>,
    (body_a, body_b): (&Isometry2<f64>, &Isometry2<f64>),
) {
    let old = contact.points;
    let old_count = contact.count;
    contact.normal = collider_a.rotation * local.normal;
    contact.count = local.count;
    let origin_delta = body_a.translation.vector - body_b.translation.vector;
    for (p, lp) in contact.points.iter_mut().zip(&local.points[..local.count]) {
        let anchor_a = collider_a.transform_vector(&lp.point)
            + (collider_a.translation.vector - body_a.translation.vector);
        let matched = old[..old_count].iter().find(|o| o.id == lp.id);
        *p = ContactPoint {
            anchor_a,
            anchor_b: anchor_a + origin_delta,
            separation: lp.separation,
            computed_separation: lp.separation,
            id: lp.id,
            normal_impulse: matched.map_or(0.0, |o| o.normal_impulse),
            tangent_impulse: matched.map_or(0.0, |o| o.tangent_impulse),
            total_normal_impulse: 0.0,
            normal_velocity: 0.0,
            point: body_a.translation.vector + anchor_a,
        };
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::shape::Shape;

    #[test]
    fn a_u64_feature_id_keeps_the_point_records_their_size() {
        // A point's id sits beside f64 words, padded to 8 bytes: the u32
        // of the soft step's former scheme took 32 and 104 bytes as the
        // u64 of the one scheme (`collision/feature_id.rs`) does.
        // LocalPoint: a Vector2<f64>, an f64 and the id.
        assert_eq!(std::mem::size_of::<manifold::LocalPoint>(), 4 * 8);
        // ContactPoint: 12 f64 words and the id.
        assert_eq!(std::mem::size_of::<ContactPoint>(), 13 * 8);
    }

    pub(crate) fn material() -> PairMaterial {
        PairMaterial {
            friction: 0.6,
            restitution: 0.0,
            rolling_resistance: 0.0,
            tangent_speed: 0.0,
        }
    }

    fn boxes() -> (SolverShape, SolverShape) {
        let s = SolverShape::new(&Shape::rectangle(1.0, 1.0).unwrap());
        (s.clone(), s)
    }

    fn pose(x: f64, y: f64, angle: f64) -> Isometry2<f64> {
        Isometry2::new(Vector2::new(x, y), angle)
    }

    /// Updates contact 0 of `set` between box `a` and box `b` (single
    /// colliders at their bodies' poses) with recycling distance `recycle`.
    fn update(
        set: &mut ContactSet,
        (a, b): (&SolverShape, &SolverShape),
        (pa, pb): (Isometry2<f64>, Isometry2<f64>),
        recycle: f64,
    ) {
        let side = |shape, pose| Side {
            shape,
            collider: pose,
            body: pose,
        };
        let was_touching = update_contact(
            &mut set.contacts[0],
            (side(a, pa), side(b, pb)),
            (0.71, 0.02, recycle),
            &mut Scratch::default(),
        );
        set.record_change(0, was_touching);
    }

    #[test]
    fn impulses_follow_their_feature_ids_across_updates() {
        let (a, b) = boxes();
        let mut set = ContactSet::default();
        set.create((0, 1), (0, 1), material(), false);
        update(
            &mut set,
            (&a, &b),
            (pose(0.0, 0.0, 0.0), pose(0.1, 0.99, 0.0)),
            0.0,
        );
        assert_eq!(set.changes, [TouchChange::Began(0)]);
        let c = &mut set.contacts[0];
        assert_eq!(c.count, 2);
        c.points[0].normal_impulse = 3.0;
        c.points[1].normal_impulse = 5.0;
        let ids = [c.points[0].id, c.points[1].id];
        // A small motion keeps the features; recycling is off (0 m), so the
        // manifold is recomputed and the impulses must come from the ids.
        update(
            &mut set,
            (&a, &b),
            (pose(0.0, 0.0, 0.0), pose(0.12, 0.992, 0.02)),
            0.0,
        );
        let c = &set.contacts[0];
        for (id, impulse) in [(ids[0], 3.0), (ids[1], 5.0)] {
            let q = c.points.iter().find(|q| q.id == id).unwrap();
            assert_eq!(q.normal_impulse, impulse);
        }
        // Other features: no impulse is inherited by a point whose id is new.
        update(
            &mut set,
            (&a, &b),
            (pose(0.0, 0.0, 0.0), pose(0.6, 0.99, 0.3)),
            0.0,
        );
        let c = &set.contacts[0];
        for p in &c.points[..c.count] {
            if !ids.contains(&p.id) {
                assert_eq!(p.normal_impulse, 0.0);
            }
        }
    }

    #[test]
    fn a_recycled_manifold_tracks_the_separation_of_a_recomputed_one() {
        let (a, b) = boxes();
        let mut recycled = ContactSet::default();
        let mut fresh = ContactSet::default();
        for set in [&mut recycled, &mut fresh] {
            set.create((0, 1), (0, 1), material(), false);
            update(
                set,
                (&a, &b),
                (pose(0.0, 0.0, 0.0), pose(0.1, 0.99, 0.0)),
                0.05,
            );
        }
        // B sinks 3 mm and slides 4 mm: a pure translation, so the recycled
        // separations are exact (the anchors did not turn).
        let moved = (pose(0.0, 0.0, 0.0), pose(0.104, 0.987, 0.0));
        update(&mut recycled, (&a, &b), moved, 0.05);
        update(&mut fresh, (&a, &b), moved, 0.0);
        let (r, f) = (&recycled.contacts[0], &fresh.contacts[0]);
        for id in [r.points[0].id, r.points[1].id] {
            let sr = r.points.iter().find(|p| p.id == id).unwrap().separation;
            let sf = f.points.iter().find(|p| p.id == id).unwrap().separation;
            assert!((sr - sf).abs() < 1e-15, "{sr} vs {sf}");
        }
        // Past the recycle distance the manifold is recomputed: B's left
        // edge is now at x = −0.3 in A's frame (it was −0.4).
        update(
            &mut recycled,
            (&a, &b),
            (pose(0.0, 0.0, 0.0), pose(0.2, 0.99, 0.0)),
            0.05,
        );
        assert!(
            recycled.contacts[0]
                .points
                .iter()
                .any(|p| (p.anchor_a.x + 0.3).abs() < 1e-12)
        );
    }

    #[test]
    fn destroy_keeps_the_pair_index_consistent() {
        let mut set = ContactSet::default();
        for (a, b) in [(0, 1), (1, 2), (2, 3)] {
            set.create((a, b), (a, b), material(), false);
        }
        set.destroy(0);
        assert!(!set.contains(0, 1));
        assert!(set.contains(3, 2) && set.contains(1, 2));
        set.destroy_body(2);
        assert!(set.contacts.is_empty());
    }
}
