//! The replay page shows what happened: `simulate --html` on
//! `scenes/container_1000.toml` (1000 boxes, circles and polygons falling
//! into a heap) writes a page whose stated bound is at most 1 % of its
//! smallest body's width, and what the page shows at every recorded sample
//! is within that bound of the trace (`--trace`, every digit), for every
//! body.
//!
//! The deviation is computed here, from the page's data decoded as the
//! page's script decodes it (integer second differences summed twice,
//! times their quantum, linear interpolation in time between a body's kept samples)
//! and from the trace, not from what the page's builder claims. The run
//! stops at 3 s (`--until`) to keep the test short: by then the first rows
//! have landed on the floor and on each other, so the heap's contacts,
//! impacts and turns are in it; the full 10 s run is the harness's
//! (`reports/replays/`).

use std::collections::HashMap;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_harness");
/// Where the test's run stops (s).
const UNTIL: &str = "3";

/// A channel's integer second differences summed twice, times `q`, as
/// the page's script reads it.
fn cumulative(deltas: &serde_json::Value, q: f64) -> Vec<f64> {
    let (mut step, mut n) = (0_i64, 0_i64);
    deltas
        .as_array()
        .expect("a channel")
        .iter()
        .map(|d| {
            step += d.as_i64().expect("an integer difference");
            n += step;
            n as f64 * q
        })
        .collect()
}

/// The smallest width (m) of a body's parts, from the page's own geometry:
/// a circle's diameter, a convex polygon's least extent across an edge.
fn smallest_width(parts: &serde_json::Value) -> f64 {
    let mut least = f64::INFINITY;
    for part in parts.as_array().expect("parts") {
        if let Some(c) = part.get("circle") {
            least = least.min(2.0 * c[2].as_f64().unwrap());
        }
        if let Some(p) = part.get("polygon") {
            let v: Vec<(f64, f64)> = p
                .as_array()
                .unwrap()
                .chunks(2)
                .map(|c| (c[0].as_f64().unwrap(), c[1].as_f64().unwrap()))
                .collect();
            for i in 0..v.len() {
                let (a, b) = (v[i], v[(i + 1) % v.len()]);
                let (nx, ny) = (a.1 - b.1, b.0 - a.0);
                let len = nx.hypot(ny);
                let extent = v
                    .iter()
                    .map(|p| ((p.0 - a.0) * nx + (p.1 - a.1) * ny) / len)
                    .fold(0.0_f64, |m, d| m.max(d.abs()));
                least = least.min(extent);
            }
        }
    }
    least
}

#[test]
fn container_1000_page_is_within_its_stated_bound_of_every_sample() {
    let dir = tempfile::tempdir().unwrap();
    let (html, csv) = (dir.path().join("c.html"), dir.path().join("c.csv"));
    let out = Command::new(BIN)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "simulate",
            "../scenes/container_1000.toml",
            "--until",
            UNTIL,
        ])
        .arg("--html")
        .arg(&html)
        .arg("--trace")
        .arg(&csv)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let page = std::fs::read_to_string(&html).unwrap();
    let tag = "<script id=\"replay-data\" type=\"application/json\">";
    let start = page.find(tag).expect("the data element") + tag.len();
    let end = start + page[start..].find("</script>").unwrap();
    let data: serde_json::Value = serde_json::from_str(&page[start..end]).unwrap();
    let bound = data["tolerance"].as_f64().unwrap();

    // The stated bound: at most 1 % of the smallest moving body's width,
    // and written on the page.
    let bodies = data["bodies"].as_array().unwrap();
    let smallest = bodies
        .iter()
        .filter(|b| b["kind"] != "static")
        .map(|b| smallest_width(&b["parts"]))
        .fold(f64::INFINITY, f64::min);
    // The scene's bodies are 0.3 to 0.8 m in size (its comment); a
    // triangle of size 0.3 m is narrower across an edge.
    assert!(smallest > 0.1 && smallest <= 0.3, "{smallest}");
    assert!(
        bound <= 0.01 * smallest * (1.0 + 1e-12),
        "{bound} vs {smallest}"
    );
    assert!(
        page.contains("within ") && page.contains(" m of every sample"),
        "the page states its bound"
    );
    assert!(page.contains("B of data."), "the page states its size");

    // The trace: every sample of every body, every digit.
    let text = std::fs::read_to_string(&csv).unwrap();
    let names: Vec<&str> = bodies.iter().map(|b| b["name"].as_str().unwrap()).collect();
    let index: HashMap<&str, usize> = names.iter().enumerate().map(|(i, n)| (*n, i)).collect();
    let mut trace: Vec<Vec<(f64, f64, f64, f64)>> = vec![Vec::new(); names.len()];
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let p = |i: usize| f[i].parse::<f64>().unwrap();
        trace[index[f[1]]].push((p(0), p(2), p(3), p(4)));
    }

    let run = &data["runs"][0];
    let q = &run["q"];
    let (q_t, q_p, q_a) = (
        q["t"].as_f64().unwrap(),
        q["p"].as_f64().unwrap(),
        q["a"].as_f64().unwrap(),
    );
    let times = cumulative(&run["t"], q_t);
    assert_eq!(times.len(), trace[0].len(), "every sample's time");
    let mut worst = 0.0_f64;
    let mut moving = 0;
    for (b, body) in run["bodies"].as_array().unwrap().iter().enumerate() {
        let radius = bodies[b]["radius"].as_f64().unwrap();
        let samples = &trace[b];
        if let Some(f) = body.get("fixed") {
            let (x, y, a) = (
                f[0].as_f64().unwrap(),
                f[1].as_f64().unwrap(),
                f[2].as_f64().unwrap(),
            );
            for s in samples {
                let e = (s.1 - x).hypot(s.2 - y) + radius * (s.3 - a).abs();
                worst = worst.max(e);
            }
            continue;
        }
        moving += 1;
        let k: Vec<usize> = cumulative(&body["k"], 1.0)
            .iter()
            .map(|&i| i as usize)
            .collect();
        let (x, y, a) = (
            cumulative(&body["x"], q_p),
            cumulative(&body["y"], q_p),
            cumulative(&body["a"], q_a),
        );
        assert_eq!((k[0], *k.last().unwrap()), (0, times.len() - 1));
        let mut m = 0;
        for (i, s) in samples.iter().enumerate() {
            while m + 1 < k.len() && k[m + 1] <= i {
                m += 1;
            }
            let j = (m + 1).min(k.len() - 1);
            let (ta, tb) = (times[k[m]], times[k[j]]);
            let u = if tb > ta {
                (times[i] - ta) / (tb - ta)
            } else {
                0.0
            };
            let lerp = |c: &[f64]| c[m] + (c[j] - c[m]) * u;
            let e = (lerp(&x) - s.1).hypot(lerp(&y) - s.2) + radius * (lerp(&a) - s.3).abs();
            worst = worst.max(e);
        }
    }
    assert!(moving >= 1000, "{moving} moving bodies");
    assert!(
        worst <= bound,
        "the page is {worst} m off a sample, over its bound {bound} m"
    );
    println!(
        "container_1000 until {UNTIL} s: bound {bound:.3e} m (smallest width {smallest} m), \
         largest deviation {worst:.3e} m, page {} bytes",
        page.len()
    );
}
