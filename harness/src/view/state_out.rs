//! `--state-out FILE`: the bodies' states as JSON, written when D is
//! pressed, when the window closes, and after `--screenshot`, with the
//! camera that drew them (so that a program driving the view knows where
//! each body is on screen: pixel = camera.to_screen(position)).

use super::camera::Camera;
use super::simulation::StateDump;
use anyhow::{Context, Result};
use serde::Serialize;
use std::path::Path;

/// The file's content.
#[derive(Debug, Serialize)]
struct StateFile<'a> {
    #[serde(flatten)]
    state: &'a StateDump,
    /// The camera (centre in m, scale in px/m, window size in px), when a
    /// frame has been drawn.
    camera: Option<&'a Camera>,
}

/// Writes `state` and `camera` to `path` (through a temporary file, so a
/// reader never sees half of it).
pub fn write(path: &Path, state: &StateDump, camera: Option<&Camera>) -> Result<()> {
    let text = serde_json::to_string_pretty(&StateFile { state, camera })?;
    let tmp = path.with_extension("json.tmp");
    std::fs::write(&tmp, text + "\n")
        .and_then(|()| std::fs::rename(&tmp, path))
        .with_context(|| format!("--state-out {}: cannot write the state", path.display()))
}
