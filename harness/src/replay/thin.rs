//! Which samples of a run the replay page keeps: as few as let the page's
//! linear interpolation between kept samples pass within a tolerance of
//! every sample dropped, for every moving body.
//!
//! The error of dropping sample `i` between kept samples `k < i < j` is,
//! for each moving body, the distance between its recorded position and
//! the one interpolated at `t_i`, plus its radius times the same gap in
//! angle (how far the outline's farthest point moves): a straight flight
//! keeps two samples, a parabola a few dozen, an impact the samples on
//! both sides of it. The search from each kept sample doubles the span
//! until the error exceeds the tolerance, then bisects: the span chosen
//! always meets the tolerance (it is checked), though a longer one might
//! too.

use engine::BodyState;

/// The largest interpolation error (m) over the samples strictly between
/// `k` and `j`, for the bodies whose `radii[b]` is `Some` (the moving
/// ones; the value is the body's radius, m).
fn error(
    times: &[f64],
    states: &[Vec<BodyState>],
    radii: &[Option<f64>],
    k: usize,
    j: usize,
) -> f64 {
    let (tk, tj) = (times[k], times[j]);
    let span = tj - tk;
    let mut worst = 0.0_f64;
    for i in k + 1..j {
        let s = if span > 0.0 {
            (times[i] - tk) / span
        } else {
            0.0
        };
        for (b, radius) in radii.iter().enumerate() {
            let Some(r) = radius else { continue };
            let (a, c, x) = (&states[k][b], &states[j][b], &states[i][b]);
            let p = a.position + (c.position - a.position) * s;
            let angle = a.angle + (c.angle - a.angle) * s;
            let e = (p - x.position).norm() + r * (angle - x.angle).abs();
            // A NaN error keeps the sample.
            if e.is_nan() {
                return f64::INFINITY;
            }
            worst = worst.max(e);
        }
    }
    worst
}

/// The indices of the samples kept, increasing: the first, the last, and
/// enough between them that interpolating linearly between kept samples
/// passes within `tolerance` (m) of every sample for every moving body
/// (`radii[b]` is the radius of body `b` if it moves, `None` if it does
/// not).
pub fn keep(
    times: &[f64],
    states: &[Vec<BodyState>],
    radii: &[Option<f64>],
    tolerance: f64,
) -> Vec<usize> {
    let n = times.len().min(states.len());
    if n <= 2 {
        return (0..n).collect();
    }
    let ok = |k: usize, j: usize| error(times, states, radii, k, j) <= tolerance;
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

    #[test]
    fn a_straight_flight_keeps_its_ends_and_a_corner_its_apex() {
        let times: Vec<f64> = (0..=100).map(|i| i as f64 * 0.01).collect();
        let straight: Vec<Vec<BodyState>> =
            times.iter().map(|&t| vec![state(t, 2.0 * t)]).collect();
        assert_eq!(keep(&times, &straight, &[Some(0.1)], 1e-9), [0, 100]);
        // Up to t = 0.5 then back down: the corner sample stays.
        let corner: Vec<Vec<BodyState>> = times
            .iter()
            .map(|&t| vec![state(t, 0.5 - (t - 0.5).abs())])
            .collect();
        assert_eq!(keep(&times, &corner, &[Some(0.1)], 1e-9), [0, 50, 100]);
        // A body that does not move counts for nothing.
        assert_eq!(keep(&times, &corner, &[None], 1e-9), [0, 100]);
    }

    #[test]
    fn every_dropped_sample_is_within_the_tolerance_of_the_interpolation() {
        // A parabola: the kept set must bound the error everywhere.
        let times: Vec<f64> = (0..=1000).map(|i| i as f64 * 0.001).collect();
        let states: Vec<Vec<BodyState>> = times
            .iter()
            .map(|&t| vec![state(t, -4.9 * t * t)])
            .collect();
        let tolerance = 1e-4;
        let kept = keep(&times, &states, &[Some(0.0)], tolerance);
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
        for pair in kept.windows(2) {
            assert!(error(&times, &states, &[Some(0.0)], pair[0], pair[1]) <= tolerance);
        }
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
        assert_eq!(keep(&times, &states, &[Some(1.0)], 1e-3), [0, 4, 5, 10]);
    }
}
