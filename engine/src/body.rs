//! Bodies (seed §4.2.1 rigid body, the seed's `GRigidBody`): particles,
//! rigid bodies and static bodies.
//!
//! A body's position is its centre of mass (m), its angle (rad) turns its
//! shape counter-clockwise, its velocity (m/s) and angular velocity (rad/s)
//! are those of the centre of mass. A body with neither a shape nor an
//! explicit inertia is a **particle**: it carries no rotational state and
//! costs no rotational work. A **static** body never moves and is not
//! integrated. A **kinematic** body moves at its prescribed velocity and
//! angular velocity whatever pushes on it (infinite mass): a conveyor, a
//! stirring paddle, a rotating container (soft-step contact model only).

use crate::error::{
    EngineError, Result, require_finite, require_non_negative, require_positive,
    require_unit_interval,
};
use crate::filter::Filter;
use crate::material::{validate_filter, validate_material};
use crate::shape::Shape;
use nalgebra::Vector2;

/// Index of a body in its [`crate::World`].
pub type BodyId = usize;

/// How a body takes part in the simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BodyKind {
    /// Moves under forces; integrated.
    #[default]
    Dynamic,
    /// Never moves; not integrated (an anchor, the ground).
    Static,
    /// Moves at its velocity and angular velocity (its initial ones, until
    /// a program sets them: [`crate::World::set_velocity`],
    /// [`crate::World::set_target_pose`]), pushed by nothing (infinite
    /// mass and inertia); pushes what it touches. Supported by the
    /// soft-step contact model.
    Kinematic,
}

/// The kinematic state of a body at one time.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodyState {
    /// Position of the centre of mass (m).
    pub position: Vector2<f64>,
    /// Orientation (rad), counter-clockwise; 0 for a particle.
    pub angle: f64,
    /// Velocity of the centre of mass (m/s).
    pub velocity: Vector2<f64>,
    /// Angular velocity (rad/s); 0 for a particle.
    pub angular_velocity: f64,
}

impl BodyState {
    /// A world-frame vector from the centre of mass to a point given in
    /// the body frame (m).
    pub fn to_world_offset(&self, local: Vector2<f64>) -> Vector2<f64> {
        let (s, c) = self.angle.sin_cos();
        Vector2::new(c * local.x - s * local.y, s * local.x + c * local.y)
    }
}

/// The description of a body, with defaults (Box2D's definition structs):
/// build one, then [`crate::World::add_body`] validates it.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyDef {
    /// Name used in errors, traces and reports.
    pub name: String,
    /// Dynamic (default) or static.
    pub kind: BodyKind,
    /// Mass (kg). Required for a dynamic body unless `density` and a shape
    /// give it.
    pub mass: Option<f64>,
    /// Density (kg/m²), used with the shape's area when `mass` is absent.
    pub density: Option<f64>,
    /// Moment of inertia about the centre of mass (kg·m²). Defaults to the
    /// shape's; a body with neither is a particle.
    pub inertia: Option<f64>,
    /// Geometry, re-centred on its centroid. Optional.
    pub shape: Option<Shape>,
    /// Initial state. Default: at rest at the origin.
    pub state: BodyState,
    /// Coulomb friction coefficient of this body's shape, ≥ 0. Default:
    /// the world's contact settings. A pair combines its two values by the
    /// contact model's mixing rule (geometric mean under the soft step).
    pub friction: Option<f64>,
    /// Coefficient of restitution of this body's shape, in [0, 1].
    /// Default: the world's contact settings. A pair takes the larger of
    /// its two values under the soft step.
    pub restitution: Option<f64>,
    /// Collision filter of this body's shapes (Box2D's category, mask and
    /// group: [`Filter`]); a compound part may override it. Default: collides
    /// with everything. Soft-step contact model only.
    pub filter: Filter,
    /// Whether this body's shapes are sensors: they detect overlaps
    /// (reported as sensor events) and never push or get pushed. Soft-step
    /// contact model only.
    pub sensor: bool,
    /// Rolling resistance coefficient (≥ 0, dimensionless) of this body's
    /// shapes; see [`crate::material`]. Default: the world's settings.
    pub rolling_resistance: Option<f64>,
    /// Tangent speed (m/s) of this body's shapes' surface, a conveyor
    /// belt's; see [`crate::material`]. Default 0.
    pub tangent_speed: Option<f64>,
    /// Whether this body is a bullet (Box2D's `isBullet`): under the soft
    /// step, a fast dynamic bullet is also swept against the other
    /// dynamic (non-bullet) bodies' end poses, not only the static ones,
    /// so it cannot pass through a thin moving body in one step
    /// (`engine/src/soft_step/bullets.rs`). Default false. No effect on a
    /// static or kinematic body (kept for when it is made dynamic), nor
    /// under the exact model, whose swept contact search already covers
    /// every pair.
    pub bullet: bool,
}

impl BodyDef {
    /// A dynamic particle of `mass` kg at `position` (m).
    pub fn particle(name: &str, mass: f64, position: Vector2<f64>) -> Self {
        Self {
            name: name.into(),
            kind: BodyKind::Dynamic,
            mass: Some(mass),
            density: None,
            inertia: None,
            shape: None,
            state: BodyState {
                position,
                ..BodyState::default()
            },
            friction: None,
            restitution: None,
            filter: Filter::DEFAULT,
            sensor: false,
            rolling_resistance: None,
            tangent_speed: None,
            bullet: false,
        }
    }

    /// A dynamic rigid body of `mass` kg with `shape`, at the origin, at rest.
    pub fn rigid(name: &str, mass: f64, shape: Shape) -> Self {
        Self {
            shape: Some(shape),
            ..Self::particle(name, mass, Vector2::zeros())
        }
    }

    /// A static body at `position` (m), optionally with a shape.
    pub fn fixed(name: &str, position: Vector2<f64>, shape: Option<Shape>) -> Self {
        Self {
            kind: BodyKind::Static,
            mass: None,
            shape,
            ..Self::particle(name, 1.0, position)
        }
    }

    /// A kinematic body at `position` (m) with `shape`, moving at
    /// `velocity` (m/s) and `angular_velocity` (rad/s) forever.
    pub fn kinematic(
        name: &str,
        position: Vector2<f64>,
        shape: Shape,
        velocity: Vector2<f64>,
        angular_velocity: f64,
    ) -> Self {
        Self {
            kind: BodyKind::Kinematic,
            mass: None,
            shape: Some(shape),
            state: BodyState {
                position,
                angle: 0.0,
                velocity,
                angular_velocity,
            },
            ..Self::particle(name, 1.0, position)
        }
    }

    /// Sets this body's friction coefficient (≥ 0) and restitution (in
    /// [0, 1]), instead of the world's.
    pub fn with_material(mut self, friction: f64, restitution: f64) -> Self {
        self.friction = Some(friction);
        self.restitution = Some(restitution);
        self
    }

    /// Puts this body in "never collide" group `group`: it no longer
    /// collides with the other bodies of that group. This is the negative
    /// filter group −(group + 1) ([`Filter::group`]), the mapping the
    /// reference adapters use.
    pub fn with_collision_group(mut self, group: u32) -> Self {
        self.filter.group = -(i64::from(group) + 1);
        self
    }

    /// Sets this body's collision filter.
    pub fn with_filter(mut self, filter: Filter) -> Self {
        self.filter = filter;
        self
    }

    /// Makes this body's shapes sensors.
    pub fn as_sensor(mut self) -> Self {
        self.sensor = true;
        self
    }

    /// Makes this body a bullet ([`BodyDef::bullet`]).
    pub fn as_bullet(mut self) -> Self {
        self.bullet = true;
        self
    }

    /// Sets the initial velocity (m/s).
    pub fn with_velocity(mut self, velocity: Vector2<f64>) -> Self {
        self.state.velocity = velocity;
        self
    }

    /// Sets the initial position (m).
    pub fn with_position(mut self, position: Vector2<f64>) -> Self {
        self.state.position = position;
        self
    }

    /// Sets the initial angle (rad) and angular velocity (rad/s).
    pub fn with_rotation(mut self, angle: f64, angular_velocity: f64) -> Self {
        self.state.angle = angle;
        self.state.angular_velocity = angular_velocity;
        self
    }
}

/// A validated body inside a world.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Body {
    /// Name, for errors and reports.
    pub name: String,
    /// Dynamic or static.
    pub kind: BodyKind,
    /// Mass (kg); infinite for a static body.
    pub mass: f64,
    /// Moment of inertia (kg·m²); `None` for a particle (no rotation),
    /// infinite for a static body.
    pub inertia: Option<f64>,
    /// Geometry in the body frame, centred on the centre of mass.
    pub shape: Option<Shape>,
    /// Friction coefficient of its shape, if it has its own.
    pub friction: Option<f64>,
    /// Restitution of its shape, if it has its own.
    pub restitution: Option<f64>,
    /// Its shapes' collision filter ([`BodyDef::filter`]).
    pub filter: Filter,
    /// Whether its shapes are sensors ([`BodyDef::sensor`]).
    pub sensor: bool,
    /// Rolling resistance of its shapes, if it has its own.
    pub rolling_resistance: Option<f64>,
    /// Tangent speed of its shapes (m/s), if it has its own.
    pub tangent_speed: Option<f64>,
    /// Whether it is a bullet ([`BodyDef::bullet`]).
    pub bullet: bool,
}

/// The "never collide" group of [`BodyDef::with_collision_group`] in
/// `filter`, if its group is negative: `g` for group −(g + 1).
fn never_collide_group(filter: &Filter) -> Option<u32> {
    (filter.group < 0)
        .then(|| u32::try_from(-(filter.group + 1)).ok())
        .flatten()
}

impl BodyDef {
    /// The "never collide" group set by [`BodyDef::with_collision_group`]
    /// (read from the filter's negative group), if any.
    pub fn collision_group(&self) -> Option<u32> {
        never_collide_group(&self.filter)
    }
}

impl Body {
    /// The "never collide" group of [`BodyDef::with_collision_group`], if
    /// the filter has a negative group: `g` for group −(g + 1).
    pub fn collision_group(&self) -> Option<u32> {
        never_collide_group(&self.filter)
    }

    /// Whether the body uses anything only the soft step supports: a
    /// filter other than the default, a sensor, or its own material.
    pub(crate) fn has_soft_step_only_shape_data(&self) -> bool {
        self.filter != Filter::DEFAULT
            || self.sensor
            || self.rolling_resistance.is_some()
            || self.tangent_speed.is_some()
    }
}

impl Body {
    /// Validates a definition: masses, densities and inertias finite and
    /// > 0, the state finite. Returns the body and its initial state.
    pub fn from_def(def: &BodyDef) -> Result<(Body, BodyState)> {
        let name = &def.name;
        let s = &def.state;
        for (what, v) in [
            ("x", s.position.x),
            ("y", s.position.y),
            ("angle", s.angle),
            ("vx", s.velocity.x),
            ("vy", s.velocity.y),
            ("angular velocity", s.angular_velocity),
        ] {
            require_finite(format!("{what} of body '{name}'"), v)?;
        }
        let shape = def.shape.as_ref().map(Shape::centered);
        let friction = def
            .friction
            .map(|mu| require_non_negative(format!("friction of body '{name}'"), mu))
            .transpose()?;
        let restitution = def
            .restitution
            .map(|e| require_unit_interval(format!("restitution of body '{name}'"), e))
            .transpose()?;
        let what = format!("body '{name}'");
        validate_material(&what, None, None, def.rolling_resistance, def.tangent_speed)?;
        validate_filter(&what, &def.filter)?;
        if let Some(Shape::Compound(c)) = &shape {
            for (k, part) in c.parts().iter().enumerate() {
                let what = format!("part {k} of body '{name}'");
                part.overrides.validate(&what)?;
                if let Some(filter) = &part.overrides.filter {
                    validate_filter(&what, filter)?;
                }
            }
        }
        if let (Some(Shape::Chain(_)), false) = (&shape, def.kind == BodyKind::Static) {
            return Err(chain_on_moving_body(name));
        }
        if def.kind != BodyKind::Dynamic {
            let body = Body {
                name: name.clone(),
                kind: def.kind,
                mass: f64::INFINITY,
                inertia: Some(f64::INFINITY),
                shape,
                friction,
                restitution,
                filter: def.filter,
                sensor: def.sensor,
                rolling_resistance: def.rolling_resistance,
                tangent_speed: def.tangent_speed,
                bullet: def.bullet,
            };
            let state = if def.kind == BodyKind::Static {
                BodyState {
                    velocity: Vector2::zeros(),
                    angular_velocity: 0.0,
                    ..*s
                }
            } else {
                *s
            };
            return Ok((body, state));
        }
        if let Some(shape) = &shape
            && shape.area() == 0.0
            && (def.mass.is_none() || def.inertia.is_none())
        {
            // As in Box2D, a segment has no mass: it cannot give a dynamic
            // body its mass or inertia.
            return Err(EngineError::InvalidParameter {
                what: format!("shape of dynamic body '{name}'"),
                value: 0.0,
                reason: "a segment has no area, hence no mass or inertia: put it on a static \
                         or kinematic body, or give the dynamic body both a mass and an inertia",
            });
        }
        let mass = match (def.mass, def.density, &shape) {
            (Some(m), _, _) => require_positive(format!("mass of body '{name}'"), m)?,
            (None, Some(rho), Some(shape)) => {
                require_positive(format!("density of body '{name}'"), rho)? * shape.area()
            }
            _ => {
                return Err(EngineError::InvalidParameter {
                    what: format!("mass of body '{name}'"),
                    value: f64::NAN,
                    reason: "a dynamic body needs a mass, or a density and a shape",
                });
            }
        };
        let inertia = match (def.inertia, &shape) {
            (Some(i), _) => Some(require_positive(format!("inertia of body '{name}'"), i)?),
            (None, Some(shape)) => Some(mass * shape.inertia_per_unit_mass()),
            (None, None) => None,
        };
        let state = if inertia.is_none() {
            BodyState {
                angle: 0.0,
                angular_velocity: 0.0,
                ..*s
            }
        } else {
            *s
        };
        Ok((
            Body {
                name: name.clone(),
                kind: BodyKind::Dynamic,
                mass,
                inertia,
                shape,
                friction,
                restitution,
                filter: def.filter,
                sensor: def.sensor,
                rolling_resistance: def.rolling_resistance,
                tangent_speed: def.tangent_speed,
                bullet: def.bullet,
            },
            state,
        ))
    }

    /// Whether the body is integrated.
    pub fn is_dynamic(&self) -> bool {
        self.kind == BodyKind::Dynamic
    }

    /// Whether the body ever moves (dynamic or kinematic).
    pub fn moves(&self) -> bool {
        self.kind != BodyKind::Static
    }

    /// Whether the body carries rotational state (a dynamic rigid body).
    pub fn rotates(&self) -> bool {
        self.is_dynamic() && self.inertia.is_some()
    }

    /// Kinetic energy ½ m v² + ½ I ω² (J); 0 for a static or kinematic
    /// body (driven from outside, not part of the energy balance).
    pub fn kinetic_energy(&self, state: &BodyState) -> f64 {
        if !self.is_dynamic() {
            return 0.0;
        }
        let rotational = self.inertia.map_or(0.0, |i| {
            0.5 * i * state.angular_velocity * state.angular_velocity
        });
        0.5 * self.mass * state.velocity.norm_squared() + rotational
    }
}

/// The error of a chain shape on a body that is not static: a chain has
/// no area, so no mass to move with.
pub(crate) fn chain_on_moving_body(name: &str) -> EngineError {
    EngineError::Unsupported {
        what: format!("the chain shape of body '{name}'"),
        reason: "a chain has no area and no mass: it goes on static bodies only",
    }
}
