//! `harness bench` through the real binary: a selected scene writes
//! `benchmarks.json` rows that carry each engine's build and the spread
//! over the repeats; the peak memory of a `simulate` run is read from that
//! child process.

use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_harness");

#[test]
fn a_bench_row_carries_the_build_and_the_spread() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = Command::new(BIN)
        .args(["--out", dir.path().to_str().unwrap(), "bench", "pyramid_10"])
        .output()
        .expect("run the harness binary");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let json = std::fs::read_to_string(dir.path().join("benchmarks.json")).unwrap();
    let rows: serde_json::Value = serde_json::from_str(&json).unwrap();
    let rows = rows.as_array().unwrap();
    // This engine, rapier2d and Box2D's release build (this test machine
    // has AVX2; without it the Box2D row is left out with the reason), on
    // one thread, then again on `bench`'s default of two.
    let avx2 = std::is_x86_feature_detected!("avx2");
    let engines = if avx2 { 3 } else { 2 };
    assert_eq!(rows.len(), 2 * engines, "{json}");
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row["scene"], "pyramid_10");
        assert_eq!(row["threads"], if k < engines { 1 } else { 2 }, "{row}");
        // Box2D's count for its pyramid, 500, all but the first timed.
        assert_eq!(row["steps"], 499);
        assert_eq!(row["repeats"], 10);
        let (min, median, max) = (
            row["ms_per_step_min"].as_f64().unwrap(),
            row["ms_per_step_median"].as_f64().unwrap(),
            row["ms_per_step_max"].as_f64().unwrap(),
        );
        assert!(0.0 < min && min <= median && median <= max, "{row}");
        for field in ["precision", "simd", "build"] {
            assert!(!row[field].as_str().unwrap().is_empty(), "{field}: {row}");
        }
    }
    assert_eq!(rows[0]["precision"], "f64");
    if avx2 {
        assert_eq!(rows[2]["engine"], "Box2D 3.2 f32 AVX2 -O3 NDEBUG");
        assert_eq!(rows[2]["simd"], "AVX2 (8 f32 lanes)");
        assert!(
            rows[2]["build"]
                .as_str()
                .unwrap()
                .ends_with("then -O3 -DNDEBUG"),
            "{}",
            rows[2]
        );
    }
    // The stages of the profiled runs: this engine's and the linked
    // Box2D's rows at each thread count (one thread: the fine stages; two:
    // the substeps as one), none for rapier2d.
    for (k, row) in rows.iter().enumerate() {
        let profiled = avx2 && k % engines != 1;
        let Some(stages) = row["stages"].as_object() else {
            assert!(!profiled && row.get("stages").is_none(), "{row}");
            continue;
        };
        assert!(profiled, "{row}");
        let fine = row["threads"] == 1;
        assert_eq!(stages.contains_key("integrate"), fine, "{row}");
        assert_eq!(stages.contains_key("substeps"), !fine, "{row}");
        for (name, ms) in stages {
            let ms = ms.as_f64().unwrap();
            assert!(ms.is_finite(), "{name}: {row}");
            if name != "outside the stages" {
                assert!(ms >= 0.0, "{name}: {row}");
            }
        }
        // Every step collides and solves.
        assert!(stages["collide"].as_f64().unwrap() > 0.0, "{row}");
    }
    let md = std::fs::read_to_string(dir.path().join("benchmarks.md")).unwrap();
    assert!(md.contains("## The engines' builds"), "{md}");
    assert!(md.contains("single-thread lead over Box2D"), "{md}");
    if avx2 {
        assert!(
            md.contains("| stage | this engine (ms) | Box2D (ms) | difference (ms) |"),
            "{md}"
        );
        assert!(md.contains("stage by stage, one thread each"), "{md}");
        assert!(md.contains("stage by stage, 2 threads each"), "{md}");
    }
    // The quality probe: this engine's one-thread row carries it exactly
    // when one of its figures is worse than rapier2d's or Box2D's (one
    // thread) by more than 1 % and 1e-6, one probed miss per such figure,
    // each said in the target tables.
    let figure = |row: &serde_json::Value, field: &str| row[field].as_f64();
    let mut missed = Vec::new();
    for reference in &rows[1..engines] {
        for (field, name) in [
            ("top_sink", "top sink (m)"),
            ("top_drift", "top drift (m)"),
            ("fastest_at_end", "fastest at the end (m/s)"),
            ("deepest_overlap", "deepest overlap (m)"),
        ] {
            let (Some(a), Some(b)) = (figure(&rows[0], field), figure(reference, field)) else {
                continue;
            };
            if !(a <= b * 1.01 || a <= b + 1e-6) {
                missed.push((name, reference["engine"].as_str().unwrap()));
            }
        }
    }
    let probe = &rows[0]["quality_probe"];
    if missed.is_empty() {
        assert!(probe.is_null(), "{}", rows[0]);
    } else {
        let misses = probe["misses"].as_array().expect("probed misses");
        assert_eq!(misses.len(), missed.len(), "{probe}");
        for (m, (name, engine)) in misses.iter().zip(&missed) {
            assert_eq!(
                (m["figure"].as_str(), m["reference"].as_str()),
                (Some(*name), Some(*engine))
            );
            assert!(m["shifted"].as_f64().unwrap().is_finite(), "{m}");
            assert!(!m["tried"].as_array().unwrap().is_empty(), "{m}");
        }
        assert!(md.contains("Rounding alone moves the figure by"), "{md}");
    }
    // The rest of the rows never carry it.
    assert!(rows[1..].iter().all(|r| r.get("quality_probe").is_none()));
}

#[test]
fn the_peak_memory_is_the_simulate_runs() {
    use harness::bench::memory::{Measured, measure, peak_of};
    // container_1000: 1003 bodies for 10 s at 60 Hz with `--svg`, whose
    // filmstrip is drawn from every sample of every body, kept in memory:
    // 601 samples of 1003 states of at least six f64 (48 bytes) are
    // 28.9 MB, which the peak of that process must exceed.
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/container_1000.toml");
    let args = [
        "simulate".into(),
        scene.into_os_string(),
        "--svg".into(),
        dir.path().join("out.svg").into_os_string(),
    ];
    let peak = peak_of(Path::new(BIN), &args).unwrap();
    assert!(peak.peak_mb >= 1003.0 * 601.0 * 48.0 / 1e6, "{peak:?}");
    // A bound is flagged as one: a reading not above the test process's
    // own peak may be that peak (see `memory`).
    assert_eq!(peak.exact, peak.peak_mb > peak.harness_mb, "{peak:?}");
    // A row of the benchmark: the scene's bodies, the steps of `--until`,
    // the command as run.
    let run = Measured {
        scene: "container_1000",
        until: Some(1.0),
        trace: None,
    };
    let row = measure(Path::new(BIN), &run).unwrap();
    assert_eq!(row.bodies, 1003);
    assert_eq!(row.steps, 60);
    assert_eq!(
        row.command,
        "harness simulate scenes/container_1000.toml --until 1"
    );
}
