//! The replay's data as the page reads it: compact JSON, each moving
//! body's channels quantised and encoded as second differences, at the
//! samples that body keeps.
//!
//! # Format (version 2)
//!
//! ```text
//! { "version": 2, "title", "subtitle", "notes": [text],
//!   "view": [x0, y0, x1, y1],          // m: the box fitted at load
//!   "step": s,                         // s: what the step buttons move
//!   "tolerance": m,                    // the page's bound: every body, as shown,
//!                                      // is within it of every recorded sample
//!   "bodies": [{ "name", "colour": "#rrggbb", "kind": "dynamic" | "static" | "kinematic",
//!                "mass": kg | null, "inertia": kg·m² | null, "radius": m,
//!                "parts": [{ "circle": [cx, cy, r] } | { "polygon": [x0, y0, x1, y1, ...] }] }],
//!   "springs": [[end, end]],           // end: { "world": [x, y] } | { "body": i, "local": [x, y] }
//!   "grounds": [y],                    // m: levels of landing events
//!   "runs": [{ "label", "short", "samples": n_recorded,
//!              "q": { "t", "p", "a", "v", "w" },   // quanta: s, m, rad, m/s, rad/s
//!              "t": [deltas],                       // every recorded sample's time
//!              "bodies": [{ "fixed": [x, y, angle] }
//!                       | { "k": [deltas],          // the samples this body keeps (indices into t)
//!                           "x", "y", "a", "vx", "vy", "w": [deltas] }],  // at those samples
//!              "energy": [J] | null,                // at every recorded sample
//!              "events": [{ "name", "t", "body": i | null, "at": [x, y] | null }] }] }
//! ```
//!
//! A channel `c` with quantum `q` holds integers `d`, second differences:
//! with `s_k = d_0 + … + d_k`, the value at frame `k` is
//! `q × (s_0 + … + s_k)` (`k` with quantum 1). Between a body's kept
//! samples the page interpolates linearly in time. Body parts are in the
//! body frame, centred on the centre of mass (m). A body that never moves
//! in a run is `fixed`.

use super::{Replay, ReplayRun};
use engine::{BodyState, Shape};
use serde_json::{Value, json};

/// The quantum for values up to `magnitude` kept to `digits` significant
/// decimal digits: a power of ten.
pub fn quantum(magnitude: f64, digits: i32) -> f64 {
    let m = if magnitude.is_finite() && magnitude > 0.0 {
        magnitude
    } else {
        1.0
    };
    10f64.powi(m.log10().floor() as i32 - digits + 1)
}

/// `values` quantised by `q` and encoded as second differences of the
/// whole numbers: smooth motion sampled evenly gives small integers (a
/// body's acceleration × dt² / q), evenly spaced times and consecutive
/// indices give zeros.
fn deltas(values: impl Iterator<Item = f64>, q: f64) -> Value {
    let (mut n1, mut d1) = (0_i64, 0_i64);
    let out: Vec<i64> = values
        .map(|v| {
            let n = (v / q).round() as i64;
            let d = n - n1;
            let dd = d - d1;
            (n1, d1) = (n, d);
            dd
        })
        .collect();
    json!(out)
}

/// A number kept to 7 significant digits (energies).
fn short(v: f64) -> Value {
    format!("{v:.6e}")
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .map_or(Value::Null, |v| json!(v))
}

fn parts(shape: Option<&Shape>) -> Value {
    let Some(shape) = shape else {
        return json!([]);
    };
    if let Shape::Chain(chain) = shape {
        // Each solid segment as its two ends and back, a closed polygon of
        // no area that draws as its line (an open chain's first and last
        // points are ghosts: not drawn).
        let segments: Vec<Value> = chain
            .segments()
            .iter()
            .map(|s| json!({ "polygon": [s.point1.x, s.point1.y, s.point2.x, s.point2.y, s.point1.x, s.point1.y] }))
            .collect();
        return json!(segments);
    }
    let out: Vec<Value> = shape
        .pieces()
        .into_iter()
        .flat_map(|(offset, angle, piece)| {
            let (s, c) = angle.sin_cos();
            let place = |x: f64, y: f64| (offset.x + c * x - s * y, offset.y + s * x + c * y);
            // A piece's points placed in the body's frame, as x0, y0, x1, ...
            let flat = |points: &[nalgebra::Vector2<f64>]| -> Vec<f64> {
                points
                    .iter()
                    .flat_map(|v| {
                        let (x, y) = place(v.x, v.y);
                        [x, y]
                    })
                    .collect()
            };
            match piece {
                Shape::Circle(circle) => {
                    vec![json!({ "circle": [offset.x, offset.y, circle.radius] })]
                }
                Shape::Polygon(p) => vec![json!({ "polygon": flat(p.vertices()) })],
                // Not pieces: a compound's are its parts, a chain's are
                // drawn above.
                Shape::Compound(_) | Shape::Chain(_) => vec![json!({ "polygon": [] })],
                // The inscribed outline (48 chords a turn); a segment's two
                // ends and back, a closed polygon of no area that draws as
                // its line.
                Shape::Rounded(r) => {
                    let mut outline = r.outline(48);
                    if outline.len() == 2 {
                        outline.push(outline[0]);
                    }
                    vec![json!({ "polygon": flat(&outline) })]
                }
            }
        })
        .collect();
    json!(out)
}

/// Whether body `b` keeps its pose through the whole run.
pub fn fixed(states: &[Vec<BodyState>], b: usize) -> bool {
    let Some(first) = states.first().map(|s| &s[b]) else {
        return true;
    };
    states
        .iter()
        .all(|s| s[b].position == first.position && s[b].angle == first.angle)
}

/// The quanta of one run's channels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunQuanta {
    /// Time (s).
    pub t: f64,
    /// Position (m).
    pub p: f64,
    /// Angle (rad).
    pub a: f64,
    /// Velocity (m/s).
    pub v: f64,
    /// Angular velocity (rad/s).
    pub w: f64,
}

/// The quanta of `run` for a page whose bound is `tolerance` (m):
/// positions ten to a hundred times finer than the bound (6 digits of the
/// view when there is no bound), angles to 1e-5 rad (coarser only past 1e7 rad) and at least ten
/// times finer than the bound over the largest moving radius (so rounding
/// takes at most about a tenth of the bound; the thinning counts it),
/// velocities to 6 digits (shown, not interpolated against the bound),
/// times to a thousandth of the shortest sample spacing and at least 12
/// digits of the run's length.
pub fn quanta(replay: &Replay, run: &ReplayRun, tolerance: f64) -> RunQuanta {
    let fine = |x: f64| {
        if x.is_finite() && x > 0.0 {
            quantum(x, 2)
        } else {
            f64::INFINITY
        }
    };
    let q_p = match fine(tolerance) {
        q if q.is_finite() => q,
        _ => quantum(replay.view_size(), 6),
    };
    let max_of = |f: &dyn Fn(&BodyState) -> f64| {
        run.states
            .iter()
            .flatten()
            .map(f)
            .filter(|v| v.is_finite())
            .fold(0.0_f64, |m, v| m.max(v.abs()))
    };
    let r_max = replay
        .bodies
        .iter()
        .filter(|b| b.kind != "static")
        .map(|b| b.radius)
        .fold(0.0_f64, f64::max);
    let q_a = quantum(max_of(&|s| s.angle), 12)
        .max(1e-5)
        .min(fine(tolerance / r_max));
    let v_max = max_of(&|s| s.velocity.x.abs().max(s.velocity.y.abs()));
    let q_v = quantum(if v_max > 0.0 { v_max } else { 1.0 }, 6);
    let w_max = max_of(&|s| s.angular_velocity);
    let q_w = quantum(if w_max > 0.0 { w_max } else { 1.0 }, 6);
    let dt_min = run
        .times
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| *d > 0.0)
        .fold(f64::INFINITY, f64::min);
    let t_max = run.times.last().copied().unwrap_or(1.0).abs().max(1e-9);
    let q_t = quantum(dt_min.min(t_max), 4).max(quantum(t_max, 12));
    RunQuanta {
        t: q_t,
        p: q_p,
        a: q_a,
        v: q_v,
        w: q_w,
    }
}

/// The JSON of one run, each body keeping the samples `kept[b]` (empty for
/// a body that never moves).
fn run_json(replay: &Replay, run: &ReplayRun, kept: &[Vec<usize>], q: &RunQuanta) -> Value {
    let bodies: Vec<Value> = (0..replay.bodies.len())
        .map(|b| {
            let frames = |f: &dyn Fn(&BodyState) -> f64, q: f64| {
                deltas(kept[b].iter().map(|&i| f(&run.states[i][b])), q)
            };
            if kept[b].is_empty() {
                let s = run.states.first().map(|s| s[b]).unwrap_or_default();
                json!({ "fixed": [s.position.x, s.position.y, s.angle] })
            } else {
                json!({
                    "k": deltas(kept[b].iter().map(|&i| i as f64), 1.0),
                    "x": frames(&|s| s.position.x, q.p),
                    "y": frames(&|s| s.position.y, q.p),
                    "a": frames(&|s| s.angle, q.a),
                    "vx": frames(&|s| s.velocity.x, q.v),
                    "vy": frames(&|s| s.velocity.y, q.v),
                    "w": frames(&|s| s.angular_velocity, q.w),
                })
            }
        })
        .collect();
    let energy = run.energies.as_ref().map_or(Value::Null, |e| {
        json!(e.iter().map(|&v| short(v)).collect::<Vec<_>>())
    });
    let events: Vec<Value> = run
        .events
        .iter()
        .map(|e| {
            json!({
                "name": e.name,
                "t": e.t,
                "body": e.body,
                "at": e.position.map(|p| [p.x, p.y]),
            })
        })
        .collect();
    json!({
        "label": run.label,
        "short": run.short,
        "samples": run.times.len(),
        "q": { "t": q.t, "p": q.p, "a": q.a, "v": q.v, "w": q.w },
        "t": deltas(run.times.iter().copied(), q.t),
        "bodies": bodies,
        "energy": energy,
        "events": events,
    })
}

/// The page's data, each body of each run keeping `kept[run][body]`, at
/// the quanta `quanta[run]`, as JSON text.
pub fn data_json(
    replay: &Replay,
    kept: &[Vec<Vec<usize>>],
    quanta: &[RunQuanta],
    tolerance: f64,
    notes: &[String],
) -> String {
    let (lo, hi) = replay.view;
    let bodies: Vec<Value> = replay
        .bodies
        .iter()
        .map(|b| {
            json!({
                "name": b.name,
                "colour": b.colour.to_string(),
                "kind": b.kind,
                "mass": b.mass,
                "inertia": b.inertia,
                "radius": b.radius,
                "parts": parts(b.shape.as_ref()),
            })
        })
        .collect();
    let end = |e: &super::SpringEnd| match *e {
        super::SpringEnd::World(p) => json!({ "world": [p.x, p.y] }),
        super::SpringEnd::Body { body, local } => {
            json!({ "body": body, "local": [local.x, local.y] })
        }
    };
    let springs: Vec<Value> = replay
        .springs
        .iter()
        .map(|(a, b)| json!([end(a), end(b)]))
        .collect();
    let runs: Vec<Value> = replay
        .runs
        .iter()
        .zip(kept)
        .zip(quanta)
        .map(|((run, kept), q)| run_json(replay, run, kept, q))
        .collect();
    let data = json!({
        "version": 2,
        "title": replay.title,
        "subtitle": replay.subtitle,
        "notes": notes,
        "view": [lo.x, lo.y, hi.x, hi.y],
        "step": replay.step,
        "tolerance": tolerance,
        "bodies": bodies,
        "springs": springs,
        "grounds": replay.grounds,
        "runs": runs,
    });
    data.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quanta_are_powers_of_ten_keeping_the_digits_asked() {
        assert_eq!(quantum(4.2, 6), 1e-5);
        assert_eq!(quantum(42.0, 6), 1e-4);
        assert_eq!(quantum(0.042, 3), 1e-4);
        assert_eq!(quantum(0.0, 6), 1e-5);
        assert_eq!(quantum(f64::NAN, 6), 1e-5);
    }

    #[test]
    fn deltas_sum_back_to_the_quantised_values() {
        let values = [1.23456, 1.23466, -2.0, -2.0, 7.5];
        let d = deltas(values.iter().copied(), 1e-5);
        let d: Vec<i64> = serde_json::from_value(d).unwrap();
        // Summed twice, as the page decodes them.
        let (mut step, mut sum) = (0, 0);
        for (v, d) in values.iter().zip(d) {
            step += d;
            sum += step;
            assert!((sum as f64 * 1e-5 - v).abs() <= 0.5e-5 + 1e-12, "{v}");
        }
        // Evenly spaced values: zeros after the first two.
        let even: Vec<i64> =
            serde_json::from_value(deltas((0..5).map(|i| 0.5 * i as f64), 0.5)).unwrap();
        assert_eq!(even, [0, 1, 0, 0, 0]);
    }
}
