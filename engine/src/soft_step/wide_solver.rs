//! The contact solver eight constraints at a time (Box2D v3's SIMD path of
//! `contact_solver.c`, written anew for f64): the constraints of one colour
//! ([`super::colouring`]) share no dynamic body, so eight of them are packed
//! side by side, one per lane of [`F64x8`], and every pass (warm start,
//! solve, relax, restitution) runs on them at once: the eight together
//! with AVX-512, four and four with AVX or SSE2 ([`super::lanes`]).
//!
//! Each pass gathers the two bodies of each lane (velocities, motion since
//! the step began, inverse masses), applies the scalar solver's formulas
//! lane by lane, and scatters the velocities back. The formulas and their
//! order of operations are those of [`super::contact_solver`], the
//! reference implementation: a lane gives the same bits as the scalar code
//! on the same constraint, and solving a colour here gives what solving its
//! constraints one after the other would give (tested below).
//!
//! Layout: what the passes read and write every substep is in
//! [`WideConstraint`] (structure of arrays, 1728 bytes per eight
//! constraints, checked below), and only that: on large scenes the passes
//! are bound by the traffic of these records through the caches
//! (docs/soft_step.md, "Smaller records"). What is the same for many
//! constraints is kept out of them: the inverse masses are the bodies'
//! ([`BodyMasses`], gathered per lane), the softness is one of the step's
//! two ([`StepSoftness`], a bit per lane in the body index), and what only
//! restitution and the store read, or the passes only in a step that has
//! tangent speeds or rolling resistance, is in [`WideExtra`]. A constraint
//! of one point has a second point with zero mass, and a colour whose size
//! is not a multiple of eight has padding lanes between the static dummy
//! body and itself, with zero masses: both give zero impulses and change
//! nothing.

use super::bodies::SolverBody;
#[cfg(test)]
use super::contact_solver::ContactConstraint;
use super::contact_solver::{self, ConstraintPoint, PairMass};
use super::contacts::Contact;
use super::lanes::{F64x8, LANES, Lanes, dispatch};
use super::pool::SharedSlice;
use nalgebra::Vector2;

/// The solver records as the passes see them: shared by the threads of a
/// parallel pass, each writing only the dynamic bodies of its own
/// constraints (no two constraints of a colour share one); see
/// [`super::pool::SharedSlice`].
pub(crate) type Bodies<'a> = SharedSlice<'a, SolverBody>;

/// Each body's inverse mass (1/kg) and inverse inertia (1/(kg·m²)), by
/// solver index (0: the static dummy, zeros): the passes gather them per
/// lane, as they gather the velocities, instead of keeping four fields of
/// them in every record (prepare's copy of the masses the constraints were
/// built with: the same values).
pub(crate) type BodyMasses<'a> = &'a [[f64; 2]];

/// What a pass reads and writes of the bodies: their solver records and
/// their masses.
#[derive(Clone, Copy)]
struct PassBodies<'a> {
    rows: Bodies<'a>,
    masses: BodyMasses<'a>,
}

/// Set in a lane's body index when that body has zero inverse mass and
/// inertia (the static dummy, a kinematic body, a padding lane): no
/// impulse changes its velocity, so its record is read but never written
/// back (which lets the threads of a parallel pass share it; the bits are
/// those of writing back the unchanged value).
pub(crate) const FIXED: u32 = 1 << 31;

/// Set in a lane's index of body A when the lane takes the second of the
/// step's two softnesses ([`StepSoftness`]: a contact with a static body),
/// clear when it takes the first.
pub(crate) const STATIC_SOFT: u32 = 1 << 30;

/// The bits of a lane's body index that number the body (below the flags
/// [`FIXED`] and [`STATIC_SOFT`]).
pub(crate) const INDEX: u32 = STATIC_SOFT - 1;

/// A lane's word for body `i`: its index, with [`FIXED`] when the body has
/// zero inverse mass and inertia (the world, a static or kinematic body:
/// read, never written back, so that the threads solving one colour write
/// disjoint bodies even when several of its constraints share such a
/// body).
#[inline]
pub(crate) fn lane_index(i: usize, inv_mass: f64, inv_inertia: f64) -> u32 {
    let index = u32::try_from(i)
        .ok()
        .filter(|&i| i <= INDEX)
        .expect("fewer than 2³⁰ bodies");
    index | fixed_flag(inv_mass, inv_inertia)
}

/// [`FIXED`] for a body of inverse mass `inv_mass` and inverse inertia
/// `inv_inertia` when both are zero, else 0 (without a branch).
#[inline(always)]
pub(crate) fn fixed_flag(inv_mass: f64, inv_inertia: f64) -> u32 {
    u32::from(inv_mass == 0.0 && inv_inertia == 0.0) * FIXED
}

/// The two softnesses of a step's contacts: prepare gives each constraint
/// one of them (`[0]` between two moving bodies or with a kinematic one,
/// `[1]` with a static body, twice as stiff), so the records keep a bit
/// per lane ([`STATIC_SOFT`]) instead of three fields of coefficients,
/// and the solve pass selects between the two lane by lane.
pub(crate) type StepSoftness = [super::Softness; 2];

/// One point of eight constraints.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct WidePoint {
    /// Anchors from each centre of mass (m).
    pub ra_x: F64x8,
    pub ra_y: F64x8,
    pub rb_x: F64x8,
    pub rb_y: F64x8,
    /// Separation minus n·(r_B − r_A) at the step's start (m).
    pub base_separation: F64x8,
    /// Effective masses along the normal and the tangent (kg).
    pub normal_mass: F64x8,
    pub tangent_mass: F64x8,
    /// Accumulated impulses (N·s).
    pub normal_impulse: F64x8,
    pub tangent_impulse: F64x8,
    /// Sum of the normal impulses applied this step (N·s).
    pub total_normal_impulse: F64x8,
}

/// Eight constraints of one colour, one per lane: what the passes read
/// every substep, and only that (the passes stream these records through
/// the caches twelve times a step: each field less is a line less per
/// record and pass).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct WideConstraint {
    /// Solver indices of the bodies (0: the static dummy), with the flags
    /// [`FIXED`] (both) and [`STATIC_SOFT`] (in `a`).
    pub a: [u32; LANES],
    pub b: [u32; LANES],
    /// Unit normal from A to B.
    pub normal_x: F64x8,
    pub normal_y: F64x8,
    pub friction: F64x8,
    /// Minus each lane's push-out bound (m/s): the bias is at least this.
    pub min_bias: F64x8,
    /// [`contact_solver::ContactConstraint::centre_depth`] of A and of B (m): 0 but for
    /// circles.
    pub centre_depth_a: F64x8,
    pub centre_depth_b: F64x8,
    pub points: [WidePoint; 2],
}

// The size the module documentation gives.
const _: () = assert!(std::mem::size_of::<WideConstraint>() == 1728);

/// What the passes seldom read of eight constraints: restitution and the
/// store, and, only in a step where some constraint has a tangent speed or
/// rolling resistance (the `rare` flag of the passes), warm start and
/// relax.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct WideExtra {
    pub restitution: F64x8,
    /// Normal velocity of each point before the solve (m/s).
    pub normal_velocity: [F64x8; 2],
    /// Tangent speed of the surfaces (m/s).
    pub tangent_speed: F64x8,
    /// Rolling resistance (m), its effective mass (kg·m²) and accumulated
    /// angular impulse (N·m·s).
    pub rolling_resistance: F64x8,
    pub rolling_mass: F64x8,
    pub rolling_impulse: F64x8,
}

/// Whether a constraint whose surfaces have tangent speed `tangent_speed`
/// (m/s) and rolling resistance `rolling_resistance` (m) makes the passes
/// read the rare fields of the records ([`WideExtra`]): a tangent speed
/// other than +0 (subtracting +0 changes no value, −0 included, so
/// skipping it gives the same bits) or rolling resistance.
#[inline(always)]
pub(crate) fn is_rare(tangent_speed: f64, rolling_resistance: f64) -> bool {
    tangent_speed.to_bits() != 0 || rolling_resistance > 0.0
}

/// What a lane holds of a constraint besides its points, as the lane
/// stores it.
struct LaneHead {
    /// The lane's body words ([`lane_index`], with [`STATIC_SOFT`] in `a`
    /// for the step's second softness).
    a: u32,
    b: u32,
    normal: Vector2<f64>,
    friction: f64,
    /// The push-out bound (m/s), stored negated as the lane's `min_bias`.
    push_out: f64,
    centre_depth: [f64; 2],
    restitution: f64,
    tangent_speed: f64,
    rolling_resistance: f64,
    rolling_mass: f64,
    rolling_impulse: f64,
}

/// Writes `h` into lane `l` of `(w, e)`: every field but the points'.
#[inline(always)]
fn set_head((w, e): (&mut WideConstraint, &mut WideExtra), l: usize, h: &LaneHead) {
    w.a[l] = h.a;
    w.b[l] = h.b;
    w.normal_x.set_lane(l, h.normal.x);
    w.normal_y.set_lane(l, h.normal.y);
    w.friction.set_lane(l, h.friction);
    w.min_bias.set_lane(l, -h.push_out);
    w.centre_depth_a.set_lane(l, h.centre_depth[0]);
    w.centre_depth_b.set_lane(l, h.centre_depth[1]);
    e.restitution.set_lane(l, h.restitution);
    e.tangent_speed.set_lane(l, h.tangent_speed);
    e.rolling_resistance.set_lane(l, h.rolling_resistance);
    e.rolling_mass.set_lane(l, h.rolling_mass);
    e.rolling_impulse.set_lane(l, h.rolling_impulse);
}

/// Writes point `cp` as point `k` (0 or 1) of lane `l` of `(w, e)`.
#[inline(always)]
fn set_point(
    (w, e): (&mut WideConstraint, &mut WideExtra),
    l: usize,
    k: usize,
    cp: &ConstraintPoint,
) {
    let p = &mut w.points[k];
    p.ra_x.set_lane(l, cp.ra.x);
    p.ra_y.set_lane(l, cp.ra.y);
    p.rb_x.set_lane(l, cp.rb.x);
    p.rb_y.set_lane(l, cp.rb.y);
    p.base_separation.set_lane(l, cp.base_separation);
    p.normal_mass.set_lane(l, cp.normal_mass);
    p.tangent_mass.set_lane(l, cp.tangent_mass);
    p.normal_impulse.set_lane(l, cp.normal_impulse);
    p.tangent_impulse.set_lane(l, cp.tangent_impulse);
    p.total_normal_impulse.set_lane(l, cp.total_normal_impulse);
    e.normal_velocity[k].set_lane(l, cp.normal_velocity);
}

/// Prepares the constraint of `contact` straight into lane `l` of `(w,
/// e)`, every field of the lane (a missing second point as zeros): what
/// [`contact_solver::prepare`] would build for it, with the same formulas
/// ([`contact_solver::prepare_point`], [`contact_solver::rolling_mass`]),
/// written as [`set_lane`] would write that constraint, without building
/// it. `mass`: the bodies' solver indices and inverse masses, and their
/// lane words ([`lane_index`] of those, computed once per body and step);
/// `static_soft`: whether the constraint takes the step's second softness
/// ([`StepSoftness`]); `push_out`: its push-out bound (m/s); `bodies`: the
/// solver records by solver index; `warm`: the warm-start scale. Returns
/// whether the constraint is rare ([`is_rare`]).
#[inline(always)]
pub(crate) fn prepare_lane(
    (w, e): (&mut WideConstraint, &mut WideExtra),
    l: usize,
    contact: &Contact,
    (mass, (word_a, word_b)): (&PairMass, (u32, u32)),
    (static_soft, push_out): (bool, f64),
    bodies: &[SolverBody],
    warm: f64,
) -> bool {
    let flag = if static_soft { STATIC_SOFT } else { 0 };
    let (ia, ib) = (mass.inv_inertia_a, mass.inv_inertia_b);
    set_head(
        (w, e),
        l,
        &LaneHead {
            a: word_a | flag,
            b: word_b,
            normal: contact.normal,
            friction: contact.friction,
            push_out,
            centre_depth: contact.centre_depth,
            restitution: contact.restitution,
            tangent_speed: contact.tangent_speed,
            rolling_resistance: contact.rolling_resistance,
            rolling_mass: contact_solver::rolling_mass(contact.rolling_resistance, ia, ib),
            rolling_impulse: warm * contact.rolling_impulse,
        },
    );
    let pair = (&bodies[mass.a], &bodies[mass.b]);
    for k in 0..2 {
        let cp = if k < contact.count {
            contact_solver::prepare_point(&contact.points[k], contact.normal, mass, pair, warm)
        } else {
            ConstraintPoint::default()
        };
        set_point((w, e), l, k, &cp);
    }
    is_rare(contact.tangent_speed, contact.rolling_resistance)
}

/// Writes constraint `c` into lane `l` of `(w, e)`, every field of the lane
/// (a missing second point as zeros); `softness`: the step's two, one of
/// which is `c`'s. The step writes its lanes with [`prepare_lane`]; this
/// is the reference it is tested against.
///
/// # Panics
/// If `c`'s softness is neither of `softness` (prepare gives every
/// constraint one of the two).
#[cfg(test)]
pub(crate) fn set_lane(
    (w, e): (&mut WideConstraint, &mut WideExtra),
    l: usize,
    c: &ContactConstraint,
    softness: &StepSoftness,
) {
    let static_soft = if c.softness == softness[1] {
        STATIC_SOFT
    } else {
        assert!(c.softness == softness[0], "a softness of the step");
        0
    };
    set_head(
        (w, e),
        l,
        &LaneHead {
            a: lane_index(c.a, c.inv_mass_a, c.inv_inertia_a) | static_soft,
            b: lane_index(c.b, c.inv_mass_b, c.inv_inertia_b),
            normal: c.normal,
            friction: c.friction,
            push_out: c.push_out,
            centre_depth: c.centre_depth,
            restitution: c.restitution,
            tangent_speed: c.tangent_speed,
            rolling_resistance: c.rolling_resistance,
            rolling_mass: c.rolling_mass,
            rolling_impulse: c.rolling_impulse,
        },
    );
    for k in 0..2 {
        let cp = if k < c.count {
            c.points[k]
        } else {
            ConstraintPoint::default()
        };
        set_point((w, e), l, k, &cp);
    }
}

/// Makes lane `l` of `(w, e)` padding: between the static dummy and itself,
/// zero masses and zero points, so it gives zero impulses (whichever
/// softness it takes).
pub(crate) fn set_padding_lane((w, e): (&mut WideConstraint, &mut WideExtra), l: usize) {
    set_head(
        (w, e),
        l,
        &LaneHead {
            a: lane_index(0, 0.0, 0.0),
            b: lane_index(0, 0.0, 0.0),
            normal: Vector2::zeros(),
            friction: 0.0,
            push_out: 0.0,
            centre_depth: [0.0; 2],
            restitution: 0.0,
            tangent_speed: 0.0,
            rolling_resistance: 0.0,
            rolling_mass: 0.0,
            rolling_impulse: 0.0,
        },
    );
    for k in 0..2 {
        set_point((w, e), l, k, &ConstraintPoint::default());
    }
}

/// The velocities of the bodies of a group of lanes (what the passes
/// change), and their Δp.x as gathered (written back with them,
/// unchanged).
#[derive(Clone, Copy)]
pub(super) struct WideBody<L> {
    pub(super) vx: L,
    pub(super) vy: L,
    pub(super) w: L,
    pub(super) dpx: L,
}

impl<L: Lanes> WideBody<L> {
    /// ω × r + v at anchors `(rx, ry)`: the velocity of the anchored point.
    #[inline(always)]
    fn point_velocity(&self, rx: L, ry: L) -> (L, L) {
        (self.vx + -self.w * ry, self.vy + self.w * rx)
    }
}

/// Reads the velocities (and Δp.x) of the bodies of group `g` of a
/// record's lanes (`index`: the record's body indices).
#[inline(always)]
pub(super) fn gather<L: Lanes>(bodies: Bodies<'_>, index: &[u32; LANES], g: usize) -> WideBody<L> {
    let [vx, vy, w, dpx] = L::gather_row(bodies, index, g, 0);
    WideBody { vx, vy, w, dpx }
}

/// The second row of the bodies of group `g`: `[Δp.y, Δθ, cos Δθ, sin
/// Δθ]`.
#[inline(always)]
pub(super) fn gather_motion<L: Lanes>(
    bodies: Bodies<'_>,
    index: &[u32; LANES],
    g: usize,
) -> [L; 4] {
    L::gather_row(bodies, index, g, 1)
}

/// Writes back the velocities of the bodies of group `g` (see
/// [`Lanes::scatter_head`]).
#[inline(always)]
pub(super) fn scatter<L: Lanes>(
    bodies: Bodies<'_>,
    index: &[u32; LANES],
    g: usize,
    w: &WideBody<L>,
) {
    L::scatter_head([w.vx, w.vy, w.w, w.dpx], bodies, index, g);
}

/// The current separation of both points of group `g`, from the
/// bodies' motion since the step began: s = s0 + n·(Δp_B + R(Δθ_B) r_B −
/// Δp_A − R(Δθ_A) r_A) (the passes change velocities only, so this is
/// computed once per pass, before the impulses); `(a, b)` the lanes'
/// bodies as gathered.
#[inline(always)]
fn separations<L: Lanes>(
    bodies: Bodies<'_>,
    (c, g): (&WideConstraint, usize),
    (a, b): (&WideBody<L>, &WideBody<L>),
) -> [L; 2] {
    let [dpy_a, _, ca, sa] = gather_motion::<L>(bodies, &c.a, g);
    let [dpy_b, _, cb, sb] = gather_motion::<L>(bodies, &c.b, g);
    let one = L::splat(1.0);
    let motion = Motion {
        dpx: b.dpx - a.dpx,
        dpy: dpy_b - dpy_a,
        ca,
        sa,
        cb,
        sb,
        nx: L::load(&c.normal_x, g),
        ny: L::load(&c.normal_y, g),
        unturned: L::load(&c.centre_depth_b, g) * (one - cb)
            + L::load(&c.centre_depth_a, g) * (one - ca),
    };
    [
        motion.separation(&c.points[0], g),
        motion.separation(&c.points[1], g),
    ]
}

/// The relative motion of a group's pairs of bodies since the step began,
/// and their normals.
#[derive(Clone, Copy)]
struct Motion<L> {
    /// Δp_B − Δp_A.
    dpx: L,
    dpy: L,
    /// cos and sin of each body's rotation since the step began.
    ca: L,
    sa: L,
    cb: L,
    sb: L,
    nx: L,
    ny: L,
    /// What the circles' turns take off the separation, the sum of
    /// k_B (1 − cos Δθ_B) and k_A (1 − cos Δθ_A): 0 for other shapes
    /// ([`contact_solver::ContactConstraint::centre_depth`]).
    unturned: L,
}

impl<L: Lanes> Motion<L> {
    /// The current separation of point `p` in group `g`.
    #[inline(always)]
    fn separation(&self, p: &WidePoint, g: usize) -> L {
        let (ra_x, ra_y) = (L::load(&p.ra_x, g), L::load(&p.ra_y, g));
        let (rb_x, rb_y) = (L::load(&p.rb_x, g), L::load(&p.rb_y, g));
        let (cb, sb, ca, sa) = (self.cb, self.sb, self.ca, self.sa);
        let (rbx, rby) = (cb * rb_x - sb * rb_y, sb * rb_x + cb * rb_y);
        let (rax, ray) = (ca * ra_x - sa * ra_y, sa * ra_x + ca * ra_y);
        let dsx = self.dpx + rbx - rax;
        let dsy = self.dpy + rby - ray;
        L::load(&p.base_separation, g) + (dsx * self.nx + dsy * self.ny) - self.unturned
    }
}

/// The inverse masses of a group's bodies.
#[derive(Clone, Copy)]
struct Masses<L> {
    a: L,
    ia: L,
    b: L,
    ib: L,
}

impl<L: Lanes> Masses<L> {
    #[inline(always)]
    fn of(masses: BodyMasses<'_>, c: &WideConstraint, g: usize) -> Self {
        let [a, ia] = L::gather_masses(masses, &c.a, g);
        let [b, ib] = L::gather_masses(masses, &c.b, g);
        Masses { a, ia, b, ib }
    }
}

/// A point's anchors, loaded.
#[derive(Clone, Copy)]
struct Anchors<L> {
    ra_x: L,
    ra_y: L,
    rb_x: L,
    rb_y: L,
}

impl<L: Lanes> Anchors<L> {
    #[inline(always)]
    fn of(p: &WidePoint, g: usize) -> Self {
        Anchors {
            ra_x: L::load(&p.ra_x, g),
            ra_y: L::load(&p.ra_y, g),
            rb_x: L::load(&p.rb_x, g),
            rb_y: L::load(&p.rb_y, g),
        }
    }

    /// The velocity of the point on B relative to the point on A.
    #[inline(always)]
    fn relative_velocity(&self, (a, b): (&WideBody<L>, &WideBody<L>)) -> (L, L) {
        let (vax, vay) = a.point_velocity(self.ra_x, self.ra_y);
        let (vbx, vby) = b.point_velocity(self.rb_x, self.rb_y);
        (vbx - vax, vby - vay)
    }
}

/// Applies impulse `(px, py)` at anchors `r`: −P on A, +P on B.
#[inline(always)]
fn apply<L: Lanes>(
    m: &Masses<L>,
    (a, b): (&mut WideBody<L>, &mut WideBody<L>),
    r: &Anchors<L>,
    (px, py): (L, L),
) {
    a.vx -= m.a * px;
    a.vy -= m.a * py;
    a.w -= m.ia * (r.ra_x * py - r.ra_y * px);
    b.vx += m.b * px;
    b.vy += m.b * py;
    b.w += m.ib * (r.rb_x * py - r.rb_y * px);
}

/// Applies every constraint's accumulated impulses. `rare`: the records'
/// [`WideExtra`], given when a constraint of the step has a tangent speed
/// or rolling resistance ([`is_rare`]; else those fields are not read).
#[inline(never)]
pub(crate) fn warm_start(
    constraints: &mut [WideConstraint],
    rare: Option<&mut [WideExtra]>,
    bodies: &mut [SolverBody],
    masses: BodyMasses<'_>,
) {
    warm_start_shared(constraints, rare, Bodies::new(bodies), masses);
}

/// [`warm_start`] on records shared by the threads of a parallel pass:
/// `constraints` (and `rare`, the same records' extras) must be of one
/// colour (or the whole list, alone).
#[inline(never)]
pub(crate) fn warm_start_shared(
    constraints: &mut [WideConstraint],
    rare: Option<&mut [WideExtra]>,
    bodies: Bodies<'_>,
    masses: BodyMasses<'_>,
) {
    let bodies = PassBodies {
        rows: bodies,
        masses,
    };
    dispatch!(warm_start_with, warm_start_avx512, warm_start_avx, (constraints: &mut [WideConstraint], rare: Option<&mut [WideExtra]>, bodies: PassBodies<'_>));
}

#[inline(always)]
fn warm_start_with<L: Lanes>(
    constraints: &mut [WideConstraint],
    rare: Option<&mut [WideExtra]>,
    bodies: PassBodies<'_>,
) {
    // Group by group, each written out with its number as a constant (a
    // loop over the groups kept values on the stack: 9 % more instructions
    // for the AVX passes); a loop with the extras and one without (no test
    // per record).
    match rare {
        Some(extras) => {
            for (c, e) in constraints.iter_mut().zip(extras.iter()) {
                warm_start_group::<L>(c, Some(e), 0, bodies);
                if L::GROUPS == 2 {
                    warm_start_group::<L>(c, Some(e), 1, bodies);
                }
            }
        }
        None => {
            for c in constraints.iter_mut() {
                warm_start_group::<L>(c, None, 0, bodies);
                if L::GROUPS == 2 {
                    warm_start_group::<L>(c, None, 1, bodies);
                }
            }
        }
    }
}

/// [`warm_start_with`] on group `g` of record `c` (`e`: its extra, when
/// the step has rare fields).
#[inline(always)]
fn warm_start_group<L: Lanes>(
    c: &mut WideConstraint,
    e: Option<&WideExtra>,
    g: usize,
    bodies: PassBodies<'_>,
) {
    let (mut a, mut b) = (
        gather::<L>(bodies.rows, &c.a, g),
        gather::<L>(bodies.rows, &c.b, g),
    );
    let m = Masses::of(bodies.masses, c, g);
    let (nx, ny) = (L::load(&c.normal_x, g), L::load(&c.normal_y, g));
    let (tx, ty) = (ny, -nx);
    for p in &mut c.points {
        let (normal_impulse, tangent_impulse) = (
            L::load(&p.normal_impulse, g),
            L::load(&p.tangent_impulse, g),
        );
        let px = normal_impulse * nx + tangent_impulse * tx;
        let py = normal_impulse * ny + tangent_impulse * ty;
        (L::load(&p.total_normal_impulse, g) + normal_impulse)
            .store(&mut p.total_normal_impulse, g);
        apply(&m, (&mut a, &mut b), &Anchors::of(p, g), (px, py));
    }
    if let Some(e) = e {
        let impulse = L::load(&e.rolling_impulse, g);
        if !L::all(impulse.eq(L::splat(0.0))) {
            a.w -= m.ia * impulse;
            b.w += m.ib * impulse;
        }
    }
    scatter(bodies.rows, &c.a, g, &a);
    scatter(bodies.rows, &c.b, g, &b);
}

/// The solve pass, with the soft bias (see [`super::contact_solver::solve`]);
/// `softness`: the step's two (see [`StepSoftness`]).
#[inline(never)]
pub(crate) fn solve(
    constraints: &mut [WideConstraint],
    bodies: &mut [SolverBody],
    masses: BodyMasses<'_>,
    inv_h: f64,
    softness: &StepSoftness,
) {
    solve_shared(constraints, Bodies::new(bodies), masses, inv_h, softness);
}

/// [`solve`] on shared records (see [`warm_start_shared`]).
#[inline(never)]
pub(crate) fn solve_shared(
    constraints: &mut [WideConstraint],
    bodies: Bodies<'_>,
    masses: BodyMasses<'_>,
    inv_h: f64,
    softness: &StepSoftness,
) {
    let bodies = PassBodies {
        rows: bodies,
        masses,
    };
    dispatch!(solve_with, solve_avx512, solve_avx, (constraints: &mut [WideConstraint], bodies: PassBodies<'_>, inv_h: f64, softness: &StepSoftness));
}

#[inline(always)]
fn solve_with<L: Lanes>(
    constraints: &mut [WideConstraint],
    bodies: PassBodies<'_>,
    inv_h: f64,
    softness: &StepSoftness,
) {
    // Per softness: the bias rate times the mass scale (the product the
    // scalar solver forms), the mass scale and the impulse scale.
    let [soft, hard] = softness.map(|s| {
        (
            L::splat(s.mass_scale * s.bias_rate),
            L::splat(s.mass_scale),
            L::splat(s.impulse_scale),
        )
    });
    let bias = Bias::Soft { soft, hard };
    for c in constraints.iter_mut() {
        pass_group::<L>(c, None, 0, bodies, (L::splat(inv_h), bias));
        if L::GROUPS == 2 {
            pass_group::<L>(c, None, 1, bodies, (L::splat(inv_h), bias));
        }
    }
}

/// The relax pass: without bias, with friction (and tangent speeds and
/// rolling resistance when `rare` is given, see [`warm_start`]).
#[inline(never)]
pub(crate) fn relax(
    constraints: &mut [WideConstraint],
    rare: Option<&mut [WideExtra]>,
    bodies: &mut [SolverBody],
    masses: BodyMasses<'_>,
    inv_h: f64,
) {
    relax_shared(constraints, rare, Bodies::new(bodies), masses, inv_h);
}

/// [`relax`] on shared records (see [`warm_start_shared`]).
#[inline(never)]
pub(crate) fn relax_shared(
    constraints: &mut [WideConstraint],
    rare: Option<&mut [WideExtra]>,
    bodies: Bodies<'_>,
    masses: BodyMasses<'_>,
    inv_h: f64,
) {
    let bodies = PassBodies {
        rows: bodies,
        masses,
    };
    dispatch!(relax_with, relax_avx512, relax_avx, (constraints: &mut [WideConstraint], rare: Option<&mut [WideExtra]>, bodies: PassBodies<'_>, inv_h: f64));
}

#[inline(always)]
fn relax_with<L: Lanes>(
    constraints: &mut [WideConstraint],
    rare: Option<&mut [WideExtra]>,
    bodies: PassBodies<'_>,
    inv_h: f64,
) {
    let inv_h = L::splat(inv_h);
    match rare {
        Some(extras) => {
            for (c, e) in constraints.iter_mut().zip(extras.iter_mut()) {
                pass_group::<L>(c, Some(&mut *e), 0, bodies, (inv_h, Bias::None));
                if L::GROUPS == 2 {
                    pass_group::<L>(c, Some(e), 1, bodies, (inv_h, Bias::None));
                }
            }
        }
        None => {
            for c in constraints.iter_mut() {
                pass_group::<L>(c, None, 0, bodies, (inv_h, Bias::None));
                if L::GROUPS == 2 {
                    pass_group::<L>(c, None, 1, bodies, (inv_h, Bias::None));
                }
            }
        }
    }
}

/// The bias of a pass: the solve's soft bias, from the step's two
/// softnesses as `(mass scale × bias rate, mass scale, impulse scale)`
/// (`soft` where a lane's [`STATIC_SOFT`] is clear, `hard` where set), or
/// none (relax).
#[derive(Clone, Copy)]
enum Bias<L> {
    Soft { soft: (L, L, L), hard: (L, L, L) },
    None,
}

/// One pass of sequential impulses on group `g` of record `c` (`e`: its
/// extra, given to relax when the step has rare fields).
#[inline(always)]
fn pass_group<L: Lanes>(
    c: &mut WideConstraint,
    e: Option<&mut WideExtra>,
    g: usize,
    bodies: PassBodies<'_>,
    (inv_h, bias): (L, Bias<L>),
) {
    let (zero, one) = (L::splat(0.0), L::splat(1.0));
    let (mut a, mut b) = (
        gather::<L>(bodies.rows, &c.a, g),
        gather::<L>(bodies.rows, &c.b, g),
    );
    let separation = separations::<L>(bodies.rows, (c, g), (&a, &b));
    let m = Masses::of(bodies.masses, c, g);
    let (nx, ny) = (L::load(&c.normal_x, g), L::load(&c.normal_y, g));
    let (bias_rate, mass_scale, impulse_scale, min_bias) = match bias {
        Bias::Soft { soft, hard } => {
            let hard_lanes = L::flagged(&c.a, g, STATIC_SOFT);
            (
                L::select(hard_lanes, hard.0, soft.0),
                L::select(hard_lanes, hard.1, soft.1),
                L::select(hard_lanes, hard.2, soft.2),
                L::load(&c.min_bias, g),
            )
        }
        // Relax: no bias (0 · s is ±0, and max(±0, −0) is ±0 as before).
        Bias::None => (zero, one, zero, L::splat(-0.0)),
    };
    for (p, s) in c.points.iter_mut().zip(separation) {
        let speculative = s.gt(zero);
        let bias = L::select(speculative, s * inv_h, (bias_rate * s).max(min_bias));
        let point_mass_scale = L::select(speculative, one, mass_scale);
        let point_impulse_scale = L::select(speculative, zero, impulse_scale);
        let r = Anchors::of(p, g);
        let (dvx, dvy) = r.relative_velocity((&a, &b));
        let vn = dvx * nx + dvy * ny;
        let normal_impulse = L::load(&p.normal_impulse, g);
        let impulse = -L::load(&p.normal_mass, g) * (point_mass_scale * vn + bias)
            - point_impulse_scale * normal_impulse;
        let accumulated = (normal_impulse + impulse).max(zero);
        let impulse = accumulated - normal_impulse;
        accumulated.store(&mut p.normal_impulse, g);
        (L::load(&p.total_normal_impulse, g) + impulse).store(&mut p.total_normal_impulse, g);
        apply(&m, (&mut a, &mut b), &r, (impulse * nx, impulse * ny));
    }
    if let Bias::None = bias {
        let friction = L::load(&c.friction, g);
        let (tx, ty) = (ny, -nx);
        for p in &mut c.points {
            let r = Anchors::of(p, g);
            let (dvx, dvy) = r.relative_velocity((&a, &b));
            // Without rare fields every tangent speed is +0: nothing to
            // subtract (see `is_rare`).
            let vt = match &e {
                Some(e) => dvx * tx + dvy * ty - L::load(&e.tangent_speed, g),
                None => dvx * tx + dvy * ty,
            };
            let max_friction = friction * L::load(&p.normal_impulse, g);
            let tangent_impulse = L::load(&p.tangent_impulse, g);
            let accumulated = (tangent_impulse - L::load(&p.tangent_mass, g) * vt)
                .clamp(-max_friction, max_friction);
            let impulse = accumulated - tangent_impulse;
            accumulated.store(&mut p.tangent_impulse, g);
            apply(&m, (&mut a, &mut b), &r, (impulse * tx, impulse * ty));
        }
        if let Some(e) = e {
            let rolling_resistance = L::load(&e.rolling_resistance, g);
            if !L::all(rolling_resistance.eq(zero)) {
                let normal = L::load(&c.points[0].normal_impulse, g)
                    + L::load(&c.points[1].normal_impulse, g);
                let max = rolling_resistance * normal;
                let old = L::load(&e.rolling_impulse, g);
                let accumulated =
                    (old - L::load(&e.rolling_mass, g) * (b.w - a.w)).clamp(-max, max);
                accumulated.store(&mut e.rolling_impulse, g);
                let delta = accumulated - old;
                a.w -= m.ia * delta;
                b.w += m.ib * delta;
            }
        }
    }
    scatter(bodies.rows, &c.a, g, &a);
    scatter(bodies.rows, &c.b, g, &b);
}

/// The restitution pass (see [`super::contact_solver::restitution`]).
#[inline(never)]
pub(crate) fn restitution(
    constraints: &mut [WideConstraint],
    extras: &[WideExtra],
    bodies: &mut [SolverBody],
    masses: BodyMasses<'_>,
    threshold: f64,
) {
    restitution_shared(constraints, extras, Bodies::new(bodies), masses, threshold);
}

/// [`restitution`] on shared records (see [`warm_start_shared`]).
#[inline(never)]
pub(crate) fn restitution_shared(
    constraints: &mut [WideConstraint],
    extras: &[WideExtra],
    bodies: Bodies<'_>,
    masses: BodyMasses<'_>,
    threshold: f64,
) {
    let bodies = PassBodies {
        rows: bodies,
        masses,
    };
    dispatch!(restitution_with, restitution_avx512, restitution_avx, (constraints: &mut [WideConstraint], extras: &[WideExtra], bodies: PassBodies<'_>, threshold: f64));
}

#[inline(always)]
fn restitution_with<L: Lanes>(
    constraints: &mut [WideConstraint],
    extras: &[WideExtra],
    bodies: PassBodies<'_>,
    threshold: f64,
) {
    let min_approach = L::splat(-threshold);
    for (c, e) in constraints.iter_mut().zip(extras) {
        restitution_group::<L>((c, e), 0, bodies, min_approach);
        if L::GROUPS == 2 {
            restitution_group::<L>((c, e), 1, bodies, min_approach);
        }
    }
}

/// [`restitution_with`] on group `g` of record `c` (`e` its extra).
#[inline(always)]
fn restitution_group<L: Lanes>(
    (c, e): (&mut WideConstraint, &WideExtra),
    g: usize,
    bodies: PassBodies<'_>,
    min_approach: L,
) {
    let zero = L::splat(0.0);
    let restitution = L::load(&e.restitution, g);
    if L::all(restitution.eq(zero)) {
        return;
    }
    let (mut a, mut b) = (
        gather::<L>(bodies.rows, &c.a, g),
        gather::<L>(bodies.rows, &c.b, g),
    );
    let m = Masses::of(bodies.masses, c, g);
    let (nx, ny) = (L::load(&c.normal_x, g), L::load(&c.normal_y, g));
    for (p, relative) in c.points.iter_mut().zip(&e.normal_velocity) {
        let relative = L::load(relative, g);
        let total = L::load(&p.total_normal_impulse, g);
        // No restitution, slow approach, or no push during the solve:
        // no bounce.
        let skip = L::or(
            L::or(relative.gt(min_approach), total.eq(zero)),
            restitution.eq(zero),
        );
        let r = Anchors::of(p, g);
        let (dvx, dvy) = r.relative_velocity((&a, &b));
        let vn = dvx * nx + dvy * ny;
        let normal_impulse = L::load(&p.normal_impulse, g);
        let impulse = -L::load(&p.normal_mass, g) * (vn + restitution * relative);
        let accumulated = (normal_impulse + impulse).max(zero);
        let impulse = L::select(skip, zero, accumulated - normal_impulse);
        L::select(skip, normal_impulse, accumulated).store(&mut p.normal_impulse, g);
        L::select(skip, total, total + impulse).store(&mut p.total_normal_impulse, g);
        apply(&m, (&mut a, &mut b), &r, (impulse * nx, impulse * ny));
    }
    scatter(bodies.rows, &c.a, g, &a);
    scatter(bodies.rows, &c.b, g, &b);
}

/// Copies the impulses of lane `l` of `(w, e)` back into its contact.
#[inline]
pub(crate) fn store_lane((w, e): (&WideConstraint, &WideExtra), l: usize, contact: &mut Contact) {
    let count = contact.count;
    for (k, p) in contact.points[..count].iter_mut().enumerate() {
        let q = &w.points[k];
        p.normal_impulse = q.normal_impulse.lane(l);
        p.tangent_impulse = q.tangent_impulse.lane(l);
        p.total_normal_impulse = q.total_normal_impulse.lane(l);
        p.normal_velocity = e.normal_velocity[k].lane(l);
    }
    contact.rolling_impulse = e.rolling_impulse.lane(l);
}

#[cfg(test)]
mod tests {
    use super::super::colouring::{Colouring, Slot};
    use super::super::contact_solver::{self, ConstraintPoint};
    use super::super::softness::Softness;
    use super::*;
    use nalgebra::Vector2;

    use crate::soft_step::lanes::F64x4;
    use crate::soft_step::lanes::tests::lane_type_runs;
    use crate::soft_step::lanes_avx::Avx4;
    use crate::soft_step::lanes_avx512::Avx8;
    use crate::soft_step::test_numbers::Numbers;

    /// Twelve moving bodies and the static dummy, a chain of contacts
    /// between neighbours and one with the ground per body, with varied
    /// anchors, separations (overlapping and speculative), impulses and
    /// softness.
    fn scene() -> (Vec<SolverBody>, Vec<[f64; 2]>, Vec<ContactConstraint>) {
        let mut n = Numbers(7);
        // Each body's inverse mass and inertia (the static dummy's zero).
        let masses: Vec<[f64; 2]> = (0..13)
            .map(|k| match k {
                0 => [0.0, 0.0],
                k => [0.5 + 0.05 * k as f64, 3.0 + 0.3 * k as f64],
            })
            .collect();
        let mut bodies = vec![SolverBody::AT_REST];
        for _ in 0..12 {
            let dtheta = 0.01 * n.next();
            bodies.push(SolverBody {
                v: Vector2::new(n.next(), n.next()),
                w: n.next(),
                dp: Vector2::new(0.01 * n.next(), 0.01 * n.next()),
                dtheta,
                dq: [dtheta.cos(), dtheta.sin()],
            });
        }
        let [soft, static_soft] = step_softness();
        let mut constraints = Vec::new();
        let pairs = (1..12).map(|i| (i, i + 1)).chain((1..13).map(|i| (0, i)));
        for (contact, (a, b)) in pairs.enumerate() {
            let angle = n.next();
            let normal = Vector2::new(angle.sin(), angle.cos());
            let mut point = |k: usize| ConstraintPoint {
                ra: Vector2::new(0.5 * n.next(), 0.5 * n.next()),
                rb: Vector2::new(0.5 * n.next(), 0.5 * n.next()),
                // Every fourth contact deep, its bias at its push-out bound.
                base_separation: if contact % 4 == 1 {
                    -0.5 - 0.1 * n.next().abs()
                } else {
                    0.01 * n.next()
                },
                normal_mass: 1.0 + n.next(),
                tangent_mass: 1.0 + n.next(),
                normal_impulse: (k as f64 + n.next()).max(0.0),
                tangent_impulse: 0.1 * n.next(),
                total_normal_impulse: 0.0,
                normal_velocity: -2.0 * n.next().abs(),
            };
            let points = [point(0), point(1)];
            let static_a = a == 0;
            constraints.push(ContactConstraint {
                a,
                b,
                contact,
                normal,
                friction: 0.6,
                restitution: if contact % 3 == 0 { 0.5 } else { 0.0 },
                inv_mass_a: masses[a][0],
                inv_inertia_a: masses[a][1],
                inv_mass_b: masses[b][0],
                inv_inertia_b: masses[b][1],
                softness: if static_a { static_soft } else { soft },
                // A shared push-out bound on some lanes (prepare's rule for
                // a body with several deep contacts).
                push_out: if contact % 4 == 1 { 0.75 } else { 3.0 },
                // A conveyor's tangent speed on some, rolling resistance
                // (with a warm-start impulse) on others.
                tangent_speed: if contact % 5 == 0 { 0.3 } else { 0.0 },
                rolling_resistance: if contact % 3 == 1 { 0.05 } else { 0.0 },
                rolling_mass: 1.0 / (masses[a][1] + masses[b][1]),
                rolling_impulse: if contact % 3 == 1 { 0.01 } else { 0.0 },
                // A circle on B on some lanes, circles on both on others.
                centre_depth: match contact % 4 {
                    2 => [0.0, 0.3],
                    3 => [0.2, 0.4],
                    _ => [0.0; 2],
                },
                count: 1 + contact % 2,
                points,
            });
        }
        (bodies, masses, constraints)
    }

    /// The scene's two softnesses: between two moving bodies, and with
    /// the static dummy.
    fn step_softness() -> StepSoftness {
        [
            Softness::new(30.0, 10.0, 1.0 / 240.0),
            Softness::new(60.0, 10.0, 1.0 / 240.0),
        ]
    }

    /// A record's fields as text: `{:?}` of an f64 is the shortest text
    /// that reads back to its bits (−0 included), so equal texts are equal
    /// bits, which `==` on f64 is not.
    fn bits_of((w, e): (&WideConstraint, &WideExtra)) -> String {
        format!("{w:?} {e:?}")
    }

    #[test]
    fn a_lane_prepared_from_its_contact_holds_the_scalar_constraints_bits() {
        // Contacts between the scene's bodies (with the static dummy, with a
        // kinematic body, between two moving ones), of one and two points,
        // with and without warm starting, tangent speeds (−0 among them),
        // rolling resistance and circles; each prepared straight into a lane
        // and, as the reference, built as a scalar constraint and copied
        // into the same lane of another record.
        let (bodies, masses, _) = scene();
        let softness = step_softness();
        let mut n = Numbers(11);
        let mut set = super::super::contacts::ContactSet::default();
        let mut rare_lanes = 0;
        for k in 0..48 {
            let (a, b) = match k % 4 {
                0 => (0, 1 + k % 12),
                _ => (1 + k % 12, 1 + (k + 1 + k / 12) % 12),
            };
            set.create(
                (2 * k, 2 * k + 1),
                (a, b),
                super::super::contacts::tests::material(),
                false,
            );
            let mut c = set.contacts.pop().unwrap();
            let angle = 3.0 * n.next();
            c.normal = Vector2::new(angle.sin(), angle.cos());
            c.count = 1 + k % 2;
            for p in &mut c.points {
                p.anchor_a = Vector2::new(0.5 * n.next(), 0.5 * n.next());
                p.anchor_b = Vector2::new(0.5 * n.next(), 0.5 * n.next());
                p.separation = 0.02 * n.next();
                p.normal_impulse = n.next().abs();
                p.tangent_impulse = 0.1 * n.next();
            }
            c.friction = 0.6 + 0.1 * n.next();
            c.restitution = if k % 3 == 0 { 0.5 } else { 0.0 };
            c.tangent_speed = [0.0, 0.3, -0.0, 0.0, -0.2][k % 5];
            c.rolling_resistance = if k % 7 == 1 { 0.05 } else { 0.0 };
            c.rolling_impulse = 0.01 * n.next();
            c.centre_depth = [[0.0; 2], [0.0, 0.3], [0.2, 0.4]][k % 3];
            // Every fifth pair of moving bodies with a kinematic B (zero
            // inverse masses, FIXED).
            let kinematic = a != 0 && k % 5 == 2;
            let [mb, ib] = if kinematic { [0.0; 2] } else { masses[b] };
            let mass = PairMass {
                a,
                b,
                inv_mass_a: masses[a][0],
                inv_inertia_a: masses[a][1],
                inv_mass_b: mb,
                inv_inertia_b: ib,
            };
            let static_soft = a == 0;
            let push_out = if k % 4 == 1 { 0.75 } else { 3.0 };
            let warm = if k % 6 == 5 { 0.0 } else { 1.0 };
            let lane = k % LANES;
            let scalar = contact_solver::prepare(
                &c,
                k,
                mass,
                (softness[usize::from(static_soft)], push_out),
                &bodies,
                warm,
            );
            let mut expected = (WideConstraint::default(), WideExtra::default());
            set_lane((&mut expected.0, &mut expected.1), lane, &scalar, &softness);
            let mut direct = (WideConstraint::default(), WideExtra::default());
            let words = (
                lane_index(a, mass.inv_mass_a, mass.inv_inertia_a),
                lane_index(b, mass.inv_mass_b, mass.inv_inertia_b),
            );
            let rare = prepare_lane(
                (&mut direct.0, &mut direct.1),
                lane,
                &c,
                (&mass, words),
                (static_soft, push_out),
                &bodies,
                warm,
            );
            assert_eq!(
                bits_of((&direct.0, &direct.1)),
                bits_of((&expected.0, &expected.1)),
                "contact {k}"
            );
            assert_eq!(
                rare,
                is_rare(scalar.tangent_speed, scalar.rolling_resistance),
                "contact {k}"
            );
            rare_lanes += usize::from(rare);
            // The lane is not left as it was (the comparison is not of two
            // default records).
            assert_ne!(direct.0, WideConstraint::default());
        }
        // Some lanes rare, some not; −0 is not rare.
        assert!(rare_lanes > 0 && rare_lanes < 48, "{rare_lanes}");
    }

    #[test]
    fn a_colour_solved_in_lanes_gives_the_bits_of_the_scalar_solver() {
        // With tangent speeds and rolling resistance (the passes read the
        // rare fields), and without (they do not).
        for rare in [true, false] {
            lanes_give_the_scalar_bits(rare);
        }
    }

    /// The scene solved by the scalar solver and by each lane type; `rare`:
    /// whether some constraints keep their tangent speeds and rolling
    /// resistance (else those are zeroed and the passes run without the
    /// rare fields).
    fn lanes_give_the_scalar_bits(rare: bool) {
        let (bodies, masses, mut constraints) = scene();
        if !rare {
            for c in &mut constraints {
                (c.tangent_speed, c.rolling_resistance, c.rolling_impulse) = (0.0, 0.0, 0.0);
            }
        }
        assert_eq!(
            constraints
                .iter()
                .any(|c| is_rare(c.tangent_speed, c.rolling_resistance)),
            rare
        );
        let softness = step_softness();
        let mut colouring = Colouring::default();
        colouring.clear(13);
        for c in &constraints {
            let dynamic = |k: usize| (k != 0).then_some(k);
            colouring.add(dynamic(c.a), dynamic(c.b));
        }
        let records = colouring.finish();
        assert_eq!(colouring.overflow(), 0);
        let mut wide = vec![WideConstraint::default(); records];
        let mut extra = vec![WideExtra::default(); records];
        let mut order = vec![(0, 0); constraints.len()];
        for (i, c) in constraints.iter().enumerate() {
            let Slot::Lane { record, lane } = colouring.slot(i) else {
                unreachable!("no overflow")
            };
            set_lane((&mut wide[record], &mut extra[record]), lane, c, &softness);
            order[i] = (record, lane);
        }
        for (record, lane) in colouring.padding() {
            set_padding_lane((&mut wide[record], &mut extra[record]), lane);
        }
        // The scalar reference visits the constraints in the order the
        // lanes solve them in: record after record, lane after lane.
        let mut by_lane: Vec<usize> = (0..constraints.len()).collect();
        by_lane.sort_by_key(|&i| order[i]);
        let mut scalar: Vec<ContactConstraint> = by_lane.iter().map(|&i| constraints[i]).collect();
        let inv_h = 240.0;
        let mut scalar_bodies = bodies.clone();
        for _ in 0..3 {
            contact_solver::warm_start(&mut scalar, &mut scalar_bodies);
            contact_solver::solve(&mut scalar, &mut scalar_bodies, inv_h, true);
            contact_solver::solve(&mut scalar, &mut scalar_bodies, inv_h, false);
        }
        contact_solver::restitution(&mut scalar, &mut scalar_bodies, 1.0);
        let mut set = super::super::contacts::ContactSet::default();
        for (i, c) in constraints.iter().enumerate() {
            set.create(
                (2 * i, 2 * i + 1),
                (c.a, c.b),
                super::super::contacts::tests::material(),
                false,
            );
            set.contacts[i].count = c.count;
        }
        let mut reference = set.contacts.clone();
        contact_solver::store_impulses(&scalar, &mut reference);
        // Each lane type (SSE2 on every x86-64 CPU, AVX and AVX-512 where
        // the CPU has them), then the dispatched passes (the lanes this CPU
        // runs): same operations in the same order on the same data as the
        // scalar solver, so equal bits.
        fn passes<L: Lanes>(
            (wide, extra): (&mut [WideConstraint], &mut [WideExtra]),
            (bodies, masses): (&mut [SolverBody], BodyMasses<'_>),
            (inv_h, softness, rare): (f64, &StepSoftness, bool),
        ) {
            fn shared<'a>(bodies: &'a mut [SolverBody], masses: BodyMasses<'a>) -> PassBodies<'a> {
                PassBodies {
                    rows: Bodies::new(bodies),
                    masses,
                }
            }
            for _ in 0..3 {
                warm_start_with::<L>(wide, rare.then_some(&mut *extra), shared(bodies, masses));
                solve_with::<L>(wide, shared(bodies, masses), inv_h, softness);
                relax_with::<L>(
                    wide,
                    rare.then_some(&mut *extra),
                    shared(bodies, masses),
                    inv_h,
                );
            }
            restitution_with::<L>(wide, extra, shared(bodies, masses), 1.0);
        }
        for path in ["SSE2", "AVX", "AVX-512", "dispatched"] {
            if !lane_type_runs(path) {
                continue;
            }
            let (mut wide, mut extra, mut wide_bodies) =
                (wide.clone(), extra.clone(), bodies.clone());
            let records = (&mut wide[..], &mut extra[..]);
            let settings = (inv_h, &softness, rare);
            match path {
                "SSE2" => passes::<F64x4>(records, (&mut wide_bodies, &masses), settings),
                "AVX" => passes::<Avx4>(records, (&mut wide_bodies, &masses), settings),
                "AVX-512" => passes::<Avx8>(records, (&mut wide_bodies, &masses), settings),
                _ => {
                    let (wide, extra) = records;
                    for _ in 0..3 {
                        let bodies = &mut wide_bodies;
                        warm_start(wide, rare.then_some(&mut *extra), bodies, &masses);
                        solve(wide, bodies, &masses, inv_h, &softness);
                        relax(wide, rare.then_some(&mut *extra), bodies, &masses, inv_h);
                    }
                    restitution(wide, extra, &mut wide_bodies, &masses, 1.0);
                }
            }
            assert_eq!(scalar_bodies, wide_bodies, "{path}, rare: {rare}");
            let mut contacts = set.contacts.clone();
            for (i, &(record, lane)) in order.iter().enumerate() {
                store_lane((&wide[record], &extra[record]), lane, &mut contacts[i]);
            }
            assert_eq!(reference, contacts, "{path}, rare: {rare}");
        }
        // Restitution acted somewhere (the test covers it).
        assert!(
            scalar
                .iter()
                .zip(&constraints)
                .any(|(c, _)| c.restitution > 0.0 && c.points[0].normal_velocity < -1.0)
        );
    }
}
