//! `harness simulate <scene.toml>`: runs a user's scene file.
//! (Being built: see the issue on scene files and pictures.)

use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `simulate`.
#[derive(Debug, Clone, Args)]
pub struct SimulateArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
}

/// Runs `simulate`.
pub fn run(args: &SimulateArgs) -> Result<()> {
    let scene = scene::Scene::load(&args.scene)?;
    let mut world = scene.build_world(None)?;
    let trace = world.run(scene.duration(), scene.dt())?;
    println!("{} samples", trace.samples.len());
    Ok(())
}
