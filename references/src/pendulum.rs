//! The simple and the physical pendulum in closed form: the exact period
//! by the complete elliptic integral of the first kind, and the exact
//! motion θ(t) by Jacobi's elliptic functions.
//!
//! A rigid body swinging without friction about a fixed pivot at distance
//! d from its centre of mass obeys I_p θ'' = −m g d sin θ (θ the angle of
//! the pivot→centre line from the downward vertical, I_p the moment of
//! inertia about the pivot): the simple pendulum θ'' = −(g/L) sin θ of the
//! equivalent length L = I_p/(m d) (a point mass on a massless rod has
//! I_p = m L²). Released at rest from θ0 (0 < θ0 < π), energy conservation
//! gives (Whittaker, *Analytical Dynamics*, §44; Lawden, *Elliptic
//! Functions and Applications*, §5.1)
//!
//!   T = 4 √(L/g) K(k),  k = sin(θ0/2),
//!   θ(t) = 2 asin(k sn(K − ω t, k)),  θ'(t) = −2 k ω cn(K − ω t, k),  ω = √(g/L),
//!
//! K(k) = ∫₀^{π/2} dφ/√(1 − k² sin²φ) the complete elliptic integral of the
//! first kind of modulus k, sn and cn Jacobi's elliptic functions of
//! modulus k.
//!
//! Both are computed by the arithmetic–geometric mean (Abramowitz &
//! Stegun, *Handbook of Mathematical Functions*, 17.6 and 16.4; DLMF
//! 19.8.5 and 22.20): K(k) = π / (2 AGM(1, √(1 − k²))), quadratically
//! convergent (each iteration doubles the correct digits: 6 iterations
//! reach round-off for k ≤ sin 85°); sn, cn, dn by the descending Landen
//! transformation driven by the same AGM sequence (A&S 16.4.3).
//!
//! Units: SI (m, s, rad, kg).

use std::f64::consts::PI;

/// Largest number of AGM iterations; the sequence converges quadratically,
/// so 40 is far beyond what any modulus below 1 − 1e-15 needs.
const MAX_AGM_ITERATIONS: usize = 40;

/// The arithmetic–geometric mean of `a` and `b` (both > 0): the common
/// limit of a ← (a + b)/2, b ← √(ab).
pub fn agm(mut a: f64, mut b: f64) -> f64 {
    for _ in 0..MAX_AGM_ITERATIONS {
        let (an, bn) = (0.5 * (a + b), (a * b).sqrt());
        if (an - bn).abs() <= 4.0 * f64::EPSILON * an {
            return an;
        }
        (a, b) = (an, bn);
    }
    a
}

/// The complete elliptic integral of the first kind K(k) of modulus `k`
/// (0 ≤ k < 1): π / (2 AGM(1, √(1 − k²))). (Libraries that take the
/// parameter m = k² compute the same K with m.)
pub fn elliptic_k(k: f64) -> f64 {
    assert!((0.0..1.0).contains(&k), "modulus {k} outside [0, 1)");
    PI / (2.0 * agm(1.0, ((1.0 - k) * (1.0 + k)).sqrt()))
}

/// Jacobi's elliptic functions (sn, cn, dn) of argument `u` and modulus
/// `k` (0 ≤ k < 1), by the descending Landen transformation (A&S 16.4):
/// a0 = 1, b0 = √(1 − k²), c0 = k; aₙ₊₁ = (aₙ + bₙ)/2, bₙ₊₁ = √(aₙbₙ),
/// cₙ₊₁ = (aₙ − bₙ)/2 until c_N ≈ 0; φ_N = 2^N a_N u; then
/// φₙ₋₁ = (φₙ + asin(cₙ sin φₙ / aₙ))/2 down to φ0; sn = sin φ0,
/// cn = cos φ0, dn = √(1 − k² sn²).
pub fn jacobi_sn_cn_dn(u: f64, k: f64) -> (f64, f64, f64) {
    assert!((0.0..1.0).contains(&k), "modulus {k} outside [0, 1)");
    if k == 0.0 {
        return (u.sin(), u.cos(), 1.0);
    }
    let mut a = vec![1.0];
    let mut c = vec![k];
    let mut b = ((1.0 - k) * (1.0 + k)).sqrt();
    while c.last().is_some_and(|&cn| cn.abs() > f64::EPSILON * 0.5) && a.len() <= MAX_AGM_ITERATIONS
    {
        let an = *a.last().expect("non-empty");
        a.push(0.5 * (an + b));
        c.push(0.5 * (an - b));
        b = (an * b).sqrt();
    }
    let n = a.len() - 1;
    let mut phi = (1u64 << n) as f64 * a[n] * u;
    for i in (1..=n).rev() {
        phi = 0.5 * (phi + (c[i] / a[i] * phi.sin()).asin());
    }
    let (sn, cn) = phi.sin_cos();
    // dn from dn² = 1 − k² sn² (> 0 for real u and k < 1): A&S's
    // cos φ0 / cos(φ1 − φ0) is 0/0 where cn vanishes.
    (sn, cn, (1.0 - k * k * sn * sn).sqrt())
}

/// A pendulum of equivalent length `length` (m) under gravity `gravity`
/// (m/s²), released at rest from `amplitude` (rad, 0 < θ0 < π) from the
/// downward vertical.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pendulum {
    /// Equivalent length L = I_pivot/(m d), m (the rod's length for a
    /// point mass).
    pub length: f64,
    /// g, m/s².
    pub gravity: f64,
    /// θ0, rad.
    pub amplitude: f64,
}

impl Pendulum {
    /// A pendulum; panics unless L > 0, g > 0 and 0 < θ0 < π.
    pub fn new(length: f64, gravity: f64, amplitude: f64) -> Self {
        assert!(length > 0.0 && gravity > 0.0, "L = {length}, g = {gravity}");
        assert!(
            amplitude > 0.0 && amplitude < PI,
            "amplitude {amplitude} outside (0, pi)"
        );
        Self {
            length,
            gravity,
            amplitude,
        }
    }

    /// k = sin(θ0/2).
    pub fn modulus(&self) -> f64 {
        (0.5 * self.amplitude).sin()
    }

    /// ω = √(g/L), rad/s (the small-amplitude angular frequency).
    pub fn omega(&self) -> f64 {
        (self.gravity / self.length).sqrt()
    }

    /// The exact period T = 4 √(L/g) K(sin(θ0/2)), s.
    pub fn period(&self) -> f64 {
        4.0 * elliptic_k(self.modulus()) / self.omega()
    }

    /// The small-amplitude period 2π √(L/g), s.
    pub fn small_angle_period(&self) -> f64 {
        2.0 * PI / self.omega()
    }

    /// The exact angle θ(t) = 2 asin(k sn(K − ω t, k)), rad.
    pub fn angle(&self, t: f64) -> f64 {
        let k = self.modulus();
        let (sn, _, _) = jacobi_sn_cn_dn(elliptic_k(k) - self.omega() * t, k);
        2.0 * (k * sn).clamp(-1.0, 1.0).asin()
    }

    /// The exact angular velocity θ'(t) = −2 k ω cn(K − ω t, k), rad/s.
    pub fn angular_velocity(&self, t: f64) -> f64 {
        let k = self.modulus();
        let (_, cn, _) = jacobi_sn_cn_dn(elliptic_k(k) - self.omega() * t, k);
        -2.0 * k * self.omega() * cn
    }

    /// Energy per unit of m L², (1/2) θ'² − (g/L) cos θ, s⁻²: constant.
    pub fn energy(&self, angle: f64, angular_velocity: f64) -> f64 {
        0.5 * angular_velocity * angular_velocity - self.omega().powi(2) * angle.cos()
    }
}

/// Area (m²), centroid (m) and polar second moment of area about the
/// centroid (m⁴) of a convex polygon with counter-clockwise `vertices`
/// (m), by the triangle fan from the first vertex (each triangle's area,
/// centroid and moment, shifted by the parallel-axis theorem). Computed
/// here, not by the engine, so the reference stays independent.
pub fn polygon_area_moment(vertices: &[[f64; 2]]) -> (f64, [f64; 2], f64) {
    assert!(vertices.len() >= 3, "a polygon needs 3 vertices");
    let o = vertices[0];
    let (mut area, mut cx, mut cy, mut j_o) = (0.0, 0.0, 0.0, 0.0);
    for w in vertices[1..].windows(2) {
        let (p, q) = (
            [w[0][0] - o[0], w[0][1] - o[1]],
            [w[1][0] - o[0], w[1][1] - o[1]],
        );
        let cross = p[0] * q[1] - p[1] * q[0];
        let a = 0.5 * cross;
        area += a;
        cx += a * (p[0] + q[0]) / 3.0;
        cy += a * (p[1] + q[1]) / 3.0;
        // ∫ r² dA over the triangle (0, p, q) about the vertex 0.
        j_o += cross / 12.0 * (p[0] * p[0] + p[0] * q[0] + q[0] * q[0])
            + cross / 12.0 * (p[1] * p[1] + p[1] * q[1] + q[1] * q[1]);
    }
    let c = [cx / area, cy / area];
    let j_c = j_o - area * (c[0] * c[0] + c[1] * c[1]);
    (area, [c[0] + o[0], c[1] + o[1]], j_c)
}

/// A rigid body pivoted about a fixed point: its distance d (m) from the
/// pivot to the centre of mass and its moment of inertia per unit mass
/// about the centre, I_c/m (m²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalPendulum {
    /// d, m (> 0).
    pub pivot_distance: f64,
    /// I_c / m, m².
    pub inertia_per_mass: f64,
}

impl PhysicalPendulum {
    /// A uniform convex polygon (`vertices` counter-clockwise, m) pivoted
    /// at `pivot` (same frame, m).
    pub fn polygon(vertices: &[[f64; 2]], pivot: [f64; 2]) -> Self {
        let (area, c, j) = polygon_area_moment(vertices);
        Self {
            pivot_distance: (c[0] - pivot[0]).hypot(c[1] - pivot[1]),
            inertia_per_mass: j / area,
        }
    }

    /// A uniform disc of `radius` (m) whose centre is `pivot_distance` (m)
    /// from the pivot (I_c/m = r²/2).
    pub fn disc(radius: f64, pivot_distance: f64) -> Self {
        Self {
            pivot_distance,
            inertia_per_mass: 0.5 * radius * radius,
        }
    }

    /// The equivalent simple-pendulum length I_pivot/(m d) =
    /// (I_c/m + d²)/d, m.
    pub fn equivalent_length(&self) -> f64 {
        assert!(self.pivot_distance > 0.0, "the pivot is at the centre");
        (self.inertia_per_mass + self.pivot_distance.powi(2)) / self.pivot_distance
    }

    /// The simple pendulum it swings as, under `gravity` from `amplitude`.
    pub fn pendulum(&self, gravity: f64, amplitude: f64) -> Pendulum {
        Pendulum::new(self.equivalent_length(), gravity, amplitude)
    }
}

#[cfg(test)]
mod tests;
