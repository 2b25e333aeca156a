//! A chain of rigid links on *elastic* pins, at rest between two anchors:
//! the static equilibrium of [`crate::catenary::DiscreteChain`] when each
//! pin lets its two anchors separate in proportion to the force it
//! carries, as a soft constraint does at rest (the `chain` case).
//!
//! # The pins
//!
//! A soft point constraint of angular frequency ω between bodies A and B
//! (Box2D's soft step, and this project's) comes to rest where its bias
//! balances its load: the separation of its anchors is
//!
//!   d = p_B − p_A = −K F / ω²,   K = Σ (1/m) 1 + (1/I) r⊥ r⊥ᵀ,
//!
//! F the force of the pin on B, K its inverse effective mass (the sum over
//! the dynamic bodies it holds, r the arm from each body's centre to its
//! anchor, r⊥ = (−r_y, r_x)). A rigid pin has ω = ∞.
//!
//! # The equilibrium
//!
//! n uniform links (mass m, moment of inertia I about the centre, length ℓ
//! between their two pins at ±ℓ/2 along the link), pin 0 holding link 0 to
//! the start anchor, pin j links j − 1 and j, pin n link n − 1 to the end
//! anchor. With F_j the force of pin j on its B side (link j, the world for
//! pin n), force balance on link j gives F_{j+1} = F_j − (0, w), w = m g,
//! so F_j = (−H, V − j w) with H the horizontal tension and V the upward
//! force the start anchor holds the chain with. Moments about link j's
//! centre put it along −(F_j + F_{j+1}) (the separations do not enter: the
//! forces act at the link's own pins), so
//!
//!   û_j ∝ (H, (j + ½) w − V),
//!
//! the rigid chain's law. Closure: start + Σ_j d_j + Σ_j ℓ û_j = end, two
//! equations in (H, V) solved by Newton's method (a finite-difference
//! Jacobian, step halving), from the rigid chain's solution, to a residual
//! below 1e-13 × the chain's length.
//!
//! Units: SI (m, kg, kg·m², N, rad/s).

use crate::catenary::{CatenaryError, DiscreteChain};

/// Links and pins of an elastic chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticChain {
    /// Number of links n (≥ 2).
    pub links: usize,
    /// Pin-to-pin length of a link ℓ, m.
    pub link_length: f64,
    /// Mass of a link m, kg.
    pub mass: f64,
    /// Moment of inertia of a link about its centre I, kg·m².
    pub inertia: f64,
    /// Gravity g (along −y), m/s².
    pub gravity: f64,
    /// The pins' angular frequency ω (rad/s); `f64::INFINITY` for rigid
    /// pins.
    pub omega: f64,
}

/// The equilibrium of an [`ElasticChain`].
#[derive(Debug, Clone, PartialEq)]
pub struct ElasticRest {
    /// Each pin's anchor on its B side (link j's left end for j < n) and,
    /// last, pin n's anchor on link n − 1 (its right end), m: n + 1 points.
    pub pins: Vec<[f64; 2]>,
    /// Each pin's separation p_B − p_A, m (n + 1 vectors).
    pub separations: Vec<[f64; 2]>,
    /// Each link's angle from the horizontal, rad.
    pub angles: Vec<f64>,
    /// H, N.
    pub horizontal_force: f64,
    /// V, N.
    pub vertical_force: f64,
}

/// Largest Newton iteration count.
const MAX_NEWTON: usize = 60;

impl ElasticChain {
    /// The links' directions û_j for forces (H, V).
    fn directions(&self, h: f64, v: f64) -> Vec<[f64; 2]> {
        let w = self.mass * self.gravity;
        (0..self.links)
            .map(|j| {
                let (x, y) = (h, (j as f64 + 0.5) * w - v);
                let n = x.hypot(y);
                [x / n, y / n]
            })
            .collect()
    }

    /// The separation of pin `j` given the link directions `u` and (H, V).
    fn separation(&self, j: usize, u: &[[f64; 2]], h: f64, v: f64) -> [f64; 2] {
        if !self.omega.is_finite() {
            return [0.0, 0.0];
        }
        let w = self.mass * self.gravity;
        let f = [-h, v - j as f64 * w];
        let a = 0.5 * self.link_length;
        // K F = Σ over the pin's links: F/m + (r⊥·F) r⊥ / I.
        let mut kf = [0.0, 0.0];
        let mut add = |r: [f64; 2]| {
            let perp = [-r[1], r[0]];
            let dot = perp[0] * f[0] + perp[1] * f[1];
            kf[0] += f[0] / self.mass + dot * perp[0] / self.inertia;
            kf[1] += f[1] / self.mass + dot * perp[1] / self.inertia;
        };
        if j > 0 {
            // Link j − 1, its right end.
            add([a * u[j - 1][0], a * u[j - 1][1]]);
        }
        if j < self.links {
            // Link j, its left end.
            add([-a * u[j][0], -a * u[j][1]]);
        }
        let k = -1.0 / (self.omega * self.omega);
        [k * kf[0], k * kf[1]]
    }

    /// The pins (B sides, then the last A side) and separations for (H, V),
    /// and the closure residual (end reached minus `end`), m.
    fn build(
        &self,
        start: [f64; 2],
        end: [f64; 2],
        h: f64,
        v: f64,
    ) -> (Vec<[f64; 2]>, Vec<[f64; 2]>, [f64; 2]) {
        let u = self.directions(h, v);
        let mut pins = Vec::with_capacity(self.links + 1);
        let mut seps = Vec::with_capacity(self.links + 1);
        let mut p = start;
        for j in 0..self.links {
            let d = self.separation(j, &u, h, v);
            seps.push(d);
            p = [p[0] + d[0], p[1] + d[1]];
            pins.push(p);
            p = [
                p[0] + self.link_length * u[j][0],
                p[1] + self.link_length * u[j][1],
            ];
        }
        pins.push(p);
        let d = self.separation(self.links, &u, h, v);
        seps.push(d);
        let reached = [p[0] + d[0], p[1] + d[1]];
        (pins, seps, [reached[0] - end[0], reached[1] - end[1]])
    }

    /// The chain at rest from `start` to `end` (start's x < end's x).
    pub fn solve(&self, start: [f64; 2], end: [f64; 2]) -> Result<ElasticRest, CatenaryError> {
        if !(self.mass > 0.0 && self.inertia > 0.0 && self.gravity > 0.0 && self.omega > 0.0) {
            return Err(CatenaryError::Invalid(
                "mass, inertia, gravity and the pins' frequency must be > 0",
            ));
        }
        let length = self.links as f64 * self.link_length;
        let rigid = DiscreteChain::solve(start, end, length, self.links)?;
        let w = self.mass * self.gravity;
        let (mut h, mut v) = (w * rigid.horizontal_force, w * rigid.left_vertical_force);
        let norm = |r: [f64; 2]| r[0].hypot(r[1]);
        let mut r = self.build(start, end, h, v).2;
        let mut iterations = 0;
        while norm(r) > 1e-13 * length {
            iterations += 1;
            if iterations > MAX_NEWTON {
                return Err(CatenaryError::NoConvergence(MAX_NEWTON));
            }
            // Central differences in H and V, steps 1e-7 of the forces.
            let (eh, ev) = (1e-7 * h.abs().max(w), 1e-7 * v.abs().max(w));
            let dh = |s: f64| self.build(start, end, h + s * eh, v).2;
            let dv = |s: f64| self.build(start, end, h, v + s * ev).2;
            let (hp, hm, vp, vm) = (dh(1.0), dh(-1.0), dv(1.0), dv(-1.0));
            let j = [
                [(hp[0] - hm[0]) / (2.0 * eh), (vp[0] - vm[0]) / (2.0 * ev)],
                [(hp[1] - hm[1]) / (2.0 * eh), (vp[1] - vm[1]) / (2.0 * ev)],
            ];
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            let step = [
                (r[0] * j[1][1] - r[1] * j[0][1]) / det,
                (j[0][0] * r[1] - j[1][0] * r[0]) / det,
            ];
            let mut lambda = 1.0;
            loop {
                let (th, tv) = (h - lambda * step[0], v - lambda * step[1]);
                let rt = self.build(start, end, th, tv).2;
                if th > 0.0 && norm(rt) < norm(r) {
                    (h, v, r) = (th, tv, rt);
                    break;
                }
                lambda *= 0.5;
                if lambda < 1e-12 {
                    return Err(CatenaryError::NoConvergence(iterations));
                }
            }
        }
        let (pins, separations, _) = self.build(start, end, h, v);
        let angles = self
            .directions(h, v)
            .iter()
            .map(|u| u[1].atan2(u[0]))
            .collect();
        Ok(ElasticRest {
            pins,
            separations,
            angles,
            horizontal_force: h,
            vertical_force: v,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::assert_close;

    fn chain(omega: f64) -> ElasticChain {
        ElasticChain {
            links: 20,
            link_length: 0.6,
            mass: 1.0,
            inertia: (0.36 + 0.0025) / 12.0,
            gravity: 9.81,
            omega,
        }
    }

    #[test]
    fn rigid_pins_give_the_rigid_chain() {
        let rest = chain(f64::INFINITY).solve([0.0, 0.0], [10.0, 0.0]).unwrap();
        let rigid = DiscreteChain::solve([0.0, 0.0], [10.0, 0.0], 12.0, 20).unwrap();
        for (p, q) in rest.pins.iter().zip(&rigid.joints) {
            assert_close(p[0], q[0], 1e-12, "x");
            assert_close(p[1], q[1], 1e-12, "y");
        }
        assert_close(
            rest.horizontal_force / 9.81,
            rigid.horizontal_force,
            1e-12,
            "H",
        );
    }

    #[test]
    fn soft_pins_balance_every_link_and_close_on_the_anchors() {
        let omega = 2.0 * std::f64::consts::PI * 60.0;
        let c = chain(omega);
        let rest = c.solve([0.0, 0.0], [10.0, 0.0]).unwrap();
        let (h, v, w) = (rest.horizontal_force, rest.vertical_force, 9.81);
        // Closure: from the start anchor through the separations and links
        // to the end anchor.
        let mut p = [0.0, 0.0];
        for (j, d) in rest.separations.iter().enumerate() {
            p = [p[0] + d[0], p[1] + d[1]];
            if j < c.links {
                assert_close(p[0], rest.pins[j][0], 1e-13, "pin x");
                let a = rest.angles[j];
                p = [p[0] + 0.6 * a.cos(), p[1] + 0.6 * a.sin()];
            }
        }
        assert_close(p[0], 10.0, 1e-12, "end x");
        assert_close(p[1], 0.0, 1e-12, "end y");
        // The anchors carry the weight: V at the start, 20 w − V at the end,
        // equal by symmetry; each link along the mean of its end forces.
        assert_close(v, 10.0 * w, 1e-9, "V");
        for (j, a) in rest.angles.iter().enumerate() {
            let slope = ((j as f64 + 0.5) * w - v) / h;
            assert_close(a.tan(), slope, 1e-12, "link direction");
        }
        // A pin pulled along its links stretches them: the middle pin
        // (force H on two links) opens by 2H/(m ω²), and by 1.2 % more
        // because its links tilt by ±w/(2H) and turn under it ((r⊥·F) r⊥/I).
        let middle = rest.separations[10];
        let expected = 2.0 * h / omega.powi(2);
        assert_close(middle[0], 1.0121 * expected, 1e-3 * expected, "middle");
        assert_close(middle[1], 0.0, 1e-15, "middle, vertical");
        // The chain sags more than the rigid one: its pins add length.
        let rigid = DiscreteChain::solve([0.0, 0.0], [10.0, 0.0], 12.0, 20).unwrap();
        assert!(rest.pins[10][1] < rigid.joints[10][1] - 1e-3);
    }
}
