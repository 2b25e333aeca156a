//! Explicit (forward) Euler, order 1 (seed §4.3: the Taylor polynomial of
//! degree n = 1, `E = k h`).
//!
//! `y1 = y0 + h f(t0, y0)`. Stable on `y' = λy` iff `|1 + hλ| ≤ 1`: on the
//! real axis `hλ ≥ −2`, and never on the imaginary axis (the spring's
//! amplitude grows by `(1 + (hω)²)^(n/2)`).

use super::Workspace;
use crate::ode::OdeSystem;

/// One step of size `h` from `(t, y)` into `out`; one evaluation.
pub(crate) fn step<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t: f64,
    y: &[f64],
    h: f64,
    ws: &mut Workspace,
    out: &mut [f64],
) {
    let k1 = &mut ws.k[0];
    sys.derivative(t, y, k1);
    ws.evaluations += 1;
    for i in 0..y.len() {
        out[i] = y[i] + h * k1[i];
    }
}
