//! Observed order of convergence per method per case, from a step sweep
//! (docs/cases.md: p = log2(e(h)/e(h/2)) in the asymptotic range, which must
//! match the nominal order within ±0.1).
//!
//! The asymptotic range keeps the stable points whose max error over the
//! run lies between [`FLOOR`] and [`CEILING`] times the size of the
//! solution: above the ceiling the error is not yet small (pre-asymptotic,
//! or unstable); below the floor it is round-off, which does not shrink
//! with h. The observed order is the median of the orders of the (up to)
//! [`FINEST_PAIRS`] finest successive halvings inside that range: the
//! finest steps are the most asymptotic, and the median ignores one stray
//! pair.

use crate::row::{Row, RowKind};
use crate::sweep::{Sweep, SweepPoint};
use engine::{Method, Tolerance};

/// Errors below this fraction of the solution's size are round-off: over
/// 10⁵–10⁶ steps the accumulated round-off reaches ~1e-12 of the size.
pub const FLOOR: f64 = 1e-10;

/// Errors above this fraction of the solution's size are not asymptotic.
pub const CEILING: f64 = 1e-2;

/// How many of the finest halvings inside the range set the order.
pub const FINEST_PAIRS: usize = 3;

/// Tolerance on the observed order (docs/cases.md).
pub const ORDER_TOLERANCE: f64 = 0.1;

/// The observed order of one method in one sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct ObservedOrder {
    /// Method label.
    pub method: String,
    /// Order of each successive halving inside the asymptotic range.
    pub pairwise: Vec<f64>,
    /// Their median (NaN when the range holds fewer than two points).
    pub order: f64,
    /// The points used.
    pub used: Vec<SweepPoint>,
}

/// The observed order of `method` in `sweep`.
pub fn observed_order(sweep: &Sweep, method: &str) -> ObservedOrder {
    let (lo, hi) = (FLOOR * sweep.scale, CEILING * sweep.scale);
    let points: Vec<&SweepPoint> = sweep
        .points
        .iter()
        .filter(|p| p.method == method && p.tolerance.is_none())
        .collect();
    let in_range = |p: &SweepPoint| p.stable && p.max_error >= lo && p.max_error <= hi;
    let mut pairwise = Vec::new();
    let mut used = Vec::new();
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if in_range(a) && in_range(b) && (a.h / b.h - 2.0).abs() < 1e-12 {
            pairwise.push((a.max_error / b.max_error).log2());
            if used.last() != Some(a) {
                used.push(a.clone());
            }
            used.push(b.clone());
        }
    }
    let finest = &pairwise[pairwise.len().saturating_sub(FINEST_PAIRS)..];
    ObservedOrder {
        method: method.to_string(),
        order: median(finest),
        pairwise,
        used,
    }
}

fn median(values: &[f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

/// One `order` row per fixed-step method of the sweep.
pub fn order_rows(sweep: &Sweep) -> Vec<Row> {
    Method::FIXED_STEP
        .iter()
        .filter(|m| sweep.points.iter().any(|p| p.method == m.id()))
        .map(|m| {
            let observed = observed_order(sweep, m.id());
            let finest = observed.used.last().map_or(f64::NAN, |p| p.h);
            // The nominal order is the method's, from theory; the error
            // is measured against the closed form.
            Row::new(
                RowKind::Validation,
                sweep.case,
                "order",
                m.id(),
                finest,
                observed.order,
                f64::from(m.order()),
                ORDER_TOLERANCE,
                crate::row::Comparison::Within,
                format!(
                    "median of log2(e(h)/e(h/2)) over the finest {} of {} halvings with max error in [{FLOOR:e}, {CEILING:e}] x {} (asymptotic range); dt = finest step used; docs/cases.md: +/- 0.1",
                    observed.pairwise.len().min(FINEST_PAIRS),
                    observed.pairwise.len(),
                    sweep.scale
                ),
            )
        })
        .collect()
}

/// Dormand–Prince's measured error against its tolerance: the slope of
/// log(error) on log(tol) (informational: a tolerance-proportional method
/// gives about 1).
pub fn tolerance_slope(sweep: &Sweep) -> f64 {
    let pts: Vec<(f64, f64)> = sweep
        .points
        .iter()
        .filter(|p| p.tolerance.is_some() && p.stable && p.max_error > FLOOR * sweep.scale)
        .map(|p| {
            (
                p.tolerance.unwrap_or(Tolerance::uniform(1.0).rtol).ln(),
                p.max_error.ln(),
            )
        })
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (mx, my) = (sx / n, sy / n);
    let (num, den) = pts.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    num / den
}

#[cfg(test)]
mod tests {
    use super::*;

    fn synthetic(order: i32, floor: f64) -> Sweep {
        // e(h) = C h^p + round-off floor, halving from h = 0.1.
        let points = (0..12)
            .map(|k| {
                let h = 0.1 / f64::from(1u32 << k);
                let e = 0.5 * h.powi(order) + floor;
                SweepPoint {
                    method: "rk4".into(),
                    h,
                    tolerance: None,
                    error_end: e,
                    max_error: e,
                    cpu_seconds: 1e-3,
                    evaluations: 1,
                    stable: true,
                }
            })
            .collect();
        Sweep {
            case: "synthetic",
            error_label: "e",
            unit: "-",
            reference: "e(h) = 0.5 h^p + floor",
            scale: 1.0,
            points,
        }
    }

    #[test]
    fn recovers_the_order_of_a_clean_power_law() {
        let o = observed_order(&synthetic(4, 0.0), "rk4");
        // Exact power law: every halving gives exactly 4 up to round-off.
        assert!((o.order - 4.0).abs() < 1e-9, "{o:?}");
    }

    #[test]
    fn ignores_the_round_off_floor() {
        // A floor of 1e-13 (below FLOOR = 1e-10) must not bend the estimate:
        // the points under 1e-10 are excluded and the finest kept ones sit
        // 1e3 above the floor, biasing p by < 0.01.
        let o = observed_order(&synthetic(4, 1e-13), "rk4");
        assert!((o.order - 4.0).abs() < 0.01, "{o:?}");
        assert!(o.used.iter().all(|p| p.max_error >= FLOOR));
    }

    #[test]
    fn no_asymptotic_points_gives_nan_and_a_failing_row() {
        let mut sweep = synthetic(1, 0.0);
        for p in &mut sweep.points {
            p.stable = false;
        }
        assert!(observed_order(&sweep, "rk4").order.is_nan());
    }
}
