//! Linear stability theory of each method: what it does, exactly, to the
//! test equations of seed §4.3 (after Eberly and Hoffman).
//!
//! - On `y' = λy` a Runge–Kutta step multiplies `y` by its stability function
//!   `R(z)`, `z = hλ`; with a forcing that is a polynomial of degree ≤ 1 in
//!   t (Hoffman's `y' = λ(y − (t + 2)) + 1`), the error `e = y − (t + 2)`
//!   obeys `e_{n+1} = R(hλ) e_n` exactly, so `e_n = R(hλ)^n e_0`.
//! - On the oscillator `u'' = −ω²u` every method, including the partitioned
//!   ones (semi-implicit Euler, velocity Verlet), is a 2×2 matrix `M(h)` on
//!   `(u, v)`; after n steps the state is `M^n (u0, v0)` exactly.
//!
//! These predictions are exact for the discrete maps, so the engine must
//! reproduce them to round-off: a stronger check than "the error is small",
//! and the way to show a method failing exactly as theory says.

use engine::Method;
use nalgebra::Matrix2;

/// The stability function `R(z)` of a one-step method on `y' = λy`, for a
/// real `z = hλ`. `None` for the partitioned methods, which need a
/// second-order system, and for the adaptive one, whose step varies.
pub fn stability_function(method: Method, z: f64) -> Option<f64> {
    match method {
        Method::ExplicitEuler => Some(1.0 + z),
        Method::Midpoint => Some(1.0 + z + z * z / 2.0),
        Method::Rk4 => Some(1.0 + z + z * z / 2.0 + z.powi(3) / 6.0 + z.powi(4) / 24.0),
        Method::ImplicitEuler => Some(1.0 / (1.0 - z)),
        Method::SemiImplicitEuler | Method::VelocityVerlet | Method::DormandPrince(_) => None,
    }
}

/// The one-step matrix `M(h)` of a fixed-step method on `u'' = −ω²u`,
/// acting on `(u, v)`. `None` for the adaptive method.
pub fn oscillator_step_matrix(method: Method, h: f64, omega: f64) -> Option<Matrix2<f64>> {
    let w2 = omega * omega;
    // The first-order form y' = A y with A = [[0, 1], [−ω², 0]].
    let a = Matrix2::new(0.0, 1.0, -w2, 0.0) * h;
    let identity = Matrix2::identity();
    match method {
        Method::ExplicitEuler => Some(identity + a),
        Method::Midpoint => Some(identity + a + a * a / 2.0),
        Method::Rk4 => {
            let a2 = a * a;
            Some(identity + a + a2 / 2.0 + a2 * a / 6.0 + a2 * a2 / 24.0)
        }
        Method::ImplicitEuler => (identity - a).try_inverse(),
        // v1 = v − hω²u, then u1 = u + h v1.
        Method::SemiImplicitEuler => Some(Matrix2::new(1.0 - w2 * h * h, h, -w2 * h, 1.0)),
        // u1 = u + h v − h²ω²u/2; v1 = v − hω²(u + u1)/2.
        Method::VelocityVerlet => {
            let u1 = [1.0 - 0.5 * w2 * h * h, h];
            Some(Matrix2::new(
                u1[0],
                u1[1],
                -0.5 * h * w2 * (1.0 + u1[0]),
                1.0 - 0.5 * h * w2 * u1[1],
            ))
        }
        Method::DormandPrince(_) => None,
    }
}

/// `(u_n, v_n) = M(h)^n (u0, v0)`: the state the method must produce after
/// `n` steps on the oscillator.
pub fn oscillator_after(
    method: Method,
    h: f64,
    omega: f64,
    n: u32,
    u0: f64,
    v0: f64,
) -> Option<(f64, f64)> {
    let m = oscillator_step_matrix(method, h, omega)?;
    let mut state = nalgebra::Vector2::new(u0, v0);
    for _ in 0..n {
        state = m * state;
    }
    Some((state.x, state.y))
}

/// The spectral radius of `M(h)`: the amplitude factor per step (> 1 grows).
pub fn oscillator_growth_per_step(method: Method, h: f64, omega: f64) -> Option<f64> {
    let m = oscillator_step_matrix(method, h, omega)?;
    let eigen = m.complex_eigenvalues();
    Some(eigen.iter().map(|c| c.norm()).fold(0.0, f64::max))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn explicit_euler_grows_by_the_textbook_factor() {
        // |1 + ihω| = sqrt(1 + (hω)²) for explicit Euler, to round-off.
        let (h, w) = (0.2, 10f64.sqrt() / 2.0);
        let g = oscillator_growth_per_step(Method::ExplicitEuler, h, w).unwrap();
        assert!((g - (1.0 + (h * w).powi(2)).sqrt()).abs() < 1e-15);
    }

    #[test]
    fn symplectic_methods_have_unit_determinant() {
        // Symplectic maps preserve area: det M = 1 to round-off.
        for m in [Method::SemiImplicitEuler, Method::VelocityVerlet] {
            let d = oscillator_step_matrix(m, 0.2, 1.58).unwrap().determinant();
            assert!((d - 1.0).abs() < 1e-15, "{m:?}: {d}");
        }
    }

    #[test]
    fn rk4_real_stability_boundary() {
        // |R(−2.785293563405282)| = 1 to the 16 digits of the constant.
        let r =
            stability_function(Method::Rk4, crate::hoffman::RK4_REAL_STABILITY_BOUNDARY).unwrap();
        assert!((r.abs() - 1.0).abs() < 1e-14, "{r}");
    }
}
