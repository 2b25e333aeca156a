//! Where each method fails: the largest stable step, found by bisection on
//! h with the engine's blow-up detection, on the two axes of docs/cases.md's
//! table — the oscillator (imaginary axis, hω) and Hoffman's stiff test
//! (real axis, hλ).
//!
//! - Oscillator: the seed spring world with an energy bound of
//!   [`ENERGY_BOUND`] × E0. A run is unstable when the engine reports
//!   [`engine::EngineError::BlowUp`] (strong instability: the bound is far
//!   above the largest bounded energy a symplectic method reaches 1 %
//!   inside its limit, E0/(1 − hω/2) = 200 E0 at hω = 1.99), or when its
//!   energy keeps growing from one half of the run to the next by more than
//!   [`GROWTH_THRESHOLD`] per step (weak instability: Dormand–Prince just
//!   past hω = 0.997 grows by 1e-6 per step, which no bound would catch in
//!   a few thousand steps).
//! - Hoffman: the error after [`HOFFMAN_STEPS`] steps; unstable when it has
//!   grown past its start (|e| > 1, e0 = −1).
//!
//! Dormand–Prince is adaptive; its stability region is measured on its
//! fixed-step fifth-order formula ([`engine::Integrator::single_step`]).

use crate::row::{Comparison, Row, RowKind};
use crate::scenes;
use anyhow::{Context, Result};
use engine::{EngineError, FnSystem, Integrator, Method, Tolerance};
use references::{Hoffman, SpringOscillator};

/// Energy bound of the oscillator runs, in units of E0.
pub const ENERGY_BOUND: f64 = 1e6;
/// Steps per half of an oscillator run.
pub const OSCILLATOR_STEPS: u64 = 4000;
/// Amplitude growth per step above which an oscillator run counts as
/// unstable: 1e-7 per step is a rise of ~1e-3 in the maximum energy from
/// one half of the run to the next. A bounded oscillation's windowed
/// maximum jitters by ~1e-6 (sampling of its phase), and 1 % past the
/// weakest limit (Dormand–Prince on the imaginary axis) the growth is
/// ~5e-6 per step: the threshold sits between them.
pub const GROWTH_THRESHOLD: f64 = 1e-7;
/// Steps per Hoffman run.
pub const HOFFMAN_STEPS: usize = 4000;
/// Relative width at which the bisection stops.
const BISECTION_WIDTH: f64 = 1e-6;
/// docs/cases.md: measured limits within 1 % of theory.
const LIMIT_TOLERANCE: f64 = 0.01;

/// Which test problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// The seed spring, u'' = −ω²u: hω on the imaginary axis.
    Imaginary,
    /// Hoffman's y' = λ(y − (t + 2)) + 1: hλ on the real axis.
    Real,
}

impl Axis {
    /// The axis and the unit of its limits, for tables.
    pub fn name(self) -> &'static str {
        match self {
            Axis::Imaginary => "imaginary axis, h w",
            Axis::Real => "real axis, -h lambda",
        }
    }
}

/// A DP method for the fixed-step runs (its tolerance is not used there).
fn dormand_prince() -> Method {
    Method::DormandPrince(Tolerance::uniform(1e-9))
}

/// A test problem of the stability study: a case's scene on one axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Problem<'a> {
    /// The case its rows belong to.
    pub case: &'a str,
    /// Its scene (`scenes/<scene>.toml`): the seed spring on the imaginary
    /// axis, a `[linear_test]` on the real axis.
    pub scene: &'a str,
    /// The axis.
    pub axis: Axis,
}

/// Whether `method` stays stable at step `h` (s) on scene `scene`, the
/// test problem of `axis`.
pub fn is_stable(scene: &str, method: Method, axis: Axis, h: f64) -> Result<bool> {
    match axis {
        Axis::Imaginary => oscillator_stable(scene, method, h),
        Axis::Real => linear_test_stable(scene, method, h),
    }
}

fn oscillator_stable(scene: &str, method: Method, h: f64) -> Result<bool> {
    let bound = ENERGY_BOUND;
    Ok(
        matches!(oscillator_growth(scene, method, h, bound)?, Some(g) if g <= 1.0 + GROWTH_THRESHOLD),
    )
}

/// Amplitude growth per step of `method` on the seed spring (scene
/// `scene`) at step `h`:
/// `(max E over the second half / max E over the first half)^(1/n)` over
/// 2 × [`OSCILLATOR_STEPS`] steps, square-rooted (energy is quadratic in
/// the amplitude). Symplectic methods' bounded oscillation gives 1; a
/// Runge–Kutta method gives its |R(ihω)|. `None` when the engine reported a
/// blow-up (energy past `bound` × E0, or a non-finite state).
fn oscillator_growth(scene: &str, method: Method, h: f64, bound: f64) -> Result<Option<f64>> {
    let exact = SpringOscillator::seed();
    let n = OSCILLATOR_STEPS as usize;
    let mut energies = Vec::with_capacity(2 * n);
    if method.is_adaptive() {
        // Dormand–Prince's fixed-step formula on u'' = −ω²u.
        let w2 = exact.omega() * exact.omega();
        let mut sys = FnSystem::new(2, move |_t, y: &[f64], dy: &mut [f64]| {
            dy[0] = y[1];
            dy[1] = -w2 * y[0];
        });
        let mut integrator = Integrator::new(method)?;
        let (mut y, mut next) = (vec![1.0, 0.0], vec![0.0; 2]);
        for i in 0..2 * n {
            integrator.single_step(&mut sys, i as f64 * h, &y, h, &mut next)?;
            std::mem::swap(&mut y, &mut next);
            let e = y[0] * y[0] + y[1] * y[1] / w2;
            if e.is_nan() || e > bound {
                return Ok(None);
            }
            energies.push(e);
        }
    } else {
        let mut world = scenes::world(scene, method)?;
        let limit = bound * exact.energy();
        world.set_energy_limit(limit.is_finite().then_some(limit))?;
        for i in 1..=2 * n {
            match world.step_to(i as f64 * h) {
                Ok(_) => energies.push(world.energy()),
                Err(EngineError::BlowUp { .. }) => return Ok(None),
                Err(e) => return Err(e.into()),
            }
        }
    }
    let first = energies[..n].iter().copied().fold(0.0, f64::max);
    let second = energies[n..].iter().copied().fold(0.0, f64::max);
    Ok(Some((second / first).powf(0.5 / n as f64)))
}

fn linear_test_stable(scene: &str, method: Method, h: f64) -> Result<bool> {
    // The case's own ODE (its `[linear_test]`), stepped with fixed steps
    // (Dormand–Prince included); e = y − g(t) must not grow past |e0| = 1.
    let mut sys = scenes::load(scene)?
        .linear_test()
        .with_context(|| format!("scenes/{scene}.toml must hold a [linear_test]"))?;
    let mut integrator = Integrator::new(method)?;
    let mut y = vec![sys.y0];
    let mut next = y.clone();
    for i in 0..HOFFMAN_STEPS {
        let t = i as f64 * h;
        match integrator.single_step(&mut sys, t, &y, h, &mut next) {
            Ok(()) => {}
            Err(EngineError::NewtonDiverged { .. }) => return Ok(false),
            Err(e) => return Err(e.into()),
        }
        std::mem::swap(&mut y, &mut next);
        let e = y[0] - sys.forcing(t + h);
        if e.is_nan() || e.abs() > 1.0 {
            return Ok(false);
        }
    }
    Ok(true)
}

/// The largest stable step between `lo` (stable) and `hi` (unstable),
/// found by bisection; `None` when `lo` is not stable or `hi` is.
pub fn largest_stable_step(
    scene: &str,
    method: Method,
    axis: Axis,
    lo: f64,
    hi: f64,
) -> Result<Option<f64>> {
    if !is_stable(scene, method, axis, lo)? || is_stable(scene, method, axis, hi)? {
        return Ok(None);
    }
    let (mut lo, mut hi) = (lo, hi);
    while (hi - lo) > BISECTION_WIDTH * lo {
        let mid = 0.5 * (lo + hi);
        if is_stable(scene, method, axis, mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(Some(lo))
}

/// Theory's limits (docs/cases.md), in units of hω (imaginary) or |hλ| (real);
/// `None` where theory says "none" (unstable for every h) and
/// `Some(INFINITY)` where it says "any".
pub fn theory_limit(method: Method, axis: Axis) -> Option<f64> {
    use Method::*;
    match (axis, method) {
        (Axis::Real, ExplicitEuler | Midpoint) => Some(2.0),
        (Axis::Real, Rk4) => Some(-references::hoffman::RK4_REAL_STABILITY_BOUNDARY),
        (Axis::Real, DormandPrince(_)) => Some(3.306_567_89),
        (Axis::Real, ImplicitEuler) => Some(f64::INFINITY),
        (Axis::Real, SemiImplicitEuler | VelocityVerlet) => None,
        (Axis::Imaginary, ExplicitEuler | Midpoint) => None,
        (Axis::Imaginary, Rk4) => Some(2.0 * 2f64.sqrt()),
        (Axis::Imaginary, DormandPrince(_)) => Some(0.997_189_01),
        (Axis::Imaginary, SemiImplicitEuler | VelocityVerlet) => Some(2.0),
        (Axis::Imaginary, ImplicitEuler) => Some(f64::INFINITY),
    }
}

/// The methods of the stability table, Dormand–Prince as a fixed-step formula.
pub fn methods() -> Vec<Method> {
    Method::FIXED_STEP
        .into_iter()
        .chain([dormand_prince()])
        .collect()
}

/// A measured limit.
#[derive(Debug, Clone, PartialEq)]
pub struct Limit {
    /// Method id.
    pub method: String,
    /// Which axis.
    pub axis: Axis,
    /// Measured limit in hω or |hλ| (NaN: none found).
    pub measured: f64,
    /// Theory (docs/cases.md); `None`: unstable at every step; ∞: stable at every step.
    pub theory: Option<f64>,
}

/// Measures every method's limit on each problem's axis and returns rows
/// comparing them with docs/cases.md.
pub fn measure_all(problems: &[Problem]) -> Result<(Vec<Limit>, Vec<Row>)> {
    let mut limits = Vec::new();
    let mut rows = Vec::new();
    for method in methods() {
        let (l, r) = measure_method(method, problems)?;
        limits.extend(l);
        rows.extend(r);
    }
    Ok((limits, rows))
}

/// [`measure_all`]'s limits and rows of one method (the part of the study
/// one job of a run computes: the methods are independent).
pub fn measure_method(method: Method, problems: &[Problem]) -> Result<(Vec<Limit>, Vec<Row>)> {
    let omega = SpringOscillator::seed().omega();
    let lambda = Hoffman::seed().lambda.abs();
    let mut limits = Vec::new();
    let mut rows = Vec::new();
    {
        for &Problem { case, scene, axis } in problems {
            if axis == Axis::Real && method.needs_second_order() {
                continue;
            }
            let scale = if axis == Axis::Imaginary {
                omega
            } else {
                lambda
            };
            let unit = if axis == Axis::Imaginary {
                "h w"
            } else {
                "|h lambda|"
            };
            let theory = theory_limit(method, axis);
            let mut row = |kind: RowKind,
                           check: &str,
                           value: f64,
                           expected: f64,
                           tol: f64,
                           cmp: Comparison,
                           reason: String| {
                rows.push(
                    Row::new(
                        kind,
                        case,
                        check,
                        method.id(),
                        f64::NAN,
                        value,
                        expected,
                        tol,
                        cmp,
                        reason,
                    )
                    .with_variant(axis.name()),
                );
            };
            let measured = match theory {
                Some(limit) if limit.is_finite() => {
                    let found = largest_stable_step(
                        scene,
                        method,
                        axis,
                        0.5 * limit / scale,
                        1.5 * limit / scale,
                    )?;
                    let value = found.map_or(f64::NAN, |h| h * scale);
                    row(
                        RowKind::PredictedFailure,
                        "stability_limit",
                        value,
                        limit,
                        LIMIT_TOLERANCE * limit,
                        Comparison::Within,
                        format!(
                            "largest stable {unit} by bisection (blow-up detection), docs/cases.md theory, within 1 %"
                        ),
                    );
                    value
                }
                Some(_) => {
                    // "Any step": stable far beyond every explicit limit.
                    let h = 1000.0 / scale;
                    let stable = is_stable(scene, method, axis, h)?;
                    row(
                        RowKind::Validation,
                        "stable_at_1000",
                        f64::from(u8::from(stable)),
                        1.0,
                        0.0,
                        Comparison::Within,
                        format!("theory: stable at every step; 1 when stable at {unit} = 1000"),
                    );
                    f64::INFINITY
                }
                None => {
                    // "No step": the amplitude grows at every step, even a
                    // small one; measure that growth against theory.
                    let y = 0.05;
                    let measured = oscillator_growth(scene, method, y / scale, f64::MAX)?
                        .map_or(f64::INFINITY, |g| g - 1.0);
                    let expected = references::linear_stability::oscillator_growth_per_step(
                        method,
                        y / scale,
                        omega,
                    )
                    .map_or(f64::NAN, |g| g - 1.0);
                    row(
                        RowKind::PredictedFailure,
                        "growth_per_step_at_0.05",
                        measured,
                        expected,
                        LIMIT_TOLERANCE * expected.abs(),
                        Comparison::Within,
                        format!(
                            "theory: no stable step on this axis; amplitude growth per step - 1 at {unit} = 0.05 (spectral radius of the step matrix), within 1 %"
                        ),
                    );
                    f64::NAN
                }
            };
            limits.push(Limit {
                method: method.id().into(),
                axis,
                measured,
                theory,
            });
        }
    }
    Ok((limits, rows))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rk4_is_stable_just_inside_two_root_two_and_not_just_outside() {
        // 1 % either side of hw = 2 sqrt 2 (docs/cases.md).
        let w = SpringOscillator::seed().omega();
        let limit = 2.0 * 2f64.sqrt() / w;
        assert!(is_stable("spring", Method::Rk4, Axis::Imaginary, 0.99 * limit).unwrap());
        assert!(!is_stable("spring", Method::Rk4, Axis::Imaginary, 1.01 * limit).unwrap());
    }

    #[test]
    fn verlet_is_stable_below_hw_two() {
        let w = SpringOscillator::seed().omega();
        assert!(is_stable("spring", Method::VelocityVerlet, Axis::Imaginary, 1.99 / w).unwrap());
        assert!(!is_stable("spring", Method::VelocityVerlet, Axis::Imaginary, 2.01 / w).unwrap());
    }

    #[test]
    fn explicit_euler_on_hoffman_switches_at_h_0002() {
        assert!(is_stable("hoffman", Method::ExplicitEuler, Axis::Real, 0.00198).unwrap());
        assert!(!is_stable("hoffman", Method::ExplicitEuler, Axis::Real, 0.00202).unwrap());
    }

    #[test]
    fn bisection_finds_the_euler_limit_within_one_percent() {
        let h = largest_stable_step("hoffman", Method::ExplicitEuler, Axis::Real, 0.001, 0.003)
            .unwrap()
            .unwrap();
        assert!((h * 1000.0 - 2.0).abs() < 0.02, "{h}");
    }
}
