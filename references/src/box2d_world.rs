//! Box2D v3.2 (Erin Catto's C library, through the `boxdd` 0.6 bindings,
//! which vendor and compile its sources) running a [`ManyBodyScene`], for
//! the many-body benchmark: the engine whose soft-step solver the project's
//! own solver follows.
//!
//! # Configuration (read in the vendored 3.2 sources: `src/types.c`
//! `b2DefaultWorldDef`, `src/physics_world.c`, `src/contact_solver.c`,
//! `include/box2d/constants.h`; and boxdd's `core/native_defaults.rs`)
//!
//! World, at Box2D's defaults except the first two:
//! - gravity = the scene's (default (0, −10) m/s²);
//! - sleeping **off** (`enableSleep`, default on): every body is simulated
//!   every step, as the benchmark protocol requires;
//! - one thread: boxdd's default `workerCount` is 1, for which Box2D takes
//!   its serial path (`b2DefaultAddTaskFcn`, no scheduler, no task system);
//! - contact hertz 30 Hz, damping ratio 10 (`contactHertz`,
//!   `contactDampingRatio`). The hertz used is min(30, 0.125/h) with
//!   h = dt/substeps (30 Hz at 4 substeps of 1/60 s); contacts with a static
//!   body use twice that (`staticSoftness`, 60 Hz), contacts with a
//!   kinematic body do not (it is in the awake set: 30 Hz);
//! - push-out speed at most 3 m/s (`contactSpeed`);
//! - restitution threshold 1 m/s (`restitutionThreshold`: a contact bounces
//!   only if it approached faster than that);
//! - maximum linear speed 400 m/s; angular speed clamped to (π/4)/dt
//!   (`B2_MAX_ROTATION`) unless a body allows fast rotation (none does);
//! - continuous collision on (`enableContinuous`): fast dynamic bodies are
//!   swept against static ones; no body is a bullet;
//! - warm starting on; contact softening off (`enableContactSoftening`);
//! - speculative distance 4 × linear slop = 0.02 m; linear slop 0.005 m;
//! - contact recycling on: a pair whose relative pose moved less than
//!   10 × linear slop = 0.05 m since its last full update keeps its
//!   manifold, separations updated from the bodies' motion.
//!
//! Bodies: `b2BodyDef` defaults (no damping, gravity scale 1) with the
//! scene's type, position, angle, velocity and angular velocity, and
//! per-body sleeping off too. Kinematic bodies move at their velocity.
//!
//! Shapes (one per body, `b2ShapeDef` defaults otherwise): density, friction
//! and restitution from the scene (Box2D mixes them per pair as friction
//! √(μa μb) and restitution max(ea, eb), its default callbacks); a circle
//! becomes a `b2Circle` at the body origin; an axis-aligned rectangle a
//! `b2MakeBox` (centred), and any other rectangle `b2MakeOffsetBox`
//! (half extents, centre and angle: a 2 mm card of Box2D's own Card House
//! sample is taken, which its hull would refuse); any other polygon a
//! `b2MakePolygon` of the hull of its vertices (radius 0). Box2D takes at
//! most 8 vertices and welds points closer than 0.005 m: a polygon it would
//! change is refused rather than silently altered. A body's
//! `collision_group` g becomes the filter group index −(g + 1) on each of
//! its shapes (shapes sharing a negative group index never collide), the
//! category and mask bits staying at Box2D's defaults.
//!
//! Joints: see [`joints`] (every joint setting, what is changed from
//! Box2D's defaults, how the world is attached).
//!
//! # Precision
//!
//! boxdd's default build is single precision: positions, rotations,
//! velocities, masses and impulses are `f32` (its double-precision build,
//! this crate's `box2d-double` feature, keeps absolute positions in f64,
//! which are then passed unrounded). The scene's f64 values are
//! rounded to the nearest f32 (relative error 2⁻²⁴ ≈ 6e-8); a position of
//! 100 m is thus held to about 8 µm. Values are read back as f64 without
//! further loss.
//!
//! # Build
//!
//! Box2D as it ships its release build: the workspace's
//! `.cargo/config.toml` appends `-O3 -DNDEBUG` to boxdd-sys's `-O2
//! -std=c17 -ffp-contract=off` (so Box2D's assertions are compiled out),
//! and this crate's default `box2d-avx2` feature takes Box2D's AVX2 path;
//! [`build`] reads which build is linked and checks that the CPU can run
//! it before any Box2D call (an AVX2 build refuses to start on a CPU
//! without AVX2 rather than stop on an illegal instruction). In debug and
//! test builds boxdd-sys compiles at -O0, the appended flags still apply.

use crate::many_body::{
    BodyKind, BodyMass, BodySample, ContactCounts, ManyBodyEngine, ManyBodyError, ManyBodyScene,
    axis_aligned_box,
};
use boxdd::{
    BodyId, BodyType, Filter, Foundation, JointId, Polygon, ShapeDef, ShapeId, SurfaceMaterial,
    World, shapes,
};
use engine::{ConvexPolygon, RoundedKind, Shape};

/// Engine name used in errors and reports.
const ENGINE: &str = "Box2D 3.2 (boxdd 0.6)";

/// Box2D's largest polygon vertex count (`B2_MAX_POLYGON_VERTICES`).
pub const MAX_POLYGON_VERTICES: usize = 8;

/// Box2D's defaults, as read in the vendored sources (see the module
/// documentation); printed by [`Box2dWorld::configuration`] and checked
/// against the world definition by the tests.
pub mod defaults {
    /// `contactHertz`, Hz.
    pub const CONTACT_HERTZ: f64 = 30.0;
    /// `contactDampingRatio`.
    pub const CONTACT_DAMPING_RATIO: f64 = 10.0;
    /// `contactSpeed`, m/s: the largest push-out speed.
    pub const CONTACT_SPEED: f64 = 3.0;
    /// `restitutionThreshold`, m/s.
    pub const RESTITUTION_THRESHOLD: f64 = 1.0;
    /// `maximumLinearSpeed`, m/s.
    pub const MAXIMUM_LINEAR_SPEED: f64 = 400.0;
    /// `B2_LINEAR_SLOP`, m.
    pub const LINEAR_SLOP: f64 = 0.005;
    /// `B2_SPECULATIVE_DISTANCE` = 4 × slop, m.
    pub const SPECULATIVE_DISTANCE: f64 = 4.0 * LINEAR_SLOP;
    /// `B2_CONTACT_RECYCLE_DISTANCE` = 10 × slop, m.
    pub const CONTACT_RECYCLE_DISTANCE: f64 = 10.0 * LINEAR_SLOP;
}

fn engine_error(e: boxdd::Error) -> ManyBodyError {
    ManyBodyError::Engine {
        engine: ENGINE,
        message: e.to_string(),
    }
}

fn refused(body: usize, message: impl Into<String>) -> ManyBodyError {
    ManyBodyError::BodyRefused {
        engine: ENGINE,
        body,
        message: message.into(),
    }
}

/// `x` rounded to f32, refused if it does not fit (Box2D's single precision).
fn to_f32(body: usize, field: &'static str, x: f64) -> Result<f32, ManyBodyError> {
    let y = x as f32;
    if y.is_finite() {
        Ok(y)
    } else {
        Err(ManyBodyError::body(
            body,
            field,
            x,
            "is beyond Box2D's single-precision range",
        ))
    }
}

/// An absolute coordinate `x` in Box2D's world scalar (f32, or f64 in its
/// double-precision build), refused if it does not fit.
fn to_world(body: usize, field: &'static str, x: f64) -> Result<boxdd::WorldScalar, ManyBodyError> {
    #[allow(clippy::unnecessary_cast)] // f64 as f64 in the double-precision build
    let y = x as boxdd::WorldScalar;
    if y.is_finite() {
        Ok(y)
    } else {
        Err(ManyBodyError::body(
            body,
            field,
            x,
            "is beyond Box2D's single-precision range",
        ))
    }
}

/// A scene-wide `x` rounded to f32, refused if it does not fit.
fn scene_f32(field: &'static str, x: f64) -> Result<f32, ManyBodyError> {
    let y = x as f32;
    if y.is_finite() {
        Ok(y)
    } else {
        Err(ManyBodyError::scene(
            field,
            x,
            "is beyond Box2D's single-precision range",
        ))
    }
}

pub mod build;
pub mod joints;
pub mod log;
pub mod profile;
mod ray;

/// A [`ManyBodyScene`] in a Box2D world.
pub struct Box2dWorld {
    world: World,
    bodies: Vec<BodyId>,
    shapes: Vec<ShapeId>,
    joints: Vec<JointId>,
    dt: f32,
    substeps: i32,
    steps: usize,
}

impl Box2dWorld {
    /// Builds `scene` in a new Box2D world configured as the module
    /// documentation says. Refuses an invalid scene
    /// ([`ManyBodyScene::validate`]), values beyond f32's range, and
    /// polygons Box2D cannot hold unchanged.
    pub fn new(scene: &ManyBodyScene) -> Result<Self, ManyBodyError> {
        Self::with_workers(scene, 1)
    }

    /// [`Box2dWorld::new`] with `workers` (1 to 32) threads: above one,
    /// boxdd's `worker_count` starts the built-in scheduler of the Box2D
    /// revision it vendors (its task system, workers meeting at the
    /// solver's stages).
    pub fn with_workers(scene: &ManyBodyScene, workers: usize) -> Result<Self, ManyBodyError> {
        scene.validate()?;
        // Before any Box2D call: an AVX2 build would stop on its first AVX2
        // instruction on a CPU without it.
        build::Box2dBuild::linked()
            .runnable()
            .map_err(|message| ManyBodyError::Engine {
                engine: ENGINE,
                message,
            })?;
        let foundation = Foundation::initialize(log::config()).map_err(engine_error)?;
        let gravity = [
            scene_f32("gravity x", scene.gravity[0])?,
            scene_f32("gravity y", scene.gravity[1])?,
        ];
        let dt = scene_f32("dt", scene.dt)?;
        if dt <= 0.0 {
            return Err(ManyBodyError::scene(
                "dt",
                scene.dt,
                "rounds to 0 in Box2D's single precision",
            ));
        }
        let def = foundation
            .world_builder()
            .gravity(gravity)
            .enable_sleep(false)
            .worker_count(
                boxdd::WorkerCount::new(u32::try_from(workers).unwrap_or(u32::MAX))
                    .map_err(engine_error)?,
            )
            .build()
            .map_err(engine_error)?;
        let mut world = foundation.create_world(def).map_err(engine_error)?;
        let mut bodies = Vec::with_capacity(scene.bodies.len());
        let mut shape_ids = Vec::with_capacity(scene.bodies.len());
        for (i, b) in scene.bodies.iter().enumerate() {
            let body_type = match b.kind {
                BodyKind::Dynamic => BodyType::Dynamic,
                BodyKind::Static => BodyType::Static,
                BodyKind::Kinematic => BodyType::Kinematic,
            };
            let position = [
                to_world(i, "position x", b.position[0])?,
                to_world(i, "position y", b.position[1])?,
            ];
            let velocity = [
                to_f32(i, "velocity x", b.velocity[0])?,
                to_f32(i, "velocity y", b.velocity[1])?,
            ];
            let def = world
                .body_builder()
                .body_type(body_type)
                .position(position)
                .angle(to_f32(i, "angle", b.angle)?)
                .linear_velocity(velocity)
                .angular_velocity(to_f32(i, "angular velocity", b.angular_velocity)?)
                .enable_sleep(false)
                .build()
                .map_err(|e| refused(i, e.to_string()))?;
            let id = world
                .create_body(def)
                .map_err(|e| refused(i, e.to_string()))?;
            if b.kind == BodyKind::Dynamic {
                let (mass, inertia) = (b.mass() as f32, b.inertia() as f32);
                if !(mass.is_normal() && inertia.is_normal()) {
                    return Err(refused(
                        i,
                        format!(
                            "its mass {} kg or moment of inertia {} kg·m² is outside \
                             Box2D's single-precision range",
                            b.mass(),
                            b.inertia()
                        ),
                    ));
                }
            }
            let restitution = to_f32(i, "restitution", b.restitution)?;
            let material = SurfaceMaterial::default()
                .with_friction(to_f32(i, "friction", b.friction)?)
                .and_then(|m| m.with_restitution(restitution))
                .map_err(|e| refused(i, e.to_string()))?;
            let filter = Filter {
                group_index: joints::group_index(i, b.collision_group)?,
                ..Filter::default()
            };
            let shape_def = ShapeDef::builder()
                .density(to_f32(i, "density", b.density)?)
                .material(material)
                .filter(filter)
                .build()
                .map_err(|e| refused(i, e.to_string()))?;
            if let Shape::Chain(chain) = &b.shape {
                // Box2D's own chain: the same points, the same ghost
                // convention (its segments are shapes of the body).
                let points = chain
                    .points()
                    .iter()
                    .map(|p| Ok([to_f32(i, "chain x", p.x)?, to_f32(i, "chain y", p.y)?]))
                    .collect::<Result<Vec<[f32; 2]>, ManyBodyError>>()?;
                let def = boxdd::shapes::chain::ChainDef::builder()
                    .points(points)
                    .is_loop(chain.is_loop())
                    .filter(filter)
                    .single_material(&material)
                    .build()
                    .map_err(|e| refused(i, e.to_string()))?;
                let chain_id = world
                    .body(id)
                    .map_err(engine_error)?
                    .create_chain(&def)
                    .map_err(|e| refused(i, e.to_string()))?;
                let segments = world
                    .chain(chain_id)
                    .map_err(engine_error)?
                    .segments()
                    .map_err(engine_error)?;
                bodies.push(id);
                shape_ids.push(
                    *segments
                        .first()
                        .ok_or_else(|| refused(i, "Box2D made no segment"))?,
                );
                continue;
            }
            let mut body = world.body(id).map_err(engine_error)?;
            // A compound becomes one Box2D shape per part, each placed in
            // the body frame (Box2D bodies take several shapes).
            let mut first = None;
            for (offset, angle, piece) in b.shape.pieces() {
                let place = |v: nalgebra::Vector2<f64>| {
                    let (s, c) = angle.sin_cos();
                    offset + nalgebra::Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
                };
                let shape = match piece {
                    Shape::Circle(c) => {
                        let centre = [
                            to_f32(i, "circle x", offset.x)?,
                            to_f32(i, "circle y", offset.y)?,
                        ];
                        let circle = shapes::circle(centre, to_f32(i, "radius", c.radius)?)
                            .map_err(|e| refused(i, e.to_string()))?;
                        body.create_circle(&shape_def, &circle)
                    }
                    Shape::Polygon(p) => {
                        let placed = if offset == nalgebra::Vector2::zeros() && angle == 0.0 {
                            p.clone()
                        } else {
                            ConvexPolygon::new(p.vertices().iter().map(|&v| place(v)).collect())
                                .map_err(|e| refused(i, e.to_string()))?
                        };
                        body.create_polygon(&shape_def, &polygon(i, &placed)?)
                    }
                    Shape::Compound(_) | Shape::Chain(_) => {
                        unreachable!("a compound's pieces are polygons and circles")
                    }
                    // Box2D's own kinds. Its mass of a rounded polygon is
                    // an approximation (b2ComputePolygonMass pushes each
                    // core vertex out by 1.412 r along its corner's
                    // bisector), replaced below by the exact one.
                    Shape::Rounded(r) => {
                        let mut ends = Vec::with_capacity(r.core().len());
                        for &v in r.core() {
                            let v = place(v);
                            ends.push([to_f32(i, "vertex x", v.x)?, to_f32(i, "vertex y", v.y)?]);
                        }
                        let radius = to_f32(i, "radius", r.radius())?;
                        match r.kind() {
                            RoundedKind::Segment => {
                                let segment = shapes::segment(ends[0], ends[1])
                                    .map_err(|e| refused(i, e.to_string()))?;
                                body.create_segment(&shape_def, &segment)
                            }
                            RoundedKind::Capsule => {
                                let capsule = shapes::capsule(ends[0], ends[1], radius)
                                    .map_err(|e| refused(i, e.to_string()))?;
                                body.create_capsule(&shape_def, &capsule)
                            }
                            RoundedKind::RoundedPolygon => {
                                let n = ends.len();
                                let polygon = shapes::polygon_from_points(ends, radius)
                                    .map_err(|e| refused(i, e.to_string()))?;
                                if polygon.count() != n {
                                    return Err(refused(
                                        i,
                                        format!(
                                            "Box2D's hull kept {} of the rounded polygon's {n} \
                                             core vertices",
                                            polygon.count()
                                        ),
                                    ));
                                }
                                body.create_polygon(&shape_def, &polygon)
                            }
                        }
                    }
                }
                .map_err(|e| refused(i, e.to_string()))?;
                first.get_or_insert(shape);
            }
            // Box2D's mass of a rounded polygon approximates the rounding
            // (its core pushed out by the radius); the body gets the
            // scene's exact mass and inertia instead, so a comparison
            // measures the contact dynamics, not that approximation.
            if b.kind == BodyKind::Dynamic
                && crate::many_body::holds_rounded(&b.shape, RoundedKind::RoundedPolygon)
            {
                let data = boxdd::MassData::new(
                    b.mass() as f32,
                    boxdd::Vec2::new(0.0, 0.0),
                    b.inertia() as f32,
                )
                .map_err(|e| refused(i, e.to_string()))?;
                body.set_mass_data(data)
                    .map_err(|e| refused(i, e.to_string()))?;
            }
            bodies.push(id);
            shape_ids.push(first.expect("every shape has at least one piece"));
        }
        let (joint_ids, _ground) = joints::build_joints(&mut world, scene, &bodies)?;
        Ok(Self {
            world,
            bodies,
            shapes: shape_ids,
            joints: joint_ids,
            dt,
            substeps: scene.substeps as i32,
            steps: 0,
        })
    }

    /// Turns contact recycling off (Box2D's default is on, within
    /// [`defaults::CONTACT_RECYCLE_DISTANCE`]): every touching pair's
    /// manifold is then recomputed every step. For quality runs that read
    /// the engine's own separations; the benchmark keeps the default.
    pub fn disable_contact_recycling(&mut self) -> Result<(), ManyBodyError> {
        self.world
            .set_contact_recycle_distance(0.0)
            .map_err(engine_error)
    }

    /// Makes body `index` a bullet (or not), `b2Body_SetBullet`: a fast
    /// dynamic bullet is swept against the dynamic bodies too
    /// (`b2SolveContinuous`), not only the static ones (the configuration
    /// above has none). Returns Box2D's own reading of the flag after the
    /// call. For the harness's `bullet_plate` case.
    pub fn set_bullet(&mut self, index: usize, bullet: bool) -> Result<bool, ManyBodyError> {
        let id = *self
            .bodies
            .get(index)
            .ok_or_else(|| refused(index, "no such body"))?;
        let mut body = self.world.body(id).map_err(engine_error)?;
        body.set_bullet(bullet).map_err(engine_error)?;
        body.is_bullet().map_err(engine_error)
    }

    /// Box2D's own reading of joint `index`: `b2Joint_GetLinearSeparation`
    /// (m) and `b2Joint_GetAngularSeparation` (rad), from its f32 state
    /// (for diagnostics; the comparison between engines uses
    /// [`ManyBodyScene::joint_states`] on the poses instead).
    pub fn joint_separations(&mut self, index: usize) -> Result<(f64, f64), ManyBodyError> {
        let id = *self.joints.get(index).ok_or(ManyBodyError::Engine {
            engine: ENGINE,
            message: format!("no joint {index}"),
        })?;
        let joint = self.world.joint(id).map_err(engine_error)?;
        Ok((
            joint.linear_separation().map_err(engine_error)? as f64,
            joint.angular_separation().map_err(engine_error)? as f64,
        ))
    }

    /// Box2D's own timers of its last step (ms, [`profile::FIELDS`]; see
    /// [`profile`] for what each times and how they nest).
    pub fn last_step_profile(&self) -> Result<[(&'static str, f64); 23], ManyBodyError> {
        let p = self.world.profile().map_err(engine_error)?;
        Ok(profile::fields(&p))
    }

    /// The world's settings as Box2D reports them (read back from the
    /// world, not from this adapter's constants).
    pub fn world_settings(&self) -> Result<WorldSettings, ManyBodyError> {
        let w = &self.world;
        Ok(WorldSettings {
            restitution_threshold: w.restitution_threshold().map_err(engine_error)? as f64,
            maximum_linear_speed: w.maximum_linear_speed().map_err(engine_error)? as f64,
            sleeping: w.is_sleeping_enabled().map_err(engine_error)?,
            continuous: w.is_continuous_enabled().map_err(engine_error)?,
            warm_starting: w.is_warm_starting_enabled().map_err(engine_error)?,
            workers: w.worker_count().map_err(engine_error)?.get() as usize,
            contact_recycle_distance: w.contact_recycle_distance().map_err(engine_error)? as f64,
        })
    }

    /// The Box2D shape of body `index`, as Box2D holds it (for tests and
    /// diagnostics): a circle's radius, or a polygon's vertices in the body
    /// frame (m, f32 values widened).
    pub fn shape_geometry(&mut self, index: usize) -> Result<ShapeGeometry, ManyBodyError> {
        let id = *self.shapes.get(index).ok_or(ManyBodyError::Engine {
            engine: ENGINE,
            message: format!("no body {index}"),
        })?;
        let shape = self.world.shape(id).map_err(engine_error)?;
        match shape.shape_type().map_err(engine_error)? {
            boxdd::ShapeType::Circle => {
                let c = shape.circle().map_err(engine_error)?;
                Ok(ShapeGeometry::Circle {
                    radius: c.radius() as f64,
                })
            }
            boxdd::ShapeType::Polygon => {
                let p = shape.polygon().map_err(engine_error)?;
                Ok(ShapeGeometry::Polygon {
                    vertices: p
                        .vertices()
                        .iter()
                        .map(|v| [v.x as f64, v.y as f64])
                        .collect(),
                })
            }
            other => Err(ManyBodyError::Engine {
                engine: ENGINE,
                message: format!("unexpected shape type {other:?}"),
            }),
        }
    }
}

/// Box2D's world settings as it reports them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldSettings {
    /// m/s.
    pub restitution_threshold: f64,
    /// m/s.
    pub maximum_linear_speed: f64,
    /// Whether bodies may sleep.
    pub sleeping: bool,
    /// Whether fast bodies are swept against static ones.
    pub continuous: bool,
    /// Whether impulses carry over between steps.
    pub warm_starting: bool,
    /// Worker count (1: serial).
    pub workers: usize,
    /// m (0 disables recycling).
    pub contact_recycle_distance: f64,
}

/// A shape as an engine holds it.
#[derive(Debug, Clone, PartialEq)]
pub enum ShapeGeometry {
    /// A circle centred on the body origin.
    Circle {
        /// m.
        radius: f64,
    },
    /// A convex polygon, vertices in the body frame (m), in the engine's
    /// order.
    Polygon {
        /// m.
        vertices: Vec<[f64; 2]>,
    },
}

/// Box2D's polygon for a polygon body shape: `b2MakeBox` for a centred
/// axis-aligned rectangle (Box2D's benchmark boxes, exact to f32),
/// `b2MakeOffsetBox` for any other rectangle ([`rectangle`]: half extents,
/// centre and angle, as Box2D's own samples build boxes, so no hull welds a
/// thin card), the hull of the vertices otherwise, refused if the hull
/// drops a vertex.
fn polygon(i: usize, p: &ConvexPolygon) -> Result<Polygon, ManyBodyError> {
    if let Some((centre, hw, hh)) = axis_aligned_box(p)
        && centre == [0.0, 0.0]
    {
        return shapes::box_polygon(to_f32(i, "half width", hw)?, to_f32(i, "half height", hh)?)
            .map_err(|e| refused(i, e.to_string()));
    }
    if let Some(r) = rectangle(p) {
        let transform = boxdd::Transform::from_pos_angle(
            [
                to_f32(i, "box centre x", r.centre[0])?,
                to_f32(i, "box centre y", r.centre[1])?,
            ],
            to_f32(i, "box angle", r.angle)?,
        )
        .map_err(|e| refused(i, e.to_string()))?;
        return shapes::offset_box_polygon(
            to_f32(i, "half width", r.half_width)?,
            to_f32(i, "half height", r.half_height)?,
            transform,
        )
        .map_err(|e| refused(i, e.to_string()));
    }
    let n = p.vertices().len();
    if n > MAX_POLYGON_VERTICES {
        return Err(refused(
            i,
            format!("a polygon of {n} vertices (Box2D takes at most {MAX_POLYGON_VERTICES})"),
        ));
    }
    let mut points = Vec::with_capacity(n);
    for v in p.vertices() {
        points.push([to_f32(i, "vertex x", v.x)?, to_f32(i, "vertex y", v.y)?]);
    }
    let poly = shapes::polygon_from_points(points, 0.0).map_err(|e| {
        refused(
            i,
            format!(
                "Box2D's hull of the {n} vertices failed ({e}); it welds points closer \
                 than 0.005 m and drops collinear ones"
            ),
        )
    })?;
    if poly.count() != n {
        return Err(refused(
            i,
            format!(
                "Box2D's hull kept {} of the {n} vertices (it welds points closer than \
                 0.005 m and drops nearly collinear ones)",
                poly.count()
            ),
        ));
    }
    Ok(poly)
}

/// A rectangle given by its half extents, centre and angle (the arguments
/// of Box2D's `b2MakeOffsetBox`).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Rectangle {
    centre: [f64; 2],
    angle: f64,
    half_width: f64,
    half_height: f64,
}

/// `p` as a rectangle of any orientation, if it is one: four vertices whose
/// corners are right angles and whose opposite sides are equal, both to a
/// relative 1e-9 (a million times finer than the f32 rounding Box2D makes
/// of every vertex anyway, so no shape that is not a rectangle to f32 is
/// taken for one). The first edge gives the angle and the width.
fn rectangle(p: &ConvexPolygon) -> Option<Rectangle> {
    const RELATIVE: f64 = 1e-9;
    let v = p.vertices();
    if v.len() != 4 {
        return None;
    }
    let edge = |k: usize| v[(k + 1) % 4] - v[k];
    for k in 0..4 {
        let (a, b) = (edge(k), edge((k + 1) % 4));
        if a.dot(&b).abs() > RELATIVE * a.norm() * b.norm() {
            return None;
        }
    }
    let (e0, e1) = (edge(0), edge(1));
    let (w, h) = (e0.norm(), e1.norm());
    if (w - edge(2).norm()).abs() > RELATIVE * w || (h - edge(3).norm()).abs() > RELATIVE * h {
        return None;
    }
    let centre = (v[0] + v[1] + v[2] + v[3]) / 4.0;
    Some(Rectangle {
        centre: [centre.x, centre.y],
        angle: e0.y.atan2(e0.x),
        half_width: 0.5 * w,
        half_height: 0.5 * h,
    })
}

impl ManyBodyEngine for Box2dWorld {
    fn name(&self) -> &'static str {
        ENGINE
    }

    fn configuration(&self) -> String {
        use defaults::*;
        let h = self.dt as f64 / self.substeps as f64;
        let hertz = CONTACT_HERTZ.min(0.125 / h);
        format!(
            "{ENGINE}, {precision}, \
             {workers}. dt = {dt} s with {s} substeps \
             (h = {h:.6} s). Soft contacts: {hertz:.3} Hz (min of contactHertz \
             {CONTACT_HERTZ} and 0.125/h; also against kinematic bodies), {shz:.3} Hz against \
             static bodies, damping ratio \
             {CONTACT_DAMPING_RATIO}; push-out speed at most {CONTACT_SPEED} m/s; no \
             slop in the bias; speculative contacts within {SPECULATIVE_DISTANCE} m; \
             friction solved in the relax pass only; restitution threshold \
             {RESTITUTION_THRESHOLD} m/s; warm starting on; continuous collision on \
             (fast dynamic vs static, no bullets); speed limits {MAXIMUM_LINEAR_SPEED} \
             m/s and (pi/4)/dt rad/s; contact recycling within \
             {CONTACT_RECYCLE_DISTANCE} m; sleeping off (changed from Box2D's default); \
             gravity from the scene. Mixing: friction sqrt(mu_a mu_b), restitution \
             max(e_a, e_b). Joints at Box2D's defaults: soft rows of min(60, 0.25/h) Hz, \
             damping ratio 2, in the biased pass, rigid in the relax pass, warm started, \
             speculative limits; angles measured with Box2D's approximate atan2.",
            dt = self.dt,
            s = self.substeps,
            shz = 2.0 * hertz,
            workers = match self.world.worker_count().map_or(1, |w| w.get()) {
                1 => "serial (one worker, no task system)".to_string(),
                n => format!(
                    "{n} workers (Box2D's built-in scheduler, through boxdd's worker_count)"
                ),
            },
            precision = if build::Box2dBuild::linked().precision == "f32" {
                "single precision (f32 positions, velocities and impulses)"
            } else {
                "its double-precision build (f64 absolute positions; f32 velocities, \
                 rotations and impulses)"
            },
        )
    }

    fn body_count(&self) -> usize {
        self.bodies.len()
    }

    fn steps_taken(&self) -> usize {
        self.steps
    }

    fn step(&mut self) -> Result<(), ManyBodyError> {
        let completed = self
            .world
            .step(self.dt, self.substeps)
            .map_err(engine_error)?;
        let late = completed.post_step_error();
        drop(completed);
        self.steps += 1;
        match late {
            None => Ok(()),
            Some(e) => Err(engine_error(e)),
        }
    }

    fn samples(&mut self, out: &mut Vec<BodySample>) -> Result<(), ManyBodyError> {
        out.clear();
        for (i, &id) in self.bodies.iter().enumerate() {
            let body = self.world.body(id).map_err(engine_error)?;
            let p = body.position().map_err(engine_error)?;
            let q = body.rotation().map_err(engine_error)?;
            let v = body.linear_velocity().map_err(engine_error)?;
            let w = body.angular_velocity().map_err(engine_error)?;
            let s = BodySample {
                position: [p.x as f64, p.y as f64],
                angle: q.angle() as f64,
                velocity: [v.x as f64, v.y as f64],
                angular_velocity: w as f64,
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
        let mut out = Vec::with_capacity(self.bodies.len());
        for &id in &self.bodies {
            let body = self.world.body(id).map_err(engine_error)?;
            out.push(BodyMass {
                mass: body.mass().map_err(engine_error)? as f64,
                inertia: body.rotational_inertia().map_err(engine_error)? as f64,
            });
        }
        Ok(out)
    }

    /// Through `b2Body_GetContactData` of every body: the contacts Box2D
    /// flags as touching (manifold with at least one point, speculative
    /// points included). Each contact is listed by both its bodies; it is
    /// counted once, by the body owning its shape A.
    fn contact_counts(&mut self) -> Result<ContactCounts, ManyBodyError> {
        let mut counts = ContactCounts::default();
        let mut deepest = 0.0_f64;
        for (&id, &shape) in self.bodies.iter().zip(&self.shapes) {
            let body = self.world.body(id).map_err(engine_error)?;
            for c in body.contact_data().map_err(engine_error)? {
                if c.shape_id_a != shape {
                    continue;
                }
                let points = c.manifold.points();
                if points.is_empty() {
                    continue;
                }
                counts.touching_pairs += 1;
                counts.points += points.len();
                for p in points {
                    if p.separation < 0.0 {
                        counts.penetrating_points += 1;
                        deepest = deepest.max(-(p.separation as f64));
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
