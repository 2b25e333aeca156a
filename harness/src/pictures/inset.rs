//! Zoomed insets: every body is drawn at its true size, so a body too small
//! to see at the scale of the run (a 0.1 m box on a 370 m trajectory) is
//! drawn a second time in a box in a corner of the plot, following it at a
//! zoom where it spans [`BODY_PX`] pixels, with its surroundings (ground
//! lines, static bodies, its trail), and the box says so: "box, zoom ×146".
//! The insets stand in the side column under the state table, so they hide
//! nothing of the plot, where a ring marks each such body. At most
//! [`MOST`] insets; a scene of many moving bodies gets none (see
//! [`super::table::MANY`]).

use super::draw::{INK, TRAIL_TINT, draw_body, plot_err, rgb, sig, text_style, tint};
use super::film::Film;
use super::table;
use super::view::{View, round_px};
use anyhow::Result;
use nalgebra::Vector2;
use plotters::coord::Shift;
use plotters::prelude::*;
use scene::Colour;

/// How many pixels the body spans in its inset.
pub const BODY_PX: f64 = 26.0;
/// Most insets in one picture.
pub const MOST: usize = 2;
/// Height of an inset's title line (px).
const TITLE_PX: i32 = 18;

/// An inset: the body it follows, its zoom over the main view and its
/// pixel box in the side column.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Inset {
    /// Index of the body.
    pub body: usize,
    /// Pixels per metre in the inset over those of the main view.
    pub zoom: f64,
    /// Left, top, right, bottom (px).
    pub frame: (i32, i32, i32, i32),
}

/// The bodies of `film` too small to see in `view` (at most [`MOST`]; none
/// in a scene of many moving bodies).
pub(crate) fn tiny(film: &Film, view: &View) -> Vec<usize> {
    if !table::per_body(film) {
        return Vec::new();
    }
    (0..film.bodies.len())
        .filter(|&i| {
            let b = &film.bodies[i];
            b.dynamic && b.shape.is_some() && view.too_small(b.radius())
        })
        .take(MOST)
        .collect()
}

/// Width and height (px) of an inset `width` px wide.
fn size(width: u32) -> (i32, i32) {
    let w = (width as i32 - 20).clamp(120, 240);
    (w, w * 3 / 5 + TITLE_PX)
}

/// The height (px) the insets of `film` take in a column `width` px wide
/// (0 without insets).
pub(crate) fn height(film: &Film, view: &View, width: u32) -> u32 {
    let n = tiny(film, view).len() as i32;
    (n * (size(width).1 + 10)) as u32
}

/// The insets of `film` in `view`, stacked in the side column (`width` px
/// wide) from `top` px down, out of the plot so that they hide nothing.
pub(crate) fn plan(film: &Film, view: &View, top: i32, width: u32) -> Vec<Inset> {
    let (w, h) = size(width);
    tiny(film, view)
        .into_iter()
        .enumerate()
        .map(|(n, body)| {
            let t = top + n as i32 * (h + 10);
            Inset {
                body,
                zoom: BODY_PX / (2.0 * film.bodies[body].radius() * view.scale()),
                frame: (10, t, 10 + w, t + h),
            }
        })
        .collect()
}

/// Rings the bodies too small to see at sample `k` in the plot `area`.
pub(crate) fn rings<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    film: &Film,
    view: &View,
    k: usize,
) -> Result<()> {
    for i in tiny(film, view) {
        let at = view.to_px(film.states[k][i].position);
        area.draw(&Circle::new(
            at,
            7,
            rgb(film.bodies[i].colour).stroke_width(2),
        ))
        .map_err(plot_err)?;
    }
    Ok(())
}

/// Draws `inset` at sample `k` into the side column `area`: the box with
/// its title and the zoomed scene around the body.
pub(crate) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    film: &Film,
    view: &View,
    inset: &Inset,
    k: usize,
    trail_idx: &[usize],
) -> Result<()> {
    let look = &film.bodies[inset.body];
    let state = &film.states[k][inset.body];
    let edge = rgb(Colour::rgb(40, 40, 40));
    let (l, t, r, b) = inset.frame;
    area.draw(&Rectangle::new([(l, t), (r, b)], WHITE.filled()))
        .map_err(plot_err)?;
    let zoomed = View::around(
        state.position,
        view.scale() * inset.zoom,
        l + 1..r - 1,
        t + TITLE_PX..b - 1,
    );
    // Ground lines and static bodies, then the body's trail and the
    // moving bodies, all cut to the inset.
    let clip = zoomed.pixel_rect();
    for &level in &film.grounds {
        let a = zoomed.to_px_f(Vector2::new(zoomed.x.0, level));
        let c = zoomed.to_px_f(Vector2::new(zoomed.x.1, level));
        if let Some((p, q)) = clip.clip(a, c) {
            area.draw(&PathElement::new(
                vec![round_px(p), round_px(q)],
                rgb(INK).stroke_width(2),
            ))
            .map_err(plot_err)?;
        }
    }
    for (i, other) in film.bodies.iter().enumerate() {
        if !other.dynamic {
            draw_body(area, film, &zoomed, i, &film.states[k][i])?;
        }
    }
    let trail: Vec<(f64, f64)> = trail_idx
        .iter()
        .take_while(|&&j| j <= k)
        .chain(std::iter::once(&k))
        .map(|&j| zoomed.to_px_f(film.states[j][inset.body].position))
        .collect();
    for run in clip.clip_polyline(&trail) {
        let run: Vec<(i32, i32)> = run.into_iter().map(round_px).collect();
        area.draw(&PathElement::new(
            run,
            rgb(tint(look.colour, TRAIL_TINT)).stroke_width(1),
        ))
        .map_err(plot_err)?;
    }
    for (i, other) in film.bodies.iter().enumerate() {
        if other.dynamic {
            draw_body(area, film, &zoomed, i, &film.states[k][i])?;
        }
    }
    let title = format!("{}, zoom ×{}", look.name, sig_zoom(inset.zoom));
    area.draw(&Rectangle::new(
        [(l, t), (r, t + TITLE_PX)],
        RGBColor(245, 245, 245).filled(),
    ))
    .map_err(plot_err)?;
    area.draw_text(
        &title,
        &text_style(14, Colour::rgb(20, 20, 20)),
        (l + 4, t + 2),
    )
    .map_err(plot_err)?;
    area.draw(&Rectangle::new([(l, t), (r, b)], edge.stroke_width(1)))
        .map_err(plot_err)?;
    Ok(())
}

/// A zoom factor for people: three significant digits, no decimals above
/// 100.
fn sig_zoom(zoom: f64) -> String {
    if zoom >= 100.0 {
        format!("{zoom:.0}")
    } else {
        sig(zoom)
    }
}
