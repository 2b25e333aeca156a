//! A scene file without contacts translated for rapier2d-f64's single-body
//! adapter (`references::rapier_world`): the one dynamic body, gravity
//! (the world setting and the forces), and the forces rapier gets as
//! external forces each step (axial and distance springs to an anchor,
//! drag, angular drag, windowed torques). Static bodies are left out: with
//! contacts off nothing touches them and they never move. Scenes outside
//! that set are refused with the reason, in the scene's words, not
//! approximated.

use anyhow::{Result, bail};
use engine::{Body, BodyKind, BodyState};
use references::rapier_world::{RapierBody, RapierForce};
use scene::Scene;
use scene::format::{ForceSpec, Window};

/// A force of the scene file as its reader knows it: its type, the body
/// it acts on and its window, e.g. `spring on 'ball' to another body`.
pub fn describe_force(force: &ForceSpec) -> String {
    let window = |w: &Option<Window>| {
        w.map_or(String::new(), |w| {
            format!(
                " with a window [{}, {}] s",
                crate::simulate::fmt_short(w.start),
                crate::simulate::fmt_short(w.end)
            )
        })
    };
    match force {
        ForceSpec::Gravity { window: w, .. } => format!("gravity{}", window(w)),
        ForceSpec::Spring {
            body,
            other_body,
            point,
            axis,
            window: w,
            ..
        } => {
            let to = match other_body {
                Some(other) => format!(" to body '{other}'"),
                None => " to an anchor".into(),
            };
            let kind = if axis.is_some() { "axial " } else { "" };
            let at = if point.is_some() {
                " at a point off its centre"
            } else {
                ""
            };
            format!("{kind}spring on '{body}'{at}{to}{}", window(w))
        }
        ForceSpec::Drag {
            body, window: w, ..
        } => format!("drag on '{body}'{}", window(w)),
        ForceSpec::AngularDrag {
            body, window: w, ..
        } => {
            format!("angular drag on '{body}'{}", window(w))
        }
        ForceSpec::PointForce {
            body, window: w, ..
        } => {
            format!("point force on '{body}'{}", window(w))
        }
        ForceSpec::Torque {
            body, window: w, ..
        } => format!("torque on '{body}'{}", window(w)),
    }
}

/// A single-body scene for rapier: the body's index in the scene, its
/// rapier description and the forces.
#[derive(Debug, Clone)]
pub struct SingleBody {
    /// Index of the dynamic body in the scene's bodies.
    pub index: usize,
    /// Mass, inertia and initial state.
    pub body: RapierBody,
    /// Gravity and the external forces.
    pub forces: Vec<RapierForce>,
}

/// The rapier description of a scene of one dynamic body (and any number
/// of static ones) with contacts off.
pub fn rapier_single_body(scene: &Scene) -> Result<SingleBody> {
    let defs = scene.bodies();
    let dynamic: Vec<usize> = (0..defs.len())
        .filter(|&i| defs[i].kind != BodyKind::Static)
        .collect();
    let [index] = dynamic[..] else {
        let names: Vec<String> = dynamic
            .iter()
            .map(|&i| format!("'{}'", defs[i].name))
            .collect();
        bail!(
            "{}: {} moving bodies ({}); without [contact] the rapier adapter runs one dynamic body \
             (static ones are left out, nothing touches them)",
            scene.origin(),
            dynamic.len(),
            names.join(", ")
        );
    };
    if defs[index].kind == BodyKind::Kinematic {
        bail!(
            "{}: body '{}' is kinematic; the rapier adapter for scenes without contacts runs a \
             dynamic body",
            scene.origin(),
            defs[index].name
        );
    }
    let (body, state) = Body::from_def(&defs[index])?;
    let single = rapier_body(&body, &state);
    let mut forces = Vec::new();
    if let Some(g) = scene.gravity() {
        forces.push(RapierForce::Gravity([g.x, g.y]));
    }
    for (i, force) in scene.file().forces.iter().enumerate() {
        let converted = match force {
            ForceSpec::Gravity { g, window: None } => RapierForce::Gravity([g.x, g.y]),
            ForceSpec::Spring {
                anchor: Some(anchor),
                axis,
                point: None,
                other_body: None,
                stiffness,
                rest_length,
                window: None,
                ..
            } => match axis {
                Some(axis) => RapierForce::AxialSpring {
                    anchor: [anchor.x, anchor.y],
                    axis: [axis.x, axis.y],
                    stiffness: *stiffness,
                    rest_length: *rest_length,
                },
                None => RapierForce::DistanceSpring {
                    anchor: [anchor.x, anchor.y],
                    stiffness: *stiffness,
                    rest_length: *rest_length,
                },
            },
            ForceSpec::Drag {
                coefficient,
                window: None,
                ..
            } => RapierForce::QuadraticDrag {
                coefficient: *coefficient,
            },
            ForceSpec::AngularDrag {
                coefficient,
                window: None,
                ..
            } => RapierForce::AngularDrag {
                coefficient: *coefficient,
            },
            ForceSpec::Torque {
                torque,
                lever,
                force,
                window,
                ..
            } => {
                let tau = match (torque, lever, force) {
                    (Some(t), _, _) => *t,
                    (None, Some(r), Some(f)) => r.x * f.y - r.y * f.x,
                    _ => bail!(
                        "{}: forces[{i}]: torque needs `torque` or `lever` and `force`",
                        scene.origin()
                    ),
                };
                let (start, end) =
                    window.map_or((f64::NEG_INFINITY, f64::INFINITY), |w| (w.start, w.end));
                RapierForce::Torque {
                    torque: tau,
                    start,
                    end,
                }
            }
            other => bail!(
                "{}: forces[{i}] ({}) is not supported by the rapier adapter (it takes gravity, \
                 a spring from the body's centre to an anchor, drag and angular drag without a \
                 window, and torques)",
                scene.origin(),
                describe_force(other)
            ),
        };
        forces.push(converted);
    }
    Ok(SingleBody {
        index,
        body: single,
        forces,
    })
}

/// The rapier description of a single-body scene: the body and forces of
/// [`rapier_single_body`].
pub fn rapier_problem(scene: &Scene) -> Result<(RapierBody, Vec<RapierForce>)> {
    let single = rapier_single_body(scene)?;
    Ok((single.body, single.forces))
}

/// `body` at `state` as the rapier2d adapters take a dynamic body: mass,
/// inertia (none for a particle), pose and velocities, SI units.
pub(crate) fn rapier_body(body: &Body, state: &BodyState) -> RapierBody {
    RapierBody {
        mass: body.mass,
        inertia: body.inertia,
        position: [state.position.x, state.position.y],
        angle: state.angle,
        velocity: [state.velocity.x, state.velocity.y],
        angular_velocity: state.angular_velocity,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(text: &str) -> Scene {
        Scene::parse_str("s.toml", text).unwrap()
    }

    const HEAD: &str = "[simulation]\ndt = 0.01\nduration = 1.0\n\
        [[bodies]]\nname = \"bar\"\nkind = \"static\"\nshape = { type = \"box\", width = 1.0, height = 0.1 }\n\
        [[bodies]]\nname = \"ball\"\nmass = 2.0\nposition = [1.0, 0.0]\n";

    #[test]
    fn a_static_body_is_left_out_and_a_distance_spring_kept() {
        let s = scene(&format!(
            "{HEAD}[[forces]]\ntype = \"spring\"\nbody = \"ball\"\nanchor = [0.0, 0.0]\nstiffness = 3.0\nrest_length = 0.5\n"
        ));
        let single = rapier_single_body(&s).unwrap();
        assert_eq!(single.index, 1);
        assert_eq!(single.body.mass, 2.0);
        assert_eq!(
            single.forces,
            [RapierForce::DistanceSpring {
                anchor: [0.0, 0.0],
                stiffness: 3.0,
                rest_length: 0.5
            }]
        );
        // The world's gravity setting becomes rapier's gravity.
        let s = scene(&HEAD.replace(
            "duration = 1.0\n",
            "duration = 1.0\ngravity = [0.0, -9.81]\n",
        ));
        let single = rapier_single_body(&s).unwrap();
        assert_eq!(single.forces, [RapierForce::Gravity([0.0, -9.81])]);
    }

    #[test]
    fn a_refusal_names_the_force_in_the_scene_s_words() {
        let s = scene(&format!(
            "{HEAD}[[forces]]\ntype = \"point_force\"\nbody = \"ball\"\nforce = [1.0, 0.0]\n"
        ));
        let e = rapier_single_body(&s).unwrap_err().to_string();
        assert!(e.contains("forces[0] (point force on 'ball')"), "{e}");
        assert!(!e.contains("PointForce"), "no Debug dump: {e}");
        let two = scene(&format!("{HEAD}[[bodies]]\nname = \"b2\"\nmass = 1.0\n"));
        let e = rapier_single_body(&two).unwrap_err().to_string();
        assert!(e.contains("2 moving bodies ('ball', 'b2')"), "{e}");
    }
}
