//! Resting contact as forces inside the integration (seed §7.1, after
//! Baraff): a body at rest on another is held by a *contact force*, computed
//! at every evaluation of the right-hand side so that the contact points
//! neither approach nor accelerate into each other, and the integrator never
//! has to stop.
//!
//! At each evaluation, for every resting pair (chosen by the world at the
//! start of each piece of step, see the exact model's `pipeline.rs`):
//! 1. the manifold of the pair at the current poses, followed from the
//!    features it was found with at the piece's start, whatever its
//!    separation now (module `persistent`: the contact set is fixed between
//!    events, as in Baraff's formulation);
//! 2. one normal row per point with the *relative normal acceleration*
//!    `a_n = n · (a_B(P) − a_A(P))` of the points, each point's
//!    acceleration being `a + α × r − ω² r` under the applied forces, plus
//!    what that misses of the separation's second derivative (a circle's
//!    centripetal term, a turning face's `2 ṅ·v`: module `persistent`);
//! 3. Coulomb friction: while the pair *slides* (its tangential velocity is
//!    above [`super::ContactSettings::sliding_speed`]) each normal force
//!    carries the kinetic friction `−μ N s t` against the sliding direction
//!    s t; while it *sticks*, one friction row at the manifold's centre keeps
//!    the tangential acceleration at zero within the cone |F_t| ≤ μ ΣN
//!    (beyond it the friction saturates and the pair starts to slide);
//! 4. the complementarity problem N ≥ 0, a_n ≥ 0, N a_n = 0 (a contact only
//!    pushes, and only while needed) is solved ([`super::solver`]) and the
//!    forces are added to the bodies' wrenches.
//!
//! A box resting flat gets exactly its weight back (zero acceleration to
//! round-off); one sliding on flat ground or down an incline gets the
//! closed-form acceleration g(sin θ − μ cos θ); a disc rolling without
//! slipping down an incline gets (2/3) g sin θ. The sticking friction row
//! holds the tangential acceleration of the material points at the contact:
//! exact on a face that does not turn (the rolling disc's case); on a
//! turning or moving face the contact point's own motion adds a term that is
//! left out, and the drift it may cause is caught between steps (the pair is
//! re-classified at every settle).
//!
//! # On jointed bodies
//!
//! With joints (`crate::exact::joints`), the contact forces are solved
//! with the joints, as the impacts are (module `constrained`): a body's
//! acceleration is a = a₀ + M⁻¹ (W_cᵀ λ_c + J_jᵀ λ_j) with J_j a + γ_j =
//! 0, so that, a_j = a₀ + M⁻¹ J_jᵀ λ_j0 being the accelerations the
//! joints alone leave ((J_j M⁻¹ J_jᵀ) λ_j0 = −(J_j a₀ + γ_j)),
//!
//! a = a_j + P W_cᵀ λ_c,   P = M⁻¹ − M⁻¹ J_jᵀ (J_j M⁻¹ J_jᵀ)⁻¹ J_j M⁻¹.
//!
//! The complementarity problem keeps its form with b read from a_j and
//! K = J_c P W_cᵀ; the joints' forces then follow from the contact
//! forces (the right-hand side solves them with a₀ + M⁻¹ W_cᵀ λ_c). A
//! row along which the joints allow no motion (K_ii below
//! [`crate::tunables::REDUNDANT_PIVOT`] of its free value) gets no force:
//! the joints carry that load. A pinned rod resting on a support at s
//! from the pin is held by N = m g x_c / s, its pin by the rest of its
//! weight (`engine/tests/exact_joints.rs`).
//!
//! Limits: with a large μ the kinetic friction riding on the normal force
//! can make the problem inconsistent (Painlevé's paradox: the effective
//! mass of a row turns ≤ 0); the solver then skips that row and returns its
//! best projected Gauss–Seidel iterate. A pair that starts to slide from
//! rest (the static friction saturates) is classified as sliding, and its
//! `Slip` event recorded, at the end of the first piece of step over which
//! it slid.

use super::constrained;
use super::persistent::{FollowedPoint, follow};
use super::rows::{BodyView, Row, RowKind, Side, effective_mass, perp};
use super::solver::solve;
use crate::body::{Body, BodyState};
use crate::collision::Manifold;
use crate::collision::features::ContactFeatures;
use crate::collision::narrow_phase::collide_with_features;
use crate::exact::joints::ExactJoints;
use crate::exact::ode::Layout;
use crate::forces::Wrench;
use nalgebra::{Isometry2, Vector2};

/// How friction acts on a resting pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum FrictionMode {
    /// μ = 0.
    Frictionless,
    /// Static friction: the tangential relative acceleration is held at 0
    /// within the cone.
    Sticking,
    /// Kinetic friction against `direction`, the unit world direction of
    /// B's tangential velocity relative to A when the piece of step began.
    Sliding { direction: Vector2<f64> },
}

/// A pair held by contact forces, with the features its contact was found
/// with at the start of the piece of step (module `persistent`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RestingPair {
    pub a: usize,
    pub b: usize,
    pub friction: FrictionMode,
    pub features: ContactFeatures,
}

/// Two classifications are the same when the pair, its friction mode and
/// the identity of its features agree (the features' coordinates move with
/// the bodies from one settle to the next).
impl PartialEq for RestingPair {
    fn eq(&self, other: &Self) -> bool {
        (self.a, self.b, self.friction, self.features.id())
            == (other.a, other.b, other.friction, other.features.id())
    }
}

impl RestingPair {
    /// The pair's manifold at `states`, followed from its features, and
    /// each point's geometry.
    pub(crate) fn follow(&self, states: &[BodyState]) -> (Manifold, [FollowedPoint; 2]) {
        follow(
            &self.features,
            &pose(&states[self.a]),
            &pose(&states[self.b]),
        )
    }
}

/// The pose of a body (its centre of mass and angle).
pub(crate) fn pose(state: &BodyState) -> Isometry2<f64> {
    Isometry2::new(state.position, state.angle)
}

/// The manifold of bodies `a < b` at their states within `margin` (m), with
/// the features it is made of.
pub(crate) fn features_of(
    bodies: &[Body],
    states: &[BodyState],
    a: usize,
    b: usize,
    margin: f64,
) -> Option<(Manifold, ContactFeatures)> {
    let (sa, sb) = (bodies[a].shape.as_ref()?, bodies[b].shape.as_ref()?);
    collide_with_features(sa, &pose(&states[a]), sb, &pose(&states[b]), margin)
}

/// The rows of one manifold of pair (a, b): one normal row per point (its
/// force column tilted by kinetic friction while sliding), then one
/// friction row at the centre while sticking.
pub(crate) fn manifold_rows(
    views: &[BodyView],
    a: usize,
    b: usize,
    manifold: &Manifold,
    friction: (f64, FrictionMode),
    mut targets: impl FnMut(usize, f64) -> f64,
    rows: &mut Vec<Row>,
) {
    let n = manifold.normal;
    let t = perp(n);
    let (mu, mode) = friction;
    let push = match mode {
        FrictionMode::Sliding { direction } if mu > 0.0 => {
            let s = if direction.dot(&t) >= 0.0 { 1.0 } else { -1.0 };
            n - mu * s * t
        }
        _ => n,
    };
    let start = rows.len();
    let mut centre = Vector2::zeros();
    for (i, p) in manifold.points().iter().enumerate() {
        let sides = sides_at(views, a, b, p.point);
        let mut row = Row {
            kind: RowKind::Normal,
            sides,
            measure: n,
            push,
            target: 0.0,
        };
        row.target = targets(i, row.velocity(views));
        rows.push(row);
        centre += p.point;
    }
    let count = manifold.points().len();
    if mu > 0.0 && mode == FrictionMode::Sticking {
        centre /= count as f64;
        rows.push(Row {
            kind: RowKind::Friction {
                mu,
                normals: (start, start + count),
            },
            sides: sides_at(views, a, b, centre),
            measure: t,
            push: t,
            target: 0.0,
        });
    }
}

fn sides_at(views: &[BodyView], a: usize, b: usize, point: Vector2<f64>) -> [Side; 2] {
    [
        Side {
            body: a,
            sign: -1.0,
            arm: point - views[a].position,
        },
        Side {
            body: b,
            sign: 1.0,
            arm: point - views[b].position,
        },
    ]
}

/// Union–find over bodies: pairs sharing a dynamic body are solved together
/// (an island); an immovable body does not join islands.
pub(crate) fn islands(views: &[BodyView], pairs: &[(usize, usize)]) -> Vec<usize> {
    let mut parent: Vec<usize> = (0..views.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let dynamic = |i: usize| views[i].inv_mass > 0.0 || views[i].inv_inertia > 0.0;
    for &(a, b) in pairs {
        if dynamic(a) && dynamic(b) {
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            parent[ra.max(rb)] = ra.min(rb);
        }
    }
    pairs
        .iter()
        .map(|&(a, b)| {
            let d = if dynamic(a) { a } else { b };
            root(&mut parent, d)
        })
        .collect()
}

/// Scratch buffers of the contact-force computation, kept between
/// evaluations so that the right-hand side allocates nothing in steady state.
#[derive(Debug, Clone, Default)]
pub(crate) struct Scratch {
    pub views: Vec<BodyView>,
    pub rows: Vec<Row>,
    /// Per row: what its material-point acceleration misses of the
    /// separation's d'' (module `persistent`), 0 for friction rows.
    pub corrections: Vec<f64>,
    pub k: Vec<f64>,
    pub b: Vec<f64>,
    pub lambda: Vec<f64>,
    pub accelerations: Vec<(Vector2<f64>, f64)>,
    pub out: Vec<(Vector2<f64>, f64)>,
    /// Generalised vectors (the layout's positions long, or the columns
    /// P W_cᵀ) of the solve on jointed bodies.
    pub generalized: Vec<f64>,
}

/// The resting pairs of a world and what their forces need: the contact
/// term of the world's right-hand side.
#[derive(Debug, Clone, Default)]
pub(crate) struct RestingContacts {
    /// The pairs held by contact forces, sorted by (a, b).
    pub pairs: Vec<RestingPair>,
    /// μ.
    pub friction: f64,
    /// ε (m): the manifold margin.
    pub tolerance: f64,
    scratch: Scratch,
}

impl RestingContacts {
    /// Contact forces for the resting pairs at `states`, given the applied
    /// `wrenches`; added to `wrenches`. With `joints` (and the state's
    /// layout) the forces are solved in the joints' constrained space
    /// (module docs, "On jointed bodies").
    pub(crate) fn apply(
        &mut self,
        bodies: &[Body],
        states: &[BodyState],
        wrenches: &mut [Wrench],
        mut joints: Option<(&mut ExactJoints, &Layout)>,
    ) {
        if self.pairs.is_empty() {
            return;
        }
        let s = &mut self.scratch;
        s.views.clear();
        s.views.extend(
            bodies
                .iter()
                .zip(states)
                .map(|(b, st)| BodyView::new(b, st)),
        );
        s.accelerations.clear();
        s.accelerations.extend(
            s.views
                .iter()
                .zip(wrenches.iter())
                .map(|(v, w)| (w.force * v.inv_mass, w.torque * v.inv_inertia)),
        );
        // Every resting pair's contact, followed from its features at these
        // poses, whatever its separation now (module `persistent`).
        let manifolds: Vec<(usize, usize, FrictionMode, Manifold, [FollowedPoint; 2])> = self
            .pairs
            .iter()
            .map(|p| {
                let (m, followed) = p.follow(states);
                (p.a, p.b, p.friction, m, followed)
            })
            .collect();
        if manifolds.is_empty() {
            return;
        }
        let mut keys: Vec<(usize, usize)> = manifolds.iter().map(|m| (m.0, m.1)).collect();
        if let Some((j, layout)) = joints.as_mut() {
            // The accelerations the joints leave the bodies (a₀ + M⁻¹ J_jᵀ
            // λ₀), which the rows' free accelerations b read; jointed
            // bodies share an island.
            constrained::accelerations(
                j,
                bodies,
                layout,
                states,
                &mut s.generalized,
                &mut s.accelerations,
            );
            keys.extend(constrained::joint_pairs(j));
        }
        let island = islands(&s.views, &keys);
        let mut order: Vec<usize> = (0..manifolds.len()).collect();
        order.sort_by_key(|&i| island[i]);
        s.out.clear();
        s.out.resize(bodies.len(), (Vector2::zeros(), 0.0));
        let mut start = 0;
        while start < order.len() {
            let mut end = start + 1;
            while end < order.len() && island[order[end]] == island[order[start]] {
                end += 1;
            }
            s.rows.clear();
            s.corrections.clear();
            for &i in &order[start..end] {
                let (a, b, mode, m, followed) = &manifolds[i];
                let first = s.rows.len();
                manifold_rows(
                    &s.views,
                    *a,
                    *b,
                    m,
                    (self.friction, *mode),
                    |_, _| 0.0,
                    &mut s.rows,
                );
                s.corrections.resize(s.rows.len(), 0.0);
                for (k, (point, f)) in m.points().iter().zip(followed).enumerate() {
                    s.corrections[first + k] =
                        f.correction(&s.views, (*a, *b), point.point, m.normal);
                }
            }
            s.b.clear();
            s.b.extend(
                s.rows
                    .iter()
                    .zip(&s.corrections)
                    .map(|(r, c)| r.acceleration(&s.views, &s.accelerations) + c),
            );
            match joints.as_mut() {
                // K = J_c P W_cᵀ: the contact rows' mass with the joints held.
                Some((j, layout)) => {
                    constrained::effective_mass(
                        j,
                        bodies,
                        layout,
                        states,
                        &s.rows,
                        &mut s.k,
                        &mut s.generalized,
                    );
                    constrained::drop_locked(&s.rows, &s.views, &mut s.k, &mut s.b);
                }
                None => effective_mass(&s.rows, &s.views, &mut s.k),
            }
            solve(&s.rows, &s.k, &s.b, &mut s.lambda);
            for (row, &l) in s.rows.iter().zip(&s.lambda) {
                if l != 0.0 {
                    row.apply(l, &mut s.out);
                }
            }
            start = end;
        }
        for ((w, v), (f, tau)) in wrenches.iter_mut().zip(&s.views).zip(&s.out) {
            if v.inv_mass > 0.0 {
                w.force += f;
            }
            if v.inv_inertia > 0.0 {
                w.torque += tau;
            }
        }
    }
}
