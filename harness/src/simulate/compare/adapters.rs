//! Which adapter of `references` runs a scene in each engine of
//! `--compare`, and why none can when none can (in the scene's words: the
//! body, the force, the setting):
//!
//! | scene | rapier2d-f64 | Box2D 3.2 |
//! |---|---|---|
//! | no `[contact]` | one dynamic body (statics left out: nothing touches them), [`crate::rapier_scene`]: gravity, springs from the centre to an anchor, drag, angular drag, torques; `references::rapier_world`, bent towards ideal rigid-body physics | one body with a shape, gravity only; `references::box2d_world` |
//! | `model = "exact"` | dynamic and static bodies with shapes, gravity only, the world's e and μ; `references::rapier_contacts` (ideal physics: no speed cap, exact mass) | the same scene at Box2D's defaults, 4 substeps |
//! | `model = "soft_step"` | any number of bodies, gravity only, each body's materials, the scene's substeps, its joints but target joints (converted by `crate::bench::neutral_joints`); `references::rapier_many` at rapier's defaults | the same, `references::box2d_world` |
//!
//! Both many-body adapters compute mass from density × area and the
//! inertia from the shape, so a body whose scene gives its own `inertia`
//! is refused there. The contact settings beyond materials and substeps
//! (stiffness, push-out speed, ...) stay each engine's defaults.

use super::super::CompareWith;
use crate::bench::convert::{Defaults, neutral_scene};
use crate::rapier_scene::{SingleBody, describe_force, rapier_body, rapier_single_body};
use anyhow::{Result, anyhow, bail};
use engine::{Body, BodyKind, ContactModel};
use references::box2d_world::Box2dWorld;
use references::many_body::{ManyBodyEngine, ManyBodyError, ManyBodyScene};
use references::rapier_contacts::{RapierContactBody, RapierContactScene};
use references::rapier_many::RapierManyWorld;
use references::rapier_world::{RapierSettings, configuration_summary};
use scene::Scene;
use scene::format::ForceSpec;

/// How a reference engine runs the scene.
pub(crate) enum Adapter {
    /// `references::rapier_world`: one dynamic body, the whole run at once.
    SingleBody(SingleBody),
    /// `references::rapier_contacts`: the exact model's scenes, the whole
    /// run at once.
    Contacts(RapierContactScene),
    /// `references::rapier_many` or `references::box2d_world`, stepped
    /// alongside the engine.
    Many(Box<dyn ManyBodyEngine>),
}

/// A reference engine set up for the scene.
pub(crate) struct Prepared {
    /// The adapter.
    pub(crate) adapter: Adapter,
    /// The engine's name and version.
    pub(crate) name: &'static str,
    /// Its substeps per step.
    pub(crate) substeps: usize,
    /// How it is configured (printed with `--verbose`).
    pub(crate) configuration: String,
    /// What the translation left out or assumed, for the reader.
    pub(crate) note: String,
}

/// The adapter's name in refusals.
fn adapter_words(with: CompareWith, scene: &Scene) -> String {
    let engine = match with {
        CompareWith::Rapier => "rapier",
        CompareWith::Box2d => "Box2D",
    };
    let model = match scene.contact() {
        None => "without contacts",
        Some(ContactModel::Exact(_)) => "for the exact contact model",
        Some(ContactModel::SoftStep(_)) => "for the soft-step contact model",
    };
    format!("the {engine} adapter {model}")
}

/// Refuses every force but gravity without a window, naming the first.
fn gravity_only(scene: &Scene, adapter: &str) -> Result<()> {
    for (i, f) in scene.file().forces.iter().enumerate() {
        if !matches!(f, ForceSpec::Gravity { window: None, .. }) {
            bail!(
                "{}: forces[{i}] ({}) is not supported by {adapter}, which takes gravity only",
                scene.origin(),
                describe_force(f)
            );
        }
    }
    Ok(())
}

/// Refuses a body without a shape, and (for the many-body adapters,
/// which compute it) one whose inertia is not its shape's.
fn shapes_only(scene: &Scene, adapter: &str, inertia_from_shape: bool) -> Result<()> {
    for (i, def) in scene.bodies().iter().enumerate() {
        let (body, _) = Body::from_def(def)?;
        let Some(shape) = &body.shape else {
            bail!(
                "{}: body '{}' is a particle (no shape); {adapter} needs a shape for every body",
                scene.origin(),
                body.name
            );
        };
        let given = scene
            .file()
            .bodies
            .get(i)
            .and_then(|b| b.inertia)
            .filter(|_| body.is_dynamic());
        if let (true, Some(inertia)) = (inertia_from_shape, given) {
            let from_shape = body.mass * shape.inertia_per_unit_mass();
            // The scene's own value, if it is the shape's to round-off, is
            // the shape's.
            if (inertia - from_shape).abs() > 1e-9 * from_shape {
                bail!(
                    "{}: body '{}' has inertia = {} kg·m² of its own; {adapter} computes it from \
                     the shape and the mass ({} kg·m²): leave `inertia` out to compare",
                    scene.origin(),
                    body.name,
                    inertia,
                    crate::simulate::fmt_short(from_shape)
                );
            }
        }
    }
    Ok(())
}

/// A many-body adapter's error in the scene's words (bodies by name).
fn many_body_error(scene: &Scene, e: ManyBodyError) -> anyhow::Error {
    let name = |i: usize| {
        scene
            .bodies()
            .get(i)
            .map_or(format!("#{i}"), |b| format!("'{}'", b.name))
    };
    match e {
        ManyBodyError::BodyRefused {
            engine,
            body,
            message,
        } => anyhow!(
            "body {} cannot be represented in {engine}: {message}",
            name(body)
        ),
        ManyBodyError::InvalidBody {
            body,
            field,
            value,
            reason,
        } => anyhow!("body {}: {field} = {value} {reason}", name(body)),
        other => anyhow!(other),
    }
}

/// The neutral scene of `scene` for the many-body adapters, with `dt`.
fn neutral(scene: &Scene, adapter: &str, dt: f64) -> Result<ManyBodyScene> {
    gravity_only(scene, adapter)?;
    shapes_only(scene, adapter, true)?;
    let defaults = match scene.contact() {
        Some(ContactModel::SoftStep(s)) => Defaults {
            friction: s.friction,
            restitution: s.restitution,
            substeps: s.substeps,
        },
        Some(ContactModel::Exact(s)) => Defaults {
            friction: s.friction,
            restitution: s.restitution,
            // Box2D's default substep count.
            substeps: 4,
        },
        None => Defaults {
            friction: 0.0,
            restitution: 0.0,
            substeps: 4,
        },
    };
    let mut many = neutral_scene(scene, defaults)?;
    many.dt = dt;
    many.validate().map_err(|e| many_body_error(scene, e))?;
    Ok(many)
}

/// The rapier scene of an exact-model `scene`.
fn contact_scene(
    scene: &Scene,
    adapter: &str,
    restitution: f64,
    friction: f64,
) -> Result<RapierContactScene> {
    gravity_only(scene, adapter)?;
    shapes_only(scene, adapter, false)?;
    let mut bodies = Vec::new();
    for def in scene.bodies() {
        let (body, state) = Body::from_def(def)?;
        let shape = body.shape.clone().expect("checked: every body has a shape");
        bodies.push(match body.kind {
            BodyKind::Dynamic => RapierContactBody::Dynamic {
                body: rapier_body(&body, &state),
                shape,
            },
            BodyKind::Static => RapierContactBody::Fixed {
                position: [state.position.x, state.position.y],
                angle: state.angle,
                shape,
            },
            BodyKind::Kinematic => bail!(
                "{}: body '{}' is kinematic, which {adapter} does not take",
                scene.origin(),
                body.name
            ),
        });
    }
    let mut gravity = scene.gravity().map_or([0.0, 0.0], |g| [g.x, g.y]);
    for f in &scene.file().forces {
        if let ForceSpec::Gravity { g, .. } = f {
            gravity[0] += g.x;
            gravity[1] += g.y;
        }
    }
    Ok(RapierContactScene {
        bodies,
        gravity,
        restitution,
        friction,
    })
}

/// What the many-body adapters leave out of a scene's joints, for the
/// note: the rigid rows' softness of the joints that set their own (the
/// neutral description has none: each engine uses its default).
fn joint_note(scene: &Scene) -> String {
    let own: Vec<&str> = scene
        .joints()
        .filter(|j| {
            j.constraint_hertz != engine::joints::DEFAULT_CONSTRAINT_HERTZ
                || j.constraint_damping_ratio != engine::joints::DEFAULT_CONSTRAINT_DAMPING_RATIO
        })
        .map(|j| j.name.as_str())
        .collect();
    let mut note = format!(
        "; {} joints converted (anchors in world coordinates at t = 0, reference angles and \
         lengths explicit)",
        scene.joint_count()
    );
    if let Some(first) = own.first() {
        let others = match own.len() {
            1 => String::new(),
            n => format!(" and {} other joints", n - 1),
        };
        note.push_str(&format!(
            "; joint '{first}'{others} set their own constraint_hertz or \
             constraint_damping_ratio, which the adapter does not carry: the engine's default \
             rigid-row softness there"
        ));
    }
    note
}

/// Sets up `with` for `scene` run in steps of `dt` (s), or says why it
/// cannot. A scene with joints uses the soft step (the scene crate sees to
/// it), so it goes to the many-body adapters, which take its joints as
/// [`crate::bench::neutral_joints`] converts them (a target joint, which
/// they cannot carry, is refused by name).
pub(crate) fn prepare(scene: &Scene, with: CompareWith, dt: f64) -> Result<Prepared> {
    let adapter = adapter_words(with, scene);
    let settings = RapierSettings::new(dt);
    let prepared = match (with, scene.contact()) {
        (CompareWith::Rapier, None) => {
            let single = rapier_single_body(scene)?;
            let statics = scene.bodies().len() - 1;
            Prepared {
                adapter: Adapter::SingleBody(single),
                name: "rapier2d-f64 0.36.1",
                substeps: settings.substeps,
                configuration: configuration_summary(&settings),
                note: if statics > 0 {
                    let (count, verb) = if statics == 1 {
                        (
                            "the static body".to_string(),
                            "never moves and nothing touches it",
                        )
                    } else {
                        (
                            format!("the {statics} static bodies"),
                            "never move and nothing touches them",
                        )
                    };
                    format!("contacts are off: rapier runs the dynamic body alone ({count} {verb})")
                } else {
                    "one body, its forces applied as rapier external forces".into()
                },
            }
        }
        (CompareWith::Rapier, Some(ContactModel::Exact(s))) => Prepared {
            adapter: Adapter::Contacts(contact_scene(scene, &adapter, s.restitution, s.friction)?),
            name: "rapier2d-f64 0.36.1",
            substeps: settings.substeps,
            configuration: references::rapier_contacts::contact_configuration_summary(&settings),
            note: format!(
                "rapier's soft contacts set as close to ideal rigid bodies as it allows, with the \
                 scene's e = {} and mu = {}",
                crate::simulate::fmt_short(s.restitution),
                crate::simulate::fmt_short(s.friction)
            ),
        },
        (CompareWith::Box2d, None) if scene.bodies().len() != 1 => bail!(
            "{}: contacts are off (the scene has no [contact]) and Box2D collides every pair of \
             bodies: {adapter} takes a single body only, this scene has {}",
            scene.origin(),
            scene.bodies().len()
        ),
        (with, model) => {
            let many = neutral(scene, &adapter, dt)?;
            let substeps = many.substeps;
            let engine: Box<dyn ManyBodyEngine> = match with {
                CompareWith::Rapier => {
                    Box::new(RapierManyWorld::new(&many).map_err(|e| many_body_error(scene, e))?)
                }
                CompareWith::Box2d => {
                    Box::new(Box2dWorld::new(&many).map_err(|e| many_body_error(scene, e))?)
                }
            };
            let mut note = match model {
                Some(ContactModel::SoftStep(_)) => {
                    "each body's materials, the gravity and the substeps from the scene; contact \
                     stiffness and the other solver settings at the engine's defaults"
                }
                Some(ContactModel::Exact(_)) => {
                    "the scene's e and mu on every body, at the engine's defaults otherwise \
                     (a soft-step engine: its impacts are not exact)"
                }
                None => "one body under gravity",
            }
            .to_string();
            if scene.joint_count() > 0 {
                note.push_str(&joint_note(scene));
            }
            Prepared {
                name: engine.name(),
                configuration: engine.configuration(),
                adapter: Adapter::Many(engine),
                substeps,
                note,
            }
        }
    };
    Ok(prepared)
}
