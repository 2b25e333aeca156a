//! The framebuffer every frame is drawn into: `width × height` pixels of
//! `0x00RRGGBB` (the layout softbuffer hands to the window system, and
//! what the PNG of `--screenshot` is made from), with the few primitives
//! the view needs: convex polygons and discs filled by scanline, lines,
//! rectangles, and coverage blending (for text).
//!
//! A pixel is covered when its centre is inside the shape: a shape of
//! true size s m at a scale of k px/m covers s·k pixels across, so bodies
//! are drawn at their true size. Everything is clipped to the canvas; any
//! coordinate (a body far off screen, a zoom of 1e6 px/m) is safe.

/// A colour as the framebuffer stores it: `0x00RRGGBB`.
pub type Rgb = u32;

/// The colour `r, g, b` as a pixel.
pub const fn rgb(r: u8, g: u8, b: u8) -> Rgb {
    ((r as u32) << 16) | ((g as u32) << 8) | b as u32
}

/// `c` mixed with `other`: `amount` 0 keeps `c`, 1 gives `other`.
pub fn mix(c: Rgb, other: Rgb, amount: f32) -> Rgb {
    let channel = |shift: u32| {
        let a = ((c >> shift) & 0xff) as f32;
        let b = ((other >> shift) & 0xff) as f32;
        ((a + (b - a) * amount).round().clamp(0.0, 255.0) as u32) << shift
    };
    channel(16) | channel(8) | channel(0)
}

/// Pixels far outside the canvas are clamped to this margin before any
/// arithmetic, so that huge coordinates stay exact in f32 and loops short.
const FAR: f64 = 1.0e5;

/// A CPU framebuffer.
#[derive(Debug, Clone)]
pub struct Canvas {
    width: usize,
    height: usize,
    pixels: Vec<Rgb>,
}

impl Canvas {
    /// A canvas of `width × height` pixels (at least 1 × 1), black.
    pub fn new(width: u32, height: u32) -> Self {
        let (width, height) = (width.max(1) as usize, height.max(1) as usize);
        Self {
            width,
            height,
            pixels: vec![0; width * height],
        }
    }

    /// Resizes to `width × height` (at least 1 × 1); the content is lost.
    pub fn resize(&mut self, width: u32, height: u32) {
        self.width = width.max(1) as usize;
        self.height = height.max(1) as usize;
        self.pixels.clear();
        self.pixels.resize(self.width * self.height, 0);
    }

    /// Width (px).
    pub fn width(&self) -> u32 {
        self.width as u32
    }

    /// Height (px).
    pub fn height(&self) -> u32 {
        self.height as u32
    }

    /// The pixels, row by row from the top.
    pub fn pixels(&self) -> &[Rgb] {
        &self.pixels
    }

    /// The pixel at (`x`, `y`), if inside.
    pub fn pixel(&self, x: u32, y: u32) -> Option<Rgb> {
        let (x, y) = (x as usize, y as usize);
        (x < self.width && y < self.height).then(|| self.pixels[y * self.width + x])
    }

    /// Copies `src` in with its left edge at column `x0` (clipped).
    pub fn blit(&mut self, src: &Canvas, x0: u32) {
        let x0 = x0 as usize;
        if x0 >= self.width {
            return;
        }
        let n = src.width.min(self.width - x0);
        for y in 0..src.height.min(self.height) {
            let to = y * self.width + x0;
            self.pixels[to..to + n].copy_from_slice(&src.pixels[y * src.width..y * src.width + n]);
        }
    }

    /// Fills the whole canvas.
    pub fn clear(&mut self, colour: Rgb) {
        self.pixels.fill(colour);
    }

    /// Fills the pixels `x0..x1` of row `y` (clipped).
    fn span(&mut self, y: i64, x0: i64, x1: i64, colour: Rgb) {
        if y < 0 || y >= self.height as i64 {
            return;
        }
        let x0 = x0.max(0) as usize;
        let x1 = x1.min(self.width as i64);
        if x1 <= x0 as i64 {
            return;
        }
        let row = y as usize * self.width;
        self.pixels[row + x0..row + x1 as usize].fill(colour);
    }

    /// Fills a convex polygon (vertices in pixels, either winding): every
    /// pixel whose centre is inside.
    pub fn fill_convex(&mut self, points: &[(f64, f64)], colour: Rgb) {
        if points.len() < 3 {
            return;
        }
        let clamp = |v: f64| v.clamp(-FAR, FAR);
        let (mut y_min, mut y_max) = (f64::INFINITY, f64::NEG_INFINITY);
        for &(_, y) in points {
            y_min = y_min.min(clamp(y));
            y_max = y_max.max(clamp(y));
        }
        // Rows whose centre y + 0.5 lies in [y_min, y_max).
        let first = ((y_min - 0.5).ceil() as i64).max(0);
        let last = ((y_max - 0.5).ceil() as i64).min(self.height as i64);
        for row in first..last {
            let yc = row as f64 + 0.5;
            let (mut left, mut right) = (f64::INFINITY, f64::NEG_INFINITY);
            for (i, &(ax, ay)) in points.iter().enumerate() {
                let (bx, by) = points[(i + 1) % points.len()];
                let (ax, ay, bx, by) = (clamp(ax), clamp(ay), clamp(bx), clamp(by));
                let crosses = (ay <= yc && yc < by) || (by <= yc && yc < ay);
                if crosses {
                    let x = ax + (yc - ay) * (bx - ax) / (by - ay);
                    left = left.min(x);
                    right = right.max(x);
                }
            }
            if left <= right {
                let x0 = (left - 0.5).ceil() as i64;
                let x1 = (right - 0.5).ceil() as i64;
                self.span(row, x0, x1, colour);
            }
        }
    }

    /// Fills a disc of centre (`cx`, `cy`) and radius `r` (px).
    pub fn fill_circle(&mut self, cx: f64, cy: f64, r: f64, colour: Rgb) {
        if r.is_nan() || r <= 0.0 || cx + r < 0.0 || cy + r < 0.0 {
            return;
        }
        if cx - r > self.width as f64 || cy - r > self.height as f64 {
            return;
        }
        let first = ((cy - r - 0.5).ceil() as i64).max(0);
        let last = ((cy + r - 0.5).ceil() as i64).min(self.height as i64);
        for row in first..last {
            let dy = row as f64 + 0.5 - cy;
            let half = (r * r - dy * dy).max(0.0).sqrt();
            let x0 = (cx - half - 0.5).ceil() as i64;
            let x1 = (cx + half - 0.5).ceil() as i64;
            self.span(row, x0, x1, colour);
        }
    }

    /// Outlines a circle (1 px), as a polygon of enough sides to look round.
    pub fn circle(&mut self, cx: f64, cy: f64, r: f64, colour: Rgb) {
        let sides = (r * 0.8).clamp(8.0, 96.0) as usize;
        let at = |i: usize| {
            let a = i as f64 * std::f64::consts::TAU / sides as f64;
            (cx + r * a.cos(), cy + r * a.sin())
        };
        for i in 0..sides {
            let (a, b) = (at(i), at(i + 1));
            self.line(a.0, a.1, b.0, b.1, colour);
        }
    }

    /// A 1 px line between two points (px), clipped to the canvas.
    pub fn line(&mut self, x0: f64, y0: f64, x1: f64, y1: f64, colour: Rgb) {
        let Some((x0, y0, x1, y1)) = self.clip(x0, y0, x1, y1) else {
            return;
        };
        let steps = (x1 - x0).abs().max((y1 - y0).abs()).ceil().max(1.0);
        let (dx, dy) = ((x1 - x0) / steps, (y1 - y0) / steps);
        let (w, h) = (self.width as i64, self.height as i64);
        for i in 0..=steps as i64 {
            let x = (x0 + dx * i as f64).floor() as i64;
            let y = (y0 + dy * i as f64).floor() as i64;
            if x >= 0 && y >= 0 && x < w && y < h {
                self.pixels[y as usize * self.width + x as usize] = colour;
            }
        }
    }

    /// The part of a segment inside the canvas (Liang–Barsky), if any.
    fn clip(&self, x0: f64, y0: f64, x1: f64, y1: f64) -> Option<(f64, f64, f64, f64)> {
        if ![x0, y0, x1, y1].iter().all(|v| v.is_finite()) {
            return None;
        }
        let (dx, dy) = (x1 - x0, y1 - y0);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        let (w, h) = (self.width as f64, self.height as f64);
        for (p, q) in [(-dx, x0), (dx, w - x0), (-dy, y0), (dy, h - y0)] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        (t0 <= t1).then_some((x0 + t0 * dx, y0 + t0 * dy, x0 + t1 * dx, y0 + t1 * dy))
    }

    /// Outlines the rectangle between two corners (px).
    pub fn rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64, colour: Rgb) {
        self.line(x0, y0, x1, y0, colour);
        self.line(x1, y0, x1, y1, colour);
        self.line(x1, y1, x0, y1, colour);
        self.line(x0, y1, x0, y0, colour);
    }

    /// Blends `colour` over the rectangle `x, y, w, h` (px) with opacity
    /// `alpha` in [0, 1] (the panels behind the text).
    pub fn shade_rect(&mut self, x: i64, y: i64, w: i64, h: i64, colour: Rgb, alpha: f32) {
        let (y0, y1) = (y.max(0), (y + h).min(self.height as i64));
        let (x0, x1) = (x.max(0), (x + w).min(self.width as i64));
        for row in y0..y1 {
            for col in x0..x1 {
                self.blend(col, row, colour, alpha);
            }
        }
    }

    /// Blends `colour` over pixel (`x`, `y`) with opacity `alpha` in [0, 1].
    pub fn blend(&mut self, x: i64, y: i64, colour: Rgb, alpha: f32) {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return;
        }
        let i = y as usize * self.width + x as usize;
        self.pixels[i] = mix(self.pixels[i], colour, alpha.clamp(0.0, 1.0));
    }

    /// The picture as 8-bit RGB bytes, row by row (for PNG).
    pub fn to_rgb8(&self) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|&p| [(p >> 16) as u8, (p >> 8) as u8, p as u8])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_of_four_pixels_covers_four_pixels() {
        let mut c = Canvas::new(10, 10);
        c.fill_convex(&[(2.0, 2.0), (6.0, 2.0), (6.0, 6.0), (2.0, 6.0)], 1);
        assert_eq!(c.pixels().iter().filter(|&&p| p == 1).count(), 16);
        assert_eq!(c.pixel(2, 2), Some(1));
        assert_eq!(c.pixel(6, 6), Some(0));
    }

    #[test]
    fn shapes_far_off_the_canvas_draw_nothing_and_do_not_panic() {
        let mut c = Canvas::new(8, 8);
        c.fill_convex(&[(-1e12, 1e12), (1e12, 1e12), (0.0, 2e12)], 1);
        c.fill_circle(1e15, 3.0, 5.0, 1);
        c.line(-1e30, -1e30, -1e29, 5.0, 1);
        c.line(f64::NAN, 0.0, 1.0, 1.0, 1);
        assert!(c.pixels().iter().all(|&p| p == 0));
    }

    #[test]
    fn a_huge_polygon_covering_the_canvas_fills_it() {
        let mut c = Canvas::new(8, 8);
        c.fill_convex(&[(-1e9, -1e9), (1e9, -1e9), (1e9, 1e9), (-1e9, 1e9)], 1);
        assert!(c.pixels().iter().all(|&p| p == 1));
    }

    #[test]
    fn a_disc_covers_about_pi_r_squared_pixels() {
        let mut c = Canvas::new(100, 100);
        c.fill_circle(50.0, 50.0, 20.0, 1);
        let n = c.pixels().iter().filter(|&&p| p == 1).count() as f64;
        // Pixel-centre sampling errs by at most the perimeter's pixels.
        let area = std::f64::consts::PI * 400.0;
        assert!(
            (n - area).abs() < 2.0 * std::f64::consts::PI * 20.0,
            "{n} vs {area}"
        );
    }
}
