//! Validation of `[[joints]]`: body names resolved (`"world"` or an absent
//! key for the world), anchors in one of their two forms, every number in
//! its domain, limits in order, a non-zero axis; each problem located at
//! its field and said in the file's words. Part of [`crate::build`]; the
//! joints of the `chain` and `ragdoll` generators are built by
//! [`crate::generate`] and checked with these by the engine itself
//! ([`check_with_engine`]).

use crate::build::{Checked, finite, non_negative, positive, xy};
use crate::error::{ErrorKind, FieldPath, Problem};
use crate::format::{
    JointSpec, PrismaticMotorSpec, Range, RevoluteMotorSpec, SpringSpec, TargetSpringSpec, Xy,
};
use engine::error::readable;
use engine::{
    Anchor, BodyDef, BodyId, BodyKind, Distance, JointDef, JointKind, JointSpring, MotorJoint,
    Prismatic, PrismaticMotor, Revolute, RevoluteMotor, Target, Weld, Wheel, WheelMotor,
};
use nalgebra::Vector2;
use std::collections::HashMap;

/// The name that means the world in `body_a` and `body_b`.
pub const WORLD: &str = "world";

/// A joint ready to add, with where the file defines it.
#[derive(Debug, Clone)]
pub(crate) struct PlannedJoint {
    pub(crate) def: JointDef,
    pub(crate) path: FieldPath,
}

/// The bodies of a scene by name, for the joints.
pub(crate) struct Names<'a> {
    pub(crate) defs: &'a [BodyDef],
    ids: HashMap<&'a str, BodyId>,
}

impl<'a> Names<'a> {
    pub(crate) fn new(defs: &'a [BodyDef]) -> Self {
        let ids = defs
            .iter()
            .enumerate()
            .map(|(i, d)| (d.name.as_str(), i))
            .collect();
        Self { defs, ids }
    }

    /// The body named at `path` (`None`: the world).
    fn side(&self, path: &FieldPath, name: Option<&str>) -> Checked<Option<BodyId>> {
        let Some(name) = name else {
            return Ok(None);
        };
        if name == WORLD {
            if self.ids.contains_key(WORLD) {
                return Err(Problem::new(
                    path,
                    ErrorKind::InvalidValue,
                    "\"world\" names the world here, and a body is also named 'world': rename that body",
                ));
            }
            return Ok(None);
        }
        match self.ids.get(name) {
            Some(&id) => Ok(Some(id)),
            None => {
                let known: Vec<String> = self
                    .defs
                    .iter()
                    .take(8)
                    .map(|b| format!("'{}'", b.name))
                    .collect();
                let more = if self.defs.len() > 8 { ", ..." } else { "" };
                Err(Problem::new(
                    path,
                    ErrorKind::UnknownBody,
                    format!(
                        "no body is named '{}' (bodies: {}{more}; \"world\" for the world)",
                        crate::build::clip(name),
                        known.join(", ")
                    ),
                ))
            }
        }
    }

    /// A point given by `anchor` on `body`, in world coordinates at t = 0.
    fn world_point(&self, body: Option<BodyId>, anchor: Anchor) -> Vector2<f64> {
        match (body, anchor) {
            (_, Anchor::World(p)) | (None, Anchor::Local(p)) => p,
            (Some(id), Anchor::Local(p)) => {
                let s = &self.defs[id].state;
                s.position + s.to_world_offset(p)
            }
        }
    }
}

/// Every `[[joints]]` entry, validated.
pub(crate) fn joints(specs: &[JointSpec], names: &Names<'_>) -> Checked<Vec<PlannedJoint>> {
    let root = FieldPath::root().key("joints");
    let mut out: Vec<PlannedJoint> = Vec::with_capacity(specs.len());
    for (i, spec) in specs.iter().enumerate() {
        let path = root.index(i);
        if let Some(name) = spec.name() {
            if name.trim().is_empty() {
                return Err(Problem::new(
                    &path.key("name"),
                    ErrorKind::InvalidValue,
                    "a joint name must not be empty",
                ));
            }
            if let Some(j) = specs[..i].iter().position(|s| s.name() == Some(name)) {
                return Err(Problem::new(
                    &path.key("name"),
                    ErrorKind::DuplicateName,
                    format!("joint name '{name}' is already used by joints[{j}]"),
                ));
            }
        }
        let def = joint(&path, spec, names, i)?;
        out.push(PlannedJoint { def, path });
    }
    Ok(out)
}

/// The common keys of a joint, as written.
struct Common<'s> {
    body_a: Option<&'s str>,
    body_b: Option<&'s str>,
    collide_connected: Option<bool>,
    constraint_hertz: Option<f64>,
    constraint_damping_ratio: Option<f64>,
    reference_angle: Option<f64>,
}

fn joint(path: &FieldPath, spec: &JointSpec, names: &Names<'_>, index: usize) -> Checked<JointDef> {
    let name = spec
        .name()
        .map_or_else(|| format!("joints[{index}]"), str::to_owned);
    let (common, kind, anchors) = match spec {
        JointSpec::Revolute {
            body_a,
            body_b,
            anchor,
            local_anchor_a,
            local_anchor_b,
            reference_angle,
            limits,
            motor,
            spring,
            collide_connected,
            constraint_hertz,
            constraint_damping_ratio,
            ..
        } => {
            let joint = Revolute {
                limits: limits
                    .map(|l| angle_limits(&path.key("limits"), l))
                    .transpose()?,
                motor: motor
                    .map(|m| revolute_motor(&path.key("motor"), m))
                    .transpose()?,
                spring: spring
                    .map(|s| spring_of(&path.key("spring"), s.hertz, s.damping_ratio))
                    .transpose()?,
                spring_target: spring
                    .map(|s| spring_target(&path.key("spring"), &s))
                    .transpose()?
                    .unwrap_or(0.0),
            };
            let common = Common {
                body_a: body_a.as_deref(),
                body_b: body_b.as_deref(),
                collide_connected: *collide_connected,
                constraint_hertz: *constraint_hertz,
                constraint_damping_ratio: *constraint_damping_ratio,
                reference_angle: *reference_angle,
            };
            let anchors = shared_anchor(path, anchor, local_anchor_a, local_anchor_b)?;
            (common, JointKind::Revolute(joint), anchors)
        }
        JointSpec::Prismatic {
            body_a,
            body_b,
            anchor,
            local_anchor_a,
            local_anchor_b,
            axis,
            reference_angle,
            limits,
            motor,
            spring,
            collide_connected,
            constraint_hertz,
            constraint_damping_ratio,
            ..
        } => {
            let axis_path = path.key("axis");
            let u = xy(&axis_path, axis)?;
            if u.norm() == 0.0 || !u.normalize().iter().all(|c| c.is_finite()) {
                return Err(Problem::new(
                    &axis_path,
                    ErrorKind::InvalidValue,
                    format!(
                        "the axis [{}, {}] has no direction: give a non-zero vector",
                        readable(u.x),
                        readable(u.y)
                    ),
                ));
            }
            let joint = Prismatic {
                axis: u,
                limits: limits
                    .map(|l| range(&path.key("limits"), l, "translation limits", "m"))
                    .transpose()?,
                motor: motor
                    .map(|m| prismatic_motor(&path.key("motor"), m))
                    .transpose()?,
                spring: spring
                    .map(|s| spring_of(&path.key("spring"), s.hertz, s.damping_ratio))
                    .transpose()?,
                spring_target: spring
                    .map(|s| spring_target(&path.key("spring"), &s))
                    .transpose()?
                    .unwrap_or(0.0),
            };
            let common = Common {
                body_a: body_a.as_deref(),
                body_b: body_b.as_deref(),
                collide_connected: *collide_connected,
                constraint_hertz: *constraint_hertz,
                constraint_damping_ratio: *constraint_damping_ratio,
                reference_angle: *reference_angle,
            };
            let anchors = shared_anchor(path, anchor, local_anchor_a, local_anchor_b)?;
            (common, JointKind::Prismatic(joint), anchors)
        }
        JointSpec::Distance {
            body_a,
            body_b,
            anchor_a,
            anchor_b,
            local_anchor_a,
            local_anchor_b,
            length,
            min_length,
            max_length,
            spring,
            collide_connected,
            constraint_hertz,
            constraint_damping_ratio,
            ..
        } => {
            let a = one_anchor(
                path,
                ("anchor_a", anchor_a),
                ("local_anchor_a", local_anchor_a),
            )?;
            let b = one_anchor(
                path,
                ("anchor_b", anchor_b),
                ("local_anchor_b", local_anchor_b),
            )?;
            let kind = distance(path, *length, (*min_length, *max_length), spring.as_ref())?;
            let common = Common {
                body_a: body_a.as_deref(),
                body_b: body_b.as_deref(),
                collide_connected: *collide_connected,
                constraint_hertz: *constraint_hertz,
                constraint_damping_ratio: *constraint_damping_ratio,
                reference_angle: None,
            };
            (common, JointKind::Distance(kind), (a, b))
        }
        JointSpec::Weld {
            body_a,
            body_b,
            anchor,
            local_anchor_a,
            local_anchor_b,
            reference_angle,
            linear_spring,
            angular_spring,
            collide_connected,
            constraint_hertz,
            constraint_damping_ratio,
            ..
        } => {
            let sprung = |key: &str, s: &Option<SpringSpec>| {
                s.map(|s| spring_of(&path.key(key), s.hertz, s.damping_ratio))
                    .transpose()
            };
            let joint = Weld {
                linear_spring: sprung("linear_spring", linear_spring)?,
                angular_spring: sprung("angular_spring", angular_spring)?,
            };
            let common = Common {
                body_a: body_a.as_deref(),
                body_b: body_b.as_deref(),
                collide_connected: *collide_connected,
                constraint_hertz: *constraint_hertz,
                constraint_damping_ratio: *constraint_damping_ratio,
                reference_angle: *reference_angle,
            };
            let anchors = shared_anchor(path, anchor, local_anchor_a, local_anchor_b)?;
            (common, JointKind::Weld(joint), anchors)
        }
        JointSpec::Wheel {
            body_a,
            body_b,
            anchor,
            local_anchor_a,
            local_anchor_b,
            axis,
            spring,
            limits,
            motor,
            collide_connected,
            constraint_hertz,
            constraint_damping_ratio,
            ..
        } => {
            let u = match axis {
                Some(axis) => direction(&path.key("axis"), axis)?,
                None => Vector2::y(),
            };
            let joint = Wheel {
                axis: u,
                spring: spring
                    .map(|s| spring_of(&path.key("spring"), s.hertz, s.damping_ratio))
                    .transpose()?,
                limits: limits
                    .map(|l| range(&path.key("limits"), l, "translation limits", "m"))
                    .transpose()?,
                motor: motor
                    .map(|m| revolute_motor(&path.key("motor"), m))
                    .transpose()?
                    .map(|m| WheelMotor {
                        speed: m.speed,
                        max_torque: m.max_torque,
                    }),
            };
            let common = Common {
                body_a: body_a.as_deref(),
                body_b: body_b.as_deref(),
                collide_connected: *collide_connected,
                constraint_hertz: *constraint_hertz,
                constraint_damping_ratio: *constraint_damping_ratio,
                reference_angle: None,
            };
            let anchors = shared_anchor(path, anchor, local_anchor_a, local_anchor_b)?;
            (common, JointKind::Wheel(joint), anchors)
        }
        JointSpec::MotorJoint {
            body_a,
            body_b,
            linear_offset,
            angular_offset,
            max_force,
            max_torque,
            linear_spring,
            angular_spring,
            collide_connected,
            ..
        } => {
            let d = MotorJoint::new(Vector2::zeros(), 0.0, 1.0, 1.0);
            let sprung = |key: &str, s: &Option<SpringSpec>, default: JointSpring| {
                s.map(|s| spring_of(&path.key(key), s.hertz, s.damping_ratio))
                    .transpose()
                    .map(|s| s.unwrap_or(default))
            };
            let joint = MotorJoint {
                linear_offset: linear_offset
                    .as_ref()
                    .map(|o| xy(&path.key("linear_offset"), o))
                    .transpose()?
                    .unwrap_or_else(Vector2::zeros),
                angular_offset: angular_offset
                    .map(|a| finite(&path.key("angular_offset"), a))
                    .transpose()?
                    .unwrap_or(0.0),
                max_force: positive(&path.key("max_force"), *max_force, "max_force", "N")?,
                max_torque: positive(&path.key("max_torque"), *max_torque, "max_torque", "N·m")?,
                linear_spring: sprung("linear_spring", linear_spring, d.linear_spring)?,
                angular_spring: sprung("angular_spring", angular_spring, d.angular_spring)?,
            };
            let common = Common {
                body_a: body_a.as_deref(),
                body_b: body_b.as_deref(),
                collide_connected: *collide_connected,
                constraint_hertz: None,
                constraint_damping_ratio: None,
                reference_angle: None,
            };
            let centre = Anchor::Local(Vector2::zeros());
            (common, JointKind::Motor(joint), (centre, centre))
        }
        JointSpec::Target {
            body,
            anchor,
            local_anchor,
            target,
            max_force,
            hertz,
            damping_ratio,
            ..
        } => {
            return target_joint(
                path,
                name,
                (body, anchor, local_anchor, target),
                (*max_force, *hertz, *damping_ratio),
                names,
            );
        }
    };
    let body_a = names.side(&path.key("body_a"), common.body_a)?;
    let body_b = names.side(&path.key("body_b"), common.body_b)?;
    bodies_allowed(path, (body_a, body_b), names)?;
    let def = JointDef {
        name,
        body_a,
        body_b,
        anchor_a: anchors.0,
        anchor_b: anchors.1,
        reference_angle: common
            .reference_angle
            .map(|a| finite(&path.key("reference_angle"), a))
            .transpose()?,
        collide_connected: common.collide_connected.unwrap_or(false),
        // Joint events are read by programs, not scene files.
        force_threshold: None,
        torque_threshold: None,
        constraint_hertz: common
            .constraint_hertz
            .map(|f| positive(&path.key("constraint_hertz"), f, "constraint_hertz", "Hz"))
            .transpose()?
            .unwrap_or(engine::joints::DEFAULT_CONSTRAINT_HERTZ),
        constraint_damping_ratio: common
            .constraint_damping_ratio
            .map(|z| {
                non_negative(
                    &path.key("constraint_damping_ratio"),
                    z,
                    "constraint_damping_ratio",
                    "",
                )
            })
            .transpose()?
            .unwrap_or(engine::joints::DEFAULT_CONSTRAINT_DAMPING_RATIO),
        kind,
    };
    if let JointKind::Distance(d) = &def.kind {
        let needs_length = !matches!(d, Distance::Rope { .. });
        let given = matches!(
            d,
            Distance::Rigid { length: Some(_) }
                | Distance::Spring {
                    length: Some(_),
                    ..
                }
        );
        let (pa, pb) = (
            names.world_point(body_a, def.anchor_a),
            names.world_point(body_b, def.anchor_b),
        );
        if needs_length && !given && (pb - pa).norm() <= 1e-9 {
            return Err(Problem::new(
                &path.key(anchor_b_key(spec)),
                ErrorKind::InvalidValue,
                format!(
                    "the anchors coincide at [{}, {}] m: a distance joint needs them apart, or a `length`",
                    readable(pa.x),
                    readable(pa.y)
                ),
            ));
        }
    }
    Ok(def)
}

fn anchor_b_key(spec: &JointSpec) -> &'static str {
    match spec {
        JointSpec::Distance {
            local_anchor_b: Some(_),
            ..
        } => "local_anchor_b",
        _ => "anchor_b",
    }
}

/// Refuses a joint without a dynamic body, or joining a body to itself.
fn bodies_allowed(
    path: &FieldPath,
    (a, b): (Option<BodyId>, Option<BodyId>),
    names: &Names<'_>,
) -> Checked<()> {
    if let (Some(a), Some(b)) = (a, b) {
        if a == b {
            return Err(Problem::new(
                &path.key("body_b"),
                ErrorKind::InvalidValue,
                format!(
                    "the joint joins body '{}' to itself: name two different bodies, or \"world\"",
                    names.defs[a].name
                ),
            ));
        }
    }
    let dynamic = |b: Option<BodyId>| b.is_some_and(|id| names.defs[id].kind == BodyKind::Dynamic);
    if !dynamic(a) && !dynamic(b) {
        let say = |b: Option<BodyId>| match b {
            None => "the world".to_owned(),
            Some(id) => format!(
                "body '{}' ({})",
                names.defs[id].name,
                match names.defs[id].kind {
                    BodyKind::Static => "static",
                    BodyKind::Kinematic => "kinematic",
                    BodyKind::Dynamic => "dynamic",
                }
            ),
        };
        let field = if b.is_some() || a.is_none() {
            "body_b"
        } else {
            "body_a"
        };
        return Err(Problem::new(
            &path.key(field),
            ErrorKind::InvalidValue,
            format!(
                "the joint holds {} to {}: at least one of body_a and body_b must be a dynamic body",
                say(a),
                say(b)
            ),
        ));
    }
    Ok(())
}

/// The anchors of a joint with one shared point: `anchor`, or both local
/// anchors.
fn shared_anchor(
    path: &FieldPath,
    anchor: &Option<Xy>,
    local_a: &Option<Xy>,
    local_b: &Option<Xy>,
) -> Checked<(Anchor, Anchor)> {
    match (anchor, local_a, local_b) {
        (Some(p), None, None) => {
            let p = xy(&path.key("anchor"), p)?;
            Ok((Anchor::World(p), Anchor::World(p)))
        }
        (None, Some(a), Some(b)) => Ok((
            Anchor::Local(xy(&path.key("local_anchor_a"), a)?),
            Anchor::Local(xy(&path.key("local_anchor_b"), b)?),
        )),
        (Some(_), _, _) => Err(Problem::new(
            &path.key(if local_a.is_some() {
                "local_anchor_a"
            } else {
                "local_anchor_b"
            }),
            ErrorKind::InvalidValue,
            "give either `anchor` (world coordinates) or `local_anchor_a` and `local_anchor_b` (the bodies' frames), not both",
        )),
        (None, None, None) => Err(Problem::new(
            &path.key("anchor"),
            ErrorKind::MissingField,
            "the joint needs its point: `anchor = [x, y]` (world coordinates at t = 0), or `local_anchor_a` and `local_anchor_b` (the bodies' frames)",
        )),
        (None, _, _) => Err(Problem::new(
            &path.key(if local_a.is_none() {
                "local_anchor_a"
            } else {
                "local_anchor_b"
            }),
            ErrorKind::MissingField,
            "with local anchors, give both `local_anchor_a` and `local_anchor_b` (or one `anchor` in world coordinates)",
        )),
    }
}

/// One anchor of a distance joint: in world coordinates or local.
fn one_anchor(
    path: &FieldPath,
    (world_key, world): (&str, &Option<Xy>),
    (local_key, local): (&str, &Option<Xy>),
) -> Checked<Anchor> {
    match (world, local) {
        (Some(p), None) => Ok(Anchor::World(xy(&path.key(world_key), p)?)),
        (None, Some(p)) => Ok(Anchor::Local(xy(&path.key(local_key), p)?)),
        (Some(_), Some(_)) => Err(Problem::new(
            &path.key(local_key),
            ErrorKind::InvalidValue,
            format!(
                "give either `{world_key}` (world coordinates) or `{local_key}` (the body's frame), not both"
            ),
        )),
        (None, None) => Err(Problem::new(
            &path.key(world_key),
            ErrorKind::MissingField,
            format!(
                "the joint needs `{world_key} = [x, y]` (world coordinates at t = 0) or `{local_key}` (the body's frame)"
            ),
        )),
    }
}

/// A non-zero direction at `path`.
fn direction(path: &FieldPath, axis: &Xy) -> Checked<Vector2<f64>> {
    let u = xy(path, axis)?;
    if u.norm() == 0.0 || !u.normalize().iter().all(|c| c.is_finite()) {
        return Err(Problem::new(
            path,
            ErrorKind::InvalidValue,
            format!(
                "the axis [{}, {}] has no direction: give a non-zero vector",
                readable(u.x),
                readable(u.y)
            ),
        ));
    }
    Ok(u)
}

fn range(path: &FieldPath, r: Range, what: &str, unit: &str) -> Checked<(f64, f64)> {
    let lo = finite(&path.index(0), r.lower)?;
    let hi = finite(&path.index(1), r.upper)?;
    if lo > hi {
        return Err(Problem::new(
            path,
            ErrorKind::InvalidValue,
            format!(
                "{what} [{}, {}] {unit} must be [lower, upper]",
                readable(lo),
                readable(hi)
            ),
        ));
    }
    Ok((lo, hi))
}

fn angle_limits(path: &FieldPath, r: Range) -> Checked<(f64, f64)> {
    let (lo, hi) = range(path, r, "angle limits", "rad")?;
    let bound = engine::joints::MAX_LIMIT_ANGLE;
    for (i, v) in [lo, hi].into_iter().enumerate() {
        if v.abs() > bound {
            return Err(Problem::new(
                &path.index(i),
                ErrorKind::InvalidValue,
                format!(
                    "angle limit {} rad is beyond ±0.99π = ±{bound:.6} rad (the joint angle is measured in [−π, π))",
                    readable(v)
                ),
            ));
        }
    }
    Ok((lo, hi))
}

fn revolute_motor(path: &FieldPath, m: RevoluteMotorSpec) -> Checked<RevoluteMotor> {
    Ok(RevoluteMotor {
        speed: finite(&path.key("speed"), m.speed)?,
        // `inf`: unbounded, a prescribed speed (the exact model's driven
        // revolute, docs/joints.md).
        max_torque: if m.max_torque == f64::INFINITY {
            m.max_torque
        } else {
            positive(&path.key("max_torque"), m.max_torque, "max_torque", "N·m")?
        },
    })
}

fn prismatic_motor(path: &FieldPath, m: PrismaticMotorSpec) -> Checked<PrismaticMotor> {
    Ok(PrismaticMotor {
        speed: finite(&path.key("speed"), m.speed)?,
        max_force: positive(&path.key("max_force"), m.max_force, "max_force", "N")?,
    })
}

fn spring_of(path: &FieldPath, hertz: f64, damping_ratio: f64) -> Checked<JointSpring> {
    Ok(JointSpring::new(
        positive(&path.key("hertz"), hertz, "the spring's hertz", "Hz")?,
        non_negative(
            &path.key("damping_ratio"),
            damping_ratio,
            "the spring's damping_ratio",
            "",
        )?,
    ))
}

fn spring_target(path: &FieldPath, s: &TargetSpringSpec) -> Checked<f64> {
    finite(&path.key("target"), s.target)
}

/// A distance joint's kind from its keys: a `spring`; else limits make a
/// rope; else rigid.
fn distance(
    path: &FieldPath,
    length: Option<f64>,
    (min, max): (Option<f64>, Option<f64>),
    spring: Option<&SpringSpec>,
) -> Checked<Distance> {
    let length = length
        .map(|l| positive(&path.key("length"), l, "length", "m"))
        .transpose()?;
    let min_length = min
        .map(|v| non_negative(&path.key("min_length"), v, "min_length", "m"))
        .transpose()?;
    let max_length = max
        .map(|v| positive(&path.key("max_length"), v, "max_length", "m"))
        .transpose()?;
    if let (Some(lo), Some(hi)) = (min_length, max_length) {
        if lo > hi {
            return Err(Problem::new(
                &path.key("min_length"),
                ErrorKind::InvalidValue,
                format!(
                    "min_length {} m is above max_length {} m",
                    readable(lo),
                    readable(hi)
                ),
            ));
        }
    }
    let (lo, hi) = (
        min_length.unwrap_or(0.0),
        max_length.unwrap_or(f64::INFINITY),
    );
    match spring {
        Some(s) => Ok(Distance::Spring {
            length,
            spring: spring_of(&path.key("spring"), s.hertz, s.damping_ratio)?,
            min_length: lo,
            max_length: hi,
        }),
        None if min_length.is_some() || max_length.is_some() => {
            if length.is_some() {
                return Err(Problem::new(
                    &path.key("length"),
                    ErrorKind::InvalidValue,
                    "with min_length or max_length and no spring the joint is a rope, free between its limits: it has no `length` (remove it, or add a `spring` to hold that length)",
                ));
            }
            if lo == 0.0 && hi == f64::INFINITY {
                return Err(Problem::new(
                    &path.key("min_length"),
                    ErrorKind::InvalidValue,
                    "a rope with min_length = 0 and no max_length holds nothing: give max_length",
                ));
            }
            Ok(Distance::Rope {
                min_length: lo,
                max_length: hi,
            })
        }
        None => Ok(Distance::Rigid { length }),
    }
}

type TargetKeys<'s> = (&'s String, &'s Option<Xy>, &'s Option<Xy>, &'s Option<Xy>);

fn target_joint(
    path: &FieldPath,
    name: String,
    (body, anchor, local_anchor, target): TargetKeys<'_>,
    (max_force, hertz, damping_ratio): (f64, Option<f64>, Option<f64>),
    names: &Names<'_>,
) -> Checked<JointDef> {
    let id = names.side(&path.key("body"), Some(body))?.ok_or_else(|| {
        Problem::new(
            &path.key("body"),
            ErrorKind::InvalidValue,
            "a target joint pulls a body: name it (not the world)",
        )
    })?;
    if names.defs[id].kind != BodyKind::Dynamic {
        return Err(Problem::new(
            &path.key("body"),
            ErrorKind::InvalidValue,
            format!("a target joint pulls a dynamic body, and '{body}' is not one"),
        ));
    }
    let point = match (anchor, local_anchor) {
        (Some(_), Some(_)) => {
            return Err(Problem::new(
                &path.key("local_anchor"),
                ErrorKind::InvalidValue,
                "give either `anchor` (world coordinates) or `local_anchor` (the body's frame), not both",
            ));
        }
        (Some(p), None) => Anchor::World(xy(&path.key("anchor"), p)?),
        (None, Some(p)) => Anchor::Local(xy(&path.key("local_anchor"), p)?),
        (None, None) => Anchor::Local(Vector2::zeros()),
    };
    let at = names.world_point(Some(id), point);
    let target = target
        .as_ref()
        .map(|t| xy(&path.key("target"), t))
        .transpose()?
        .unwrap_or(at);
    let d = Target::new(1.0);
    let joint = Target {
        max_force: positive(&path.key("max_force"), max_force, "max_force", "N")?,
        spring: JointSpring::new(
            hertz
                .map(|f| positive(&path.key("hertz"), f, "hertz", "Hz"))
                .transpose()?
                .unwrap_or(d.spring.hertz),
            damping_ratio
                .map(|z| non_negative(&path.key("damping_ratio"), z, "damping_ratio", ""))
                .transpose()?
                .unwrap_or(d.spring.damping_ratio),
        ),
    };
    let mut def = JointDef::target(&name, id, at, target, joint);
    def.anchor_b = point;
    Ok(def)
}

/// The engine's own check of every joint (those of the file and of the
/// generators), so that building the world cannot fail: a world of the
/// scene's contact model (`exact`: the exact model's joints, which refuse
/// limits, motors and springs; else the soft step) with the bodies, each
/// joint added in turn; a refusal is located at the joint.
pub(crate) fn check_with_engine(
    bodies: &[BodyDef],
    joints: &[PlannedJoint],
    exact: bool,
) -> Checked<()> {
    if joints.is_empty() {
        return Ok(());
    }
    let world = if exact {
        engine::World::with_model(
            engine::Method::Rk4,
            engine::ContactModel::Exact(engine::ContactSettings::default()),
        )
    } else {
        let model = engine::ContactModel::SoftStep(engine::SoftStepSettings::default());
        engine::World::with_model(engine::Method::SemiImplicitEuler, model)
    };
    let Ok(mut world) = world else {
        return Ok(());
    };
    for def in bodies {
        if world.add_body(def.clone()).is_err() {
            return Ok(()); // refused earlier, with its own message
        }
    }
    for j in joints {
        world
            .add_joint(j.def.clone())
            .map_err(|e| Problem::engine(&j.path, e))?;
    }
    Ok(())
}
