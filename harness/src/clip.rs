//! Clipping a segment to an axis-aligned rectangle (Liang–Barsky), shared
//! by the charts (a curve leaving a fixed axis range is cut where it
//! leaves, not flattened onto the edge) and the scene pictures (trails
//! inside a zoomed inset).

/// An axis-aligned rectangle: x from `x.0` to `x.1`, y from `y.0` to `y.1`
/// (any unit, `x.0 <= x.1`, `y.0 <= y.1`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// x range.
    pub x: (f64, f64),
    /// y range.
    pub y: (f64, f64),
}

impl Rect {
    /// Whether `p` lies inside or on the boundary.
    pub fn contains(&self, (x, y): (f64, f64)) -> bool {
        (self.x.0..=self.x.1).contains(&x) && (self.y.0..=self.y.1).contains(&y)
    }

    /// The part of the segment from `a` to `b` inside the rectangle, as
    /// the fractions `(t0, t1)` of the way from `a` to `b` where it enters
    /// and leaves (`0 <= t0 <= t1 <= 1`); `None` when it misses.
    pub fn clip_fractions(&self, a: (f64, f64), b: (f64, f64)) -> Option<(f64, f64)> {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let mut t0: f64 = 0.0;
        let mut t1: f64 = 1.0;
        // Each boundary as p * t <= q.
        for (p, q) in [
            (-dx, a.0 - self.x.0),
            (dx, self.x.1 - a.0),
            (-dy, a.1 - self.y.0),
            (dy, self.y.1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
                continue;
            }
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return None;
            }
        }
        (t0.is_finite() && t1.is_finite()).then_some((t0, t1))
    }

    /// The segment from `a` to `b` cut to the rectangle; `None` when it
    /// misses.
    pub fn clip(&self, a: (f64, f64), b: (f64, f64)) -> Option<((f64, f64), (f64, f64))> {
        let (t0, t1) = self.clip_fractions(a, b)?;
        // Clamped, so that round-off never puts an end a hair outside.
        let at = |t: f64| {
            (
                (a.0 + t * (b.0 - a.0)).clamp(self.x.0, self.x.1),
                (a.1 + t * (b.1 - a.1)).clamp(self.y.0, self.y.1),
            )
        };
        Some((at(t0), at(t1)))
    }

    /// A polyline cut to the rectangle: the runs of it that lie inside,
    /// each a polyline of its own.
    pub fn clip_polyline(&self, points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
        let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
        let mut current: Vec<(f64, f64)> = Vec::new();
        for pair in points.windows(2) {
            match self.clip(pair[0], pair[1]) {
                Some((p, q)) => {
                    if current.last() != Some(&p) {
                        if current.len() > 1 {
                            runs.push(std::mem::take(&mut current));
                        }
                        current.clear();
                        current.push(p);
                    }
                    current.push(q);
                }
                None => {
                    if current.len() > 1 {
                        runs.push(std::mem::take(&mut current));
                    }
                    current.clear();
                }
            }
        }
        if current.len() > 1 {
            runs.push(current);
        }
        runs
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const UNIT: Rect = Rect {
        x: (0.0, 1.0),
        y: (0.0, 1.0),
    };

    #[test]
    fn a_segment_leaving_the_box_is_cut_where_it_leaves() {
        let (p, q) = UNIT.clip((0.5, 0.5), (0.5, 3.0)).unwrap();
        assert_eq!(p, (0.5, 0.5));
        assert!((q.1 - 1.0).abs() < 1e-15 && q.0 == 0.5, "{q:?}");
        // Crossing the whole box diagonally.
        let (p, q) = UNIT.clip((-1.0, -1.0), (2.0, 2.0)).unwrap();
        assert!(
            (p.0).abs() < 1e-15 && (q.0 - 1.0).abs() < 1e-15,
            "{p:?} {q:?}"
        );
        // Outside altogether, and parallel outside.
        assert_eq!(UNIT.clip((2.0, 0.0), (3.0, 1.0)), None);
        assert_eq!(UNIT.clip((-1.0, 2.0), (5.0, 2.0)), None);
    }

    #[test]
    fn a_polyline_through_the_box_splits_into_runs() {
        let runs =
            UNIT.clip_polyline(&[(0.2, 0.2), (0.4, 0.8), (0.5, 5.0), (0.6, 0.5), (0.8, 0.5)]);
        assert_eq!(runs.len(), 2, "{runs:?}");
        assert_eq!(runs[0][0], (0.2, 0.2));
        assert_eq!(runs[1].last(), Some(&(0.8, 0.5)));
        assert!(runs.iter().flatten().all(|&p| UNIT.contains(p)), "{runs:?}");
    }
}
