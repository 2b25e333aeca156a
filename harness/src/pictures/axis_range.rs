//! Axis ranges that plotters can draw, checked before a chart is built.
//!
//! plotters 0.3.7 picks an axis's tick values in `compute_f64_key_points`
//! (`src/coord/ranged1d/types/numeric.rs`): starting from
//! `scale = 10^floor(log10(width))`, it divides the scale by 2, 5 and 10
//! until `npoints = 1 + (right − left) / scale · k` exceeds the number of
//! ticks wanted, where `left` and `right` are the bounds rounded to
//! multiples of the scale by `a − floor(a / b) · b`. That loop ends only
//! when `npoints` grows, and it never does when:
//!
//! - a bound is infinite or NaN, or the width overflows (−1e308 to 1e308):
//!   the scale is inf or NaN, `npoints` is NaN, and NaN exceeds nothing —
//!   the reported hangs of a particle at x = 1e308 (whose view centre
//!   `(lo + hi) / 2` overflowed) and of a `[linear_test]` curve going to −inf;
//! - the width is tiny next to the bounds (1e300 ± 1): once `a / b`
//!   passes 2^53 the rounding loses every digit, `npoints` stays 1, and the
//!   scale shrinks to 0 and then NaN.
//!
//! [`drawable`] refuses the first case with a clear error and widens the
//! second to a width plotters resolves, saying so: bounds within
//! [`MAX_COORDINATE`] and a width of at least [`MIN_RELATIVE_WIDTH`] times
//! the larger bound. Then, at the loop's end, `b ≥ width / (10 · ticks)`
//! and `a / b ≤ 2^30 · 10 · ticks`, below 2^53 for any tick count under
//! 800 (plotters asks for at most about 100: 10 light lines per label).

use anyhow::{Result, bail};
use engine::error::readable;

/// The largest coordinate drawn (in the axis's unit): its double still
/// fits in f64, with room for the margins a layout adds.
pub const MAX_COORDINATE: f64 = 1e300;

/// The smallest width of a range relative to its largest bound, 2^-30
/// (≈ 9.3e-10): see the module documentation.
pub const MIN_RELATIVE_WIDTH: f64 = 9.313_225_746_154_785e-10;

/// A range plotters can draw, and a note when it had to be widened.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawable {
    /// Lower bound.
    pub lo: f64,
    /// Upper bound, > `lo`.
    pub hi: f64,
    /// Set when the range was widened, saying so (for the picture's
    /// header).
    pub note: Option<String>,
}

/// Checks the range `lo..hi` of the axis named `axis` (e.g. `"x (m)"`),
/// widening one too narrow for its distance from 0; refuses a range with
/// an infinite, NaN or larger-than-[`MAX_COORDINATE`] bound.
pub fn drawable(lo: f64, hi: f64, axis: &str) -> Result<Drawable> {
    for v in [lo, hi] {
        if !v.is_finite() {
            bail!("cannot draw the {axis} axis: the run reaches {v}, not a finite number");
        }
        if v.abs() > MAX_COORDINATE {
            bail!(
                "cannot draw the {axis} axis: the run reaches {}, beyond the ±{} a picture's axes can show",
                readable(v),
                readable(MAX_COORDINATE)
            );
        }
    }
    let (lo, hi) = (lo.min(hi), lo.max(hi));
    let reach = lo.abs().max(hi.abs());
    let least = (reach * MIN_RELATIVE_WIDTH).max(f64::MIN_POSITIVE.sqrt());
    if hi - lo >= least {
        return Ok(Drawable { lo, hi, note: None });
    }
    let centre = lo + 0.5 * (hi - lo);
    let half = 0.5 * least;
    Ok(Drawable {
        lo: centre - half,
        hi: centre + half,
        note: Some(format!(
            "The {axis} axis is widened to {} around {}: the run spans less than f64 axes resolve this far from 0.",
            readable(least),
            readable(centre)
        )),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use plotters::prelude::*;

    /// Builds a chart with the guarded ranges and draws its mesh: the call
    /// that looped forever before the guard.
    fn draw(x: (f64, f64), y: (f64, f64)) -> Result<()> {
        let (x, y) = (drawable(x.0, x.1, "x")?, drawable(y.0, y.1, "y")?);
        let mut svg = String::new();
        let root = SVGBackend::with_string(&mut svg, (300, 200)).into_drawing_area();
        let mut chart = ChartBuilder::on(&root)
            .x_label_area_size(20)
            .y_label_area_size(20)
            .build_cartesian_2d(x.lo..x.hi, y.lo..y.hi)?;
        chart.configure_mesh().disable_axes().draw()?;
        Ok(())
    }

    #[test]
    fn ranges_that_hung_plotters_are_refused_or_widened_then_drawn() {
        assert!(draw((f64::INFINITY, f64::INFINITY), (0.0, 1.0)).is_err());
        assert!(draw((f64::NEG_INFINITY, 1.0), (0.0, 1.0)).is_err());
        assert!(draw((-1e308, 1e308), (0.0, 1.0)).is_err());
        for x in [
            (1e300, 1e300),
            (1e299 - 1e284, 1e299 + 1e284),
            (-1e300, 1e300),
            (1e154, 1e154 + 1.0),
            (0.0, 0.0),
            (-1e-300, 1e-300),
            (-3.0, 5.0),
        ] {
            draw(x, x).unwrap_or_else(|e| panic!("{x:?}: {e}"));
        }
    }

    #[test]
    fn a_range_too_narrow_for_its_place_is_widened_and_said() {
        let d = drawable(1e300, 1e300, "x (m)").unwrap();
        assert!(d.hi > d.lo);
        assert!(d.note.unwrap().contains("x (m) axis is widened"));
        let d = drawable(-3.0, 5.0, "x (m)").unwrap();
        assert_eq!((d.lo, d.hi, d.note), (-3.0, 5.0, None));
    }
}
