//! A blow-up is detected and reported as a typed `EngineError::BlowUp`
//! naming the time and the step, never returned as silent garbage
//! (docs/design.md, Principles: "a blow-up is detected and reported
//! (non-finite state, energy growth)").

use etalon2d::forces::{Attachment, Spring};
use etalon2d::{BodyDef, EngineError, FnSystem, Method, World, integrate_fixed};
use nalgebra::Vector2;

/// E0 of the seed spring, ½ k (x0 − l0)² (J).
const E0: f64 = 62_500.0;

/// The seed spring (docs/cases.md case I) with `method`.
fn spring_world(method: Method) -> World {
    let mut world = World::new(method).unwrap();
    let id = world
        .add_body(BodyDef::particle("mass", 20.0, Vector2::new(100.0, 0.0)))
        .unwrap();
    world
        .add_force(Spring {
            a: Attachment::World(Vector2::zeros()),
            b: Attachment::center_of(id),
            stiffness: 50.0,
            rest_length: 50.0,
            axis: Some(Vector2::x()),
        })
        .unwrap();
    world
}

/// Explicit Euler at h = 1 s (hω = 1.58) multiplies the energy by exactly
/// 1 + (hω)² = 3.5 per step: 218 750, 765 625, then 2 679 687.5 J, the
/// first value past a 1e6 J bound, produced by the third step (index 2,
/// from t = 2 s to 3 s).
fn energy_blow_up() -> (World, EngineError) {
    let mut world = spring_world(Method::ExplicitEuler);
    world.set_energy_limit(Some(1e6)).unwrap();
    let err = world.run(100.0, 1.0).unwrap_err();
    (world, err)
}

#[test]
fn energy_growth_past_the_bound_is_a_blow_up() {
    let (world, err) = energy_blow_up();
    let EngineError::BlowUp { ref reason, .. } = err else {
        panic!("expected BlowUp, got {err:?}");
    };
    // 62 500 × 3.5³ is exact in binary: the reason quotes it exactly, in
    // plain notation (between 1e-4 and 1e16, as every message's numbers).
    assert_eq!(E0 * 3.5f64.powi(3), 2_679_687.5);
    assert!(
        reason.contains("2679687.5 J") && reason.contains("1000000 J"),
        "{reason}"
    );
    let message = err.to_string();
    assert!(
        message.starts_with("blow-up at t = ") && message.contains("(step "),
        "{message}"
    );
    // The world keeps the last state within the bound, at t = 2 s.
    assert_eq!(world.time(), 2.0);
    assert_eq!(world.energy(), E0 * 3.5 * 3.5);
}

#[test]
fn energy_blow_up_names_the_start_and_index_of_the_offending_step() {
    let (_, err) = energy_blow_up();
    match err {
        EngineError::BlowUp { t, step, .. } => {
            assert_eq!((t, step), (2.0, 2), "the third step starts at t = 2 s");
        }
        other => panic!("expected BlowUp, got {other:?}"),
    }
}

#[test]
fn a_stable_run_never_trips_the_energy_bound() {
    // RK4 at h = 0.2 s loses energy monotonically (|R(ihω)| < 1), so a
    // bound 1e-9 above E0 (round-off of E ≈ 1e-11 J at 62 500 J) holds for
    // all 286 steps: the guard fires on growth, not on every run.
    let mut world = spring_world(Method::Rk4);
    world.set_energy_limit(Some(E0 * (1.0 + 1e-9))).unwrap();
    let trace = world.run(57.2, 0.2).unwrap();
    assert_eq!(trace.samples.len(), 287);
}

#[test]
fn non_finite_world_state_is_a_blow_up_naming_t_and_step() {
    // h = 100 s, hω = 158: the amplitude grows ×158 per step and overflows
    // after ≈ 139 steps; no energy bound is set, the NaN/inf check fires.
    let h = 100.0;
    let mut world = spring_world(Method::ExplicitEuler);
    let err = world.run(1e5, h).unwrap_err();
    let EngineError::BlowUp { t, step, reason } = err.clone() else {
        panic!("expected BlowUp, got {err:?}");
    };
    assert!(reason.contains("non-finite"), "{reason}");
    // log(f64::MAX / (50 m × 160)) / log(158) ≈ 138.4: the overflow comes
    // within a step of 139 (the exact step depends on the phase).
    assert!((138..=140).contains(&step), "step {step}");
    // t is the start of step number `step` (0-based), where the world stays
    // with its last finite state.
    assert_eq!(t, step as f64 * h);
    assert_eq!(world.time(), t);
    let s = world.states()[0];
    assert!(s.position.x.is_finite() && s.velocity.x.is_finite());
    let message = err.to_string();
    assert!(message.contains(&format!("t = {t} s")), "{message}");
    assert!(message.contains(&format!("step {step}")), "{message}");
}

#[test]
fn non_finite_ode_state_is_a_blow_up_at_the_predicted_step() {
    // Hoffman's test with explicit Euler at h = 0.1: the error is
    // e_n = −(−99)^n (see hoffman_stability.rs). The step from y_n computes
    // −1000 e_n, which overflows first when 1000·99^n > f64::MAX.
    let h = 0.1;
    let mut n = 0;
    let mut e = 1.0f64;
    while (1000.0 * e).is_finite() {
        e *= 99.0;
        n += 1;
    }
    assert_eq!(n, 153, "ceil(ln(MAX/1000)/ln 99) = ceil(152.96)");
    let mut sys = FnSystem::new(1, |t: f64, y: &[f64], dy: &mut [f64]| {
        dy[0] = -1000.0 * (y[0] - (t + 2.0)) + 1.0;
    });
    let err = integrate_fixed(&mut sys, Method::ExplicitEuler, 0.0, &[1.0], h, 1000).unwrap_err();
    match err {
        EngineError::BlowUp {
            t,
            step,
            ref reason,
        } => {
            assert_eq!(step, n as u64);
            // integrate_fixed's grid: t0 + i·h.
            assert_eq!(t, n as f64 * h);
            assert!(reason.contains("non-finite"), "{reason}");
        }
        other => panic!("expected BlowUp, got {other:?}"),
    }
}
