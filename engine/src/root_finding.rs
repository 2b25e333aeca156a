//! Bracketed root finding, used to locate events inside a step.
//!
//! The Illinois variant of regula falsi: superlinear on smooth functions,
//! never leaves its bracket. Written here rather than taken from a crate
//! because the function is fallible (each evaluation is an integration step
//! that may report a blow-up) and the method is twenty lines.

use crate::error::Result;

/// Finds `s` in `[a, b]` with `f(s) = 0`, given `fa = f(a)` and `fb = f(b)`
/// of opposite signs (or one of them zero). Stops when the bracket is
/// narrower than `tolerance` or `f` vanishes exactly; at most 200
/// evaluations. Returns the end of the final bracket on the side of `b`, so
/// the located point has already crossed.
pub fn illinois<F>(
    mut f: F,
    mut a: f64,
    mut fa: f64,
    mut b: f64,
    mut fb: f64,
    tolerance: f64,
) -> Result<f64>
where
    F: FnMut(f64) -> Result<f64>,
{
    if fb == 0.0 {
        return Ok(b);
    }
    if fa == 0.0 {
        return Ok(a);
    }
    let mut side = 0i8;
    for _ in 0..200 {
        if (b - a).abs() <= tolerance {
            break;
        }
        let mut s = (a * fb - b * fa) / (fb - fa);
        if !(s > a.min(b) && s < a.max(b)) {
            s = 0.5 * (a + b);
        }
        let fs = f(s)?;
        if fs == 0.0 {
            return Ok(s);
        }
        if fs.signum() == fb.signum() {
            b = s;
            fb = fs;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        } else {
            a = s;
            fa = fs;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        }
    }
    Ok(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_sqrt_two_to_the_tolerance() {
        let r = illinois(|x| Ok(x * x - 2.0), 0.0, -2.0, 2.0, 2.0, 1e-15).unwrap();
        // The bracket closes to 1e-15; the root is then within a few ulps.
        assert!((r - 2f64.sqrt()).abs() < 4e-15, "{r}");
    }
}
