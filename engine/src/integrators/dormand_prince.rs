//! Dormand–Prince 5(4), adaptive, with FSAL and a PI step-size controller
//! (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.4–II.5, the `dopri5`
//! code).
//!
//! Each attempt computes the fifth-order solution and an embedded
//! fourth-order estimate; the scaled RMS norm of their difference
//! `err = sqrt(mean((e_i / (atol + rtol max(|y_i|, |y1_i|)))²))` decides
//! acceptance (`err ≤ 1`) and the next step through [`super::step_controller`].
//! Stability limits of the fifth-order solution: `hλ ≥ −3.30656789` on the
//! real axis, `hω ≤ 0.99718901` on the imaginary axis (docs/cases.md; the
//! harness measures both by bisection).

use super::{Tolerance, Workspace};
use crate::ode::OdeSystem;

const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// Error coefficients: fifth-order weights minus the embedded fourth-order ones.
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;

/// One Dormand–Prince attempt of size `h` from `(t, y)`, whose derivative
/// `ws.k[0] = f(t, y)` is already known (FSAL). Writes the fifth-order
/// solution to `out`, leaves `f(t + h, out)` in `ws.k[6]`, and returns the
/// scaled error norm. Six new evaluations.
pub(crate) fn attempt<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t: f64,
    y: &[f64],
    h: f64,
    tol: Tolerance,
    ws: &mut Workspace,
    out: &mut [f64],
) -> f64 {
    let Tolerance { rtol, atol } = tol;
    let n = y.len();
    let [k1, k2, k3, k4, k5, k6, k7] = &mut ws.k[..] else {
        unreachable!("workspace holds seven stages")
    };
    let tmp = &mut ws.tmp;
    for i in 0..n {
        tmp[i] = y[i] + h * A21 * k1[i];
    }
    sys.derivative(t + C2 * h, tmp, k2);
    for i in 0..n {
        tmp[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i]);
    }
    sys.derivative(t + C3 * h, tmp, k3);
    for i in 0..n {
        tmp[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
    }
    sys.derivative(t + C4 * h, tmp, k4);
    for i in 0..n {
        tmp[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
    }
    sys.derivative(t + C5 * h, tmp, k5);
    for i in 0..n {
        tmp[i] = y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
    }
    sys.derivative(t + h, tmp, k6);
    for i in 0..n {
        out[i] = y[i] + h * (A71 * k1[i] + A73 * k3[i] + A74 * k4[i] + A75 * k5[i] + A76 * k6[i]);
    }
    sys.derivative(t + h, out, k7);
    ws.evaluations += 6;
    let mut sum = 0.0;
    for i in 0..n {
        let e = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
        let scale = atol + rtol * y[i].abs().max(out[i].abs());
        sum += (e / scale) * (e / scale);
    }
    (sum / n.max(1) as f64).sqrt()
}

/// Hairer's initial step guess (`hinit` of `dopri5`), for order 5, given
/// `ws.k[0] = f(t0, y0)`. One evaluation.
pub(crate) fn initial_step<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t: f64,
    y: &[f64],
    h_max: f64,
    tol: Tolerance,
    ws: &mut Workspace,
) -> f64 {
    let Tolerance { rtol, atol } = tol;
    let n = y.len();
    let mut d0 = 0.0;
    let mut d1 = 0.0;
    for i in 0..n {
        let sk = atol + rtol * y[i].abs();
        d0 += (y[i] / sk).powi(2);
        d1 += (ws.k[0][i] / sk).powi(2);
    }
    let (d0, d1) = ((d0 / n as f64).sqrt(), (d1 / n as f64).sqrt());
    let mut h0 = if d0 <= 1e-10 || d1 <= 1e-10 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    h0 = h0.min(h_max);
    for i in 0..n {
        ws.tmp[i] = y[i] + h0 * ws.k[0][i];
    }
    let (k1, rest) = ws.k.split_at_mut(1);
    sys.derivative(t + h0, &ws.tmp, &mut rest[0]);
    ws.evaluations += 1;
    let mut d2 = 0.0;
    for i in 0..n {
        let sk = atol + rtol * y[i].abs();
        d2 += ((rest[0][i] - k1[0][i]) / sk).powi(2);
    }
    let d2 = (d2 / n as f64).sqrt() / h0;
    let h1 = if d1.max(d2) <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d1.max(d2)).powf(1.0 / 5.0)
    };
    (100.0 * h0).min(h1).min(h_max)
}
