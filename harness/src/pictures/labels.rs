//! Body names, drawn where they fit: inside the body when the name fits in
//! its inscribed circle (any rotation), else just above, below, right or
//! left of it where that neither leaves the plot nor covers another moving
//! body or label; nowhere otherwise. A scene of more than
//! [`super::table::MANY`] moving bodies gets no labels (its table is a
//! summary).

use super::draw::{plot_err, text_style};
use super::film::{BodyLook, Film};
use super::table;
use super::view::{PARTICLE_PX, View};
use anyhow::Result;
use engine::{BodyState, Shape};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use scene::Colour;

/// A pixel rectangle: left, top, right, bottom.
pub(crate) type Boxed = (i32, i32, i32, i32);

/// Size of label text (plotters units).
const TEXT: u32 = 14;

fn overlaps(a: Boxed, b: Boxed) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

/// The pixel box of body `look` at `state` (its outline's bounding box at
/// its angle; its rotation radius for a compound), cut to the plot.
pub(crate) fn body_box(look: &BodyLook, state: &BodyState, view: &View) -> Boxed {
    let (x, y) = view.to_px(state.position);
    let scale = view.scale();
    let (hx, hy) = match &look.shape {
        None => (f64::from(PARTICLE_PX), f64::from(PARTICLE_PX)),
        Some(Shape::Circle(c)) => (c.radius * scale, c.radius * scale),
        Some(Shape::Polygon(p)) => {
            let rotation = nalgebra::Rotation2::new(state.angle);
            p.vertices().iter().fold((0.0f64, 0.0f64), |(a, b), v| {
                let w = rotation * v;
                (a.max(w.x.abs() * scale), b.max(w.y.abs() * scale))
            })
        }
        Some(Shape::Compound(_) | Shape::Chain(_)) => {
            (look.radius() * scale, look.radius() * scale)
        }
        Some(Shape::Rounded(r)) => {
            let rotation = nalgebra::Rotation2::new(state.angle);
            r.core().iter().fold((0.0f64, 0.0f64), |(a, b), v| {
                let w = rotation * v;
                (
                    a.max((w.x.abs() + r.radius()) * scale),
                    b.max((w.y.abs() + r.radius()) * scale),
                )
            })
        }
    };
    let (hx, hy) = (hx.ceil().min(1e6) as i32, hy.ceil().min(1e6) as i32);
    (
        (x - hx).max(view.px.start),
        (y - hy).max(view.py.start),
        (x + hx).min(view.px.end),
        (y + hy).min(view.py.end),
    )
}

/// Labels the bodies `which` selects at `states` in `view`, avoiding the
/// boxes in `taken` (and adding its own).
pub(crate) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    film: &Film,
    view: &View,
    states: &[BodyState],
    which: impl Fn(&BodyLook) -> bool,
    taken: &mut Vec<Boxed>,
) -> Result<()> {
    if !table::per_body(film) {
        return Ok(());
    }
    let obstacles: Vec<(usize, Boxed)> = film
        .bodies
        .iter()
        .zip(states)
        .enumerate()
        .filter(|(_, (look, _))| look.dynamic)
        .map(|(i, (look, s))| (i, body_box(look, s, view)))
        .collect();
    let plot: Boxed = (view.px.start, view.py.start, view.px.end, view.py.end);
    for (i, (look, state)) in film.bodies.iter().zip(states).enumerate() {
        if !which(look) {
            continue;
        }
        let style = text_style(TEXT, Colour::rgb(30, 30, 30));
        let (w, h) = area
            .estimate_text_size(&look.name, &style)
            .map_err(plot_err)?;
        let (w, h) = (w as i32, h as i32);
        let (cx, cy) = view.to_px(state.position);
        let inner = look
            .shape
            .as_ref()
            .map_or(0.0, |s| s.inner_radius() * view.scale());
        let half_diagonal = 0.5 * f64::from(w).hypot(f64::from(h));
        // A rotating body carries a mark from its centre along its x axis:
        // the name goes on the other side of the centre.
        let (c, sn) = (state.angle.cos(), state.angle.sin());
        let shift = if look.rotates {
            0.5 * (f64::from(w) * c.abs() + f64::from(h) * sn.abs()) + 2.0
        } else {
            0.0
        };
        let (sx, sy) = ((-c * shift).round() as i32, (sn * shift).round() as i32);
        let (ix, iy) = (cx + sx, cy + sy);
        let centred = (ix - w / 2, iy - h / 2, ix + w / 2, iy + h / 2);
        if half_diagonal + shift + 1.0 <= inner && contains(plot, centred) {
            let c = look.colour;
            let light = 0.299 * f64::from(c.r) + 0.587 * f64::from(c.g) + 0.114 * f64::from(c.b);
            let ink = if light < 150.0 {
                Colour::rgb(255, 255, 255)
            } else {
                Colour::rgb(20, 20, 20)
            };
            let style = text_style(TEXT, ink).pos(Pos::new(HPos::Center, VPos::Center));
            area.draw_text(&look.name, &style, (ix, iy))
                .map_err(plot_err)?;
            taken.push(centred);
            continue;
        }
        if !look.dynamic {
            continue; // a static body is labelled inside, or not at all
        }
        let b = body_box(look, state, view);
        let candidates = [
            (cx - w / 2, b.1 - 3 - h),
            (cx - w / 2, b.3 + 3),
            (b.2 + 4, cy - h / 2),
            (b.0 - 4 - w, cy - h / 2),
        ];
        let free = candidates
            .into_iter()
            .map(|(x, y)| (x, y, x + w, y + h))
            .find(|&r| {
                contains(plot, r)
                    && !taken.iter().any(|&t| overlaps(t, r))
                    && !obstacles.iter().any(|&(j, o)| j != i && overlaps(o, r))
            });
        if let Some(r) = free {
            let style = text_style(TEXT, Colour::rgb(30, 30, 30));
            area.draw_text(&look.name, &style, (r.0, r.1))
                .map_err(plot_err)?;
            taken.push(r);
        }
    }
    Ok(())
}

fn contains(outer: Boxed, inner: Boxed) -> bool {
    inner.0 >= outer.0 && inner.1 >= outer.1 && inner.2 <= outer.2 && inner.3 <= outer.3
}
