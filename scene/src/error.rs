//! The error of this crate: [`SceneError`], which names the file, the field
//! (`bodies[1].mass`), the line and column, and what is wrong, like a
//! compiler diagnostic:
//!
//! ```text
//! scenes/spring.toml:19:8: bodies[0].mass: mass of body 'mass' must be > 0, got -20 kg
//! ```
//!
//! Inside the crate, validation produces a `Problem` (a field path and a
//! message, no file); [`crate::Scene`] turns it into a [`SceneError`] by
//! looking the path up in the source text (module `location`).

use std::fmt;
use thiserror::Error;

/// What kind of problem a [`SceneError`] reports, for callers (and tests)
/// that branch on it. The message says the rest.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ErrorKind {
    /// The file could not be read: missing, not a regular file (a folder,
    /// a FIFO, a device), or larger than [`crate::MAX_SCENE_BYTES`].
    Io,
    /// The bytes are not UTF-8 (UTF-16, Latin-1, ...): located at the first
    /// bad byte.
    Encoding,
    /// The text is not valid TOML (unclosed bracket, duplicate key, ...).
    Syntax,
    /// A key the format does not know (a typo, or a field of another shape
    /// or force type).
    UnknownField,
    /// A required key is absent.
    MissingField,
    /// A value has the wrong type or form (a string for a number, an array
    /// of three numbers for `[x, y]`, an unknown `type` tag or method id).
    InvalidType,
    /// A number is NaN or infinite (TOML allows `nan` and `inf`).
    NonFinite,
    /// A number too large or too small for the engine's arithmetic: every
    /// number of a scene is 0 or between about 1.5e-154 and 1.3e154 in
    /// magnitude (see [`crate::format`]); or a value derived from the
    /// scene (an inertia, an energy, an exact solution) leaves f64's range.
    OutOfRange,
    /// A number or combination out of its domain (mass ≤ 0, dt ≤ 0, a window
    /// that ends before it starts, both `mass` and `density`, ...).
    InvalidValue,
    /// A polygon outline that is not simple (edges crossing or touching, a
    /// point twice), is clockwise, or is degenerate.
    InvalidPolygon,
    /// A force or event names a body that the file does not define.
    UnknownBody,
    /// Two bodies share a name.
    DuplicateName,
    /// `duration / dt` asks for more than [`engine::MAX_RUN_STEPS`] steps.
    TooManySteps,
    /// The request does not fit this scene (building a world from a
    /// `[linear_test]` scene, or the reverse).
    WrongSceneKind,
    /// The engine refused the converted scene (should not happen once
    /// validation passed; reported rather than panicking).
    Engine,
}

/// A problem with a scene file: which file, which field, which line, what.
///
/// `Display` gives `origin:line:column: field: message`, leaving out the
/// parts that are unknown (an I/O error has no line). Boxed inside, so that
/// a `Result<_, SceneError>` stays small.
#[derive(Debug, Error)]
#[error(transparent)]
pub struct SceneError(Box<Details>);

#[derive(Debug, Error)]
struct Details {
    origin: String,
    field: Option<String>,
    line: Option<usize>,
    column: Option<usize>,
    kind: ErrorKind,
    message: String,
    #[source]
    source: Option<Box<dyn std::error::Error + Send + Sync + 'static>>,
}

impl SceneError {
    pub(crate) fn new(origin: &str, kind: ErrorKind, message: impl Into<String>) -> Self {
        Self(Box::new(Details {
            origin: origin.to_owned(),
            field: None,
            line: None,
            column: None,
            kind,
            message: message.into(),
            source: None,
        }))
    }

    pub(crate) fn with_field(mut self, field: Option<String>) -> Self {
        self.0.field = field.filter(|f| !f.is_empty());
        self
    }

    pub(crate) fn at(mut self, position: Option<(usize, usize)>) -> Self {
        if let Some((line, column)) = position {
            self.0.line = Some(line);
            self.0.column = Some(column);
        }
        self
    }

    pub(crate) fn with_source(
        mut self,
        source: impl std::error::Error + Send + Sync + 'static,
    ) -> Self {
        self.0.source = Some(Box::new(source));
        self
    }

    /// The file path given to [`crate::Scene::load`], or the name given to
    /// [`crate::Scene::parse_str`].
    pub fn origin(&self) -> &str {
        &self.0.origin
    }

    /// The field at fault, e.g. `bodies[1].mass` or
    /// `bodies[0].shape.vertices[2]`; `None` for I/O and syntax errors.
    pub fn field(&self) -> Option<&str> {
        self.0.field.as_deref()
    }

    /// Line of the field in the file, 1-based.
    pub fn line(&self) -> Option<usize> {
        self.0.line
    }

    /// Column of the field in the file, 1-based, in characters.
    pub fn column(&self) -> Option<usize> {
        self.0.column
    }

    /// The kind of problem.
    pub fn kind(&self) -> ErrorKind {
        self.0.kind
    }

    /// What is wrong, without the location.
    pub fn message(&self) -> &str {
        &self.0.message
    }
}

impl fmt::Display for Details {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.origin)?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            if let Some(column) = self.column {
                write!(f, ":{column}")?;
            }
        }
        write!(f, ": ")?;
        if let Some(field) = &self.field {
            write!(f, "{field}: ")?;
        }
        write!(f, "{}", self.message)
    }
}

/// One step of a [`FieldPath`]: a table key or an array index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Segment {
    /// A key of a table.
    Key(String),
    /// An index into an array (`[[bodies]]` entries, vertices, `[x, y]`).
    Index(usize),
}

/// Where a value sits in the document, e.g. `bodies[1].shape.vertices[2]`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub(crate) struct FieldPath(pub(crate) Vec<Segment>);

impl FieldPath {
    /// The root of the document.
    pub(crate) fn root() -> Self {
        Self::default()
    }

    /// This path extended by a key.
    pub(crate) fn key(&self, key: &str) -> Self {
        let mut p = self.clone();
        p.0.push(Segment::Key(key.to_owned()));
        p
    }

    /// This path extended by an index.
    pub(crate) fn index(&self, index: usize) -> Self {
        let mut p = self.clone();
        p.0.push(Segment::Index(index));
        p
    }

    /// The last key of the path, if it ends with one.
    pub(crate) fn last_key(&self) -> Option<&str> {
        match self.0.last() {
            Some(Segment::Key(k)) => Some(k),
            _ => None,
        }
    }
}

impl fmt::Display for FieldPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, segment) in self.0.iter().enumerate() {
            match segment {
                Segment::Key(k) if i == 0 => write!(f, "{k}")?,
                Segment::Key(k) => write!(f, ".{k}")?,
                Segment::Index(n) => write!(f, "[{n}]")?,
            }
        }
        Ok(())
    }
}

/// A validation failure before it is placed in a file: the field, the
/// kind, the message and an optional underlying error.
#[derive(Debug)]
pub(crate) struct Problem {
    pub(crate) path: FieldPath,
    pub(crate) kind: ErrorKind,
    pub(crate) message: String,
    pub(crate) source: Option<engine::EngineError>,
}

impl Problem {
    pub(crate) fn new(path: &FieldPath, kind: ErrorKind, message: impl Into<String>) -> Self {
        Self {
            path: path.clone(),
            kind,
            message: message.into(),
            source: None,
        }
    }

    /// The engine refused something: keep its error as the source.
    pub(crate) fn engine(path: &FieldPath, error: engine::EngineError) -> Self {
        Self {
            path: path.clone(),
            kind: ErrorKind::Engine,
            message: format!("the engine refused it: {error}"),
            source: Some(error),
        }
    }
}
