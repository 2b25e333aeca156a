//! The closed forms against literature values and an independent DOP853
//! solve of θ'' = −(g/L) sin θ.

use super::*;
use crate::test_support::assert_close;
use ode_solvers::{Dop853, OutputType, System, Vector2};

/// The reference values of `docs/cases.md` (`pendulum`,
/// `physical_pendulum`), quoted to 16 significant digits: 1e-13 relative
/// is well above their last-digit rounding (5e-16) and the AGM's round-off
/// (a few ulps over ~6 iterations), far below any modelling error.
const REL: f64 = 1e-13;

#[test]
fn elliptic_k_matches_its_special_values() {
    // K(0) = π/2 exactly; K(1/√2) (modular angle 45°, m = 1/2) =
    // Γ(1/4)²/(4√π) = 1.8540746773013719184… (mpmath 1.3 at 30 digits).
    // 2e-15: a few ulps of the AGM's six iterations.
    assert_close(elliptic_k(0.0), std::f64::consts::FRAC_PI_2, 1e-16, "K(0)");
    assert_close(
        elliptic_k(std::f64::consts::FRAC_1_SQRT_2),
        1.854_074_677_301_371_9,
        2e-15,
        "K(1/sqrt 2)",
    );
}

#[test]
fn simple_pendulum_periods_match_the_quoted_values() {
    for (deg, t) in [
        (10.0, 2.009892627298601),
        (90.0, 2.367841947576237),
        (170.0, 4.893524274105486),
    ] {
        let p = Pendulum::new(1.0, 9.81, f64::to_radians(deg));
        assert_close(p.period(), t, REL * t, &format!("T({deg} deg)"));
    }
    // Small amplitude: T → 2π √(L/g) = 2.006066681 s, the first
    // correction being (1 + θ0²/16): at 1e-3 rad, 6e-8 relative.
    let p = Pendulum::new(1.0, 9.81, 1e-3);
    assert_close(
        p.period(),
        p.small_angle_period() * (1.0 + 1e-6 / 16.0),
        1e-14 * p.period(),
        "small angle",
    );
}

#[test]
fn box_pivoted_at_a_corner_matches_the_quoted_values() {
    // A 1 m × 0.5 m box pivoted at its corner: L_eq = 2 √(b² + h²)/3.
    let corners = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.5], [0.0, 0.5]];
    let p = PhysicalPendulum::polygon(&corners, [0.0, 0.0]);
    assert_close(
        p.equivalent_length(),
        0.7453559924999299,
        REL,
        "equivalent length",
    );
    for (deg, t) in [(10.0, 1.735220743804285), (90.0, 2.044252717622318)] {
        let period = p.pendulum(9.81, f64::to_radians(deg)).period();
        assert_close(period, t, REL * t, &format!("T({deg} deg)"));
    }
    // The same box pivoted about any corner, listed from another vertex.
    let shifted = [[1.0, 0.5], [0.0, 0.5], [0.0, 0.0], [1.0, 0.0]];
    let q = PhysicalPendulum::polygon(&shifted, [1.0, 0.5]);
    assert_close(
        q.equivalent_length(),
        0.7453559924999299,
        REL,
        "other corner",
    );
    // A disc pivoted on its rim: L_eq = (r²/2 + r²)/r = 3r/2.
    assert_close(
        PhysicalPendulum::disc(0.2, 0.2).equivalent_length(),
        0.3,
        1e-16,
        "disc",
    );
}

#[test]
fn jacobi_functions_match_their_identities_and_quarter_period_values() {
    for k in [0.1_f64, 0.5, 0.9, 0.996] {
        let kp = ((1.0 - k) * (1.0 + k)).sqrt();
        let big_k = elliptic_k(k);
        // sn(K) = 1, cn(K) = 0, dn(K) = k' (DLMF 22.5.1).
        let (s, c, d) = jacobi_sn_cn_dn(big_k, k);
        assert_close(s, 1.0, 1e-14, "sn(K)");
        assert_close(c, 0.0, 1e-7, "cn(K)"); // cn ≈ √(2(1 − sn)): sqrt of round-off
        assert_close(d, kp, 1e-7, "dn(K)");
        // DLMF 22.5.2: sn(K/2) = (1 + k')^(−1/2), cn(K/2) = (k'/(1 + k'))^(1/2),
        // dn(K/2) = k'^(1/2).
        let (s, c, d) = jacobi_sn_cn_dn(0.5 * big_k, k);
        assert_close(s, (1.0 + kp).powf(-0.5), 1e-14, "sn(K/2)");
        assert_close(c, (kp / (1.0 + kp)).sqrt(), 1e-14, "cn(K/2)");
        assert_close(d, kp.sqrt(), 1e-14, "dn(K/2)");
        for &u in &[-3.7, 0.0, 0.4, 2.2, 9.0] {
            let (s, c, d) = jacobi_sn_cn_dn(u, k);
            assert_close(s * s + c * c, 1.0, 1e-14, "sn² + cn²");
            assert_close(d * d + k * k * s * s, 1.0, 1e-14, "dn² + k² sn²");
        }
    }
}

struct PendulumOde {
    omega2: f64,
}

impl System<f64, Vector2<f64>> for PendulumOde {
    fn system(&self, _t: f64, y: &Vector2<f64>, dy: &mut Vector2<f64>) {
        dy[0] = y[1];
        dy[1] = -self.omega2 * y[0].sin();
    }
}

#[test]
fn closed_form_motion_matches_a_dop853_solve() {
    for deg in [10.0, 90.0, 170.0] {
        let p = Pendulum::new(1.0, 9.81, f64::to_radians(deg));
        let mut t0 = 0.0;
        let mut y = Vector2::new(p.amplitude, 0.0);
        // Checked every 0.37 s over three periods, DOP853 at 1e-14 (the
        // tightest tolerance it accepts) from the previous point. The
        // closed form agrees with mpmath to 2e-14 rad even at 170° after
        // 13 s (test below), so the difference is DOP853's global error:
        // largest at 170°, where the period depends steeply on the energy
        // and an energy error becomes a growing phase error: 7e-12 rad in
        // θ and 1.2e-11 rad/s in θ' at 1e-14, 1.0e-10 and 1.7e-10 at 1e-13
        // (it tracks the tolerance); 6e-14 and 1.3e-13 at 90°. The bounds
        // allow 7× and 8× the measured 170° error.
        while t0 + 0.37 < 3.0 * p.period() {
            let t1 = t0 + 0.37;
            let mut s = Dop853::new(
                PendulumOde {
                    omega2: p.omega().powi(2),
                },
                t0,
                t1,
                t1 - t0,
                y,
                1e-14,
                1e-14,
            );
            s.set_output(OutputType::Sparse);
            s.integrate().unwrap();
            assert_close(*s.x_out().last().unwrap(), t1, 1e-14, "DOP853 end");
            y = *s.y_out().last().unwrap();
            t0 = t1;
            assert_close(
                p.angle(t0),
                y[0],
                5e-11,
                &format!("theta({t0}) at {deg} deg"),
            );
            assert_close(
                p.angular_velocity(t0),
                y[1],
                1e-10,
                &format!("theta'({t0}) at {deg} deg"),
            );
            // Energy per m L² is constant along the closed form.
            assert_close(
                p.energy(p.angle(t0), p.angular_velocity(t0)),
                -p.omega().powi(2) * p.amplitude.cos(),
                1e-11,
                "energy",
            );
        }
    }
}

#[test]
fn closed_form_motion_matches_mpmath_values() {
    // 2 asin(k sn(K − ω t, k)) at 90°, L = 1, g = 9.81, evaluated by
    // mpmath 1.3 (ellipk, ellipfun) at 30 digits and rounded to 17
    // (1e-13: ulps of K and of the Landen recursion, far above the
    // quoted digits).
    let p = Pendulum::new(1.0, 9.81, f64::to_radians(90.0));
    for (t, theta) in [
        (0.3, 1.132_186_341_090_512_7),
        (1.0, -1.405_027_311_524_799),
        (2.5, 1.485_147_769_705_835_8),
    ] {
        assert_close(p.angle(t), theta, 1e-13, &format!("theta({t})"));
    }
    // At 170°, late in the run, where the DOP853 comparison is loosest:
    // θ and θ' by mpmath at t = 11.1 s and 13.32 s. Measured 1.5e-14: the
    // ulps of K carried through ω t ≈ 40 rad of phase, and θ' ≤ 6 rad/s
    // times the 1e-15 s rounding of t; 1e-13 allows 6×.
    let p = Pendulum::new(1.0, 9.81, f64::to_radians(170.0));
    for (t, theta, omega) in [
        (11.1, -0.551_758_498_241_307_4, -6.002_532_779_404_759),
        (13.32, -0.830_926_026_036_121_5, 5.705_223_715_919_462_8),
    ] {
        assert_close(p.angle(t), theta, 1e-13, &format!("theta({t}) at 170 deg"));
        assert_close(
            p.angular_velocity(t),
            omega,
            1e-13,
            &format!("theta'({t}) at 170 deg"),
        );
    }
}
