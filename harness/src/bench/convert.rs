//! A scene file as the reference engines take it: the neutral
//! [`ManyBodyScene`] of `references::many_body`, built from the same
//! validated bodies the engine gets (shapes re-centred on their centroids,
//! mass from the density or the given mass), with the soft step's default
//! materials filled in, the scene's gravity, its step and its substeps,
//! and its joints ([`super::neutral_joints`]).

use anyhow::{Context, Result, bail};
use engine::{Body, BodyKind, ContactModel};
use references::many_body::{self, ManyBodyScene, SceneBody};
use scene::Scene;
use scene::format::ForceSpec;

/// The materials and substeps a scene gives bodies without their own.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Defaults {
    /// Friction coefficient of a body without its own.
    pub friction: f64,
    /// Restitution of a body without its own.
    pub restitution: f64,
    /// Substeps per step.
    pub substeps: usize,
}

/// The neutral description of a soft-step `scene` (bodies in file order,
/// so indices agree with the engine's).
pub fn many_body_scene(scene: &Scene) -> Result<ManyBodyScene> {
    let settings = match scene.contact() {
        Some(ContactModel::SoftStep(s)) => s,
        _ => bail!(
            "{}: a benchmark scene must use the soft-step contact model",
            scene.origin()
        ),
    };
    neutral_scene(
        scene,
        Defaults {
            friction: settings.friction,
            restitution: settings.restitution,
            substeps: settings.substeps,
        },
    )
}

/// The neutral description of `scene` with `defaults` for the bodies
/// without their own materials: every body with a shape, gravity the only
/// force (the world setting and unwindowed `gravity` forces, summed).
pub fn neutral_scene(scene: &Scene, defaults: Defaults) -> Result<ManyBodyScene> {
    let mut gravity = scene.gravity().map_or([0.0, 0.0], |g| [g.x, g.y]);
    for f in &scene.file().forces {
        match f {
            ForceSpec::Gravity { g, window: None } => {
                gravity[0] += g.x;
                gravity[1] += g.y;
            }
            _ => bail!(
                "{}: only gravity acts in a benchmark scene (the reference engines take no other force)",
                scene.origin()
            ),
        }
    }
    let mut states = Vec::with_capacity(scene.bodies().len());
    let bodies = scene
        .bodies()
        .iter()
        .map(|def| {
            let (body, state) = Body::from_def(def)?;
            states.push(state);
            // The reference adapters take a "never collide" group and
            // nothing else of the filters, and no sensor or material
            // beyond friction and restitution: refused, not dropped.
            let plain_filter = engine::Filter {
                group: 0,
                ..body.filter
            } == engine::Filter::DEFAULT
                && body.filter.group <= 0;
            if !plain_filter
                || body.sensor
                || body.rolling_resistance.is_some()
                || body.tangent_speed.is_some()
            {
                bail!(
                    "{}: body '{}' has a filter other than a \"never collide\" group, a sensor, \
                     a rolling resistance or a tangent speed, which the reference engines' \
                     conversion does not carry",
                    scene.origin(),
                    body.name
                );
            }
            let shape = body
                .shape
                .clone()
                .with_context(|| format!("body '{}' has no shape", body.name))?;
            let kind = match body.kind {
                BodyKind::Dynamic => many_body::BodyKind::Dynamic,
                BodyKind::Static => many_body::BodyKind::Static,
                BodyKind::Kinematic => many_body::BodyKind::Kinematic,
            };
            let density = if body.is_dynamic() {
                body.mass / shape.area()
            } else {
                0.0
            };
            Ok(SceneBody {
                kind,
                shape,
                position: [state.position.x, state.position.y],
                angle: state.angle,
                velocity: [state.velocity.x, state.velocity.y],
                angular_velocity: state.angular_velocity,
                density,
                friction: body.friction.unwrap_or(defaults.friction),
                restitution: body.restitution.unwrap_or(defaults.restitution),
                collision_group: def.collision_group(),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let scene = ManyBodyScene {
        gravity,
        dt: scene.dt(),
        substeps: defaults.substeps,
        bodies,
        joints: super::neutral_joints::neutral_joints(scene.joints(), &states)
            .with_context(|| scene.origin().to_owned())?,
    };
    scene.validate()?;
    Ok(scene)
}
