//! The marks a chart draws in pixels: markers of every shape, filled or
//! hollow; lines solid, dashed or dotted; the outward triangle where a
//! curve leaves a fixed axis range.

use super::style::{Dash, Marker, Style};
use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

/// Half the size of a filled marker (px).
pub const FILLED: i32 = 4;
/// Half the size of a hollow marker (px): larger, so that a filled marker
/// under it shows inside.
pub const HOLLOW: i32 = 5;

fn err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow!("drawing a chart: {e}")
}

/// Draws `style`'s marker centred at pixel `at` of `area`.
pub fn draw_marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (x, y): (i32, i32),
    style: Style,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let r = if style.hollow { HOLLOW } else { FILLED };
    let ink = ShapeStyle::from(&style.colour);
    let (fill, edge) = if style.hollow {
        (None, ink.stroke_width(2))
    } else {
        (Some(ink.filled()), ink.stroke_width(1))
    };
    let outline: Vec<(i32, i32)> = match style.marker {
        Marker::None => return Ok(()),
        Marker::Circle => {
            if let Some(f) = fill {
                area.draw(&Circle::new((x, y), r as u32, f)).map_err(err)?;
            } else {
                area.draw(&Circle::new((x, y), r as u32, edge))
                    .map_err(err)?;
            }
            return Ok(());
        }
        Marker::Square => {
            let s = r - 1;
            vec![
                (x - s, y - s),
                (x + s, y - s),
                (x + s, y + s),
                (x - s, y + s),
            ]
        }
        Marker::TriangleUp => vec![(x, y - r - 1), (x + r + 1, y + r), (x - r - 1, y + r)],
        Marker::TriangleDown => vec![(x, y + r + 1), (x + r + 1, y - r), (x - r - 1, y - r)],
        Marker::Diamond => {
            let s = r + 1;
            vec![(x, y - s), (x + s, y), (x, y + s), (x - s, y)]
        }
        Marker::Cross | Marker::Plus => {
            let s = r;
            let strokes = if style.marker == Marker::Cross {
                [
                    [(x - s, y - s), (x + s, y + s)],
                    [(x - s, y + s), (x + s, y - s)],
                ]
            } else {
                [[(x - s, y), (x + s, y)], [(x, y - s), (x, y + s)]]
            };
            for stroke in strokes {
                area.draw(&PathElement::new(stroke.to_vec(), ink.stroke_width(2)))
                    .map_err(err)?;
            }
            return Ok(());
        }
    };
    if let Some(f) = fill {
        area.draw(&Polygon::new(outline.clone(), f)).map_err(err)?;
    }
    let mut closed = outline;
    closed.push(closed[0]);
    area.draw(&PathElement::new(closed, edge)).map_err(err)?;
    Ok(())
}

/// Draws a polyline in pixels with `style`'s dash, `width` px wide.
pub fn draw_polyline<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    points: Vec<(i32, i32)>,
    style: Style,
    width: u32,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    if points.len() < 2 || style.dash == Dash::None {
        return Ok(());
    }
    let ink = ShapeStyle::from(&style.colour).stroke_width(width);
    match style.dash.pattern() {
        None => area.draw(&PathElement::new(points, ink)).map_err(err)?,
        Some((on, off)) => area
            .draw(&DashedPathElement::new(points, on, off, ink))
            .map_err(err)?,
    }
    Ok(())
}

/// The mark of a curve leaving a fixed axis range at pixel `at` on the
/// plot's edge: a hollow triangle inside the plot, pointing out of it
/// (`up` at the top edge, else down), its tip on the edge.
pub fn draw_off_scale<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (x, y): (i32, i32),
    up: bool,
    colour: RGBColor,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let s = 5;
    let depth = s + 3;
    let points = if up {
        vec![(x, y), (x + s, y + depth), (x - s, y + depth), (x, y)]
    } else {
        vec![(x, y), (x + s, y - depth), (x - s, y - depth), (x, y)]
    };
    area.draw(&Polygon::new(points.clone(), WHITE.filled()))
        .map_err(err)?;
    area.draw(&PathElement::new(
        points,
        ShapeStyle::from(&colour).stroke_width(2),
    ))
    .map_err(err)?;
    Ok(())
}
