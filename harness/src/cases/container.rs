//! `container`: many bodies dropped into a static container under the
//! soft-step model at its defaults, the robustness scenes of the many-body
//! and hostile-input work:
//!
//! - `container_1000`: 1000 boxes, circles and polygons into a container
//!   60 m wide, 10 s: none leaves it, and the heap comes to rest;
//! - `container_10k`: 10 000 of them into one 110 m wide, 1000 steps
//!   (16.7 s): none leaves it, and the kinetic energy settles;
//! - `drop_20`: twenty boxes and circles dropped from 2 to 8 m with
//!   restitution 0.2 (the pile the exact model could not run): none ends
//!   under the ground, no energy is gained, and a step costs milliseconds.
//!
//! A run that blows up or goes non-finite is an error of the world (the
//! engine refuses such a step, naming the body), so a row here means the
//! run went through with every state finite. The runs step the world
//! without keeping a trace (10 000 bodies × 1000 steps would not fit).

use super::soft_step_common::SOFT_STEP;
use super::{Case, CaseReport, Snapshots};
use crate::row::{RowKind, RowSink};
use crate::scenes;
use crate::timing::min_time;
use anyhow::{Context, Result, bail};
use engine::{Body, BodyKind, BodyState, ContactModel, Shape, World};
use nalgebra::Vector2;
use scene::Scene;

/// Many bodies into a container.
pub const CASE: Case = Case {
    scenes: &["container_1000", "drop_20", "container_10k"],
    snapshots: Snapshots::HarnessOnly(
        "10 000 bodies take seconds even in a release build; engine/tests/soft_step_robustness.rs \
         drops 300 bodies into a container (none may leave it) and hashes a 1000-body pile",
    ),
    ..Case::new(
        "container",
        "Soft step: 1000 and 10 000 bodies dropped into a container, 20 dropped on a ground",
        run,
    )
};

/// A run to the end of its scene.
struct Ran {
    /// The world at the end.
    world: World,
    /// The largest kinetic energy (J) seen at a step's end.
    peak: f64,
    /// Every body's state [`STEADY_OVER`] seconds before the end (the
    /// first state when the run is shorter).
    before: Vec<BodyState>,
}

/// The span (s) over which a rolling circle's motion must stay the same to
/// count as steady rolling rather than unrest: one second, sixty steps.
const STEADY_OVER: f64 = 1.0;

/// The world after running `scene` to its end, its peak kinetic energy, and
/// the states [`STEADY_OVER`] before the end.
fn run_scene(scene: &Scene) -> Result<Ran> {
    let mut world = scene.build_world(None)?;
    let steps = engine::step_count(scene.duration(), scene.dt())?;
    let keep_at = steps.saturating_sub((STEADY_OVER / scene.dt()).round() as u64);
    let mut peak = kinetic_energy(&world);
    let mut before = world.states().to_vec();
    for step in 0..steps {
        if step == keep_at {
            before = world.states().to_vec();
        }
        world
            .step(scene.dt())
            .with_context(|| format!("{}: step at t = {} s", scene.origin(), world.time()))?;
        peak = peak.max(kinetic_energy(&world));
    }
    Ok(Ran {
        world,
        peak,
        before,
    })
}

/// Whether a dynamic body is a circle rolling steadily on something at rest
/// rather than a body not at rest: a circle with no rolling resistance
/// rolling on a flat support never stops (rolling without slipping
/// dissipates nothing), so a heap that has come to rest may still carry
/// one, and whether it does is chaos (which circle ends on a flat top at
/// what speed). Both conditions use the solver's rest speed `v_rest`:
///
/// - no slip: the slowest point of its rim, moving at | |v| − |ω| r |
///   (the rim's points move at v + ω × r, and ω × r takes every direction
///   with length |ω| r), moves slower than `v_rest`, the speed the solver
///   counts as rest, so the point touching the support is at rest on it;
/// - steady: over the last [`STEADY_OVER`] seconds neither v nor ω r
///   changed by more than `v_rest`. A disc rolling down a slope θ gains
///   (2/3) g sin θ per second (solid disc, I = m r²/2), so this admits only
///   supports flatter than asin(3 · 0.05 / (2 · 10)) = 0.43°; a body
///   falling, bouncing, toppling or pushed changes its velocity by far more.
fn rolls_steadily(body: &Body, now: &BodyState, before: &BodyState, v_rest: f64) -> bool {
    let Some(Shape::Circle(circle)) = &body.shape else {
        return false;
    };
    let r = circle.radius;
    let slip = (now.velocity.norm() - now.angular_velocity.abs() * r).abs();
    let dv = (now.velocity - before.velocity).norm();
    let dw = (now.angular_velocity - before.angular_velocity).abs() * r;
    slip < v_rest && dv <= v_rest && dw <= v_rest
}

/// Σ ½ m v² + ½ I ω² over the dynamic bodies (J).
fn kinetic_energy(world: &World) -> f64 {
    world
        .bodies()
        .iter()
        .zip(world.states())
        .map(|(b, s)| b.kinetic_energy(s))
        .sum()
}

fn total_dynamic_mass(world: &World) -> f64 {
    world
        .bodies()
        .iter()
        .filter(|b| b.is_dynamic())
        .map(|b| b.mass)
        .sum()
}

fn fastest(world: &World) -> f64 {
    world
        .bodies()
        .iter()
        .zip(world.states())
        .filter(|(b, _)| b.is_dynamic())
        .map(|(_, s)| s.velocity.norm())
        .fold(0.0, f64::max)
}

/// The container's interior: from the inner faces of the static bodies
/// named `left_wall` and `right_wall` and the top of `floor` (m).
struct Interior {
    left: f64,
    right: f64,
    floor: f64,
}

impl Interior {
    fn of(scene: &Scene, world: &World) -> Result<Interior> {
        let extent = |name: &str| -> Result<(Vector2<f64>, Vector2<f64>)> {
            let id = scene
                .body_id(name)
                .with_context(|| format!("{}: no body '{name}'", scene.origin()))?;
            let body = &world.bodies()[id];
            if body.kind != BodyKind::Static {
                bail!("{}: '{name}' is not static", scene.origin());
            }
            let shape = body.shape.as_ref().context("a wall without a shape")?;
            let s = &world.states()[id];
            let aabb = engine::validation::collision::Aabb::of_shape(
                shape,
                &nalgebra::Isometry2::new(s.position, s.angle),
            );
            Ok((aabb.min, aabb.max))
        };
        Ok(Interior {
            left: extent("left_wall")?.1.x,
            right: extent("right_wall")?.0.x,
            floor: extent("floor")?.1.y,
        })
    }

    /// Dynamic bodies whose centre is not strictly inside.
    fn outside(&self, world: &World) -> usize {
        world
            .bodies()
            .iter()
            .zip(world.states())
            .filter(|(b, _)| b.is_dynamic())
            .filter(|(_, s)| {
                let p = s.position;
                !(p.x > self.left && p.x < self.right && p.y > self.floor)
            })
            .count()
    }
}

/// The speed below which the soft step counts a body as at rest (its
/// sleeping threshold, Box2D's 0.05 m/s), read from the scene's settings.
fn rest_speed(scene: &Scene) -> Result<f64> {
    match scene.contact() {
        Some(ContactModel::SoftStep(s)) => Ok(s.sleep_threshold),
        _ => bail!("{}: not a soft-step scene", scene.origin()),
    }
}

const OUTSIDE: &str = "dynamic bodies whose centre left the container's interior (inside the \
     walls' inner faces, above the floor's top): a centre past a face means the body went at \
     least halfway through a static wall, which contacts must never allow; none";

/// Runs `container`.
pub fn run() -> Result<CaseReport> {
    let mut report = CaseReport::default();
    let rows = &mut report.rows;

    let scene = scenes::load("container_1000")?;
    let Ran { world, before, .. } = run_scene(&scene)?;
    let interior = Interior::of(&scene, &world)?;
    let v_rest = rest_speed(&scene)?;
    let mut sink = RowSink {
        case: "container",
        method: SOFT_STEP,
        dt: scene.dt(),
        rows,
    };
    let outside_1000 = interior.outside(&world);
    sink.at_most(RowKind::Criterion, "outside_1000", outside_1000 as f64, 0.0, 0.0, OUTSIDE);
    let (mut fastest_1000, mut rollers, mut fastest_roller) = (0.0_f64, 0, 0.0_f64);
    for ((body, now), then) in world.bodies().iter().zip(world.states()).zip(&before) {
        if !body.is_dynamic() {
            continue;
        }
        let speed = now.velocity.norm();
        // A body slower than the rest speed passes whatever it does; only a
        // faster one is asked whether it rolls steadily.
        if speed >= v_rest && rolls_steadily(body, now, then, v_rest) {
            rollers += 1;
            fastest_roller = fastest_roller.max(speed);
        } else {
            fastest_1000 = fastest_1000.max(speed);
        }
    }
    sink.at_most(
        RowKind::Criterion,
        "fastest_at_end_1000",
        fastest_1000,
        0.0,
        v_rest,
        format!(
            "the largest body speed after 10 s, circles rolling steadily left out ({rollers} \
             of them, the fastest at {fastest_roller:.3} m/s: without rolling resistance a \
             circle rolling on a flat support never stops, and whether one ends so is chaos; \
             steady rolling = the slowest rim point and the change of v and ω r over the last \
             second all below the rest speed, see `rolls_steadily`): the heap has come to rest \
             by the solver's own measure of rest, the speed below which it lets a body sleep \
             ({v_rest} m/s, Box2D's)"
        ),
    );

    let scene = scenes::load("drop_20")?;
    let Ran { world, .. } = run_scene(&scene)?;
    let ground_top = 0.0;
    let below = world
        .bodies()
        .iter()
        .zip(world.states())
        .filter(|(b, s)| b.is_dynamic() && s.position.y < ground_top)
        .count();
    let mut sink = RowSink {
        case: "container",
        method: SOFT_STEP,
        dt: scene.dt(),
        rows,
    };
    sink.at_most(
        RowKind::Criterion,
        "below_ground_20",
        below as f64,
        0.0,
        0.0,
        "dynamic bodies whose centre ended below the ground's top face (y = 0): none",
    );
    let e0 = scene.build_world(None)?.energy();
    let e1 = world.energy();
    sink.at_most(
        RowKind::Validation,
        "energy_gain_20",
        (e1 - e0) / e0.abs(),
        0.0,
        0.0,
        "relative change of the total energy over the 5 s: contacts with restitution 0.2 and \
         friction only dissipate, and the bodies start apart (no overlap for the push-out to \
         undo), so it may not rise",
    );
    let steps = engine::step_count(scene.duration(), scene.dt())?;
    let seconds = min_time(3, || run_scene(&scene).map(|_| ()))?;
    report.notes.push(format!(
        "`drop_20`: 20 bodies, {steps} steps in {:.1} ms (minimum of 3 runs), {:.3} ms per \
         step. Circles still roll at the end (up to {:.2} m/s: rolling \
         without slipping dissipates nothing, and no rolling resistance is modelled).",
        seconds * 1e3,
        seconds * 1e3 / steps as f64,
        fastest(&world),
    ));

    let scene = scenes::load("container_10k")?;
    let started = std::time::Instant::now();
    let Ran { world, peak, .. } = run_scene(&scene)?;
    let seconds = started.elapsed().as_secs_f64();
    let interior = Interior::of(&scene, &world)?;
    let v_rest = rest_speed(&scene)?;
    let mut sink = RowSink {
        case: "container",
        method: SOFT_STEP,
        dt: scene.dt(),
        rows,
    };
    let outside_10k = interior.outside(&world);
    sink.at_most(RowKind::Criterion, "outside_10k", outside_10k as f64, 0.0, 0.0, OUTSIDE);
    let mass = total_dynamic_mass(&world);
    let settled = 0.5 * mass * v_rest * v_rest;
    let kinetic = kinetic_energy(&world);
    sink.at_most(
        RowKind::Criterion,
        "kinetic_energy_at_end_10k",
        kinetic,
        0.0,
        settled,
        format!(
            "kinetic energy after 1000 steps (it peaked at {peak:.4e} J in the fall): settled \
             means no more than the heap would have if every body moved at the solver's rest \
             speed, ½ M v² with M = {mass:.1} kg and v = {v_rest} m/s"
        ),
    );
    report.notes.push(format!(
        "`container_10k`: 10 000 bodies, 1000 steps in {seconds:.1} s (one run, wall time); \
         kinetic energy {peak:.4e} J at its peak, {kinetic:.4e} J at the end; fastest body at \
         the end {:.3} m/s; bodies outside the container {outside_10k}. `container_1000`: \
         fastest body at the end not rolling steadily {fastest_1000:.2e} m/s, circles rolling \
         steadily {rollers} (fastest {fastest_roller:.2e} m/s), outside {outside_1000}.",
        fastest(&world),
    ));
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::BodyDef;

    fn state(vx: f64, omega: f64) -> BodyState {
        BodyState {
            position: Vector2::zeros(),
            angle: 0.0,
            velocity: Vector2::new(vx, 0.0),
            angular_velocity: omega,
        }
    }

    #[test]
    fn a_circle_rolling_steadily_is_told_from_slipping_accelerating_and_non_circles() {
        let (r, v_rest) = (0.4, 0.05);
        let disc = BodyDef::rigid("disc", 1.0, Shape::circle(r).unwrap());
        let (disc, _) = Body::from_def(&disc).unwrap();
        // Rolling to the right at 0.5 m/s: ω = −v / r, the same a second ago.
        let rolling = state(0.5, -0.5 / r);
        assert!(rolls_steadily(&disc, &rolling, &rolling, v_rest));
        // Its rim's slowest point at 0.1 m/s: slipping, not rolling.
        let slipping = state(0.5, -0.4 / r);
        assert!(!rolls_steadily(&disc, &slipping, &slipping, v_rest));
        // Rolling, but 0.1 m/s faster than a second ago (down a slope).
        assert!(!rolls_steadily(&disc, &rolling, &state(0.4, -0.4 / r), v_rest));
        // A box moving the same way is never a roller.
        let square = BodyDef::rigid("box", 1.0, Shape::rectangle(0.8, 0.8).unwrap());
        let (square, _) = Body::from_def(&square).unwrap();
        assert!(!rolls_steadily(&square, &rolling, &rolling, v_rest));
    }
}
