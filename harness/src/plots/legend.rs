//! Legends, drawn outside the data: a band under a panel (or, when every
//! panel of a figure draws the same series, one band under the whole
//! figure), entries flowing left to right in rows. Each entry is a sample
//! of the series' line with its marker, then its label.

use super::marks::{draw_marker, draw_off_scale, draw_polyline};
use super::style::{Dash, GUIDE, Marker, Style};
use super::{Role, TEXT};
use crate::pictures::font::FAMILY;
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// One legend entry.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// Its text.
    pub label: String,
    /// What its sample shows.
    pub sample: Sample,
}

/// What a legend entry's sample shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sample {
    /// A series: its line and marker.
    Series(Style, Role),
    /// The outward triangle of a curve leaving a fixed axis range.
    OffScale,
    /// A marker in the band under a log axis, for values exactly 0.
    Zero,
}

/// Width of an entry's sample (px).
const SAMPLE: i32 = 34;
/// Gap between a sample and its text, and after an entry (px).
const GAP: i32 = 6;
const AFTER: i32 = 22;
/// Height of a legend row (px).
pub const ROW: i32 = 20;
/// Space above and below the rows (px).
const PAD: i32 = 6;

fn text_width(text: &str) -> i32 {
    (FAMILY, TEXT)
        .into_font()
        .box_size(text)
        .map_or(text.len() as i32 * 7, |(w, _)| w as i32)
}

/// The entries' positions in a band `width` px wide: (row, x) of each.
fn layout(entries: &[Entry], width: i32, left: i32) -> Vec<(i32, i32)> {
    let mut out = Vec::with_capacity(entries.len());
    let (mut row, mut x) = (0, left);
    for e in entries {
        let w = SAMPLE + GAP + text_width(&e.label);
        if x > left && x + w > width - 8 {
            row += 1;
            x = left;
        }
        out.push((row, x));
        x += w + AFTER;
    }
    out
}

/// The height (px) of the band holding `entries` in `width` px; 0 for none.
pub fn height(entries: &[Entry], width: i32, left: i32) -> i32 {
    match layout(entries, width, left).last() {
        None => 0,
        Some((rows, _)) => (rows + 1) * ROW + 2 * PAD,
    }
}

/// Draws `entries` into `area` (a band of [`height`] px), from `left` px.
pub fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[Entry],
    left: i32,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let (width, _) = area.dim_in_pixel();
    let font = (FAMILY, TEXT)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    for (e, (row, x)) in entries.iter().zip(layout(entries, width as i32, left)) {
        let y = PAD + row * ROW + ROW / 2;
        let (a, b) = (x + 2, x + SAMPLE - 2);
        match e.sample {
            Sample::Series(style, role) => {
                let line = vec![(a, y), (b, y)];
                match role {
                    Role::Reference => draw_polyline(area, line, style, 6)?,
                    Role::Guide => draw_polyline(area, line, style, 1)?,
                    Role::Data => {
                        if style.dash != Dash::None {
                            draw_polyline(area, line, style, 2)?;
                        }
                        if style.marker != Marker::None {
                            draw_marker(area, ((a + b) / 2, y), style)?;
                        }
                    }
                }
            }
            Sample::OffScale => draw_off_scale(area, ((a + b) / 2, y - 4), true, GUIDE)?,
            Sample::Zero => {
                let style = Style {
                    colour: GUIDE,
                    marker: Marker::Circle,
                    hollow: true,
                    dash: Dash::None,
                };
                draw_marker(area, ((a + b) / 2, y), style)?;
            }
        }
        area.draw_text(&e.label, &font, (x + SAMPLE + GAP, y))
            .map_err(|e| anyhow::anyhow!("legend: {e}"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(label: &str) -> Entry {
        Entry {
            label: label.into(),
            sample: Sample::OffScale,
        }
    }

    #[test]
    fn entries_wrap_into_rows_that_fit() {
        crate::pictures::font::ensure_fonts();
        let entries: Vec<Entry> = (0..10).map(|i| entry(&format!("series {i}"))).collect();
        let rows = layout(&entries, 400, 10);
        assert!(rows.iter().all(|&(_, x)| x < 400));
        assert!(rows.last().unwrap().0 >= 2, "{rows:?}");
        assert_eq!(height(&[], 400, 10), 0);
        assert_eq!(height(&entries[..1], 400, 10), ROW + 2 * PAD);
    }
}
