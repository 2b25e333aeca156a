//! Validation of a parsed [`SceneFile`] and its conversion into engine
//! values ([`Plan`]), then into an [`engine::World`].
//!
//! Validation runs once, when the scene is loaded, and checks everything
//! the engine would refuse and more, so that [`crate::Scene::build_world`]
//! cannot fail on a loaded scene except for a bad method override:
//!
//! 1. `[simulation]`: a known method id, dt > 0, duration > 0, at most
//!    [`engine::MAX_RUN_STEPS`] steps, tolerance > 0;
//! 2. `[[bodies]]`: unique names, mass xor density (> 0), inertia > 0,
//!    shapes (boxes and circles > 0, polygons simple and counter-clockwise,
//!    checked and cut into convex parts by [`Shape::simple_polygon`],
//!    compounds of such parts), static bodies without mass or
//!    velocity, particles without rotation, colours `#rrggbb`;
//! 3. `[[forces]]` and `[[events]]`: every body name defined, parameters in
//!    their domain, windows with `end > start`, no force on static bodies
//!    only, no torque on a particle (in [`crate::forces`]);
//! 4. `[contact]` and `[linear_test]`: in their domain; a `[contact]` table
//!    turns the world's contact handling on.
//!
//! Every number is checked finite first: TOML allows `nan` and `inf`.

use crate::colour::Colour;
use crate::error::{ErrorKind, FieldPath, Problem};
use crate::format::{
    BodyKindSpec, BodySpec, ContactModelSpec, ContactSpec, DEFAULT_METHOD, DEFAULT_TOLERANCE,
    FilterSpec, LinearTestSpec, MixingSpec, PartSpec, SceneFile, ShapeSpec, ToiMethodSpec, Window,
    Xy,
};
use crate::linear_test::LinearTest;
use engine::error::readable;
use engine::forces::{AngularDrag, Gravity, PointForce, QuadraticDrag, Spring, TimeWindow, Torque};
use engine::{
    BodyDef, BodyKind, BodyState, Circle, Compound, CompoundPart, ContactModel, ContactSettings,
    EventSpec, Force, MAX_RUN_STEPS, Method, RoundedConvex, Shape, SoftStepSettings, ToiMethod,
    Tolerance, World,
};
use nalgebra::Vector2;

pub(crate) type Checked<T> = Result<T, Problem>;

/// A validated scene, in engine values.
#[derive(Debug, Clone)]
pub(crate) struct Plan {
    pub(crate) method: Method,
    pub(crate) tolerance: Tolerance,
    pub(crate) dt: f64,
    pub(crate) duration: f64,
    pub(crate) steps: u64,
    pub(crate) content: Content,
}

/// What the scene simulates.
#[derive(Debug, Clone)]
pub(crate) enum Content {
    World(Box<WorldPlan>),
    LinearTest(LinearTest),
}

/// A world's bodies, forces and events, ready to add.
#[derive(Debug, Clone)]
pub(crate) struct WorldPlan {
    pub(crate) bodies: Vec<BodyDef>,
    pub(crate) colours: Vec<Colour>,
    pub(crate) forces: Vec<PlannedForce>,
    pub(crate) events: Vec<EventSpec>,
    /// The file's joints, then the generators'.
    pub(crate) joints: Vec<crate::joints::PlannedJoint>,
    pub(crate) contact: Option<ContactModel>,
    pub(crate) gravity: Option<Vector2<f64>>,
}

/// One force with its window and where the file defines it.
#[derive(Debug, Clone)]
pub(crate) struct PlannedForce {
    pub(crate) force: EngineForce,
    pub(crate) window: TimeWindow,
    pub(crate) path: FieldPath,
}

/// The engine's force types are `Copy`; a world takes them boxed, so the
/// plan keeps them unboxed and boxes a fresh copy per world built.
#[derive(Debug, Clone, Copy)]
pub(crate) enum EngineForce {
    Gravity(Gravity),
    Spring(Spring),
    Drag(QuadraticDrag),
    AngularDrag(AngularDrag),
    PointForce(PointForce),
    Torque(Torque),
}

impl EngineForce {
    pub(crate) fn boxed(self) -> Box<dyn Force> {
        match self {
            EngineForce::Gravity(f) => Box::new(f),
            EngineForce::Spring(f) => Box::new(f),
            EngineForce::Drag(f) => Box::new(f),
            EngineForce::AngularDrag(f) => Box::new(f),
            EngineForce::PointForce(f) => Box::new(f),
            EngineForce::Torque(f) => Box::new(f),
        }
    }
}

/// The number of steps [`engine::World::run`] takes over `duration` with
/// `dt` ([`engine::step_count`]), with its refusal as a plain reason.
pub(crate) fn step_count(duration: f64, dt: f64) -> Result<u64, &'static str> {
    engine::step_count(duration, dt).map_err(|e| match e {
        engine::EngineError::InvalidParameter { reason, .. } => reason,
        _ => "invalid step count",
    })
}

/// Validates `file` and converts it.
pub(crate) fn plan(file: &SceneFile) -> Checked<Plan> {
    let sim = FieldPath::root().key("simulation");
    let sim_spec = &file.simulation;
    let tolerance = match sim_spec.tolerance {
        Some(t) => tolerance_in_reach(&sim.key("tolerance"), t)?,
        None => DEFAULT_TOLERANCE,
    };
    let tolerance = Tolerance::uniform(tolerance);
    let soft_step =
        model_of(file) == Some(ContactModelSpec::SoftStep) && file.linear_test.is_none();
    let method_id = match (&sim_spec.method, soft_step) {
        (Some(m), true) if m != Method::SemiImplicitEuler.id() => {
            let way_out = if has_joints(file) {
                "remove `method` (the scene's joints need the soft step)".to_owned()
            } else {
                format!("remove `method`, or set [contact] model = \"exact\" to integrate with {m}")
            };
            return Err(Problem::new(
                &sim.key("method"),
                ErrorKind::InvalidValue,
                format!(
                    "method \"{m}\" does not apply under the soft_step contact model, which \
                     integrates by semi-implicit Euler per substep: {way_out}"
                ),
            ));
        }
        (Some(m), _) => m.as_str(),
        (None, true) => Method::SemiImplicitEuler.id(),
        (None, false) => DEFAULT_METHOD,
    };
    let method = Method::from_id(method_id, tolerance).ok_or_else(|| {
        let known: Vec<&str> = Method::FIXED_STEP
            .iter()
            .map(Method::id)
            .chain(["dormand_prince"])
            .collect();
        Problem::new(
            &sim.key("method"),
            ErrorKind::InvalidType,
            format!(
                "unknown method {}; expected one of {}",
                quote(method_id),
                known.join(", ")
            ),
        )
    })?;
    let dt = positive(&sim.key("dt"), sim_spec.dt, "dt", "s")?;
    let duration = positive(&sim.key("duration"), sim_spec.duration, "duration", "s")?;
    let steps = step_count(duration, dt).map_err(|_| {
        Problem::new(
            &sim.key("dt"),
            ErrorKind::TooManySteps,
            format!(
                "duration / dt = {:.3e} steps, more than the {MAX_RUN_STEPS:.0e} allowed: raise dt or shorten the run",
                duration / dt
            ),
        )
    })?;
    let content = match &file.linear_test {
        Some(spec) => {
            refuse_world_tables(file)?;
            if method.needs_second_order() {
                return Err(Problem::new(
                    &sim.key("method"),
                    ErrorKind::InvalidValue,
                    format!(
                        "{} needs a (position, velocity) system; a [linear_test] is first order",
                        method.id()
                    ),
                ));
            }
            let test = linear_test(spec)?;
            test.check_horizon(duration).map_err(|reason| {
                Problem::new(
                    &FieldPath::root().key("linear_test").key("lambda"),
                    ErrorKind::OutOfRange,
                    reason,
                )
            })?;
            Content::LinearTest(test)
        }
        None => {
            let plan = world(file)?;
            crate::energy_check::initial_energy(&plan, method)?;
            Content::World(Box::new(plan))
        }
    };
    Ok(Plan {
        method,
        tolerance,
        dt,
        duration,
        steps,
        content,
    })
}

/// Whether the scene has joints (its own or a generator's).
fn has_joints(file: &SceneFile) -> bool {
    !file.joints.is_empty() || file.generate.iter().any(|g| g.has_joints())
}

/// The scene's contact model: `[contact] model`; with joints and no
/// `[contact]`, the soft step (joints need it; it is the scene default);
/// else none (contacts off).
fn model_of(file: &SceneFile) -> Option<ContactModelSpec> {
    match file.contact {
        Some(c) => Some(c.model),
        None if has_joints(file) => Some(ContactModelSpec::SoftStep),
        None => None,
    }
}

fn refuse_world_tables(file: &SceneFile) -> Checked<()> {
    let root = FieldPath::root();
    let present = [
        ("bodies", !file.bodies.is_empty()),
        ("forces", !file.forces.is_empty()),
        ("events", !file.events.is_empty()),
        ("joints", !file.joints.is_empty()),
        ("contact", file.contact.is_some()),
        ("generate", !file.generate.is_empty()),
    ];
    match present.iter().find(|(_, here)| *here) {
        Some((table, _)) => Err(Problem::new(
            &root.key(table),
            ErrorKind::InvalidValue,
            format!("a [linear_test] scene has no {table}: remove them or the [linear_test]"),
        )),
        None => Ok(()),
    }
}

fn linear_test(spec: &LinearTestSpec) -> Checked<LinearTest> {
    let p = FieldPath::root().key("linear_test");
    Ok(LinearTest {
        lambda: finite(&p.key("lambda"), spec.lambda)?,
        y0: finite(&p.key("y0"), spec.y0)?,
        forcing_offset: finite(&p.key("forcing_offset"), spec.forcing_offset)?,
        forcing_slope: finite(&p.key("forcing_slope"), spec.forcing_slope)?,
    })
}

fn world(file: &SceneFile) -> Checked<WorldPlan> {
    if file.bodies.is_empty() && file.generate.is_empty() {
        return Err(Problem::new(
            &FieldPath::root().key("bodies"),
            ErrorKind::MissingField,
            "the scene defines no [[bodies]] or [[generate]] (and no [linear_test]): nothing to simulate",
        ));
    }
    let model = model_of(file);
    let mut contact = match file.contact {
        Some(c) => Some(contact(&c)?),
        // Joints and no [contact]: the soft step at its defaults.
        None if model.is_some() => Some(ContactModel::SoftStep(SoftStepSettings::default())),
        None => None,
    };
    if let Some(n) = file.simulation.threads {
        let path = FieldPath::root().key("simulation").key("threads");
        let Some(ContactModel::SoftStep(settings)) = &mut contact else {
            return Err(Problem::new(
                &path,
                ErrorKind::InvalidValue,
                "`threads` is a setting of the soft-step contact model (the exact model and the plain integrators run on one thread): remove it or add [contact] model = \"soft_step\"",
            ));
        };
        settings.threads = match usize::try_from(n) {
            Ok(n) if (1..=256).contains(&n) => n,
            _ => {
                return Err(Problem::new(
                    &path,
                    ErrorKind::InvalidValue,
                    format!("threads must be between 1 and 256, got {n}"),
                ));
            }
        };
    }
    let mut bodies = Vec::with_capacity(file.bodies.len());
    let mut colours = Vec::with_capacity(file.bodies.len());
    // Default colours count the bodies that move: a ground first does not
    // shift them.
    let mut moving = 0;
    for (i, spec) in file.bodies.iter().enumerate() {
        let path = FieldPath::root().key("bodies").index(i);
        if let Some(j) = file.bodies[..i].iter().position(|b| b.name == spec.name) {
            return Err(Problem::new(
                &path.key("name"),
                ErrorKind::DuplicateName,
                format!("body name '{}' is already used by bodies[{j}]", spec.name),
            ));
        }
        let def = body(&path, spec)?;
        model_allows_body(&path, &def, spec, model)?;
        bodies.push(def);
        colours.push(colour(&path, spec, moving)?);
        if spec.kind != BodyKindSpec::Static {
            moving += 1;
        }
    }
    let names = crate::forces::Bodies {
        specs: &file.bodies,
        defs: &bodies,
    };
    let forces = file
        .forces
        .iter()
        .enumerate()
        .map(|(i, f)| crate::forces::force(&FieldPath::root().key("forces").index(i), f, &names))
        .collect::<Checked<Vec<_>>>()?;
    let events = file
        .events
        .iter()
        .enumerate()
        .map(|(i, e)| crate::forces::event(&FieldPath::root().key("events").index(i), e, &names))
        .collect::<Checked<Vec<_>>>()?;
    let mut joints = generated(file, model, &mut bodies, &mut colours, moving)?;
    let names = crate::joints::Names::new(&bodies);
    let mut planned = crate::joints::joints(&file.joints, &names)?;
    planned.append(&mut joints);
    crate::joints::check_with_engine(&bodies, &planned, model == Some(ContactModelSpec::Exact))?;
    let gravity = file
        .simulation
        .gravity
        .map(|g| xy(&FieldPath::root().key("simulation").key("gravity"), &g))
        .transpose()?;
    Ok(WorldPlan {
        bodies,
        colours,
        forces,
        events,
        joints: planned,
        contact,
        gravity,
    })
}

/// Appends the bodies of every `[[generate]]` block, with their colours;
/// names must not clash with any other body's. Returns the generators'
/// joints.
fn generated(
    file: &SceneFile,
    model: Option<ContactModelSpec>,
    bodies: &mut Vec<BodyDef>,
    colours: &mut Vec<Colour>,
    moving: usize,
) -> Checked<Vec<crate::joints::PlannedJoint>> {
    let mut joints = Vec::new();
    for (i, spec) in file.generate.iter().enumerate() {
        let path = FieldPath::root().key("generate").index(i);
        if model == Some(ContactModelSpec::Exact)
            && matches!(spec, crate::generate::GenerateSpec::Ragdoll { .. })
        {
            return Err(Problem::new(
                &path.key("type"),
                ErrorKind::InvalidValue,
                "a ragdoll's bones share a collision group and its joints have limits and springs, which the exact contact model does not solve: set model = \"soft_step\"",
            ));
        }
        if model != Some(ContactModelSpec::SoftStep) {
            let (field, what) = match spec {
                crate::generate::GenerateSpec::Pyramid {
                    friction: Some(_), ..
                }
                | crate::generate::GenerateSpec::Stack {
                    friction: Some(_), ..
                }
                | crate::generate::GenerateSpec::Grid {
                    friction: Some(_), ..
                } => ("friction", "per-body friction"),
                crate::generate::GenerateSpec::Pyramid {
                    restitution: Some(_),
                    ..
                }
                | crate::generate::GenerateSpec::Stack {
                    restitution: Some(_),
                    ..
                }
                | crate::generate::GenerateSpec::Grid {
                    restitution: Some(_),
                    ..
                } => ("restitution", "per-body restitution"),
                _ => ("", ""),
            };
            if !field.is_empty() {
                return Err(needs_soft_step(&path.key(field), what, model));
            }
        }
        let prefix = spec.prefix();
        let clash = |name: &str| name.starts_with(prefix) && name[prefix.len()..].starts_with('_');
        if let Some(j) = file
            .bodies
            .iter()
            .position(|b| clash(&b.name))
            .map(|j| format!("bodies[{j}] ('{}')", file.bodies[j].name))
            .or_else(|| {
                file.generate[..i]
                    .iter()
                    .position(|g| g.prefix() == prefix)
                    .map(|j| format!("generate[{j}]"))
            })
        {
            return Err(Problem::new(
                &path.key("name"),
                ErrorKind::DuplicateName,
                format!(
                    "the bodies of this generator are named {prefix}_0, {prefix}_1, ... and {j} uses that prefix: give it another `name`"
                ),
            ));
        }
        let colour = match spec.colour() {
            // The cycle goes on after the listed bodies that move.
            None => Colour::default_for(i + moving),
            Some(text) => Colour::parse_hex(text).ok_or_else(|| {
                Problem::new(
                    &path.key("colour"),
                    ErrorKind::InvalidValue,
                    format!("colour must be \"#rrggbb\" (hex), got \"{text}\""),
                )
            })?,
        };
        let more = crate::generate::expand(&path, spec, bodies.len())?;
        match more.colours {
            Some(own) if spec.colour().is_none() => colours.extend(own),
            // Static bodies are grey unless the generator names a colour.
            _ => colours.extend(more.bodies.iter().map(|b| {
                if b.kind == BodyKind::Static && spec.colour().is_none() {
                    Colour::STATIC
                } else {
                    colour
                }
            })),
        }
        bodies.extend(more.bodies);
        joints.extend(
            more.joints
                .into_iter()
                .map(|def| crate::joints::PlannedJoint {
                    def,
                    path: path.clone(),
                }),
        );
    }
    Ok(joints)
}

/// The error of a body feature the scene's contact model cannot simulate.
/// The remedy depends on the model: a scene without `[contact]` adds one;
/// a scene with `model = "exact"` changes the model or, for a material,
/// gives it world-wide (the exact model's `[contact]` friction and
/// restitution are the whole world's).
fn needs_soft_step(path: &FieldPath, what: &str, model: Option<ContactModelSpec>) -> Problem {
    let message = match model {
        Some(ContactModelSpec::Exact) => {
            let world_wide = path
                .last_key()
                .filter(|k| *k == "friction" || *k == "restitution")
                .map(|k| {
                    format!(", or remove it and give [contact] {k}, the whole world's under the exact model")
                })
                .unwrap_or_default();
            format!(
                "{what} needs the soft_step contact model, and this scene's [contact] has model = \"exact\": \
                 set [contact] model = \"soft_step\"{world_wide}"
            )
        }
        _ => format!(
            "{what} needs the soft_step contact model, and this scene has no [contact] table (contacts are off): \
             add [contact] (model = \"soft_step\" is the default)"
        ),
    };
    Problem::new(path, ErrorKind::InvalidValue, message)
}

/// Refuses what the scene's contact model cannot simulate, at its field.
fn model_allows_body(
    path: &FieldPath,
    def: &BodyDef,
    spec: &BodySpec,
    model: Option<ContactModelSpec>,
) -> Checked<()> {
    if model == Some(ContactModelSpec::SoftStep) {
        return Ok(());
    }
    if def.kind == BodyKind::Kinematic {
        return Err(needs_soft_step(
            &path.key("kind"),
            "a kinematic body",
            model,
        ));
    }
    if let Some(ShapeSpec::HollowBox { .. }) = spec.shape {
        return Err(needs_soft_step(
            &path.key("shape"),
            "a hollow_box shape",
            model,
        ));
    }
    if spec.friction.is_some() {
        return Err(needs_soft_step(
            &path.key("friction"),
            "per-body friction",
            model,
        ));
    }
    if spec.restitution.is_some() {
        return Err(needs_soft_step(
            &path.key("restitution"),
            "per-body restitution",
            model,
        ));
    }
    for (field, given, what) in [
        (
            "rolling_resistance",
            spec.rolling_resistance.is_some(),
            "rolling resistance",
        ),
        (
            "tangent_speed",
            spec.tangent_speed.is_some(),
            "a tangent speed",
        ),
        ("filter", spec.filter.is_some(), "a collision filter"),
        ("sensor", spec.sensor.is_some(), "a sensor"),
    ] {
        if given {
            return Err(needs_soft_step(&path.key(field), what, model));
        }
    }
    Ok(())
}

// ---------------------------------------------------------------- numbers

/// The largest magnitude a scene's number may have, 2^512 ≈ 1.3e154: the
/// square root of f64's largest value (≈ 1.8e308). The engine multiplies
/// the scene's quantities by each other (½ m v², m g·x, k ψ², m r², D v²,
/// lever × force): with both factors within this bound, a product stays
/// finite.
pub const MAX_MAGNITUDE: f64 = 1.340_780_792_994_259_7e154; // 2^512

/// The smallest non-zero magnitude, 2^-511 ≈ 1.5e-154: the square root of
/// f64's smallest normal number (≈ 2.2e-308), so that a product of two
/// such numbers does not underflow to 0 (a radius of 1e-200 m gives an
/// inertia of exactly 0).
pub const MIN_MAGNITUDE: f64 = 1.491_668_146_240_041_3e-154; // 2^-511

/// Every number of a scene enters here: finite, and 0 or within
/// [`MIN_MAGNITUDE`, `MAX_MAGNITUDE`] in magnitude.
pub(crate) fn finite(path: &FieldPath, value: f64) -> Checked<f64> {
    if !value.is_finite() {
        return Err(Problem::new(
            path,
            ErrorKind::NonFinite,
            format!(
                "{} is not a finite number (TOML allows nan and inf; a scene does not)",
                readable(value)
            ),
        ));
    }
    let magnitude = value.abs();
    if value != 0.0 && !(MIN_MAGNITUDE..=MAX_MAGNITUDE).contains(&magnitude) {
        let side = if magnitude > MAX_MAGNITUDE {
            "too large"
        } else {
            "too small"
        };
        return Err(Problem::new(
            path,
            ErrorKind::OutOfRange,
            format!(
                "{} is {side} for the engine's arithmetic: a scene's numbers are 0 or between 1.5e-154 and 1.3e154 in magnitude (the square roots of f64's range, since the physics multiplies quantities together)",
                readable(value)
            ),
        ));
    }
    Ok(value)
}

/// Text the user wrote, for a message: cut after 40 characters.
pub(crate) fn clip(text: &str) -> String {
    const SHOWN: usize = 40;
    match text.char_indices().nth(SHOWN) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_owned(),
    }
}

/// Text the user wrote, in double quotes, cut after 40 characters.
pub(crate) fn quote(text: &str) -> String {
    format!("\"{}\"", clip(text))
}

/// dormand_prince's tolerance, refused when f64 cannot reach it.
///
/// The error estimate |y5 − y4| / (tol (1 + |y|)) is a difference of two
/// solutions each carrying rounding errors of a few ε (ε = 2.2e-16) relative
/// to |y|: below about 10 ε the controller chases rounding noise and the step
/// shrinks until it underflows. Hairer's reference code DOPRI5 refuses
/// `rtol <= 10 * uround` ("tolerances are too small") for the same reason.
fn tolerance_in_reach(path: &FieldPath, value: f64) -> Checked<f64> {
    let tolerance = positive(path, value, "tolerance", "")?;
    let floor = 10.0 * f64::EPSILON;
    if tolerance <= floor {
        return Err(Problem::new(
            path,
            ErrorKind::OutOfRange,
            format!(
                "tolerance {} is below what f64 arithmetic can reach: the error estimate itself carries rounding errors of a few ε = 2.2e-16, so the tolerance must exceed 10 ε = {}",
                readable(tolerance),
                readable(floor)
            ),
        ));
    }
    Ok(tolerance)
}

fn with_unit(value: f64, unit: &str) -> String {
    if unit.is_empty() {
        readable(value)
    } else {
        format!("{} {unit}", readable(value))
    }
}

/// A body's `filter = { category, mask, group }`: category > 0, mask ≥ 0
/// (TOML integers are signed), any group.
fn filter_of(path: &FieldPath, spec: &FilterSpec) -> Checked<engine::Filter> {
    let d = engine::Filter::DEFAULT;
    let category = match spec.category {
        None => d.category,
        Some(c) if c > 0 => c as u64,
        Some(c) => {
            return Err(Problem::new(
                &path.key("category"),
                ErrorKind::InvalidValue,
                format!(
                    "filter category is a bit set and must be > 0 (a shape belongs to at least one category), got {c}"
                ),
            ));
        }
    };
    let mask = match spec.mask {
        None => d.mask,
        Some(m) if m >= 0 => m as u64,
        Some(m) => {
            return Err(Problem::new(
                &path.key("mask"),
                ErrorKind::InvalidValue,
                format!(
                    "filter mask is a bit set and must be >= 0 (leave it out for every bit), got {m}"
                ),
            ));
        }
    };
    Ok(engine::Filter {
        category,
        mask,
        group: spec.group.unwrap_or(d.group),
    })
}

/// The engine's mixing rule for a scene's.
fn mixing_rule(spec: MixingSpec) -> engine::MixingRule {
    match spec {
        MixingSpec::GeometricMean => engine::MixingRule::GeometricMean,
        MixingSpec::Max => engine::MixingRule::Max,
        MixingSpec::Min => engine::MixingRule::Min,
        MixingSpec::Average => engine::MixingRule::Average,
        MixingSpec::Product => engine::MixingRule::Product,
    }
}

pub(crate) fn positive(path: &FieldPath, value: f64, what: &str, unit: &str) -> Checked<f64> {
    if finite(path, value)? > 0.0 {
        Ok(value)
    } else {
        Err(Problem::new(
            path,
            ErrorKind::InvalidValue,
            format!("{what} must be > 0, got {}", with_unit(value, unit)),
        ))
    }
}

pub(crate) fn non_negative(path: &FieldPath, value: f64, what: &str, unit: &str) -> Checked<f64> {
    if finite(path, value)? >= 0.0 {
        Ok(value)
    } else {
        Err(Problem::new(
            path,
            ErrorKind::InvalidValue,
            format!("{what} must be >= 0, got {}", with_unit(value, unit)),
        ))
    }
}

pub(crate) fn unit_interval(path: &FieldPath, value: f64, what: &str) -> Checked<f64> {
    let v = finite(path, value)?;
    if !(0.0..=1.0).contains(&v) {
        return Err(Problem::new(
            path,
            ErrorKind::InvalidValue,
            format!("{what} must be in [0, 1], got {}", readable(v)),
        ));
    }
    Ok(v)
}

pub(crate) fn xy(path: &FieldPath, value: &Xy) -> Checked<Vector2<f64>> {
    Ok(Vector2::new(
        finite(&path.index(0), value.x)?,
        finite(&path.index(1), value.y)?,
    ))
}

pub(crate) fn window(path: &FieldPath, window: Option<&Window>) -> Checked<TimeWindow> {
    let Some(w) = window else {
        return Ok(TimeWindow::ALWAYS);
    };
    let start = finite(&path.index(0), w.start)?;
    let end = finite(&path.index(1), w.end)?;
    TimeWindow::new(start, end).map_err(|_| {
        Problem::new(
            path,
            ErrorKind::InvalidValue,
            format!(
                "window [{}, {}] s must end after it starts",
                readable(start),
                readable(end)
            ),
        )
    })
}

// ---------------------------------------------------------------- bodies

fn body(path: &FieldPath, spec: &BodySpec) -> Checked<BodyDef> {
    let name = &spec.name;
    if name.trim().is_empty() {
        return Err(Problem::new(
            &path.key("name"),
            ErrorKind::InvalidValue,
            "a body name must not be empty",
        ));
    }
    let shape = spec
        .shape
        .as_ref()
        .map(|s| shape(&path.key("shape"), s, name))
        .transpose()?;
    if let (Some(ShapeSpec::Chain { .. }), false) = (&spec.shape, spec.kind == BodyKindSpec::Static)
    {
        return Err(Problem::new(
            &path.key("shape").key("type"),
            ErrorKind::InvalidValue,
            format!(
                "body '{name}' has a chain shape but is not static: a chain has no area and no mass, it goes on static bodies only"
            ),
        ));
    }
    let state = BodyState {
        position: xy(&path.key("position"), &spec.position)?,
        angle: finite(&path.key("angle"), spec.angle)?,
        velocity: xy(&path.key("velocity"), &spec.velocity)?,
        angular_velocity: finite(&path.key("angular_velocity"), spec.angular_velocity)?,
    };
    let (kind, mass, density, inertia) = match spec.kind {
        BodyKindSpec::Static => {
            static_body_has_no_dynamics(path, spec)?;
            (BodyKind::Static, None, None, None)
        }
        BodyKindSpec::Kinematic => {
            kinematic_body_has_no_mass(path, spec)?;
            (BodyKind::Kinematic, None, None, None)
        }
        BodyKindSpec::Dynamic => {
            let (mass, density) = mass_or_density(path, spec)?;
            let inertia = spec
                .inertia
                .map(|i| {
                    positive(
                        &path.key("inertia"),
                        i,
                        &format!("inertia of body '{name}'"),
                        "kg·m²",
                    )
                })
                .transpose()?;
            if shape.is_none() && inertia.is_none() {
                for (field, value) in [
                    ("angle", state.angle),
                    ("angular_velocity", state.angular_velocity),
                ] {
                    if value != 0.0 {
                        return Err(Problem::new(
                            &path.key(field),
                            ErrorKind::InvalidValue,
                            format!(
                                "body '{name}' is a particle (no shape, no inertia) and cannot rotate: remove `{field}` or give it a shape"
                            ),
                        ));
                    }
                }
            }
            (BodyKind::Dynamic, mass, density, inertia)
        }
    };
    let friction = spec
        .friction
        .map(|f| {
            non_negative(
                &path.key("friction"),
                f,
                &format!("friction of body '{name}'"),
                "",
            )
        })
        .transpose()?;
    let restitution = spec
        .restitution
        .map(|e| {
            unit_interval(
                &path.key("restitution"),
                e,
                &format!("restitution of body '{name}'"),
            )
        })
        .transpose()?;
    let rolling_resistance = spec
        .rolling_resistance
        .map(|r| {
            non_negative(
                &path.key("rolling_resistance"),
                r,
                &format!("rolling resistance of body '{name}'"),
                "",
            )
        })
        .transpose()?;
    let tangent_speed = spec
        .tangent_speed
        .map(|u| finite(&path.key("tangent_speed"), u))
        .transpose()?;
    let filter = spec
        .filter
        .map(|f| filter_of(&path.key("filter"), &f))
        .transpose()?
        .unwrap_or(engine::Filter::DEFAULT);
    let def = BodyDef {
        name: name.clone(),
        kind,
        mass,
        density,
        inertia,
        shape,
        state,
        friction,
        restitution,
        filter,
        sensor: spec.sensor.unwrap_or(false),
        rolling_resistance,
        tangent_speed,
        bullet: spec.bullet.unwrap_or(false),
    };
    if let (BodyKind::Dynamic, Some(ShapeSpec::Segment { .. })) = (kind, &spec.shape)
        && (def.mass.is_none() || def.inertia.is_none())
    {
        return Err(Problem::new(
            &path.key("shape").key("type"),
            ErrorKind::InvalidValue,
            format!(
                "dynamic body '{name}' has a segment, which has no area, hence no mass or inertia (as in Box2D): make the body static or kinematic, or give it both mass and inertia"
            ),
        ));
    }
    // The engine's own check, so that building the world cannot fail.
    let (built, _) = engine::Body::from_def(&def).map_err(|e| Problem::engine(path, e))?;
    derived_in_range(path, spec, &built)?;
    Ok(def)
}

/// The mass and inertia a dynamic body gets from its shape must be usable:
/// finite, and at least f64's smallest normal number (≈ 2.2e-308) so that
/// 1/m and 1/I, which the engine divides by, stay finite. A circle of radius
/// 1e-150 m and mass 1e-10 kg has I = m r²/2 = 5e-311 kg·m²: refused here,
/// naming the shape's field, rather than blowing up in the first step.
fn derived_in_range(path: &FieldPath, spec: &BodySpec, body: &engine::Body) -> Checked<()> {
    if !body.is_dynamic() {
        return Ok(());
    }
    let shape_field = match &spec.shape {
        Some(ShapeSpec::Circle { .. }) => path.key("shape").key("radius"),
        Some(ShapeSpec::Box { .. }) => path.key("shape").key("width"),
        Some(ShapeSpec::Polygon { .. }) => path.key("shape").key("vertices"),
        Some(ShapeSpec::HollowBox { .. }) => path.key("shape").key("wall"),
        Some(ShapeSpec::Compound { .. }) => path.key("shape").key("parts"),
        Some(ShapeSpec::Chain { .. }) => path.key("shape").key("points"),
        Some(ShapeSpec::Capsule { .. }) => path.key("shape").key("radius"),
        Some(ShapeSpec::Segment { .. }) => path.key("shape").key("type"),
        None => path.key("inertia"),
    };
    let name = &spec.name;
    let usable = |v: f64| v.is_finite() && v >= f64::MIN_POSITIVE;
    if !usable(body.mass) {
        return Err(Problem::new(
            &path.key("density"),
            ErrorKind::OutOfRange,
            format!(
                "the mass of body '{name}', density × shape area = {} kg, is out of f64's usable range (2.2e-308 to 1.8e308): change the density or the shape",
                readable(body.mass)
            ),
        ));
    }
    if let Some(inertia) = body.inertia {
        if !usable(inertia) {
            let (field, source) = if spec.inertia.is_some() {
                (path.key("inertia"), "given")
            } else {
                (shape_field, "from its shape and mass")
            };
            return Err(Problem::new(
                &field,
                ErrorKind::OutOfRange,
                format!(
                    "the moment of inertia of body '{name}' {source} is {} kg·m², out of f64's usable range (2.2e-308 to 1.8e308; 1/I must be finite): the shape is too {} for its mass",
                    readable(inertia),
                    if inertia.is_finite() && inertia < 1.0 {
                        "small"
                    } else {
                        "large"
                    }
                ),
            ));
        }
    }
    Ok(())
}

fn static_body_has_no_dynamics(path: &FieldPath, spec: &BodySpec) -> Checked<()> {
    let offending = [
        ("mass", spec.mass.is_some()),
        ("density", spec.density.is_some()),
        ("inertia", spec.inertia.is_some()),
        ("velocity", spec.velocity != Xy::default()),
        ("angular_velocity", spec.angular_velocity != 0.0),
    ];
    match offending.iter().find(|(_, present)| *present) {
        Some((field, _)) => Err(Problem::new(
            &path.key(field),
            ErrorKind::InvalidValue,
            format!(
                "body '{}' is static and never moves: remove `{field}`, or make it kind = \"dynamic\"",
                spec.name
            ),
        )),
        None => Ok(()),
    }
}

fn kinematic_body_has_no_mass(path: &FieldPath, spec: &BodySpec) -> Checked<()> {
    let offending = [
        ("mass", spec.mass.is_some()),
        ("density", spec.density.is_some()),
        ("inertia", spec.inertia.is_some()),
    ];
    match offending.iter().find(|(_, present)| *present) {
        Some((field, _)) => Err(Problem::new(
            &path.key(field),
            ErrorKind::InvalidValue,
            format!(
                "body '{}' is kinematic: it moves at its velocity whatever pushes it, so it takes no `{field}`",
                spec.name
            ),
        )),
        None => Ok(()),
    }
}

fn mass_or_density(path: &FieldPath, spec: &BodySpec) -> Checked<(Option<f64>, Option<f64>)> {
    let name = &spec.name;
    match (spec.mass, spec.density) {
        (Some(_), Some(_)) => Err(Problem::new(
            &path.key("density"),
            ErrorKind::InvalidValue,
            format!("body '{name}' gives both mass and density: keep one"),
        )),
        (Some(m), None) => Ok((
            Some(positive(
                &path.key("mass"),
                m,
                &format!("mass of body '{name}'"),
                "kg",
            )?),
            None,
        )),
        (None, Some(rho)) => {
            let rho = positive(
                &path.key("density"),
                rho,
                &format!("density of body '{name}'"),
                "kg/m²",
            )?;
            if spec.shape.is_none() {
                return Err(Problem::new(
                    &path.key("density"),
                    ErrorKind::InvalidValue,
                    format!(
                        "body '{name}' has a density but no shape to give it an area: add a shape or give a mass"
                    ),
                ));
            }
            Ok((None, Some(rho)))
        }
        (None, None) => Err(Problem::new(
            &path.key("mass"),
            ErrorKind::MissingField,
            format!("dynamic body '{name}' needs a mass (kg), or a density (kg/m²) and a shape"),
        )),
    }
}

fn shape(path: &FieldPath, spec: &ShapeSpec, body: &str) -> Checked<Shape> {
    match spec {
        ShapeSpec::Box {
            width,
            height,
            radius,
        } => {
            let w = positive(
                &path.key("width"),
                *width,
                &format!("box width of body '{body}'"),
                "m",
            )?;
            let h = positive(
                &path.key("height"),
                *height,
                &format!("box height of body '{body}'"),
                "m",
            )?;
            let r = non_negative(
                &path.key("radius"),
                *radius,
                &format!("box radius of body '{body}'"),
                "m",
            )?;
            if r > 0.0 {
                Shape::rounded_box(w, h, r).map_err(|e| Problem::engine(path, e))
            } else {
                Shape::rectangle(w, h).map_err(|e| Problem::engine(path, e))
            }
        }
        ShapeSpec::Capsule { length, radius } => {
            let l = positive(
                &path.key("length"),
                *length,
                &format!("capsule length of body '{body}'"),
                "m",
            )?;
            let r = positive(
                &path.key("radius"),
                *radius,
                &format!("capsule radius of body '{body}'"),
                "m",
            )?;
            Shape::capsule(l, r).map_err(|e| Problem::engine(path, e))
        }
        ShapeSpec::Segment { a, b } => {
            let (pa, pb) = (xy(&path.key("a"), a)?, xy(&path.key("b"), b)?);
            if pa == pb {
                return Err(Problem::new(
                    &path.key("b"),
                    ErrorKind::InvalidValue,
                    format!(
                        "segment of body '{body}': b = a = [{}, {}]; a segment needs two distinct ends",
                        readable(pa.x),
                        readable(pa.y)
                    ),
                ));
            }
            Shape::segment(pa, pb).map_err(|e| Problem::engine(path, e))
        }
        ShapeSpec::Circle { radius } => {
            let r = positive(
                &path.key("radius"),
                *radius,
                &format!("radius of body '{body}'"),
                "m",
            )?;
            Ok(Shape::Circle(
                Circle::new(r).map_err(|e| Problem::engine(path, e))?,
            ))
        }
        ShapeSpec::HollowBox {
            width,
            height,
            wall,
        } => {
            let w = positive(
                &path.key("width"),
                *width,
                &format!("inside width of body '{body}'"),
                "m",
            )?;
            let h = positive(
                &path.key("height"),
                *height,
                &format!("inside height of body '{body}'"),
                "m",
            )?;
            let t = positive(
                &path.key("wall"),
                *wall,
                &format!("wall of body '{body}'"),
                "m",
            )?;
            Ok(Shape::Compound(
                Compound::hollow_box(w, h, t).map_err(|e| Problem::engine(path, e))?,
            ))
        }
        ShapeSpec::Polygon { vertices, radius } => {
            let vpath = path.key("vertices");
            let r = non_negative(
                &path.key("radius"),
                *radius,
                &format!("polygon radius of body '{body}'"),
                "m",
            )?;
            let points = vertices
                .iter()
                .enumerate()
                .map(|(i, v)| xy(&vpath.index(i), v))
                .collect::<Checked<Vec<_>>>()?;
            let shape = Shape::simple_polygon(&points).map_err(|e| match e.vertex() {
                Some(vertex) if vertex < vertices.len() => {
                    let v = vertices[vertex];
                    Problem::new(
                        &vpath.index(vertex),
                        ErrorKind::InvalidPolygon,
                        format!(
                            "polygon of body '{body}': {e} [{}, {}]",
                            readable(v.x),
                            readable(v.y)
                        ),
                    )
                }
                _ => Problem::new(
                    &vpath,
                    ErrorKind::InvalidPolygon,
                    format!(
                        "polygon of body '{body}' has {} vertices: {e}",
                        vertices.len()
                    ),
                ),
            })?;
            match shape {
                _ if r == 0.0 => Ok(shape),
                Shape::Polygon(p) => Ok(Shape::Rounded(
                    RoundedConvex::rounded_polygon(p, r).map_err(|e| Problem::engine(path, e))?,
                )),
                _ => Err(Problem::new(
                    &path.key("radius"),
                    ErrorKind::InvalidValue,
                    format!(
                        "polygon of body '{body}' is concave: only a convex polygon can be rounded (radius = {})",
                        readable(r)
                    ),
                )),
            }
        }
        ShapeSpec::Compound { parts } => compound(&path.key("parts"), parts, body),
        ShapeSpec::Chain { points, is_loop } => {
            let ppath = path.key("points");
            let xys = points
                .iter()
                .enumerate()
                .map(|(i, v)| xy(&ppath.index(i), v))
                .collect::<Checked<Vec<_>>>()?;
            Shape::chain(xys, *is_loop).map_err(|e| match e {
                engine::EngineError::InvalidChain { point, .. } if point < points.len() => {
                    Problem::new(
                        &ppath.index(point),
                        ErrorKind::InvalidValue,
                        format!("chain of body '{body}': {e}"),
                    )
                }
                _ => Problem::new(
                    &ppath,
                    ErrorKind::InvalidValue,
                    format!("chain of body '{body}' has {} points: {e}", points.len()),
                ),
            })
        }
    }
}

/// A `compound` shape: each part built as a shape of its own, then placed;
/// a part that is itself several shapes (a concave polygon, a hollow box)
/// adds each of them, placed through both placements.
fn compound(path: &FieldPath, parts: &[PartSpec], body: &str) -> Checked<Shape> {
    if parts.is_empty() {
        return Err(Problem::new(
            path,
            ErrorKind::InvalidValue,
            format!("compound shape of body '{body}' needs at least one part"),
        ));
    }
    let mut placed = Vec::new();
    for (i, part) in parts.iter().enumerate() {
        let ppath = path.index(i);
        if let ShapeSpec::Chain { .. } = part.shape {
            return Err(Problem::new(
                &ppath.key("shape").key("type"),
                ErrorKind::InvalidValue,
                format!(
                    "part {i} of the compound shape of body '{body}' is a chain: a chain is a shape of its own, on a static body"
                ),
            ));
        }
        if let ShapeSpec::Compound { .. } = part.shape {
            return Err(Problem::new(
                &ppath.key("shape").key("type"),
                ErrorKind::InvalidValue,
                format!(
                    "part {i} of the compound shape of body '{body}' is a compound: list its parts in this one"
                ),
            ));
        }
        let offset = xy(&ppath.key("offset"), &part.offset)?;
        let angle = finite(&ppath.key("angle"), part.angle)?;
        let turn = nalgebra::UnitComplex::new(angle);
        for (inner_offset, inner_angle, piece) in
            shape(&ppath.key("shape"), &part.shape, body)?.pieces()
        {
            placed.push(CompoundPart::new(
                offset + turn * inner_offset,
                angle + inner_angle,
                piece.clone(),
            ));
        }
    }
    Compound::new(placed)
        .map(Shape::Compound)
        .map_err(|e| Problem::engine(path, e))
}

/// The body's colour: its own, else grey for a static body, else the
/// palette's for the `moving`-th body that is not static.
fn colour(path: &FieldPath, spec: &BodySpec, moving: usize) -> Checked<Colour> {
    match &spec.colour {
        None if spec.kind == BodyKindSpec::Static => Ok(Colour::STATIC),
        None => Ok(Colour::default_for(moving)),
        Some(text) => Colour::parse_hex(text).ok_or_else(|| {
            Problem::new(
                &path.key("colour"),
                ErrorKind::InvalidValue,
                format!("colour must be \"#rrggbb\" (hex), got {}", quote(text)),
            )
        }),
    }
}

// ---------------------------------------------------------------- contact

fn contact(spec: &ContactSpec) -> Checked<ContactModel> {
    let path = FieldPath::root().key("contact");
    let restitution = spec
        .restitution
        .map(|e| unit_interval(&path.key("restitution"), e, "restitution"))
        .transpose()?;
    let friction = spec
        .friction
        .map(|f| non_negative(&path.key("friction"), f, "friction", ""))
        .transpose()?;
    let soft_keys = [
        ("substeps", spec.substeps.is_some()),
        ("contact_hertz", spec.contact_hertz.is_some()),
        ("damping_ratio", spec.damping_ratio.is_some()),
        ("push_out_speed", spec.push_out_speed.is_some()),
        (
            "restitution_threshold",
            spec.restitution_threshold.is_some(),
        ),
        ("speculative_distance", spec.speculative_distance.is_some()),
        ("aabb_margin", spec.aabb_margin.is_some()),
        ("recycle_distance", spec.recycle_distance.is_some()),
        ("continuous", spec.continuous.is_some()),
        ("sleeping", spec.sleeping.is_some()),
        ("friction_mixing", spec.friction_mixing.is_some()),
        ("restitution_mixing", spec.restitution_mixing.is_some()),
        ("rolling_resistance", spec.rolling_resistance.is_some()),
        ("hit_event_threshold", spec.hit_event_threshold.is_some()),
    ];
    match spec.model {
        ContactModelSpec::Exact => {
            if let Some((key, _)) = soft_keys.iter().find(|(_, given)| *given) {
                return Err(Problem::new(
                    &path.key(key),
                    ErrorKind::InvalidValue,
                    format!(
                        "`{key}` is a setting of the soft_step contact model; this [contact] has model = \"exact\": remove it or change the model"
                    ),
                ));
            }
            let d = ContactSettings::default();
            Ok(ContactModel::Exact(ContactSettings {
                restitution: restitution.unwrap_or(d.restitution),
                friction: friction.unwrap_or(d.friction),
                toi_method: match spec.toi_method {
                    None => d.toi_method,
                    Some(ToiMethodSpec::Swept) => ToiMethod::Swept,
                    Some(ToiMethodSpec::Bisection) => ToiMethod::Bisection,
                    Some(ToiMethodSpec::ConservativeAdvancement) => {
                        ToiMethod::ConservativeAdvancement
                    }
                },
                ..d
            }))
        }
        ContactModelSpec::SoftStep => {
            if spec.toi_method.is_some() {
                return Err(Problem::new(
                    &path.key("toi_method"),
                    ErrorKind::InvalidValue,
                    "`toi_method` is a setting of the exact contact model (the soft step sweeps fast bodies by itself, see `continuous`): remove it or set model = \"exact\"",
                ));
            }
            let d = SoftStepSettings::default();
            let substeps = match spec.substeps {
                None => d.substeps,
                Some(n) if (1..=1024).contains(&n) => n as usize,
                Some(n) => {
                    return Err(Problem::new(
                        &path.key("substeps"),
                        ErrorKind::InvalidValue,
                        format!("substeps must be between 1 and 1024, got {n}"),
                    ));
                }
            };
            let pos = |key: &str, v: Option<f64>, default: f64, unit: &str| -> Checked<f64> {
                v.map_or(Ok(default), |v| positive(&path.key(key), v, key, unit))
            };
            let nonneg = |key: &str, v: Option<f64>, default: f64, unit: &str| -> Checked<f64> {
                v.map_or(Ok(default), |v| non_negative(&path.key(key), v, key, unit))
            };
            Ok(ContactModel::SoftStep(SoftStepSettings {
                substeps,
                contact_hertz: pos("contact_hertz", spec.contact_hertz, d.contact_hertz, "Hz")?,
                contact_damping_ratio: nonneg(
                    "damping_ratio",
                    spec.damping_ratio,
                    d.contact_damping_ratio,
                    "",
                )?,
                push_out_speed: pos(
                    "push_out_speed",
                    spec.push_out_speed,
                    d.push_out_speed,
                    "m/s",
                )?,
                restitution_threshold: nonneg(
                    "restitution_threshold",
                    spec.restitution_threshold,
                    d.restitution_threshold,
                    "m/s",
                )?,
                speculative_distance: nonneg(
                    "speculative_distance",
                    spec.speculative_distance,
                    d.speculative_distance,
                    "m",
                )?,
                aabb_margin: pos("aabb_margin", spec.aabb_margin, d.aabb_margin, "m")?,
                recycle_distance: nonneg(
                    "recycle_distance",
                    spec.recycle_distance,
                    d.recycle_distance,
                    "m",
                )?,
                continuous: spec.continuous.unwrap_or(d.continuous),
                sleeping: spec.sleeping.unwrap_or(d.sleeping),
                friction: friction.unwrap_or(d.friction),
                restitution: restitution.unwrap_or(d.restitution),
                friction_mixing: spec.friction_mixing.map_or(d.friction_mixing, mixing_rule),
                restitution_mixing: spec
                    .restitution_mixing
                    .map_or(d.restitution_mixing, mixing_rule),
                rolling_resistance: nonneg(
                    "rolling_resistance",
                    spec.rolling_resistance,
                    d.rolling_resistance,
                    "",
                )?,
                hit_event_threshold: nonneg(
                    "hit_event_threshold",
                    spec.hit_event_threshold,
                    d.hit_event_threshold,
                    "m/s",
                )?,
                ..d
            }))
        }
    }
}

// ---------------------------------------------------------------- world

/// Builds the world of a validated plan with `method`. `method_path` is
/// where the method came from (`simulation.method`, or none for an
/// override).
pub(crate) fn build_world(
    plan: &WorldPlan,
    method: Method,
    method_path: &FieldPath,
) -> Checked<World> {
    let mut world = World::new(method).map_err(|e| Problem::engine(method_path, e))?;
    // Every step checks that the total energy is still a finite number: a
    // state can stay finite while ½ m v² or m g·x overflows, and a world
    // built from a scene never returns such a step as a success.
    world
        .set_energy_limit(Some(f64::MAX))
        .map_err(|e| Problem::engine(method_path, e))?;
    if let Some(model) = plan.contact {
        // A [contact] table turns contact handling on, under its model,
        // before any body is added (the soft step inserts each body's
        // shapes into its broad phase as it comes).
        world
            .set_contact_model(model)
            .map_err(|e| Problem::engine(&FieldPath::root().key("contact"), e))?;
    }
    if let Some(g) = plan.gravity {
        world
            .set_gravity(g)
            .map_err(|e| Problem::engine(&FieldPath::root().key("simulation").key("gravity"), e))?;
    }
    for (i, def) in plan.bodies.iter().enumerate() {
        world
            .add_body(def.clone())
            .map_err(|e| Problem::engine(&FieldPath::root().key("bodies").index(i), e))?;
    }
    for f in &plan.forces {
        world
            .add_force_during(f.force.boxed(), f.window)
            .map_err(|e| Problem::engine(&f.path, e))?;
    }
    for (i, event) in plan.events.iter().enumerate() {
        world
            .add_event(event.clone())
            .map_err(|e| Problem::engine(&FieldPath::root().key("events").index(i), e))?;
    }
    for j in &plan.joints {
        world
            .add_joint(j.def.clone())
            .map_err(|e| Problem::engine(&j.path, e))?;
    }
    Ok(world)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_count_matches_world_run() {
        assert_eq!(step_count(57.2, 0.2), Ok(286));
        assert_eq!(step_count(8.7, 0.01), Ok(870));
        assert_eq!(step_count(1.0, 0.0019), Ok(527));
        assert_eq!(step_count(1e-3, 1.0), Ok(1));
        assert!(step_count(1.0, 1e-9).is_err());
        assert!(step_count(1.0, 0.0).is_err());
    }
}
