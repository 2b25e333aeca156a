//! Velocity Verlet, order 2, symplectic for position-dependent forces.
//!
//! On a mechanical state `[q, v]`:
//! `q1 = q0 + h v0 + h²/2 a0`, `a1 = a(t0 + h, q1, v*)`,
//! `v1 = v0 + h/2 (a0 + a1)`, with `a0 = a(t0, q0, v0)`.
//!
//! Velocity-dependent forces (drag) make the textbook scheme implicit in
//! `v1`; we evaluate `a1` at the predictor `v* = v0 + h a0`, whose O(h²)
//! error enters `v1` as O(h³) per step, so the method stays second order.
//! Position-only forces never read `v*`, and the scheme is then exactly the
//! textbook one. Two evaluations per step (`a1` is not reused as the next
//! `a0`, because it was computed at `v*`, not `v1`).
//!
//! Stable on the spring iff `hω < 2`; energy error in [−0.025, 0] at h = 0.2.

use super::Workspace;
use crate::ode::OdeSystem;

/// One step of size `h`; `n` is the number of positions. Two evaluations.
pub(crate) fn step<S: OdeSystem + ?Sized>(
    sys: &mut S,
    n: usize,
    t: f64,
    y: &[f64],
    h: f64,
    ws: &mut Workspace,
    out: &mut [f64],
) {
    let (k1, rest) = ws.k.split_at_mut(1);
    let (a0, a1) = (&mut k1[0], &mut rest[0]);
    let tmp = &mut ws.tmp;
    sys.derivative(t, y, a0);
    for i in 0..n {
        tmp[i] = y[i] + h * y[n + i] + 0.5 * h * h * a0[n + i];
        tmp[n + i] = y[n + i] + h * a0[n + i];
    }
    sys.derivative(t + h, tmp, a1);
    ws.evaluations += 2;
    for i in 0..n {
        out[i] = tmp[i];
        out[n + i] = y[n + i] + 0.5 * h * (a0[n + i] + a1[n + i]);
    }
}
