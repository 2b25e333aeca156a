//! rapier2d-f64 (0.36.1) running a [`ManyBodyScene`] for the many-body
//! benchmark, at rapier's own defaults except where the benchmark protocol
//! or the scene says otherwise.
//!
//! Unlike the single-body and collision adapters ([`crate::rapier_world`],
//! [`crate::rapier_contacts`]), which bend rapier towards ideal rigid-body
//! physics (no speed cap, fast rotation, exact mass through
//! `additional_mass_properties`), this one measures rapier as it ships: the
//! benchmark compares engines at their defaults.
//!
//! # Configuration (every change from rapier's defaults, and why)
//!
//! [`IntegrationParameters`]:
//! - `dt` = the scene's (default 1/60 s);
//! - `num_solver_iterations` = the scene's substeps (default 4). In 0.36
//!   this is the number of substeps of length dt/substeps, each one
//!   biased solve and one relax (`num_internal_pgs_iterations` and
//!   `num_internal_stabilization_iterations`, both 1 by default);
//! - everything else at its default, as read in `integration_parameters.rs`:
//!   contact softness 30 Hz with damping ratio 10 (`contact_softness`), 60 Hz
//!   against fixed bodies (`static_contact_softness`; kinematic bodies get
//!   the 30 Hz, as in Box2D), push-out speed at most
//!   3 m/s (`normalized_max_corrective_velocity`), speculative contacts
//!   within 0.02 m (`normalized_prediction_distance`), no penetration slop
//!   in the bias (`normalized_allowed_linear_error` 0.005 m is only the CCD
//!   standoff), friction in the relax pass only (`friction_in_bias_pass`
//!   false), warm starting 1, speed clamp 400 m/s
//!   (`normalized_max_linear_velocity`), CCD of fast dynamic bodies against
//!   fixed colliders (`max_ccd_substeps` 1), contact recycling on within
//!   0.05 m (`contact_recycling`, `normalized_contact_recycle_distance`).
//!
//! World gravity = the scene's (`PhysicsWorld` default (0, −9.81) m/s²).
//!
//! Bodies ([`RigidBodyBuilder`]): `dynamic()`, `fixed()` or
//! `kinematic_velocity_based()` (a kinematic body moves at its velocity,
//! like Box2D's) at the scene's pose and velocity, `can_sleep(false)`
//! (default true: the benchmark protocol turns sleeping off). Damping (0),
//! gravity scale (1), angular speed clamp (π/4)/dt (`allow_fast_rotation`
//! false, as Box2D) and CCD flags stay at their defaults.
//!
//! Colliders ([`ColliderBuilder`]), one per body at its origin (never
//! offset from it: rapier would carry the mass properties' centre along
//! with the offset): a ball; a cuboid for an axis-aligned rectangle centred
//! on the origin; any other convex polygon with its vertices as given
//! (`ConvexPolygon::from_convex_polyline_unmodified`; rapier's usual
//! constructor would drop nearly collinear vertices). For a dynamic body,
//! density from the scene, so rapier computes mass = density × area and the
//! inertia itself, as Box2D does. For a static or kinematic body, mass
//! properties zero at the body origin (`ColliderBuilder::mass_properties`)
//! whatever the scene's density: with a density > 0 rapier would put the
//! body's centre at the collider's centroid and turn a kinematic body about
//! it, so an off-centre wall would orbit its own centroid instead of the
//! body origin (Box2D gives non-dynamic bodies no mass and turns them about
//! their origin). Segments, capsules and rounded polygons are parry's
//! segment, capsule and round convex polygon; as parry gives a round
//! polygon its core's mass properties (ignoring the border) and a 2D
//! capsule an inertia off by the 3D hemisphere's centroid offset (3r/8
//! for 4r/3π: 1.9 % low for L = 1, r = 0.25), a dynamic body holding
//! either gets the scene's exact mass and inertia instead of a density
//! (the Box2D adapter does the same for rounded polygons, Box2D's mass of
//! which is an approximation; its capsule's is exact). Friction and restitution from the scene with the combine
//! rules `GeometricMean` for friction (exactly Box2D's √(μa μb); rapier's
//! default is `Average`) and `Max` for restitution (Box2D's rule; default
//! `Average`). Both colliders of a pair carry the same rules, so no
//! precedence between rules arises.
//!
//! # Threads
//!
//! The `parallel` feature of rapier2d-f64 is not enabled in this workspace
//! (no rayon in `references`' dependency tree): rapier runs on the calling
//! thread.
//!
//! Joints and collision groups: see [`joints`] (how each joint is built,
//! the exact mapping of springs from Hz and damping ratio, what rapier
//! cannot express).
//!
//! Units: SI (m, s, kg, rad).

use crate::many_body::holds_rounded;
use crate::many_body::{
    BodyKind, BodyMass, BodySample, ContactCounts, ManyBodyEngine, ManyBodyError, ManyBodyScene,
    axis_aligned_box,
};
use engine::{RoundedKind, Shape};
use parry2d_f64::shape::{ConvexPolygon, SharedShape};
use rapier2d_f64::dynamics::{
    CoefficientCombineRule, ImpulseJointHandle, IntegrationParameters, MassProperties,
    RigidBodyBuilder, RigidBodyHandle,
};
use rapier2d_f64::geometry::ColliderBuilder;
use rapier2d_f64::math::Vector;
use rapier2d_f64::pipeline::PhysicsWorld;

/// Engine name used in errors and reports.
const ENGINE: &str = "rapier2d-f64 0.36.1";

pub mod joints;
mod ray;

/// A [`ManyBodyScene`] in a rapier world.
pub struct RapierManyWorld {
    world: PhysicsWorld,
    bodies: Vec<RigidBodyHandle>,
    joints: Vec<Vec<ImpulseJointHandle>>,
    steps: usize,
    /// The rayon pool rapier's parallel paths run in (one thread unless
    /// [`RapierManyWorld::with_threads`] said more).
    pool: rayon::ThreadPool,
}

/// Rapier's integration parameters for `scene`: the defaults with the
/// scene's `dt` and substeps.
pub fn benchmark_parameters(scene: &ManyBodyScene) -> IntegrationParameters {
    IntegrationParameters {
        dt: scene.dt,
        num_solver_iterations: scene.substeps,
        ..IntegrationParameters::default()
    }
}

fn collider(i: usize, shape: &Shape) -> Result<ColliderBuilder, ManyBodyError> {
    Ok(match shape {
        Shape::Compound(_) | Shape::Chain(_) | Shape::Rounded(_) => {
            ColliderBuilder::new(crate::parry_queries::to_parry_shape(shape))
        }
        Shape::Circle(c) => ColliderBuilder::ball(c.radius),
        Shape::Polygon(p) => {
            if let Some(([0.0, 0.0], hw, hh)) = axis_aligned_box(p) {
                ColliderBuilder::cuboid(hw, hh)
            } else {
                let points = p.vertices().iter().map(|v| Vector::new(v.x, v.y)).collect();
                let polygon = ConvexPolygon::from_convex_polyline_unmodified(points).ok_or(
                    ManyBodyError::BodyRefused {
                        engine: ENGINE,
                        body: i,
                        message: "parry refuses the polygon as a convex polyline".into(),
                    },
                )?;
                ColliderBuilder::new(SharedShape::new(polygon))
            }
        }
    })
}

impl RapierManyWorld {
    /// Builds `scene` in a new rapier world configured as the module
    /// documentation says. Refuses an invalid scene
    /// ([`ManyBodyScene::validate`]).
    pub fn new(scene: &ManyBodyScene) -> Result<Self, ManyBodyError> {
        Self::with_threads(scene, 1)
    }

    /// [`RapierManyWorld::new`] stepping on `threads` (≥ 1) threads: rapier's
    /// `parallel` paths in a rayon pool of that many threads, made here.
    pub fn with_threads(scene: &ManyBodyScene, threads: usize) -> Result<Self, ManyBodyError> {
        crate::serial_rayon();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.max(1))
            .build()
            .map_err(|e| ManyBodyError::Engine {
                engine: ENGINE,
                message: format!("rayon pool of {threads} threads: {e}"),
            })?;
        scene.validate()?;
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::new(scene.gravity[0], scene.gravity[1]);
        world.integration_parameters = benchmark_parameters(scene);
        let mut bodies = Vec::with_capacity(scene.bodies.len());
        let groups = joints::interaction_groups(&scene.bodies)?;
        for (i, b) in scene.bodies.iter().enumerate() {
            let builder = match b.kind {
                BodyKind::Dynamic => RigidBodyBuilder::dynamic(),
                BodyKind::Static => RigidBodyBuilder::fixed(),
                BodyKind::Kinematic => RigidBodyBuilder::kinematic_velocity_based(),
            }
            .translation(Vector::new(b.position[0], b.position[1]))
            .rotation(b.angle)
            .linvel(Vector::new(b.velocity[0], b.velocity[1]))
            .angvel(b.angular_velocity)
            .can_sleep(false);
            let collider = match b.kind {
                // parry's round convex polygon takes its core's mass
                // properties, ignoring the border, and its 2D capsule's
                // inertia places each half disc's centroid 3r/8 past its
                // cap centre (the 3D hemisphere's) instead of 4r/3π: give
                // the exact ones.
                BodyKind::Dynamic
                    if holds_rounded(&b.shape, RoundedKind::RoundedPolygon)
                        || holds_rounded(&b.shape, RoundedKind::Capsule) =>
                {
                    collider(i, &b.shape)?.mass_properties(MassProperties::new(
                        Vector::ZERO,
                        b.mass(),
                        b.inertia(),
                    ))
                }
                BodyKind::Dynamic => collider(i, &b.shape)?.density(b.density),
                BodyKind::Static | BodyKind::Kinematic => collider(i, &b.shape)?
                    .mass_properties(MassProperties::new(Vector::ZERO, 0.0, 0.0)),
            }
            .friction(b.friction)
            .friction_combine_rule(CoefficientCombineRule::GeometricMean)
            .restitution(b.restitution)
            .restitution_combine_rule(CoefficientCombineRule::Max)
            .collision_groups(groups[i]);
            let (handle, _) = world.insert(builder, collider);
            bodies.push(handle);
        }
        let joint_handles = joints::build_joints(&mut world, scene, &bodies)?;
        Ok(Self {
            world,
            bodies,
            joints: joint_handles,
            steps: 0,
            pool,
        })
    }

    /// Turns contact recycling off (rapier's default is on, within 0.05 m):
    /// every pair's manifolds, and the `dist` that [`contact_counts`]
    /// reads, are then recomputed every step. For quality runs that read
    /// the engine's own separations; the benchmark keeps the default.
    ///
    /// [`contact_counts`]: ManyBodyEngine::contact_counts
    pub fn disable_contact_recycling(&mut self) {
        self.world.integration_parameters.contact_recycling = false;
    }

    /// Turns rapier's continuous collision on (or off) for body `index`
    /// (`RigidBody::enable_ccd`; off by default, the configuration above):
    /// a CCD body's motion is swept against the colliders it may cross,
    /// dynamic ones included. Returns rapier's reading of the flag after
    /// the call; `None` for an index that is not a body. For the harness's
    /// `bullet_plate` case.
    pub fn enable_ccd(&mut self, index: usize, ccd: bool) -> Option<bool> {
        let body = self.world.bodies.get_mut(*self.bodies.get(index)?)?;
        body.enable_ccd(ccd);
        Some(body.is_ccd_enabled())
    }

    /// The rapier world (for diagnostics and tests).
    pub fn world(&self) -> &PhysicsWorld {
        &self.world
    }

    /// The impulse joints of scene joint `index`: the main one, then the
    /// separate motor row if the joint has both a spring and a motor (see
    /// [`joints`]).
    pub fn joint_handles(&self, index: usize) -> &[ImpulseJointHandle] {
        &self.joints[index]
    }
}

impl ManyBodyEngine for RapierManyWorld {
    fn name(&self) -> &'static str {
        ENGINE
    }

    fn configuration(&self) -> String {
        let p = &self.world.integration_parameters;
        let s = p.num_solver_iterations;
        format!(
            "{ENGINE}, double precision (f64), single thread (no `parallel` feature). \
             dt = {dt} s with num_solver_iterations = {s} substeps (h = {h:.6} s), each \
             {pgs} biased PGS and {stab} relax iteration(s). Soft contacts: {hz} Hz, \
             damping ratio {z} ({shz} Hz, ratio {sz} against fixed bodies); push-out \
             speed at most {push} m/s; no slop in the bias; speculative contacts within \
             {pred} m; friction in the relax pass only (friction_in_bias_pass = {fb}); \
             restitution for new contacts only, no velocity threshold; warm start \
             coefficient {ws}; CCD of fast dynamic bodies against fixed colliders \
             (max_ccd_substeps = {ccd}); speed limits {vmax} m/s and (pi/4)/dt rad/s; \
             contact recycling {rec} within {recd} m; sleeping off (can_sleep(false) on \
             every body, changed from rapier's default); gravity from the scene. Mixing: \
             friction GeometricMean = sqrt(mu_a mu_b), restitution Max (both changed from \
             rapier's default Average to Box2D's rules). Impulse joints at rapier's \
             defaults: softness {jhz:e} Hz, ratio {jz} (rigid), bias in the biased pass \
             only, no joint warm starting (warmstart_joints = {wj}), limits active only \
             once violated; springs as AccelerationBased motors of stiffness (2 pi f)^2 and \
             damping 2 zeta (2 pi f) (Box2D's soft spring exactly), a spring plus a motor \
             as two impulse joints; collision groups as interaction-group bits. Every other \
             parameter at rapier's default.",
            dt = p.dt,
            h = p.dt / s as f64,
            pgs = p.num_internal_pgs_iterations,
            stab = p.num_internal_stabilization_iterations,
            hz = p.contact_softness.natural_frequency,
            z = p.contact_softness.damping_ratio,
            shz = p.static_contact_softness.natural_frequency,
            sz = p.static_contact_softness.damping_ratio,
            push = p.normalized_max_corrective_velocity * p.length_unit,
            pred = p.normalized_prediction_distance * p.length_unit,
            fb = p.friction_in_bias_pass,
            ws = p.warmstart_coefficient,
            ccd = p.max_ccd_substeps,
            vmax = p.normalized_max_linear_velocity * p.length_unit,
            rec = if p.contact_recycling { "on" } else { "off" },
            recd = p.normalized_contact_recycle_distance * p.length_unit,
            jhz = rapier2d_f64::dynamics::SpringCoefficients::<f64>::joint_defaults()
                .natural_frequency,
            jz = rapier2d_f64::dynamics::SpringCoefficients::<f64>::joint_defaults().damping_ratio,
            wj = p.warmstart_joints,
        )
    }

    fn body_count(&self) -> usize {
        self.bodies.len()
    }

    fn steps_taken(&self) -> usize {
        self.steps
    }

    fn step(&mut self) -> Result<(), ManyBodyError> {
        let world = &mut self.world;
        self.pool.install(|| world.step());
        self.steps += 1;
        if let Some(h) = self.world.quarantine().bodies().first() {
            let body = self
                .bodies
                .iter()
                .position(|b| b == h)
                .unwrap_or(usize::MAX);
            return Err(ManyBodyError::NonFinite {
                engine: ENGINE,
                body,
                steps: self.steps,
            });
        }
        Ok(())
    }

    fn samples(&mut self, out: &mut Vec<BodySample>) -> Result<(), ManyBodyError> {
        out.clear();
        for (i, h) in self.bodies.iter().enumerate() {
            let rb = &self.world.bodies[*h];
            let (p, v) = (rb.translation(), rb.linvel());
            let s = BodySample {
                position: [p.x, p.y],
                angle: rb.rotation().angle(),
                velocity: [v.x, v.y],
                angular_velocity: rb.angvel(),
            };
            let finite = s.position.iter().chain(&s.velocity).all(|x| x.is_finite())
                && s.angle.is_finite()
                && s.angular_velocity.is_finite();
            if !finite {
                return Err(ManyBodyError::NonFinite {
                    engine: ENGINE,
                    body: i,
                    steps: self.steps,
                });
            }
            out.push(s);
        }
        Ok(())
    }

    fn mass_properties(&mut self) -> Result<Vec<BodyMass>, ManyBodyError> {
        Ok(self
            .bodies
            .iter()
            .map(|h| {
                let rb = &self.world.bodies[*h];
                if rb.is_dynamic() {
                    BodyMass {
                        mass: rb.mass(),
                        inertia: rb.mass_properties().local_mprops.principal_inertia(),
                    }
                } else {
                    BodyMass::default()
                }
            })
            .collect())
    }

    /// From the narrow phase: every contact pair's solver manifolds (the
    /// points the solver used in the last step, speculative ones within the
    /// prediction distance included) and their `dist`. With contact
    /// recycling, `dist` is that of the pair's last full update, up to
    /// 0.05 m of relative motion ago (rapier re-derives the live separation
    /// inside its solver and does not write it back).
    fn contact_counts(&mut self) -> Result<ContactCounts, ManyBodyError> {
        let mut counts = ContactCounts::default();
        let mut deepest = 0.0_f64;
        for pair in self.world.narrow_phase.contact_pairs() {
            let points: usize = pair
                .solver_manifolds()
                .iter()
                .map(|m| m.data.solver_contacts.len())
                .sum();
            if points == 0 {
                continue;
            }
            counts.touching_pairs += 1;
            counts.points += points;
            for m in pair.solver_manifolds() {
                for c in &m.data.solver_contacts {
                    if c.dist < 0.0 {
                        counts.penetrating_points += 1;
                        deepest = deepest.max(-c.dist);
                    }
                }
            }
        }
        counts.deepest_penetration = deepest;
        Ok(counts)
    }
}

#[cfg(test)]
mod tests;
