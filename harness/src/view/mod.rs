//! `harness view SCENE.toml`: any scene file run live in a window, in real
//! time, and controlled by hand: run, pause, single-step, reset, speed,
//! zoom and pan, drag a body with the mouse (through a target joint),
//! drop a box or a circle at the cursor, switch the contact model where
//! the engine accepts it, and toggle overlays (contact points and
//! normals, bounding boxes, joints, sleeping bodies, centres of mass,
//! paths, the step profile and counters). `--screenshot out.png --steps
//! N` draws the same picture without a display. Behind the harness's
//! cargo feature `view` (docs/view.md says why and how).
//!
//! The parts, one concept per file:
//!
//! - [`simulation`]: the world, stepped in real time, and the commands;
//!   [`drag`] (the target joint), [`snapshot`] (the world copied into a
//!   [`frame::Frame`]), [`meter`] (the live numbers);
//! - [`reference`]: the engine of `--compare` beside the world, in sync;
//! - [`physics_thread`]: the simulation on its own thread;
//! - [`window`]: the winit window, the mouse, frame pacing; [`input`]: the
//!   keys; [`pick`]: the body under the cursor;
//! - [`renderer`], [`overlays`], [`canvas`], [`glyphs`], [`camera`]: the
//!   CPU drawing, the same for the window and the screenshot;
//! - [`screenshot`], [`state_out`]: the PNG and the JSON state;
//!   [`cpu_time`]: what `--frames` measures with.

pub mod camera;
pub mod canvas;
pub mod cpu_time;
pub mod drag;
pub mod frame;
pub mod glyphs;
pub mod input;
pub mod meter;
pub mod overlays;
pub mod physics_thread;
pub mod pick;
pub mod reference;
pub mod renderer;
pub mod screenshot;
pub mod simulation;
pub mod snapshot;
pub mod state_out;
pub mod window;

use anyhow::{Result, bail};
use clap::Args;
use std::path::PathBuf;

/// `harness view`'s arguments.
#[derive(Debug, Clone, Args)]
pub struct ViewArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// Write the view after --steps steps to this PNG and exit, without a
    /// window (no display needed).
    #[arg(long, value_name = "out.png")]
    pub screenshot: Option<PathBuf>,
    /// Steps before the screenshot.
    #[arg(long, value_name = "N", default_value_t = 0, requires = "screenshot")]
    pub steps: u64,
    /// Window (or screenshot) size in pixels, WIDTHxHEIGHT.
    #[arg(long, value_name = "WxH", default_value = "1280x800", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Start paused.
    #[arg(long)]
    pub paused: bool,
    /// Draw this many frames (after 10 to warm up), print the frame rate
    /// and the time per frame (drawing; the physics on its thread), close.
    #[arg(long, value_name = "N", conflicts_with = "screenshot",
          value_parser = clap::value_parser!(u64).range(1..))]
    pub frames: Option<u64>,
    /// Write the bodies' states and the camera as JSON here: on D, on
    /// closing, and after --screenshot.
    #[arg(long, value_name = "FILE")]
    pub state_out: Option<PathBuf>,
    /// Overlays to turn on besides the defaults (joints, sleeping,
    /// profile, help), e.g. `--show contacts,boxes`: in the window at the
    /// start, and in --screenshot.
    #[arg(long, value_name = "OVERLAYS", value_enum, value_delimiter = ',')]
    pub show: Vec<input::Overlay>,
    /// Run this engine beside ours on the same scene, in sync (same steps,
    /// dt and substeps as `simulate --compare`), in a second panel.
    #[arg(long, value_name = "ENGINE", value_enum)]
    pub compare: Option<crate::simulate::CompareWith>,
}

/// `WIDTHxHEIGHT`, each 64 to 8192 px.
fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let parsed = text
        .split_once(['x', 'X'])
        .and_then(|(w, h)| Some((w.trim().parse().ok()?, h.trim().parse().ok()?)));
    match parsed {
        Some((w, h)) if (64..=8192).contains(&w) && (64..=8192).contains(&h) => Ok((w, h)),
        _ => Err(format!(
            "'{text}': give WIDTHxHEIGHT in pixels, each 64 to 8192, e.g. 1280x800"
        )),
    }
}

/// Runs `harness view`.
pub fn run(args: &ViewArgs) -> Result<()> {
    let scene_name = args.scene.display().to_string();
    let scene = scene::Scene::load(&args.scene)?;
    if let Some(out) = &args.screenshot {
        if out.extension().and_then(|e| e.to_str()) != Some("png") {
            bail!(
                "--screenshot {}: the picture is a PNG; name it .png",
                out.display()
            );
        }
        let sim = simulation::Simulation::new(scene, false, args.compare)?;
        return screenshot::write(
            sim,
            &screenshot::ScreenshotOptions {
                scene: scene_name,
                size: args.size,
                steps: args.steps,
                out: out.clone(),
                state_out: args.state_out.clone(),
                show: args.show.clone(),
            },
        );
    }
    let (running, compare) = (!args.paused, args.compare);
    let physics = physics_thread::PhysicsThread::spawn(move || {
        simulation::Simulation::new(scene, running, compare)
    })?;
    window::run(
        physics,
        window::WindowOptions {
            scene: scene_name,
            size: args.size,
            frames: args.frames,
            state_out: args.state_out.clone(),
            compare: args.compare.is_some(),
            show: args.show.clone(),
        },
    )
}
