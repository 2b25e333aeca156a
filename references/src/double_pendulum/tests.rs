//! The double pendulum's equations against the textbook point-mass form
//! and a closed-form reduction; the solve's energy, error estimate and
//! horizon.

use super::*;
use crate::pendulum::Pendulum;
use crate::test_support::assert_close;

/// The point-mass double pendulum's explicit accelerations, angles from
/// the downward vertical (as given e.g. by E. Neumann, myPhysicsLab
/// "Double Pendulum", derived from the same Lagrangian by hand).
fn textbook(m1: f64, m2: f64, l1: f64, l2: f64, g: f64, s: &PendulumState) -> [f64; 2] {
    let [t1, t2] = s.angles;
    let [w1, w2] = s.rates;
    let d = 2.0 * m1 + m2 - m2 * (2.0 * t1 - 2.0 * t2).cos();
    let a1 = (-g * (2.0 * m1 + m2) * t1.sin()
        - m2 * g * (t1 - 2.0 * t2).sin()
        - 2.0 * (t1 - t2).sin() * m2 * (w2 * w2 * l2 + w1 * w1 * l1 * (t1 - t2).cos()))
        / (l1 * d);
    let a2 = 2.0
        * (t1 - t2).sin()
        * (w1 * w1 * l1 * (m1 + m2)
            + g * (m1 + m2) * t1.cos()
            + w2 * w2 * l2 * m2 * (t1 - t2).cos())
        / (l2 * d);
    [a1, a2]
}

#[test]
fn point_masses_follow_the_textbook_equations() {
    let (m1, m2, l1, l2, g) = (1.3, 0.7, 1.1, 0.6, 9.81);
    let p = DoublePendulum::point_masses(m1, m2, l1, l2, g);
    // A few states over the whole circle, fast and slow.
    for (a, b, w1, w2) in [
        (0.3, -0.2, 0.0, 0.0),
        (2.0, 1.0, 1.5, -3.0),
        (-2.9, 0.4, -4.0, 6.0),
        (1.0, 2.5, 0.2, 0.1),
    ] {
        let s = PendulumState {
            angles: [a, b],
            rates: [w1, w2],
        };
        let (got, want) = (p.accelerations(&s), textbook(m1, m2, l1, l2, g, &s));
        for i in 0..2 {
            // Two evaluations of the same rational expression in f64: a
            // few ulps of terms up to ~100 rad/s².
            assert_close(
                got[i],
                want[i],
                1e-12 * want[i].abs().max(10.0),
                "acceleration",
            );
        }
    }
}

#[test]
fn a_point_mass_at_the_joint_makes_body_1_a_physical_pendulum() {
    // Body 2 with its centre on the joint (c2 = 0) exerts only a force at
    // P: body 1 swings as a physical pendulum of inertia about O
    // I1 + m1|c1|² + m2|ℓ1|² and moment m1|c1| + m2|ℓ1| (c1 ∥ ℓ1), i.e. of
    // equivalent length L = (I1 + m1 c² + m2 ℓ²)/(m1 c + m2 ℓ). A bar of
    // 1 m (I1 = m1/12) with a 0.5 kg mass at its tip, from 60°.
    let (m1, m2) = (2.0, 0.5);
    let p = DoublePendulum {
        mass1: m1,
        inertia1: m1 / 12.0,
        mass2: m2,
        inertia2: 1e-3,
        com1: [0.0, -0.5],
        joint: [0.0, -1.0],
        com2: [0.0, 0.0],
        gravity: 9.81,
    };
    let length = (m1 / 12.0 + m1 * 0.25 + m2) / (m1 * 0.5 + m2);
    let exact = Pendulum::new(length, 9.81, 60f64.to_radians());
    let start = PendulumState {
        angles: [exact.amplitude, 0.3],
        rates: [0.0, 0.7],
    };
    let times: Vec<f64> = (1..=8).map(|k| 0.45 * k as f64).collect();
    let states = p
        .states_at(start, &times, DOUBLE_PENDULUM_TOLERANCE)
        .unwrap();
    for (t, s) in times.iter().zip(&states) {
        // DOP853 at 1e-13 over 3.6 s (about two periods): the
        // single-pendulum comparison in `pendulum` found its global error
        // 1e-13 to 1e-10 rad depending on the amplitude over three periods;
        // measured here 4.3e-14 rad and 1.9e-13 rad/s. The bounds allow
        // 20× and 10× that.
        assert_close(s.angles[0], exact.angle(*t), 1e-12, "phi1");
        assert_close(s.rates[0], exact.angular_velocity(*t), 2e-12, "phi1'");
        // Body 2 spins freely: no torque acts on it (measured 9e-16 rad).
        assert_close(s.angles[1], 0.3 + 0.7 * t, 1e-14, "phi2");
    }
}

/// Two uniform bars of 1 m (1 kg, I = 1/12 kg·m²), each hinged at its
/// end, released from `a1`, `a2` rad at rest.
fn two_bars() -> DoublePendulum {
    DoublePendulum {
        mass1: 1.0,
        inertia1: 1.0 / 12.0,
        mass2: 1.0,
        inertia2: 1.0 / 12.0,
        com1: [0.0, -0.5],
        joint: [0.0, -1.0],
        com2: [0.0, -0.5],
        gravity: 9.81,
    }
}

#[test]
fn the_solve_conserves_energy_and_its_error_estimate_holds() {
    let p = two_bars();
    let start = PendulumState {
        angles: [90f64.to_radians(), 90f64.to_radians()],
        rates: [0.0, 0.0],
    };
    let times: Vec<f64> = (1..=10).map(|k| 0.5 * k as f64).collect();
    let reference = p.solve(start, &times).unwrap();
    // A third solve, tighter still (1e-14, the tightest DOP853 accepts),
    // is within the estimate wherever the estimate is meaningful.
    let tighter = p.states_at(start, &times, 1e-14).unwrap();
    // Energy scale: m g L = 9.81 J.
    for (r, s) in reference.iter().zip(&tighter) {
        // DOP853 at 1e-13 per step: its energy error accumulates to at
        // most ~(steps) × 1e-13 × 10 J over 5 s (under a thousand steps):
        // 1e-9 J. Measured 1.5e-12 J. The estimate (1e-10 solve against
        // the 1e-13 one) grows from 6e-11 to 1.3e-8 rad over 5 s; the
        // 1e-13 solve's distance from the 1e-14 one stays below 2e-11 rad.
        assert!(
            r.energy_drift < 1e-9,
            "t = {}: {:e}",
            r.time,
            r.energy_drift
        );
        let diff = (0..2)
            .map(|i| (r.state.angles[i] - s.angles[i]).abs())
            .fold(0.0, f64::max);
        assert!(
            diff <= r.error_estimate.max(1e-11),
            "t = {}: tight − tighter {diff:e} > estimate {:e}",
            r.time,
            r.error_estimate
        );
    }
}

#[test]
fn the_horizon_is_finite_for_chaos_and_absent_for_small_swings() {
    let p = two_bars();
    let chaotic = PendulumState {
        angles: [120f64.to_radians(), -30f64.to_radians()],
        rates: [0.0, 0.0],
    };
    let t1 = p
        .divergence_time(chaotic, 1e-8, 30.0)
        .unwrap()
        .expect("chaotic");
    let t2 = p
        .divergence_time(chaotic, 1e-10, 30.0)
        .unwrap()
        .expect("chaotic");
    // Exponential divergence: a 100 times smaller perturbation buys time,
    // but not 100 times more (linear growth would).
    assert!(t1 > 0.5 && t2 > t1 && t2 < 5.0 * t1, "{t1} {t2}");
    // Small swings are quasi-periodic: a 1e-8 rad perturbation grows
    // linearly (the frequencies depend on amplitude only at second order),
    // far from 1e-3 rad in 20 s.
    let small = PendulumState {
        angles: [5f64.to_radians(), 3f64.to_radians()],
        rates: [0.0, 0.0],
    };
    assert_eq!(p.divergence_time(small, 1e-8, 20.0).unwrap(), None);
}

#[test]
fn from_world_reads_a_scene_layout() {
    // Two bars hanging straight down from the origin, the second hinged
    // at the first's tip, described in world coordinates.
    let p = DoublePendulum::from_world(
        [1.0, 1.0],
        [1.0 / 12.0; 2],
        [0.0, 0.0],
        [0.0, -1.0],
        [0.0, -0.5],
        [0.0, -1.5],
        [0.0, 0.0],
        9.81,
    );
    assert_eq!(p, two_bars());
    // Turned by 90° at t = 0, the body frames turn with them.
    let q = DoublePendulum::from_world(
        [1.0, 1.0],
        [1.0 / 12.0; 2],
        [0.0, 0.0],
        [1.0, 0.0],
        [0.5, 0.0],
        [1.5, 0.0],
        [std::f64::consts::FRAC_PI_2; 2],
        9.81,
    );
    for (a, b) in [(q.com1, p.com1), (q.joint, p.joint), (q.com2, p.com2)] {
        assert_close(a[0], b[0], 1e-15, "x");
        assert_close(a[1], b[1], 1e-15, "y");
    }
}

#[test]
fn the_solve_matches_an_independent_taylor_series_solve() {
    // Two bars from 90°/90° at rest, integrated by mpmath 1.3's `odefun`
    // (adaptive Taylor series at 25 digits) on the same equations, printed
    // to 17 digits. The tight DOP853 solve must agree within its own error
    // estimate (the 1e-10 solve's distance from it, 5e-10 and 8e-10 rad
    // here), which is what the harness will quote. Measured: 1.3e-12.
    let p = two_bars();
    let start = PendulumState {
        angles: [std::f64::consts::FRAC_PI_2; 2],
        rates: [0.0, 0.0],
    };
    let expected = [
        [
            -1.207_716_238_190_638,
            -0.814_391_023_091_296_4,
            -3.406_517_532_971_958,
            -0.516_045_472_105_208_9,
        ],
        [
            -0.082_758_306_820_570_85,
            0.407_362_074_911_907_2,
            -0.961_145_444_545_998_5,
            11.898_955_053_045_295,
        ],
    ];
    let reference = p.solve(start, &[1.0, 2.0]).unwrap();
    for (r, e) in reference.iter().zip(&expected) {
        let got = [
            r.state.angles[0],
            r.state.angles[1],
            r.state.rates[0],
            r.state.rates[1],
        ];
        for (g, w) in got.iter().zip(e) {
            assert_close(*g, *w, r.error_estimate, &format!("state at {} s", r.time));
        }
    }
}
