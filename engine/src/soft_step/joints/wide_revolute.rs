//! Revolute joints eight at a time, as the contacts are
//! ([`crate::soft_step::wide_solver`]): the joints of one colour (the
//! joints' own colouring, [`crate::soft_step::colouring`]) share no dynamic
//! body, so eight of them are packed side by side, one per lane of
//! [`F64x8`], and warm started, solved and relaxed at once (four and four
//! without AVX-512).
//!
//! The formulas and their order of operations are those of the scalar
//! solver, [`super::revolute`] (its `warm_start` and `solve`, with the
//! helpers of [`super::frame`]), the reference: a lane gives the same bits
//! as the scalar code on the same joint, and solving a colour here gives
//! what solving its joints one after the other would give (tested below).
//! The optional rows (spring, motor, limits) are computed in every lane
//! and kept only in the lanes whose joint has them, by a blend of the old
//! and new values, so a lane without them is left exactly as the scalar
//! code leaves it; a record none of whose joints has one skips them.
//!
//! Layout: [`WideRevolute`] holds what the point rows read and write
//! (the bodies, masses, anchors, the centres' distance, the rigid rows'
//! softness, the point impulse: 1088 bytes per eight joints, 136 per joint
//! against the 336 of a joint's scalar record); [`WideAxial`], beside it,
//! the angle rows' parameters and impulses, read only by the records that
//! have some. Padding lanes join the static dummy body to itself with zero
//! masses and change nothing.

use super::frame::{JointFrame, RowScale};
use super::revolute::RevoluteRows;
use super::wrap_angle;
use crate::soft_step::bodies::SolverBody;
use crate::soft_step::lanes::{F64x8, LANES, Lanes, dispatch};
use crate::soft_step::wide_solver::{Bodies, WideBody, gather, gather_motion, lane_index, scatter};

/// Four revolute joints' point rows: what every pass reads.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct WideRevolute {
    /// Solver indices of the bodies (0: the static dummy or the world),
    /// with the `FIXED` bit for a body the lane does not move.
    pub a: [u32; LANES],
    pub b: [u32; LANES],
    /// Whether a lane's joint has a spring, a motor or limits (then the
    /// passes read this record's [`WideAxial`]).
    pub axial: bool,
    /// Inverse masses (1/kg) and inertias (1/(kg·m²)).
    ma: F64x8,
    ia: F64x8,
    mb: F64x8,
    ib: F64x8,
    /// Anchors from each centre of mass at the step's start, world frame
    /// (m).
    ra_x: F64x8,
    ra_y: F64x8,
    rb_x: F64x8,
    rb_y: F64x8,
    /// c_B − c_A at the step's start (m).
    dc_x: F64x8,
    dc_y: F64x8,
    /// The rigid rows' coefficients in the solve pass ([`RowScale::soft`]
    /// of the joint's softness).
    bias_rate: F64x8,
    mass_scale: F64x8,
    impulse_scale: F64x8,
    /// Accumulated point impulse (N·s).
    linear_x: F64x8,
    linear_y: F64x8,
}

/// Four revolute joints' angle rows: spring, motor, limits.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct WideAxial {
    /// θB − θA − θref at the step's start (rad).
    angle: F64x8,
    /// 1/(i_A + i_B).
    axial_mass: F64x8,
    /// 1 where the joint has the row and its bodies turn, else 0.
    spring_on: F64x8,
    motor_on: F64x8,
    limits_on: F64x8,
    /// The spring's coefficients ([`RowScale::soft`]) and rest angle
    /// (rad).
    spring_bias_rate: F64x8,
    spring_mass_scale: F64x8,
    spring_impulse_scale: F64x8,
    spring_target: F64x8,
    /// The motor's speed (rad/s) and largest impulse per substep, h τ_max
    /// (N·m·s).
    motor_speed: F64x8,
    motor_max: F64x8,
    /// The limits (rad).
    lower: F64x8,
    upper: F64x8,
    /// Accumulated impulses (N·m·s).
    spring: F64x8,
    motor: F64x8,
    lower_impulse: F64x8,
    upper_impulse: F64x8,
}

// The size the module documentation gives.
const _: () = assert!(std::mem::size_of::<WideRevolute>() == 1088);

/// Writes joint (`frame`, `rows`), prepared for substeps of `h` (s), into
/// lane `l` of `(w, x)`, every field of the lane (the caller clears
/// `w.axial` before the step's first lane of the record). The angle rows
/// are written once the record has a joint with one: its first such joint
/// zeroes the four lanes of `x` (no rows, no impulses: what the plain
/// joints before it in the record have, since only a row changes its
/// impulse), so a record of plain joints (a joint grid's) never writes
/// `x`.
#[inline]
pub(crate) fn set_lane(
    (w, x): (&mut WideRevolute, &mut WideAxial),
    l: usize,
    (frame, rows): (&JointFrame, &RevoluteRows),
    h: f64,
) {
    // A body with zero inverse mass and inertia (the world, the static
    // dummy, a kinematic body) is read but never written back, as in the
    // contacts' lanes (`lane_index`).
    w.a[l] = lane_index(frame.a, frame.ma, frame.ia);
    w.b[l] = lane_index(frame.b, frame.mb, frame.ib);
    w.ma.set_lane(l, frame.ma);
    w.ia.set_lane(l, frame.ia);
    w.mb.set_lane(l, frame.mb);
    w.ib.set_lane(l, frame.ib);
    w.ra_x.set_lane(l, frame.ra.x);
    w.ra_y.set_lane(l, frame.ra.y);
    w.rb_x.set_lane(l, frame.rb.x);
    w.rb_y.set_lane(l, frame.rb.y);
    w.dc_x.set_lane(l, frame.delta_center.x);
    w.dc_y.set_lane(l, frame.delta_center.y);
    let rigid = RowScale::soft(&frame.softness);
    w.bias_rate.set_lane(l, rigid.bias_rate);
    w.mass_scale.set_lane(l, rigid.mass_scale);
    w.impulse_scale.set_lane(l, rigid.impulse_scale);
    w.linear_x.set_lane(l, rows.linear.x);
    w.linear_y.set_lane(l, rows.linear.y);
    let joint = &rows.joint;
    if joint.spring.is_some() || joint.motor.is_some() || joint.limits.is_some() {
        if !w.axial {
            *x = WideAxial::default();
        }
        w.axial = true;
    }
    if !w.axial {
        return;
    }
    let turns = !frame.fixed_rotation();
    let flag = |on: bool| if on && turns { 1.0 } else { 0.0 };
    x.angle.set_lane(l, frame.angle);
    x.axial_mass.set_lane(l, rows.axial_mass);
    x.spring_on.set_lane(l, flag(joint.spring.is_some()));
    x.motor_on.set_lane(l, flag(joint.motor.is_some()));
    x.limits_on.set_lane(l, flag(joint.limits.is_some()));
    let spring = RowScale::soft(&rows.spring_softness);
    x.spring_bias_rate.set_lane(l, spring.bias_rate);
    x.spring_mass_scale.set_lane(l, spring.mass_scale);
    x.spring_impulse_scale.set_lane(l, spring.impulse_scale);
    x.spring_target.set_lane(l, joint.spring_target);
    let (speed, max) = joint
        .motor
        .map_or((0.0, 0.0), |m| (m.speed, h * m.max_torque));
    x.motor_speed.set_lane(l, speed);
    x.motor_max.set_lane(l, max);
    let (lower, upper) = joint.limits.unwrap_or((0.0, 0.0));
    x.lower.set_lane(l, lower);
    x.upper.set_lane(l, upper);
    x.spring.set_lane(l, rows.spring);
    x.motor.set_lane(l, rows.motor);
    x.lower_impulse.set_lane(l, rows.lower);
    x.upper_impulse.set_lane(l, rows.upper);
}

/// Makes lane `l` of `(w, x)` padding: the static dummy joined to itself,
/// zero masses and impulses, no angle rows.
pub(crate) fn set_padding_lane((w, x): (&mut WideRevolute, &mut WideAxial), l: usize) {
    let rows = RevoluteRows::new(super::Revolute::default());
    let frame = JointFrame::EMPTY;
    // No spring, motor or limits: the record's axial rows are left as
    // its other lanes set them.
    set_lane((w, x), l, (&frame, &rows), 0.0);
}

/// Copies the impulses of lane `l` of `(w, x)` back into `rows`.
#[inline]
pub(crate) fn store_lane((w, x): (&WideRevolute, &WideAxial), l: usize, rows: &mut RevoluteRows) {
    rows.linear.x = w.linear_x.lane(l);
    rows.linear.y = w.linear_y.lane(l);
    if w.axial {
        rows.spring = x.spring.lane(l);
        rows.motor = x.motor.lane(l);
        rows.lower = x.lower_impulse.lane(l);
        rows.upper = x.upper_impulse.lane(l);
    }
}

/// The anchors now, r turned by each body's rotation since the step began
/// (as [`SolverBody::rotate`]; `motion_a`, `motion_b` the bodies' second
/// rows, `[Δp.y, Δθ, cos Δθ, sin Δθ]`): (r_Ax, r_Ay, r_Bx, r_By).
#[inline(always)]
fn anchors<L: Lanes>(
    (w, g): (&WideRevolute, usize),
    (motion_a, motion_b): (&[L; 4], &[L; 4]),
) -> [L; 4] {
    let (ca, sa) = (motion_a[2], motion_a[3]);
    let (cb, sb) = (motion_b[2], motion_b[3]);
    let (rax, ray) = (L::load(&w.ra_x, g), L::load(&w.ra_y, g));
    let (rbx, rby) = (L::load(&w.rb_x, g), L::load(&w.rb_y, g));
    [
        ca * rax - sa * ray,
        sa * rax + ca * ray,
        cb * rbx - sb * rby,
        sb * rbx + cb * rby,
    ]
}

/// The inverse masses of a group of joints' bodies: (m_A, i_A, m_B, i_B).
#[inline(always)]
fn masses<L: Lanes>(w: &WideRevolute, g: usize) -> [L; 4] {
    [
        L::load(&w.ma, g),
        L::load(&w.ia, g),
        L::load(&w.mb, g),
        L::load(&w.ib, g),
    ]
}

/// Applies the impulse `(px, py)` at the anchors and the angular impulse
/// `l`: −P on A, +P on B (as [`JointFrame::apply`]).
#[inline(always)]
fn apply<L: Lanes>(
    [ma, ia, mb, ib]: [L; 4],
    (a, b): (&mut WideBody<L>, &mut WideBody<L>),
    [rax, ray, rbx, rby]: [L; 4],
    (px, py): (L, L),
    l: L,
) {
    a.vx -= ma * px;
    a.vy -= ma * py;
    a.w -= ia * ((rax * py - ray * px) + l);
    b.vx += mb * px;
    b.vy += mb * py;
    b.w += ib * ((rbx * py - rby * px) + l);
}

/// Applies the angular impulse `d` (−d on A, +d on B) in the lanes of
/// `on` only.
#[inline(always)]
fn apply_angular<L: Lanes>(
    (ia, ib): (L, L),
    (a, b): (&mut WideBody<L>, &mut WideBody<L>),
    d: L,
    on: L::Mask,
) {
    a.w = L::select(on, a.w - ia * d, a.w);
    b.w = L::select(on, b.w + ib * d, b.w);
}

/// Applies every joint's accumulated impulses.
pub(crate) fn warm_start(records: &[WideRevolute], axial: &[WideAxial], bodies: &mut [SolverBody]) {
    warm_start_shared(records, axial, Bodies::new(bodies));
}

/// [`warm_start`] of `records` on bodies shared with other threads, which
/// write none of the bodies these records move (the records of one colour,
/// split among the threads).
#[inline(never)]
pub(crate) fn warm_start_shared(records: &[WideRevolute], axial: &[WideAxial], bodies: Bodies<'_>) {
    dispatch!(warm_start_with, warm_start_avx512, warm_start_avx, (records: &[WideRevolute], axial: &[WideAxial], bodies: Bodies<'_>));
}

#[inline(always)]
fn warm_start_with<L: Lanes>(records: &[WideRevolute], axial: &[WideAxial], bodies: Bodies<'_>) {
    for (w, x) in records.iter().zip(axial) {
        for g in 0..L::GROUPS {
            let (mut a, mut b) = (gather::<L>(bodies, &w.a, g), gather::<L>(bodies, &w.b, g));
            let motion = (
                gather_motion(bodies, &w.a, g),
                gather_motion(bodies, &w.b, g),
            );
            let r = anchors::<L>((w, g), (&motion.0, &motion.1));
            // The scalar joint's spring + motor + lower − upper, all 0 without
            // angle rows.
            let l = if w.axial {
                ((L::load(&x.spring, g) + L::load(&x.motor, g)) + L::load(&x.lower_impulse, g))
                    - L::load(&x.upper_impulse, g)
            } else {
                L::splat(0.0)
            };
            let p = (L::load(&w.linear_x, g), L::load(&w.linear_y, g));
            apply(masses(w, g), (&mut a, &mut b), r, p, l);
            scatter(bodies, &w.a, g, &a);
            scatter(bodies, &w.b, g, &b);
        }
    }
}

/// The solve pass, with the rigid rows' soft bias, for substeps of 1/`inv_h`.
pub(crate) fn solve(
    records: &mut [WideRevolute],
    axial: &mut [WideAxial],
    bodies: &mut [SolverBody],
    inv_h: f64,
) {
    solve_shared(records, axial, Bodies::new(bodies), inv_h);
}

/// [`solve`] on shared bodies (as [`warm_start_shared`]).
#[inline(never)]
pub(crate) fn solve_shared(
    records: &mut [WideRevolute],
    axial: &mut [WideAxial],
    bodies: Bodies<'_>,
    inv_h: f64,
) {
    dispatch!(solve_with, solve_avx512, solve_avx, (records: &mut [WideRevolute], axial: &mut [WideAxial], bodies: Bodies<'_>, inv_h: f64));
}

#[inline(always)]
fn solve_with<L: Lanes>(
    records: &mut [WideRevolute],
    axial: &mut [WideAxial],
    bodies: Bodies<'_>,
    inv_h: f64,
) {
    pass::<L, true>(records, axial, bodies, inv_h);
}

/// The relax pass: rigid rows without bias.
pub(crate) fn relax(
    records: &mut [WideRevolute],
    axial: &mut [WideAxial],
    bodies: &mut [SolverBody],
    inv_h: f64,
) {
    relax_shared(records, axial, Bodies::new(bodies), inv_h);
}

/// [`relax`] on shared bodies (as [`warm_start_shared`]).
#[inline(never)]
pub(crate) fn relax_shared(
    records: &mut [WideRevolute],
    axial: &mut [WideAxial],
    bodies: Bodies<'_>,
    inv_h: f64,
) {
    dispatch!(relax_with, relax_avx512, relax_avx, (records: &mut [WideRevolute], axial: &mut [WideAxial], bodies: Bodies<'_>, inv_h: f64));
}

#[inline(always)]
fn relax_with<L: Lanes>(
    records: &mut [WideRevolute],
    axial: &mut [WideAxial],
    bodies: Bodies<'_>,
    inv_h: f64,
) {
    pass::<L, false>(records, axial, bodies, inv_h);
}

/// The coefficients of the rigid rows: soft in the solve pass (`BIAS`),
/// rigid without bias in the relax pass ([`RowScale::rigid_row`]).
#[derive(Clone, Copy)]
struct Row<L> {
    bias_rate: L,
    mass_scale: L,
    impulse_scale: L,
}

/// One pass over the joints, a group of lanes at a time.
#[inline(always)]
fn pass<L: Lanes, const BIAS: bool>(
    records: &mut [WideRevolute],
    axial: &mut [WideAxial],
    bodies: Bodies<'_>,
    inv_h: f64,
) {
    let inv_h = L::splat(inv_h);
    let (zero, one) = (L::splat(0.0), L::splat(1.0));
    for (w, x) in records.iter_mut().zip(axial.iter_mut()) {
        for g in 0..L::GROUPS {
            let (mut a, mut b) = (gather::<L>(bodies, &w.a, g), gather::<L>(bodies, &w.b, g));
            let (motion_a, motion_b) = (
                gather_motion::<L>(bodies, &w.a, g),
                gather_motion(bodies, &w.b, g),
            );
            let r = anchors::<L>((w, g), (&motion_a, &motion_b));
            // Δp_B − Δp_A and Δθ_B − Δθ_A since the step began.
            let delta = if BIAS {
                (b.dpx - a.dpx, motion_b[0] - motion_a[0])
            } else {
                (zero, zero)
            };
            let turned = if w.axial {
                motion_b[1] - motion_a[1]
            } else {
                zero
            };
            let m = masses::<L>(w, g);
            let row = if BIAS {
                Row {
                    bias_rate: L::load(&w.bias_rate, g),
                    mass_scale: L::load(&w.mass_scale, g),
                    impulse_scale: L::load(&w.impulse_scale, g),
                }
            } else {
                Row {
                    bias_rate: zero,
                    mass_scale: one,
                    impulse_scale: zero,
                }
            };
            if w.axial {
                angle_rows::<L, BIAS>((x, g), (&mut a, &mut b), (m[1], m[3]), (turned, row, inv_h));
            }
            point_rows::<L, BIAS>((w, g), (&mut a, &mut b), (m, r), (delta, row));
            scatter(bodies, &w.a, g, &a);
            scatter(bodies, &w.b, g, &b);
        }
    }
}

/// The spring, motor and limit rows of a group of joints (the scalar
/// [`RevoluteRows::solve`]'s first part), each kept only in the lanes
/// that have it; `turned` is Δθ_B − Δθ_A since the step began.
#[inline(always)]
fn angle_rows<L: Lanes, const BIAS: bool>(
    (x, g): (&mut WideAxial, usize),
    (a, b): (&mut WideBody<L>, &mut WideBody<L>),
    (ia, ib): (L, L),
    (turned, rigid, inv_h): (L, Row<L>, L),
) {
    let zero = L::splat(0.0);
    let k = L::load(&x.axial_mass, g);
    let angle = L::load(&x.angle, g) + turned;
    // Spring.
    let on = L::load(&x.spring_on, g).gt(zero);
    let c = wrap(angle - L::load(&x.spring_target, g));
    let spring = L::load(&x.spring, g);
    let d = -k
        * (L::load(&x.spring_mass_scale, g) * (b.w - a.w) + L::load(&x.spring_bias_rate, g) * c)
        - L::load(&x.spring_impulse_scale, g) * spring;
    L::select(on, spring + d, spring).store(&mut x.spring, g);
    apply_angular((ia, ib), (a, b), d, on);
    // Motor.
    let on = L::load(&x.motor_on, g).gt(zero);
    let max = L::load(&x.motor_max, g);
    let old = L::load(&x.motor, g);
    let new = (old - k * ((b.w - a.w) - L::load(&x.motor_speed, g))).clamp(-max, max);
    L::select(on, new, old).store(&mut x.motor, g);
    apply_angular((ia, ib), (a, b), new - old, on);
    // Limits: lower on ω_B − ω_A, upper on ω_A − ω_B.
    let on = L::load(&x.limits_on, g).gt(zero);
    let d = limit_row::<L, BIAS>(
        (&mut x.lower_impulse, g),
        (k, b.w - a.w, angle - L::load(&x.lower, g)),
        (rigid, inv_h),
        on,
    );
    apply_angular((ia, ib), (a, b), d, on);
    let d = limit_row::<L, BIAS>(
        (&mut x.upper_impulse, g),
        (k, a.w - b.w, L::load(&x.upper, g) - angle),
        (rigid, inv_h),
        on,
    );
    apply_angular((ia, ib), (a, b), -d, on);
}

/// A one-sided limit row (the scalar `frame::limit_row`): speculative
/// while its error `c` is positive, soft in the solve pass, rigid in the
/// relax pass; returns the increment, keeping the accumulated impulse
/// ≥ 0 in the lanes of `on` (the others keep theirs).
#[inline(always)]
fn limit_row<L: Lanes, const BIAS: bool>(
    (impulse, g): (&mut F64x8, usize),
    (mass, cdot, c): (L, L, L),
    (rigid, inv_h): (Row<L>, L),
    on: L::Mask,
) -> L {
    let (zero, one) = (L::splat(0.0), L::splat(1.0));
    let speculative = c.gt(zero);
    let bias_rate = L::select(speculative, inv_h, rigid.bias_rate);
    let mass_scale = L::select(speculative, one, rigid.mass_scale);
    let impulse_scale = L::select(speculative, zero, rigid.impulse_scale);
    let c = if BIAS {
        c
    } else {
        L::select(speculative, c, zero)
    };
    let old = L::load(impulse, g);
    let new = (old + (-mass * (mass_scale * cdot + bias_rate * c) - impulse_scale * old)).max(zero);
    L::select(on, new, old).store(impulse, g);
    new - old
}

/// Each lane wrapped into [−π, π) by the scalar [`wrap_angle`].
#[inline(always)]
fn wrap<L: Lanes>(x: L) -> L {
    x.map(wrap_angle)
}

/// The two point rows of a group of joints (the scalar
/// [`RevoluteRows::solve`]'s second part); `delta` is Δp_B − Δp_A since
/// the step began (used in the solve pass only).
#[inline(always)]
fn point_rows<L: Lanes, const BIAS: bool>(
    (w, g): (&mut WideRevolute, usize),
    (a, b): (&mut WideBody<L>, &mut WideBody<L>),
    (m, r): ([L; 4], [L; 4]),
    ((dx, dy), row): ((L, L), Row<L>),
) {
    let zero = L::splat(0.0);
    let [ma, ia, mb, ib] = m;
    let [rax, ray, rbx, rby] = r;
    // J v: v_B + ω_B × r_B − v_A − ω_A × r_A.
    let cdot_x = (b.vx + -b.w * rby) - (a.vx + -a.w * ray);
    let cdot_y = (b.vy + b.w * rbx) - (a.vy + a.w * rax);
    let (bias_x, bias_y) = if BIAS {
        let sx = (dx + L::load(&w.dc_x, g)) + (rbx - rax);
        let sy = (dy + L::load(&w.dc_y, g)) + (rby - ray);
        (row.bias_rate * sx, row.bias_rate * sy)
    } else {
        (zero, zero)
    };
    let k11 = ((ma + mb) + ray * ray * ia) + rby * rby * ib;
    let k12 = -ray * rax * ia - rby * rbx * ib;
    let k22 = ((ma + mb) + rax * rax * ia) + rbx * rbx * ib;
    let (hx, hy) = (
        row.mass_scale * cdot_x + bias_x,
        row.mass_scale * cdot_y + bias_y,
    );
    let det = k11 * k22 - k12 * k12;
    let singular = det.eq(zero);
    let inv = L::splat(1.0) / det;
    let sol_x = L::select(singular, zero, inv * (k22 * hx - k12 * hy));
    let sol_y = L::select(singular, zero, inv * (k11 * hy - k12 * hx));
    let (lx, ly) = (L::load(&w.linear_x, g), L::load(&w.linear_y, g));
    let d = (
        -sol_x - row.impulse_scale * lx,
        -sol_y - row.impulse_scale * ly,
    );
    (lx + d.0).store(&mut w.linear_x, g);
    (ly + d.1).store(&mut w.linear_y, g);
    apply(m, (a, b), r, d, zero);
}

#[cfg(test)]
mod tests {
    use super::super::{JointSpring, Revolute, RevoluteMotor};
    use super::*;
    use crate::soft_step::Softness;
    use crate::soft_step::colouring::{Colouring, Slot};
    use nalgebra::Vector2;

    use crate::soft_step::lanes::F64x4;
    use crate::soft_step::lanes::tests::lane_type_runs;
    use crate::soft_step::lanes_avx::Avx4;
    use crate::soft_step::lanes_avx512::Avx8;
    use crate::soft_step::test_numbers::Numbers;

    /// Twelve moving bodies and the static dummy; a chain of revolute
    /// joints between neighbours and one to the world per body, with
    /// varied anchors, angles, impulses and options: free joints, springs,
    /// motors, limits (some reached, some not), a spring stretched past π
    /// (its error wraps), and a joint with every option whose bodies
    /// cannot turn (its angle rows are skipped).
    fn scene() -> (Vec<SolverBody>, Vec<(JointFrame, RevoluteRows)>) {
        let mut n = Numbers(11);
        let mut bodies = vec![SolverBody::AT_REST];
        for _ in 0..12 {
            let dtheta = 0.05 * n.next();
            bodies.push(SolverBody {
                v: Vector2::new(n.next(), n.next()),
                w: 2.0 * n.next(),
                dp: Vector2::new(0.01 * n.next(), 0.01 * n.next()),
                dtheta,
                dq: [dtheta.cos(), dtheta.sin()],
            });
        }
        let h = 1.0 / 240.0;
        let mut joints = Vec::new();
        let pairs = (1..12).map(|i| (i, i + 1)).chain((1..13).map(|i| (0, i)));
        for (k, (a, b)) in pairs.enumerate() {
            let world = a == 0;
            let still = k == 1;
            let frame = JointFrame {
                a,
                b,
                ma: if world { 0.0 } else { 1.0 + 0.5 * n.next() },
                ia: if world || still { 0.0 } else { 4.0 + n.next() },
                mb: 0.5 + 0.25 * n.next(),
                ib: if still { 0.0 } else { 3.0 + n.next() },
                ra: Vector2::new(0.5 * n.next(), 0.5 * n.next()),
                rb: Vector2::new(0.5 * n.next(), 0.5 * n.next()),
                delta_center: Vector2::new(0.02 * n.next(), 0.02 * n.next()),
                angle: if k == 6 { 3.1 } else { 0.5 * n.next() },
                softness: Softness::new(60.0, if k % 2 == 0 { 2.0 } else { 0.0 }, h),
            };
            let joint = Revolute {
                limits: (k % 3 != 0).then_some((-0.2 - 0.1 * n.next().abs(), 0.3)),
                motor: (k % 4 == 1).then_some(RevoluteMotor {
                    speed: n.next(),
                    max_torque: 0.5,
                }),
                spring: (k % 5 < 2).then_some(JointSpring::new(5.0, 0.5)),
                spring_target: if k == 6 { -3.1 } else { 0.1 * n.next() },
            };
            let mut rows = RevoluteRows::new(joint);
            let spring = joint.spring.map_or(Softness::RIGID, |s| {
                Softness::new(s.hertz, s.damping_ratio, h)
            });
            rows.prepare(&frame, spring, true);
            // Last step's impulses, of the rows the joint has (the others
            // stay 0: only their rows change them).
            rows.linear = Vector2::new(0.01 * n.next(), 0.01 * n.next());
            let some = |on: bool, x: f64| if on { x } else { 0.0 };
            rows.spring = some(joint.spring.is_some(), 0.001 * n.next());
            rows.motor = some(joint.motor.is_some(), 0.001 * n.next());
            rows.lower = some(joint.limits.is_some(), 0.001 * n.next().abs());
            rows.upper = some(joint.limits.is_some(), 0.001 * n.next().abs());
            if k % 6 == 5 || k >= 19 {
                // A free joint (the last ones: a record without angle rows,
                // checked below).
                rows = RevoluteRows::new(Revolute::default());
                rows.prepare(&frame, Softness::RIGID, true);
            }
            joints.push((frame, rows));
        }
        (bodies, joints)
    }

    #[test]
    fn a_colour_of_revolute_joints_solved_in_lanes_gives_the_bits_of_the_scalar_solver() {
        let (bodies, joints) = scene();
        let h = 1.0 / 240.0;
        let mut colouring = Colouring::default();
        colouring.clear(13);
        for (f, _) in &joints {
            let dynamic = |k: usize| (k != 0).then_some(k);
            colouring.add(dynamic(f.a), dynamic(f.b));
        }
        let records = colouring.finish();
        let mut wide = vec![WideRevolute::default(); records];
        let mut axial = vec![WideAxial::default(); records];
        let mut order = vec![(0, 0); joints.len()];
        for (i, (f, rows)) in joints.iter().enumerate() {
            let Slot::Lane { record, lane } = colouring.slot(i) else {
                unreachable!("no overflow")
            };
            set_lane((&mut wide[record], &mut axial[record]), lane, (f, rows), h);
            order[i] = (record, lane);
        }
        for (record, lane) in colouring.padding() {
            set_padding_lane((&mut wide[record], &mut axial[record]), lane);
        }
        // Both kinds of record are exercised.
        assert!(wide.iter().any(|w| w.axial) && wide.iter().any(|w| !w.axial));
        // The scalar reference, in the lanes' order: record after record,
        // lane after lane.
        let mut by_lane: Vec<usize> = (0..joints.len()).collect();
        by_lane.sort_by_key(|&i| order[i]);
        let mut scalar = joints.clone();
        let mut scalar_bodies = bodies.clone();
        let inv_h = 1.0 / h;
        for _ in 0..3 {
            for pass in 0..3 {
                for &i in &by_lane {
                    let (f, rows) = &mut scalar[i];
                    let (mut a, mut b) = (scalar_bodies[f.a], scalar_bodies[f.b]);
                    match pass {
                        0 => rows.warm_start(f, &mut a, &mut b),
                        _ => rows.solve(f, (&mut a, &mut b), (h, inv_h), pass == 1),
                    }
                    for (index, body) in [(f.a, a), (f.b, b)] {
                        scalar_bodies[index].v = body.v;
                        scalar_bodies[index].w = body.w;
                    }
                }
            }
        }
        // Each lane type (SSE2 on every x86-64 CPU, AVX and AVX-512 where
        // the CPU has them), then the dispatched passes.
        fn passes<L: Lanes>(
            (wide, axial): (&mut [WideRevolute], &mut [WideAxial]),
            bodies: &mut [SolverBody],
            inv_h: f64,
        ) {
            let bodies = Bodies::new(bodies);
            for _ in 0..3 {
                warm_start_with::<L>(wide, axial, bodies);
                solve_with::<L>(wide, axial, bodies, inv_h);
                relax_with::<L>(wide, axial, bodies, inv_h);
            }
        }
        for path in ["SSE2", "AVX", "AVX-512", "dispatched"] {
            if !lane_type_runs(path) {
                continue;
            }
            let (mut wide, mut axial, mut wide_bodies) =
                (wide.clone(), axial.clone(), bodies.clone());
            let records = (&mut wide[..], &mut axial[..]);
            match path {
                "SSE2" => passes::<F64x4>(records, &mut wide_bodies, inv_h),
                "AVX" => passes::<Avx4>(records, &mut wide_bodies, inv_h),
                "AVX-512" => passes::<Avx8>(records, &mut wide_bodies, inv_h),
                _ => {
                    for _ in 0..3 {
                        warm_start(records.0, records.1, &mut wide_bodies);
                        solve(records.0, records.1, &mut wide_bodies, inv_h);
                        relax(records.0, records.1, &mut wide_bodies, inv_h);
                    }
                }
            }
            let bits = |b: &[SolverBody]| -> Vec<[u64; 3]> {
                b.iter()
                    .map(|s| [s.v.x.to_bits(), s.v.y.to_bits(), s.w.to_bits()])
                    .collect()
            };
            assert_eq!(bits(&scalar_bodies), bits(&wide_bodies), "{path}");
            for (i, &(record, lane)) in order.iter().enumerate() {
                let mut rows = joints[i].1;
                store_lane((&wide[record], &axial[record]), lane, &mut rows);
                let impulses = |r: &RevoluteRows| {
                    [r.linear.x, r.linear.y, r.spring, r.motor, r.lower, r.upper].map(f64::to_bits)
                };
                assert_eq!(impulses(&rows), impulses(&scalar[i].1), "joint {i}, {path}");
            }
        }
        // Every option acted somewhere.
        let moved = |f: fn(&RevoluteRows) -> f64| {
            scalar
                .iter()
                .zip(&joints)
                .any(|((_, s), (_, j))| f(s) != f(j))
        };
        assert!(moved(|r| r.spring) && moved(|r| r.motor));
        assert!(moved(|r| r.lower) && moved(|r| r.upper));
    }
}
