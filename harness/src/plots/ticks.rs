//! The ticks of a chart axis, chosen here rather than by plotters, so that
//! a log axis is labelled at whole decades only (`1e-4`, `1e-3`, never a
//! half decade such as `3.2e-4`) and a linear axis at round multiples of 1,
//! 2 or 5 × 10^k, its zero written `0` (never `-5.6e-17`).
//!
//! A log axis is handled in log10 units: the chart draws log10 of the data
//! on a linear coordinate, and [`Ticks::label`] writes `1e<k>`.

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use std::ops::Range;

/// An axis: its range in drawn units (log10 of the data on a log axis),
/// the labelled ticks and the unlabelled minor grid lines.
#[derive(Debug, Clone, PartialEq)]
pub struct Ticks {
    /// Lower end of the axis (drawn units).
    pub lo: f64,
    /// Upper end of the axis (drawn units).
    pub hi: f64,
    /// Labelled ticks (drawn units).
    pub major: Vec<f64>,
    /// Unlabelled grid lines (drawn units).
    pub minor: Vec<f64>,
    /// A log10 axis.
    pub log: bool,
    /// Linear axes: the step, as mantissa (1, 2 or 5) and power of ten.
    step: (i64, i32),
}

/// An axis as a plotters coordinate: linear over `[lo, hi]` (drawn
/// units), its grid and labels at the given ticks (plotters' own
/// `WithKeyPoints` loses the value formatter of `f64` axes).
#[derive(Debug, Clone)]
pub struct Coord {
    lo: f64,
    hi: f64,
    major: Vec<f64>,
    minor: Vec<f64>,
}

impl Ranged for Coord {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let f = (value - self.lo) / (self.hi - self.lo);
        let span = f64::from(limit.1 - limit.0);
        let offset = (span * f + 1e-3).floor();
        // Far-off values (a clipped curve's ends never are) stay finite.
        limit.0 + offset.clamp(-1e6, 1e6) as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.major.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

/// Most labelled ticks wanted on an axis.
const TARGET: f64 = 7.0;

impl Ticks {
    /// A linear axis over `[lo, hi]` (data units, `lo < hi`), about
    /// [`TARGET`] ticks at multiples of 1, 2 or 5 × 10^k.
    pub fn linear(lo: f64, hi: f64) -> Self {
        let span = (hi - lo).max(f64::MIN_POSITIVE);
        let raw = span / TARGET;
        let mut k = raw.log10().floor() as i32;
        let m = loop {
            if let Some(m) = [1, 2, 5]
                .into_iter()
                .find(|&m| m as f64 * 10f64.powi(k) >= raw)
            {
                break m;
            }
            k += 1;
        };
        let step = m as f64 * 10f64.powi(k);
        // A tick within round-off of an end is on it (3e-4 / 5e-5 = 5.99…).
        let first = (lo / step - 1e-9).ceil() as i64;
        let last = (hi / step + 1e-9).floor() as i64;
        let major = (first..=last).map(|i| i as f64 * step).collect();
        Self {
            lo,
            hi,
            major,
            minor: Vec::new(),
            log: false,
            step: (m, k),
        }
    }

    /// A log10 axis over `[lo, hi]` (log10 units): ticks at whole decades,
    /// every decade labelled up to 8 of them (beyond, every second or
    /// more, the others unlabelled grid lines). When the range holds fewer
    /// than two decades it is widened to the decades around it, so that
    /// every log axis shows at least two labelled decades.
    pub fn log(lo: f64, hi: f64) -> Self {
        let eps = 1e-9;
        let (mut lo, mut hi) = (lo, hi);
        let inside = |lo: f64, hi: f64| ((lo - eps).ceil() as i64, (hi + eps).floor() as i64);
        let (mut d0, mut d1) = inside(lo, hi);
        if d1 - d0 < 1 {
            lo = lo.min((lo + eps).floor());
            hi = hi.max((hi - eps).ceil());
            if hi - lo < 1.0 {
                hi = lo + 1.0;
            }
            (d0, d1) = inside(lo, hi);
        }
        let decades = (d1 - d0).max(1);
        let stride = (decades as f64 / 8.0).ceil().max(1.0) as i64;
        let mut major = Vec::new();
        let mut minor = Vec::new();
        for d in d0..=d1 {
            if d.rem_euclid(stride) == 0 {
                major.push(d as f64);
            } else {
                minor.push(d as f64);
            }
        }
        if decades <= 5 {
            for d in (d0 - 1)..=d1 {
                for k in 2..=9 {
                    let v = d as f64 + (k as f64).log10();
                    if v > lo && v < hi {
                        minor.push(v);
                    }
                }
            }
        }
        Self {
            lo,
            hi,
            major,
            minor,
            log: true,
            step: (1, 0),
        }
    }

    /// The plotters coordinate of this axis, with `extra` labelled ticks.
    pub fn coord(&self, extra: &[f64]) -> Coord {
        let mut major = self.major.clone();
        major.extend_from_slice(extra);
        Coord {
            lo: self.lo,
            hi: self.hi,
            major,
            minor: self.minor.clone(),
        }
    }

    /// The text of the tick at `v` (drawn units).
    pub fn label(&self, v: f64) -> String {
        if self.log {
            return format!("1e{}", v.round() as i64);
        }
        let (m, k) = self.step;
        let n = (v / (m as f64 * 10f64.powi(k))).round() as i64 * m;
        if n == 0 {
            return "0".into();
        }
        let big = self.lo.abs().max(self.hi.abs());
        if !(1e-3..1e6).contains(&big) {
            return scientific(n, k);
        }
        if k >= 0 {
            format!("{}", n as f64 * 10f64.powi(k))
        } else {
            format!("{:.*}", (-k) as usize, n as f64 * 10f64.powi(k))
        }
    }
}

/// `n × 10^k` as `d.ddde<e>`, with no trailing zeros.
fn scientific(n: i64, k: i32) -> String {
    let digits = n.unsigned_abs().to_string();
    let exponent = k + digits.len() as i32 - 1;
    let (head, tail) = digits.split_at(1);
    let tail = tail.trim_end_matches('0');
    let sign = if n < 0 { "-" } else { "" };
    if tail.is_empty() {
        format!("{sign}{head}e{exponent}")
    } else {
        format!("{sign}{head}.{tail}e{exponent}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(t: &Ticks) -> Vec<String> {
        t.major.iter().map(|&v| t.label(v)).collect()
    }

    #[test]
    fn a_log_axis_is_labelled_at_decades_only() {
        // 3e-5 to 0.3: the decades 1e-4 .. 1e-1, no half decades.
        let t = Ticks::log(3e-5f64.log10(), 0.3f64.log10());
        assert_eq!(labels(&t), ["1e-4", "1e-3", "1e-2", "1e-1"]);
        assert!(t.minor.iter().all(|v| t.lo < *v && *v < t.hi));
        // Twenty decades: every third labelled, the rest grid lines.
        let t = Ticks::log(-18.0, 2.0);
        assert!(labels(&t).iter().all(|l| !l.contains('.')), "{t:?}");
        assert!(t.major.len() <= 8 && t.major.len() >= 5, "{t:?}");
        assert_eq!(t.major.len() + t.minor.len(), 21);
    }

    #[test]
    fn a_log_range_within_one_decade_is_widened_to_two() {
        let t = Ticks::log(2e-3f64.log10(), 8e-3f64.log10());
        assert_eq!(labels(&t), ["1e-3", "1e-2"]);
        assert!(t.lo <= -3.0 && t.hi >= -2.0);
    }

    #[test]
    fn a_linear_zero_is_written_0() {
        // The energy chart's range: -0.35 .. 0.2, zero among the ticks
        // even where the sum of steps carries round-off.
        let t = Ticks::linear(-0.3500000000000001, 0.2000000000000003);
        let l = labels(&t);
        assert!(l.contains(&"0".to_string()), "{l:?}");
        assert_eq!(l, ["-0.3", "-0.2", "-0.1", "0", "0.1", "0.2"]);
        let t = Ticks::linear(-5.551115123125783e-17, 1.0);
        assert_eq!(t.label(t.major[0]), "0");
        let t = Ticks::linear(-1.0, 5.0);
        assert_eq!(labels(&t), ["-1", "0", "1", "2", "3", "4", "5"]);
    }

    #[test]
    fn tiny_and_huge_linear_ranges_read_in_powers_of_ten() {
        let t = Ticks::linear(0.0, 3e-4);
        assert_eq!(
            labels(&t),
            ["0", "5e-5", "1e-4", "1.5e-4", "2e-4", "2.5e-4", "3e-4"]
        );
        let t = Ticks::linear(0.0, 6e6);
        assert_eq!(t.label(t.major[1]), "1e6");
        let t = Ticks::linear(0.0, 2.0);
        assert_eq!(labels(&t), ["0", "0.5", "1.0", "1.5", "2.0"]);
    }
}
