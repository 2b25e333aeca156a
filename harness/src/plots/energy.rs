//! Energy over a long run: ΔE/E0 of the seed spring at h = 0.2 s over
//! 5720 s (100 × the seed's run) for semi-implicit Euler, velocity Verlet
//! and RK4 — bounded against drifting — with rows for docs/cases.md's bands.

use super::{Chart, Series, method_style, save_svg};
use crate::cases::FigureOutput;
use crate::row::{Comparison, Row, RowKind};
use crate::scenes;
use crate::tolerance::{ROUND_OFF_RELATIVE, half_unit};
use anyhow::Result;
use engine::Method;
use references::SpringOscillator;
use references::linear_stability::oscillator_growth_per_step;
use std::path::Path;

/// Step (s) and duration (s) of the long run.
pub const DT: f64 = 0.2;
/// 100 times the seed's 57.2 s.
pub const DURATION: f64 = 5720.0;

/// Runs the three methods on the seed spring (scene and case `id`), writes
/// `<dir>/energy_<id>.svg` and returns the band rows.
pub fn write(dir: &Path, id: &str) -> Result<FigureOutput> {
    let file = format!("energy_{id}.svg");
    let exact = SpringOscillator::seed();
    let e0 = exact.energy();
    let mut series = Vec::new();
    let mut rows = Vec::new();
    let mut row = |check: &str,
                   method: Method,
                   value: f64,
                   expected: f64,
                   tol: f64,
                   cmp: Comparison,
                   reason: &str| {
        // The bands and the decay are docs/cases.md's and linear
        // stability theory's, independent of the engine.
        rows.push(Row::new(
            RowKind::Validation,
            id,
            check,
            method.id(),
            DT,
            value,
            expected,
            tol,
            cmp,
            reason,
        ));
    };
    for method in [
        Method::SemiImplicitEuler,
        Method::VelocityVerlet,
        Method::Rk4,
    ] {
        let trace = scenes::world(id, method)?.run(DURATION, DT)?;
        let rel: Vec<(f64, f64)> = trace
            .samples
            .iter()
            .map(|s| (s.t, (s.energy - e0) / e0))
            .collect();
        let (lo, hi) = rel
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(_, e)| {
                (a.min(e), b.max(e))
            });
        let band = |decimals: i32| {
            format!(
                "docs/cases.md band, quoted to {decimals} decimals: +/- half a unit; over 5720 s = 28600 steps"
            )
        };
        match method {
            Method::SemiImplicitEuler => {
                row(
                    "energy_min_5720s",
                    method,
                    lo,
                    -0.1365,
                    half_unit(4),
                    Comparison::AtLeast,
                    &band(4),
                );
                row(
                    "energy_max_5720s",
                    method,
                    hi,
                    0.1878,
                    half_unit(4),
                    Comparison::AtMost,
                    &band(4),
                );
            }
            Method::VelocityVerlet => {
                row(
                    "energy_min_5720s",
                    method,
                    lo,
                    -0.025,
                    half_unit(3),
                    Comparison::AtLeast,
                    &band(3),
                );
                row(
                    "energy_max_5720s",
                    method,
                    hi,
                    0.0,
                    ROUND_OFF_RELATIVE,
                    Comparison::AtMost,
                    "docs/cases.md: Verlet's energy never exceeds E0 on the spring at h = 0.2; 1e-9 round-off, over 5720 s = 28600 steps",
                );
            }
            _ => {
                let n = trace.samples.len() as i32 - 1;
                let r = oscillator_growth_per_step(method, DT, exact.omega()).unwrap_or(f64::NAN);
                let predicted = r.powi(2 * n);
                let end = rel.last().map_or(f64::NAN, |p| p.1) + 1.0;
                row(
                    "energy_ratio_5720s",
                    method,
                    end,
                    predicted,
                    ROUND_OFF_RELATIVE * predicted,
                    Comparison::Within,
                    "RK4 decays as |R(i h w)|^(2n) (docs/cases.md), n = 28600; 1e-9 relative round-off",
                );
            }
        }
        let thinned = crate::cases::thin(&rel, 2000);
        series.push(Series::new(method.id(), method_style(method.id()), thinned).line());
    }
    let chart = Chart {
        title: "spring, h = 0.2 s: relative energy error over 5720 s".into(),
        x_label: "t (s)".into(),
        y_label: "(E - E0) / E0".into(),
        series,
        ..Chart::default()
    };
    save_svg(&dir.join(&file), &[chart], 1, (900, 480))?;
    Ok(FigureOutput { file, rows })
}
