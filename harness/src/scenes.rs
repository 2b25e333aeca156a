//! The harness's cases are scene files (`scenes/*.toml` at the workspace
//! root): one description feeds the cases, the sweeps, the benches and the
//! pictures. Editing a number there changes the next run, no rebuild needed.

use anyhow::{Context, Result};
use engine::{Method, World};
use scene::Scene;
use std::path::PathBuf;

/// Environment variable that points the harness at another scenes folder.
pub const SCENES_DIR_VAR: &str = "HARNESS_SCENES";

/// The folder of the case scenes: `$HARNESS_SCENES`, else `scenes/` at the
/// workspace root.
pub fn scenes_dir() -> PathBuf {
    std::env::var_os(SCENES_DIR_VAR)
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                .join("..")
                .join("scenes")
        })
}

/// The path of scene `id` (`spring` → `scenes/spring.toml`).
pub fn path_of(id: &str) -> PathBuf {
    scenes_dir().join(format!("{id}.toml"))
}

/// Loads scene `id`.
pub fn load(id: &str) -> Result<Scene> {
    let path = path_of(id);
    Scene::load(&path).with_context(|| format!("loading case scene '{id}'"))
}

/// The world of scene `id`, integrated by `method`.
pub fn world(id: &str, method: Method) -> Result<World> {
    Ok(load(id)?.build_world(Some(method))?)
}

/// The case scenes and every other `.toml` in the scenes folder, sorted.
pub fn list() -> Result<Vec<PathBuf>> {
    let dir = scenes_dir();
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .with_context(|| format!("reading {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    Ok(files)
}
