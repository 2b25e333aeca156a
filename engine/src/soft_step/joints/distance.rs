//! The distance joint: the distance between a point of A and a point of B,
//! held rigid (a massless rod), free between limits (a rope), or sprung
//! (Box2D's `distance_joint.c`).
//!
//! With d = p_B − p_A the anchors' separation (updated from the bodies'
//! motion in each substep), ℓ = |d| its length and u = d/ℓ, every row
//! acts along u:
//!
//! J v = u·(v_B + ω_B × r_B − v_A − ω_A × r_A),
//! k = m_A + m_B + i_A (r_A × u)² + i_B (r_B × u)², effective mass 1/k,
//!
//! and an impulse λ applies −λu at A's anchor and +λu at B's. The rows,
//! by kind:
//!
//! | kind | row | C | softness |
//! |---|---|---|---|
//! | rigid | length | ℓ − L | rigid rows' (soft in solve, rigid in relax) |
//! | spring | spring | ℓ − L | the spring's f, ζ, both passes |
//! | spring, rope | lower limit | ℓ − ℓ_min ≥ 0 | speculative / rigid rows'; λ ≥ 0 |
//! | spring, rope | upper limit | ℓ_max − ℓ ≥ 0 (J v negated) | speculative / rigid rows'; λ ≥ 0 |
//!
//! A limit at ℓ_min = 0 or ℓ_max = ∞ is not solved. u and k are taken at
//! the current anchors in every row (u turns with the bodies within a
//! step); the rows do nothing while the anchors coincide (ℓ < 1e-12 m: no
//! direction).

use super::frame::{JointFrame, RowScale, cross, limit_row};
use super::{JointSpring, invalid, positive};
use crate::error::Result;
use crate::soft_step::Softness;
use crate::soft_step::bodies::SolverBody;

/// Below this length (m) the anchors have no direction: no row acts.
const MIN_LENGTH: f64 = 1e-12;

/// The parameters of a distance joint ([`super::JointDef::distance`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Distance {
    /// The length held at `length` (m, > 0); `None`: the anchors'
    /// distance when the joint is added. The default, with `None`.
    Rigid {
        /// Length (m).
        length: Option<f64>,
    },
    /// Free between `min_length` and `max_length` (m): a rope when
    /// `min_length` is 0, a strut that cannot shorten when `max_length` is
    /// infinite. 0 ≤ min ≤ max, max > 0, at least one limit.
    Rope {
        /// Shortest length (m), ≥ 0; 0 for a rope.
        min_length: f64,
        /// Longest length (m), > 0; `f64::INFINITY` for none.
        max_length: f64,
    },
    /// A spring of rest length `length` (m, > 0; `None`: the anchors'
    /// distance when added), held within [`min_length`, `max_length`] (0
    /// and ∞ for no limits).
    Spring {
        /// Rest length (m).
        length: Option<f64>,
        /// Stiffness and damping.
        spring: JointSpring,
        /// Shortest length (m), ≥ 0. 0: no lower limit.
        min_length: f64,
        /// Longest length (m), > min; `f64::INFINITY`: no upper limit.
        max_length: f64,
    },
}

impl Default for Distance {
    fn default() -> Self {
        Distance::Rigid { length: None }
    }
}

impl Distance {
    /// A rope of at most `max_length` (m).
    pub fn rope(max_length: f64) -> Self {
        Distance::Rope {
            min_length: 0.0,
            max_length,
        }
    }

    /// A spring of `hertz` (Hz) and `damping_ratio` whose rest length is
    /// the anchors' distance when added, without limits.
    pub fn spring(hertz: f64, damping_ratio: f64) -> Self {
        Distance::Spring {
            length: None,
            spring: JointSpring::new(hertz, damping_ratio),
            min_length: 0.0,
            max_length: f64::INFINITY,
        }
    }

    /// The given rest length, if any.
    pub(super) fn length(&self) -> Option<f64> {
        match *self {
            Distance::Rigid { length } | Distance::Spring { length, .. } => length,
            Distance::Rope { .. } => None,
        }
    }

    pub(super) fn check(&self, name: &str) -> Result<()> {
        if let Some(l) = self.length() {
            positive(name, "length (m)", l)?;
        }
        let limits = match *self {
            Distance::Rigid { .. } => None,
            Distance::Rope {
                min_length,
                max_length,
            } => {
                if max_length == f64::INFINITY && min_length == 0.0 {
                    return Err(invalid(
                        name,
                        "a rope with neither a shortest nor a longest length holds nothing: give max_length (or min_length)".into(),
                    ));
                }
                if max_length != f64::INFINITY {
                    positive(name, "largest length of a rope (m)", max_length)?;
                }
                Some((min_length, max_length))
            }
            Distance::Spring {
                spring,
                min_length,
                max_length,
                ..
            } => {
                spring.check(name, "spring")?;
                Some((min_length, max_length))
            }
        };
        if let Some((lo, hi)) = limits {
            if !(lo.is_finite() && lo >= 0.0) {
                return Err(invalid(
                    name,
                    format!(
                        "the shortest length must be finite and >= 0 m, got {}",
                        crate::error::readable(lo)
                    ),
                ));
            }
            if hi.is_nan() || hi <= 0.0 || hi < lo {
                return Err(invalid(
                    name,
                    format!(
                        "the longest length {} m must be > 0 and at least the shortest {} m",
                        crate::error::readable(hi),
                        crate::error::readable(lo)
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// What a distance joint solves.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum Mode {
    Rigid,
    Spring,
    Free,
}

/// A distance joint's parameters, per-step values and impulses (N·s).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct DistanceRows {
    mode: Mode,
    /// Rest or rigid length (m).
    pub length: f64,
    pub min_length: f64,
    pub max_length: f64,
    spring: Option<JointSpring>,
    spring_softness: Softness,
    pub impulse: f64,
    pub lower: f64,
    pub upper: f64,
}

impl DistanceRows {
    /// The rows of `joint` whose anchors are `measured` m apart now.
    pub(super) fn new(joint: &Distance, measured: f64) -> Self {
        let (mode, length, min_length, max_length, spring) = match *joint {
            Distance::Rigid { length } => (
                Mode::Rigid,
                length.unwrap_or(measured),
                0.0,
                f64::INFINITY,
                None,
            ),
            Distance::Rope {
                min_length,
                max_length,
            } => (Mode::Free, measured, min_length, max_length, None),
            Distance::Spring {
                length,
                spring,
                min_length,
                max_length,
            } => (
                Mode::Spring,
                length.unwrap_or(measured),
                min_length,
                max_length,
                Some(spring),
            ),
        };
        Self {
            mode,
            length,
            min_length,
            max_length,
            spring,
            spring_softness: Softness::RIGID,
            impulse: 0.0,
            lower: 0.0,
            upper: 0.0,
        }
    }

    /// Whether the length is held (a rigid rod).
    pub fn is_rigid(&self) -> bool {
        self.mode == Mode::Rigid
    }

    /// The accumulated impulse along the axis, on B (N·s).
    pub fn axial_impulse(&self) -> f64 {
        self.impulse + self.lower - self.upper
    }

    pub(super) fn prepare(&mut self, h: f64, warm: bool) {
        self.spring_softness = match self.spring {
            Some(s) => Softness::new(s.hertz, s.damping_ratio, h),
            None => Softness::RIGID,
        };
        if !warm {
            (self.impulse, self.lower, self.upper) = (0.0, 0.0, 0.0);
        }
    }

    pub(super) fn warm_start(&self, f: &JointFrame, a: &mut SolverBody, b: &mut SolverBody) {
        let anchors = f.anchors(a, b);
        let d = f.separation(a, b, anchors);
        let length = d.norm();
        if length < MIN_LENGTH {
            return;
        }
        f.apply(a, b, anchors, (self.axial_impulse() / length) * d, 0.0);
    }

    pub(super) fn solve(
        &mut self,
        f: &JointFrame,
        (a, b): (&mut SolverBody, &mut SolverBody),
        inv_h: f64,
        use_bias: bool,
    ) {
        let anchors = f.anchors(a, b);
        let d = f.separation(a, b, anchors);
        let length = d.norm();
        if length < MIN_LENGTH {
            return;
        }
        let u = d / length;
        let (cra, crb) = (cross(anchors.0, u), cross(anchors.1, u));
        let k = f.ma + f.mb + f.ia * cra * cra + f.ib * crb * crb;
        let mass = if k > 0.0 { 1.0 / k } else { 0.0 };
        let speed = |a: &SolverBody, b: &SolverBody| u.dot(&f.anchor_velocity(a, b, anchors));
        if self.mode == Mode::Rigid {
            let row = RowScale::rigid_row(&f.softness, use_bias);
            let c = if use_bias { length - self.length } else { 0.0 };
            let delta = row.increment(mass, speed(a, b), c, self.impulse);
            self.impulse += delta;
            f.apply(a, b, anchors, delta * u, 0.0);
            return;
        }
        if self.mode == Mode::Spring {
            let row = RowScale::soft(&self.spring_softness);
            let delta = row.increment(mass, speed(a, b), length - self.length, self.impulse);
            self.impulse += delta;
            f.apply(a, b, anchors, delta * u, 0.0);
        }
        let s = &f.softness;
        if self.min_length > 0.0 {
            let c = (mass, speed(a, b), length - self.min_length);
            let delta = limit_row(&mut self.lower, c, s, use_bias, inv_h);
            f.apply(a, b, anchors, delta * u, 0.0);
        }
        if self.max_length < f64::INFINITY {
            let c = (mass, -speed(a, b), self.max_length - length);
            let delta = limit_row(&mut self.upper, c, s, use_bias, inv_h);
            f.apply(a, b, anchors, -delta * u, 0.0);
        }
    }
}
