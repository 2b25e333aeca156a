//! `contact_forces` (issue 17): the contact data the soft step reports
//! ([`engine::World::contact_data`]) carries the loads of a resting pile. A
//! stack of 5 boxes and a pyramid with a base of 4 rest on the ground; after
//! 4 s, the normal impulses each contact delivered over the last step,
//! summed with their signs on each box (+J n on the pair's second shape,
//! −J n on its first), must equal the box's weight times the step.
//!
//! Why they must, and how closely: over one step the box's vertical
//! momentum changes by the contact impulses minus m g dt. The normal
//! impulses' step totals are reported (`total_normal_impulse`). Friction
//! is reported as the accumulated impulse of the last substep, which at
//! rest each of the n substeps applies again (warm start, no correction):
//! its step total is n times it; in this scene it is horizontal (the
//! pyramid's boxes are 5 cm apart in a row, so none hangs on a neighbour's
//! friction). So Σ J_y − m g dt = m Δv_y (first row: this identity, which
//! tests the reporting), and a resting box's Δv_y is what is left of the
//! pile's settling (second row). At the soft model's fixed point every
//! substep's normal impulse is exactly m g h, so the closed form holds
//! exactly there; the second row measures how far 4 s of settling leave
//! the pile from it.

use crate::row::RowKind;
use super::soft_step_common::SOFT_STEP;
use super::{Case, CaseReport};
use crate::row::RowSink;
use crate::scenes;
use anyhow::{Context, Result};
use engine::{BodyState, ContactModel, step_count};

/// The resting stack and pyramid.
pub const CASE: Case = Case {
    scenes: &["contact_forces"],
    ..Case::new(
        "contact_forces",
        "Soft step: the reported normal impulses carry each resting box's weight",
        run,
    )
};

/// Runs `contact_forces`.
pub fn run() -> Result<CaseReport> {
    let scene = scenes::load("contact_forces")?;
    let substeps = match scene.contact() {
        Some(ContactModel::SoftStep(s)) => s.substeps as f64,
        _ => anyhow::bail!("contact_forces: the scene must use the soft step"),
    };
    let mut world = scene.build_world(None)?;
    let dt = scene.dt();
    let g = 10.0;
    let steps = step_count(scene.duration(), dt)?;
    let mut before: Vec<BodyState> = Vec::new();
    for k in 0..steps {
        if k + 1 == steps {
            before = world.states().to_vec();
        }
        world.step(dt).context("stepping contact_forces")?;
    }
    // Σ J_y per body over the last step.
    let mut carried = vec![0.0; world.bodies().len()];
    for c in world.contact_data()? {
        let normal: f64 = c.points().iter().map(|p| p.total_normal_impulse).sum();
        let tangent: f64 = c.points().iter().map(|p| p.tangent_impulse).sum();
        // Tangent (n.y, −n.x): its vertical component is −n.x.
        let j_y = normal * c.normal.y - substeps * tangent * c.normal.x;
        carried[c.b.body] += j_y;
        carried[c.a.body] -= j_y;
    }
    let mut report = CaseReport::default();
    let mut rows = RowSink {
        case: "contact_forces",
        method: SOFT_STEP,
        dt,
        rows: &mut report.rows,
    };
    let (mut identity, mut residual) = (0.0f64, 0.0f64);
    let (mut worst_identity, mut worst_residual) = (String::new(), String::new());
    for (id, body) in world.bodies().iter().enumerate() {
        if !body.is_dynamic() {
            continue;
        }
        let weight = body.mass * g * dt;
        let dv = world.states()[id].velocity.y - before[id].velocity.y;
        let id_error = (carried[id] - (weight + body.mass * dv)).abs() / weight;
        let error = (carried[id] - weight).abs() / weight;
        if id_error >= identity {
            identity = id_error;
            worst_identity.clone_from(&body.name);
        }
        if error >= residual {
            residual = error;
            worst_residual.clone_from(&body.name);
        }
    }
    rows.at_most(
        RowKind::Validation,
        "momentum_balance",
        identity,
        0.0,
        1e-12,
        format!(
            "validation of the reporting against an identity: for every box, \
             |Σ J_y − m (g dt + Δv_y)| / (m g dt) over the last step (worst: {worst_identity}), \
             J_y the normal impulses' step totals plus n = 4 times the last substep's \
             friction impulse (horizontal here, see the module docs): the impulses the \
             solver applied, summed with a few roundings per contact: 1e-12"
        ),
    );
    rows.at_most(
        RowKind::Validation,
        "weight_carried",
        residual,
        0.0,
        1e-6,
        format!(
            "validation against the closed form m g dt (the weight times the step), with a \
             criterion of rest: the largest |Σ J_y − m g dt| / (m g dt) over the 15 boxes \
             after 4 s (worst: {worst_residual}). The soft model's fixed point carries the \
             weight exactly (each substep's normal impulse m g h); by the identity above \
             the departure is the box's residual vertical acceleration over g, |Δv_y| / \
             (g dt), what the pile's settling leaves. Criterion: a box at rest carries its \
             weight to one part in a million, 1e-6"
        ),
    );
    report.notes.push(format!(
        "`contact_forces`: after {} steps the largest departure of a box's reported \
         normal impulses from its weight times the step is {residual:.3e} of it \
         ({worst_residual}); the momentum identity holds to {identity:.3e}.",
        steps
    ));
    Ok(report)
}
