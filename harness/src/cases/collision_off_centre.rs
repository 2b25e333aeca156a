//! Case III, `collision_off_centre` (docs/cases.md; seed §7.2 eq. 7.1–7.16): a
//! turned box's corner hits a box's face off the line of centres, e = 1 and
//! e = 0.5, in the engine against eq. 7.15 at the exact contact point and
//! the conservation laws, and in rapier2d-f64.

use super::collision_common::{
    EngineRun, IMPULSE_ROUND_OFF, kinetic_energy, rapier_row, rapier_settings, run_rapier,
    run_soft_step, soft_step_sink,
};
use super::{Case, CaseReport, Headline, Snapshots};
use crate::row::{RowKind, RowSink};
use crate::scenes;
use anyhow::{Context, Result, ensure};
use engine::validation::contact::{ImpactBody, ImpactOutcome, Velocities, impact_eq_7_15};
use engine::{Body, ContactEventKind, Shape};
use nalgebra::Vector2;

/// The off-centre impact of two boxes.
pub const CASE: Case = Case {
    scenes: &["collision_off_centre", "collision_off_centre_half"],
    snapshots: Snapshots::ContactEvents,
    headline: &[Headline::new("omega_a_after_e0.5", "rk4")],
    ..Case::new(
        "collision_off_centre",
        "Case III: off-centre impact of two boxes against eq. 7.15, momentum and energy",
        run,
    )
};

/// The closed form of the off-centre impact: A's leading corner meets B's
/// face x = −0.5 (B a unit box at the origin at rest, A translating at
/// +vx without turning), and eq. 7.15 there.
struct OffCentre {
    t_hit: f64,
    point: Vector2<f64>,
    outcome: ImpactOutcome,
    /// Largest change of any velocity component when the contact point
    /// moves by ±ε along x or y.
    sensitivity: f64,
    a: (f64, f64),
    b: (f64, f64),
}

fn off_centre_closed_form(run: &EngineRun, e: f64) -> Result<OffCentre> {
    let defs = run.scene.bodies();
    let (ia, ib) = (run.body("a")?, run.body("b")?);
    let (body_a, sa) = Body::from_def(&defs[ia])?;
    let (body_b, sb) = Body::from_def(&defs[ib])?;
    let Some(Shape::Polygon(poly)) = &body_a.shape else {
        anyhow::bail!("body a is not a polygon");
    };
    let Some(Shape::Polygon(poly_b)) = &body_b.shape else {
        anyhow::bail!("body b is not a polygon");
    };
    let face = poly_b
        .vertices()
        .iter()
        .map(|v| v.x)
        .fold(f64::INFINITY, f64::min)
        + sb.position.x;
    let corner = poly
        .vertices()
        .iter()
        .map(|v| sa.to_world_offset(*v))
        .max_by(|p, q| p.x.total_cmp(&q.x))
        .context("a polygon has vertices")?;
    let t_hit = (face - (sa.position.x + corner.x)) / sa.velocity.x;
    let centre_a = sa.position + t_hit * sa.velocity;
    let point = centre_a + corner;
    let (ma, ia_) = (body_a.mass, body_a.inertia.context("a rotates")?);
    let (mb, ib_) = (body_b.mass, body_b.inertia.context("b rotates")?);
    let eq = |p: Vector2<f64>| {
        impact_eq_7_15(
            &ImpactBody {
                mass: ma,
                inertia: ia_,
                arm: p - centre_a,
                velocities: Velocities {
                    linear: sa.velocity,
                    angular: sa.angular_velocity,
                },
            },
            &ImpactBody {
                mass: mb,
                inertia: ib_,
                arm: p - sb.position,
                velocities: Velocities {
                    linear: sb.velocity,
                    angular: sb.angular_velocity,
                },
            },
            -Vector2::x(),
            e,
        )
    };
    let outcome = eq(point);
    let eps = run.world.contact_settings().tolerance;
    let components = |o: &ImpactOutcome| {
        [
            o.a.linear.x,
            o.a.linear.y,
            o.a.angular,
            o.b.linear.x,
            o.b.linear.y,
            o.b.angular,
            o.impulse,
        ]
    };
    let base = components(&outcome);
    let mut sensitivity = 0.0f64;
    for d in [
        Vector2::new(eps, 0.0),
        Vector2::new(-eps, 0.0),
        Vector2::new(0.0, eps),
        Vector2::new(0.0, -eps),
    ] {
        for (x, y) in components(&eq(point + d)).iter().zip(&base) {
            sensitivity = sensitivity.max((x - y).abs());
        }
    }
    Ok(OffCentre {
        t_hit,
        point,
        outcome,
        sensitivity,
        a: (ma, ia_),
        b: (mb, ib_),
    })
}

/// Runs `collision_off_centre`.
pub fn run() -> Result<CaseReport> {
    let mut report = CaseReport::default();
    for (id, e) in [
        ("collision_off_centre", 1.0),
        ("collision_off_centre_half", 0.5),
    ] {
        off_centre(&mut report, id, e)?;
    }
    report.notes.push(
        "Off-centre: A (0.4 m x 0.2 m, 1 kg, turned 0.5 rad, +2 m/s) hits B (1 m x 1 m, \
         2 kg, at rest) with one corner, 0.308 m off B's centre line; the expected values \
         are eq. 7.15 and 7.11-7.14 at the exact contact point and time."
            .into(),
    );
    Ok(report)
}

fn off_centre(report: &mut CaseReport, id: &str, e: f64) -> Result<()> {
    // Stop right after the first impact: read the velocities it produced.
    let scene = scenes::load(id)?;
    let mut world = scene.build_world(None)?;
    world.set_profiling(true);
    let dt = scene.dt();
    let mut steps = 0u64;
    while !world
        .contact_events()
        .iter()
        .any(|c| c.kind == ContactEventKind::Impact)
    {
        world.step_to((steps + 1) as f64 * dt)?;
        steps += 1;
        ensure!(steps <= scene.steps(), "{id}: no impact");
    }
    let trace = engine::Trace::default();
    let run = EngineRun {
        scene,
        world,
        trace,
    };
    let closed = off_centre_closed_form(&run, e)?;
    let (ia, ib) = (run.body("a")?, run.body("b")?);
    let impacts = run.events(ContactEventKind::Impact);
    ensure!(
        impacts.len() == 1 && impacts[0].points == 1,
        "{id}: expected one impact at one point, found {} impact(s){}",
        impacts.len(),
        impacts
            .first()
            .map_or(String::new(), |i| format!(", the first at {} point(s)", i.points))
    );
    let hit = impacts[0];
    let s = run.world.states();
    let tag = if e == 1.0 { "e1" } else { "e0.5" };
    let eps = run.world.contact_settings().tolerance;
    let tol = 2.0 * closed.sensitivity + IMPULSE_ROUND_OFF;
    let why = format!(
        "eq. 7.15, 7.11-7.14 at the exact contact (t = {:.12} s, P = ({:.6}, {:.6}) m); the \
         engine stops within ε = {eps:e} m of contact, so its P may differ by ε: twice the \
         largest change of these values when P moves by ±ε ({:.2e}), plus {IMPULSE_ROUND_OFF:e} \
         round-off",
        closed.t_hit, closed.point.x, closed.point.y, closed.sensitivity
    );
    let o = &closed.outcome;
    let method = run.scene.method().id();
    let mut sink = RowSink {
        case: "collision_off_centre",
        method,
        dt,
        rows: &mut report.rows,
    };
    for (check, value, expected) in [
        ("va_x_after", s[ia].velocity.x, o.a.linear.x),
        ("va_y_after", s[ia].velocity.y, o.a.linear.y),
        ("omega_a_after", s[ia].angular_velocity, o.a.angular),
        ("vb_x_after", s[ib].velocity.x, o.b.linear.x),
        ("vb_y_after", s[ib].velocity.y, o.b.linear.y),
        ("omega_b_after", s[ib].angular_velocity, o.b.angular),
        ("impulse", hit.normal_impulse, o.impulse),
    ] {
        sink.within(RowKind::Validation, &format!("{check}_{tag}"), value, expected, tol, &why);
    }
    sink.within(
        RowKind::Validation,
        &format!("impact_time_{tag}"),
        hit.t,
        closed.t_hit,
        eps / 2.0,
        format!("the corner closes the gap at 2 m/s: bisection to ε = {eps:e} m gives ε/(2 m/s)"),
    );
    let (ma, ia_) = closed.a;
    let (mb, ib_) = closed.b;
    let (a0, b0) = (run.scene.bodies()[ia].state, run.scene.bodies()[ib].state);
    let p0 = ma * a0.velocity + mb * b0.velocity;
    let p = ma * s[ia].velocity + mb * s[ib].velocity;
    sink.within(
        RowKind::Validation,
        &format!("momentum_x_{tag}"),
        p.x,
        p0.x,
        IMPULSE_ROUND_OFF,
        "linear momentum is kept by equal and opposite impulses (eq. 7.11-7.12); round-off, 1e-12",
    );
    sink.within(
        RowKind::Validation,
        &format!("momentum_y_{tag}"),
        p.y,
        p0.y,
        IMPULSE_ROUND_OFF,
        "linear momentum is kept by equal and opposite impulses (eq. 7.11-7.12); round-off, 1e-12",
    );
    // Angular momentum about the origin: Σ m (x × v) + I ω, kept by an
    // impulse pair acting at one point.
    let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
    let l0 = ma * cross(a0.position, a0.velocity)
        + ia_ * a0.angular_velocity
        + mb * cross(b0.position, b0.velocity)
        + ib_ * b0.angular_velocity;
    let l1 = ma * cross(s[ia].position, s[ia].velocity)
        + ia_ * s[ia].angular_velocity
        + mb * cross(s[ib].position, s[ib].velocity)
        + ib_ * s[ib].angular_velocity;
    sink.within(
        RowKind::Validation,
        &format!("angular_momentum_{tag}"),
        l1,
        l0,
        IMPULSE_ROUND_OFF,
        "angular momentum about the origin, Σ m x × v + I ω, is kept by an impulse pair at one point (eq. 7.13-7.14); round-off",
    );
    let ke = kinetic_energy(run.world.bodies(), s);
    if e == 1.0 {
        sink.within(
            RowKind::Validation,
            "kinetic_energy_e1",
            ke,
            0.5 * ma * 4.0,
            IMPULSE_ROUND_OFF,
            "e = 1: kinetic energy (with rotation) is kept, ½·1 kg·(2 m/s)² = 2 J; round-off",
        );
    } else {
        let expected = 0.5 * ma * o.a.linear.norm_squared()
            + 0.5 * ia_ * o.a.angular * o.a.angular
            + 0.5 * mb * o.b.linear.norm_squared()
            + 0.5 * ib_ * o.b.angular * o.b.angular;
        sink.within(
            RowKind::Validation,
            "kinetic_energy_e0.5",
            ke,
            expected,
            tol * 4.0,
            "the kinetic energy of eq. 7.15's velocities (e < 1 loses some), to the tolerance of the velocities",
        );
    }
    // rapier2d.
    let rapier = run_rapier(&run.scene)?;
    let last = rapier.samples.last().context("rapier ran no step")?;
    let rdt = rapier_settings(&run.scene).dt;
    let contact_steps = rapier.contacts.len();
    let first = rapier.contacts.first().map_or(f64::NAN, |c| c.t);
    let why = format!(
        "rapier solves the new one-point contact in the step where it appears (the first \
         ending at {first} s; {contact_steps} step(s) with an impulse) by one \
         sequential-impulse row whose restitution target -e v_n uses the velocity at the start \
         of that step, equal to the velocity at contact (no force acts): eq. 7.15 to \
         round-off; 1e-12 bounds a dozen roundings of the O(1)-O(10) lever-arm terms"
    );
    let case = "collision_off_centre";
    for (check, value, expected) in [
        ("va_x_after", last[ia].velocity[0], o.a.linear.x),
        ("va_y_after", last[ia].velocity[1], o.a.linear.y),
        ("omega_a_after", last[ia].angular_velocity, o.a.angular),
        ("vb_x_after", last[ib].velocity[0], o.b.linear.x),
        ("vb_y_after", last[ib].velocity[1], o.b.linear.y),
        ("omega_b_after", last[ib].angular_velocity, o.b.angular),
    ] {
        rapier_row(
            RowKind::Validation,
            &mut report.rows,
            case,
            rdt,
            &format!("{check}_{tag}"),
            value,
            expected,
            IMPULSE_ROUND_OFF,
            &why,
        );
    }
    let rp = [
        ma * last[ia].velocity[0] + mb * last[ib].velocity[0],
        ma * last[ia].velocity[1] + mb * last[ib].velocity[1],
    ];
    rapier_row(
        RowKind::Validation,
        &mut report.rows,
        case,
        rdt,
        &format!("momentum_x_{tag}"),
        rp[0],
        2.0,
        1e-12,
        "rapier applies equal and opposite impulses: momentum kept to round-off",
    );
    if e == 1.0 {
        let rke = 0.5 * ma * (last[ia].velocity[0].powi(2) + last[ia].velocity[1].powi(2))
            + 0.5 * ia_ * last[ia].angular_velocity.powi(2)
            + 0.5 * mb * (last[ib].velocity[0].powi(2) + last[ib].velocity[1].powi(2))
            + 0.5 * ib_ * last[ib].angular_velocity.powi(2);
        rapier_row(
            RowKind::Validation,
            &mut report.rows,
            case,
            rdt,
            "kinetic_energy_e1",
            rke,
            2.0,
            IMPULSE_ROUND_OFF,
            "rapier, e = 1: eq. 7.15's velocities to round-off keep the kinetic energy, 2 J",
        );
    }
    let diff = |v: f64, w: f64| v - w;
    report.notes.push(format!(
        "`{id}`: engine after the impact at t = {:.12} s minus eq. 7.15: vA ({:.1e}, {:.1e}) \
         m/s, ωA {:.1e} rad/s, vB ({:.1e}, {:.1e}) m/s, ωB {:.1e} rad/s; rapier2d at the end \
         minus eq. 7.15: vA ({:.1e}, {:.1e}), ωA {:.1e}, vB ({:.1e}, {:.1e}), ωB {:.1e} \
         (first contact impulse in the step ending at {first} s).",
        hit.t,
        diff(s[ia].velocity.x, o.a.linear.x),
        diff(s[ia].velocity.y, o.a.linear.y),
        diff(s[ia].angular_velocity, o.a.angular),
        diff(s[ib].velocity.x, o.b.linear.x),
        diff(s[ib].velocity.y, o.b.linear.y),
        diff(s[ib].angular_velocity, o.b.angular),
        diff(last[ia].velocity[0], o.a.linear.x),
        diff(last[ia].velocity[1], o.a.linear.y),
        diff(last[ia].angular_velocity, o.a.angular),
        diff(last[ib].velocity[0], o.b.linear.x),
        diff(last[ib].velocity[1], o.b.linear.y),
        diff(last[ib].angular_velocity, o.b.angular),
    ));
    report.notes.push(run.profile_note(id));
    soft_step(report, id, &closed.outcome, e)
}

/// The same impact under the soft-step model, run over the whole scene
/// (the boxes separate after one impact and never meet again). A's corner
/// closes at 2 m/s, at most the 0.02 m speculative distance per step, so
/// the point is found before overlap, midway between the corner and B's
/// face. Its anchors differ from the exact contact point only along the
/// normal (x), which does not change r × n; every impulse of the step acts
/// there along the same normal and the restitution pass ends at −e × the
/// approach speed: eq. 7.15 to round-off.
fn soft_step(report: &mut CaseReport, id: &str, o: &ImpactOutcome, e: f64) -> Result<()> {
    let run = run_soft_step(id)?;
    let (ia, ib) = (run.body("a")?, run.body("b")?);
    let s = run.world.states();
    let tag = if e == 1.0 { "e1" } else { "e0.5" };
    let mut sink = soft_step_sink(&mut report.rows, "collision_off_centre", &run);
    let why = "one speculative point found before overlap; the anchors' error lies along the \
               normal, where it leaves r × n unchanged; one total impulse (1 + e) j along one \
               normal: eq. 7.15 to the round-off of a few dozen operations on O(1) numbers, \
               1e-12";
    for (check, value, expected) in [
        ("va_x_after", s[ia].velocity.x, o.a.linear.x),
        ("va_y_after", s[ia].velocity.y, o.a.linear.y),
        ("omega_a_after", s[ia].angular_velocity, o.a.angular),
        ("vb_x_after", s[ib].velocity.x, o.b.linear.x),
        ("vb_y_after", s[ib].velocity.y, o.b.linear.y),
        ("omega_b_after", s[ib].angular_velocity, o.b.angular),
    ] {
        sink.within(RowKind::Validation, &format!("{check}_{tag}"), value, expected, IMPULSE_ROUND_OFF, why);
    }
    Ok(())
}

