//! From world metres to window pixels and back: one scale on both axes
//! (bodies keep their true proportions), y up in the world and down on
//! screen. Zooming keeps the world point under the cursor fixed; panning
//! moves the view by whole pixels.

use super::frame::Frame;
use engine::BodyKind;
use nalgebra::Vector2;
use serde::Serialize;

/// The space left around the scene when fitted (a fraction of the window
/// on each side).
const FIT_MARGIN: f64 = 0.08;
/// The window's text above and below the scene (px): four lines of
/// numbers at the top, the two help lines at the bottom.
const TEXT_INSETS: (f64, f64) = (76.0, 44.0);
/// A fitted view is at least this many of the widest dynamic body wide.
const ROOM_IN_BODIES: f64 = 8.0;
/// The reach given to a particle when fitting (m).
const PARTICLE_REACH: f64 = 0.1;

/// The smallest and largest scales (px/m) a zoom reaches: from a 10 km
/// wide view on a 1000 px window to a millimetre filling it.
const SCALE_RANGE: (f64, f64) = (0.1, 1.0e6);

/// The view's camera.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Camera {
    /// The world point at the centre of the window (m).
    pub centre: [f64; 2],
    /// Pixels per metre.
    pub scale: f64,
    /// Window width (px).
    pub width: u32,
    /// Window height (px).
    pub height: u32,
}

impl Camera {
    /// A camera on a `width × height` px window showing the box
    /// `lo..hi` (m) whole, with `margin` (a fraction of the window) around.
    pub fn fit(lo: Vector2<f64>, hi: Vector2<f64>, width: u32, height: u32, margin: f64) -> Self {
        Self::fit_band(lo, hi, width, height, margin, (0.0, 0.0))
    }

    /// As [`Camera::fit`], in the band of the window between `insets.0`
    /// px from the top and `insets.1` px from the bottom (where the text
    /// is), when the window is tall enough to spare them.
    pub fn fit_band(
        lo: Vector2<f64>,
        hi: Vector2<f64>,
        width: u32,
        height: u32,
        margin: f64,
        insets: (f64, f64),
    ) -> Self {
        let (w, h) = (f64::from(width.max(1)), f64::from(height.max(1)));
        let (top, bottom) = if h >= 3.0 * (insets.0 + insets.1) {
            insets
        } else {
            (0.0, 0.0)
        };
        let size = (hi - lo).map(|v| v.max(1e-3));
        let usable = (1.0 - 2.0 * margin).max(0.1);
        let scale = (w * usable / size.x)
            .min((h - top - bottom) * usable / size.y)
            .clamp(SCALE_RANGE.0, SCALE_RANGE.1);
        let middle = lo + 0.5 * (hi - lo);
        // The box's middle goes to the band's middle.
        let band_middle = top + 0.5 * (h - top - bottom);
        Self {
            centre: [middle.x, middle.y + (band_middle - 0.5 * h) / scale],
            scale,
            width,
            height,
        }
    }

    /// A camera on a `width × height` px window showing the scene of
    /// `frame`: every dynamic body, with room for at least
    /// [`ROOM_IN_BODIES`] of the widest across, and the parts of the
    /// static ones near them (a 1 km ground would make a pile of boxes
    /// invisible); every body when none is dynamic.
    pub fn fit_frame(frame: &Frame, width: u32, height: u32) -> Self {
        let reach = |id: usize| {
            let r = frame.looks[id].radius.max(PARTICLE_REACH);
            let p = frame.states[id].position;
            (p - Vector2::repeat(r), p + Vector2::repeat(r))
        };
        let union = |ids: &mut dyn Iterator<Item = usize>| {
            ids.map(reach).reduce(|a, b| (a.0.inf(&b.0), a.1.sup(&b.1)))
        };
        let n = frame.looks.len().min(frame.states.len());
        let live = |id: &usize| !frame.removed.get(*id).copied().unwrap_or(false);
        let dynamic = |id: &usize| frame.looks[*id].kind == BodyKind::Dynamic;
        let moving = union(&mut (0..n).filter(live).filter(dynamic));
        // A lone body is shown with room around it to move.
        let widest = (0..n)
            .filter(live)
            .filter(dynamic)
            .map(|id| 2.0 * frame.looks[id].radius)
            .fold(0.0, f64::max);
        let moving = moving.map(|(lo, hi)| {
            let centre = 0.5 * (lo + hi);
            let half = (0.5 * (hi - lo)).sup(&Vector2::repeat(0.5 * ROOM_IN_BODIES * widest));
            (centre - half, centre + half)
        });
        let bounds = match moving {
            // The static bodies where the dynamic ones are, clipped to
            // their box enlarged by a quarter on each side: the ground
            // under a pile shows, a 1 km ground does not shrink the pile.
            Some((lo, hi)) => {
                let reach = 0.25 * (hi - lo);
                let (near_lo, near_hi) = (lo - reach, hi + reach);
                (0..n)
                    .filter(live)
                    .filter(|id| !dynamic(id))
                    .map(|id| frame.looks[id].aabb(&frame.states[id]))
                    .map(|(a, b)| (a.sup(&near_lo), b.inf(&near_hi)))
                    .filter(|(a, b)| a.x <= b.x && a.y <= b.y)
                    .fold((lo, hi), |(a, b), (c, d)| (a.inf(&c), b.sup(&d)))
            }
            None => union(&mut (0..n).filter(live))
                .unwrap_or((Vector2::repeat(-1.0), Vector2::repeat(1.0))),
        };
        Self::fit_band(bounds.0, bounds.1, width, height, FIT_MARGIN, TEXT_INSETS)
    }

    /// The pixel of world point `p` (x right, y down; fractional).
    pub fn to_screen(&self, p: Vector2<f64>) -> (f64, f64) {
        (
            0.5 * f64::from(self.width) + (p.x - self.centre[0]) * self.scale,
            0.5 * f64::from(self.height) - (p.y - self.centre[1]) * self.scale,
        )
    }

    /// The world point (m) at pixel (`x`, `y`).
    pub fn to_world(&self, x: f64, y: f64) -> Vector2<f64> {
        Vector2::new(
            self.centre[0] + (x - 0.5 * f64::from(self.width)) / self.scale,
            self.centre[1] - (y - 0.5 * f64::from(self.height)) / self.scale,
        )
    }

    /// Zooms by `factor` (> 1 in) about pixel (`x`, `y`), which keeps
    /// showing the same world point.
    pub fn zoom_at(&mut self, x: f64, y: f64, factor: f64) {
        let before = self.to_world(x, y);
        self.scale = (self.scale * factor).clamp(SCALE_RANGE.0, SCALE_RANGE.1);
        let after = self.to_world(x, y);
        self.centre[0] += before.x - after.x;
        self.centre[1] += before.y - after.y;
    }

    /// Moves the view so that the scene follows the cursor by (`dx`, `dy`) px.
    pub fn pan(&mut self, dx: f64, dy: f64) {
        self.centre[0] -= dx / self.scale;
        self.centre[1] += dy / self.scale;
    }

    /// The window was resized: same centre and scale.
    pub fn resize(&mut self, width: u32, height: u32) {
        self.width = width;
        self.height = height;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn screen_and_world_are_inverse_and_zoom_keeps_the_cursor_point() {
        let mut c = Camera::fit(
            Vector2::new(-2.0, 0.0),
            Vector2::new(2.0, 3.0),
            800,
            600,
            0.1,
        );
        let p = Vector2::new(1.25, -0.5);
        let (x, y) = c.to_screen(p);
        assert!((c.to_world(x, y) - p).norm() < 1e-12);
        c.zoom_at(100.0, 50.0, 3.0);
        let q = c.to_world(100.0, 50.0);
        c.zoom_at(100.0, 50.0, 0.5);
        assert!((c.to_world(100.0, 50.0) - q).norm() < 1e-9);
    }

    #[test]
    fn fit_shows_the_box_whole_with_y_up() {
        let c = Camera::fit(
            Vector2::new(0.0, 0.0),
            Vector2::new(4.0, 1.0),
            400,
            400,
            0.0,
        );
        assert_eq!(c.scale, 100.0);
        assert_eq!(c.to_screen(Vector2::new(0.0, 0.0)), (0.0, 250.0));
        assert_eq!(c.to_screen(Vector2::new(4.0, 1.0)), (400.0, 150.0));
    }
}
