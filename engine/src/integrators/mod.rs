//! Numerical integrators (seed §4.3), all on the generic [`OdeSystem`].
//!
//! One file per method; this module holds the closed [`Method`] enum, the
//! [`Integrator`] that owns the stage buffers and the work counters, and the
//! fixed-step driver [`integrate_fixed`] used for plain ODEs such as the
//! Hoffman stiff test. A [`crate::World`] drives the same [`Integrator`].
//!
//! The methods are written as index loops over the stage vectors, the way
//! their Butcher tableaux read; clippy's `needless_range_loop` is silenced
//! for that reason.

#![allow(clippy::needless_range_loop)]

mod dormand_prince;
mod explicit_euler;
mod implicit_euler;
mod midpoint;
mod rk4;
mod semi_implicit_euler;
mod step_controller;
mod velocity_verlet;

use crate::error::{EngineError, Result};
use crate::ode::{OdeSystem, Structure};
use step_controller::StepController;

/// Error tolerances of the adaptive method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Relative tolerance (dimensionless).
    pub rtol: f64,
    /// Absolute tolerance, in the units of each state variable.
    pub atol: f64,
}

impl Tolerance {
    /// The same value for the relative and the absolute tolerance.
    pub fn uniform(tol: f64) -> Self {
        Self {
            rtol: tol,
            atol: tol,
        }
    }
}

/// The integration methods of the engine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Explicit Euler, order 1.
    ExplicitEuler,
    /// Semi-implicit (symplectic) Euler, order 1; mechanical systems only.
    SemiImplicitEuler,
    /// Explicit midpoint (RK2), order 2.
    Midpoint,
    /// Classical Runge–Kutta, order 4.
    Rk4,
    /// Velocity Verlet, order 2; mechanical systems only.
    VelocityVerlet,
    /// Implicit Euler with Newton iterations, order 1.
    ImplicitEuler,
    /// Adaptive Dormand–Prince 5(4); the step given to it is the largest
    /// step it may take (an output interval), its own steps are controlled.
    DormandPrince(Tolerance),
}

impl Method {
    /// Every fixed-step method, in the order reports list them.
    pub const FIXED_STEP: [Method; 6] = [
        Method::ExplicitEuler,
        Method::SemiImplicitEuler,
        Method::Midpoint,
        Method::Rk4,
        Method::VelocityVerlet,
        Method::ImplicitEuler,
    ];

    /// Short stable identifier used in reports and snapshots.
    pub fn id(&self) -> &'static str {
        match self {
            Method::ExplicitEuler => "explicit_euler",
            Method::SemiImplicitEuler => "semi_implicit_euler",
            Method::Midpoint => "rk2_midpoint",
            Method::Rk4 => "rk4",
            Method::VelocityVerlet => "velocity_verlet",
            Method::ImplicitEuler => "implicit_euler",
            Method::DormandPrince(_) => "dormand_prince",
        }
    }

    /// Parses an identifier of [`Method::id`]; Dormand–Prince gets `tol`.
    /// `"midpoint"`, the variant's own name, is accepted for
    /// `"rk2_midpoint"`.
    pub fn from_id(id: &str, tol: Tolerance) -> Option<Method> {
        let id = if id == "midpoint" { "rk2_midpoint" } else { id };
        let all = Method::FIXED_STEP
            .into_iter()
            .chain([Method::DormandPrince(tol)]);
        all.into_iter().find(|m| m.id() == id)
    }

    /// Nominal order of global convergence.
    pub fn order(&self) -> u32 {
        match self {
            Method::ExplicitEuler | Method::SemiImplicitEuler | Method::ImplicitEuler => 1,
            Method::Midpoint | Method::VelocityVerlet => 2,
            Method::Rk4 => 4,
            Method::DormandPrince(_) => 5,
        }
    }

    /// Whether the method only applies to a `[q, v]` mechanical state.
    pub fn needs_second_order(&self) -> bool {
        matches!(self, Method::SemiImplicitEuler | Method::VelocityVerlet)
    }

    /// Whether the method chooses its own step.
    pub fn is_adaptive(&self) -> bool {
        matches!(self, Method::DormandPrince(_))
    }
}

/// Work counters: machine-independent measures of cost.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Stats {
    /// Evaluations of the right-hand side `f(t, y)`.
    pub evaluations: u64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected attempts (adaptive method only).
    pub rejected: u64,
}

/// Stage buffers shared by the methods, sized once for the system.
#[derive(Debug, Clone, Default)]
pub(crate) struct Workspace {
    /// Seven stage vectors (Dormand–Prince needs seven, RK4 four).
    pub(crate) k: [Vec<f64>; 7],
    /// A scratch state.
    pub(crate) tmp: Vec<f64>,
    /// Evaluations since creation.
    pub(crate) evaluations: u64,
}

impl Workspace {
    fn resize(&mut self, n: usize) {
        for k in &mut self.k {
            k.resize(n, 0.0);
        }
        self.tmp.resize(n, 0.0);
    }
}

/// An integrator: a [`Method`] with its buffers, its step-size controller
/// (adaptive method) and its work counters.
#[derive(Debug, Clone)]
pub struct Integrator {
    method: Method,
    ws: Workspace,
    steps: u64,
    rejected: u64,
    controller: StepController,
    /// Next step the adaptive method will try, in s.
    next_h: Option<f64>,
    /// `(t, y)` whose derivative sits in `ws.k[0]` (first same as last).
    fsal: Option<(f64, Vec<f64>)>,
    out: Vec<f64>,
}

impl Integrator {
    /// A new integrator for `method`. Tolerances of an adaptive method must be
    /// finite and > 0.
    pub fn new(method: Method) -> Result<Self> {
        if let Method::DormandPrince(tol) = method {
            crate::error::require_positive("relative tolerance", tol.rtol)?;
            crate::error::require_positive("absolute tolerance", tol.atol)?;
        }
        Ok(Self {
            method,
            ws: Workspace::default(),
            steps: 0,
            rejected: 0,
            controller: StepController::default(),
            next_h: None,
            fsal: None,
            out: Vec::new(),
        })
    }

    /// The method.
    pub fn method(&self) -> Method {
        self.method
    }

    /// Work done so far.
    pub fn stats(&self) -> Stats {
        Stats {
            evaluations: self.ws.evaluations,
            steps: self.steps,
            rejected: self.rejected,
        }
    }

    fn check_structure<S: OdeSystem + ?Sized>(&self, sys: &S) -> Result<usize> {
        match (sys.structure(), self.method.needs_second_order()) {
            (Structure::SecondOrder { positions }, _) => Ok(positions),
            (Structure::FirstOrder, false) => Ok(0),
            (Structure::FirstOrder, true) => Err(EngineError::MethodNeedsSecondOrder {
                method: self.method.id(),
            }),
        }
    }

    /// Forgets the cached derivative of the last step (first same as last).
    /// Call it whenever the right-hand side changes between steps (a force
    /// switched on or off, a collision changed velocities), so no stage is
    /// computed with the old one.
    pub fn invalidate_cache(&mut self) {
        self.fsal = None;
    }

    /// Exactly one step of size `h` from `(t, y)` into `out`, without error
    /// control (for the adaptive method: one Dormand–Prince step). Used to
    /// locate events inside a step by root finding on `h`.
    pub fn single_step<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h: f64,
        out: &mut [f64],
    ) -> Result<()> {
        let n = self.check_structure(sys)?;
        self.ws.resize(y.len());
        let ws = &mut self.ws;
        match self.method {
            Method::ExplicitEuler => explicit_euler::step(sys, t, y, h, ws, out),
            Method::SemiImplicitEuler => semi_implicit_euler::step(sys, n, t, y, h, ws, out),
            Method::Midpoint => midpoint::step(sys, t, y, h, ws, out),
            Method::Rk4 => rk4::step(sys, t, y, h, ws, out),
            Method::VelocityVerlet => velocity_verlet::step(sys, n, t, y, h, ws, out),
            Method::ImplicitEuler => implicit_euler::step(sys, t, y, h, ws, out)?,
            Method::DormandPrince(tol) => {
                self.load_fsal(sys, t, y);
                dormand_prince::attempt(sys, t, y, h, tol, &mut self.ws, out);
                // The stages now describe (t + h, out), not a state we keep.
                self.fsal = None;
            }
        }
        Ok(())
    }

    /// Puts `f(t, y)` in `ws.k[0]`, reusing the last step's final stage when
    /// it was computed at this very `(t, y)`.
    fn load_fsal<S: OdeSystem + ?Sized>(&mut self, sys: &mut S, t: f64, y: &[f64]) {
        let cached = matches!(&self.fsal, Some((tf, yf)) if *tf == t && yf.as_slice() == y);
        if !cached {
            sys.derivative(t, y, &mut self.ws.k[0]);
            self.ws.evaluations += 1;
        }
    }

    /// Advances `y` in place from `t` by one accepted step of size at most
    /// `h_max` and returns the step taken. Fixed-step methods take exactly
    /// `h_max`; the adaptive method takes the step its controller allows
    /// (never more than `h_max`), rejecting and retrying as needed.
    ///
    /// A non-finite result is reported as [`EngineError::BlowUp`].
    pub fn advance<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &mut [f64],
        h_max: f64,
    ) -> Result<f64> {
        crate::error::require_positive("step", h_max)?;
        let mut out = std::mem::take(&mut self.out);
        out.resize(y.len(), 0.0);
        let result = match self.method {
            Method::DormandPrince(tol) => self.adaptive_step(sys, t, y, h_max, tol, &mut out),
            _ => self.single_step(sys, t, y, h_max, &mut out).map(|()| h_max),
        };
        let outcome = result.and_then(|h| {
            if out.iter().all(|v| v.is_finite()) {
                y.copy_from_slice(&out);
                self.steps += 1;
                Ok(h)
            } else {
                Err(EngineError::BlowUp {
                    t,
                    step: self.steps,
                    reason: "non-finite state".into(),
                })
            }
        });
        self.out = out;
        outcome
    }

    fn adaptive_step<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h_max: f64,
        tol: Tolerance,
        out: &mut [f64],
    ) -> Result<f64> {
        self.ws.resize(y.len());
        self.load_fsal(sys, t, y);
        let mut h = match self.next_h {
            Some(h) => h,
            None => dormand_prince::initial_step(sys, t, y, h_max, tol, &mut self.ws),
        };
        loop {
            let clipped = h >= h_max;
            let h_try = h.min(h_max);
            if h_try <= 16.0 * f64::EPSILON * t.abs().max(h_max) {
                return Err(EngineError::StepSizeUnderflow { t, h: h_try });
            }
            let err = dormand_prince::attempt(sys, t, y, h_try, tol, &mut self.ws, out);
            let (accepted, h_next) = self.controller.judge(h_try, err);
            if accepted {
                // A step clipped to reach an output time says nothing about
                // the step the controller would like: keep the larger one.
                self.next_h = Some(if clipped { h_next.max(h) } else { h_next });
                self.ws.k.swap(0, 6);
                self.fsal = Some((t + h_try, out.to_vec()));
                return Ok(h_try);
            }
            self.rejected += 1;
            h = h_next;
        }
    }
}

/// A sampled solution of a plain ODE.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Solution {
    /// Times, in the units of the system.
    pub t: Vec<f64>,
    /// States at those times.
    pub y: Vec<Vec<f64>>,
    /// Work done.
    pub stats: Stats,
}

/// Integrates `sys` from `(t0, y0)` over `steps` steps of size `h` (times
/// `t0 + i h`, not an accumulated `t += h`), recording every step. With the
/// adaptive method, `h` is the output interval.
///
/// A blow-up (non-finite state) is an error naming the time and the step; a
/// finite but huge state is returned as it is, for the caller to judge.
pub fn integrate_fixed<S: OdeSystem + ?Sized>(
    sys: &mut S,
    method: Method,
    t0: f64,
    y0: &[f64],
    h: f64,
    steps: usize,
) -> Result<Solution> {
    crate::error::require_positive("step", h)?;
    integrate_grid(sys, method, t0, y0, t0 + steps as f64 * h, h, steps as u64)
}

/// Integrates `sys` from `(t0, y0)` to `t_end` in steps of `dt` on the grid
/// of [`crate::time_grid`] (the last step shortened when `dt` does not divide
/// the span), recording every step.
pub fn integrate_to<S: OdeSystem + ?Sized>(
    sys: &mut S,
    method: Method,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    dt: f64,
) -> Result<Solution> {
    let steps = crate::time_grid::step_count(t_end - t0, dt)?;
    integrate_grid(sys, method, t0, y0, t_end, dt, steps)
}

fn integrate_grid<S: OdeSystem + ?Sized>(
    sys: &mut S,
    method: Method,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    h: f64,
    steps: u64,
) -> Result<Solution> {
    let mut integrator = Integrator::new(method)?;
    let mut y = y0.to_vec();
    let mut solution = Solution {
        t: vec![t0],
        y: vec![y.clone()],
        stats: Stats::default(),
    };
    let mut t = t0;
    for i in 1..=steps {
        let t_next = crate::time_grid::grid_time(t0, t_end, h, i, steps);
        while t < t_next {
            let taken = integrator.advance(sys, t, &mut y, t_next - t)?;
            // A step that used all the room left lands exactly on t_next.
            t = if taken == t_next - t {
                t_next
            } else {
                t + taken
            };
        }
        solution.t.push(t_next);
        solution.y.push(y.clone());
    }
    solution.stats = integrator.stats();
    Ok(solution)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn midpoint_is_accepted_for_rk2_midpoint() {
        let tol = Tolerance::uniform(1e-9);
        assert_eq!(Method::from_id("midpoint", tol), Some(Method::Midpoint));
        assert_eq!(Method::from_id("rk2_midpoint", tol), Some(Method::Midpoint));
        assert_eq!(Method::from_id("rk5", tol), None);
    }
}
