//! The seed's mass-spring (docs/cases.md case I, seed §5): a 20 kg particle at
//! x0 = 100 m on an axial spring k = 50 N/m, l0 = 50 m anchored at the
//! origin, h = 0.2 s, 286 steps to t = 57.2 s.
//!
//! With u = x − l0 the system is u'' = −ω²u, ω = √(k/m). In the complex
//! variable z = u − i v/ω it is z' = iωz, so every linear one-step method
//! gives exactly z_n = R(ihω)^n z_0 with its stability function R, and the
//! energy E = ½mv² + ½ku² = ½k|z|² evolves as E_n = E_0 |R(ihω)|^(2n). The
//! symplectic methods are not of that form (they update u and v in turn) but
//! each conserves an exact quadratic invariant, derived below. These
//! discrete closed forms let the tests check the engine at round-off level,
//! and the docs/cases.md numbers are checked to the digits it quotes.

use etalon2d::forces::{Attachment, Spring};
use etalon2d::{BodyDef, Method, Trace, World};
use nalgebra::{Complex, Vector2};

const MASS: f64 = 20.0;
const STIFFNESS: f64 = 50.0;
const REST: f64 = 50.0;
const X0: f64 = 100.0;
const H: f64 = 0.2;
const T_END: f64 = 57.2;
const STEPS: usize = 286;
/// E0 = ½ k (x0 − l0)² = 62 500 J.
const E0: f64 = 0.5 * STIFFNESS * (X0 - REST) * (X0 - REST);

fn omega() -> f64 {
    (STIFFNESS / MASS).sqrt()
}

/// The seed scene run by `method` at step `h` until `t_end`.
fn run(method: Method, h: f64, t_end: f64) -> Trace {
    let mut world = World::new(method).unwrap();
    let id = world
        .add_body(BodyDef::particle("mass", MASS, Vector2::new(X0, 0.0)))
        .unwrap();
    assert_eq!(id, 0);
    world
        .add_force(Spring {
            a: Attachment::World(Vector2::zeros()),
            b: Attachment::center_of(id),
            stiffness: STIFFNESS,
            rest_length: REST,
            axis: Some(Vector2::x()),
        })
        .unwrap();
    world.run(t_end, h).unwrap()
}

fn seed_run(method: Method) -> Trace {
    let trace = run(method, H, T_END);
    assert_eq!(trace.samples.len(), STEPS + 1, "286 steps plus t = 0");
    assert_eq!(trace.last().unwrap().t, T_END);
    trace
}

/// The state of sample `s` as z = (x − l0) − i v/ω.
fn z_of(trace: &Trace, s: usize) -> Complex<f64> {
    let st = trace.samples[s].states[0];
    Complex::new(st.position.x - REST, -st.velocity.x / omega())
}

fn exact_x(t: f64) -> f64 {
    REST + (X0 - REST) * (omega() * t).cos()
}

/// Stability function R(ihω) of each linear one-step method.
fn r_of(method: Method, y: f64) -> Complex<f64> {
    let iy = Complex::new(0.0, y);
    let one = Complex::new(1.0, 0.0);
    match method {
        Method::ExplicitEuler => one + iy,
        Method::Midpoint => one + iy + iy * iy / 2.0,
        Method::Rk4 => one + iy + iy * iy / 2.0 + iy * iy * iy / 6.0 + iy * iy * iy * iy / 24.0,
        Method::ImplicitEuler => one / (one - iy),
        _ => unreachable!("not a linear one-step method of this form"),
    }
}

#[test]
fn rk4_reproduces_the_seed_numbers() {
    let trace = seed_run(Method::Rk4);
    let last = trace.last().unwrap();
    let x = last.states[0].position.x;
    // docs/cases.md quotes x(57.2) = 10.95756 m: 5 decimals, ±5e-6 of rounding.
    assert!((x - 10.95756).abs() < 1e-5, "x(57.2) = {x}");
    // The exact value it quotes to 10 decimals (checks our formula).
    assert!((exact_x(T_END) - 10.6555761116).abs() < 1e-9);
    // Error at the end 0.30198 m and max |error| 0.37346 m, 5 decimals.
    assert!(((x - exact_x(T_END)) - 0.30198).abs() < 1e-5, "final error");
    let max_error = trace
        .samples
        .iter()
        .map(|s| (s.states[0].position.x - exact_x(s.t)).abs())
        .fold(0.0, f64::max);
    assert!(
        (max_error - 0.37346).abs() < 1e-5,
        "max |error| {max_error}"
    );
    // Phase lag 7.269e-3 rad (4 digits: ±5e-7): arg(z_exact / z_num).
    let z_exact = Complex::from_polar(X0 - REST, omega() * T_END);
    let lag = (z_exact / z_of(&trace, STEPS)).arg();
    assert!((lag - 7.269e-3).abs() < 1e-6, "phase lag {lag:e}");
}

#[test]
fn linear_methods_follow_their_discrete_closed_form() {
    // z_n = R(ihω)^n z_0 at every sample. Tolerance: 286 steps × a few ulps
    // relative, i.e. 1e-11 of the current amplitude |z_n|, plus an absolute
    // 1e-12 m: x itself is ≈ 50 m (ulp 7e-15 m) while implicit Euler damps
    // the amplitude to 1e-4 m.
    let y = H * omega();
    for method in [
        Method::ExplicitEuler,
        Method::Midpoint,
        Method::Rk4,
        Method::ImplicitEuler,
    ] {
        let trace = seed_run(method);
        let r = r_of(method, y);
        let mut predicted = Complex::new(X0 - REST, 0.0);
        for s in 0..=STEPS {
            let z = z_of(&trace, s);
            assert!(
                (z - predicted).norm() <= 1e-11 * predicted.norm() + 1e-12,
                "{} sample {s}: z = {z}, closed form {predicted}",
                method.id()
            );
            predicted *= r;
        }
    }
}

#[test]
fn explicit_euler_amplitude_grows_as_one_plus_h_omega_squared_to_the_n_over_2() {
    let trace = seed_run(Method::ExplicitEuler);
    let growth = 1.0 + (H * omega()).powi(2);
    for (n, sample) in trace.samples.iter().enumerate() {
        // Energy ∝ |z|², so E_n/E_0 = (1 + (hω)²)^n; 286 steps × few ulps.
        let expected = growth.powi(n as i32);
        let ratio = sample.energy / E0;
        assert!(
            (ratio / expected - 1.0).abs() < 1e-11,
            "step {n}: {ratio:e} vs {expected:e}"
        );
    }
    // docs/cases.md: "amplitude ×8.3e5 at 57.2 s" (two digits: ±0.05e5).
    let amplitude = z_of(&trace, STEPS).norm() / (X0 - REST);
    assert!(
        (amplitude - 8.3e5).abs() < 0.05e5,
        "amplitude ×{amplitude:e}"
    );
}

#[test]
fn rk4_energy_decays_monotonically_as_r_to_the_2n() {
    let trace = seed_run(Method::Rk4);
    let g = r_of(Method::Rk4, H * omega()).norm_sqr();
    assert!(g < 1.0, "|R(ihω)|² = {g} at hω = 0.316");
    for pair in trace.samples.windows(2) {
        assert!(
            pair[1].energy < pair[0].energy,
            "energy rose at t = {}",
            pair[1].t
        );
    }
    for (n, sample) in trace.samples.iter().enumerate() {
        // Round-off as above: 1e-11 relative.
        let expected = g.powi(n as i32);
        assert!((sample.energy / E0 / expected - 1.0).abs() < 1e-11, "{n}");
    }
}

#[test]
fn midpoint_energy_grows_weakly_and_implicit_euler_damps() {
    // |R(iy)|² = 1 + y⁴/4 for the midpoint rule, 1/(1 + y²) for implicit
    // Euler (docs/cases.md: RK2 "weak growth", implicit Euler "damps").
    let y = H * omega();
    let mid = seed_run(Method::Midpoint).last().unwrap().energy / E0;
    let expected = (1.0 + y.powi(4) / 4.0).powi(STEPS as i32);
    assert!((mid / expected - 1.0).abs() < 1e-11, "{mid} vs {expected}");
    assert!(mid > 2.0, "energy doubled over 57.2 s: {mid}");
    let ie = seed_run(Method::ImplicitEuler).last().unwrap().energy / E0;
    let expected = (1.0 + y * y).powi(-(STEPS as i32));
    assert!((ie / expected - 1.0).abs() < 1e-9, "{ie:e} vs {expected:e}");
    assert!(ie < 1e-11, "damped to {ie:e}");
}

/// Largest and smallest E/E0 − 1 over a trace.
fn energy_range(trace: &Trace) -> (f64, f64) {
    trace
        .samples
        .iter()
        .map(|s| s.energy / E0 - 1.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), e| {
            (lo.min(e), hi.max(e))
        })
}

#[test]
fn semi_implicit_euler_energy_stays_in_the_seed_band() {
    // v1 = v0 − hω²u0, u1 = u0 + h v1 conserves Q = u² + (v/ω)² − h u v
    // exactly (check: with a = hω and w = v/ω, the map is w1 = w0 − a u0,
    // u1 = u0 + a w1, and u1² + w1² − a u1 w1 = u0² + w0² − a u0 w0).
    // On the ellipse Q = C, u² + w² lies in [C/(1 + a/2), C/(1 − a/2)], and
    // C = (x0 − l0)², so E/E0 ∈ [1/(1 + a/2), 1/(1 − a/2)].
    let trace = seed_run(Method::SemiImplicitEuler);
    let (w, a) = (omega(), H * omega());
    let q = |s: &etalon2d::Sample| {
        let (u, v) = (s.states[0].position.x - REST, s.states[0].velocity.x);
        u * u + (v / w) * (v / w) - H * u * v
    };
    let q0 = q(&trace.samples[0]);
    for s in &trace.samples {
        // 286 steps × a few ulps of the 2500 m² invariant.
        assert!((q(s) / q0 - 1.0).abs() < 1e-12, "t = {}: Q drifted", s.t);
    }
    let (lo_bound, hi_bound) = (1.0 / (1.0 + a / 2.0) - 1.0, 1.0 / (1.0 - a / 2.0) - 1.0);
    // The derived band is docs/cases.md's [−0.1365, +0.1878] to its 4 decimals.
    assert!((lo_bound + 0.1365).abs() < 5e-5 && (hi_bound - 0.1878).abs() < 5e-5);
    let (lo, hi) = energy_range(&trace);
    // Inside the band up to round-off (1e-12), and the samples, 0.32 rad of
    // phase apart, come within 1e-3 of both extremes over 14 periods.
    assert!(
        lo >= lo_bound - 1e-12 && hi <= hi_bound + 1e-12,
        "[{lo}, {hi}]"
    );
    assert!(lo < lo_bound + 1e-3 && hi > hi_bound - 1e-3, "[{lo}, {hi}]");
}

#[test]
fn velocity_verlet_energy_stays_in_the_seed_band() {
    // Velocity Verlet on u'' = −ω²u conserves (1 − a²/4)u² + (v/ω)² exactly
    // (a = hω; the modified energy of Störmer–Verlet). Starting at v = 0,
    // E/E0 = (u² + w²)/u0² lies in [1 − a²/4, 1], so ΔE/E0 ∈ [−0.025, 0]
    // since a² = h²k/m = 0.1.
    let trace = seed_run(Method::VelocityVerlet);
    let (w, a) = (omega(), H * omega());
    let q = |s: &etalon2d::Sample| {
        let (u, v) = (s.states[0].position.x - REST, s.states[0].velocity.x);
        (1.0 - a * a / 4.0) * u * u + (v / w) * (v / w)
    };
    let q0 = q(&trace.samples[0]);
    for s in &trace.samples {
        assert!((q(s) / q0 - 1.0).abs() < 1e-12, "t = {}: Q drifted", s.t);
    }
    let lo_bound = -a * a / 4.0;
    assert!((lo_bound + 0.025).abs() < 1e-15, "the seed's −0.025");
    let (lo, hi) = energy_range(&trace);
    // Round-off margin 1e-12 (E0 = 62 500 J, 286 steps).
    assert!(lo >= lo_bound - 1e-12 && hi <= 1e-12, "[{lo}, {hi}]");
    assert!(lo < lo_bound + 1e-3, "the band's floor is reached: {lo}");
}

/// E/E0 after `steps` steps of `method` at h = factor · limit / ω.
fn energy_after(method: Method, h_omega: f64, steps: usize) -> f64 {
    let h = h_omega / omega();
    let trace = run(method, h, h * steps as f64);
    trace.last().unwrap().energy / E0
}

#[test]
fn stability_limits_on_the_imaginary_axis() {
    // docs/cases.md: semi-implicit Euler and Verlet stable iff hω < 2, RK4 iff
    // hω ≤ 2√2. 1 % either side, 100 steps:
    // - symplectic, hω = 1.98: bounded by the invariant (E/E0 ≤ 1/(1 − hω/2)
    //   = 100 for semi-implicit Euler, ≤ 1 for Verlet); hω = 2.02: an
    //   eigenvalue of modulus 1.33, E grows by 1.33^200 ≈ 1e24;
    // - RK4, |R(iy)|² = 1 − y⁶/72 + y⁸/576 is 0.87 at 0.99·2√2 (decay) and
    //   1.15 at 1.01·2√2 (E × 1e6 over 100 steps).
    for method in [Method::SemiImplicitEuler, Method::VelocityVerlet] {
        let stable = energy_after(method, 0.99 * 2.0, 100);
        assert!(stable <= 100.0 + 1e-9, "{} at 1.98: {stable}", method.id());
        let unstable = energy_after(method, 1.01 * 2.0, 100);
        assert!(unstable > 1e20, "{} at 2.02: {unstable:e}", method.id());
    }
    let two_root_two = 2.0 * 2f64.sqrt();
    let stable = energy_after(Method::Rk4, 0.99 * two_root_two, 100);
    assert!(stable < 1.0, "rk4 at 0.99·2√2: {stable}");
    let unstable = energy_after(Method::Rk4, 1.01 * two_root_two, 100);
    assert!(unstable > 1e5, "rk4 at 1.01·2√2: {unstable:e}");
}
