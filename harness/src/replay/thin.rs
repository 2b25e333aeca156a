//! Which samples of a run the replay page keeps, body by body: as few as
//! let the page's linear interpolation between a body's kept samples pass
//! within a tolerance of every one of its recorded samples.
//!
//! The page stores values rounded to quanta (positions, angles, times:
//! [`Quanta`]) and interpolates between the rounded values at the rounded
//! times; the error of a body at recorded sample `i`, between its kept
//! samples `k ≤ i ≤ j`, is the distance between its recorded position and
//! the one the page computes at `t_i`, plus its radius times the same gap
//! in angle (how far the outline's farthest point moves). The rounding is
//! inside that error, so the bound holds for what the page shows, not only
//! for the unrounded samples. A straight flight keeps two samples, a
//! parabola a few dozen, an impact the samples on both sides of it, a body
//! at rest in a heap its settling only. The search from each kept sample
//! doubles the span until the error exceeds the tolerance, then bisects:
//! the span chosen always meets the tolerance (it is checked), though a
//! longer one might too.

use engine::BodyState;

/// The page's quanta (the `q` of a run, `encode`): every stored value is a
/// whole number of its quantum; a quantum of 0 keeps the value as it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quanta {
    /// Time (s).
    pub t: f64,
    /// Position (m).
    pub p: f64,
    /// Angle (rad).
    pub a: f64,
}

/// `v` rounded to a whole number of `q`, as the page reads it back; `v`
/// itself when `q` is 0.
pub fn rounded(v: f64, q: f64) -> f64 {
    if q > 0.0 { (v / q).round() * q } else { v }
}

/// The interpolation error (m) of body `b` with radius `radius` over the
/// samples `k..=j` (the ends included: their rounding counts), the page
/// interpolating between the rounded values at `k` and `j`.
fn error(
    times: &[f64],
    states: &[Vec<BodyState>],
    b: usize,
    radius: f64,
    q: Quanta,
    (k, j): (usize, usize),
) -> f64 {
    let t = |i: usize| rounded(times[i], q.t);
    let (tk, tj) = (t(k), t(j));
    let span = tj - tk;
    let (a, c) = (&states[k][b], &states[j][b]);
    let (ax, ay, aa) = (
        rounded(a.position.x, q.p),
        rounded(a.position.y, q.p),
        rounded(a.angle, q.a),
    );
    let (cx, cy, ca) = (
        rounded(c.position.x, q.p),
        rounded(c.position.y, q.p),
        rounded(c.angle, q.a),
    );
    let mut worst = 0.0_f64;
    for (i, sample) in states.iter().enumerate().take(j + 1).skip(k) {
        let s = if span > 0.0 { (t(i) - tk) / span } else { 0.0 };
        let x = &sample[b];
        let (px, py) = (ax + (cx - ax) * s, ay + (cy - ay) * s);
        let angle = aa + (ca - aa) * s;
        let e = (px - x.position.x).hypot(py - x.position.y) + radius * (angle - x.angle).abs();
        // A NaN error keeps the sample.
        if e.is_nan() {
            return f64::INFINITY;
        }
        worst = worst.max(e);
    }
    worst
}

/// The indices of the samples kept for body `b` (radius `radius`, m),
/// increasing: the first, the last, and enough between them that the
/// page's interpolation between kept samples, from values rounded to `q`,
/// passes within `tolerance` (m) of every recorded sample (when the
/// rounding alone allows it: a tolerance under the rounding keeps every
/// sample).
pub fn keep_body(
    times: &[f64],
    states: &[Vec<BodyState>],
    b: usize,
    radius: f64,
    q: Quanta,
    tolerance: f64,
) -> Vec<usize> {
    let n = times.len().min(states.len());
    if n <= 2 {
        return (0..n).collect();
    }
    let ok = |k: usize, j: usize| error(times, states, b, radius, q, (k, j)) <= tolerance;
    let mut kept = vec![0];
    let mut k = 0;
    while k < n - 1 {
        // Double the span while it meets the tolerance...
        let mut good = k + 1;
        let mut probe = k + 2;
        while probe < n && ok(k, probe) {
            good = probe;
            probe = k + 2 * (probe - k);
        }
        // ... then bisect between the last good span and the first bad one.
        let mut bad = probe.min(n);
        while bad - good > 1 {
            let mid = good + (bad - good) / 2;
            if ok(k, mid) {
                good = mid;
            } else {
                bad = mid;
            }
        }
        kept.push(good);
        k = good;
    }
    kept
}

/// The largest interpolation error (m) of body `b` over every recorded
/// sample, the page keeping `kept` (what a page built from `kept` is
/// within).
pub fn max_error(
    times: &[f64],
    states: &[Vec<BodyState>],
    b: usize,
    radius: f64,
    q: Quanta,
    kept: &[usize],
) -> f64 {
    kept.windows(2)
        .map(|w| error(times, states, b, radius, q, (w[0], w[1])))
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    fn state(x: f64, y: f64) -> BodyState {
        BodyState {
            position: Vector2::new(x, y),
            ..BodyState::default()
        }
    }

    /// No rounding.
    const FINE: Quanta = Quanta {
        t: 0.0,
        p: 0.0,
        a: 0.0,
    };

    #[test]
    fn a_straight_flight_keeps_its_ends_and_a_corner_its_apex() {
        let times: Vec<f64> = (0..=100).map(|i| i as f64 * 0.01).collect();
        let straight: Vec<Vec<BodyState>> =
            times.iter().map(|&t| vec![state(t, 2.0 * t)]).collect();
        assert_eq!(keep_body(&times, &straight, 0, 0.1, FINE, 1e-9), [0, 100]);
        // Up to t = 0.5 then back down: the corner sample stays.
        let corner: Vec<Vec<BodyState>> = times
            .iter()
            .map(|&t| vec![state(t, 0.5 - (t - 0.5).abs())])
            .collect();
        assert_eq!(keep_body(&times, &corner, 0, 0.1, FINE, 1e-9), [0, 50, 100]);
    }

    #[test]
    fn every_sample_is_within_the_tolerance_of_the_interpolation() {
        // A parabola: the kept set must bound the error everywhere.
        let times: Vec<f64> = (0..=1000).map(|i| i as f64 * 0.001).collect();
        let states: Vec<Vec<BodyState>> = times
            .iter()
            .map(|&t| vec![state(t, -4.9 * t * t)])
            .collect();
        let tolerance = 1e-4;
        let kept = keep_body(&times, &states, 0, 0.0, FINE, tolerance);
        // A chord of a parabola y'' = g over Δt misses it by at most
        // g Δt²/8, so no valid set has chords longer than
        // sqrt(8 tolerance / g) = 9.0 ms: at least 111 of them over 1 s.
        // The error grows with the span, so the search finds the longest
        // chord from each kept sample: within a few samples of that count.
        let least = (1.0 / (8.0 * tolerance / 9.8_f64).sqrt()).ceil() as usize;
        assert!(
            kept.len() > least && kept.len() <= least + 5,
            "{} kept, at least {least} chords",
            kept.len()
        );
        assert!(max_error(&times, &states, 0, 0.0, FINE, &kept) <= tolerance);
    }

    #[test]
    fn the_rounding_counts_in_the_error() {
        // At rest at x = 0.4 with positions rounded to 1: the page shows
        // 0, 0.4 m off. A tolerance of 0.5 m allows it, 0.3 m does not,
        // and then every sample is kept (the rounding alone exceeds it).
        let times: Vec<f64> = (0..=10).map(|i| i as f64).collect();
        let states: Vec<Vec<BodyState>> = times.iter().map(|_| vec![state(0.4, 0.0)]).collect();
        let coarse = Quanta { p: 1.0, ..FINE };
        assert_eq!(keep_body(&times, &states, 0, 0.0, coarse, 0.5), [0, 10]);
        assert_eq!(keep_body(&times, &states, 0, 0.0, coarse, 0.3).len(), 11);
        assert!((max_error(&times, &states, 0, 0.0, coarse, &[0, 10]) - 0.4).abs() < 1e-12);
    }

    #[test]
    fn a_turning_body_counts_its_outline() {
        let times: Vec<f64> = (0..=10).map(|i| i as f64).collect();
        let states: Vec<Vec<BodyState>> = times
            .iter()
            .map(|&t| {
                vec![BodyState {
                    angle: if t < 5.0 { 0.0 } else { 1.0 },
                    ..BodyState::default()
                }]
            })
            .collect();
        // The angle jumps between samples 4 and 5: both stay.
        assert_eq!(
            keep_body(&times, &states, 0, 1.0, FINE, 1e-3),
            [0, 4, 5, 10]
        );
    }
}
