//! Stills as SVG: a filmstrip of a few frames of a run (the scene drawn at
//! evenly spaced times, each with the path so far over the faint path of
//! the whole run), and for a `[linear_test]` scene, which has no bodies, its
//! y(t) curve against the exact solution.

use super::axis_range::drawable;
use super::draw::{Trails, background, foreground, header, plot_err, trail_samples};
use super::film::Film;
use super::font::{FAMILY, ensure_fonts};
use super::view::{Layout, MARGIN};
use super::{inset, table};
use anyhow::Result;
use plotters::prelude::*;

/// Panel width of the filmstrip (px).
const PANEL_WIDTH: u32 = 420;
/// Header of the whole filmstrip (px): title, subtitle, note.
const STRIP_HEADER: u32 = 58;
/// Header of one panel (px): its live label.
const PANEL_HEADER: u32 = 24;
/// Samples drawn per trail: SVG coordinates are whole pixels, so fewer,
/// longer segments draw a smoother curve.
const TRAIL_POINTS: usize = 160;

/// The filmstrip SVG of `film`: `frames` panels (2 per row, each a plot
/// and its side table) at evenly spaced times from the first sample to the
/// last.
pub fn filmstrip(film: &Film, frames: usize) -> Result<String> {
    ensure_fonts();
    let picks = film.evenly_spaced(frames);
    let layout = Layout::plan(film, PANEL_WIDTH, PANEL_HEADER, 150..330)?;
    let cols = picks.len().clamp(1, 2);
    let rows = picks.len().div_ceil(cols).max(1);
    let side = table::width(film);
    let nominal = layout.nominal_view();
    let insets_top = (PANEL_HEADER + table::height(film) + 8) as i32;
    let panel = (
        layout.width + side,
        layout
            .height
            .max(insets_top as u32 + inset::height(film, &nominal, side)),
    );
    let size = (panel.0 * cols as u32, STRIP_HEADER + panel.1 * rows as u32);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        let note = strip_note(film, &layout);
        header(&root, &[&film.title, &film.subtitle, &note])?;
        let body = root.margin(STRIP_HEADER, 0, 0, 0);
        let panels = body.split_evenly((rows, cols));
        let trail_idx = trail_samples(film, TRAIL_POINTS);
        for (panel, &k) in panels.iter().zip(&picks) {
            let (plot, beside) = panel.split_horizontally(layout.width);
            let (plot, _) = plot.split_vertically(layout.height);
            let view = background(&plot, film, &layout, &[])?;
            foreground(
                &plot,
                film,
                &view,
                k,
                (Trails::WholeAndPast, &trail_idx),
                (MARGIN as i32, 5),
            )?;
            table::draw(&beside.margin(PANEL_HEADER, 0, 0, 0), film, k)?;
            for zoom in inset::plan(film, &view, insets_top, side) {
                inset::draw(&beside, film, &view, &zoom, k, &trail_idx)?;
            }
        }
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
}

/// The third header line: what is drawn, and any zoomed inset.
fn strip_note(film: &Film, layout: &Layout) -> String {
    let mut note = String::from(
        "Frames at evenly spaced times; lines: path of each centre of mass (faint: whole run). Axes in metres, one scale on both; bodies at their true size.",
    );
    // The insets depend only on the layout's scale, the same for every
    // panel: find them on a view of the nominal plot size.
    let zoomed: Vec<String> = inset::tiny(film, &layout.nominal_view())
        .into_iter()
        .map(|i| film.bodies[i].name.clone())
        .collect();
    if !zoomed.is_empty() {
        note.push_str(&format!(
            " Too small to see at this scale, ringed in the plot and zoomed in an inset beside it: {}.",
            zoomed.join(", ")
        ));
    }
    if let Some(widened) = &layout.note {
        note.push(' ');
        note.push_str(widened);
    }
    note
}

/// A `[linear_test]` run as SVG: the numerical y(t) (dots and line) and
/// the exact solution, over the whole run and over its first tenth (the
/// stiff transient).
pub fn linear_test_curve(
    title: &str,
    subtitle: &str,
    t: &[f64],
    y: &[f64],
    exact: impl Fn(f64) -> f64,
) -> Result<String> {
    ensure_fonts();
    let mut svg = String::new();
    let t_end = t.last().copied().unwrap_or(1.0);
    {
        let root = SVGBackend::with_string(&mut svg, (1000, 440)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        header(
            &root,
            &[
                title,
                subtitle,
                "Blue: the method's y(t) at every step; black: the exact solution. Right: the first tenth of the run.",
            ],
        )?;
        let panels = root.margin(STRIP_HEADER, 0, 0, 0).split_evenly((1, 2));
        for (panel, span) in panels.iter().zip([t_end, 0.1 * t_end]) {
            curve_panel(panel, t, y, &exact, span)?;
        }
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
}

fn curve_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    t: &[f64],
    y: &[f64],
    exact: &impl Fn(f64) -> f64,
    span: f64,
) -> Result<()> {
    let points: Vec<(f64, f64)> = t
        .iter()
        .zip(y)
        .filter(|(t, y)| **t <= span && y.is_finite())
        .map(|(t, y)| (*t, *y))
        .collect();
    let exact_points: Vec<(f64, f64)> = (0..=400)
        .map(|j| {
            let s = span * j as f64 / 400.0;
            (s, exact(s))
        })
        .collect();
    let (lo, hi) = points
        .iter()
        .chain(&exact_points)
        .map(|p| p.1)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    // Checked before the padding, which could overflow.
    let y_range = drawable(lo, hi, "y")?;
    let (lo, hi) = (y_range.lo, y_range.hi);
    let pad = (0.05 * (hi - lo)).max(1e-12);
    let y_range = drawable(lo - pad, hi + pad, "y")?;
    let t_range = drawable(0.0, span.max(1e-12), "t (s)")?;
    let mut chart = ChartBuilder::on(area)
        .margin(MARGIN)
        .x_label_area_size(34)
        .y_label_area_size(70)
        .build_cartesian_2d(t_range.lo..t_range.hi, y_range.lo..y_range.hi)
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc("y")
        .label_style((FAMILY, 14))
        .axis_desc_style((FAMILY, 15))
        .bold_line_style(RGBColor(225, 225, 225))
        .light_line_style(RGBColor(242, 242, 242))
        .draw()
        .map_err(plot_err)?;
    chart
        .draw_series(LineSeries::new(exact_points, BLACK.stroke_width(1)))
        .map_err(plot_err)?;
    let blue = RGBColor(0x1f, 0x77, 0xb4);
    chart
        .draw_series(LineSeries::new(
            points.clone(),
            blue.mix(0.5).stroke_width(1),
        ))
        .map_err(plot_err)?;
    if points.len() <= 400 {
        chart
            .draw_series(points.iter().map(|&p| Circle::new(p, 2, blue.filled())))
            .map_err(plot_err)?;
    }
    Ok(())
}
