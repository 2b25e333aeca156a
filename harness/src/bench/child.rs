//! Box2D builds other than the one linked into the harness, as extra rows
//! of the benchmark (`harness bench --box2d-sse2`, `--box2d-double`).
//!
//! One cargo build links boxdd once, with one set of features (SSE2 or
//! AVX2, f32 or f64 positions). Another build is another binary: the crate
//! `box2d_child/` at the workspace root, outside the workspace's members,
//! which links this harness library without its default `box2d-avx2`
//! feature (and with `box2d-double` for the double build) and runs
//! [`child_main`]. The harness builds it on demand, before any timing,
//! into the workspace's `target/` folder, where cargo reuses the compiled
//! registry crates of the main build (same versions through the child's
//! copy of Cargo.lock, same profile, same `[env]`) and compiles again only
//! boxdd-sys (Box2D's C sources), boxdd, the workspace's crates and the
//! child; it runs the child once per repeat, alternating with the engines
//! in this process as Box2D's protocol asks. (`cargo run` replaces its
//! process with the harness's, so the folder's lock is free.)
//!
//! The protocol: the harness runs `box2d_child <scene id> <timed steps>`;
//! the child loads the benchmark scene from the same scenes folder,
//! converts it as [`super::convert`] does for the linked Box2D, builds it
//! in its Box2D, takes step 0 untimed and the timed steps, and prints one
//! line of JSON ([`ChildRun`]): its build, the time per step and the final
//! states, from which the harness computes the same quality figures as for
//! every engine. A failure is a non-zero exit with the reason on stderr.

use super::convert::many_body_scene;
use anyhow::{Context, Result, bail};
use references::box2d_world::Box2dWorld;
use references::box2d_world::build::Box2dBuild;
use references::many_body::{BodySample, ManyBodyEngine};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

/// A Box2D build run as a child process.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChildBuild {
    /// SSE2 (4 f32 lanes), f32, the workspace's C flags.
    Sse2,
    /// AVX2 with boxdd's `double-precision` (f64 absolute positions).
    Double,
}

impl ChildBuild {
    /// The build's name in messages.
    pub fn label(self) -> &'static str {
        match self {
            ChildBuild::Sse2 => "SSE2",
            ChildBuild::Double => "double-precision",
        }
    }

    /// The suffix of its binary's copy.
    fn file_suffix(self) -> &'static str {
        match self {
            ChildBuild::Sse2 => "sse2",
            ChildBuild::Double => "double",
        }
    }

    /// Whether a child's own name for its build ([`Box2dBuild::bench_name`])
    /// is this build's.
    pub fn is_named(self, name: &str) -> bool {
        match self {
            ChildBuild::Sse2 => name.contains(" SSE2 ") && name.contains(" f32 "),
            ChildBuild::Double => name.contains(" f64-pos "),
        }
    }

    /// The child crate's cargo features for this build.
    fn features(self) -> &'static str {
        match self {
            ChildBuild::Sse2 => "",
            ChildBuild::Double => "avx2,double",
        }
    }

    /// The child's target folder: the workspace's (see the module
    /// documentation).
    fn target_dir(self) -> PathBuf {
        crate::workspace::root().join("target")
    }
}

/// What the child prints: one run of one scene.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ChildRun {
    /// The child's Box2D build, as it reads it ([`Box2dBuild::bench_name`]).
    pub name: String,
    /// Its configuration paragraph.
    pub configuration: String,
    /// Precision of its build.
    pub precision: String,
    /// SIMD path on this CPU.
    pub simd: String,
    /// C flags of its build.
    pub flags: String,
    /// Time per timed step (ms).
    pub ms_per_step: f64,
    /// Final states in scene order: x, y, angle, vx, vy, angular velocity.
    pub states: Vec<[f64; 6]>,
    /// Touching pairs after the last step.
    pub touching: usize,
    /// Contact points after the last step.
    pub points: usize,
}

impl ChildRun {
    /// The final states as samples.
    pub fn samples(&self) -> Vec<BodySample> {
        self.states
            .iter()
            .map(|s| BodySample {
                position: [s[0], s[1]],
                angle: s[2],
                velocity: [s[3], s[4]],
                angular_velocity: s[5],
            })
            .collect()
    }
}

/// Builds the child binary of `build` (cargo prints its progress on
/// stderr) and returns its path and the build's wall time (s).
pub fn build(build: ChildBuild) -> Result<(PathBuf, f64)> {
    let root = crate::workspace::root();
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let target = build.target_dir();
    let mut command = Command::new(cargo);
    command
        .current_dir(&root)
        .args(["build", "--release", "--manifest-path"])
        .arg(root.join("box2d_child").join("Cargo.toml"))
        .arg("--target-dir")
        .arg(&target);
    if !build.features().is_empty() {
        command.args(["--features", build.features()]);
    }
    let started = Instant::now();
    let status = command
        .status()
        .with_context(|| format!("running cargo to build box2d_child ({})", build.label()))?;
    if !status.success() {
        bail!("building box2d_child ({}) failed: {status}", build.label());
    }
    let built = target.join("release").join("box2d_child");
    if !built.is_file() {
        bail!("box2d_child built, but {} is missing", built.display());
    }
    // Each build under its own name: the other build writes the same
    // output file.
    let binary = target
        .join("release")
        .join(format!("box2d_child_{}", build.file_suffix()));
    std::fs::copy(&built, &binary)
        .with_context(|| format!("copying {} to {}", built.display(), binary.display()))?;
    Ok((binary, started.elapsed().as_secs_f64()))
}

/// Runs `binary` on benchmark scene `file` (relative to the scenes folder)
/// for `steps` timed steps.
pub fn run(binary: &std::path::Path, file: &str, steps: usize) -> Result<ChildRun> {
    let out = Command::new(binary)
        .arg(file)
        .arg(steps.to_string())
        .output()
        .with_context(|| format!("running {}", binary.display()))?;
    if !out.status.success() {
        bail!(
            "{} {file} {steps} failed ({}): {}",
            binary.display(),
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text
        .lines()
        .rev()
        .find(|l| l.starts_with('{'))
        .with_context(|| format!("{} printed no result for {file}", binary.display()))?;
    serde_json::from_str(line).with_context(|| format!("reading the result of {file}"))
}

/// The child's side: `args` = scene id (relative to the scenes folder) and
/// timed steps. Prints one [`ChildRun`] as a line of JSON.
pub fn child_main(args: &[String]) -> Result<()> {
    let [file, steps] = args else {
        bail!("usage: box2d_child <benchmark scene, e.g. bench/pyramid_40> <timed steps>");
    };
    let steps: usize = steps
        .parse()
        .with_context(|| format!("timed steps '{steps}' is not a count"))?;
    let built = Box2dBuild::linked();
    let scene = crate::scenes::load(file)?;
    let neutral = many_body_scene(&scene)?;
    let mut world = Box2dWorld::new(&neutral)?;
    world.step()?;
    let started = Instant::now();
    for _ in 0..steps {
        world.step()?;
    }
    let per_step = started.elapsed().as_secs_f64() / steps.max(1) as f64;
    let mut samples = Vec::new();
    world.samples(&mut samples)?;
    let counts = world.contact_counts()?;
    let run = ChildRun {
        name: built.bench_name(),
        configuration: world.configuration(),
        precision: built.precision.to_string(),
        simd: built.simd_at_run_time(),
        flags: built.flags.clone(),
        ms_per_step: 1e3 * per_step,
        states: samples
            .iter()
            .map(|s| {
                [
                    s.position[0],
                    s.position[1],
                    s.angle,
                    s.velocity[0],
                    s.velocity[1],
                    s.angular_velocity,
                ]
            })
            .collect(),
        touching: counts.touching_pairs,
        points: counts.points,
    };
    println!("{}", serde_json::to_string(&run)?);
    Ok(())
}
