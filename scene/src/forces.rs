//! Validation of `[[forces]]` and `[[events]]`: body names resolved to ids,
//! parameters in their domain, windows well ordered, no force on static
//! bodies only, no torque on a particle. Part of [`crate::build`].

use crate::build::{Checked, EngineForce, PlannedForce, finite, non_negative, window, xy};
use crate::error::{ErrorKind, FieldPath, Problem};
use crate::format::{BodySpec, EventEntry, ForceSpec, Xy};
use engine::forces::{AngularDrag, Attachment, Gravity, PointForce, QuadraticDrag, Spring, Torque};
use engine::{BodyDef, BodyId, BodyKind, EventSpec};
use nalgebra::Vector2;

/// Body lookup by name for forces and events.
pub(crate) struct Bodies<'a> {
    pub(crate) specs: &'a [BodySpec],
    pub(crate) defs: &'a [BodyDef],
}

impl Bodies<'_> {
    fn id(&self, path: &FieldPath, name: &str) -> Checked<BodyId> {
        self.specs
            .iter()
            .position(|b| b.name == name)
            .ok_or_else(|| {
                let known: Vec<String> =
                    self.specs.iter().map(|b| format!("'{}'", b.name)).collect();
                Problem::new(
                    path,
                    ErrorKind::UnknownBody,
                    format!(
                        "no body is named '{}' (bodies: {})",
                        crate::build::clip(name),
                        known.join(", ")
                    ),
                )
            })
    }

    fn is_dynamic(&self, id: BodyId) -> bool {
        self.defs[id].kind == BodyKind::Dynamic
    }

    /// A dynamic body with rotational state (a shape or an inertia).
    fn rotates(&self, id: BodyId) -> bool {
        self.is_dynamic(id) && (self.defs[id].shape.is_some() || self.defs[id].inertia.is_some())
    }

    /// The dynamic body `name` at `path`, refusing a static one.
    fn dynamic(&self, path: &FieldPath, name: &str, force: &str) -> Checked<BodyId> {
        let id = self.id(path, name)?;
        if !self.is_dynamic(id) {
            return Err(Problem::new(
                path,
                ErrorKind::InvalidValue,
                format!("{force} acts on body '{name}', which is static and never moves"),
            ));
        }
        Ok(id)
    }

    /// The rotating body `name` at `path`, refusing a static body or a
    /// particle.
    fn rotating(&self, path: &FieldPath, name: &str, force: &str) -> Checked<BodyId> {
        let id = self.dynamic(path, name, force)?;
        if !self.rotates(id) {
            return Err(Problem::new(
                path,
                ErrorKind::InvalidValue,
                format!(
                    "{force} on body '{name}', a particle (no shape, no inertia) that cannot rotate: give it a shape or an inertia"
                ),
            ));
        }
        Ok(id)
    }

    /// An attachment point on body `id`: must be the centre on a particle.
    fn point(&self, path: &FieldPath, id: BodyId, point: Option<&Xy>) -> Checked<Vector2<f64>> {
        let p = point.map(|p| xy(path, p)).transpose()?.unwrap_or_default();
        if p != Vector2::zeros() && self.is_dynamic(id) && !self.rotates(id) {
            return Err(Problem::new(
                path,
                ErrorKind::InvalidValue,
                format!(
                    "body '{}' is a particle (no shape, no inertia): a force off its centre would need a torque it cannot take; use [0, 0] or give it a shape",
                    self.specs[id].name
                ),
            ));
        }
        Ok(p)
    }
}

pub(crate) fn force(
    path: &FieldPath,
    spec: &ForceSpec,
    bodies: &Bodies<'_>,
) -> Checked<PlannedForce> {
    let (force, w) = match spec {
        ForceSpec::Gravity { g, window } => (
            EngineForce::Gravity(Gravity {
                g: xy(&path.key("g"), g)?,
            }),
            window,
        ),
        ForceSpec::Spring { window, .. } => (spring(path, spec, bodies)?, window),
        ForceSpec::Drag {
            body,
            coefficient,
            window,
        } => (
            EngineForce::Drag(QuadraticDrag {
                body: bodies.dynamic(&path.key("body"), body, "drag")?,
                coefficient: non_negative(
                    &path.key("coefficient"),
                    *coefficient,
                    "drag coefficient",
                    "kg/m",
                )?,
            }),
            window,
        ),
        ForceSpec::AngularDrag {
            body,
            coefficient,
            window,
        } => (
            EngineForce::AngularDrag(AngularDrag {
                body: bodies.rotating(&path.key("body"), body, "angular drag")?,
                coefficient: non_negative(
                    &path.key("coefficient"),
                    *coefficient,
                    "angular drag coefficient",
                    "N·m·s²",
                )?,
            }),
            window,
        ),
        ForceSpec::PointForce {
            body,
            force,
            point,
            window,
        } => {
            let id = bodies.dynamic(&path.key("body"), body, "point force")?;
            (
                EngineForce::PointForce(PointForce {
                    body: id,
                    force: xy(&path.key("force"), force)?,
                    local_point: bodies.point(&path.key("point"), id, point.as_ref())?,
                }),
                window,
            )
        }
        ForceSpec::Torque {
            body,
            torque,
            lever,
            force,
            window,
        } => {
            let id = bodies.rotating(&path.key("body"), body, "torque")?;
            let t = match (torque, lever, force) {
                (Some(t), None, None) => Torque {
                    body: id,
                    torque: finite(&path.key("torque"), *t)?,
                },
                (None, Some(r), Some(f)) => {
                    Torque::from_lever(id, xy(&path.key("lever"), r)?, xy(&path.key("force"), f)?)
                }
                (Some(_), _, _) => {
                    let extra = if lever.is_some() { "lever" } else { "force" };
                    return Err(Problem::new(
                        &path.key(extra),
                        ErrorKind::InvalidValue,
                        "give `torque`, or `lever` and `force`, not both",
                    ));
                }
                (None, _, _) => {
                    let missing = if lever.is_some() { "force" } else { "lever" };
                    return Err(Problem::new(
                        &path.key(missing),
                        ErrorKind::MissingField,
                        "a torque needs `torque` (N·m), or `lever` (m) and `force` (N)",
                    ));
                }
            };
            (EngineForce::Torque(t), window)
        }
    };
    Ok(PlannedForce {
        force,
        window: window(&path.key("window"), w.as_ref())?,
        path: path.clone(),
    })
}

fn spring(path: &FieldPath, spec: &ForceSpec, bodies: &Bodies<'_>) -> Checked<EngineForce> {
    let ForceSpec::Spring {
        body,
        point,
        anchor,
        other_body,
        other_point,
        stiffness,
        rest_length,
        axis,
        ..
    } = spec
    else {
        // Only called on a spring; an error rather than a panic regardless.
        return Err(Problem::new(path, ErrorKind::InvalidType, "not a spring"));
    };
    let id = bodies.id(&path.key("body"), body)?;
    let b = Attachment::Body {
        body: id,
        local_point: bodies.point(&path.key("point"), id, point.as_ref())?,
    };
    let a = match (anchor, other_body) {
        (Some(p), None) => {
            if other_point.is_some() {
                return Err(Problem::new(
                    &path.key("other_point"),
                    ErrorKind::InvalidValue,
                    "`other_point` needs `other_body` (an anchor is already a point)",
                ));
            }
            Attachment::World(xy(&path.key("anchor"), p)?)
        }
        (None, Some(other)) => {
            let other_id = bodies.id(&path.key("other_body"), other)?;
            if other_id == id {
                return Err(Problem::new(
                    &path.key("other_body"),
                    ErrorKind::InvalidValue,
                    format!("a spring from body '{body}' to itself"),
                ));
            }
            Attachment::Body {
                body: other_id,
                local_point: bodies.point(
                    &path.key("other_point"),
                    other_id,
                    other_point.as_ref(),
                )?,
            }
        }
        (Some(_), Some(_)) => {
            return Err(Problem::new(
                &path.key("other_body"),
                ErrorKind::InvalidValue,
                "give `anchor` or `other_body`, not both",
            ));
        }
        (None, None) => {
            return Err(Problem::new(
                &path.key("anchor"),
                ErrorKind::MissingField,
                "a spring needs `anchor = [x, y]` (m) or `other_body`",
            ));
        }
    };
    let moves =
        |att: &Attachment| matches!(att, Attachment::Body { body, .. } if bodies.is_dynamic(*body));
    if !moves(&a) && !moves(&b) {
        return Err(Problem::new(
            &path.key("body"),
            ErrorKind::InvalidValue,
            format!("the spring on '{body}' joins no dynamic body: it would do nothing"),
        ));
    }
    let axis = match axis {
        None => None,
        Some(u) => {
            let apath = path.key("axis");
            let u = xy(&apath, u)?;
            if u.norm() == 0.0 {
                return Err(Problem::new(
                    &apath,
                    ErrorKind::InvalidValue,
                    "a spring axis must not be [0, 0]",
                ));
            }
            // Scaled by its largest component first, so that the norm of
            // [1e300, 0] or [1e-300, 0] neither overflows nor underflows.
            let u = u / u.amax();
            Some(u / u.norm())
        }
    };
    Ok(EngineForce::Spring(Spring {
        a,
        b,
        stiffness: non_negative(&path.key("stiffness"), *stiffness, "stiffness", "N/m")?,
        rest_length: non_negative(&path.key("rest_length"), *rest_length, "rest length", "m")?,
        axis,
    }))
}

pub(crate) fn event(
    path: &FieldPath,
    spec: &EventEntry,
    bodies: &Bodies<'_>,
) -> Checked<EventSpec> {
    Ok(match spec {
        EventEntry::Landing { body, level } => EventSpec::landing(
            bodies.id(&path.key("body"), body)?,
            finite(&path.key("level"), *level)?,
        ),
        EventEntry::Apex { body } => EventSpec::apex(bodies.id(&path.key("body"), body)?),
    })
}
