//! Explicit midpoint rule (RK2), order 2.
//!
//! `k1 = f(t, y)`, `k2 = f(t + h/2, y + h/2 k1)`, `y1 = y + h k2`. Exact on
//! the vacuum projectile (a quadratic in t). Stability polynomial
//! `1 + z + z²/2`: real-axis limit `hλ ≥ −2`; on the imaginary axis
//! `|R(iy)|² = 1 + y⁴/4 > 1`, a weak growth at every step.

use super::Workspace;
use crate::ode::OdeSystem;

/// One step of size `h`; two evaluations.
pub(crate) fn step<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t: f64,
    y: &[f64],
    h: f64,
    ws: &mut Workspace,
    out: &mut [f64],
) {
    let (k1, rest) = ws.k.split_at_mut(1);
    let (k1, k2) = (&mut k1[0], &mut rest[0]);
    let tmp = &mut ws.tmp;
    sys.derivative(t, y, k1);
    for i in 0..y.len() {
        tmp[i] = y[i] + 0.5 * h * k1[i];
    }
    sys.derivative(t + 0.5 * h, tmp, k2);
    ws.evaluations += 2;
    for i in 0..y.len() {
        out[i] = y[i] + h * k2[i];
    }
}
