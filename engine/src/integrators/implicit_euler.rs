//! Implicit (backward) Euler, order 1, A-stable (seed §4.3).
//!
//! Solves `z = y0 + h f(t0 + h, z)` by Newton's iterations on the same
//! [`OdeSystem`]: the Jacobian of `f` is taken by forward differences and
//! refreshed at every iteration (full Newton). Stable for every step on
//! `y' = λy`, λ < 0 (|1/(1 − hλ)| < 1), and it damps the spring's amplitude.
//!
//! Convergence: `‖Δz‖∞ ≤ 1e-12 (1 + ‖z‖∞)`, at most [`MAX_ITERATIONS`];
//! otherwise a typed [`EngineError::NewtonDiverged`].

use super::Workspace;
use crate::error::{EngineError, Result};
use crate::ode::OdeSystem;
use nalgebra::{DMatrix, DVector};

/// Read from `engine/src/tunables.rs` (unit, value and source there).
pub use crate::tunables::IMPLICIT_EULER_MAX_ITERATIONS as MAX_ITERATIONS;

use crate::tunables::NEWTON_TOLERANCE;

/// One step of size `h` from `(t, y)` into `out`. Costs `(n + 1)` evaluations
/// per Newton iteration (the residual and n difference columns).
pub(crate) fn step<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t: f64,
    y: &[f64],
    h: f64,
    ws: &mut Workspace,
    out: &mut [f64],
) -> Result<()> {
    let n = y.len();
    if n == 0 {
        // Nothing to solve (a world of static bodies only).
        return Ok(());
    }
    let t1 = t + h;
    // Start from the current state: safe for stiff problems, where an
    // explicit predictor would land far outside the basin of convergence.
    out.copy_from_slice(y);
    let mut jacobian = DMatrix::<f64>::zeros(n, n);
    let mut residual = DVector::<f64>::zeros(n);
    let mut last = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        let [f0, fp, ..] = &mut ws.k[..] else {
            unreachable!("workspace holds seven stages")
        };
        sys.derivative(t1, out, f0);
        ws.evaluations += 1;
        for i in 0..n {
            residual[i] = out[i] - y[i] - h * f0[i];
        }
        // Newton matrix M = I − h ∂f/∂z by forward differences.
        for j in 0..n {
            let zj = out[j];
            let delta = f64::EPSILON.sqrt() * zj.abs().max(1.0);
            ws.tmp.copy_from_slice(out);
            ws.tmp[j] = zj + delta;
            sys.derivative(t1, &ws.tmp, fp);
            ws.evaluations += 1;
            for i in 0..n {
                let dfdz = (fp[i] - f0[i]) / delta;
                jacobian[(i, j)] = if i == j { 1.0 } else { 0.0 } - h * dfdz;
            }
        }
        let lu = jacobian.clone().lu();
        let Some(correction) = lu.solve(&residual) else {
            return Err(EngineError::SingularJacobian { t });
        };
        let mut norm_dz: f64 = 0.0;
        let mut norm_z: f64 = 0.0;
        for i in 0..n {
            out[i] -= correction[i];
            norm_dz = norm_dz.max(correction[i].abs());
            norm_z = norm_z.max(out[i].abs());
        }
        if !norm_dz.is_finite() {
            break;
        }
        last = norm_dz;
        if norm_dz <= NEWTON_TOLERANCE * (1.0 + norm_z) {
            return Ok(());
        }
    }
    Err(EngineError::NewtonDiverged {
        t,
        iterations: MAX_ITERATIONS,
        residual: last,
    })
}
