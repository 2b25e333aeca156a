//! The double pendulum of two rigid bodies on revolute joints, by DOP853:
//! body 1 hinged to the world at a fixed pivot O, body 2 hinged to body 1
//! at a point P of body 1, under uniform gravity g along −y, without
//! friction. The reference for the `double_pendulum` case: the state at
//! given times, an error estimate, the energy, and the time before which
//! a comparison is meaningful (chaos).
//!
//! # Equations (Lagrange, two rigid bodies with inertia)
//!
//! Coordinates: the bodies' absolute angles φ1, φ2 (counter-clockwise,
//! the engines' body angles). In body 1's frame its centre of mass is at
//! c1 from O and the joint P at ℓ1 from O; in body 2's frame its centre of
//! mass is at c2 from P; masses m1, m2, moments of inertia I1, I2 about
//! the centres. With a1 = R(φ1) c1, p = R(φ1) ℓ1, a2 = R(φ2) c2 (world
//! vectors), the centres are at O + a1 and O + p + a2 and
//!
//!   T = ½ M11 φ1'² + M12 φ1' φ2' + ½ M22 φ2'²,
//!   M11 = I1 + m1|c1|² + m2|ℓ1|²,  M22 = I2 + m2|c2|²,  M12 = m2 p·a2,
//!   V = g (m1 (a1)_y + m2 (p + a2)_y).
//!
//! With S = ∂M12/∂φ1 = −∂M12/∂φ2 = m2 p × a2 (2D cross product) and
//! ∂V/∂φ1 = g (m1 (a1)_x + m2 p_x), ∂V/∂φ2 = g m2 (a2)_x, Lagrange's
//! equations d/dt ∂T/∂φ' − ∂T/∂φ + ∂V/∂φ = 0 are
//!
//!   M11 φ1'' + M12 φ2'' = S φ2'² − ∂V/∂φ1,
//!   M12 φ1'' + M22 φ2'' = −S φ1'² − ∂V/∂φ2,
//!
//! solved for (φ1'', φ2'') by Cramer's rule (det M = M11 M22 − M12² > 0).
//! Two point masses on massless rods of lengths L1, L2 hanging at φ = 0
//! are c1 = ℓ1 = (0, −L1), c2 = (0, −L2), I1 = I2 = 0: the textbook
//! double pendulum (Goldstein, *Classical Mechanics*, §1.6 exercise;
//! the tests compare with its explicit form). The energy
//! E = T + V is conserved.
//!
//! # The reference
//!
//! [`DoublePendulum::solve`] integrates with DOP853 (crate `ode_solvers`)
//! at rtol = atol = 1e-13 ([`DOUBLE_PENDULUM_TOLERANCE`]) and again at
//! 1e-10: their difference is the error estimate of the looser one, a
//! bound on the tight one's error well inside chaos' horizon. The
//! **horizon** ([`DoublePendulum::divergence_time`]) is the first time at
//! which the solution from angles perturbed by δ0 differs from the
//! unperturbed one by 1e-3 rad in either angle: before it the motion is
//! predictable to 1e-3 rad from an initial state known to δ0 (choose δ0
//! from the engine's own initial rounding and per-step error); after it
//! no engine can be expected to match any reference.
//!
//! Units: SI (m, kg, kg·m², s, rad).

use ode_solvers::{Dop853, OutputType, System, Vector4};

/// The tolerance (rtol = atol) of the reference solve.
pub const DOUBLE_PENDULUM_TOLERANCE: f64 = 1e-13;

/// The looser tolerance of the second solve, whose difference from the
/// first estimates the error.
pub const LOOSE_TOLERANCE: f64 = 1e-10;

/// The separation (rad, in either angle) that defines the horizon.
pub const DIVERGENCE_THRESHOLD: f64 = 1e-3;

/// A double pendulum of two rigid bodies (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoublePendulum {
    /// m1, kg.
    pub mass1: f64,
    /// I1 about body 1's centre of mass, kg·m².
    pub inertia1: f64,
    /// m2, kg.
    pub mass2: f64,
    /// I2 about body 2's centre of mass, kg·m² (> 0 if c2 = 0).
    pub inertia2: f64,
    /// c1: body 1's centre of mass from the pivot O, body 1's frame, m.
    pub com1: [f64; 2],
    /// ℓ1: the joint P from O, body 1's frame, m.
    pub joint: [f64; 2],
    /// c2: body 2's centre of mass from P, body 2's frame, m.
    pub com2: [f64; 2],
    /// g (acting along −y), m/s².
    pub gravity: f64,
}

/// A state: angles (rad) and angular velocities (rad/s) of the two
/// bodies.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PendulumState {
    /// φ1, φ2, rad.
    pub angles: [f64; 2],
    /// φ1', φ2', rad/s.
    pub rates: [f64; 2],
}

fn rot(a: f64, v: [f64; 2]) -> [f64; 2] {
    let (s, c) = a.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

fn norm2(v: [f64; 2]) -> f64 {
    v[0] * v[0] + v[1] * v[1]
}

impl DoublePendulum {
    /// Two point masses on massless rods of lengths `l1`, `l2` (m),
    /// hanging straight down at angles 0.
    pub fn point_masses(m1: f64, m2: f64, l1: f64, l2: f64, gravity: f64) -> Self {
        Self {
            mass1: m1,
            inertia1: 0.0,
            mass2: m2,
            inertia2: 0.0,
            com1: [0.0, -l1],
            joint: [0.0, -l1],
            com2: [0.0, -l2],
            gravity,
        }
    }

    /// Two bodies as a many-body scene describes them: masses and
    /// inertias, the world pivot `pivot`, the joint `joint`, the centres
    /// `centre1`, `centre2` (all world coordinates, m) and the body angles
    /// `angle1`, `angle2` (rad) at t = 0. Returns the pendulum and its
    /// initial angles (the body angles themselves).
    #[allow(clippy::too_many_arguments)]
    pub fn from_world(
        masses: [f64; 2],
        inertias: [f64; 2],
        pivot: [f64; 2],
        joint: [f64; 2],
        centre1: [f64; 2],
        centre2: [f64; 2],
        angles: [f64; 2],
        gravity: f64,
    ) -> Self {
        let sub = |a: [f64; 2], b: [f64; 2]| [a[0] - b[0], a[1] - b[1]];
        Self {
            mass1: masses[0],
            inertia1: inertias[0],
            mass2: masses[1],
            inertia2: inertias[1],
            com1: rot(-angles[0], sub(centre1, pivot)),
            joint: rot(-angles[0], sub(joint, pivot)),
            com2: rot(-angles[1], sub(centre2, joint)),
            gravity,
        }
    }

    /// (M11, M22): the constant diagonal of the mass matrix, kg·m².
    fn diagonal(&self) -> (f64, f64) {
        (
            self.inertia1 + self.mass1 * norm2(self.com1) + self.mass2 * norm2(self.joint),
            self.inertia2 + self.mass2 * norm2(self.com2),
        )
    }

    /// (φ1'', φ2''), rad/s², at `state`.
    pub fn accelerations(&self, state: &PendulumState) -> [f64; 2] {
        let [f1, f2] = state.angles;
        let [w1, w2] = state.rates;
        let (a1, p, a2) = (rot(f1, self.com1), rot(f1, self.joint), rot(f2, self.com2));
        let (m11, m22) = self.diagonal();
        let m12 = self.mass2 * (p[0] * a2[0] + p[1] * a2[1]);
        let s = self.mass2 * (p[0] * a2[1] - p[1] * a2[0]);
        let dv1 = self.gravity * (self.mass1 * a1[0] + self.mass2 * p[0]);
        let dv2 = self.gravity * self.mass2 * a2[0];
        let (r1, r2) = (s * w2 * w2 - dv1, -s * w1 * w1 - dv2);
        let det = m11 * m22 - m12 * m12;
        [(r1 * m22 - r2 * m12) / det, (m11 * r2 - m12 * r1) / det]
    }

    /// The energy T + V, J (V = 0 with both centres at the pivot's
    /// height).
    pub fn energy(&self, state: &PendulumState) -> f64 {
        let [f1, f2] = state.angles;
        let [w1, w2] = state.rates;
        let (a1, p, a2) = (rot(f1, self.com1), rot(f1, self.joint), rot(f2, self.com2));
        let (m11, m22) = self.diagonal();
        let m12 = self.mass2 * (p[0] * a2[0] + p[1] * a2[1]);
        let t = 0.5 * m11 * w1 * w1 + m12 * w1 * w2 + 0.5 * m22 * w2 * w2;
        t + self.gravity * (self.mass1 * a1[1] + self.mass2 * (p[1] + a2[1]))
    }

    /// The world positions of the two centres of mass relative to the
    /// pivot O, m.
    pub fn centres(&self, state: &PendulumState) -> [[f64; 2]; 2] {
        let [f1, f2] = state.angles;
        let (a1, p, a2) = (rot(f1, self.com1), rot(f1, self.joint), rot(f2, self.com2));
        [a1, [p[0] + a2[0], p[1] + a2[1]]]
    }

    /// The state at each of `times` (s, increasing, ≥ 0) from `initial`
    /// at t = 0, by DOP853 at rtol = atol = `tolerance`.
    pub fn states_at(
        &self,
        initial: PendulumState,
        times: &[f64],
        tolerance: f64,
    ) -> Result<Vec<PendulumState>, DoublePendulumError> {
        let mut out = Vec::with_capacity(times.len());
        let (mut t, mut s) = (0.0, initial);
        for &t1 in times {
            if !(t1 >= t && t1.is_finite()) {
                return Err(DoublePendulumError::Times(t1));
            }
            s = self.advance(s, t, t1, tolerance)?;
            t = t1;
            out.push(s);
        }
        Ok(out)
    }

    fn advance(
        &self,
        s: PendulumState,
        t0: f64,
        t1: f64,
        tolerance: f64,
    ) -> Result<PendulumState, DoublePendulumError> {
        if t1 == t0 {
            return Ok(s);
        }
        let y0 = Vector4::new(s.angles[0], s.angles[1], s.rates[0], s.rates[1]);
        let mut solver = Dop853::new(*self, t0, t1, t1 - t0, y0, tolerance, tolerance);
        solver.set_output(OutputType::Sparse);
        solver
            .integrate()
            .map_err(|e| DoublePendulumError::Solver(format!("{e:?}")))?;
        let reached = *solver.x_out().last().unwrap_or(&t0);
        if (reached - t1).abs() > 1e-9 * t1.abs().max(1.0) {
            return Err(DoublePendulumError::Solver(format!(
                "stopped at t = {reached} s instead of {t1} s"
            )));
        }
        let y = *solver.y_out().last().expect("at least the start");
        Ok(PendulumState {
            angles: [y[0], y[1]],
            rates: [y[2], y[3]],
        })
    }

    /// The reference at `times`: the solve at [`DOUBLE_PENDULUM_TOLERANCE`]
    /// with, per time, the largest difference (rad or rad/s) from the
    /// solve at [`LOOSE_TOLERANCE`] (the error estimate) and the energy
    /// drift |E(t) − E(0)| (J).
    pub fn solve(
        &self,
        initial: PendulumState,
        times: &[f64],
    ) -> Result<Vec<ReferencePoint>, DoublePendulumError> {
        let tight = self.states_at(initial, times, DOUBLE_PENDULUM_TOLERANCE)?;
        let loose = self.states_at(initial, times, LOOSE_TOLERANCE)?;
        let e0 = self.energy(&initial);
        Ok(tight
            .iter()
            .zip(&loose)
            .zip(times)
            .map(|((a, b), &t)| ReferencePoint {
                time: t,
                state: *a,
                error_estimate: (0..2)
                    .map(|i| {
                        (a.angles[i] - b.angles[i])
                            .abs()
                            .max((a.rates[i] - b.rates[i]).abs())
                    })
                    .fold(0.0, f64::max),
                energy_drift: (self.energy(a) - e0).abs(),
            })
            .collect())
    }

    /// The first time (s) at which the solution from `initial` with both
    /// angles increased by `delta0` (rad) differs from the one from
    /// `initial` by [`DIVERGENCE_THRESHOLD`] in either angle, searched up
    /// to `horizon` s; `None` if they stay closer. Both are solved at
    /// [`DOUBLE_PENDULUM_TOLERANCE`] on a 0.01 s grid; the crossing is
    /// located by bisection on re-integrations from the grid point before
    /// it, to 1e-6 s.
    pub fn divergence_time(
        &self,
        initial: PendulumState,
        delta0: f64,
        horizon: f64,
    ) -> Result<Option<f64>, DoublePendulumError> {
        let tol = DOUBLE_PENDULUM_TOLERANCE;
        let perturbed = PendulumState {
            angles: [initial.angles[0] + delta0, initial.angles[1] + delta0],
            ..initial
        };
        let gap = |a: &PendulumState, b: &PendulumState| {
            (a.angles[0] - b.angles[0])
                .abs()
                .max((a.angles[1] - b.angles[1]).abs())
        };
        let dt = 0.01;
        let (mut t, mut a, mut b) = (0.0, initial, perturbed);
        while t < horizon {
            let t1 = (t + dt).min(horizon);
            let (a1, b1) = (self.advance(a, t, t1, tol)?, self.advance(b, t, t1, tol)?);
            if gap(&a1, &b1) >= DIVERGENCE_THRESHOLD {
                let (mut lo, mut hi) = (t, t1);
                while hi - lo > 1e-6 {
                    let mid = 0.5 * (lo + hi);
                    let (am, bm) = (self.advance(a, t, mid, tol)?, self.advance(b, t, mid, tol)?);
                    if gap(&am, &bm) >= DIVERGENCE_THRESHOLD {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                return Ok(Some(hi));
            }
            (t, a, b) = (t1, a1, b1);
        }
        Ok(None)
    }
}

impl System<f64, Vector4<f64>> for DoublePendulum {
    fn system(&self, _t: f64, y: &Vector4<f64>, dy: &mut Vector4<f64>) {
        let s = PendulumState {
            angles: [y[0], y[1]],
            rates: [y[2], y[3]],
        };
        let acc = self.accelerations(&s);
        *dy = Vector4::new(y[2], y[3], acc[0], acc[1]);
    }
}

/// One time of the reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferencePoint {
    /// s.
    pub time: f64,
    /// The state by DOP853 at 1e-13.
    pub state: PendulumState,
    /// Largest difference from the 1e-10 solve, rad or rad/s.
    pub error_estimate: f64,
    /// |E(t) − E(0)|, J.
    pub energy_drift: f64,
}

/// Why the double pendulum reference could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DoublePendulumError {
    /// A requested time is not finite or goes backwards.
    #[error("double pendulum: time {0} s is not finite or precedes the previous one")]
    Times(f64),
    /// DOP853 failed.
    #[error("double pendulum: DOP853 failed: {0}")]
    Solver(String),
}

#[cfg(test)]
mod tests;
