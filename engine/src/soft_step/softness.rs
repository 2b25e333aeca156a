//! Soft constraints: the coefficients that turn a rigid constraint into an
//! implicit spring-damper (Catto's "Solver2D" study, after Bepu; Box2D v3's
//! `b2Softness`).
//!
//! A constraint C (here a contact's separation) with a spring of stiffness
//! k and damping c, integrated implicitly over a substep h, gives the
//! impulse increment
//!
//! Δλ = −m_eff · mass_scale · (v + bias_rate · C) − impulse_scale · λ,
//!
//! with λ the impulse accumulated so far in the step and m_eff the
//! constraint's effective mass. Written with the mass-independent natural
//! frequency ω = 2πf and damping ratio ζ instead of k and c:
//!
//! a1 = 2ζ + hω,  a2 = hω·a1,  a3 = 1/(1 + a2),
//! bias_rate = ω/a1,  mass_scale = a2·a3,  impulse_scale = a3.
//!
//! As f → ∞ the constraint becomes rigid (mass_scale → 1, impulse_scale →
//! 0, bias_rate → 1/h). The same coefficients serve every soft constraint
//! (contacts now, joints later).

/// The three coefficients of a soft constraint for one substep length.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Softness {
    /// Fraction of the constraint error removed per unit time (1/s).
    pub bias_rate: f64,
    /// Scale of the effective mass (dimensionless, in [0, 1]).
    pub mass_scale: f64,
    /// Fraction of the accumulated impulse bled off per solve
    /// (dimensionless, in [0, 1]).
    pub impulse_scale: f64,
}

impl Softness {
    /// A rigid constraint: no softness, no bias.
    pub const RIGID: Softness = Softness {
        bias_rate: 0.0,
        mass_scale: 1.0,
        impulse_scale: 0.0,
    };

    /// The coefficients of a spring of natural frequency `hertz` (Hz) and
    /// damping ratio `zeta` over a substep of `h` (s). `hertz = 0` gives a
    /// constraint that does nothing (no bias, no mass).
    pub fn new(hertz: f64, zeta: f64, h: f64) -> Self {
        if hertz == 0.0 {
            return Softness {
                bias_rate: 0.0,
                mass_scale: 0.0,
                impulse_scale: 0.0,
            };
        }
        let omega = 2.0 * std::f64::consts::PI * hertz;
        let a1 = 2.0 * zeta + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Softness {
            bias_rate: omega / a1,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stiff_limit_is_rigid() {
        // f → ∞: mass_scale → 1, impulse_scale → 0, bias_rate → 1/h.
        let h = 1.0 / 240.0;
        let s = Softness::new(1e9, 1.0, h);
        assert!((s.mass_scale - 1.0).abs() < 1e-6);
        assert!(s.impulse_scale < 1e-6);
        assert!((s.bias_rate * h - 1.0).abs() < 1e-6);
    }

    #[test]
    fn coefficients_match_the_implicit_spring_damper() {
        // The implicit Euler step of m x'' = −k x − c x' over h, solved for
        // the impulse that the constraint form gives, with k = m ω², c = 2 m ζ ω:
        // v' = (v − h ω² x) / (1 + 2ζωh + h²ω²). Check that
        // Δv = −mass_scale·(v + bias_rate·x) (unit mass, λ = 0) is the same.
        let (f, zeta, h) = (30.0, 10.0, 1.0 / 240.0);
        let w = 2.0 * std::f64::consts::PI * f;
        let s = Softness::new(f, zeta, h);
        let (x, v) = (-0.01, 0.3);
        let implicit = (v - h * w * w * x) / (1.0 + 2.0 * zeta * w * h + h * h * w * w);
        let soft = v - s.mass_scale * (v + s.bias_rate * x);
        // Both are exact algebra on the same model: agree to round-off.
        assert!((implicit - soft).abs() < 1e-14, "{implicit} vs {soft}");
    }
}
