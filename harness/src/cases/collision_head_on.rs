//! Case III, `collision_head_on` (docs/cases.md; seed §7.2 eq. 7.11–7.15): a
//! disc of 1 kg at +2 m/s hits one of 3 kg at rest, e = 1 and e = 0.5, in
//! the engine against eq. 7.15 and the conservation laws, and in
//! rapier2d-f64.

use super::collision_common::{
    IMPULSE_ROUND_OFF, kinetic_energy, rapier_row, rapier_settings, run_engine, run_rapier,
    run_soft_step, soft_step_sink,
};
use super::{Case, CaseReport, Headline, Snapshots};
use crate::row::{RowKind, RowSink};
use anyhow::{Context, Result, ensure};
use engine::ContactEventKind;

/// The head-on impact of two discs.
pub const CASE: Case = Case {
    scenes: &["collision_head_on", "collision_head_on_half"],
    snapshots: Snapshots::ContactEvents,
    headline: &[Headline::new("v1_after_e0.5", "rk4")],
    ..Case::new(
        "collision_head_on",
        "Case III: head-on impact, 1 kg at 2 m/s on 3 kg at rest, e = 1 and 0.5 (seed eq. 7.15)",
        run,
    )
};

/// Runs `collision_head_on`.
pub fn run() -> Result<CaseReport> {
    let mut report = CaseReport::default();
    for (id, e, v1, v2) in [
        ("collision_head_on", 1.0, -1.0, 1.0),
        ("collision_head_on_half", 0.5, -0.25, 0.75),
    ] {
        head_on(&mut report, id, e, v1, v2)?;
    }
    report.notes.push(
        "Head-on: discs of 0.5 m, 1 kg at +2 m/s and 3 kg at rest, centres 3.057 m apart; no \
         gravity. Eq. 7.15 with r × N = 0: j = (1 + e)·2/(1/1 + 1/3) N·s."
            .into(),
    );
    Ok(report)
}

fn head_on(report: &mut CaseReport, id: &str, e: f64, v1: f64, v2: f64) -> Result<()> {
    let run = run_engine(id)?;
    let (a, b) = (run.body("m1")?, run.body("m2")?);
    let tag = if e == 1.0 { "e1" } else { "e0.5" };
    let dt = run.scene.dt();
    let method = run.scene.method().id();
    let s = run.world.states();
    let (m1, m2) = (1.0, 3.0);
    let impacts = run.events(ContactEventKind::Impact);
    ensure!(impacts.len() == 1, "{id}: {} impacts", impacts.len());
    let eps = run.world.contact_settings().tolerance;
    let j = (1.0 + e) * 2.0 / (1.0 / m1 + 1.0 / m2);
    let energy_after = 0.5 * m1 * v1 * v1 + 0.5 * m2 * v2 * v2;
    let mut sink = RowSink {
        case: "collision_head_on",
        method,
        dt,
        rows: &mut report.rows,
    };
    let why = format!(
        "eq. 7.15 and 7.11-7.12; no force after the impact, so the velocities are the \
         solver's impulse applied once: round-off of O(1) numbers, {IMPULSE_ROUND_OFF:e} \
         (docs/cases.md)"
    );
    sink.within(
        RowKind::Validation,
        &format!("v1_after_{tag}"),
        s[a].velocity.x,
        v1,
        IMPULSE_ROUND_OFF,
        &why,
    );
    sink.within(
        RowKind::Validation,
        &format!("v2_after_{tag}"),
        s[b].velocity.x,
        v2,
        IMPULSE_ROUND_OFF,
        &why,
    );
    sink.within(
        RowKind::Validation,
        &format!("momentum_{tag}"),
        m1 * s[a].velocity.x + m2 * s[b].velocity.x,
        m1 * 2.0,
        IMPULSE_ROUND_OFF,
        "momentum m1 v1 + m2 v2 = 2 kg·m/s is kept by equal and opposite impulses; round-off, 1e-12 (docs/cases.md)",
    );
    sink.within(
        RowKind::Validation,
        &format!("kinetic_energy_{tag}"),
        kinetic_energy(run.world.bodies(), s),
        energy_after,
        IMPULSE_ROUND_OFF,
        "½ m1 v1'² + ½ m2 v2'² of the closed-form velocities (2 J kept for e = 1); round-off",
    );
    sink.within(
        RowKind::Validation,
        &format!("impulse_{tag}"),
        impacts[0].normal_impulse,
        j,
        IMPULSE_ROUND_OFF,
        "j = (1 + e)·|v_n|/(1/m1 + 1/m2) (eq. 7.15, r × N = 0); round-off",
    );
    let defs = run.scene.bodies();
    let gap = (defs[b].state.position.x - defs[a].state.position.x) - 1.0;
    let t_hit = gap / 2.0;
    sink.within(
        RowKind::Validation,
        &format!("impact_time_{tag}"),
        impacts[0].t,
        t_hit,
        eps / 2.0,
        format!(
            "the {gap} m gap between the discs (radii 0.5 m) closes at 2 m/s at t = {t_hit} s, \
             inside a step; the seed's bisection stops when the separation is within \
             ε = {eps:e} m, i.e. within ε/(2 m/s) of it"
        ),
    );
    // rapier2d on the same scene.
    let rapier = run_rapier(&run.scene)?;
    let last = rapier.samples.last().context("rapier ran no step")?;
    let (r1, r2) = (last[a].velocity[0], last[b].velocity[0]);
    let contact_steps = rapier
        .contacts
        .iter()
        .filter(|c| (c.body_a, c.body_b) == (a, b))
        .count();
    let rdt = rapier_settings(&run.scene).dt;
    let case = "collision_head_on";
    let rows = &mut report.rows;
    let model = format!(
        "rapier solves a single new contact point by one sequential-impulse row with the \
         restitution target -e v_n (v_n at the start of the step it is found in, equal to the \
         velocity at contact since no force acts): exact to round-off, {IMPULSE_ROUND_OFF:e}; \
         {contact_steps} step(s) with a contact impulse"
    );
    rapier_row(
        RowKind::Validation,
        rows,
        case,
        rdt,
        &format!("v1_after_{tag}"),
        r1,
        v1,
        IMPULSE_ROUND_OFF,
        &model,
    );
    rapier_row(
        RowKind::Validation,
        rows,
        case,
        rdt,
        &format!("v2_after_{tag}"),
        r2,
        v2,
        IMPULSE_ROUND_OFF,
        &model,
    );
    rapier_row(
        RowKind::Validation,
        rows,
        case,
        rdt,
        &format!("momentum_{tag}"),
        m1 * r1 + m2 * r2,
        2.0,
        1e-12,
        "rapier applies equal and opposite impulses: momentum is kept to round-off",
    );
    report.notes.push(format!(
        "`{id}`: engine v1' - ({v1}) = {:.1e}, v2' - {v2} = {:.1e} m/s; rapier2d v1' - ({v1}) = \
         {:.1e}, v2' - {v2} = {:.1e} m/s ({contact_steps} step(s) with a contact impulse, dt = {rdt} s).",
        s[a].velocity.x - v1,
        s[b].velocity.x - v2,
        r1 - v1,
        r2 - v2,
    ));
    report.notes.push(run.profile_note(id));
    soft_step(report, id, (v1, v2))
}

/// The same impact under the soft-step model. The discs meet along the
/// line of centres at one point; at 2 m/s they close at most 0.02 m per
/// step, the speculative distance, so the point is found before they
/// overlap. Every impulse of that step (the speculative stop, the soft
/// and relax passes, the restitution pass) acts at the same anchors along
/// the same normal: they add up to one impulse, and the restitution pass
/// sets the final normal velocity to −e × the approach speed measured at
/// the step's start, which no force changed. So the soft step gives
/// eq. 7.15's velocities to round-off.
fn soft_step(report: &mut CaseReport, id: &str, (v1, v2): (f64, f64)) -> Result<()> {
    let run = run_soft_step(id)?;
    let (a, b) = (run.body("m1")?, run.body("m2")?);
    let tag = if id.ends_with("half") { "e0.5" } else { "e1" };
    let s = run.world.states();
    let mut sink = soft_step_sink(&mut report.rows, "collision_head_on", &run);
    let why = "one speculative point found before overlap (2 m/s × 0.01 s = the 0.02 m \
               speculative distance): the step's impulses act at one point along one normal \
               and the restitution pass ends at −e × the approach speed, so eq. 7.15 holds \
               to round-off, 1e-12";
    sink.within(RowKind::Validation, &format!("v1_after_{tag}"), s[a].velocity.x, v1, IMPULSE_ROUND_OFF, why);
    sink.within(RowKind::Validation, &format!("v2_after_{tag}"), s[b].velocity.x, v2, IMPULSE_ROUND_OFF, why);
    sink.within(
        RowKind::Validation,
        &format!("momentum_{tag}"),
        s[a].velocity.x + 3.0 * s[b].velocity.x,
        2.0,
        IMPULSE_ROUND_OFF,
        "equal and opposite impulses keep m1 v1 + m2 v2 = 2 kg·m/s; round-off",
    );
    Ok(())
}

