//! `simulate --trace`, streamed: the file holds the same bytes the
//! in-memory writer wrote before the trace was streamed (a committed
//! fixture, `fixtures/trace_names.csv`, written by that writer), and a run
//! that fails leaves neither the trace nor its temporary file, nor touches
//! a trace already there.

use std::path::Path;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_harness");

fn simulate(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .current_dir(dir)
        .arg("simulate")
        .args(args)
        .output()
        .expect("run the harness binary")
}

fn fixture(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

#[test]
fn the_streamed_trace_is_the_bytes_of_the_in_memory_writer() {
    let dir = tempfile::tempdir().unwrap();
    let scene = fixture("trace_names.toml");
    let out = simulate(
        dir.path(),
        &[
            scene.to_str().unwrap(),
            "--max-samples",
            "41",
            "--trace",
            "trace.csv",
        ],
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("wrote trace.csv (41 samples, every 5th step)"),
        "{stdout}"
    );
    let written = std::fs::read(dir.path().join("trace.csv")).unwrap();
    let expected = std::fs::read(fixture("trace_names.csv")).unwrap();
    if written != expected {
        let (w, e) = (
            String::from_utf8_lossy(&written),
            String::from_utf8_lossy(&expected),
        );
        let first = w.lines().zip(e.lines()).position(|(a, b)| a != b);
        panic!(
            "the trace differs from the fixture ({} against {} bytes), first at line {first:?}",
            written.len(),
            expected.len()
        );
    }
    // Only the trace is left: its temporary file was renamed.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn a_failed_run_leaves_no_trace_and_keeps_the_old_one() {
    // Explicit Euler on a stiff spring: |1 + i h w| = 1000 per step, so
    // the energy overflows after about a hundred steps, each of which has
    // streamed its row to the temporary file by then.
    let dir = tempfile::tempdir().unwrap();
    let scene = "[simulation]\nmethod = \"explicit_euler\"\ndt = 1.0\nduration = 1000.0\n\
                 [[bodies]]\nname = \"p\"\nmass = 1.0\nposition = [1.0, 0.0]\n\
                 [[forces]]\ntype = \"spring\"\nbody = \"p\"\nanchor = [0.0, 0.0]\nstiffness = 1e6\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    std::fs::write(dir.path().join("old.csv"), "an earlier trace\n").unwrap();
    for trace in ["new.csv", "old.csv"] {
        let out = simulate(dir.path(), &["scene.toml", "--trace", trace]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains("blow-up"), "{stderr}");
        let mut left: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(left, ["old.csv", "scene.toml"], "after --trace {trace}");
        assert_eq!(
            std::fs::read_to_string(dir.path().join("old.csv")).unwrap(),
            "an earlier trace\n"
        );
    }
}
