//! Pictures of simulations, as the seed drew them on screen (§2.1.2,
//! figures 5.3 and 6.6): each body as a coloured polygon or circle (a
//! particle as a dot), springs as zigzags, the ground of a landing event,
//! the path of every centre of mass, and the current time, position, angle
//! and angular speed.
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
pub mod svg;
pub mod text;
mod view;

pub use cases::write_case_pictures;
pub use draw::sig;
pub use film::Film;
pub use gif::GifOptions;

/// Frames in a filmstrip SVG.
pub const FILMSTRIP_FRAMES: usize = 6;
