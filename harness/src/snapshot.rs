//! Text form of traces for insta snapshots: sampled, rounded to significant
//! digits (not decimals: values span 1e-15 to 1e250), −0 mapped to 0, so a
//! snapshot changes only when the physics does.

use crate::cases::{MethodTrace, thin};
use std::fmt::Write as _;

/// Significant digits kept in snapshots: six digits sit far above the
/// last-bit differences of libm between platforms and far below any change
/// worth reviewing.
pub const SIGNIFICANT_DIGITS: usize = 6;

/// Magnitudes below this print as 0: in the harness's traces they are
/// round-off (errors of methods exact on the case, ~1e-16 to 1e-12), which
/// may differ in the last bits between platforms' libm.
pub const ROUND_OFF_FLOOR: f64 = 1e-11;

/// Samples kept per trace.
pub const SAMPLES: usize = 12;

/// `v` rounded to [`SIGNIFICANT_DIGITS`] in scientific notation.
pub fn round_sig(v: f64) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    if v.abs() < ROUND_OFF_FLOOR {
        return "0".into();
    }
    format!("{:.*e}", SIGNIFICANT_DIGITS - 1, v)
}

/// The snapshot text of one method's traces.
pub fn render(traces: &[&MethodTrace]) -> String {
    let mut out = String::new();
    for trace in traces {
        let _ = writeln!(out, "method {} dt {}", trace.method, trace.dt);
        let _ = writeln!(out, "{}", trace.columns.join("\t"));
        for row in thin(&trace.samples, SAMPLES) {
            let cells: Vec<String> = row.iter().map(|&v| round_sig(v)).collect();
            let _ = writeln!(out, "{}", cells.join("\t"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_keeps_six_significant_digits_and_drops_negative_zero() {
        assert_eq!(round_sig(10.957557729966094), "1.09576e1");
        assert_eq!(round_sig(-0.0), "0");
        assert_eq!(round_sig(-5.045662e19), "-5.04566e19");
        assert_eq!(round_sig(f64::NAN), "NaN");
        assert_eq!(round_sig(-8.88e-16), "0");
    }
}
