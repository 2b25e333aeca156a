//! The contact constraints of one step and the passes the soft step runs
//! over them (Box2D v3's `contact_solver.c`, written anew for f64):
//!
//! - **prepare** (once per step): per touching point, the anchors from each
//!   centre of mass, the separation at the step's start, the effective
//!   masses along the normal and the tangent, the impulses inherited from
//!   the last step, and the normal velocity before the solve (for
//!   restitution);
//! - **warm start** (each substep): apply the accumulated impulses;
//! - **solve** (each substep, with the soft bias) and **relax** (each
//!   substep, without): sequential impulses on every point, the normal
//!   impulse clamped ≥ 0; friction, clamped to the Coulomb cone
//!   |λt| ≤ μ λn, in the relax pass (Box2D v3.2's order: the friction of a
//!   point is solved against its final normal impulse of the substep);
//! - **restitution** (once, after the substeps): a point that approached
//!   faster than the threshold and pushed gets the normal velocity
//!   −e × its approach speed;
//! - **store**: impulses back into the contacts for the next step.
//!
//! The current separation of a point inside the substeps comes from the
//! bodies' motion since the step began, not from collision:
//! s = s0 + n·(Δp_B + R(Δθ_B) r_B − Δp_A − R(Δθ_A) r_A) − n·(r_B − r_A),
//! with the normal and the anchors fixed for the step (Box2D v3's). A
//! circle's point is the exception: the point of a circle facing the other
//! shape is the one along the normal from its centre, whatever the circle's
//! turn, so its part of the separation follows the centre, at the distance
//! k along the normal from the point ([`ContactConstraint::centre_depth`]):
//! R(Δθ) r turned about the centre instead, which subtracts
//! k (1 − cos Δθ) per circle. Box2D turns the point with the body: a disc
//! rolling at ω opens its contact by r (1 − cos ωt) within a step (0.5 mm
//! for a 0.1 m disc at 6 rad/s and dt = 1/60 s), so the soft contact lets
//! it sink by about that much and pushes it back at the next step, a
//! bump per step which a rolling disc feels as drag and, where a new
//! contact begins, as a loss of speed (docs/cases.md#bowl).
//!
//! The solve is matrix-free: each point's effective mass is a scalar, and
//! the constraints are visited in order (projected Gauss–Seidel), so the
//! cost is linear in the number of points and nothing is allocated.
//!
//! This is the reference implementation, one constraint at a time. The
//! step runs it on the overflow of the colouring (constraints that found
//! no colour, usually none); the coloured constraints go through
//! [`super::wide_solver`], which applies these same formulas, in the same
//! order of operations, to four constraints at once and is tested to give
//! the same bits.

use super::bodies::SolverBody;
use super::contacts::{Contact, ContactPoint};
use super::softness::Softness;
use crate::shape::cross;
use nalgebra::Vector2;

/// A point of a constraint.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct ConstraintPoint {
    /// Anchors from each centre of mass, fixed for the step (m).
    pub ra: Vector2<f64>,
    pub rb: Vector2<f64>,
    /// Separation minus n·(r_B − r_A) at the step's start (m).
    pub base_separation: f64,
    /// 1 / (effective mass along the normal) inverted: kg.
    pub normal_mass: f64,
    /// Effective mass along the tangent (kg).
    pub tangent_mass: f64,
    /// Accumulated impulses (N·s).
    pub normal_impulse: f64,
    pub tangent_impulse: f64,
    /// Sum of the normal impulses applied this step (N·s).
    pub total_normal_impulse: f64,
    /// Normal velocity before the solve (m/s), for restitution.
    pub normal_velocity: f64,
}

/// The constraint of one touching contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ContactConstraint {
    /// Solver indices of the two bodies (0: static).
    pub a: usize,
    pub b: usize,
    /// Index of the contact in the contact set.
    pub contact: usize,
    /// Unit normal from A to B (world).
    pub normal: Vector2<f64>,
    pub friction: f64,
    pub restitution: f64,
    pub inv_mass_a: f64,
    pub inv_inertia_a: f64,
    pub inv_mass_b: f64,
    pub inv_inertia_b: f64,
    pub softness: Softness,
    /// The largest speed (m/s) at which the bias pushes this contact's
    /// overlapping points apart: the settings' push-out speed, shared
    /// among the deep contacts of a body that has several
    /// ([`super::prepare`]).
    pub push_out: f64,
    /// Speed of the surfaces along the tangent (m/s): friction drives the
    /// relative tangential velocity to it instead of 0 (a conveyor belt).
    pub tangent_speed: f64,
    /// Rolling resistance (m): the largest rolling torque impulse is this
    /// times the normal impulse.
    pub rolling_resistance: f64,
    /// 1/(1/I_A + 1/I_B) (kg·m²), the effective mass of the relative
    /// rotation.
    pub rolling_mass: f64,
    /// Accumulated rolling-resistance angular impulse (N·m·s).
    pub rolling_impulse: f64,
    /// For a circle on side A (B), the distance (m) along the normal from
    /// the point to its centre, else 0 ([`super::contacts::Contact::centre_depth`]).
    pub centre_depth: [f64; 2],
    pub count: usize,
    pub points: [ConstraintPoint; 2],
}

/// ω × r for a scalar ω.
#[inline(always)]
fn cross_sv(w: f64, r: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-w * r.y, w * r.x)
}

/// The inverse masses and solver indices of a contact's two bodies.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairMass {
    pub a: usize,
    pub b: usize,
    pub inv_mass_a: f64,
    pub inv_inertia_a: f64,
    pub inv_mass_b: f64,
    pub inv_inertia_b: f64,
}

/// The per-step quantities of point `p` of a contact whose unit normal
/// (A to B) is `normal`, between bodies of inverse masses `mass` whose
/// solver records are `(ba, bb)`: its anchors, its separation less
/// n·(r_B − r_A) (m), its effective masses (kg), the impulses inherited
/// from the last step scaled by `warm` (N·s) and its normal velocity
/// (m/s). The formulas of both solvers' prepare ([`prepare`] and
/// [`super::wide_solver::prepare_lane`]), written once so that a lane and
/// the scalar constraint hold the same bits.
#[inline(always)]
pub(crate) fn prepare_point(
    p: &ContactPoint,
    normal: Vector2<f64>,
    mass: &PairMass,
    (ba, bb): (&SolverBody, &SolverBody),
    warm: f64,
) -> ConstraintPoint {
    let tangent = Vector2::new(normal.y, -normal.x);
    let (ma, ia, mb, ib) = (
        mass.inv_mass_a,
        mass.inv_inertia_a,
        mass.inv_mass_b,
        mass.inv_inertia_b,
    );
    let (ra, rb) = (p.anchor_a, p.anchor_b);
    let (rna, rnb) = (cross(ra, normal), cross(rb, normal));
    let k_normal = ma + mb + ia * rna * rna + ib * rnb * rnb;
    let (rta, rtb) = (cross(ra, tangent), cross(rb, tangent));
    let k_tangent = ma + mb + ia * rta * rta + ib * rtb * rtb;
    let vra = ba.v + cross_sv(ba.w, ra);
    let vrb = bb.v + cross_sv(bb.w, rb);
    ConstraintPoint {
        ra,
        rb,
        base_separation: p.separation - (rb - ra).dot(&normal),
        normal_mass: if k_normal > 0.0 { 1.0 / k_normal } else { 0.0 },
        tangent_mass: if k_tangent > 0.0 {
            1.0 / k_tangent
        } else {
            0.0
        },
        normal_impulse: warm * p.normal_impulse,
        tangent_impulse: warm * p.tangent_impulse,
        total_normal_impulse: 0.0,
        normal_velocity: normal.dot(&(vrb - vra)),
    }
}

/// The rolling resistance's effective mass, 1/(1/I_A + 1/I_B) (kg·m²),
/// of a contact with rolling resistance `rolling_resistance` (m) between
/// bodies of inverse inertias `ia` and `ib` (1/(kg·m²)); 0 without
/// rolling resistance (only read with it: no division otherwise) or when
/// neither body turns.
#[inline(always)]
pub(crate) fn rolling_mass(rolling_resistance: f64, ia: f64, ib: f64) -> f64 {
    if rolling_resistance > 0.0 && ia + ib > 0.0 {
        1.0 / (ia + ib)
    } else {
        0.0
    }
}

/// Builds the constraint of `contact` (with its points) for a step, with
/// warm-starting impulses scaled by `warm` (1 on, 0 off) and the soft bias
/// bounded by `push_out` (m/s).
pub(crate) fn prepare(
    contact: &Contact,
    index: usize,
    mass: PairMass,
    (softness, push_out): (Softness, f64),
    bodies: &[SolverBody],
    warm: f64,
) -> ContactConstraint {
    let normal = contact.normal;
    let pair = (&bodies[mass.a], &bodies[mass.b]);
    let mut points = [ConstraintPoint::default(); 2];
    for (cp, p) in points.iter_mut().zip(&contact.points[..contact.count]) {
        *cp = prepare_point(p, normal, &mass, pair, warm);
    }
    ContactConstraint {
        a: mass.a,
        b: mass.b,
        contact: index,
        normal,
        friction: contact.friction,
        restitution: contact.restitution,
        inv_mass_a: mass.inv_mass_a,
        inv_inertia_a: mass.inv_inertia_a,
        inv_mass_b: mass.inv_mass_b,
        inv_inertia_b: mass.inv_inertia_b,
        softness,
        push_out,
        tangent_speed: contact.tangent_speed,
        rolling_resistance: contact.rolling_resistance,
        rolling_mass: rolling_mass(
            contact.rolling_resistance,
            mass.inv_inertia_a,
            mass.inv_inertia_b,
        ),
        rolling_impulse: warm * contact.rolling_impulse,
        centre_depth: contact.centre_depth,
        count: contact.count,
        points,
    }
}

/// Reads two bodies; `a == b` cannot happen (a pair is two bodies, and a
/// static one is index 0 only on one side).
#[inline(always)]
fn load(bodies: &[SolverBody], a: usize, b: usize) -> (SolverBody, SolverBody) {
    (bodies[a], bodies[b])
}

/// Writes back the velocities; the static body at index 0 keeps its zero
/// velocity (its inverse masses are 0, so nothing changed it).
#[inline(always)]
fn store(bodies: &mut [SolverBody], c: &ContactConstraint, va: SolverBody, vb: SolverBody) {
    bodies[c.a].v = va.v;
    bodies[c.a].w = va.w;
    bodies[c.b].v = vb.v;
    bodies[c.b].w = vb.w;
}

/// Applies every constraint's accumulated impulses.
#[inline(never)]
pub(crate) fn warm_start(constraints: &mut [ContactConstraint], bodies: &mut [SolverBody]) {
    for c in constraints.iter_mut() {
        let (mut a, mut b) = load(bodies, c.a, c.b);
        let tangent = Vector2::new(c.normal.y, -c.normal.x);
        for cp in &mut c.points[..c.count] {
            let p = cp.normal_impulse * c.normal + cp.tangent_impulse * tangent;
            cp.total_normal_impulse += cp.normal_impulse;
            a.w -= c.inv_inertia_a * cross(cp.ra, p);
            a.v -= c.inv_mass_a * p;
            b.w += c.inv_inertia_b * cross(cp.rb, p);
            b.v += c.inv_mass_b * p;
        }
        if c.rolling_impulse != 0.0 {
            a.w -= c.inv_inertia_a * c.rolling_impulse;
            b.w += c.inv_inertia_b * c.rolling_impulse;
        }
        store(bodies, c, a, b);
    }
}

/// One pass of sequential impulses. With `use_bias` the soft bias pushes
/// overlapping points apart (at most each constraint's `push_out`, m/s); without it
/// (relax) the pass removes the bias velocity and solves friction.
/// Speculative points (s > 0) may close their gap in one substep of
/// length 1/`inv_h` and no more.
#[inline(never)]
pub(crate) fn solve(
    constraints: &mut [ContactConstraint],
    bodies: &mut [SolverBody],
    inv_h: f64,
    use_bias: bool,
) {
    for c in constraints.iter_mut() {
        let (mut a, mut b) = load(bodies, c.a, c.b);
        let (ma, ia, mb, ib) = (c.inv_mass_a, c.inv_inertia_a, c.inv_mass_b, c.inv_inertia_b);
        let normal = c.normal;
        let dp = b.dp - a.dp;
        // A circle's facing point does not turn with it: 0 for other shapes.
        let [ka, kb] = c.centre_depth;
        let unturned = kb * (1.0 - b.dq[0]) + ka * (1.0 - a.dq[0]);
        let (bias_rate, mass_scale, impulse_scale) = if use_bias {
            let s = c.softness;
            (s.mass_scale * s.bias_rate, s.mass_scale, s.impulse_scale)
        } else {
            (0.0, 1.0, 0.0)
        };
        for cp in &mut c.points[..c.count] {
            // Current separation from the motion since the step began.
            let ds = dp + b.rotate(cp.rb) - a.rotate(cp.ra);
            let s = cp.base_separation + ds.dot(&normal) - unturned;
            let (bias, point_mass_scale, point_impulse_scale) = if s > 0.0 {
                (s * inv_h, 1.0, 0.0)
            } else {
                ((bias_rate * s).max(-c.push_out), mass_scale, impulse_scale)
            };
            let vra = a.v + cross_sv(a.w, cp.ra);
            let vrb = b.v + cross_sv(b.w, cp.rb);
            let vn = (vrb - vra).dot(&normal);
            let impulse = -cp.normal_mass * (point_mass_scale * vn + bias)
                - point_impulse_scale * cp.normal_impulse;
            let accumulated = (cp.normal_impulse + impulse).max(0.0);
            let impulse = accumulated - cp.normal_impulse;
            cp.normal_impulse = accumulated;
            cp.total_normal_impulse += impulse;
            let p = impulse * normal;
            a.v -= ma * p;
            a.w -= ia * cross(cp.ra, p);
            b.v += mb * p;
            b.w += ib * cross(cp.rb, p);
        }
        if !use_bias {
            let tangent = Vector2::new(normal.y, -normal.x);
            for cp in &mut c.points[..c.count] {
                let vra = a.v + cross_sv(a.w, cp.ra);
                let vrb = b.v + cross_sv(b.w, cp.rb);
                // Relative to the surfaces' own tangent speed (Box2D's).
                let vt = (vrb - vra).dot(&tangent) - c.tangent_speed;
                let max_friction = c.friction * cp.normal_impulse;
                let accumulated =
                    (cp.tangent_impulse - cp.tangent_mass * vt).clamp(-max_friction, max_friction);
                let impulse = accumulated - cp.tangent_impulse;
                cp.tangent_impulse = accumulated;
                let p = impulse * tangent;
                a.v -= ma * p;
                a.w -= ia * cross(cp.ra, p);
                b.v += mb * p;
                b.w += ib * cross(cp.rb, p);
            }
            if c.rolling_resistance > 0.0 {
                // Box2D v3's rolling resistance: a torque impulse opposing
                // the relative rotation, at most the rolling resistance
                // times the pair's normal impulse.
                let normal: f64 = c.points[..c.count].iter().map(|p| p.normal_impulse).sum();
                let max = c.rolling_resistance * normal;
                let old = c.rolling_impulse;
                c.rolling_impulse = (old - c.rolling_mass * (b.w - a.w)).clamp(-max, max);
                let delta = c.rolling_impulse - old;
                a.w -= ia * delta;
                b.w += ib * delta;
            }
        }
        store(bodies, c, a, b);
    }
}

/// The restitution pass: every point that approached faster than
/// `threshold` (m/s) before the solve and pushed during it gets the normal
/// velocity −e × its approach speed (the impulse stays ≥ 0).
#[inline(never)]
pub(crate) fn restitution(
    constraints: &mut [ContactConstraint],
    bodies: &mut [SolverBody],
    threshold: f64,
) {
    for c in constraints.iter_mut() {
        if c.restitution == 0.0 {
            continue;
        }
        let (mut a, mut b) = load(bodies, c.a, c.b);
        let normal = c.normal;
        for cp in &mut c.points[..c.count] {
            if cp.normal_velocity > -threshold || cp.total_normal_impulse == 0.0 {
                continue;
            }
            let vra = a.v + cross_sv(a.w, cp.ra);
            let vrb = b.v + cross_sv(b.w, cp.rb);
            let vn = (vrb - vra).dot(&normal);
            let impulse = -cp.normal_mass * (vn + c.restitution * cp.normal_velocity);
            let accumulated = (cp.normal_impulse + impulse).max(0.0);
            let impulse = accumulated - cp.normal_impulse;
            cp.normal_impulse = accumulated;
            cp.total_normal_impulse += impulse;
            let p = impulse * normal;
            a.v -= c.inv_mass_a * p;
            a.w -= c.inv_inertia_a * cross(cp.ra, p);
            b.v += c.inv_mass_b * p;
            b.w += c.inv_inertia_b * cross(cp.rb, p);
        }
        store(bodies, c, a, b);
    }
}

/// Copies the impulses back into the contacts, for the next step's warm
/// start and for the reports.
#[inline(never)]
pub(crate) fn store_impulses(constraints: &[ContactConstraint], contacts: &mut [Contact]) {
    for c in constraints {
        let contact = &mut contacts[c.contact];
        for (p, cp) in contact.points.iter_mut().zip(&c.points[..c.count]) {
            p.normal_impulse = cp.normal_impulse;
            p.tangent_impulse = cp.tangent_impulse;
            p.total_normal_impulse = cp.total_normal_impulse;
            p.normal_velocity = cp.normal_velocity;
        }
        contact.rolling_impulse = c.rolling_impulse;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pair(inv_mass_b: f64) -> PairMass {
        PairMass {
            a: 0,
            b: 1,
            inv_mass_a: 0.0,
            inv_inertia_a: 0.0,
            inv_mass_b,
            inv_inertia_b: 0.0,
        }
    }

    fn contact_with(separation: f64) -> Contact {
        let mut set = super::super::contacts::ContactSet::default();
        let mut material = super::super::contacts::tests::material();
        material.friction = 0.0;
        set.create((0, 1), (0, 1), material, false);
        let mut c = set.contacts.pop().unwrap();
        c.normal = Vector2::y();
        c.count = 1;
        c.points[0].separation = separation;
        c.touching = true;
        c
    }

    #[test]
    fn a_rigid_solve_stops_a_falling_point_exactly() {
        // A particle (no rotation) falling at 2 m/s onto the ground with no
        // overlap: one rigid pass gives it zero normal velocity, and the
        // impulse is m·v.
        let mut bodies = vec![SolverBody::AT_REST, SolverBody::AT_REST];
        bodies[1].v = Vector2::new(0.0, -2.0);
        let mut c = [prepare(
            &contact_with(0.0),
            0,
            pair(0.5),
            (Softness::RIGID, 3.0),
            &bodies,
            1.0,
        )];
        solve(&mut c, &mut bodies, 240.0, false);
        assert!(bodies[1].v.y.abs() < 1e-15);
        assert!((c[0].points[0].normal_impulse - 4.0).abs() < 1e-15);
        assert_eq!(bodies[0], SolverBody::AT_REST);
    }

    #[test]
    fn a_speculative_point_lets_the_gap_close_in_one_substep() {
        // 1 cm apart, approaching at 10 m/s, substep 1/240 s: the solver
        // lets it come 1 cm closer and no more, so v_n = −s/h = −2.4 m/s.
        let mut bodies = vec![SolverBody::AT_REST, SolverBody::AT_REST];
        bodies[1].v = Vector2::new(0.0, -10.0);
        let mut c = [prepare(
            &contact_with(0.01),
            0,
            pair(1.0),
            (Softness::RIGID, 3.0),
            &bodies,
            1.0,
        )];
        solve(&mut c, &mut bodies, 240.0, true);
        assert!((bodies[1].v.y + 2.4).abs() < 1e-12, "{}", bodies[1].v.y);
    }

    #[test]
    fn the_push_out_speed_bounds_the_soft_bias() {
        // 10 cm deep, at rest, stiff spring: the bias alone would push far
        // faster than 3 m/s; the clamp holds it to 3 m/s (times the mass
        // scale).
        let mut bodies = vec![SolverBody::AT_REST, SolverBody::AT_REST];
        let soft = Softness::new(1000.0, 1.0, 1.0 / 240.0);
        let mut c = [prepare(
            &contact_with(-0.1),
            0,
            pair(1.0),
            (soft, 3.0),
            &bodies,
            1.0,
        )];
        solve(&mut c, &mut bodies, 240.0, true);
        assert!((bodies[1].v.y - 3.0).abs() < 1e-12, "{}", bodies[1].v.y);
    }

    #[test]
    fn restitution_reflects_the_approach_speed() {
        let mut bodies = vec![SolverBody::AT_REST, SolverBody::AT_REST];
        bodies[1].v = Vector2::new(0.0, -5.0);
        let mut contact = contact_with(0.0);
        contact.restitution = 0.8;
        let mut c = [prepare(
            &contact,
            0,
            pair(1.0),
            (Softness::RIGID, 3.0),
            &bodies,
            1.0,
        )];
        solve(&mut c, &mut bodies, 240.0, true);
        restitution(&mut c, &mut bodies, 1.0);
        assert!((bodies[1].v.y - 4.0).abs() < 1e-12, "{}", bodies[1].v.y);
        // Below the threshold nothing bounces.
        bodies[1].v = Vector2::new(0.0, -0.5);
        let mut c = [prepare(
            &contact,
            0,
            pair(1.0),
            (Softness::RIGID, 3.0),
            &bodies,
            1.0,
        )];
        solve(&mut c, &mut bodies, 240.0, true);
        restitution(&mut c, &mut bodies, 1.0);
        assert!(bodies[1].v.y.abs() < 1e-15);
    }

    #[test]
    fn friction_holds_within_the_cone_and_slides_outside_it() {
        // A particle pressed on the ground by an impulse of 1 N·s and moving
        // sideways: friction can take at most mu × 1 N·s of momentum.
        for (mu, vx, expected) in [(0.5, 0.3, 0.0), (0.5, 2.0, 1.5)] {
            let mut bodies = vec![SolverBody::AT_REST, SolverBody::AT_REST];
            bodies[1].v = Vector2::new(vx, -1.0);
            let mut contact = contact_with(0.0);
            contact.friction = mu;
            let mut c = [prepare(
                &contact,
                0,
                pair(1.0),
                (Softness::RIGID, 3.0),
                &bodies,
                1.0,
            )];
            solve(&mut c, &mut bodies, 240.0, false);
            assert!(
                (bodies[1].v.x - expected).abs() < 1e-15,
                "mu {mu} vx {vx}: {}",
                bodies[1].v.x
            );
        }
    }
}
