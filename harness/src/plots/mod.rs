//! Charts of `reports/`, drawn with plotters into SVG: work-precision
//! diagrams, convergence, stability failures, energy, trajectories, the
//! collision cases and the benchmark.
//!
//! One small chart model ([`Chart`], [`Series`]) serves them all, and holds
//! every chart to one standard:
//!
//! - legends outside the data: a band under each panel, or one under the
//!   whole figure when its panels draw the same series ([`legend`]);
//! - every series of a chart its own colour *and* its own marker or dash
//!   ([`style`]; [`Chart::check`] refuses a chart that breaks this), with
//!   one style per method across charts;
//! - text of at least 11 px at the stored size ([`TEXT`]);
//! - ticks chosen here ([`ticks`]): decades on log axes (`1e-4`), round
//!   steps on linear ones with the zero written `0`;
//! - references drawn as a wide pale line under the curves that follow
//!   them, lines before markers, filled markers before hollow ones, so a
//!   series under another still shows;
//! - a curve leaving a fixed axis range is cut where it leaves and marked
//!   there with an outward triangle (legend: "off scale"); points between
//!   two off-scale samples are not drawn as lines across the frame;
//! - a value exactly 0 on a log axis (which has no 0) is drawn in a band
//!   under the axis, labelled `0`, never on the lowest decade;
//! - slope guides thin, each with its own dash and its label at its end.
//!
//! Log axes are drawn as linear axes over log10 of the data.

pub mod bench;
pub mod convergence;
pub mod energy;
pub mod failures;
mod legend;
mod marks;
pub mod style;
pub mod ticks;
pub mod trajectories;
pub mod work_precision;

pub use style::{Dash, Marker, REFERENCE, REFERENCE_ALT, Style, method_style, palette};

use crate::clip::Rect;
use crate::pictures::font::{FAMILY, ensure_fonts};
use anyhow::{Context, Result, anyhow, bail};
use legend::{Entry, Sample};
use marks::{draw_marker, draw_off_scale, draw_polyline};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;
use ticks::Ticks;

/// Size of tick labels, legends and annotations, in plotters' units: its
/// SVG font size is `TEXT / 1.24` = 11.3 px (plotters divides by 1.24).
pub const TEXT: u32 = 14;
/// Axis titles (12.1 px).
const AXIS_TITLE: u32 = 15;
/// Panel titles (14.5 px).
const TITLE: u32 = 18;
/// Where legends start (px from a panel's left): under the plot's y axis.
const LEGEND_LEFT: i32 = 12;
/// Markers along a curve drawn without a marker at every point.
const SPARSE_MARKERS: usize = 10;
/// A series of more points than this gets sparse markers.
const DENSE: usize = 50;

/// What a series is to its chart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Role {
    /// Measured or computed data: line and markers.
    Data,
    /// A closed form or reference: a wide pale line under the data.
    Reference,
    /// A guide (slope): thin, labelled at its end, not in the legend, and
    /// not counted in the axis range.
    Guide,
}

/// One curve.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend label (a guide's label is written at its end).
    pub label: String,
    /// Points in data units (non-finite points break the line; on a log
    /// axis, 0 is drawn in the zero band and negative values skipped).
    pub points: Vec<(f64, f64)>,
    /// Colour, marker and dash.
    pub style: Style,
    /// Data, reference or guide.
    pub role: Role,
    /// Markers at about [`SPARSE_MARKERS`] points only (a dense curve).
    pub sparse: bool,
}

impl Series {
    /// A data series, a marker at every point.
    pub fn new(label: impl Into<String>, style: Style, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            points,
            style,
            role: Role::Data,
            sparse: false,
        }
    }

    /// A closed form or reference, drawn wide and pale under the data.
    pub fn reference(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            role: Role::Reference,
            ..Self::new(label, REFERENCE, points)
        }
    }

    /// A slope guide with its own `dash`, labelled `label` at its end.
    pub fn guide(label: impl Into<String>, dash: Dash, points: Vec<(f64, f64)>) -> Self {
        let style = Style {
            colour: style::GUIDE,
            marker: Marker::None,
            hollow: false,
            dash,
        };
        Self {
            role: Role::Guide,
            ..Self::new(label, style, points)
        }
    }

    /// A dense curve: markers at about [`SPARSE_MARKERS`] points.
    pub fn line(mut self) -> Self {
        self.sparse = true;
        self
    }

    /// The same series in another style.
    pub fn styled(mut self, style: Style) -> Self {
        self.style = style;
        self
    }

    fn width(&self) -> u32 {
        line_width(self.style, self.role)
    }
}

/// The line width (px) of a style in a role.
fn line_width(style: Style, role: Role) -> u32 {
    match role {
        Role::Reference if style.dash == Dash::Solid => 6,
        Role::Reference => 3,
        Role::Guide => 1,
        Role::Data => 2,
    }
}

/// One chart panel.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    /// Caption.
    pub title: String,
    /// x axis label (with unit).
    pub x_label: String,
    /// y axis label (with unit).
    pub y_label: String,
    /// log10 x axis.
    pub log_x: bool,
    /// log10 y axis.
    pub log_y: bool,
    /// Curves.
    pub series: Vec<Series>,
    /// Fixed y range in data units: curves leaving it are cut and marked
    /// off scale where they leave.
    pub y_range: Option<(f64, f64)>,
}

impl Chart {
    /// Refuses a chart whose series could be confused: two data or
    /// reference series of one colour, or of one marker and dash (alike in
    /// grey), or two guides of one dash.
    pub fn check(&self) -> Result<()> {
        for (i, a) in self.series.iter().enumerate() {
            for b in &self.series[i + 1..] {
                let guides = (a.role == Role::Guide, b.role == Role::Guide);
                let clash = match guides {
                    (true, true) => a.style.dash == b.style.dash,
                    (false, false) => {
                        a.style.colour == b.style.colour
                            || (a.style.grey_signature(), a.role)
                                == (b.style.grey_signature(), b.role)
                    }
                    _ => false,
                };
                if clash {
                    bail!(
                        "chart '{}': series '{}' and '{}' look alike (same colour, or same marker and dash)",
                        self.title,
                        a.label,
                        b.label
                    );
                }
            }
        }
        Ok(())
    }
}

/// A point in drawn units (log10 on log axes), classified.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Pt {
    /// Inside the axis range.
    In(f64, f64),
    /// Beyond a fixed y range.
    Out(f64, f64),
    /// 0 (or, `true`, negative) on a log y axis: drawn in the zero band at
    /// this x.
    Zero(f64, bool),
    /// Not drawable: breaks the line.
    Skip,
}

/// A chart ready to draw: its axes and its classified points.
struct Prepared {
    x: Ticks,
    y: Ticks,
    /// The zero band's centre (drawn y) and its upper edge, if any.
    zero: Option<(f64, f64)>,
    /// Whether the zero band holds negative values too (labelled `≤ 0`).
    negative: bool,
    points: Vec<Vec<Pt>>,
    off_scale: bool,
}

fn to_axis(v: f64, log: bool) -> Option<f64> {
    if !v.is_finite() {
        return None;
    }
    if log {
        (v > 0.0).then(|| v.log10())
    } else {
        Some(v)
    }
}

fn extent(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    lo.is_finite().then_some((lo, hi))
}

/// An axis over the data extent `(lo, hi)` (drawn units), padded.
fn axis(extent: Option<(f64, f64)>, log: bool) -> Ticks {
    let (lo, hi) = extent.unwrap_or((0.0, 1.0));
    if log {
        let pad = (0.04 * (hi - lo)).max(0.05);
        Ticks::log(lo - pad, hi + pad)
    } else {
        let pad = if hi > lo {
            0.05 * (hi - lo)
        } else {
            0.5 * lo.abs().max(1e-12)
        };
        Ticks::linear(lo - pad, hi + pad)
    }
}

impl Prepared {
    fn new(chart: &Chart) -> Result<Self> {
        let fixed = match chart.y_range {
            Some((lo, hi)) => {
                let (a, b) = (to_axis(lo, chart.log_y), to_axis(hi, chart.log_y));
                match (a, b) {
                    (Some(a), Some(b)) if a < b => Some((a, b)),
                    _ => bail!(
                        "chart '{}': y range {lo}..{hi} cannot be drawn",
                        chart.title
                    ),
                }
            }
            None => None,
        };
        let raw: Vec<Vec<Pt>> = chart
            .series
            .iter()
            .map(|s| {
                s.points
                    .iter()
                    .map(|&(x, y)| {
                        let Some(x) = to_axis(x, chart.log_x) else {
                            return Pt::Skip;
                        };
                        match to_axis(y, chart.log_y) {
                            Some(y) => match fixed {
                                Some((lo, hi)) if y < lo || y > hi => Pt::Out(x, y),
                                _ => Pt::In(x, y),
                            },
                            None if chart.log_y && y <= 0.0 && s.role != Role::Guide => {
                                Pt::Zero(x, y < 0.0)
                            }
                            None => Pt::Skip,
                        }
                    })
                    .collect()
            })
            .collect();
        // The range comes from the data and references; guides follow it.
        let counted = |guides: bool| {
            chart
                .series
                .iter()
                .zip(&raw)
                .filter(move |(s, _)| (s.role == Role::Guide) == guides)
                .flat_map(|(_, pts)| pts.iter().copied())
        };
        let xs = |guides: bool| {
            extent(counted(guides).filter_map(|p| match p {
                Pt::In(x, _) | Pt::Out(x, _) | Pt::Zero(x, _) => Some(x),
                Pt::Skip => None,
            }))
        };
        let ys = |guides: bool| {
            extent(counted(guides).filter_map(|p| match p {
                Pt::In(_, y) => Some(y),
                _ => None,
            }))
        };
        let x = axis(xs(false).or_else(|| xs(true)), chart.log_x);
        let mut y = match fixed {
            Some((lo, hi)) if chart.log_y => Ticks::log(lo, hi),
            Some((lo, hi)) => Ticks::linear(lo, hi),
            None => axis(ys(false).or_else(|| ys(true)), chart.log_y),
        };
        let has_zero = raw.iter().flatten().any(|p| matches!(p, Pt::Zero(..)));
        let negative = raw.iter().flatten().any(|p| matches!(p, Pt::Zero(_, true)));
        let zero = has_zero.then(|| {
            let band = 0.1 * (y.hi - y.lo);
            let top = y.lo;
            y.lo -= band;
            (top - 0.55 * band, top - 0.1 * band)
        });
        let off_scale = raw.iter().flatten().any(|p| matches!(p, Pt::Out(..)));
        Ok(Self {
            x,
            y,
            zero,
            negative,
            points: raw,
            off_scale,
        })
    }

    fn rect(&self) -> Rect {
        Rect {
            x: (self.x.lo, self.x.hi),
            y: (self.y.lo, self.y.hi),
        }
    }
}

/// The legend entries of a chart: its data and references that have
/// something drawn, then the marks it uses.
fn entries(chart: &Chart, prepared: &Prepared) -> Vec<Entry> {
    let mut out: Vec<Entry> = chart
        .series
        .iter()
        .zip(&prepared.points)
        .filter(|(s, pts)| s.role != Role::Guide && pts.iter().any(|p| *p != Pt::Skip))
        .map(|(s, _)| Entry {
            label: s.label.clone(),
            sample: Sample::Series(s.style, s.role),
        })
        .collect();
    if prepared.off_scale {
        out.push(Entry {
            label: "off scale: the curve leaves the axis range here".into(),
            sample: Sample::OffScale,
        });
    }
    if prepared.zero.is_some() {
        let label = if prepared.negative {
            "in the band labelled ≤ 0: 0 or negative (no log value)"
        } else {
            "in the band labelled 0: exactly 0 (no log value)"
        };
        out.push(Entry {
            label: label.into(),
            sample: Sample::Zero,
        });
    }
    out
}

/// One legend for the whole figure when its panels agree: at least one
/// series appears in several panels, every label has one look, and no two
/// labels share a colour.
fn shared_entries(per_panel: &[Vec<Entry>]) -> Option<Vec<Entry>> {
    if per_panel.len() < 2 {
        return None;
    }
    let mut union: Vec<Entry> = Vec::new();
    let mut repeated = false;
    for entry in per_panel.iter().flatten() {
        match union.iter().find(|e| e.label == entry.label) {
            Some(e) if e.sample != entry.sample => return None,
            Some(_) => repeated = true,
            None => union.push(entry.clone()),
        }
    }
    let colour = |e: &Entry| match e.sample {
        Sample::Series(s, _) => Some(s.colour),
        _ => None,
    };
    for (i, a) in union.iter().enumerate() {
        if union[i + 1..]
            .iter()
            .any(|b| colour(a).is_some() && colour(a) == colour(b))
        {
            return None;
        }
    }
    // Marks last, as in each panel's own legend.
    union.sort_by_key(|e| !matches!(e.sample, Sample::Series(..)));
    repeated.then_some(union)
}

/// Draws `chart` into `area` (no legend).
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &Chart,
    prepared: &Prepared,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let (x, y) = (&prepared.x, &prepared.y);
    let zero = prepared.zero;
    let zero_label = if prepared.negative { "≤ 0" } else { "0" };
    let y_extra: Vec<f64> = zero.iter().map(|z| z.0).collect();
    let plot_err = |e| anyhow!("chart '{}': {e}", chart.title);
    let mut ctx = ChartBuilder::on(area)
        .caption(&chart.title, (FAMILY, TITLE))
        .margin(12)
        .x_label_area_size(48)
        .y_label_area_size(76)
        .build_cartesian_2d(x.coord(&[]), y.coord(&y_extra))
        .map_err(plot_err)?;
    ctx.configure_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .x_label_formatter(&|v| x.label(*v))
        .y_label_formatter(&|v| match zero {
            Some((z, _)) if (v - z).abs() < 1e-9 => zero_label.into(),
            _ => y.label(*v),
        })
        .label_style((FAMILY, TEXT))
        .axis_desc_style((FAMILY, AXIS_TITLE))
        .bold_line_style(RGBColor(210, 210, 210))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(plot_err)?;
    let (bx, by) = area.get_base_pixel();
    let px = |(a, b): (f64, f64)| {
        let (u, v) = ctx.backend_coord(&(a, b));
        (u - bx, v - by)
    };
    let rect = prepared.rect();
    if let Some((_, sep)) = zero {
        // The axis break between the decades and the zero band.
        let (l, r) = (px((x.lo, sep)), px((x.hi, sep)));
        let style = Style {
            colour: style::GUIDE,
            marker: Marker::None,
            hollow: false,
            dash: Dash::Dotted,
        };
        draw_polyline(area, vec![l, r], style, 1)?;
    }
    // Lines: references, guides, then data; markers after every line.
    let order = |role: Role| {
        chart
            .series
            .iter()
            .zip(&prepared.points)
            .filter(move |(s, _)| s.role == role)
    };
    let mut exits: Vec<((i32, i32), bool, RGBColor)> = Vec::new();
    for role in [Role::Reference, Role::Guide, Role::Data] {
        for (series, pts) in order(role) {
            let colour = series.style.colour;
            for run in runs(pts, &rect, &mut |at: (f64, f64), up| {
                // Only data is marked where it leaves the scale.
                if role == Role::Data {
                    exits.push((px(at), up, colour));
                }
            }) {
                let pixels: Vec<(i32, i32)> = run.into_iter().map(&px).collect();
                if let (Role::Guide, Some(&end)) = (role, pixels.last()) {
                    guide_label(area, &series.label, end, &px, &rect)?;
                }
                draw_polyline(area, pixels, series.style, series.width())?;
            }
        }
    }
    let data: Vec<(usize, &Series, &Vec<Pt>)> = order(Role::Data)
        .enumerate()
        .map(|(i, (s, p))| (i, s, p))
        .collect();
    let count = data.len().max(1);
    for hollow in [false, true] {
        for &(i, series, pts) in data.iter().filter(|(_, s, _)| s.style.hollow == hollow) {
            for k in marker_indices(pts, series.sparse, i, count) {
                if let Pt::In(a, b) = pts[k] {
                    draw_marker(area, px((a, b)), series.style)?;
                }
            }
        }
    }
    for (at, up, colour) in exits {
        draw_off_scale(area, at, up, colour)?;
    }
    if let Some((z, _)) = zero {
        for (series, pts) in chart.series.iter().zip(&prepared.points) {
            let mut style = series.style;
            if style.marker == Marker::None {
                style.marker = Marker::Circle;
                style.hollow = true;
            }
            for p in pts {
                if let Pt::Zero(a, _) = *p {
                    draw_marker(area, px((a, z)), style)?;
                }
            }
        }
    }
    Ok(())
}

/// The drawable runs of a series' points: in-range neighbours joined; a
/// segment from an in-range point to an off-scale one cut where it leaves
/// the range, reporting that point (and whether it leaves by the top) to
/// `exit`; nothing between two off-scale points.
fn runs(pts: &[Pt], rect: &Rect, exit: &mut impl FnMut((f64, f64), bool)) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    let flush = |current: &mut Vec<(f64, f64)>, out: &mut Vec<Vec<(f64, f64)>>| {
        if current.len() > 1 {
            out.push(std::mem::take(current));
        }
        current.clear();
    };
    for (k, p) in pts.iter().enumerate() {
        let previous = k.checked_sub(1).map(|j| pts[j]);
        match (previous, *p) {
            (_, Pt::In(a, b)) => {
                if let Some(Pt::Out(c, d)) = previous
                    && let Some((enter, _)) = rect.clip((c, d), (a, b))
                {
                    exit(enter, d > rect.y.1);
                    current.push(enter);
                }
                current.push((a, b));
            }
            (Some(Pt::In(a, b)), Pt::Out(c, d)) => {
                if let Some((_, leave)) = rect.clip((a, b), (c, d)) {
                    current.push(leave);
                    exit(leave, d > rect.y.1);
                }
                flush(&mut current, &mut out);
            }
            _ => flush(&mut current, &mut out),
        }
    }
    flush(&mut current, &mut out);
    // Guides and references may reach beyond an automatic range: cut them.
    out.into_iter()
        .flat_map(|run| rect.clip_polyline(&run))
        .collect()
}

/// Which points of series number `i` (of `count`) get a marker.
fn marker_indices(pts: &[Pt], sparse: bool, i: usize, count: usize) -> Vec<usize> {
    let n = pts.len();
    // Beyond DENSE points, markers at every point would hide the lines
    // (and a reference under them).
    if !sparse && n <= DENSE {
        return (0..n).collect();
    }
    let stride = (n / SPARSE_MARKERS).max(1);
    // Staggered per series, so that coinciding curves show each marker.
    let offset = stride * (2 * i + 1) / (2 * count.max(1));
    (offset.min(n.saturating_sub(1))..n)
        .step_by(stride)
        .collect()
}

/// A guide's label at its end `at` (px), inside the plot.
fn guide_label<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    label: &str,
    at: (i32, i32),
    px: &impl Fn((f64, f64)) -> (i32, i32),
    rect: &Rect,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let top = px((rect.x.0, rect.y.1)).1;
    let (pos, dy) = if at.1 <= top + 4 {
        (Pos::new(HPos::Right, VPos::Top), 4)
    } else {
        (Pos::new(HPos::Right, VPos::Bottom), -4)
    };
    let font = (FAMILY, TEXT).into_font().color(&style::GUIDE).pos(pos);
    let (w, h) = (FAMILY, TEXT)
        .into_font()
        .box_size(label)
        .map_or((40, 12), |(w, h)| (w as i32, h as i32));
    let (x1, y0) = (at.0 - 4, at.1 + dy);
    let y1 = if dy > 0 { y0 + h } else { y0 - h };
    // A pale ground, so the label reads over the curves it crosses.
    area.draw(&Rectangle::new(
        [(x1 - w - 2, y0.min(y1) - 1), (x1 + 2, y0.max(y1) + 1)],
        WHITE.mix(0.8).filled(),
    ))
    .map_err(|e| anyhow!("chart label: {e}"))?;
    area.draw_text(label, &font, (x1, y0))
        .map_err(|e| anyhow!("chart label: {e}"))
}

/// Saves `panels` as one SVG, `columns` panels a row, each panel `w × h`
/// pixels plus its legend band (or the figure's one legend under all).
pub fn save_svg(path: &Path, panels: &[Chart], columns: usize, (w, h): (u32, u32)) -> Result<()> {
    ensure_fonts();
    for chart in panels {
        chart.check()?;
    }
    let prepared: Vec<Prepared> = panels.iter().map(Prepared::new).collect::<Result<_>>()?;
    let legends: Vec<Vec<Entry>> = panels
        .iter()
        .zip(&prepared)
        .map(|(c, p)| entries(c, p))
        .collect();
    let shared = shared_entries(&legends);
    let columns = columns.max(1);
    let rows = panels.len().div_ceil(columns).max(1);
    let width = w * columns as u32;
    let (band, bottom) = match &shared {
        Some(all) => (0, legend::height(all, width as i32, LEGEND_LEFT)),
        None => (
            legends
                .iter()
                .map(|e| legend::height(e, w as i32, LEGEND_LEFT))
                .max()
                .unwrap_or(0),
            0,
        ),
    };
    let cell = h + band as u32;
    let size = (width, cell * rows as u32 + bottom as u32);
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let (grid, under) = root.split_vertically(cell * rows as u32);
    let areas = grid.split_evenly((rows, columns));
    for (i, (area, chart)) in areas.iter().zip(panels).enumerate() {
        let (plot, band_area) = area.split_vertically(h);
        draw_panel(&plot, chart, &prepared[i])?;
        if shared.is_none() {
            legend::draw(&band_area, &legends[i], LEGEND_LEFT)?;
        }
    }
    if let Some(all) = &shared {
        legend::draw(&under, all, LEGEND_LEFT)?;
    }
    root.present()
        .map_err(|e| anyhow!("{e}"))
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chart(series: Vec<Series>) -> Chart {
        Chart {
            title: "t".into(),
            series,
            ..Chart::default()
        }
    }

    #[test]
    fn series_that_look_alike_are_refused() {
        let a = Series::new("a", palette(0), vec![(0.0, 1.0)]);
        let b = Series::new("b", palette(0), vec![(0.0, 2.0)]);
        assert!(chart(vec![a.clone(), b]).check().is_err());
        // Another colour but the same marker and dash: alike in grey.
        let c = Series::new(
            "c",
            Style {
                colour: RGBColor(1, 2, 3),
                ..palette(0)
            },
            vec![],
        );
        assert!(chart(vec![a.clone(), c]).check().is_err());
        let d = Series::new("d", palette(1), vec![]);
        assert!(chart(vec![a, d]).check().is_ok());
    }

    #[test]
    fn a_curve_leaving_a_fixed_range_is_cut_and_marked_where_it_leaves() {
        let c = Chart {
            y_range: Some((-1.0, 1.0)),
            series: vec![Series::new(
                "s",
                palette(0),
                vec![(0.0, 0.0), (1.0, 0.5), (2.0, 3.0), (3.0, -3.0), (4.0, 0.5)],
            )],
            ..chart(vec![])
        };
        let p = Prepared::new(&c).unwrap();
        assert!(p.off_scale);
        let mut exits = Vec::new();
        let runs = runs(&p.points[0], &p.rect(), &mut |at, up| exits.push((at, up)));
        // (0, 0)-(1, 0.5) then up to y = 1; the jump from +3 to -3 is not
        // drawn; then from y = -1 back to (4, 0.5).
        assert_eq!(runs.len(), 2, "{runs:?}");
        assert_eq!(runs[0].last().unwrap().1, 1.0);
        assert_eq!(runs[1][0].1, -1.0);
        assert_eq!(exits.len(), 2);
        assert!(exits[0].1 && !exits[1].1, "{exits:?}");
    }

    #[test]
    fn an_exact_zero_on_a_log_axis_goes_to_the_zero_band() {
        let c = Chart {
            log_y: true,
            series: vec![Series::new(
                "s",
                palette(0),
                vec![(1.0, 1e-3), (2.0, 0.0), (3.0, 1e-5)],
            )],
            ..chart(vec![])
        };
        let p = Prepared::new(&c).unwrap();
        let (centre, top) = p.zero.unwrap();
        assert!(p.y.lo < centre && centre < top && top < p.y.major[0]);
        assert_eq!(p.points[0][1], Pt::Zero(2.0, false));
        let labels = entries(&c, &p);
        assert!(labels.iter().any(|e| e.label.contains("exactly 0")));
    }

    #[test]
    fn a_figure_shares_its_legend_only_when_its_panels_agree() {
        let a = Series::new("a", palette(0), vec![(0.0, 1.0)]);
        let b = Series::new("b", palette(1), vec![(0.0, 1.0)]);
        let panels = [chart(vec![a.clone(), b.clone()]), chart(vec![a.clone()])];
        let legends: Vec<Vec<Entry>> = panels
            .iter()
            .map(|c| entries(c, &Prepared::new(c).unwrap()))
            .collect();
        assert_eq!(shared_entries(&legends).unwrap().len(), 2);
        // Same colour under two labels in two panels: each its own legend.
        let c = Series::new("c", palette(0), vec![(0.0, 1.0)]);
        let panels = [chart(vec![a, b.clone()]), chart(vec![c, b])];
        let legends: Vec<Vec<Entry>> = panels
            .iter()
            .map(|c| entries(c, &Prepared::new(c).unwrap()))
            .collect();
        assert!(shared_entries(&legends).is_none());
    }
}
