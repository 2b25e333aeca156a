//! Drawing one frame of a [`Film`] on any plotters backend (SVG for the
//! filmstrip, an RGB buffer for the GIF): the static part once
//! ([`background`]: axes in metres, ground lines, static bodies, spring
//! anchors, their names), then per frame the moving part ([`foreground`]:
//! trails, springs, joints, bodies at their pose and true size, their names where
//! they fit, event markers drawn once per place, zoomed insets of bodies
//! too small to see, the time), as the seed drew its simulations on screen
//! (§2.1.2, figures 5.3 and 6.6: the bodies' vertices and colours; the
//! current x, y and angular speed of every body go in the side table,
//! `super::table`).

use super::film::{Film, SpringEnd};
use super::font::FAMILY;
use super::view::{Layout, MARGIN, PARTICLE_PX, View, X_LABEL_AREA, Y_LABEL_AREA, round_px};
use super::{inset, labels};
use anyhow::{Result, anyhow};
use engine::{BodyState, Shape};
use nalgebra::{Rotation2, Vector2};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use scene::Colour;

/// Turns a plotters error into an `anyhow` one.
pub(crate) fn plot_err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("drawing failed: {e}")
}

/// The plotters colour of a scene colour.
pub(crate) fn rgb(c: Colour) -> RGBColor {
    RGBColor(c.r, c.g, c.b)
}

/// `c` mixed with white: `amount` 0 keeps it, 1 gives white.
pub(crate) fn tint(c: Colour, amount: f64) -> Colour {
    let mix = |v: u8| (f64::from(v) + (255.0 - f64::from(v)) * amount).round() as u8;
    Colour::rgb(mix(c.r), mix(c.g), mix(c.b))
}

/// `c` darkened: `factor` 1 keeps it, 0 gives black.
pub(crate) fn shade(c: Colour, factor: f64) -> Colour {
    let mix = |v: u8| (f64::from(v) * factor).round() as u8;
    Colour::rgb(mix(c.r), mix(c.g), mix(c.b))
}

/// Amount of white in a trail's colour.
pub(crate) const TRAIL_TINT: f64 = 0.3;
/// Amount of white in the faint whole-run path (filmstrip only).
pub(crate) const PATH_TINT: f64 = 0.82;
/// Darkening of outlines and orientation marks.
pub(crate) const OUTLINE_SHADE: f64 = 0.55;
/// Springs and anchors.
pub(crate) const INK: Colour = Colour::rgb(70, 70, 70);
/// Chart grid lines.
pub(crate) const GRID: Colour = Colour::rgb(225, 225, 225);
/// Chart fine grid lines.
pub(crate) const GRID_FINE: Colour = Colour::rgb(242, 242, 242);

/// The header's first line, at the top of a picture.
pub(crate) const TITLE_Y: i32 = 5;
/// Height of one header line (px).
pub(crate) const LINE_PX: i32 = 19;
/// Size of body, tick and event text (plotters units: 11.3 px in SVG,
/// 12 px em in the GIF).
pub(crate) const TEXT: u32 = 14;
/// Most moving bodies drawn with their trails: beyond, a pile of paths
/// hides the bodies.
const TRAILS_MOST: usize = 50;
/// Bodies spanning fewer pixels get no outline (it would cover them).
const OUTLINE_PX: f64 = 6.0;

/// Numbers for labels: four significant digits, no "-0"; below 1e-12 in
/// magnitude (round-off around a zero, such as the height at a located
/// landing) is shown as 0.
pub fn sig(v: f64) -> String {
    if v.abs() < 1e-12 || !v.is_finite() {
        return if v.is_finite() {
            "0".into()
        } else {
            format!("{v}")
        };
    }
    let a = v.abs();
    if (1e-3..1e6).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.decimals$}");
        if s.trim_start_matches('-')
            .trim_matches(|c| c == '0' || c == '.')
            .is_empty()
        {
            "0".into()
        } else {
            s
        }
    } else {
        format!("{v:.3e}")
    }
}

/// What the live label says at sample `k`: the time (every body's state
/// is in the side table).
pub fn live_label(film: &Film, k: usize) -> String {
    format!("t = {} s", sig(film.times[k]))
}

/// Text of `size` in `colour`.
pub(crate) fn text_style(size: u32, colour: Colour) -> TextStyle<'static> {
    (FAMILY, size).into_font().color(&rgb(colour))
}

/// Draws `lines` of header text from the top of `area`, the first one bold.
pub(crate) fn header<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    lines: &[&str],
) -> Result<()> {
    for (i, line) in lines.iter().enumerate() {
        let style = if i == 0 {
            (FAMILY, 16)
                .into_font()
                .style(FontStyle::Bold)
                .color(&BLACK)
        } else {
            text_style(TEXT, Colour::rgb(40, 40, 40))
        };
        area.draw_text(line, &style, (MARGIN as i32, TITLE_Y + i as i32 * LINE_PX))
            .map_err(plot_err)?;
    }
    Ok(())
}

/// Fills `area` white, draws the `header` lines, the axes in metres over
/// `layout`'s window, the ground lines, the static bodies and the world
/// anchors of springs; returns the view to draw the moving part with.
pub(crate) fn background<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    film: &Film,
    layout: &Layout,
    header_lines: &[&str],
) -> Result<View> {
    area.fill(&WHITE).map_err(plot_err)?;
    header(area, header_lines)?;
    let mut chart = ChartBuilder::on(area)
        .margin(MARGIN)
        .margin_top(layout.header)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(layout.x.0..layout.x.1, layout.y.0..layout.y.1)
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .x_desc("x (m)")
        .y_desc("y (m)")
        .x_labels(8)
        .y_labels(6)
        .label_style(text_style(TEXT, Colour::rgb(60, 60, 60)))
        .axis_desc_style(text_style(15, Colour::rgb(60, 60, 60)))
        .bold_line_style(rgb(GRID))
        .light_line_style(rgb(GRID_FINE))
        .draw()
        .map_err(plot_err)?;
    let (px, py) = chart.plotting_area().get_pixel_range();
    let (bx, by) = area.get_base_pixel();
    let view = View::new(
        layout,
        px.start - bx..px.end - bx,
        py.start - by..py.end - by,
    );
    for &level in &film.grounds {
        let (x0, y) = view.to_px(Vector2::new(view.x.0, level));
        let (x1, _) = view.to_px(Vector2::new(view.x.1, level));
        area.draw(&PathElement::new(
            vec![(x0, y), (x1, y)],
            rgb(INK).stroke_width(2),
        ))
        .map_err(plot_err)?;
        // Hatching under the ground line.
        let mut x = x0 + 4;
        while x < x1 {
            area.draw(&PathElement::new(
                vec![(x, y + 1), (x - 6, y + 7)],
                rgb(tint(INK, 0.5)).stroke_width(1),
            ))
            .map_err(plot_err)?;
            x += 10;
        }
    }
    if let Some(states) = film.states.first() {
        for (i, look) in film.bodies.iter().enumerate() {
            if !look.dynamic {
                draw_body(area, film, &view, i, &states[i])?;
            }
        }
        labels::draw(area, film, &view, states, |b| !b.dynamic, &mut Vec::new())?;
    }
    for (a, b) in &film.springs {
        for end in [a, b] {
            if let SpringEnd::World(p) = end {
                let (x, y) = view.to_px(*p);
                area.draw(&Rectangle::new(
                    [(x - 4, y - 4), (x + 4, y + 4)],
                    rgb(INK).filled(),
                ))
                .map_err(plot_err)?;
            }
        }
    }
    Ok(view)
}

/// Which trails the foreground draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Trails {
    /// The path so far.
    Past,
    /// The whole run faint, the path so far strong (stills).
    WholeAndPast,
}

/// Sample indices of the trails: those the trailed bodies' paths need so
/// that the polyline through them passes within 1 % of the smallest
/// moving body's width of every sample's centre (1/2000 of the run's
/// extent when no moving body has a shape), the first and the last
/// included. `count` caps the samples taken when no body is trailed.
pub(crate) fn trail_samples(film: &Film, count: usize) -> Vec<usize> {
    let n = film.times.len();
    let moving: Vec<usize> = (0..film.bodies.len())
        .filter(|&b| film.bodies[b].dynamic)
        .collect();
    if moving.is_empty() || moving.len() > TRAILS_MOST {
        let stride = n.div_ceil(count.max(1)).max(1);
        return (0..n).step_by(stride).collect();
    }
    let widest = film
        .bounds()
        .map_or(1.0, |(lo, hi)| (hi - lo).x.max((hi - lo).y));
    let tolerance = moving
        .iter()
        .filter_map(|&b| film.bodies[b].shape.as_ref().map(super::film::shape_width))
        .filter(|w| w.is_finite() && *w > 0.0)
        .reduce(f64::min)
        .map_or(widest / 2000.0, |w| 0.01 * w);
    // The trail is drawn from the samples themselves: no rounding.
    let exact = crate::replay::thin::Quanta {
        t: 0.0,
        p: 0.0,
        a: 0.0,
    };
    let mut keep = vec![false; n];
    for &b in &moving {
        for i in crate::replay::thin::keep_body(&film.times, &film.states, b, 0.0, exact, tolerance)
        {
            keep[i] = true;
        }
    }
    (0..n).filter(|&i| keep[i]).collect()
}

/// Draws the moving part at sample `k`: trails, springs, dynamic bodies,
/// their names, the markers of the events passed (once per place, with a
/// count), a ring round each body too small to see (its zoomed inset is
/// drawn beside the plot, `super::inset`), and the time at `label_at`.
pub(crate) fn foreground<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    film: &Film,
    view: &View,
    k: usize,
    (trails, trail_idx): (Trails, &[usize]),
    label_at: (i32, i32),
) -> Result<()> {
    let states = &film.states[k];
    let moving = film.bodies.iter().filter(|b| b.dynamic).count();
    for (i, look) in film.bodies.iter().enumerate() {
        if !look.dynamic || moving > TRAILS_MOST {
            continue;
        }
        let centre = |j: usize| view.to_px(film.states[j][i].position);
        if trails == Trails::WholeAndPast {
            let mut all: Vec<(i32, i32)> = trail_idx.iter().map(|&j| centre(j)).collect();
            all.push(centre(film.times.len() - 1));
            area.draw(&PathElement::new(
                all,
                rgb(tint(look.colour, PATH_TINT)).stroke_width(1),
            ))
            .map_err(plot_err)?;
        }
        let mut past: Vec<(i32, i32)> = trail_idx
            .iter()
            .take_while(|&&j| j <= k)
            .map(|&j| centre(j))
            .collect();
        past.push(centre(k));
        past.dedup();
        if past.len() > 1 {
            // Bitmaps draw 1 px lines cleanly; wider ones are polygons,
            // jagged along a curve of many short segments.
            let width = if trails == Trails::Past { 1 } else { 2 };
            area.draw(&PathElement::new(
                past,
                rgb(tint(look.colour, TRAIL_TINT)).stroke_width(width),
            ))
            .map_err(plot_err)?;
        }
    }
    for (i, look) in film.bodies.iter().enumerate() {
        if look.dynamic {
            draw_body(area, film, view, i, &states[i])?;
        }
    }
    // Springs and joints over the bodies, so that the bodies do not hide
    // them.
    for (a, b) in &film.springs {
        draw_spring(area, view.to_px(a.at(states)), view.to_px(b.at(states)))?;
    }
    // A joint as Box2D draws it: each body's centre to its anchor, and
    // anchor to anchor (a revolute's coincide: its pivot).
    for (a, b) in &film.joints {
        let (pa, pb) = (view.to_px(a.at(states)), view.to_px(b.at(states)));
        let centre = |end: &SpringEnd, p: (i32, i32)| match end {
            SpringEnd::Body { body, .. } => view.to_px(states[*body].position),
            SpringEnd::World(_) => p,
        };
        let path = vec![centre(a, pa), pa, pb, centre(b, pb)];
        area.draw(&PathElement::new(path, rgb(INK).stroke_width(1)))
            .map_err(plot_err)?;
        for p in [pa, pb] {
            area.draw(&Circle::new(p, 2, rgb(INK).filled()))
                .map_err(plot_err)?;
        }
    }
    let mut taken = Vec::new();
    // Events at one place (the apex of 100 bounces) are one marker and one
    // label with their count, not a hundred drawn over each other.
    let t = film.times[k];
    let mut places: Vec<(&str, (i32, i32), usize)> = Vec::new();
    for mark in film.marks.iter().filter(|m| m.t <= t) {
        let p = view.to_px(mark.position);
        match places
            .iter_mut()
            .find(|(n, q, _)| *n == mark.name && (q.0 - p.0).abs() <= 6 && (q.1 - p.1).abs() <= 6)
        {
            Some(place) => place.2 += 1,
            None => places.push((&mark.name, p, 1)),
        }
    }
    for (name, (x, y), count) in places {
        area.draw(&Circle::new((x, y), 4, BLACK.stroke_width(1)))
            .map_err(plot_err)?;
        let text = if count > 1 {
            format!("{name} ×{count}")
        } else {
            name.to_owned()
        };
        // Left of the marker near the right edge, so the name stays inside.
        let left = x > view.px.end - 90;
        let anchor = if left { HPos::Right } else { HPos::Left };
        let style = text_style(TEXT, Colour::rgb(30, 30, 30)).pos(Pos::new(anchor, VPos::Top));
        let at = if left {
            (x - 6, y - 18)
        } else {
            (x + 6, y - 18)
        };
        area.draw_text(&text, &style, at).map_err(plot_err)?;
        let (w, h) = area
            .estimate_text_size(&text, &style)
            .map_or((60, 14), |(w, h)| (w as i32, h as i32));
        let x0 = if left { at.0 - w } else { at.0 };
        taken.push((x0, at.1, x0 + w, at.1 + h));
    }
    labels::draw(area, film, view, states, |b| b.dynamic, &mut taken)?;
    inset::rings(area, film, view, k)?;
    area.draw_text(
        &live_label(film, k),
        &text_style(TEXT, Colour::rgb(20, 20, 20)),
        label_at,
    )
    .map_err(plot_err)?;
    Ok(())
}

/// A spring as a zigzag between two pixels.
fn draw_spring<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    a: (i32, i32),
    b: (i32, i32),
) -> Result<()> {
    let (ax, ay) = (f64::from(a.0), f64::from(a.1));
    let (dx, dy) = (f64::from(b.0) - ax, f64::from(b.1) - ay);
    let length = dx.hypot(dy);
    if length < 2.0 {
        return Ok(());
    }
    let (ux, uy) = (dx / length, dy / length);
    let (nx, ny) = (-uy, ux);
    let coils = 14;
    let amplitude = 5.0;
    let lead = 0.1;
    let mut points = vec![a];
    for j in 0..=coils {
        let f = lead + (1.0 - 2.0 * lead) * j as f64 / coils as f64;
        let side = if j == 0 || j == coils {
            0.0
        } else if j % 2 == 0 {
            amplitude
        } else {
            -amplitude
        };
        points.push((
            (ax + f * dx + side * nx).round() as i32,
            (ay + f * dy + side * ny).round() as i32,
        ));
    }
    points.push(b);
    area.draw(&PathElement::new(points, rgb(INK).stroke_width(1)))
        .map_err(plot_err)?;
    Ok(())
}

/// The outline of a polygon, circle, capsule or rounded polygon in its own
/// frame (m), a segment's two ends; a compound has one per part (see
/// [`Shape::pieces`]).
fn outline(shape: &Shape) -> Vec<Vector2<f64>> {
    match shape {
        Shape::Polygon(p) => p.vertices().to_vec(),
        Shape::Rounded(r) => r.outline(48),
        Shape::Circle(c) => (0..48)
            .map(|j| {
                let a = std::f64::consts::TAU * j as f64 / 48.0;
                Vector2::new(a.cos(), a.sin()) * c.radius
            })
            .collect(),
        Shape::Compound(_) => Vec::new(),
        // An open line, drawn by `draw_body` (see `chain_line`).
        Shape::Chain(_) => Vec::new(),
    }
}

/// Body `i` at `state`, at its true size: its shape filled in its colour
/// with a darker outline and a mark from the centre along its x axis (so
/// rotation shows on a circle too), both left out on a body too small to
/// carry them; a particle as a dot; a shapeless static body as a small
/// square.
pub(crate) fn draw_body<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    film: &Film,
    view: &View,
    i: usize,
    state: &BodyState,
) -> Result<()> {
    let look = &film.bodies[i];
    let centre = view.to_px(state.position);
    let edge = rgb(shade(look.colour, OUTLINE_SHADE));
    let Some(shape) = &look.shape else {
        if look.dynamic {
            area.draw(&Circle::new(centre, PARTICLE_PX, rgb(look.colour).filled()))
                .map_err(plot_err)?;
            area.draw(&Circle::new(centre, PARTICLE_PX, edge.stroke_width(1)))
                .map_err(plot_err)?;
        } else {
            let (x, y) = centre;
            area.draw(&Rectangle::new(
                [(x - 4, y - 4), (x + 4, y + 4)],
                rgb(INK).filled(),
            ))
            .map_err(plot_err)?;
        }
        return Ok(());
    };
    if let Shape::Chain(chain) = shape {
        // A chain is a line, not a region: its points joined (a loop
        // closed), ghosts included, in the outline's shade.
        let rotation = Rotation2::new(state.angle);
        let mut points: Vec<(i32, i32)> = chain
            .points()
            .iter()
            .map(|v| view.to_px(state.position + rotation * v))
            .collect();
        if chain.is_loop() {
            points.push(points[0]);
        }
        area.draw(&PathElement::new(points, edge.stroke_width(2)))
            .map_err(plot_err)?;
        return Ok(());
    }
    let span = 2.0 * look.radius() * view.scale();
    let outlined = span >= OUTLINE_PX;
    let rotation = Rotation2::new(state.angle);
    let fill = rgb(look.colour).filled();
    let mut reach: f64 = 0.0;
    for (offset, angle, piece) in shape.pieces() {
        let piece_rotation = rotation * Rotation2::new(angle);
        let origin = state.position + rotation * offset;
        let local = outline(piece);
        reach = reach.max(
            local
                .iter()
                .map(|v| (offset + Rotation2::new(angle) * v).x)
                .fold(0.0, f64::max),
        );
        let corners: Vec<(f64, f64)> = local
            .iter()
            .map(|v| view.to_px_f(origin + piece_rotation * v))
            .collect();
        let clipped = view.clip(&corners);
        let whole = clipped.len() == corners.len() && clipped == corners;
        match piece {
            // A circle wholly inside the plot is drawn as one (exact in SVG).
            Shape::Circle(c) if whole => {
                let at = view.to_px(origin);
                let radius = (c.radius * view.scale()).round().max(1.0) as i32;
                area.draw(&Circle::new(at, radius, fill))
                    .map_err(plot_err)?;
                if outlined {
                    area.draw(&Circle::new(at, radius, edge.stroke_width(1)))
                        .map_err(plot_err)?;
                }
            }
            _ if clipped.len() >= 3 => {
                let pixels: Vec<(i32, i32)> = clipped.into_iter().map(round_px).collect();
                area.draw(&Polygon::new(pixels.clone(), fill))
                    .map_err(plot_err)?;
                if outlined {
                    let mut closed = pixels;
                    closed.push(closed[0]);
                    area.draw(&PathElement::new(closed, edge.stroke_width(1)))
                        .map_err(plot_err)?;
                }
            }
            // A segment: a line two pixels wide in the outline's colour.
            _ if corners.len() == 2 => {
                let ends: Vec<(i32, i32)> = corners.into_iter().map(round_px).collect();
                area.draw(&PathElement::new(ends, edge.stroke_width(2)))
                    .map_err(plot_err)?;
            }
            _ => {}
        }
    }
    if look.rotates && span >= 2.0 * OUTLINE_PX {
        let tip = view.to_px(state.position + rotation * Vector2::new(reach, 0.0));
        area.draw(&PathElement::new(vec![centre, tip], edge.stroke_width(2)))
            .map_err(plot_err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_keep_four_significant_digits() {
        assert_eq!(sig(0.0), "0");
        assert_eq!(sig(-0.0), "0");
        assert_eq!(sig(367.1015801), "367.1");
        assert_eq!(sig(4.326333611), "4.326");
        assert_eq!(sig(-0.0123456), "-0.01235");
        assert_eq!(sig(1.2e-7), "1.200e-7");
        assert_eq!(sig(-0.00001), "-1.000e-5");
        assert_eq!(sig(-2.7e-17), "0");
    }

    #[test]
    fn tints_and_shades_stay_in_range() {
        let c = Colour::rgb(200, 10, 0);
        assert_eq!(tint(c, 0.0), c);
        assert_eq!(tint(c, 1.0), Colour::rgb(255, 255, 255));
        assert_eq!(shade(c, 0.5), Colour::rgb(100, 5, 0));
    }
}
