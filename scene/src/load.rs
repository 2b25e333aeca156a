//! [`Scene`]: a scene file read, parsed, validated, and ready to build
//! worlds from.
//!
//! Loading goes in three passes, each with its own errors:
//! 1. **syntax**: the text parses as TOML ([`toml::de::DeTable`], which keeps
//!    the span of every key and value);
//! 2. **form**: it deserializes into [`SceneFile`] (known keys only, values
//!    of the right types); serde reports a byte offset, turned into the
//!    field path and line through the spanned tree;
//! 3. **values**: [`crate::build`] checks every number and reference and
//!    converts to engine values, reporting a field path, turned into a line.

use crate::build::{self, Content, Plan};
use crate::colour::Colour;
use crate::error::{ErrorKind, FieldPath, Problem, SceneError};
use crate::form_error::form_error;
use crate::format::SceneFile;
use crate::linear_test::LinearTest;
use crate::location::{line_column, position_of};
use engine::{BodyDef, BodyId, Method, Tolerance, World};
use std::path::Path;

/// A validated scene: its settings, its bodies by name, and what it needs to
/// build an [`engine::World`] (or, for a `[linear_test]`, the ODE).
#[derive(Debug, Clone)]
pub struct Scene {
    origin: String,
    source: String,
    file: SceneFile,
    plan: Plan,
}

impl Scene {
    /// Reads, parses and validates the scene file at `path`. Errors name the
    /// path as given.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let origin = path.display().to_string();
        let text = crate::read::read_scene_file(path, &origin)?;
        Self::parse_str(&origin, &text)
    }

    /// Decodes scene bytes (UTF-8; anything else is refused with the
    /// encoding seen and the line of the first bad byte), then parses and
    /// validates them like [`Scene::parse_str`].
    pub fn parse_bytes(origin: &str, bytes: &[u8]) -> Result<Scene, SceneError> {
        let text = crate::read::decode(origin, bytes)?;
        Self::parse_str(origin, &text)
    }

    /// Parses and validates scene text; `origin` names it in errors (a file
    /// name, or e.g. `"<inline>"`).
    pub fn parse_str(origin: &str, text: &str) -> Result<Scene, SceneError> {
        match toml::de::DeTable::parse(text) {
            Err(e) => return Err(syntax_error(origin, text, &e)),
            Ok(root) => crate::form_error::check_sections(origin, text, &root)?,
        }
        let file: SceneFile = toml::from_str(text).map_err(|e| form_error(origin, text, &e))?;
        let plan = build::plan(&file).map_err(|p| locate(origin, text, p))?;
        Ok(Scene {
            origin: origin.to_owned(),
            source: text.to_owned(),
            file,
            plan,
        })
    }

    /// Builds a fresh world at t = 0: the bodies in file order (the body
    /// `bodies[i]` has id `i`), then the forces, events and joints. Integrated by
    /// the file's method, or by `method_override` (for sweeps over methods;
    /// an override of `dormand_prince` carries its own tolerance).
    ///
    /// Run it with `world.run(scene.duration(), scene.dt())`. Fails with
    /// [`ErrorKind::WrongSceneKind`] on a `[linear_test]` scene.
    pub fn build_world(&self, method_override: Option<Method>) -> Result<World, SceneError> {
        let Content::World(plan) = &self.plan.content else {
            return Err(SceneError::new(
                &self.origin,
                ErrorKind::WrongSceneKind,
                "this is a [linear_test] scene, not a world: use Scene::linear_test()",
            ));
        };
        let (method, path) = match method_override {
            Some(m) => (m, FieldPath::root()),
            None => (
                self.plan.method,
                FieldPath::root().key("simulation").key("method"),
            ),
        };
        build::build_world(plan, method, &path).map_err(|p| self.locate(p))
    }

    fn locate(&self, problem: Problem) -> SceneError {
        locate(&self.origin, &self.source, problem)
    }

    /// The file path or name the scene came from.
    pub fn origin(&self) -> &str {
        &self.origin
    }

    /// What the file says, as parsed (before conversion; defaults filled).
    pub fn file(&self) -> &SceneFile {
        &self.file
    }

    /// The integration method of `[simulation]` (with its tolerance for
    /// `dormand_prince`).
    pub fn method(&self) -> Method {
        self.plan.method
    }

    /// The tolerance of `dormand_prince` (relative and absolute), given or
    /// default, whatever the method; handy to build an override.
    pub fn tolerance(&self) -> Tolerance {
        self.plan.tolerance
    }

    /// Time step (s).
    pub fn dt(&self) -> f64 {
        self.plan.dt
    }

    /// Run length (s).
    pub fn duration(&self) -> f64 {
        self.plan.duration
    }

    /// Steps of a full run, as [`engine::World::run`] counts them:
    /// `duration / dt` when it is a whole number to within round-off, else
    /// rounded up (the last step shortened). At most 1e8.
    pub fn steps(&self) -> u64 {
        self.plan.steps
    }

    /// Whether this is a `[linear_test]` scene (no bodies).
    pub fn is_linear_test(&self) -> bool {
        matches!(self.plan.content, Content::LinearTest(_))
    }

    /// The stiff test of a `[linear_test]` scene; `None` for a world. Solve
    /// it with [`LinearTest::solve`]`(method, scene.dt(), scene.duration())`.
    pub fn linear_test(&self) -> Option<LinearTest> {
        match &self.plan.content {
            Content::LinearTest(t) => Some(*t),
            Content::World(_) => None,
        }
    }

    /// The bodies as engine definitions, in file order (index = id).
    /// Empty for a `[linear_test]`.
    pub fn bodies(&self) -> &[BodyDef] {
        match &self.plan.content {
            Content::World(w) => &w.bodies,
            Content::LinearTest(_) => &[],
        }
    }

    /// Body names, in file order (index = id).
    pub fn body_names(&self) -> Vec<&str> {
        self.bodies().iter().map(|b| b.name.as_str()).collect()
    }

    /// The id of the body named `name` in a world built from this scene.
    pub fn body_id(&self, name: &str) -> Option<BodyId> {
        self.bodies().iter().position(|b| b.name == name)
    }

    /// Body colours, in file order: the file's `colour`, or the
    /// [`Colour::PALETTE`] entry for the body's index.
    pub fn colours(&self) -> &[Colour] {
        match &self.plan.content {
            Content::World(w) => &w.colours,
            Content::LinearTest(_) => &[],
        }
    }

    /// The colour of the body named `name`.
    pub fn colour_of(&self, name: &str) -> Option<Colour> {
        self.body_id(name).map(|i| self.colours()[i])
    }

    /// The joints, as the engine takes them: the file's `[[joints]]` in
    /// order, then the generators' (joint id = position). Anchors are as
    /// written (world points at t = 0, or body-frame points); resolve them
    /// with [`engine::JointDef::local_anchors`] at the bodies' initial
    /// states, or read them back from a built world
    /// ([`engine::World::joint`]).
    pub fn joints(&self) -> impl Iterator<Item = &engine::JointDef> {
        let joints = match &self.plan.content {
            Content::World(w) => w.joints.as_slice(),
            Content::LinearTest(_) => &[],
        };
        joints.iter().map(|j| &j.def)
    }

    /// How many joints a world built from this scene holds.
    pub fn joint_count(&self) -> usize {
        self.joints().count()
    }

    /// The contact model and its settings from `[contact]`, validated and
    /// with every default filled in; `None` when contacts are off. A scene
    /// with joints and no `[contact]` runs the soft step at its defaults.
    pub fn contact(&self) -> Option<engine::ContactModel> {
        match &self.plan.content {
            Content::World(w) => w.contact,
            Content::LinearTest(_) => None,
        }
    }

    /// The world's gravity setting from `[simulation] gravity` (m/s²).
    pub fn gravity(&self) -> Option<nalgebra::Vector2<f64>> {
        match &self.plan.content {
            Content::World(w) => w.gravity,
            Content::LinearTest(_) => None,
        }
    }
}

/// Places a validation problem in the file.
fn locate(origin: &str, text: &str, problem: Problem) -> SceneError {
    let field = (!problem.path.0.is_empty()).then(|| problem.path.to_string());
    let error = SceneError::new(origin, problem.kind, problem.message)
        .with_field(field)
        .at(position_of(text, &problem.path));
    match problem.source {
        Some(source) => error.with_source(source),
        None => error,
    }
}

/// Keys nested deeper than this are refused by toml's parser ("recursion
/// limit", with no position): its limit, 80 levels.
const TOML_KEY_DEPTH: usize = 80;

/// Arrays and inline tables nested deeper than this are refused by toml's
/// parser ("cannot recurse further", at the value).
const TOML_VALUE_DEPTH: usize = 80;

/// A TOML syntax error, located. The parser gives no span when a dotted
/// key nests too deep: the first line holding such a key is found here.
fn syntax_error(origin: &str, text: &str, e: &toml::de::Error) -> SceneError {
    let message = e.message().trim();
    if let Some(span) = e.span() {
        let message = if message.starts_with("cannot recurse further") {
            format!(
                "arrays or inline tables nested more than {TOML_VALUE_DEPTH} levels deep; a \
                 scene needs 3 (a polygon's vertices, in a shape's inline table)"
            )
        } else if message == "duplicate key" {
            let key = text.get(span.clone()).unwrap_or("").trim();
            format!("duplicate key `{key}`: each key may be given once in its table")
        } else {
            message.to_owned()
        };
        return SceneError::new(origin, ErrorKind::Syntax, message)
            .at(Some(line_column(text, span.start)));
    }
    if message.contains("recursion limit") {
        let deep = text.lines().enumerate().find_map(|(i, line)| {
            let key = line.split('=').next().unwrap_or("");
            let depth = key.matches('.').count() + 1;
            (depth >= TOML_KEY_DEPTH).then_some((i + 1, depth))
        });
        let (line, depth) = deep.unwrap_or((1, TOML_KEY_DEPTH));
        return SceneError::new(
            origin,
            ErrorKind::Syntax,
            format!(
                "a key nested {depth} levels deep (a dotted key of {depth} parts); TOML files are read up to {} levels and a scene needs 4",
                TOML_KEY_DEPTH - 1
            ),
        )
        .at(Some((line, 1)));
    }
    SceneError::new(origin, ErrorKind::Syntax, message).at(Some((1, 1)))
}
