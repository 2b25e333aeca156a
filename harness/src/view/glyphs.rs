//! Text on the canvas, in the repository's font (DejaVu Sans, compiled in:
//! `crate::pictures::font`), so that the view reads the same on every
//! platform and headless. Each glyph is rasterised once per size by
//! ab_glyph and kept as a coverage map; drawing blends it.

use super::canvas::{Canvas, Rgb};
use ab_glyph::{Font, GlyphId, PxScale, ScaleFont, point};
use std::collections::HashMap;

/// A glyph's coverage map and placement.
#[derive(Debug, Clone)]
struct Glyph {
    /// Offset of the map's top-left corner from the pen (px).
    left: i64,
    top: i64,
    width: usize,
    coverage: Vec<f32>,
    advance: f32,
}

/// Rasterised glyphs of one pixel size.
#[derive(Debug)]
pub struct Glyphs {
    size: f32,
    cache: HashMap<char, Glyph>,
}

impl Glyphs {
    /// Glyphs of `size` px (the font's ascent to descent).
    pub fn new(size: f32) -> Self {
        Self {
            size,
            cache: HashMap::new(),
        }
    }

    /// The height of a line (px).
    pub fn line_height(&self) -> f32 {
        self.size * 1.2
    }

    fn glyph(&mut self, c: char) -> Option<&Glyph> {
        let face = crate::pictures::font::face()?;
        let size = self.size;
        Some(self.cache.entry(c).or_insert_with(|| {
            let scale = PxScale::from(size);
            let scaled = face.as_scaled(scale);
            let id: GlyphId = scaled.glyph_id(c);
            let advance = scaled.h_advance(id);
            let glyph = id.with_scale_and_position(scale, point(0.0, scaled.ascent()));
            match face.outline_glyph(glyph) {
                Some(outline) => {
                    let bounds = outline.px_bounds();
                    let width = bounds.width().max(0.0) as usize;
                    let height = bounds.height().max(0.0) as usize;
                    let mut coverage = vec![0.0; width * height];
                    outline.draw(|x, y, v| {
                        let (x, y) = (x as usize, y as usize);
                        if x < width && y < height {
                            coverage[y * width + x] = v.min(1.0);
                        }
                    });
                    Glyph {
                        left: bounds.min.x as i64,
                        top: bounds.min.y as i64,
                        width,
                        coverage,
                        advance,
                    }
                }
                None => Glyph {
                    left: 0,
                    top: 0,
                    width: 0,
                    coverage: Vec::new(),
                    advance,
                },
            }
        }))
    }

    /// The width of `text` (px).
    pub fn width(&mut self, text: &str) -> f32 {
        text.chars()
            .map(|c| self.glyph(c).map_or(0.0, |g| g.advance))
            .sum()
    }

    /// Draws `text` with its top-left corner at (`x`, `y`) px; returns the
    /// pen's x after it.
    pub fn draw(&mut self, canvas: &mut Canvas, text: &str, x: f32, y: f32, colour: Rgb) -> f32 {
        let mut pen = x;
        for c in text.chars() {
            let Some(g) = self.glyph(c) else {
                continue;
            };
            let (gx, gy) = (pen.round() as i64 + g.left, y.round() as i64 + g.top);
            if g.width > 0 {
                for (i, &v) in g.coverage.iter().enumerate() {
                    if v > 0.0 {
                        let (dx, dy) = ((i % g.width) as i64, (i / g.width) as i64);
                        canvas.blend(gx + dx, gy + dy, colour, v);
                    }
                }
            }
            pen += g.advance;
        }
        pen
    }
}
