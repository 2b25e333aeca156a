//! A disc rolling without slipping inside a bowl: the `bowl` case's
//! references (docs/cases.md#bowl).
//!
//! **The circle.** A disc of radius r rolling without slipping inside a
//! circle of radius R: its centre moves on the circle of radius R − r at
//! the polar angle θ from the bottom, the contact point is at rest, so
//! its kinetic energy is (1/2) m v² + (1/2)(m r²/2)(v/r)² = (3/4) m v²
//! with v = (R − r) θ', and energy conservation gives
//!
//!   (3/2)(R − r) θ'' = −g sin θ,
//!
//! a pendulum of length 3(R − r)/2: small oscillations of period
//! T₀ = 2π √(3(R − r)/(2g)), and from rest at θ₀ the period
//! T₀ · (2/π) K(sin(θ₀/2)) (K the complete elliptic integral of the first
//! kind, by the arithmetic–geometric mean).
//!
//! **The polygon.** The bowl made of N equal segments whose ends lie on
//! the circle (a segment centred at the bottom): away from the joins the
//! disc rolls on a straight segment, so its centre runs on straight pieces
//! at distance a = R cos(π/N) − r from the bowl's centre (the regular
//! N-gon of apothem a), and along piece k, whose normal points at
//! φ_k = −π/2 + 2πk/N, it accelerates at −(2/3) g cos φ_k (gravity's
//! component along the piece, times m/(m + I/r²) = 2/3 for rolling). At a
//! join the path turns by β = 2π/N: a rigid disc meeting the next segment
//! loses its speed across it (a perfectly inelastic impact, the contact's
//! restitution being 0) and keeps its spin, then friction brings it back
//! to rolling keeping the angular momentum about the contact point:
//! v' = v (2 cos β + 1)/3. [`PolygonBowl::crossings`] steps this motion
//! from piece to piece in closed form (constant acceleration on each) and
//! reports when the centre crosses the bottom (x = 0).
//!
//! Units: SI (m, s, rad).

use std::f64::consts::PI;

/// The bowl, the disc and the release (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolygonBowl {
    /// Radius R of the circle the bowl's points lie on (m).
    pub bowl_radius: f64,
    /// Radius r of the disc (m).
    pub disc_radius: f64,
    /// Number of segments N of the bowl.
    pub sides: usize,
    /// Gravity g (m/s²), along −y.
    pub gravity: f64,
    /// Polar angle θ₀ of the disc's centre from the bottom at release
    /// (rad), counter-clockwise positive; released at rest.
    pub release: f64,
}

/// The complete elliptic integral of the first kind K(k), |k| < 1, by the
/// arithmetic–geometric mean: K = π / (2 AGM(1, √(1 − k²))), converging
/// quadratically (to round-off in a few iterations).
pub fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, (1.0 - k * k).sqrt());
    for _ in 0..64 {
        if (a - b).abs() <= 1e-16 * a {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

impl PolygonBowl {
    /// T₀ = 2π √(3(R − r)/(2g)) (s): small oscillations in the circle.
    pub fn small_oscillation_period(&self) -> f64 {
        2.0 * PI * (3.0 * (self.bowl_radius - self.disc_radius) / (2.0 * self.gravity)).sqrt()
    }

    /// The period (s) in the circle from rest at θ₀:
    /// T₀ · (2/π) K(sin(θ₀/2)).
    pub fn circle_period(&self) -> f64 {
        self.small_oscillation_period() * 2.0 / PI * elliptic_k((0.5 * self.release).sin())
    }

    /// The apothem a = R cos(π/N) − r of the centre's path (m).
    pub fn path_apothem(&self) -> f64 {
        self.bowl_radius * (PI / self.sides as f64).cos() - self.disc_radius
    }

    /// The centre's position (m) at release: on the piece under the polar
    /// angle θ₀, at that angle.
    pub fn release_position(&self) -> [f64; 2] {
        let (piece, s) = self.release_piece();
        let (n, d) = self.frame(piece);
        let a = self.path_apothem();
        [a * n[0] + s * d[0], a * n[1] + s * d[1]]
    }

    /// The piece under θ₀ and the centre's coordinate along it (m).
    fn release_piece(&self) -> (i64, f64) {
        let beta = 2.0 * PI / self.sides as f64;
        let piece = ((self.release + 0.5 * beta) / beta).floor() as i64;
        let s = self.path_apothem() * (self.release - piece as f64 * beta).tan();
        (piece, s)
    }

    /// Piece `k`'s outward normal (towards the bowl) and its direction of
    /// increasing polar angle.
    fn frame(&self, k: i64) -> ([f64; 2], [f64; 2]) {
        let phi = -0.5 * PI + k as f64 * 2.0 * PI / self.sides as f64;
        ([phi.cos(), phi.sin()], [-phi.sin(), phi.cos()])
    }

    /// The first `count` times (s) at which the centre crosses x = 0 (the
    /// bottom piece's middle), the motion stepped piece by piece in closed
    /// form; fewer if the disc comes to rest on the bottom piece first or
    /// `until` (s) passes.
    pub fn crossings(&self, count: usize, until: f64) -> Vec<f64> {
        self.crossings_with_lead(count, until, |_| 0.0)
    }

    /// [`PolygonBowl::crossings`] with each join's impact taken τ seconds
    /// early (late if τ < 0), τ = `lead(|v_j|)` of the speed v_j (m/s) the
    /// disc reaches the join with: the impact's factor applies to the speed
    /// the disc had τ earlier on the old piece, v_j − a_old τ, and the new
    /// piece's acceleration acts over τ, v' = ((2 cos β + 1)/3)(v_j −
    /// a_old τ) + a_new τ (a along the pieces, m/s²): the motion switches
    /// from one piece's acceleration to the next's τ early, as the soft
    /// step's impact does (docs/cases.md#bowl). The positions and times
    /// are the exact model's (the shift of the join's place, O(a τ²), is
    /// left out).
    pub fn crossings_with_lead(
        &self,
        count: usize,
        until: f64,
        lead: impl Fn(f64) -> f64,
    ) -> Vec<f64> {
        let beta = 2.0 * PI / self.sides as f64;
        let half = self.path_apothem() * (0.5 * beta).tan();
        let corner = (2.0 * beta.cos() + 1.0) / 3.0;
        let (mut piece, mut s) = self.release_piece();
        let (mut v, mut t) = (0.0_f64, 0.0_f64);
        let mut out = Vec::new();
        while out.len() < count && t < until {
            let (_, d) = self.frame(piece);
            let accel = -(2.0 / 3.0) * self.gravity * d[1];
            if piece == 0 {
                // The bottom piece is level: uniform motion; x = s.
                if v == 0.0 {
                    break;
                }
                if (s < 0.0) != (v < 0.0) && s != 0.0 {
                    out.push(t - s / v);
                    if out.len() == count {
                        break;
                    }
                }
                let end = if v > 0.0 { half } else { -half };
                t += (end - s) / v;
                s = end;
            } else {
                // s + v τ + a τ²/2 reaches an end: the earliest positive
                // root over both ends.
                let tau = [half, -half]
                    .into_iter()
                    .filter_map(|end| first_root(0.5 * accel, v, s - end))
                    .fold(f64::INFINITY, f64::min);
                if !tau.is_finite() {
                    break;
                }
                v += accel * tau;
                t += tau;
                s = if v > 0.0 { half } else { -half };
            }
            // Onto the next piece, losing speed at the join.
            let step = if v > 0.0 { 1 } else { -1 };
            let lead = lead(v.abs());
            let before = v - accel * lead;
            piece += step;
            s = -s;
            let (_, d) = self.frame(piece);
            v = corner * before - (2.0 / 3.0) * self.gravity * d[1] * lead;
        }
        out
    }
}

/// The smallest τ > 0 with `a τ² + b τ + c = 0`, if any (computed without
/// cancellation).
fn first_root(a: f64, b: f64, c: f64) -> Option<f64> {
    let roots: Vec<f64> = if a == 0.0 {
        if b == 0.0 { vec![] } else { vec![-c / b] }
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc < 0.0 {
            return None;
        }
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        if q == 0.0 {
            vec![0.0]
        } else {
            vec![q / a, c / q]
        }
    };
    roots
        .into_iter()
        .filter(|&r| r > 1e-15)
        .fold(None, |best: Option<f64>, r| {
            Some(best.map_or(r, |b| b.min(r)))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bowl(sides: usize) -> PolygonBowl {
        PolygonBowl {
            bowl_radius: 2.0,
            disc_radius: 0.1,
            sides,
            gravity: 10.0,
            release: 0.2,
        }
    }

    #[test]
    fn elliptic_k_has_its_known_values() {
        assert!((elliptic_k(0.0) - PI / 2.0).abs() < 1e-15);
        // K(1/√2) = Γ(1/4)² / (4 √π) = 1.854 074 677 301 372 (A&S 17.3).
        assert!((elliptic_k(0.5f64.sqrt()) - 1.854_074_677_301_372).abs() < 1e-14);
    }

    #[test]
    fn the_polygon_period_tends_to_the_circle_period() {
        // Crossings every half period: the full period from the first and
        // third.
        let error = |n| {
            let b = bowl(n);
            let c = b.crossings(3, 100.0);
            ((c[2] - c[0]) - b.circle_period()).abs() / b.circle_period()
        };
        let (e1, e2, e3) = (error(32), error(128), error(512));
        assert!(e1 > e2 && e2 > e3, "{e1} {e2} {e3}");
        assert!(e3 < 1e-3, "{e3}");
    }

    #[test]
    fn a_lead_at_the_joins_moves_the_period_and_none_keeps_it() {
        let b = bowl(32);
        let period = |lead: f64| {
            let c = b.crossings_with_lead(4, 100.0, |_| lead);
            0.5 * ((c[2] - c[0]) + (c[3] - c[1]))
        };
        let c = b.crossings(4, 100.0);
        assert_eq!(period(0.0), 0.5 * ((c[2] - c[0]) + (c[3] - c[1])));
        // An early switch loses speed at every join (downhill it misses
        // the steeper piece's acceleration, uphill it meets the steeper
        // piece's deceleration sooner): a smaller swing, and on this well
        // of few pieces a shorter period; a late one the reverse.
        assert!(period(0.005) < period(0.0) && period(0.0) < period(-0.005));
        // To first order the speed after a join falls by the difference of
        // the two pieces' accelerations times the lead: at the first join
        // (piece 1 to the level piece 0), (2/3) g sin β τ.
        let beta = 2.0 * PI / 32.0;
        let first_join = |lead: f64| {
            // The speed on leaving the first join is that at the first
            // crossing, the bottom piece being level.
            let c = b.crossings_with_lead(1, 100.0, |_| lead);
            let half = b.path_apothem() * (0.5 * beta).tan();
            let (piece, s) = b.release_piece();
            assert_eq!(piece, 1);
            let a = (2.0 / 3.0) * 10.0 * beta.sin();
            let t_join = (2.0 * (s + half) / a).sqrt();
            half / (c[0] - t_join)
        };
        let tau = 1e-4;
        let drop = first_join(0.0) - first_join(tau);
        let expected = (2.0 * beta.cos() + 1.0) / 3.0 * (2.0 / 3.0) * 10.0 * beta.sin() * tau;
        assert!((drop - expected).abs() < 1e-9, "{drop} {expected}");
    }

    #[test]
    fn the_release_point_is_on_the_path_at_the_release_angle() {
        let b = bowl(32);
        let [x, y] = b.release_position();
        assert!((x.atan2(-y) - b.release).abs() < 1e-14);
    }
}
