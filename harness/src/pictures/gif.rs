//! The animated GIF of a run, written without plotters' own GIF encoder
//! (which quantises every frame with NeuQuant and writes straight to a
//! file): each frame is drawn by plotters into an RGB buffer over a
//! background drawn once, mapped to one fixed global palette (white, greys,
//! and each body colour with its tints and shade) through a 32K-entry
//! lookup table, and only the rectangle that changed since the previous
//! frame is stored, with unchanged pixels transparent. That keeps a
//! 120-frame animation to a few hundred kilobytes and a few tens of
//! milliseconds, and the bytes are returned for the caller to write.

use super::draw::{
    GRID, GRID_FINE, INK, LINE_PX, OUTLINE_SHADE, PATH_TINT, TITLE_Y, TRAIL_TINT, Trails,
    background, foreground, plot_err, shade, tint, trail_samples,
};
use super::film::Film;
use super::font::ensure_fonts;
use super::text::Crisp;
use super::view::{Layout, MARGIN};
use super::{inset, table};
use anyhow::{Context, Result};
use plotters::prelude::*;
use scene::Colour;
use std::borrow::Cow;

/// Size and pace of an animation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GifOptions {
    /// Picture width (px); the height follows the run's aspect.
    pub width: u32,
    /// Most frames (evenly spaced in time over the run).
    pub max_frames: usize,
    /// Delay between frames (1/100 s).
    pub delay_cs: u16,
    /// How long the last frame stays (1/100 s).
    pub hold_cs: u16,
}

impl Default for GifOptions {
    /// 480 px wide, at most 120 frames at 25 frames per second, the last
    /// one held 2 s: a loop of about 7 s.
    fn default() -> Self {
        Self {
            width: 480,
            max_frames: 120,
            delay_cs: 4,
            hold_cs: 200,
        }
    }
}

/// Header of an animation frame (px): title line and the time.
const GIF_HEADER: u32 = 46;
/// Samples drawn per trail.
const TRAIL_POINTS: usize = 600;

/// The animated GIF of `film`, as bytes.
pub fn animation(film: &Film, options: &GifOptions) -> Result<Vec<u8>> {
    ensure_fonts();
    anyhow::ensure!(
        !film.times.is_empty(),
        "nothing to animate: the run has no samples"
    );
    let layout = Layout::plan(film, options.width.clamp(240, 2000), GIF_HEADER, 160..320)?;
    // The plot on the left, every moving body's state in a table beside it.
    let side = table::width(film);
    let insets_top = (GIF_HEADER + table::height(film) + 8) as i32;
    let size = (
        layout.width + side,
        layout
            .height
            .max(insets_top as u32 + inset::height(film, &layout.nominal_view(), side)),
    );
    let (w, h) = (size.0 as usize, size.1 as usize);
    let title = match &layout.note {
        Some(note) => format!("{} — {} — {note}", film.title, film.subtitle),
        None => format!("{} — {}", film.title, film.subtitle),
    };
    let mut background_rgb = vec![255u8; w * h * 3];
    let view = {
        let root = Crisp::with_buffer(&mut background_rgb, size).into_drawing_area();
        let (plot, _) = root.split_horizontally(layout.width);
        let (plot, _) = plot.split_vertically(layout.height);
        let view = background(&plot, film, &layout, &[&title])?;
        root.present().map_err(plot_err)?;
        view
    };
    let palette = Palette::new(film);
    let transparent = palette.transparent;
    let mut encoder = gif::Encoder::new(Vec::new(), w as u16, h as u16, &palette.rgb)
        .context("starting the GIF")?;
    encoder
        .set_repeat(gif::Repeat::Infinite)
        .context("writing the GIF")?;
    let frames = film.evenly_spaced(options.max_frames.max(1));
    let trail_idx = trail_samples(film, TRAIL_POINTS);
    let mut rgb = vec![0u8; w * h * 3];
    let mut previous: Option<Vec<u8>> = None;
    let mut current = vec![0u8; w * h];
    let label_at = (MARGIN as i32, TITLE_Y + LINE_PX + 2);
    for (n, &k) in frames.iter().enumerate() {
        rgb.copy_from_slice(&background_rgb);
        {
            let root = Crisp::with_buffer(&mut rgb, size).into_drawing_area();
            let (plot, beside) = root.split_horizontally(layout.width);
            let (plot, _) = plot.split_vertically(layout.height);
            foreground(&plot, film, &view, k, (Trails::Past, &trail_idx), label_at)?;
            table::draw(&beside.margin(GIF_HEADER, 0, 0, 0), film, k)?;
            for zoom in inset::plan(film, &view, insets_top, side) {
                inset::draw(&beside, film, &view, &zoom, k, &trail_idx)?;
            }
            root.present().map_err(plot_err)?;
        }
        palette.index(&rgb, &mut current);
        let delay = if n + 1 == frames.len() {
            options.hold_cs
        } else {
            options.delay_cs
        };
        let (rect, buffer) = match &previous {
            None => ((0, 0, w, h), current.clone()),
            Some(prev) => changed(prev, &current, w, h, transparent),
        };
        let frame = gif::Frame {
            left: rect.0 as u16,
            top: rect.1 as u16,
            width: rect.2 as u16,
            height: rect.3 as u16,
            buffer: Cow::Owned(buffer),
            transparent: previous.as_ref().map(|_| transparent),
            dispose: gif::DisposalMethod::Keep,
            delay,
            ..gif::Frame::default()
        };
        encoder.write_frame(&frame).context("writing a GIF frame")?;
        match &mut previous {
            Some(prev) => prev.copy_from_slice(&current),
            None => previous = Some(current.clone()),
        }
    }
    encoder.into_inner().context("finishing the GIF")
}

/// The rectangle (left, top, width, height) where `current` differs from
/// `previous`, and its pixels with the unchanged ones set to `transparent`.
/// A frame identical to the previous one gives a single transparent pixel.
fn changed(
    previous: &[u8],
    current: &[u8],
    w: usize,
    h: usize,
    transparent: u8,
) -> ((usize, usize, usize, usize), Vec<u8>) {
    let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0, 0);
    for y in 0..h {
        let row = y * w..(y + 1) * w;
        let (p, c) = (&previous[row.clone()], &current[row]);
        if p == c {
            continue;
        }
        let first = p.iter().zip(c).position(|(a, b)| a != b).unwrap_or(0);
        let last = w
            - 1
            - p.iter()
                .rev()
                .zip(c.iter().rev())
                .position(|(a, b)| a != b)
                .unwrap_or(0);
        x0 = x0.min(first);
        x1 = x1.max(last);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x0 > x1 || y0 > y1 {
        return ((0, 0, 1, 1), vec![transparent]);
    }
    let (rw, rh) = (x1 - x0 + 1, y1 - y0 + 1);
    let mut out = Vec::with_capacity(rw * rh);
    for y in y0..=y1 {
        for x in x0..=x1 {
            let i = y * w + x;
            out.push(if previous[i] == current[i] {
                transparent
            } else {
                current[i]
            });
        }
    }
    ((x0, y0, rw, rh), out)
}

/// A fixed palette and its lookup table from 15-bit RGB.
struct Palette {
    /// Flat `r, g, b` triples.
    rgb: Vec<u8>,
    /// The index no colour uses, for unchanged pixels.
    transparent: u8,
    /// Palette index of each 5-bit-per-channel colour.
    lut: Vec<u8>,
}

impl Palette {
    /// White, 24 greys, the chart and ink colours, and for each distinct
    /// body colour (up to 40) the colour, its trail and path tints, a mid
    /// tint for edges and its outline shade.
    fn new(film: &Film) -> Self {
        let mut colours: Vec<Colour> = vec![Colour::rgb(255, 255, 255)];
        for j in 0..24u8 {
            let v = (u32::from(j) * 255 / 23) as u8;
            colours.push(Colour::rgb(v, v, v));
        }
        colours.extend([INK, GRID, GRID_FINE]);
        let mut bodies: Vec<Colour> = film.bodies.iter().map(|b| b.colour).collect();
        bodies.dedup();
        for c in bodies.into_iter().take(40) {
            colours.extend([
                c,
                tint(c, TRAIL_TINT),
                tint(c, PATH_TINT),
                tint(c, 0.7),
                shade(c, OUTLINE_SHADE),
            ]);
        }
        colours.dedup();
        colours.truncate(255);
        let transparent = colours.len() as u8;
        let mut rgb: Vec<u8> = colours.iter().flat_map(|c| [c.r, c.g, c.b]).collect();
        rgb.extend([255, 0, 255]);
        let lut = (0..32768u32)
            .map(|key| {
                let centre = |shift: u32| (((key >> shift) & 31) << 3 | 4) as i32;
                let (r, g, b) = (centre(10), centre(5), centre(0));
                colours
                    .iter()
                    .enumerate()
                    .min_by_key(|(_, c)| {
                        let d = |a: u8, b: i32| (i32::from(a) - b).pow(2);
                        d(c.r, r) + d(c.g, g) + d(c.b, b)
                    })
                    .map_or(0, |(i, _)| i as u8)
            })
            .collect();
        Self {
            rgb,
            transparent,
            lut,
        }
    }

    /// Maps an RGB buffer to palette indices.
    fn index(&self, rgb: &[u8], out: &mut [u8]) {
        for (px, idx) in rgb.chunks_exact(3).zip(out.iter_mut()) {
            let key = (usize::from(px[0] >> 3) << 10)
                | (usize::from(px[1] >> 3) << 5)
                | usize::from(px[2] >> 3);
            *idx = self.lut[key];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_changed_rectangle_is_kept() {
        let prev = vec![0u8; 5 * 4];
        let mut cur = prev.clone();
        cur[6] = 3; // (1, 1)
        cur[13] = 4; // (3, 2)
        let (rect, pixels) = changed(&prev, &cur, 5, 4, 9);
        assert_eq!(rect, (1, 1, 3, 2));
        assert_eq!(pixels, vec![3, 9, 9, 9, 9, 4]);
        let (rect, pixels) = changed(&prev, &prev, 5, 4, 9);
        assert_eq!((rect, pixels), ((0, 0, 1, 1), vec![9]));
    }
}
