//! Semi-implicit (symplectic) Euler, order 1.
//!
//! On a mechanical state `[q, v]`: `v1 = v0 + h a(t0, q0, v0)`, then
//! `q1 = q0 + h v1`. Symplectic: on the spring its energy error stays
//! bounded (docs/cases.md: ΔE/E0 in [−0.1365, +0.1878] at h = 0.2) and it is
//! stable iff `hω < 2`. On a parabola its position errs by `−g h t / 2`.

use super::Workspace;
use crate::ode::OdeSystem;

/// One step of size `h`; `n` is the number of positions. One evaluation.
pub(crate) fn step<S: OdeSystem + ?Sized>(
    sys: &mut S,
    n: usize,
    t: f64,
    y: &[f64],
    h: f64,
    ws: &mut Workspace,
    out: &mut [f64],
) {
    let k1 = &mut ws.k[0];
    sys.derivative(t, y, k1);
    ws.evaluations += 1;
    for i in 0..n {
        let v1 = y[n + i] + h * k1[n + i];
        out[n + i] = v1;
        out[i] = y[i] + h * v1;
    }
}
