//! The replay's data as the page reads it: compact JSON, each moving
//! body's channels quantised and delta-encoded.
//!
//! # Format (version 1)
//!
//! ```text
//! { "version": 1, "title", "subtitle", "notes": [text],
//!   "view": [x0, y0, x1, y1],          // m: the box fitted at load
//!   "step": s,                         // s: what the step buttons move
//!   "tolerance": m,                    // interpolation error bound
//!   "bodies": [{ "name", "colour": "#rrggbb", "kind": "dynamic" | "static" | "kinematic",
//!                "mass": kg | null, "inertia": kg·m² | null, "radius": m,
//!                "parts": [{ "circle": [cx, cy, r] } | { "polygon": [x0, y0, x1, y1, ...] }] }],
//!   "springs": [[end, end]],           // end: { "world": [x, y] } | { "body": i, "local": [x, y] }
//!   "grounds": [y],                    // m: levels of landing events
//!   "runs": [{ "label", "short", "samples": n_recorded,
//!              "q": { "t", "p", "a", "v", "w" },   // quanta: s, m, rad, m/s, rad/s
//!              "t": [deltas],
//!              "bodies": [{ "fixed": [x, y, angle] }
//!                       | { "x", "y", "a", "vx", "vy", "w": [deltas] }],
//!              "energy": [J] | null,
//!              "events": [{ "name", "t", "body": i | null, "at": [x, y] | null }] }] }
//! ```
//!
//! A channel `c` with quantum `q` holds integers `d`: the value at frame
//! `k` is `q × (d_0 + … + d_k)`. Body parts are in the body frame, centred
//! on the centre of mass (m). A body that never moves in a run is `fixed`.

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

/// `values` quantised by `q` and delta-encoded.
fn deltas(values: impl Iterator<Item = f64>, q: f64) -> Value {
    let mut previous = 0_i64;
    let out: Vec<i64> = values
        .map(|v| {
            let n = (v / q).round() as i64;
            let d = n - previous;
            previous = n;
            d
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
    let out: Vec<Value> = shape
        .pieces()
        .into_iter()
        .map(|(offset, angle, piece)| {
            let (s, c) = angle.sin_cos();
            let place = |x: f64, y: f64| (offset.x + c * x - s * y, offset.y + s * x + c * y);
            match piece {
                Shape::Circle(circle) => {
                    json!({ "circle": [offset.x, offset.y, circle.radius] })
                }
                Shape::Polygon(p) => {
                    let flat: Vec<f64> = p
                        .vertices()
                        .iter()
                        .flat_map(|v| {
                            let (x, y) = place(v.x, v.y);
                            [x, y]
                        })
                        .collect();
                    json!({ "polygon": flat })
                }
                Shape::Compound(_) => json!({ "polygon": [] }),
            }
        })
        .collect();
    json!(out)
}

/// Whether body `b` keeps its pose through the whole run.
fn fixed(states: &[Vec<BodyState>], b: usize) -> bool {
    let first = &states[0][b];
    states
        .iter()
        .all(|s| s[b].position == first.position && s[b].angle == first.angle)
}

/// The JSON of one run, keeping the samples `kept`.
fn run_json(replay: &Replay, run: &ReplayRun, kept: &[usize]) -> Value {
    let size = replay.view_size();
    let q_p = quantum(size, 6);
    let max_of = |f: &dyn Fn(&BodyState) -> f64| {
        run.states
            .iter()
            .flatten()
            .map(f)
            .filter(|v| v.is_finite())
            .fold(0.0_f64, |m, v| m.max(v.abs()))
    };
    // Angles to 1e-5 rad, coarser only past 1e7 rad (12 digits).
    let q_a = quantum(max_of(&|s| s.angle), 12).max(1e-5);
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
    // Times to a thousandth of the shortest sample spacing, and at least
    // to 12 digits of the run's length.
    let q_t = quantum(dt_min.min(t_max), 4).max(quantum(t_max, 12));
    let frames = |f: &dyn Fn(&BodyState) -> f64, b: usize, q: f64| {
        deltas(kept.iter().map(|&i| f(&run.states[i][b])), q)
    };
    let bodies: Vec<Value> = (0..replay.bodies.len())
        .map(|b| {
            if run.states.is_empty() || fixed(&run.states, b) {
                let s = run.states.first().map(|s| s[b]).unwrap_or_default();
                json!({ "fixed": [s.position.x, s.position.y, s.angle] })
            } else {
                json!({
                    "x": frames(&|s| s.position.x, b, q_p),
                    "y": frames(&|s| s.position.y, b, q_p),
                    "a": frames(&|s| s.angle, b, q_a),
                    "vx": frames(&|s| s.velocity.x, b, q_v),
                    "vy": frames(&|s| s.velocity.y, b, q_v),
                    "w": frames(&|s| s.angular_velocity, b, q_w),
                })
            }
        })
        .collect();
    let energy = run.energies.as_ref().map_or(Value::Null, |e| {
        json!(kept.iter().map(|&i| short(e[i])).collect::<Vec<_>>())
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
        "q": { "t": q_t, "p": q_p, "a": q_a, "v": q_v, "w": q_w },
        "t": deltas(kept.iter().map(|&i| run.times[i]), q_t),
        "bodies": bodies,
        "energy": energy,
        "events": events,
    })
}

/// The page's data, the runs thinned to `kept` (one list per run), as
/// JSON text.
pub fn data_json(replay: &Replay, kept: &[Vec<usize>], tolerance: f64, notes: &[String]) -> String {
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
        .map(|(run, kept)| run_json(replay, run, kept))
        .collect();
    let data = json!({
        "version": 1,
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
        let values = [1.23456, 1.23466, -2.0, -2.0];
        let d = deltas(values.iter().copied(), 1e-5);
        let d: Vec<i64> = serde_json::from_value(d).unwrap();
        let mut sum = 0;
        for (v, d) in values.iter().zip(d) {
            sum += d;
            assert!((sum as f64 * 1e-5 - v).abs() <= 0.5e-5 + 1e-12, "{v}");
        }
    }
}
