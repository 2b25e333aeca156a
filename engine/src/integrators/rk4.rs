//! The classical fourth-order Runge–Kutta method (seed §4.3, the method the
//! seed's engine used for its cases I and II).
//!
//! `y1 = y + h/6 (k1 + 2k2 + 2k3 + k4)`. Stability polynomial
//! `1 + z + z²/2 + z³/6 + z⁴/24`: stable on the real axis for
//! `hλ ≥ −2.78529356` and on the imaginary axis for `hω ≤ 2√2`. On the seed
//! spring at h = 0.2 it gives x(57.2) = 10.95756 m (docs/cases.md case I).

use super::Workspace;
use crate::ode::OdeSystem;

/// One step of size `h`; four evaluations.
pub(crate) fn step<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t: f64,
    y: &[f64],
    h: f64,
    ws: &mut Workspace,
    out: &mut [f64],
) {
    let n = y.len();
    let [k1, k2, k3, k4, ..] = &mut ws.k[..] else {
        unreachable!("workspace holds seven stages")
    };
    let tmp = &mut ws.tmp;
    sys.derivative(t, y, k1);
    for i in 0..n {
        tmp[i] = y[i] + 0.5 * h * k1[i];
    }
    sys.derivative(t + 0.5 * h, tmp, k2);
    for i in 0..n {
        tmp[i] = y[i] + 0.5 * h * k2[i];
    }
    sys.derivative(t + 0.5 * h, tmp, k3);
    for i in 0..n {
        tmp[i] = y[i] + h * k3[i];
    }
    sys.derivative(t + h, tmp, k4);
    ws.evaluations += 4;
    for i in 0..n {
        out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
}
