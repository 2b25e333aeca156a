//! The side table of a picture: every moving body's state at the frame's
//! time (position, and for a rotating body its angle and angular speed),
//! one row per body with its colour; a scene of more than [`MANY`] moving
//! bodies gets a summary instead (how many, the fastest, the highest and
//! the lowest), which stays legible for thousands.

use super::draw::{OUTLINE_SHADE, plot_err, rgb, shade, sig, text_style};
use super::film::Film;
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use scene::Colour;

/// Most moving bodies drawn with a row (and a label) each.
pub const MANY: usize = 10;
/// Size of the table's text (plotters units: 11.3 px in SVG, 12 px em in
/// the GIF).
const TEXT: u32 = 14;
/// Row height (px).
const ROW: i32 = 19;
/// Left margin, the colour swatch, the name column, a number column (px).
const LEFT: i32 = 10;
const SWATCH: i32 = 14;
const NAME: i32 = 84;
const NUMBER: i32 = 66;

/// Whether the film's table has the angle columns.
fn rotating(film: &Film) -> bool {
    film.bodies.iter().any(|b| b.dynamic && b.rotates)
}

fn moving(film: &Film) -> Vec<usize> {
    (0..film.bodies.len())
        .filter(|&i| film.bodies[i].dynamic)
        .collect()
}

/// Whether the film gets a row per body (else a summary).
pub fn per_body(film: &Film) -> bool {
    moving(film).len() <= MANY
}

/// The table's width (px).
pub fn width(film: &Film) -> u32 {
    if !per_body(film) {
        return 300;
    }
    let numbers = if rotating(film) { 4 } else { 2 };
    (LEFT + SWATCH + NAME + numbers * NUMBER + LEFT) as u32
}

/// The table's height (px), its title row included.
pub fn height(film: &Film) -> u32 {
    let rows = if per_body(film) {
        moving(film).len().max(1) + 1
    } else {
        5
    };
    (rows as i32 * ROW + 2 * 6) as u32
}

/// Draws the table of sample `k` into `area`, from its top left.
pub fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    film: &Film,
    k: usize,
) -> Result<()> {
    let ink = Colour::rgb(25, 25, 25);
    let head = Colour::rgb(80, 80, 80);
    let left = |size: u32, c: Colour| text_style(size, c).pos(Pos::new(HPos::Left, VPos::Center));
    let right = |c: Colour| text_style(TEXT, c).pos(Pos::new(HPos::Right, VPos::Center));
    let bodies = moving(film);
    let states = &film.states[k];
    let mut y = 6 + ROW / 2;
    if !per_body(film) {
        for line in summary(film, k) {
            area.draw_text(&line, &left(TEXT, ink), (LEFT, y))
                .map_err(plot_err)?;
            y += ROW;
        }
        return Ok(());
    }
    let mut heads = vec!["x (m)", "y (m)"];
    if rotating(film) {
        heads.extend(["θ (rad)", "ω (rad/s)"]);
    }
    let name_x = LEFT + SWATCH;
    area.draw_text("body", &left(TEXT, head), (name_x, y))
        .map_err(plot_err)?;
    for (j, h) in heads.iter().enumerate() {
        let x = name_x + NAME + (j as i32 + 1) * NUMBER - 6;
        area.draw_text(h, &right(head), (x, y)).map_err(plot_err)?;
    }
    for &i in &bodies {
        y += ROW;
        let look = &film.bodies[i];
        let s = &states[i];
        area.draw(&Rectangle::new(
            [(LEFT, y - 5), (LEFT + 10, y + 5)],
            rgb(look.colour).filled(),
        ))
        .map_err(plot_err)?;
        area.draw(&Rectangle::new(
            [(LEFT, y - 5), (LEFT + 10, y + 5)],
            rgb(shade(look.colour, OUTLINE_SHADE)).stroke_width(1),
        ))
        .map_err(plot_err)?;
        area.draw_text(&short(&look.name, 12), &left(TEXT, ink), (name_x, y))
            .map_err(plot_err)?;
        let mut values = vec![sig(s.position.x), sig(s.position.y)];
        if rotating(film) {
            if look.rotates {
                values.extend([sig(s.angle), sig(s.angular_velocity)]);
            } else {
                values.extend(["-".to_string(), "-".to_string()]);
            }
        }
        for (j, v) in values.iter().enumerate() {
            let x = name_x + NAME + (j as i32 + 1) * NUMBER - 6;
            area.draw_text(v, &right(ink), (x, y)).map_err(plot_err)?;
        }
    }
    Ok(())
}

/// A name cut to `n` characters (an ellipsis marks the cut).
fn short(name: &str, n: usize) -> String {
    if name.chars().count() <= n {
        name.to_owned()
    } else {
        let mut s: String = name.chars().take(n - 1).collect();
        s.push('…');
        s
    }
}

/// The summary lines of a scene of many moving bodies at sample `k`.
pub fn summary(film: &Film, k: usize) -> Vec<String> {
    let bodies = moving(film);
    let states = &film.states[k];
    let speed = |i: usize| states[i].velocity.norm();
    let by = |f: &dyn Fn(usize) -> f64| {
        bodies
            .iter()
            .copied()
            .max_by(|&a, &b| f(a).total_cmp(&f(b)))
            .unwrap_or(0)
    };
    let fastest = by(&speed);
    let highest = by(&|i| states[i].position.y);
    let lowest = by(&|i| -states[i].position.y);
    let name = |i: usize| short(&film.bodies[i].name, 16);
    vec![
        format!("{} moving bodies, in summary", bodies.len()),
        "(a row each would be too many)".to_owned(),
        format!("fastest: {}, {} m/s", name(fastest), sig(speed(fastest))),
        format!(
            "highest: {}, y = {} m",
            name(highest),
            sig(states[highest].position.y)
        ),
        format!(
            "lowest: {}, y = {} m",
            name(lowest),
            sig(states[lowest].position.y)
        ),
    ]
}
