//! Contact materials per shape and the rules that mix two of them.
//!
//! Every shape of the soft step carries a friction coefficient, a
//! restitution, a rolling resistance and a tangent speed. They come, most
//! specific first, from the compound part ([`ShapeOverrides`] on a
//! [`crate::CompoundPart`]), the body ([`crate::BodyDef`]) and the world's
//! defaults ([`crate::SoftStepSettings`], a scene's `[contact]`). A touching
//! pair combines its two shapes' values:
//!
//! - friction and restitution by the settings' [`MixingRule`]s (Box2D's
//!   defaults: the geometric mean √(μa μb) for friction, the larger of the
//!   two for restitution);
//! - rolling resistance as Box2D v3: the larger coefficient times the
//!   larger rounding radius of the two shapes (a circle's radius; a
//!   polygon's is 0, so a box never resists rolling);
//! - tangent speed as Box2D v3: the sum of the two shapes' (a conveyor
//!   belt: the surface of its shape moves at that speed along the contact
//!   tangent, and friction drives what rests on it toward that speed).

use crate::error::{EngineError, Result, require_finite, require_non_negative};
use crate::filter::Filter;

/// How a pair combines two shapes' friction or restitution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum MixingRule {
    /// √(a b) (Box2D's friction rule).
    #[default]
    GeometricMean,
    /// max(a, b) (Box2D's restitution rule).
    Max,
    /// min(a, b).
    Min,
    /// (a + b) / 2.
    Average,
    /// a b.
    Product,
}

impl MixingRule {
    /// The pair's value from the two shapes' `a` and `b`.
    #[inline]
    pub fn mix(self, a: f64, b: f64) -> f64 {
        match self {
            MixingRule::GeometricMean => (a * b).sqrt(),
            MixingRule::Max => a.max(b),
            MixingRule::Min => a.min(b),
            MixingRule::Average => 0.5 * (a + b),
            MixingRule::Product => a * b,
        }
    }

    /// The rule named `name` (`"geometric_mean"`, `"max"`, `"min"`,
    /// `"average"`, `"product"`), for scene files.
    pub fn from_name(name: &str) -> Option<Self> {
        Some(match name {
            "geometric_mean" => MixingRule::GeometricMean,
            "max" => MixingRule::Max,
            "min" => MixingRule::Min,
            "average" => MixingRule::Average,
            "product" => MixingRule::Product,
            _ => return None,
        })
    }
}

/// What a compound part may set for itself instead of taking its body's:
/// every field `None` (the default) inherits.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ShapeOverrides {
    /// The part's collision filter ([`Filter`]).
    pub filter: Option<Filter>,
    /// Whether the part is a sensor (detects overlaps, never pushes).
    pub sensor: Option<bool>,
    /// Friction coefficient, ≥ 0.
    pub friction: Option<f64>,
    /// Restitution, in [0, 1].
    pub restitution: Option<f64>,
    /// Rolling resistance coefficient, ≥ 0 (dimensionless; see the module
    /// docs).
    pub rolling_resistance: Option<f64>,
    /// Tangent speed of the surface (m/s, finite).
    pub tangent_speed: Option<f64>,
}

impl ShapeOverrides {
    /// Checks every value given, naming `what` (e.g. "part 2 of body
    /// 'belt'") in the error.
    pub(crate) fn validate(&self, what: &str) -> Result<()> {
        validate_material(
            what,
            self.friction,
            self.restitution,
            self.rolling_resistance,
            self.tangent_speed,
        )
    }
}

/// Checks a shape's material values: friction and rolling resistance
/// finite and ≥ 0, restitution in [0, 1], tangent speed finite.
pub(crate) fn validate_material(
    what: &str,
    friction: Option<f64>,
    restitution: Option<f64>,
    rolling_resistance: Option<f64>,
    tangent_speed: Option<f64>,
) -> Result<()> {
    if let Some(mu) = friction {
        require_non_negative(format!("friction of {what}"), mu)?;
    }
    if let Some(e) = restitution {
        crate::error::require_unit_interval(format!("restitution of {what}"), e)?;
    }
    if let Some(r) = rolling_resistance {
        require_non_negative(format!("rolling resistance of {what}"), r)?;
    }
    if let Some(u) = tangent_speed {
        require_finite(format!("tangent speed of {what}"), u)?;
    }
    Ok(())
}

/// Refuses a filter whose category is empty (it could never collide with
/// anything, which is never what was meant).
pub(crate) fn validate_filter(what: &str, filter: &Filter) -> Result<()> {
    if filter.category == 0 {
        return Err(EngineError::InvalidParameter {
            what: format!("filter category of {what}"),
            value: 0.0,
            reason: "a shape must belong to at least one category (bit)",
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rules_mix_as_named() {
        let (a, b) = (0.25, 0.64);
        // Each result is within one or two roundings of the exact value.
        let close = |x: f64, y: f64| (x - y).abs() < 4.0 * f64::EPSILON;
        assert!(close(MixingRule::GeometricMean.mix(a, b), 0.4));
        assert_eq!(MixingRule::Max.mix(a, b), 0.64);
        assert_eq!(MixingRule::Min.mix(a, b), 0.25);
        assert!(close(MixingRule::Average.mix(a, b), 0.445));
        assert!(close(MixingRule::Product.mix(a, b), 0.16));
        for name in ["geometric_mean", "max", "min", "average", "product"] {
            assert!(MixingRule::from_name(name).is_some());
        }
        assert_eq!(MixingRule::from_name("mean"), None);
    }

    #[test]
    fn bad_materials_are_refused_by_name() {
        let bad = ShapeOverrides {
            rolling_resistance: Some(-1.0),
            ..ShapeOverrides::default()
        };
        let e = bad.validate("part 0 of body 'b'").unwrap_err().to_string();
        assert!(
            e.contains("rolling resistance of part 0 of body 'b'"),
            "{e}"
        );
        let nan = ShapeOverrides {
            tangent_speed: Some(f64::NAN),
            ..ShapeOverrides::default()
        };
        assert!(nan.validate("x").is_err());
        assert!(ShapeOverrides::default().validate("x").is_ok());
    }
}
