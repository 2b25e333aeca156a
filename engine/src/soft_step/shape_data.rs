//! What the soft step keeps per collider besides its geometry: the
//! collision filter, the sensor flag and the resolved material, kept in an
//! array beside the colliders (the bounding-box update reads only the
//! geometry) and read when a pair is created and when its manifold is
//! computed.

use super::settings::SoftStepSettings;
use crate::body::Body;
use crate::filter::Filter;
use crate::material::ShapeOverrides;
use crate::shape::Shape;

/// A collider's filter, sensor flag and material.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ShapeData {
    /// Its part index in its body (0 for a body with one shape).
    pub part: usize,
    pub filter: Filter,
    pub sensor: bool,
    /// What the part sets itself (kept to re-resolve the material when the
    /// settings change).
    overrides: ShapeOverrides,
    /// Friction coefficient, restitution, rolling resistance coefficient
    /// (dimensionless) and tangent speed (m/s), resolved.
    pub friction: f64,
    pub restitution: f64,
    pub rolling_resistance: f64,
    pub tangent_speed: f64,
    /// Its rounding radius for rolling resistance (m):
    /// [`Shape::rounding_radius`] (a circle's or capsule's radius, 0 for a
    /// polygon; Box2D's `b2GetShapeRadius`).
    pub radius: f64,
}

impl ShapeData {
    /// The data of every piece of `body`'s shape, in collider order.
    pub(crate) fn of(body: &Body, settings: &SoftStepSettings) -> Vec<ShapeData> {
        let Some(shape) = &body.shape else {
            return Vec::new();
        };
        let parts: Vec<(ShapeOverrides, f64)> = match shape {
            Shape::Compound(c) => c
                .parts()
                .iter()
                .map(|p| (p.overrides, p.shape.rounding_radius()))
                .collect(),
            // One collider per segment (`geometry.rs`), each with the body's
            // filter and material.
            Shape::Chain(c) => vec![(ShapeOverrides::default(), 0.0); c.segments().len()],
            other => vec![(ShapeOverrides::default(), other.rounding_radius())],
        };
        parts
            .into_iter()
            .enumerate()
            .map(|(part, (overrides, radius))| {
                let mut data = ShapeData {
                    part,
                    filter: overrides.filter.unwrap_or(body.filter),
                    sensor: overrides.sensor.unwrap_or(body.sensor),
                    overrides,
                    friction: 0.0,
                    restitution: 0.0,
                    rolling_resistance: 0.0,
                    tangent_speed: 0.0,
                    radius,
                };
                data.resolve(body, settings);
                data
            })
            .collect()
    }

    /// The material from the part, else the body, else the settings.
    pub(crate) fn resolve(&mut self, body: &Body, settings: &SoftStepSettings) {
        let o = &self.overrides;
        self.friction = o.friction.or(body.friction).unwrap_or(settings.friction);
        self.restitution = o
            .restitution
            .or(body.restitution)
            .unwrap_or(settings.restitution);
        self.rolling_resistance = o
            .rolling_resistance
            .or(body.rolling_resistance)
            .unwrap_or(settings.rolling_resistance);
        self.tangent_speed = o.tangent_speed.or(body.tangent_speed).unwrap_or(0.0);
    }
}

/// A pair's material, mixed from its two shapes' (see [`crate::material`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PairMaterial {
    pub friction: f64,
    pub restitution: f64,
    /// Rolling resistance (m: coefficient × radius).
    pub rolling_resistance: f64,
    pub tangent_speed: f64,
}

impl PairMaterial {
    /// Mixes `a`'s and `b`'s materials by the settings' rules.
    #[inline]
    pub(crate) fn mix(a: &ShapeData, b: &ShapeData, settings: &SoftStepSettings) -> Self {
        let rolling_resistance = if a.rolling_resistance > 0.0 || b.rolling_resistance > 0.0 {
            a.rolling_resistance.max(b.rolling_resistance) * a.radius.max(b.radius)
        } else {
            0.0
        };
        PairMaterial {
            friction: settings.friction_mixing.mix(a.friction, b.friction),
            restitution: settings
                .restitution_mixing
                .mix(a.restitution, b.restitution),
            rolling_resistance,
            tangent_speed: a.tangent_speed + b.tangent_speed,
        }
    }
}
