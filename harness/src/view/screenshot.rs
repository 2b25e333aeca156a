//! `--screenshot out.png --steps N`: the view's picture after N steps,
//! drawn by the window's renderer into a canvas and written as PNG, with
//! no window and no display (for docs and tests). The overlays are the
//! window's defaults and those of `--show`; the numbers in the corner are this run's, its
//! counters but not its wall times.

use super::camera::Camera;
use super::canvas::Canvas;
use super::frame::Frame;
use super::overlays::Overlays;
use super::renderer::{Hud, Renderer, panel_width};
use super::simulation::{Command, Simulation};
use super::state_out;
use anyhow::{Context, Result};
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// What to draw and where.
#[derive(Debug, Clone)]
pub struct ScreenshotOptions {
    /// The scene file, as given.
    pub scene: String,
    /// Picture size (px).
    pub size: (u32, u32),
    /// Steps before the picture.
    pub steps: u64,
    /// The PNG file.
    pub out: PathBuf,
    /// Also write the state here.
    pub state_out: Option<PathBuf>,
    /// Overlays turned on besides the defaults.
    pub show: Vec<super::input::Overlay>,
}

/// Steps `sim`, draws it, writes the PNG (and the state).
pub fn write(mut sim: Simulation, options: &ScreenshotOptions) -> Result<()> {
    let mut overlays = Overlays::default();
    for &overlay in &options.show {
        overlays.show(overlay);
    }
    sim.apply(Command::Needs(overlays.needs()));
    sim.step_n(options.steps)?;
    let mut frame = Frame::default();
    sim.publish(&mut frame);
    sim.whole_run_means(&mut frame.status);
    // Wall times would be the noise of whatever else the machine ran while
    // the picture was made: a picture keeps the counters only (`--frames`
    // measures times).
    frame.status.step_ms = None;
    frame.status.phases.clear();
    if let Some(reference) = &mut frame.reference {
        reference.status.step_ms = None;
    }
    let (w, h) = options.size;
    let camera = Camera::fit_frame(&frame, panel_width(w, frame.reference.is_some()), h);
    let mut canvas = Canvas::new(w, h);
    let hud = Hud {
        scene: options.scene.clone(),
        ..Hud::default()
    };
    Renderer::default().draw(&mut canvas, &frame, &camera, &overlays, &hud);
    write_png(&options.out, &canvas)?;
    if let Some(path) = &options.state_out {
        state_out::write(path, &sim.dump(), Some(&camera))?;
    }
    Ok(())
}

/// Writes the canvas as an 8-bit RGB PNG.
pub fn write_png(path: &Path, canvas: &Canvas) -> Result<()> {
    let context = || format!("--screenshot {}: cannot write the PNG", path.display());
    let file = std::fs::File::create(path).with_context(context)?;
    let mut encoder = png::Encoder::new(BufWriter::new(file), canvas.width(), canvas.height());
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().with_context(context)?;
    writer
        .write_image_data(&canvas.to_rgb8())
        .with_context(context)?;
    writer.finish().with_context(context)
}
