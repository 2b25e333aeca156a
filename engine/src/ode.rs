//! The generic ODE system every integrator works on (seed §4.3:
//! `x' = f(t, x)`, `x(t0) = x0`).
//!
//! The same trait carries the scalar stiff test of Hoffman and a whole world
//! of bodies, so one integrator implementation serves both.

/// How the state vector is organised.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Structure {
    /// A general first-order system `y' = f(t, y)`.
    FirstOrder,
    /// A mechanical system: `y = [q, v]` with `n` positions `q` then `n`
    /// velocities `v`, and `q' = v`, `v' = a(t, q, v)`. Required by the
    /// symplectic methods (semi-implicit Euler, velocity Verlet).
    SecondOrder {
        /// Number of position coordinates `n` (the state has `2n` entries).
        positions: usize,
    },
}

/// A system of ordinary differential equations `y' = f(t, y)`.
pub trait OdeSystem {
    /// Number of state variables.
    fn dimension(&self) -> usize;

    /// Writes `f(t, y)` into `dydt` (same length as `y`).
    fn derivative(&mut self, t: f64, y: &[f64], dydt: &mut [f64]);

    /// The layout of the state; first order unless the system says otherwise.
    fn structure(&self) -> Structure {
        Structure::FirstOrder
    }
}

/// An [`OdeSystem`] defined by a closure, for small scalar problems such as
/// the Hoffman stiff test.
pub struct FnSystem<F> {
    dimension: usize,
    f: F,
}

impl<F: FnMut(f64, &[f64], &mut [f64])> FnSystem<F> {
    /// A first-order system of `dimension` variables with right-hand side `f`.
    pub fn new(dimension: usize, f: F) -> Self {
        Self { dimension, f }
    }
}

impl<F: FnMut(f64, &[f64], &mut [f64])> OdeSystem for FnSystem<F> {
    fn dimension(&self) -> usize {
        self.dimension
    }
    fn derivative(&mut self, t: f64, y: &[f64], dydt: &mut [f64]) {
        (self.f)(t, y, dydt)
    }
}
