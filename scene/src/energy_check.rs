//! The initial energy of a world: a finite number, or a refusal naming the
//! field that makes it overflow. Part of [`crate::build`].
//!
//! Every number of a scene is within the square root of f64's range
//! ([`crate::MAX_MAGNITUDE`]), but ½ m v² multiplies three of them: a mass
//! of 1e100 kg at 1e110 m/s overflows. The engine checks the energy after
//! each step of a world built from a scene; this is the check at t = 0,
//! when the file is loaded, so that the refusal names the field.

use crate::build::{Checked, WorldPlan};
use crate::error::{ErrorKind, FieldPath, Problem};
use engine::error::readable;
use engine::{Body, Method, World};

/// Refuses a world whose energy at t = 0 is not finite, naming the body
/// (its velocity or angular velocity, or its position under the scene's
/// gravity), else the force, whose term overflows; else the sum.
pub(crate) fn initial_energy(plan: &WorldPlan, method: Method) -> Checked<()> {
    let bodies = FieldPath::root().key("bodies");
    // Each body as the engine builds it; one refused earlier (with its own
    // message) is skipped.
    let built: Vec<_> = plan
        .bodies
        .iter()
        .enumerate()
        .filter_map(|(i, def)| Body::from_def(def).ok().map(|b| (i, def, b)))
        .collect();
    for &(i, def, (ref body, ref state)) in &built {
        let kinetic = body.kinetic_energy(state);
        if !kinetic.is_finite() {
            let translation = 0.5 * body.mass * state.velocity.norm_squared();
            let field = if translation.is_finite() {
                "angular_velocity"
            } else {
                "velocity"
            };
            return Err(overflow(
                &bodies.index(i).key(field),
                format!(
                    "the kinetic energy of body '{}' (½ m v² + ½ I ω²) is {} J",
                    def.name,
                    readable(kinetic)
                ),
            ));
        }
    }
    // Gravity as a world setting ([simulation] gravity): m |g| |x| per
    // body, located at the position (the height is what a user changes).
    let g = plan.gravity.map_or(0.0, |g| g.norm());
    for &(i, def, (ref body, ref state)) in &built {
        let potential = body.mass * g * state.position.norm();
        if body.is_dynamic() && !potential.is_finite() {
            return Err(overflow(
                &bodies.index(i).key("position"),
                format!(
                    "the potential energy of body '{}' under the gravity of [simulation] \
                     (m |g| |x|) is {} J",
                    def.name,
                    readable(potential)
                ),
            ));
        }
    }
    let total = |forces: &[crate::build::PlannedForce]| -> Option<f64> {
        let mut world = World::new(method).ok()?;
        if let Some(g) = plan.gravity {
            world.set_gravity(g).ok()?;
        }
        for def in &plan.bodies {
            world.add_body(def.clone()).ok()?;
        }
        for f in forces {
            world.add_force_during(f.force.boxed(), f.window).ok()?;
        }
        Some(world.energy())
    };
    // A finite sum has only finite terms: the search for the force to
    // blame runs only when the whole is not finite (each try builds a
    // world of every body).
    let whole = total(&plan.forces);
    if whole.is_none_or(f64::is_finite) {
        return Ok(());
    }
    for f in &plan.forces {
        if let Some(energy) = total(std::slice::from_ref(f)) {
            if !energy.is_finite() {
                return Err(overflow(
                    &f.path,
                    format!(
                        "the potential energy of this force at t = 0 is {} J",
                        readable(energy)
                    ),
                ));
            }
        }
    }
    match whole {
        Some(energy) if !energy.is_finite() => Err(overflow(
            &bodies,
            format!(
                "the total energy at t = 0 is {} J: each term is finite but their sum is not",
                readable(energy)
            ),
        )),
        _ => Ok(()),
    }
}

fn overflow(path: &FieldPath, what: String) -> Problem {
    Problem::new(
        path,
        ErrorKind::OutOfRange,
        format!(
            "{what}, beyond f64's range (1.8e308): the scene's masses, speeds, distances or forces are too large together"
        ),
    )
}
