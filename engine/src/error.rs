//! Typed errors of the engine. Every error names what is wrong and carries
//! the numbers needed to find it (the habit of `ode_solvers`:
//! `StepSizeUnderflow { t }`).

use thiserror::Error;

/// Everything the engine can refuse or report instead of silently producing
/// garbage.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum EngineError {
    /// A user-supplied number is out of its domain (mass ≤ 0, dt ≤ 0, NaN, ...).
    #[error("invalid {what}: {} ({reason})", readable(*.value))]
    InvalidParameter {
        /// Which parameter, e.g. `"mass of body 'box'"`.
        what: String,
        /// The offending value.
        value: f64,
        /// Why it is refused, e.g. `"must be finite and > 0"`.
        reason: &'static str,
    },
    /// A polygon is not convex or not counter-clockwise, or is degenerate.
    #[error("invalid polygon: {reason} at vertex {vertex}")]
    InvalidPolygon {
        /// Index of the first offending vertex.
        vertex: usize,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A chain with too few points, a non-finite point, or two consecutive
    /// points closer than the linear slop (5 mm).
    #[error("invalid chain: {reason} at point {point}")]
    InvalidChain {
        /// Index of the first offending point.
        point: usize,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// An outline that is not a simple counter-clockwise polygon, given
    /// to [`crate::Shape::simple_polygon`] or
    /// [`crate::shape::decompose::convex_parts`].
    #[error("invalid polygon outline: {0}")]
    InvalidOutline(#[from] crate::shape::decompose::OutlineError),
    /// A force or event refers to a body that is not in the world.
    #[error("unknown body index {index} (the world has {count} bodies)")]
    UnknownBody {
        /// The index that was asked for.
        index: usize,
        /// How many bodies the world holds.
        count: usize,
    },
    /// A joint definition the engine cannot build: a body missing or given
    /// twice, no dynamic body, a parameter out of its domain, limits out
    /// of order, a zero axis, ...
    #[error("joint '{joint}': {reason}")]
    InvalidJoint {
        /// Name of the joint.
        joint: String,
        /// What is wrong, with the numbers.
        reason: String,
    },
    /// A joint id that is not in the world.
    #[error("unknown joint index {index} (the world has {count} joints)")]
    UnknownJoint {
        /// The index that was asked for.
        index: usize,
        /// How many joints the world holds.
        count: usize,
    },
    /// A force was asked to act on a static body where that makes no sense
    /// (e.g. a spring between two static bodies).
    #[error("force '{force}' acts on no dynamic body")]
    ForceOnStaticBodies {
        /// Name of the force.
        force: String,
    },
    /// The method needs the state in mechanical form `[q, v]` with `q' = v`
    /// (semi-implicit Euler, velocity Verlet) and the system is first order.
    #[error("{method} needs a second-order (position, velocity) system")]
    MethodNeedsSecondOrder {
        /// Name of the method.
        method: &'static str,
    },
    /// The state stopped being finite: the integration blew up.
    #[error("blow-up at t = {} s (step {step}): {reason}", readable(*.t))]
    BlowUp {
        /// Time at the start of the step that produced it, in s.
        t: f64,
        /// Index of that step (0-based).
        step: u64,
        /// What was detected, e.g. `"non-finite state"`.
        reason: String,
    },
    /// The adaptive controller needed a step smaller than round-off allows.
    #[error("step size underflow at t = {} s (h = {} s)", readable(*.t), readable(*.h))]
    StepSizeUnderflow {
        /// Time at which the step could not be taken, in s.
        t: f64,
        /// The rejected step, in s.
        h: f64,
    },
    /// Newton's iterations of the implicit method did not converge.
    #[error(
        "implicit solver did not converge at t = {} s after {iterations} iterations (residual {})",
        readable(*.t),
        readable(*.residual)
    )]
    NewtonDiverged {
        /// Time at the start of the step, in s.
        t: f64,
        /// Iterations spent.
        iterations: usize,
        /// Last residual norm.
        residual: f64,
    },
    /// Contact handling could not go on: a time-of-impact search did not
    /// converge, or a step needed more contact events than allowed.
    #[error("contact handling failed at t = {} s: {reason}", readable(*.t))]
    Contact {
        /// Time at the start of the step (or piece of step), in s.
        t: f64,
        /// What went wrong, with its numbers.
        reason: String,
    },
    /// The world's contact model cannot do what was asked (a kinematic
    /// body under the exact model, an integrator the soft step does not
    /// use, a joint under the exact model, ...).
    #[error("{what} is not supported: {reason}")]
    Unsupported {
        /// What was asked, e.g. `"kinematic body 'paddle'"`.
        what: String,
        /// Why, and what to use instead.
        reason: &'static str,
    },
    /// A body that was removed from the world ([`crate::World::remove_body`])
    /// was asked to change.
    #[error("body {index} ('{name}') was removed from the world")]
    RemovedBody {
        /// Its id.
        index: usize,
        /// Its name.
        name: String,
    },
    /// A force id that is not in the world (never returned by it, or
    /// already removed).
    #[error("unknown force id {id} (never added to this world, or already removed)")]
    UnknownForce {
        /// The id's number.
        id: u64,
    },
    /// A world that cannot be written as bytes: it holds a force of the
    /// program's own type, which the engine cannot serialize (clone the
    /// world in memory instead, or rebuild that force after restoring).
    #[error("the world cannot be serialized: {what}")]
    NotSerializable {
        /// What stands in the way, e.g. `"user force 'wind' (not one of
        /// the engine's forces)"`.
        what: String,
    },
    /// The Jacobian of the implicit step is singular.
    #[error("singular Newton matrix at t = {} s", readable(*.t))]
    SingularJacobian {
        /// Time at the start of the step, in s.
        t: f64,
    },
}

/// A number for messages: Rust's shortest digits that read back exactly,
/// switched to scientific notation when the magnitude is at least 1e16 or
/// below 1e-4 (`-1e308`, `1e-320`, `2.5e-7`), so that no message prints
/// hundreds of digits. Zero, infinities and NaN print as Rust prints them.
pub fn readable(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || !value.is_finite() || (1e-4..1e16).contains(&magnitude) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

/// A computed quantity for messages where its exact digits are noise (the
/// kinetic energy and speed of the body a blow-up names): four significant
/// digits, in scientific notation outside [1e-4, 1e4), trailing zeros
/// dropped (`1.798e308`, `1.414e149`, `12.35`, `0.5`), where [`readable`]'s
/// exact digits would be noise. Zero, infinities and NaN print as Rust
/// prints them.
pub fn approximate(value: f64) -> String {
    fn trim(digits: &str) -> &str {
        if digits.contains('.') {
            digits.trim_end_matches('0').trim_end_matches('.')
        } else {
            digits
        }
    }
    let magnitude = value.abs();
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    if (1e-4..1e4).contains(&magnitude) {
        let decimals = (3 - magnitude.log10().floor() as i32).max(0) as usize;
        trim(&format!("{value:.decimals$}")).to_owned()
    } else {
        let text = format!("{value:.3e}");
        match text.split_once('e') {
            Some((mantissa, exponent)) => format!("{}e{exponent}", trim(mantissa)),
            None => text,
        }
    }
}

/// Short alias used across the engine.
pub type Result<T, E = EngineError> = std::result::Result<T, E>;

/// Checks that `value` is finite and strictly positive.
pub(crate) fn require_positive(what: impl Into<String>, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(EngineError::InvalidParameter {
            what: what.into(),
            value,
            reason: "must be finite and > 0",
        })
    }
}

/// Checks that `value` is finite and ≥ 0.
pub(crate) fn require_non_negative(what: impl Into<String>, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(EngineError::InvalidParameter {
            what: what.into(),
            value,
            reason: "must be finite and >= 0",
        })
    }
}

/// Checks that `value` is in [0, 1] (a restitution coefficient).
pub(crate) fn require_unit_interval(what: impl Into<String>, value: f64) -> Result<f64> {
    if (0.0..=1.0).contains(&value) {
        Ok(value)
    } else {
        Err(EngineError::InvalidParameter {
            what: what.into(),
            value,
            reason: "must be in [0, 1]",
        })
    }
}

/// Checks that `value` is finite.
pub(crate) fn require_finite(what: impl Into<String>, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(EngineError::InvalidParameter {
            what: what.into(),
            value,
            reason: "must be finite",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn readable_numbers_are_short_and_exact() {
        assert_eq!(readable(-1e308), "-1e308");
        assert_eq!(readable(-1e-320), "-1e-320");
        assert_eq!(readable(0.25), "0.25");
        assert_eq!(readable(-20.0), "-20");
        assert_eq!(readable(1e16), "1e16");
        assert_eq!(readable(2.5e-7), "2.5e-7");
        assert_eq!(readable(f64::INFINITY), "inf");
        for v in [1.2345678901234567e300, 3e-310, 0.1, 123456.789] {
            assert_eq!(readable(v).parse::<f64>(), Ok(v));
        }
        assert_eq!(approximate(f64::MAX), "1.798e308");
        assert_eq!(approximate(1.4142135623730949e149), "1.414e149");
        assert_eq!(approximate(12.3456), "12.35");
        assert_eq!(approximate(0.5), "0.5");
        assert_eq!(approximate(-2.5e-7), "-2.5e-7");
        assert_eq!(approximate(f64::INFINITY), "inf");
        let e = require_positive("mass", -1e308).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid mass: -1e308 (must be finite and > 0)"
        );
    }
}
