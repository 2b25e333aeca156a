//! Impacts on jointed bodies under the exact model: the contact impulses
//! solved in the joints' constrained space, so that the velocities after
//! the impact satisfy every joint's velocity rows exactly and each
//! contact point gets its restitution target (`docs/joints.md`,
//! "Impacts on jointed bodies").
//!
//! With v the generalised velocities (x, y, θ of every dynamic body), M
//! the mass matrix, J_j the joints' Jacobian (J_j v = 0 before the impact)
//! and J_c, W_c the contact rows' measure and push Jacobians
//! ([`super::rows`]), an impulse λ_c on the contacts and μ on the joints
//! give
//!
//! ```text
//! M Δv = W_cᵀ λ_c + J_jᵀ μ,      J_j (v + Δv) = 0.
//! ```
//!
//! Eliminating μ: Δv = P W_cᵀ λ_c with the constrained mobility
//!
//! ```text
//! P = M⁻¹ − M⁻¹ J_jᵀ (J_j M⁻¹ J_jᵀ)⁻¹ J_j M⁻¹,
//! ```
//!
//! so the contact problem keeps its form (normal rows λ ≥ 0 with the
//! restitution targets, friction in its cone, [`super::solver`]) with the
//! effective mass K = J_c P W_cᵀ in place of J_c M⁻¹ W_cᵀ. Without joints
//! P = M⁻¹ and this is seed eq. 7.15. For one point at distance ρ from
//! the pivot of a body pinned there, the normal across the arm, K =
//! ρ²/I_pivot (I_pivot = I_cm + m d², d the centre's distance to the
//! pivot): the body's inertia about the pivot seen from the contact,
//! where the free solve would take 1/m + (r × n)²/I_cm.
//! The joints' own impulse μ (the pivot's reaction) is implied; it is
//! never needed.
//!
//! Resting contacts on jointed bodies use the same K at the acceleration
//! level ([`super::resting`], "On jointed bodies"), with the free
//! accelerations the joints leave ([`accelerations`]).

use super::rows::{BodyView, Row};
use crate::body::{Body, BodyState};
use crate::exact::joints::ExactJoints;
use crate::exact::ode::Layout;
use crate::shape::cross;
use crate::tunables::REDUNDANT_PIVOT;
use nalgebra::Vector2;

/// Adds row `row`'s generalised column along `direction` (its measure u
/// or its push w) to `out` (the layout's positions long): ±u on the
/// body's x, y and ±(r × u) on its θ.
fn add_column(row: &Row, direction: Vector2<f64>, layout: &Layout, out: &mut [f64]) {
    for s in &row.sides {
        let Some(slot) = layout.slots[s.body] else {
            continue;
        };
        let o = slot.offset;
        out[o] += s.sign * direction.x;
        out[o + 1] += s.sign * direction.y;
        if slot.rotates {
            out[o + 2] += s.sign * cross(s.arm, direction);
        }
    }
}

/// The pairs of bodies a live joint connects (both present), so that the
/// islands of the impulse solve follow the joints too.
pub(crate) fn joint_pairs(joints: &ExactJoints) -> Vec<(usize, usize)> {
    joints
        .set
        .infos
        .iter()
        .filter(|i| !i.removed)
        .filter_map(|i| Some((i.body_a?, i.body_b?)))
        .collect()
}

/// K = J_c P W_cᵀ (row-major, rows × rows) of `rows` at `states`: the
/// effective mass of the contact rows with the joints held.
/// `scratch` holds the columns P W_cᵀ afterwards.
pub(crate) fn effective_mass(
    joints: &mut ExactJoints,
    bodies: &[Body],
    layout: &Layout,
    states: &[BodyState],
    rows: &[Row],
    k: &mut Vec<f64>,
    scratch: &mut Vec<f64>,
) {
    let (m, n) = (rows.len(), layout.positions);
    scratch.clear();
    scratch.resize(m * n, 0.0);
    for (row, w) in rows.iter().zip(scratch.chunks_mut(n.max(1))) {
        add_column(row, row.push, layout, w);
    }
    joints.mobility(bodies, layout, states, scratch);
    let mut j = vec![0.0; n];
    k.clear();
    k.resize(m * m, 0.0);
    for (i, row) in rows.iter().enumerate() {
        j.iter_mut().for_each(|x| *x = 0.0);
        add_column(row, row.measure, layout, &mut j);
        for c in 0..m {
            let pw = &scratch[c * n..(c + 1) * n];
            k[i * m + c] = j.iter().zip(pw).map(|(a, b)| a * b).sum();
        }
    }
}

/// Zeroes the rows and columns of K (and b) of the rows along which the
/// joints allow no motion: their constrained K_ii below
/// [`REDUNDANT_PIVOT`] of the free J M⁻¹ Wᵀ diagonal (a slider's contact
/// across its rail). Their λ stays 0 (the joints carry the load), where
/// the solver would divide a round-off residual by a round-off mass.
pub(crate) fn drop_locked(rows: &[Row], views: &[BodyView], k: &mut [f64], b: &mut [f64]) {
    let m = rows.len();
    for (i, row) in rows.iter().enumerate() {
        let free = row.coupling(row, views);
        if k[i * m + i] > REDUNDANT_PIVOT * free.abs() {
            continue;
        }
        for c in 0..m {
            k[i * m + c] = 0.0;
            k[c * m + i] = 0.0;
        }
        b[i] = 0.0;
    }
}

/// The accelerations the joints leave the bodies, a_j = a₀ + M⁻¹ J_jᵀ λ₀
/// with (J_j M⁻¹ J_jᵀ) λ₀ = −(J_j a₀ + γ_j) (the joints' force laws in
/// a₀ too): `accelerations` (per body, linear m/s² and angular rad/s²)
/// holds a₀ on entry and a_j on exit; `scratch` is the generalised
/// vector.
pub(crate) fn accelerations(
    joints: &mut ExactJoints,
    bodies: &[Body],
    layout: &Layout,
    states: &[BodyState],
    scratch: &mut Vec<f64>,
    accelerations: &mut [(Vector2<f64>, f64)],
) {
    scratch.clear();
    scratch.resize(layout.positions, 0.0);
    for (slot, (a, alpha)) in layout.slots.iter().zip(accelerations.iter()) {
        let Some(slot) = slot else { continue };
        scratch[slot.offset] = a.x;
        scratch[slot.offset + 1] = a.y;
        if slot.rotates {
            scratch[slot.offset + 2] = *alpha;
        }
    }
    joints.constrain(bodies, layout, states, scratch);
    for (slot, (a, alpha)) in layout.slots.iter().zip(accelerations.iter_mut()) {
        let Some(slot) = slot else { continue };
        *a = Vector2::new(scratch[slot.offset], scratch[slot.offset + 1]);
        if slot.rotates {
            *alpha = scratch[slot.offset + 2];
        }
    }
}

/// Applies the per-body impulses `impulses` (linear N·s, angular N·m·s, as
/// [`Row::apply`] accumulates them) with the joints held: Δv = P F. Updates
/// `views`, `states` and the velocity block of `y`; returns whether any
/// velocity changed.
#[allow(clippy::too_many_arguments)]
pub(crate) fn apply_impulses(
    joints: &mut ExactJoints,
    bodies: &[Body],
    layout: &Layout,
    states: &mut [BodyState],
    views: &mut [BodyView],
    impulses: &[(Vector2<f64>, f64)],
    y: &mut [f64],
) -> bool {
    let n = layout.positions;
    let mut dv = vec![0.0; n];
    for (slot, (f, torque)) in layout.slots.iter().zip(impulses) {
        let Some(slot) = slot else { continue };
        dv[slot.offset] = f.x;
        dv[slot.offset + 1] = f.y;
        if slot.rotates {
            dv[slot.offset + 2] = *torque;
        }
    }
    if dv.iter().all(|x| *x == 0.0) {
        return false;
    }
    joints.mobility(bodies, layout, states, &mut dv);
    let mut changed = false;
    for (i, slot) in layout.slots.iter().enumerate() {
        let Some(slot) = slot else { continue };
        let o = slot.offset;
        let d = Vector2::new(dv[o], dv[o + 1]);
        let dw = if slot.rotates { dv[o + 2] } else { 0.0 };
        if d.x == 0.0 && d.y == 0.0 && dw == 0.0 {
            continue;
        }
        changed = true;
        states[i].velocity += d;
        views[i].velocity = states[i].velocity;
        y[n + o] = states[i].velocity.x;
        y[n + o + 1] = states[i].velocity.y;
        if slot.rotates {
            states[i].angular_velocity += dw;
            views[i].omega = states[i].angular_velocity;
            y[n + o + 2] = states[i].angular_velocity;
        }
    }
    changed
}
