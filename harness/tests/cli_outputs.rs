//! Where `harness run` writes, through the real binary: the report goes
//! where `--out` says (before or after `run`), whole (the case's charts
//! and pictures included, every link of every page resolving), and a run
//! without `--out` writes nothing at all: not in the folder it is started
//! from, not in the workspace.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::SystemTime;

const BIN: &str = env!("CARGO_BIN_EXE_harness");

/// A cheap case that draws a chart of its own (`collision_slide_distance.svg`).
const CASE_WITH_CHART: &str = "collision_slide";

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn harness(cwd: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .current_dir(cwd)
        .args(args)
        .output()
        .expect("run the harness binary")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Every file under `dir` (recursively), sorted.
fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    if let Ok(entries) = std::fs::read_dir(dir) {
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                out.extend(files_under(&path));
            } else {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// What a run could change in the workspace: `git status` (when git and a
/// checkout are there) and the modification time of every file of
/// `reports/` and of the README.
fn workspace_state() -> (Option<String>, Vec<(PathBuf, SystemTime)>) {
    let root = workspace();
    let status = Command::new("git")
        .arg("-C")
        .arg(&root)
        .args(["status", "--porcelain", "--untracked-files=all"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| text(&o.stdout));
    let mut files = files_under(&root.join("reports"));
    files.push(root.join("README.md"));
    let times = files
        .into_iter()
        .filter_map(|p| {
            let t = std::fs::metadata(&p).ok()?.modified().ok()?;
            Some((p, t))
        })
        .collect();
    (status, times)
}

#[test]
fn out_after_run_receives_the_whole_report_with_every_link_resolving() {
    let cwd = tempfile::tempdir().expect("temp dir");
    let target = tempfile::tempdir().expect("temp dir");
    let out = target.path().join("report");
    let out_arg = out.to_str().expect("utf-8 path");
    let done = harness(cwd.path(), &["run", CASE_WITH_CHART, "--out", out_arg]);
    assert_eq!(done.status.code(), Some(0), "{}", text(&done.stderr));
    for file in [
        "README.md",
        "summary.json",
        "collision_slide_distance.svg",
        "scenes/README.md",
    ] {
        assert!(out.join(file).is_file(), "{file} not written in {out_arg}");
    }
    let pages: String = files_under(&out)
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .map(|p| std::fs::read_to_string(p).expect("page"))
        .collect();
    assert!(
        pages.contains("(collision_slide_distance.svg)")
            || pages.contains("(../collision_slide_distance.svg)"),
        "no page links the case's chart"
    );
    let broken = harness::links::broken_links(&out).expect("report readable");
    assert!(broken.is_empty(), "broken links: {broken:#?}");
    assert!(
        files_under(cwd.path()).is_empty(),
        "the run wrote into the folder it was started from: {:?}",
        files_under(cwd.path())
    );
}

#[test]
fn out_before_run_still_works() {
    let cwd = tempfile::tempdir().expect("temp dir");
    let out = cwd.path().join("r");
    let done = harness(
        cwd.path(),
        &["--out", out.to_str().expect("utf-8"), "run", "projectile"],
    );
    assert_eq!(done.status.code(), Some(0), "{}", text(&done.stderr));
    assert!(out.join("summary.json").is_file());
}

#[test]
fn a_run_of_a_case_without_out_writes_nothing() {
    let cwd = tempfile::tempdir().expect("temp dir");
    let before = workspace_state();
    let done = harness(cwd.path(), &["run", CASE_WITH_CHART]);
    assert_eq!(done.status.code(), Some(0), "{}", text(&done.stderr));
    assert!(
        !text(&done.stdout).contains("Report written"),
        "{}",
        text(&done.stdout)
    );
    assert!(
        files_under(cwd.path()).is_empty(),
        "the run wrote into the folder it was started from: {:?}",
        files_under(cwd.path())
    );
    let after = workspace_state();
    assert_eq!(before.0, after.0, "git status changed");
    assert_eq!(
        before.1, after.1,
        "a file of reports/ or the README changed"
    );
}

#[test]
fn out_is_refused_by_the_commands_that_write_no_report() {
    let cwd = tempfile::tempdir().expect("temp dir");
    let done = harness(cwd.path(), &["list", "--out", "x"]);
    assert_eq!(done.status.code(), Some(2));
    assert!(
        text(&done.stderr).contains("--out x: `list` writes no report"),
        "{}",
        text(&done.stderr)
    );
    std::fs::write(
        cwd.path().join("scene.toml"),
        "[simulation]\ndt = 0.01\nduration = 0.1\n[[bodies]]\nname = \"p\"\nmass = 1.0\n",
    )
    .expect("write scene");
    let done = harness(cwd.path(), &["simulate", "scene.toml", "--out", "x"]);
    assert_eq!(done.status.code(), Some(2));
    let stderr = text(&done.stderr);
    assert!(
        stderr.contains("--trace, --svg, --gif and --html"),
        "{stderr}"
    );
    assert!(!cwd.path().join("x").exists());
}

#[test]
fn an_unknown_case_is_refused_before_anything_runs() {
    let cwd = tempfile::tempdir().expect("temp dir");
    let done = harness(cwd.path(), &["run", "projectile", "sprnig"]);
    assert_eq!(done.status.code(), Some(2));
    let stderr = text(&done.stderr);
    assert!(stderr.contains("unknown case 'sprnig'"), "{stderr}");
    assert!(stderr.contains("spring"), "{stderr}");
    assert!(
        !text(&done.stdout).contains("== projectile"),
        "a case ran before the refusal"
    );
}

#[test]
fn a_benchmark_of_selected_scenes_needs_out_and_known_ids() {
    let cwd = tempfile::tempdir().expect("temp dir");
    let before = workspace_state();
    let done = harness(cwd.path(), &["bench", "joint_grid"]);
    assert_eq!(done.status.code(), Some(2));
    let stderr = text(&done.stderr);
    assert!(stderr.contains("give --out DIR"), "{stderr}");
    let done = harness(cwd.path(), &["bench", "joint_gird", "--out", "x"]);
    assert_eq!(done.status.code(), Some(2));
    let stderr = text(&done.stderr);
    assert!(
        stderr.contains("unknown benchmark 'joint_gird'"),
        "{stderr}"
    );
    assert!(stderr.contains("ragdoll_rain"), "{stderr}");
    assert!(files_under(cwd.path()).is_empty(), "something was written");
    assert_eq!(before, workspace_state(), "the workspace changed");
}
