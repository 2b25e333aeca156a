//! A scene file translated for rapier2d-f64 (`references::rapier_world`):
//! the one dynamic body, gravity, and the forces rapier gets as external
//! forces each step (axial spring, drag, angular drag, windowed torque).
//! Scenes outside that set are refused with a reason, not approximated.

use anyhow::{Result, bail};
use engine::{Body, BodyKind};
use references::rapier_world::{RapierBody, RapierForce};
use scene::Scene;
use scene::format::ForceSpec;

/// The rapier description of a single-body scene.
pub fn rapier_problem(scene: &Scene) -> Result<(RapierBody, Vec<RapierForce>)> {
    let defs = scene.bodies();
    let dynamic: Vec<usize> = (0..defs.len())
        .filter(|&i| defs[i].kind == BodyKind::Dynamic)
        .collect();
    let [index] = dynamic[..] else {
        bail!(
            "{}: the rapier comparison handles scenes with exactly one dynamic body (found {})",
            scene.origin(),
            dynamic.len()
        );
    };
    let (body, state) = Body::from_def(&defs[index])?;
    let rapier_body = RapierBody {
        mass: body.mass,
        inertia: body.inertia,
        position: [state.position.x, state.position.y],
        angle: state.angle,
        velocity: [state.velocity.x, state.velocity.y],
        angular_velocity: state.angular_velocity,
    };
    let mut forces = Vec::new();
    for (i, force) in scene.file().forces.iter().enumerate() {
        let windowed = |w: &Option<scene::format::Window>| w.is_some();
        let converted = match force {
            ForceSpec::Gravity { g, window } if !windowed(window) => {
                RapierForce::Gravity([g.x, g.y])
            }
            ForceSpec::Spring {
                anchor: Some(anchor),
                axis: Some(axis),
                point: None,
                other_body: None,
                stiffness,
                rest_length,
                window,
                ..
            } if !windowed(window) => RapierForce::AxialSpring {
                anchor: [anchor.x, anchor.y],
                axis: [axis.x, axis.y],
                stiffness: *stiffness,
                rest_length: *rest_length,
            },
            ForceSpec::Drag {
                coefficient,
                window,
                ..
            } if !windowed(window) => RapierForce::QuadraticDrag {
                coefficient: *coefficient,
            },
            ForceSpec::AngularDrag {
                coefficient,
                window,
                ..
            } if !windowed(window) => RapierForce::AngularDrag {
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
                "{}: forces[{i}] ({other:?}) has no rapier2d counterpart in the comparison (supported: gravity, an axial spring to an anchor, drag, angular drag, a windowed torque)",
                scene.origin()
            ),
        };
        forces.push(converted);
    }
    Ok((rapier_body, forces))
}
