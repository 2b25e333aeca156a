//! Warnings `simulate` prints (on stderr, the run goes on) for scenes and
//! options that run but are likely mistakes:
//!
//! - gravity given twice, in `[simulation] gravity` and a `[[forces]]
//!   type = "gravity"`: both apply, so bodies fall under their sum;
//! - a step longer than the run: the run is then one step (of the run's
//!   length), whatever the step asked;
//! - the energy growing by orders of magnitude during the run (more than
//!   [`ENERGY_GROWTH`] times its size at t = 0), the mark of a method
//!   unstable at this step when no force of the scene feeds it.

use super::fmt_short;
use crate::report::fmt_num;
use scene::Scene;
use scene::format::ForceSpec;

/// The energy's rise above its value at t = 0, relative to that value's
/// size, beyond which [`energy_growth`] warns: three orders of magnitude.
/// A method that is merely inaccurate at its step (explicit Euler on a
/// pendulum gains a few per cent per period) stays far below it; an
/// unstable one passes it within a few periods, since its error grows
/// geometrically.
pub const ENERGY_GROWTH: f64 = 1e3;

/// The warnings known before the run: gravity twice, a step longer than
/// the run. `dt_from_option` says whether `dt` came from `--dt`.
pub fn before_run(scene: &Scene, dt: f64, dt_from_option: bool, until: f64) -> Vec<String> {
    let mut out = Vec::new();
    let file = scene.file();
    if let Some(g) = file.simulation.gravity {
        for (i, force) in file.forces.iter().enumerate() {
            if let ForceSpec::Gravity { g: g2, window } = force {
                let sum = g.vector() + g2.vector();
                out.push(format!(
                    "warning: {}: gravity is given twice, in [simulation] gravity = [{}, {}] and in forces[{i}] \
                     (type = \"gravity\", g = [{}, {}]{}): both apply, so bodies fall under their sum [{}, {}] m/s²; \
                     keep one of the two",
                    scene.origin(),
                    fmt_short(g.x),
                    fmt_short(g.y),
                    fmt_short(g2.x),
                    fmt_short(g2.y),
                    if window.is_some() { ", within its window" } else { "" },
                    fmt_short(sum.x),
                    fmt_short(sum.y),
                ));
            }
        }
    }
    if dt > until {
        let from = if dt_from_option {
            format!("--dt {}", fmt_short(dt))
        } else {
            format!("[simulation] dt = {}", fmt_short(dt))
        };
        out.push(format!(
            "warning: {}: {from} s is longer than the run ({} s): the run is a single step of {} s; \
             give a step well below the run's length",
            scene.origin(),
            fmt_short(until),
            fmt_short(until)
        ));
    }
    out
}

/// The warning after a run whose energy (J), sampled, rose from `first`
/// (at t = 0) to `highest` (the largest of the later samples) by more than
/// [`ENERGY_GROWTH`] times the size of `first`; `None` otherwise, or when
/// `first` is 0 (no scale to compare with) or not finite.
pub fn energy_growth(
    origin: &str,
    method: &str,
    dt: f64,
    (first, highest): (f64, f64),
) -> Option<String> {
    let size = first.abs();
    if !(size.is_finite() && size > 0.0 && highest.is_finite()) {
        return None;
    }
    let rise = highest - first;
    (rise > ENERGY_GROWTH * size).then(|| {
        format!(
            "warning: {origin}: the energy rose from {} J to {} J during the run, {} times its size at \
             t = 0: unless a force of the scene feeds it that much, {method} is unstable at dt = {} s; \
             use a smaller dt (or --method implicit_euler, stable at any step)",
            fmt_num(first),
            fmt_num(highest),
            fmt_num(rise / size),
            fmt_short(dt)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energy_growth_warns_only_beyond_three_orders_of_magnitude() {
        assert!(energy_growth("s", "rk4", 0.1, (-6.6, -6.0)).is_none());
        assert!(energy_growth("s", "rk4", 0.1, (-6.6, 1e4)).is_some());
        assert!(energy_growth("s", "rk4", 0.1, (-6.6, 6000.0)).is_none());
        // Energy lost, however much, is no warning.
        assert!(energy_growth("s", "rk4", 0.1, (1e6, 1.0)).is_none());
        // No scale at t = 0.
        assert!(energy_growth("s", "rk4", 0.1, (0.0, 1e9)).is_none());
        // A run of one sample has no later sample.
        assert!(energy_growth("s", "rk4", 0.1, (-6.6, f64::NEG_INFINITY)).is_none());
    }
}
