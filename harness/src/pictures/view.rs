//! From world metres to pixels: the picture's size and the world window
//! shown (one scale on both axes, so shapes keep their proportions, and
//! every body at its true size), and the window of a zoomed inset.

use super::axis_range::{MAX_COORDINATE, drawable};
use super::film::Film;
use anyhow::Result;
use nalgebra::Vector2;
use std::ops::Range;

/// Space around the chart (px).
pub const MARGIN: u32 = 10;
/// Height of the x-axis labels (px).
pub const X_LABEL_AREA: u32 = 42;
/// Width of the y-axis labels (px).
pub const Y_LABEL_AREA: u32 = 66;
/// Free space between the bodies' extent and the plot's edge (px).
const INSET: f64 = 14.0;
/// A body whose outline spans fewer pixels than this is too small to see
/// at the scale of the run (a 0.1 m box on a 370 m trajectory): it gets a
/// zoomed inset (`super::inset`).
pub const TINY_PX: f64 = 4.0;
/// Radius of the dot that stands for a particle (px).
pub const PARTICLE_PX: i32 = 6;

/// The size of a picture and of its plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Picture width (px).
    pub width: u32,
    /// Picture height (px).
    pub height: u32,
    /// Height of the header above the chart (px).
    pub header: u32,
    /// The world window's x range (m).
    pub x: (f64, f64),
    /// The world window's y range (m).
    pub y: (f64, f64),
    /// Set when an axis had to be widened to be drawn (see
    /// [`super::axis_range`]), saying so.
    pub note: Option<String>,
}

impl Layout {
    /// Plans a picture `width` px wide with a `header` px band on top, whose
    /// plot shows the whole run of `film` at one scale; the plot height is
    /// what the run's aspect asks for, kept within `plot_height` (px).
    ///
    /// Fails when the run reaches coordinates no picture can show (beyond
    /// ±[`MAX_COORDINATE`] m); widens, with a note, a view too narrow for
    /// its distance from the origin ([`super::axis_range`]).
    pub fn plan(film: &Film, width: u32, header: u32, plot_height: Range<u32>) -> Result<Self> {
        let (lo, hi) = film
            .bounds()
            .unwrap_or((Vector2::repeat(-1.0), Vector2::repeat(1.0)));
        // Checked first, so that the sizes and the centre below stay finite.
        drawable(lo.x, hi.x, "x (m)")?;
        drawable(lo.y, hi.y, "y (m)")?;
        let max_radius = film
            .bodies
            .iter()
            .map(|b| b.radius())
            .fold(0.0, f64::max)
            .min(MAX_COORDINATE);
        let mut size = hi - lo;
        let mut big = size.x.max(size.y);
        if big.is_nan() || big <= 0.0 {
            big = (4.0 * max_radius).max(1.0);
        }
        // A run along one line still gets some height (or width).
        size.x = size.x.max(0.2 * big) + 0.1 * big;
        size.y = size.y.max(0.2 * big) + 0.1 * big;
        let centre = lo + 0.5 * (hi - lo);
        let plot_w = f64::from(width - 2 * MARGIN - Y_LABEL_AREA);
        let wanted_h = plot_w * size.y / size.x;
        let plot_h = wanted_h
            .round()
            .clamp(f64::from(plot_height.start), f64::from(plot_height.end));
        let scale = ((plot_w - 2.0 * INSET) / size.x).min((plot_h - 2.0 * INSET) / size.y);
        let half = Vector2::new(plot_w, plot_h) / (2.0 * scale);
        let x = drawable(centre.x - half.x, centre.x + half.x, "x (m)")?;
        let y = drawable(centre.y - half.y, centre.y + half.y, "y (m)")?;
        let notes: Vec<String> = [x.note, y.note].into_iter().flatten().collect();
        Ok(Self {
            width,
            height: header + plot_h as u32 + X_LABEL_AREA + MARGIN,
            header,
            x: (x.lo, x.hi),
            y: (y.lo, y.hi),
            note: (!notes.is_empty()).then(|| notes.join(" ")),
        })
    }
}

impl Layout {
    /// The view of a plot of this layout at its nominal size (the drawn
    /// one agrees to a pixel): for sizing what depends on the scale before
    /// drawing.
    pub fn nominal_view(&self) -> View {
        let plot_w = (self.width - 2 * MARGIN - Y_LABEL_AREA) as i32;
        let plot_h = (self.height - self.header - X_LABEL_AREA - MARGIN) as i32;
        View::new(self, 0..plot_w, 0..plot_h)
    }
}

/// The mapping from world to pixels of one drawn chart.
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    /// World x range (m) of the plot.
    pub x: (f64, f64),
    /// World y range (m) of the plot.
    pub y: (f64, f64),
    /// Plot pixel columns, relative to the drawing area.
    pub px: Range<i32>,
    /// Plot pixel rows (top to bottom), relative to the drawing area.
    pub py: Range<i32>,
}

impl View {
    /// The view of a plot covering `px` × `py` with `layout`'s window.
    pub fn new(layout: &Layout, px: Range<i32>, py: Range<i32>) -> Self {
        Self {
            x: layout.x,
            y: layout.y,
            px,
            py,
        }
    }

    /// The view of `px` × `py` centred on world point `centre` (m) at
    /// `scale` pixels per metre (a zoomed inset).
    pub fn around(centre: Vector2<f64>, scale: f64, px: Range<i32>, py: Range<i32>) -> Self {
        let half_w = f64::from(px.end - px.start) / (2.0 * scale);
        let half_h = f64::from(py.end - py.start) / (2.0 * scale);
        Self {
            x: (centre.x - half_w, centre.x + half_w),
            y: (centre.y - half_h, centre.y + half_h),
            px,
            py,
        }
    }

    /// The plot's pixel rectangle, for clipping lines to it.
    pub fn pixel_rect(&self) -> crate::clip::Rect {
        crate::clip::Rect {
            x: (f64::from(self.px.start), f64::from(self.px.end)),
            y: (f64::from(self.py.start), f64::from(self.py.end)),
        }
    }

    /// Whether a body of `radius` (m) is too small to see here.
    pub fn too_small(&self, radius: f64) -> bool {
        let span = 2.0 * radius * self.scale();
        span > 0.0 && span < TINY_PX
    }

    /// Pixels per metre (the smaller of the two axes, which agree to a
    /// pixel).
    pub fn scale(&self) -> f64 {
        let sx = f64::from(self.px.end - self.px.start) / (self.x.1 - self.x.0);
        let sy = f64::from(self.py.end - self.py.start) / (self.y.1 - self.y.0);
        sx.min(sy)
    }

    /// The pixel of world point `p`, unrounded.
    pub fn to_px_f(&self, p: Vector2<f64>) -> (f64, f64) {
        let fx = (p.x - self.x.0) / (self.x.1 - self.x.0);
        let fy = (self.y.1 - p.y) / (self.y.1 - self.y.0);
        (
            f64::from(self.px.start) + fx * f64::from(self.px.end - self.px.start),
            f64::from(self.py.start) + fy * f64::from(self.py.end - self.py.start),
        )
    }

    /// The pixel of world point `p`.
    pub fn to_px(&self, p: Vector2<f64>) -> (i32, i32) {
        round_px(self.to_px_f(p))
    }

    /// Clips a convex polygon in pixels to the plot (Sutherland–Hodgman),
    /// so that a body larger than the view (a long floor) stays inside it.
    pub fn clip(&self, polygon: &[(f64, f64)]) -> Vec<(f64, f64)> {
        let (x0, x1) = (f64::from(self.px.start), f64::from(self.px.end));
        let (y0, y1) = (f64::from(self.py.start), f64::from(self.py.end));
        let mut out = polygon.to_vec();
        // Each edge: inside test, and the crossing of a segment with it.
        let edges: [(usize, f64, bool); 4] =
            [(0, x0, true), (0, x1, false), (1, y0, true), (1, y1, false)];
        for (axis, bound, keep_above) in edges {
            let inside = |p: (f64, f64)| {
                let v = if axis == 0 { p.0 } else { p.1 };
                if keep_above { v >= bound } else { v <= bound }
            };
            let input = std::mem::take(&mut out);
            for (j, &q) in input.iter().enumerate() {
                let p = input[(j + input.len() - 1) % input.len()];
                let cross = || {
                    let (a, b) = if axis == 0 { (p.0, q.0) } else { (p.1, q.1) };
                    let f = (bound - a) / (b - a);
                    (p.0 + f * (q.0 - p.0), p.1 + f * (q.1 - p.1))
                };
                match (inside(p), inside(q)) {
                    (true, true) => out.push(q),
                    (true, false) => out.push(cross()),
                    (false, true) => {
                        out.push(cross());
                        out.push(q);
                    }
                    (false, false) => {}
                }
            }
            if out.is_empty() {
                break;
            }
        }
        out
    }
}

/// A pixel position rounded; far-off points (a blown-up trail) are
/// clamped, not wrapped.
pub fn round_px((x, y): (f64, f64)) -> (i32, i32) {
    let clamp = |v: f64| v.round().clamp(-1e6, 1e6) as i32;
    (clamp(x), clamp(y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_cuts_a_long_floor_to_the_plot() {
        let view = View {
            x: (0.0, 1.0),
            y: (0.0, 1.0),
            px: 10..110,
            py: 20..120,
        };
        let floor = [
            (-500.0, 100.0),
            (600.0, 100.0),
            (600.0, 300.0),
            (-500.0, 300.0),
        ];
        let clipped = view.clip(&floor);
        let xs: Vec<f64> = clipped.iter().map(|p| p.0).collect();
        let ys: Vec<f64> = clipped.iter().map(|p| p.1).collect();
        assert_eq!(clipped.len(), 4, "{clipped:?}");
        assert!(
            xs.iter().all(|&x| (10.0..=110.0).contains(&x)),
            "{clipped:?}"
        );
        assert!(
            ys.iter().all(|&y| (100.0..=120.0).contains(&y)),
            "{clipped:?}"
        );
        assert!(view.clip(&[(0.0, 0.0), (5.0, 0.0), (0.0, 5.0)]).is_empty());
        let inside = [(20.0, 30.0), (40.0, 30.0), (30.0, 50.0)];
        assert_eq!(view.clip(&inside), inside);
    }
}
