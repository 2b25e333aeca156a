//! Hoffman's stiff test (docs/cases.md "Stiff test", seed §4.3):
//! y' = −1000(y − (t + 2)) + 1, y(0) = 1, exact y = t + 2 − e^(−1000t),
//! integrated with `integrate_fixed` over t ∈ [0, 1].
//!
//! Why the error has a closed form for every one-step method here: write
//! y = g + e with g = t + 2. Then e' = λe with λ = −1000, and g is linear,
//! which all these methods integrate exactly; a linear one-step method maps
//! e_{n+1} = R(hλ)·e_n with its stability function R. With e_0 = y0 − 2 = −1,
//! the numerical error against the exact solution is
//!   err_n = y_n − y(t_n) = −R(hλ)^n + e^(−1000 t_n).
//! The tests check the engine against this formula, which is what "stable"
//! and "blown up" mean quantitatively.

use etalon2d::{EngineError, FnSystem, Method, Solution, integrate_fixed};

const LAMBDA: f64 = -1000.0;

fn hoffman(method: Method, h: f64) -> Result<Solution, EngineError> {
    let mut sys = FnSystem::new(1, |t: f64, y: &[f64], dy: &mut [f64]| {
        dy[0] = LAMBDA * (y[0] - (t + 2.0)) + 1.0;
    });
    // Whole steps that fit in [0, 1]: the last time is ≤ 1 ("near t = 1").
    let steps = (1.0 / h).floor() as usize;
    integrate_fixed(&mut sys, method, 0.0, &[1.0], h, steps)
}

fn exact(t: f64) -> f64 {
    t + 2.0 - (LAMBDA * t).exp()
}

/// Stability functions R(z) of the linear one-step methods.
fn r_explicit_euler(z: f64) -> f64 {
    1.0 + z
}
fn r_rk4(z: f64) -> f64 {
    1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0
}
fn r_implicit_euler(z: f64) -> f64 {
    1.0 / (1.0 - z)
}

/// The closed-form error −R^n + e^(λ t_n) at every output time.
fn predicted_errors(sol: &Solution, h: f64, r: fn(f64) -> f64) -> Vec<f64> {
    let rz = r(h * LAMBDA);
    sol.t
        .iter()
        .enumerate()
        .map(|(n, &t)| -rz.powi(n as i32) + (LAMBDA * t).exp())
        .collect()
}

fn errors(sol: &Solution) -> Vec<f64> {
    sol.t
        .iter()
        .zip(&sol.y)
        .map(|(&t, y)| y[0] - exact(t))
        .collect()
}

/// Checks a stable run: every error within `floor` of the closed form
/// (whose terms are both ≤ 1 and decaying), and the final error tiny.
fn assert_stable(method: Method, h: f64, r: fn(f64) -> f64, floor: f64, final_bound: f64) {
    let sol = hoffman(method, h).unwrap();
    let predicted = predicted_errors(&sol, h, r);
    for (n, (e, p)) in errors(&sol).iter().zip(&predicted).enumerate() {
        assert!(
            (e - p).abs() <= floor,
            "{} h={h}: step {n} error {e:e}, closed form {p:e}",
            method.id()
        );
    }
    let last = *errors(&sol).last().unwrap();
    assert!(
        last.abs() <= final_bound,
        "{} h={h}: error {last:e} near t = 1",
        method.id()
    );
}

/// Checks a blown-up run: the error near t = 1 beyond `at_least` and equal
/// to the closed form to `rel` (round-off, relative, is amplified along with
/// the transient, so it stays relative).
fn assert_unstable(method: Method, h: f64, r: fn(f64) -> f64, at_least: f64) -> f64 {
    let sol = hoffman(method, h).unwrap();
    let last = *errors(&sol).last().unwrap();
    let predicted = *predicted_errors(&sol, h, r).last().unwrap();
    assert!(
        last.abs() > at_least,
        "{} h={h}: error {last:e} near t = {}",
        method.id(),
        sol.t.last().unwrap()
    );
    // ≈ 500 steps × a few ulps of relative round-off: 1e-10 is ample.
    assert!(
        ((last - predicted) / predicted).abs() < 1e-10,
        "{} h={h}: error {last:e}, closed form {predicted:e}",
        method.id()
    );
    last
}

#[test]
fn explicit_euler_is_stable_just_below_h_0_002() {
    // R = 1 − 1.9 = −0.9; after 526 steps |R|^n ≈ 1e-24, under round-off.
    // Floor: each step adds ≈ 2 ulps of y ≈ 3 (9e-16), damped by 0.9 per
    // step, so the sum stays < 10 × 9e-16 ≈ 1e-14.
    assert_stable(
        Method::ExplicitEuler,
        0.0019,
        r_explicit_euler,
        1e-14,
        1e-14,
    );
}

#[test]
fn explicit_euler_blows_up_at_h_0_0021() {
    // R = −1.1, 476 steps: −1.1^476 ≈ −5.05e19 (docs/cases.md: "about −5e19").
    let e = assert_unstable(Method::ExplicitEuler, 0.0021, r_explicit_euler, 1e19);
    // docs/cases.md quotes one significant digit: −5e19 means [−5.5e19, −4.5e19).
    assert!((-5.5e19..-4.5e19).contains(&e), "{e:e}");
}

#[test]
fn explicit_euler_at_h_0_003_reaches_1e100() {
    // R = −2, 333 steps: +2^333 ≈ 1.75e100 (docs/cases.md: "about 1.7e100").
    let e = assert_unstable(Method::ExplicitEuler, 0.003, r_explicit_euler, 1e100);
    assert!((1.65e100..1.85e100).contains(&e), "{e:e}");
}

#[test]
fn explicit_euler_limit_is_h_0_002_within_one_percent() {
    // 1 % either side of h = 2/|λ|: |R| = 0.98 decays to 3.6e-5 over 505
    // steps, |R| = 1.02 grows to 1.8e4 over 495 steps.
    assert_stable(
        Method::ExplicitEuler,
        0.00198,
        r_explicit_euler,
        1e-13,
        1e-4,
    );
    assert_unstable(Method::ExplicitEuler, 0.00202, r_explicit_euler, 1e3);
}

#[test]
fn rk4_is_stable_at_h_0_0027() {
    // R(−2.7) = 0.8785, 370 steps: |R|^n ≈ 1.5e-21. Floor as for Euler with
    // damping 0.88 per step and four stages: ≈ 10 × 4 ulps of 3 < 1e-13.
    assert_stable(Method::Rk4, 0.0027, r_rk4, 1e-13, 1e-13);
}

#[test]
fn rk4_blows_up_at_h_0_0029() {
    // R(−2.9) = 1.187, 344 steps: R^n ≈ 4.3e25.
    assert_unstable(Method::Rk4, 0.0029, r_rk4, 1e25);
}

#[test]
fn rk4_limit_is_h_0_0027852936_within_one_percent() {
    // docs/cases.md: RK4 stable iff h ≤ 0.0027852936 (hλ ≥ −2.78529356). 1 %
    // either side: |R| ≈ 0.958 (→ 2e-7 after 362 steps) and ≈ 1.042
    // (→ 3e6 after 355 steps).
    let h_star = 0.0027852936;
    assert!((r_rk4(-2.78529356) - 1.0).abs() < 1e-7, "the quoted limit");
    assert_stable(Method::Rk4, 0.99 * h_star, r_rk4, 1e-13, 1e-5);
    assert_unstable(Method::Rk4, 1.01 * h_star, r_rk4, 1e5);
}

#[test]
fn implicit_euler_is_stable_at_h_0_01_and_0_1() {
    // R = 1/(1 + 1000h) ∈ (0, 1): the error is −R^n + e^(−1000 t_n), whose
    // size is bounded by R ≤ 1/11 from the first step on. Floor: Newton
    // stops at a correction ≤ 1e-12 (1 + |y|) ≈ 4e-12 per step, and its
    // finite-difference Jacobian (relative error ~1e-8) leaves far less
    // than that; the errors damp, so 1e-11 bounds their sum.
    for h in [0.01, 0.1] {
        assert_stable(Method::ImplicitEuler, h, r_implicit_euler, 1e-11, 1e-11);
        let sol = hoffman(Method::ImplicitEuler, h).unwrap();
        // |err_n| ≤ R^n + e^(−1000 t_n) ≤ R, plus the Newton floor.
        let bound = 1.0 / (1.0 + 1000.0 * h) + 1e-11;
        for (n, e) in errors(&sol).iter().enumerate().skip(1) {
            assert!(e.abs() <= bound, "h={h} step {n}: {e:e} > {bound:e}");
        }
    }
}

#[test]
fn symplectic_methods_refuse_a_first_order_system() {
    for method in [Method::SemiImplicitEuler, Method::VelocityVerlet] {
        let err = hoffman(method, 0.001).unwrap_err();
        assert_eq!(
            err,
            EngineError::MethodNeedsSecondOrder {
                method: method.id()
            }
        );
        let message = err.to_string();
        assert!(
            message.contains(method.id()) && message.contains("second-order"),
            "{message}"
        );
    }
}
