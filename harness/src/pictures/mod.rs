//! Pictures of simulations, as the seed drew them on screen (§2.1.2,
//! figures 5.3 and 6.6): each body at its true size as a coloured polygon
//! or circle (a particle as a dot; static bodies grey unless the scene
//! says otherwise), named where the name fits, springs as zigzags, the
//! ground of a landing event, the path of every centre of mass, each event
//! marked once per place, and beside the plot a table of every moving
//! body's position, angle and angular speed at the frame's time (a summary
//! for a scene of many bodies). A body too small to see at the scale of
//! the run gets a zoomed inset that says so.
//!
//! - [`svg::filmstrip`]: an SVG of a few frames at evenly spaced times;
//! - [`gif::animation`]: an animated GIF (≤ 200 frames, a few hundred kB);
//! - [`svg::linear_test_curve`]: a `[linear_test]` scene has no bodies, so
//!   its y(t) curve against the exact solution instead;
//! - [`write_case_pictures`]: all of them for every case, in
//!   `reports/scenes/`.
//!
//! A [`Film`] holds what is drawn; [`font::ensure_fonts`] registers the
//! embedded font that every chart of the harness uses.

pub mod axis_range;
mod cases;
mod draw;
pub mod film;
pub mod font;
pub mod gif;
mod inset;
mod labels;
pub mod svg;
mod table;
pub mod text;
mod view;

pub use cases::{Drawn, jobs as drawing_jobs, write_case_pictures, write_drawn};
pub use draw::sig;
pub use film::Film;
pub use gif::GifOptions;

/// Frames in a filmstrip SVG.
pub const FILMSTRIP_FRAMES: usize = 6;
