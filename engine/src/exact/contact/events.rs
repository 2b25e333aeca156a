//! The record of what contact handling did: impacts with their impulses,
//! contacts beginning and ending, sticking and slipping.

use crate::body::BodyId;
use nalgebra::Vector2;

/// What happened at a contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactEventKind {
    /// An impact: some point approached faster than the resting speed and
    /// got an impulse with restitution (seed eq. 7.15).
    Impact,
    /// A pair came to rest in contact (a resting contact began): it is now
    /// held by contact forces inside the integration.
    Rest,
    /// A resting pair separated (its contact ended).
    Release,
    /// A sliding contact stopped sliding: its tangential velocity reached
    /// zero (located by root finding) and static friction now holds it.
    Stick,
    /// A sticking contact started to slide.
    Slip,
}

impl ContactEventKind {
    /// A short stable name for reports and snapshots.
    pub fn id(&self) -> &'static str {
        match self {
            ContactEventKind::Impact => "impact",
            ContactEventKind::Rest => "rest",
            ContactEventKind::Release => "release",
            ContactEventKind::Stick => "stick",
            ContactEventKind::Slip => "slip",
        }
    }
}

/// One contact event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEvent {
    /// When (s).
    pub t: f64,
    /// What happened.
    pub kind: ContactEventKind,
    /// The pair, `body_a < body_b`.
    pub body_a: BodyId,
    /// The second body of the pair.
    pub body_b: BodyId,
    /// Where (m, world frame): the contact point, or with two points their
    /// centre weighted by the normal impulses (their midpoint when no
    /// impulse was applied).
    pub point: Vector2<f64>,
    /// Unit contact normal, from `body_a` towards `body_b`.
    pub normal: Vector2<f64>,
    /// Number of contact points of the manifold (1 or 2).
    pub points: usize,
    /// Total normal impulse on `body_b` (N·s, ≥ 0); `body_a` gets the
    /// opposite. It is the j of seed eq. 7.15 for a single point.
    pub normal_impulse: f64,
    /// Total friction impulse on `body_b` along the tangent
    /// `(−normal.y, normal.x)` (N·s).
    pub tangent_impulse: f64,
    /// Relative normal velocity of the points before (m/s, < 0 when
    /// approaching): the most negative over the manifold's points.
    pub normal_velocity_before: f64,
    /// The same after the response (m/s).
    pub normal_velocity_after: f64,
}
