//! rapier2d-f64 (0.36.1) running the collision scenes of `docs/cases.md` case III
//! (head-on and off-centre impacts, bounces, sliding, inclines, resting),
//! configured as close to ideal rigid-body physics as rapier allows, so the
//! harness can set rapier's numbers beside the engine's and the closed
//! forms, and report what differs.
//!
//! # Configuration (every change from rapier's defaults)
//!
//! World ([`integration_parameters`] of [`crate::rapier_world`], shared with
//! the single-body scenes): `dt` and `num_solver_iterations` (= substeps) from
//! [`RapierSettings`], `normalized_max_linear_velocity = f64::MAX` (no speed
//! cap), `contact_recycling = false` (every pair's contacts recomputed every
//! step), gravity from the scene (default (0, −9.81) replaced).
//!
//! Dynamic bodies ([`rigid_body_builder`]): zero linear and angular damping,
//! `can_sleep(false)`, `allow_fast_rotation(true)`, mass and inertia exactly
//! the scene's through `additional_mass_properties`, with colliders of
//! **density 0** so that they add no mass (checked by reading the mass back).
//! Fixed bodies: `RigidBodyBuilder::fixed()` at the scene's pose.
//!
//! Colliders: the scene's shape (ball, cuboid or convex polygon with the same
//! vertices) at the body origin (the engine's body origin is the centre of
//! mass, and its shapes are centred on their centroids), with
//! - `restitution(e)` and `friction(μ)` on **both** colliders of every pair,
//!   with the explicit combine rule `CoefficientCombineRule::Max` for both
//!   (rapier's default is `Average`; with the same value on both colliders
//!   every rule but `Multiply` gives that value, and `Max` says so plainly);
//! - friction 0 unless the scene has friction (rapier's default is 0.5).
//!
//! Not changed: contact softness (30 Hz, ζ = 10; 60 Hz against fixed
//! bodies), warm-starting, one PGS and one stabilisation iteration per
//! substep, CCD (`max_ccd_substeps` = 1), prediction distance 0.02 m,
//! `length_unit` 1.
//!
//! # What rapier does with a contact (read in the 0.36.1 source)
//!
//! - Restitution (`geometry/contact_pair.rs`, `is_bouncy`): a *new* contact
//!   (no impulse at the previous step) bounces if e > 0; a contact still
//!   present one step later is a resting contact and no longer bounces
//!   unless e ≥ 1. The restitution target `−e·v_n` uses the normal velocity
//!   at the *start* of the step (`restitution_seed`), and is applied once
//!   after the substeps ("end-of-step restitution, color by color, box2d
//!   style", `staged_island_solver/worker.rs`).
//! - Contacts are soft: a spring of natural frequency f and damping ratio ζ
//!   pushes penetrations out over several substeps, so bodies overlap during
//!   impacts and a resting body sinks into its support by a small amount.
//! - Speculative contacts (within the prediction distance) are solved before
//!   the bodies touch, so an impact happens at the start of a step, with the
//!   velocity the body has then: impacts are quantised to the step.
//! - Per substep, symplectic Euler: v += a·h, then x += v·h (see
//!   [`crate::rapier_world`]).
//!
//! Units: SI (m, s, kg, N, rad).

use crate::rapier_world::{
    RapierBody, RapierError, RapierSample, RapierSettings, integration_parameters,
    rigid_body_builder,
};
use engine::Shape;
use rapier2d_f64::dynamics::{CoefficientCombineRule, RigidBodyBuilder, RigidBodyHandle};
use rapier2d_f64::geometry::{ColliderBuilder, ColliderHandle};
use rapier2d_f64::math::Vector;
use rapier2d_f64::pipeline::PhysicsWorld;
use std::collections::HashMap;

/// A body of a collision scene.
#[derive(Debug, Clone, PartialEq)]
pub enum RapierContactBody {
    /// A dynamic body with a collider of the given shape (density 0).
    Dynamic {
        /// Mass, inertia and initial state.
        body: RapierBody,
        /// Its shape, centred on its centre of mass.
        shape: Shape,
    },
    /// A fixed body.
    Fixed {
        /// Position of its origin (m).
        position: [f64; 2],
        /// Orientation (rad).
        angle: f64,
        /// Its shape, centred on its origin.
        shape: Shape,
    },
}

/// A collision scene for rapier.
#[derive(Debug, Clone, PartialEq)]
pub struct RapierContactScene {
    /// The bodies, in order; indices in the results refer to this order.
    pub bodies: Vec<RapierContactBody>,
    /// Uniform gravity (m/s²).
    pub gravity: [f64; 2],
    /// Restitution e ∈ [0, 1], set on every collider.
    pub restitution: f64,
    /// Friction μ ≥ 0, set on every collider.
    pub friction: f64,
}

/// A pair in contact during one step, as rapier reports it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RapierContactRecord {
    /// End of the step (s).
    pub t: f64,
    /// The pair, `body_a < body_b` (scene indices).
    pub body_a: usize,
    /// Second body.
    pub body_b: usize,
    /// Unit normal from `body_a` towards `body_b` (of the manifold with the
    /// largest impulse).
    pub normal: [f64; 2],
    /// Total normal impulse of the step (N·s, summed over the manifolds and
    /// points the solver used).
    pub normal_impulse: f64,
    /// Contact points rapier solved.
    pub points: usize,
}

/// A rapier run of a collision scene.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RapierContactRun {
    /// For each time n·dt, n = 0..=steps, every body's state (fixed bodies
    /// too, at rest).
    pub samples: Vec<Vec<RapierSample>>,
    /// The pairs with a positive normal impulse at each step.
    pub contacts: Vec<RapierContactRecord>,
}

fn collider(shape: &Shape, e: f64, mu: f64) -> Result<ColliderBuilder, RapierError> {
    let builder = match shape {
        Shape::Compound(_) | Shape::Chain(_) | Shape::Rounded(_) => {
            ColliderBuilder::new(crate::parry_queries::to_parry_shape(shape))
        }
        Shape::Circle(c) => ColliderBuilder::ball(c.radius),
        Shape::Polygon(p) => {
            let v = p.vertices();
            let is_box = v.len() == 4
                && v[0].y == v[1].y
                && v[1].x == v[2].x
                && v[2].y == v[3].y
                && v[3].x == v[0].x
                && v[0].x == -v[1].x
                && v[0].y == -v[3].y;
            if is_box {
                ColliderBuilder::cuboid(v[1].x, v[2].y)
            } else {
                let points = v.iter().map(|q| Vector::new(q.x, q.y)).collect();
                ColliderBuilder::convex_polyline(points).ok_or(RapierError::InvalidParameter {
                    what: "polygon",
                    value: f64::NAN,
                    reason: "rapier refuses it as a convex polyline",
                })?
            }
        }
    };
    Ok(builder
        .density(0.0)
        .restitution(e)
        .restitution_combine_rule(CoefficientCombineRule::Max)
        .friction(mu)
        .friction_combine_rule(CoefficientCombineRule::Max))
}

/// Runs `scene` in rapier for `duration` seconds (a whole number of steps of
/// `settings.dt`) and returns every body's state at each step and the pairs
/// in contact at each step.
pub fn run_contact_scene(
    scene: &RapierContactScene,
    settings: &RapierSettings,
    duration: f64,
) -> Result<RapierContactRun, RapierError> {
    let e = scene.restitution;
    if !(e.is_finite() && (0.0..=1.0).contains(&e)) {
        return Err(RapierError::InvalidParameter {
            what: "restitution",
            value: e,
            reason: "must be in [0, 1]",
        });
    }
    if !(scene.friction.is_finite() && scene.friction >= 0.0) {
        return Err(RapierError::InvalidParameter {
            what: "friction",
            value: scene.friction,
            reason: "must be finite and >= 0",
        });
    }
    if !(settings.dt.is_finite() && settings.dt > 0.0 && settings.substeps >= 1) {
        return Err(RapierError::InvalidParameter {
            what: "dt",
            value: settings.dt,
            reason: "dt must be finite and > 0 with at least one substep",
        });
    }
    let steps = (duration / settings.dt).round();
    if !(steps >= 1.0 && (steps * settings.dt - duration).abs() <= 1e-9 * duration) {
        return Err(RapierError::DurationNotWholeSteps {
            duration,
            dt: settings.dt,
        });
    }
    let steps = steps as usize;
    crate::serial_rayon();
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(scene.gravity[0], scene.gravity[1]);
    world.integration_parameters = integration_parameters(settings);
    let mut handles: Vec<RigidBodyHandle> = Vec::new();
    let mut owner: HashMap<ColliderHandle, usize> = HashMap::new();
    for (i, b) in scene.bodies.iter().enumerate() {
        let (builder, shape) = match b {
            RapierContactBody::Dynamic { body, shape } => (rigid_body_builder(body), shape),
            RapierContactBody::Fixed {
                position,
                angle,
                shape,
            } => (
                RigidBodyBuilder::fixed()
                    .translation(Vector::new(position[0], position[1]))
                    .rotation(*angle),
                shape,
            ),
        };
        let (h, c) = world.insert(builder, collider(shape, e, scene.friction)?);
        handles.push(h);
        owner.insert(c, i);
    }
    let mut run = RapierContactRun::default();
    let mut angles: Vec<f64> = Vec::new();
    let mut raw: Vec<f64> = Vec::new();
    let sample = |world: &PhysicsWorld, t: f64, angles: &mut Vec<f64>, raw: &mut Vec<f64>| {
        let mut out = Vec::with_capacity(handles.len());
        for (i, h) in handles.iter().enumerate() {
            let rb = &world.bodies[*h];
            let (p, v, w) = (rb.translation(), rb.linvel(), rb.angvel());
            let a = rb.rotation().angle();
            if angles.len() <= i {
                angles.push(match &scene.bodies[i] {
                    RapierContactBody::Dynamic { body, .. } => body.angle,
                    RapierContactBody::Fixed { angle, .. } => *angle,
                });
                raw.push(a);
            } else {
                // Unwrap: the branch of the change nearest ω·dt.
                let principal = a - raw[i];
                let k = ((w * settings.dt - principal) / std::f64::consts::TAU).round();
                angles[i] += principal + std::f64::consts::TAU * k;
                raw[i] = a;
            }
            out.push(RapierSample {
                t,
                position: [p.x, p.y],
                angle: angles[i],
                velocity: [v.x, v.y],
                angular_velocity: w,
            });
        }
        out
    };
    run.samples.push(sample(&world, 0.0, &mut angles, &mut raw));
    for n in 0..steps {
        world.step();
        let t = (n + 1) as f64 * settings.dt;
        if !world.quarantine().is_empty() {
            return Err(RapierError::NonFinite { t });
        }
        if n == 0 {
            for (b, h) in scene.bodies.iter().zip(&handles) {
                if let RapierContactBody::Dynamic { body, .. } = b {
                    let m = world.bodies[*h].mass();
                    if (m - body.mass).abs() > 8.0 * f64::EPSILON * body.mass {
                        return Err(RapierError::MassPropertiesMismatch {
                            what: "mass",
                            expected: body.mass,
                            got: m,
                        });
                    }
                }
            }
        }
        let states = sample(&world, t, &mut angles, &mut raw);
        if states.iter().any(|s| {
            !(s.position.iter().chain(&s.velocity).all(|x| x.is_finite())
                && s.angle.is_finite()
                && s.angular_velocity.is_finite())
        }) {
            return Err(RapierError::NonFinite { t });
        }
        run.samples.push(states);
        let mut records: Vec<RapierContactRecord> = Vec::new();
        for pair in world.narrow_phase.contact_pairs() {
            let impulse = pair.total_impulse_magnitude();
            if impulse <= 0.0 {
                continue;
            }
            let (Some(&i1), Some(&i2)) = (owner.get(&pair.collider1), owner.get(&pair.collider2))
            else {
                continue;
            };
            let (mut best, mut normal, mut points) = (f64::NEG_INFINITY, Vector::ZERO, 0);
            for m in pair.solver_manifolds() {
                points += m.data.solver_contacts.len();
                let j: f64 = m.points.iter().map(|p| p.data.impulse).sum();
                if j > best {
                    best = j;
                    normal = m.data.normal;
                }
            }
            let sign = if i1 < i2 { 1.0 } else { -1.0 };
            records.push(RapierContactRecord {
                t,
                body_a: i1.min(i2),
                body_b: i1.max(i2),
                normal: [sign * normal.x, sign * normal.y],
                normal_impulse: impulse,
                points,
            });
        }
        records.sort_by_key(|r| (r.body_a, r.body_b));
        run.contacts.extend(records);
    }
    Ok(run)
}

/// One paragraph for the report: how rapier is configured for the collision
/// scenes and what its contact model does.
pub fn contact_configuration_summary(settings: &RapierSettings) -> String {
    format!(
        "rapier2d-f64 0.36.1, dt = {dt} s, num_solver_iterations = {s} substeps (its \
         default 4), normalized_max_linear_velocity = f64::MAX (default 400 m/s), \
         contact_recycling = false (default true), gravity from the scene; dynamic bodies \
         with zero damping, can_sleep(false), allow_fast_rotation(true), mass and inertia \
         exactly the scene's (additional mass properties, colliders of density 0); \
         restitution e and friction mu (0 unless the case has friction; rapier's default \
         is 0.5) on both colliders with combine rule Max (default Average). Everything \
         else at its default: soft contacts (30 Hz, damping ratio 10; 60 Hz against fixed \
         bodies), warm-starting, speculative contacts within 0.02 m, restitution applied \
         only to new contacts (a contact present one step later rests unless e >= 1) and \
         computed from the normal velocity at the start of the step, symplectic Euler per \
         substep.",
        dt = settings.dt,
        s = settings.substeps,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::Circle;

    fn ball_over_ground(e: f64) -> RapierContactScene {
        RapierContactScene {
            bodies: vec![
                RapierContactBody::Fixed {
                    position: [0.0, -0.5],
                    angle: 0.0,
                    shape: Shape::rectangle(20.0, 1.0).unwrap(),
                },
                RapierContactBody::Dynamic {
                    body: RapierBody {
                        mass: 1.0,
                        inertia: Some(0.005),
                        position: [0.0, 1.1],
                        angle: 0.0,
                        velocity: [0.0, 0.0],
                        angular_velocity: 0.0,
                    },
                    shape: Shape::Circle(Circle::new(0.1).unwrap()),
                },
            ],
            gravity: [0.0, -9.80665],
            restitution: e,
            friction: 0.0,
        }
    }

    #[test]
    fn rapier_ball_bounces_and_reports_its_contacts() {
        let run =
            run_contact_scene(&ball_over_ground(1.0), &RapierSettings::new(0.01), 2.0).unwrap();
        assert_eq!(run.samples.len(), 201);
        let first = run.contacts.first().expect("the ball hits the ground");
        // It falls 1 m in 0.4516 s: the contact appears within a step or two
        // of it (speculative contacts act before touching).
        assert!((first.t - 0.4516).abs() < 0.03, "{}", first.t);
        assert_eq!((first.body_a, first.body_b), (0, 1));
        assert!(first.normal[1] > 0.99, "{:?}", first.normal);
        // The ball goes back up to most of its height.
        let top = run
            .samples
            .iter()
            .skip(60)
            .map(|s| s[1].position[1])
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(top > 1.0 && top < 1.11, "{top}");
    }

    #[test]
    fn rapier_contact_scene_rejects_bad_input() {
        let mut s = ball_over_ground(1.5);
        assert!(run_contact_scene(&s, &RapierSettings::new(0.01), 1.0).is_err());
        s.restitution = 1.0;
        assert!(run_contact_scene(&s, &RapierSettings::new(0.01), 0.015).is_err());
    }
}
