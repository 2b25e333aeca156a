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
        .unwrap_or_else(|| crate::workspace::root().join("scenes"))
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

/// The `.toml` files of the scenes folder and of its subfolders one level
/// down (`scenes/examples/`), sorted.
pub fn list() -> Result<Vec<PathBuf>> {
    let dir = scenes_dir();
    let entries = |d: &std::path::Path| -> Result<Vec<PathBuf>> {
        Ok(std::fs::read_dir(d)
            .with_context(|| format!("reading {}", d.display()))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .collect())
    };
    let mut files = Vec::new();
    for path in entries(&dir)? {
        if path.is_dir() {
            files.extend(entries(&path)?);
        } else {
            files.push(path);
        }
    }
    files.retain(|p| p.extension().is_some_and(|x| x == "toml"));
    files.sort();
    Ok(files)
}

/// The world of scene `id` for a timed run: as [`world`], without the
/// energy check a scene's world makes after every step (one evaluation of
/// the total energy per step, a safety net for user scenes that the timing
/// of the engine's integration must not include; these scenes are the
/// harness's own, whose energies stay finite).
pub fn timed_world(id: &str, method: Method) -> Result<World> {
    let mut world = world(id, method)?;
    world.set_energy_limit(None)?;
    Ok(world)
}
