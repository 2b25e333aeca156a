//! A chain hanging between two anchors: the continuous catenary, and the
//! exact equilibrium of a chain of n equal rigid links, which is what a
//! simulated chain of rigid bodies rests on (the `chain` case).
//!
//! # The continuous catenary
//!
//! A perfectly flexible inextensible chain of uniform weight per length
//! hangs as y = a cosh((x − x0)/a) + c (Leibniz, Huygens and Johann
//! Bernoulli, 1691; e.g. Routh, *Analytical Statics*, §443). Through
//! (x1, y1) and (x2, y2), Δx = x2 − x1 > 0, Δy = y2 − y1, with arc length
//! S > √(Δx² + Δy²): the arc length and the height difference give
//! S = 2a cosh(m) sinh(Δx/(2a)) and Δy = 2a sinh(m) sinh(Δx/(2a)) with
//! m = ((x1 + x2)/2 − x0)/a, hence
//!
//!   √(S² − Δy²) = 2a sinh(Δx/(2a)),  x0 = (x1 + x2)/2 − a atanh(Δy/S),
//!   c = y1 − a cosh((x1 − x0)/a).
//!
//! With u = Δx/(2a) the first is sinh(u)/u = √(S² − Δy²)/Δx > 1, whose
//! left side increases from 1 on u > 0: one root, found here by bisection
//! on a bracket doubled until it holds (robust, to round-off).
//!
//! # The discrete chain
//!
//! n links of length ℓ = S/n and equal weight w, joined by frictionless
//! hinges, the ends hinged at the anchors. Cut the chain anywhere: the
//! horizontal force H is the same everywhere (no horizontal load), and the
//! vertical force steps by each weight it passes. Each link is a uniform
//! bar (as rigid-body links are): the forces at its ends and its weight at
//! its middle balance in moment about the middle, so it lies along the
//! mean of its end forces. With (H, V0) the force the first link's left
//! end exerts on the left anchor (V0 < 0: the anchor holds the chain up
//! with −V0), link i (from 0 at the left) is turned by φi from the
//! horizontal with
//!
//!   tan φi = (V0 + (i + ½) w)/H,
//!
//! and the chain closes on the right anchor: Σ ℓ cos φi = Δx,
//! Σ ℓ sin φi = Δy. These two equations in (w/H, V0/H) are solved by
//! Newton's method (analytic Jacobian, step halving while the residual
//! does not decrease) from the continuous catenary's values, to a
//! residual below 1e-13 × S. The joints are then the partial sums.
//!
//! The same joints are the equilibrium of massless links with a point
//! mass w at each of the n − 1 interior joints (the textbook discrete
//! catenary, tan φi = (V0' + i w)/H with V0' = V0 + w/2): a uniform link's
//! weight acts on the chain as half at each of its ends, and the halves at
//! the two anchors go straight into them. Only the anchor forces differ.
//!
//! Units: SI (m; forces in units of one link's weight w).

use thiserror::Error;

/// Why a chain configuration has no solution.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CatenaryError {
    /// The inputs admit no hanging chain.
    #[error("catenary: {0}")]
    Invalid(&'static str),
    /// Newton's method did not converge.
    #[error("discrete chain: no convergence after {0} Newton iterations")]
    NoConvergence(usize),
}

/// The continuous catenary y = a cosh((x − x0)/a) + c through two anchors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Catenary {
    /// The parameter a = H / (weight per length), m.
    pub a: f64,
    /// x of the lowest point (possibly outside the span), m.
    pub x0: f64,
    /// The vertical offset c, m (the lowest point is at y = a + c).
    pub c: f64,
    /// The left anchor, m.
    pub start: [f64; 2],
    /// The right anchor, m.
    pub end: [f64; 2],
    /// Arc length S between the anchors, m.
    pub length: f64,
}

impl Catenary {
    /// The catenary of arc length `length` (m) from `start` to `end`
    /// (start's x < end's x), refused if the chain is not longer than the
    /// straight line between the anchors.
    pub fn through(start: [f64; 2], end: [f64; 2], length: f64) -> Result<Self, CatenaryError> {
        let (dx, dy) = (end[0] - start[0], end[1] - start[1]);
        if !(dx.is_finite() && dy.is_finite() && length.is_finite()) || dx <= 0.0 {
            return Err(CatenaryError::Invalid(
                "the anchors must be finite, the first to the left of the second",
            ));
        }
        if length <= dx.hypot(dy) {
            return Err(CatenaryError::Invalid(
                "the chain must be longer than the straight line between its anchors",
            ));
        }
        let r = (length * length - dy * dy).sqrt() / dx;
        let g = |u: f64| u.sinh() / u - r;
        // sinh(u)/u − r is negative near 0 and increasing: double the
        // upper end of the bracket until it is positive, then bisect.
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        while g(hi) <= 0.0 {
            lo = hi;
            hi *= 2.0;
            if hi > 700.0 {
                return Err(CatenaryError::Invalid(
                    "the chain is too slack to represent",
                ));
            }
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if g(mid) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let u = 0.5 * (lo + hi);
        let a = dx / (2.0 * u);
        let x0 = 0.5 * (start[0] + end[0]) - a * (dy / length).atanh();
        let c = start[1] - a * ((start[0] - x0) / a).cosh();
        Ok(Self {
            a,
            x0,
            c,
            start,
            end,
            length,
        })
    }

    /// y at `x`, m.
    pub fn y(&self, x: f64) -> f64 {
        self.a * ((x - self.x0) / self.a).cosh() + self.c
    }

    /// The point at arc length `s` (m) from the left anchor:
    /// x = x0 + a asinh(s/a + sinh((x1 − x0)/a)).
    pub fn point_at(&self, s: f64) -> [f64; 2] {
        let x =
            self.x0 + self.a * (s / self.a + ((self.start[0] - self.x0) / self.a).sinh()).asinh();
        [x, self.y(x)]
    }

    /// Arc length from the left anchor to `x`, m.
    pub fn arc_length_to(&self, x: f64) -> f64 {
        let sh = |x: f64| ((x - self.x0) / self.a).sinh();
        self.a * (sh(x) - sh(self.start[0]))
    }
}

/// Weights passed from the left end to the middle of link `i`.
fn offset(i: usize) -> f64 {
    i as f64 + 0.5
}

/// The equilibrium of `links` equal links hanging from `start` to `end`.
#[derive(Debug, Clone, PartialEq)]
pub struct DiscreteChain {
    /// The n + 1 joint positions, anchors included, m.
    pub joints: Vec<[f64; 2]>,
    /// H / w: the horizontal force in units of one link's weight.
    pub horizontal_force: f64,
    /// −V0 / w: the upward force with which the left anchor holds the
    /// chain, in link weights.
    pub left_vertical_force: f64,
    /// Length of each link, m.
    pub link_length: f64,
}

/// Largest Newton iteration count of [`DiscreteChain::solve`].
const MAX_NEWTON: usize = 100;

impl DiscreteChain {
    /// Solves the chain of `links` uniform links of total length `length`
    /// (m) between `start` and `end` (start's x < end's x).
    pub fn solve(
        start: [f64; 2],
        end: [f64; 2],
        length: f64,
        links: usize,
    ) -> Result<Self, CatenaryError> {
        if links < 2 {
            return Err(CatenaryError::Invalid(
                "a hanging chain needs at least 2 links",
            ));
        }
        let cont = Catenary::through(start, end, length)?;
        let (dx, dy) = (end[0] - start[0], end[1] - start[1]);
        let l = length / links as f64;
        // Unknowns z = (u, v) = (w/H, V0/H): tan φi = v + k_i u.
        // Start from the continuous chain: w/H = ℓ/a, V0/H its slope at
        // the left anchor.
        let mut z = [l / cont.a, ((start[0] - cont.x0) / cont.a).sinh()];
        let residual = |z: [f64; 2]| {
            let (mut fx, mut fy) = (-dx, -dy);
            for i in 0..links {
                let t = z[1] + offset(i) * z[0];
                let q = 1.0 / (1.0 + t * t).sqrt();
                fx += l * q;
                fy += l * t * q;
            }
            [fx, fy]
        };
        let norm = |f: [f64; 2]| f[0].hypot(f[1]);
        let mut f = residual(z);
        let mut iterations = 0;
        while norm(f) > 1e-13 * length {
            iterations += 1;
            if iterations > MAX_NEWTON {
                return Err(CatenaryError::NoConvergence(MAX_NEWTON));
            }
            // d cos φ/dt = −t/(1+t²)^(3/2), d sin φ/dt = 1/(1+t²)^(3/2);
            // dt/du = k_i, dt/dv = 1.
            let mut j = [[0.0; 2]; 2];
            for i in 0..links {
                let k = offset(i);
                let t = z[1] + k * z[0];
                let q3 = (1.0 + t * t).powf(-1.5);
                j[0][0] += -l * t * q3 * k;
                j[0][1] += -l * t * q3;
                j[1][0] += l * q3 * k;
                j[1][1] += l * q3;
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            let step = [
                (f[0] * j[1][1] - f[1] * j[0][1]) / det,
                (j[0][0] * f[1] - j[1][0] * f[0]) / det,
            ];
            let mut lambda = 1.0;
            loop {
                let trial = [z[0] - lambda * step[0], z[1] - lambda * step[1]];
                let ft = residual(trial);
                if trial[0] > 0.0 && norm(ft) < norm(f) {
                    (z, f) = (trial, ft);
                    break;
                }
                lambda *= 0.5;
                if lambda < 1e-12 {
                    return Err(CatenaryError::NoConvergence(iterations));
                }
            }
        }
        let mut joints = Vec::with_capacity(links + 1);
        let mut p = start;
        joints.push(p);
        for i in 0..links {
            let t = z[1] + offset(i) * z[0];
            let q = 1.0 / (1.0 + t * t).sqrt();
            p = [p[0] + l * q, p[1] + l * t * q];
            joints.push(p);
        }
        Ok(Self {
            joints,
            horizontal_force: 1.0 / z[0],
            left_vertical_force: -z[1] / z[0],
            link_length: l,
        })
    }

    /// The potential energy of uniform links through `joints`, in link
    /// weights × m (each link's weight at its middle): what the
    /// equilibrium minimises among chains of the same links.
    pub fn potential(joints: &[[f64; 2]]) -> f64 {
        joints.windows(2).map(|w| 0.5 * (w[0][1] + w[1][1])).sum()
    }
}

#[cfg(test)]
mod tests;
