//! `harness run --shard i/n` and `harness merge` through the real binary:
//! a run of a few cases split in two shards and merged writes the report
//! the unsharded run writes, file for file and byte for byte (the cases
//! chosen write no timing into their pages).

use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_harness");

/// Three quick cases; the split gives each shard at least one.
const CASES: &[&str] = &["spring", "projectile", "torque"];

/// Every file under `dir`, relative, sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(root, &path, out);
            } else {
                out.push(path.strip_prefix(root).unwrap().to_path_buf());
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

fn harness(args: &[&str]) -> std::process::Output {
    let out = Command::new(BIN)
        .args(args)
        .output()
        .expect("the harness runs");
    assert!(
        out.status.success(),
        "harness {args:?} failed: {}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

#[test]
fn two_shards_merged_write_the_report_of_the_whole_run() {
    let root = tempfile::tempdir().unwrap();
    let dir = |name: &str| root.path().join(name);
    let path = |name: &str| dir(name).to_str().unwrap().to_string();
    let run = |extra: &[&str], out: &str| {
        let mut args = vec!["run"];
        args.extend(CASES);
        args.extend(extra);
        args.extend(["--out", out]);
        harness(&args)
    };
    run(&[], &path("whole"));
    let first = run(&["--shard", "1/2"], &path("s1"));
    let second = run(&["--shard", "2/2"], &path("s2"));
    // Each shard ran a part, together every case: "run --shard i/2: k of
    // the 3 cases".
    let ran = |shard: &std::process::Output| -> usize {
        let stdout = String::from_utf8_lossy(&shard.stdout);
        let (_, after) = stdout.split_once("/2: ").expect("the shard's announcement");
        after.split_whitespace().next().unwrap().parse().unwrap()
    };
    let (a, b) = (ran(&first), ran(&second));
    assert!(a >= 1 && b >= 1 && a + b == CASES.len(), "{a} + {b}");
    // In any order.
    harness(&["merge", &path("s2"), &path("s1"), "--out", &path("merged")]);
    let (whole, merged) = (dir("whole"), dir("merged"));
    assert_eq!(files(&whole), files(&merged));
    for file in files(&whole) {
        assert!(
            std::fs::read(whole.join(&file)).unwrap() == std::fs::read(merged.join(&file)).unwrap(),
            "{} differs between the whole run and the merged shards",
            file.display()
        );
    }
    let summary = std::fs::read_to_string(merged.join("summary.json")).unwrap();
    for case in CASES {
        assert!(summary.contains(&format!("\"case\": \"{case}\"")), "{case}");
    }
}

#[test]
fn merge_refuses_a_missing_or_repeated_shard() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("s1");
    let s1 = out.to_str().unwrap();
    harness(&["run", "projectile", "torque", "--shard", "1/2", "--out", s1]);
    for args in [
        vec!["merge", s1, "--out", "/nonexistent/never"],
        vec!["merge", s1, s1, "--out", "/nonexistent/never"],
    ] {
        let done = Command::new(BIN).args(&args).output().unwrap();
        assert_eq!(done.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&done.stderr);
        assert!(
            stderr.contains("missing") || stderr.contains("twice"),
            "{stderr}"
        );
    }
}
