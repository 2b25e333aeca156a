//! `simulate`'s peak memory does not grow with the number of steps: the
//! same scene run for N and for 10·N steps, as a child process whose peak
//! resident set is read from the kernel (`harness::bench::memory`, the
//! benchmark's own measure), with no output asked and with `--trace` of
//! every step.
//!
//! The margin: keeping every sample (what `simulate` did before it
//! streamed) adds 9·N samples × bodies × one `BodyState` from N to 10·N
//! steps (and the CSV text on top with `--trace`); a recorder that keeps
//! nothing per step adds none. The test allows half of the first, so it
//! fails on a recorder that keeps every sample, or every other one, and
//! passes on one that keeps a bounded amount (allocator and page noise are
//! a few hundred kB against the ~19 MB allowed).

#![cfg(target_os = "linux")]

use harness::bench::memory::{ChildPeak, peak_of};
use std::ffi::OsString;
use std::path::Path;

const BIN: &str = env!("CARGO_BIN_EXE_harness");

/// 900 shapes on a 30 × 30 grid, 1.5 m apart (each under 0.8 m, so
/// under 1.14 m across however turned), falling
/// together under gravity without contacts: no two ever touch, and a step
/// costs little even in a debug build.
const SCENE: &str = "[simulation]\ndt = 0.01\nduration = 1.0\ngravity = [0.0, -9.81]\n\
    [[generate]]\ntype = \"grid\"\nrows = 30\ncolumns = 30\norigin = [0.0, 30.0]\n\
    spacing = [1.5, 1.5]\nshapes = [\"box\", \"circle\", \"polygon\"]\nsize = [0.3, 0.8]\nseed = 3\n";
const BODIES: u64 = 900;
/// N steps of 0.01 s.
const N: u64 = 100;

fn peak(dir: &Path, steps: u64, trace: bool) -> ChildPeak {
    let until = (steps as f64 * 0.01).to_string();
    let mut args: Vec<OsString> = vec![
        "simulate".into(),
        dir.join("grid.toml").into(),
        "--until".into(),
        until.into(),
    ];
    if trace {
        args.extend(["--trace".into(), dir.join("out.csv").into()]);
    }
    peak_of(Path::new(BIN), &args).unwrap()
}

#[test]
fn peak_memory_is_the_same_for_n_and_ten_n_steps() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("grid.toml"), SCENE).unwrap();
    let kept_mb = (9 * N * BODIES) as f64 * std::mem::size_of::<engine::BodyState>() as f64 / 1e6;
    let allowed_mb = 0.5 * kept_mb;
    for trace in [false, true] {
        let short = peak(dir.path(), N, trace);
        let long = peak(dir.path(), 10 * N, trace);
        // Linux may count in a child's reading the peak of the address
        // space it leaves at exec (see harness::bench::memory): a reading
        // equal to this process's own peak could be that, and two such
        // readings would agree whatever the child did. The readings must
        // be the child's: apart from this process's peak.
        for reading in [short, long] {
            assert!(
                (reading.peak_mb - reading.harness_mb).abs() > 1.0,
                "the reading is this process's own peak: {reading:?}"
            );
        }
        if trace {
            let rows = std::fs::read_to_string(dir.path().join("out.csv"))
                .unwrap()
                .lines()
                .count() as u64;
            assert_eq!(rows, 1 + (10 * N + 1) * BODIES, "every step traced");
        }
        let growth = long.peak_mb - short.peak_mb;
        println!(
            "trace {trace}: peak {:.1} MB at {N} steps, {:.1} MB at {} steps (growth {growth:.2} MB, \
             allowed {allowed_mb:.1}; keeping every sample would add {kept_mb:.1})",
            short.peak_mb,
            long.peak_mb,
            10 * N
        );
        assert!(
            growth < allowed_mb,
            "the peak grew by {growth:.2} MB from {N} to {} steps (trace {trace}), more than \
             half of the {kept_mb:.1} MB that keeping every sample adds",
            10 * N
        );
    }
}
