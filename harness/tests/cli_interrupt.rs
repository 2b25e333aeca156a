//! SIGTERM and SIGINT through the real binary: an interrupted `simulate`
//! or `run` leaves no temporary file and no half-written output
//! (`harness::interrupt`).

#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_harness");

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Every path under `dir`, recursively (folders too), sorted.
fn entries(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    if let Ok(list) = std::fs::read_dir(dir) {
        for entry in list.flatten() {
            let path = entry.path();
            out.push(path.clone());
            if path.is_dir() {
                out.extend(entries(&path));
            }
        }
    }
    out.sort();
    out
}

fn signal(child: &Child, signal: libc::c_int) {
    let pid = libc::pid_t::try_from(child.id()).expect("a pid");
    // SAFETY: sending a signal to our own child process.
    assert_eq!(unsafe { libc::kill(pid, signal) }, 0, "kill failed");
}

/// Waits for `child` at most `limit`; kills it (and fails) beyond.
fn wait(child: &mut Child, limit: Duration) -> std::process::ExitStatus {
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("wait") {
            return status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("the harness did not end within {limit:?} of the signal");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// Polls `check` every millisecond until it holds or `limit` passes.
fn until(limit: Duration, mut check: impl FnMut() -> bool) -> bool {
    let start = Instant::now();
    while start.elapsed() < limit {
        if check() {
            return true;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    false
}

/// The signal ended the process (the default action, re-raised once the
/// temporaries are gone).
fn killed_by(status: std::process::ExitStatus, expected: libc::c_int) {
    use std::os::unix::process::ExitStatusExt;
    assert_eq!(
        status.signal(),
        Some(expected),
        "the harness should end by the signal, got {status}"
    );
}

#[test]
fn sigterm_during_a_long_simulate_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let scene = workspace().join("scenes/bench/large_pyramid.toml");
    // A long run (5051 bodies, 1000 s of simulated time): the signal lands
    // while it runs, before any output is written.
    let mut child = Command::new(BIN)
        .current_dir(dir.path())
        .args(["simulate"])
        .arg(&scene)
        .args([
            "--until", "1000", "--trace", "out.csv", "--html", "out.html",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Once the header is printed the scene is loaded and the run going;
    // give it a moment of stepping.
    std::thread::sleep(Duration::from_millis(1500));
    assert!(
        child.try_wait().unwrap().is_none(),
        "the run ended before the signal"
    );
    signal(&child, libc::SIGTERM);
    let status = wait(&mut child, Duration::from_secs(20));
    killed_by(status, libc::SIGTERM);
    assert_eq!(entries(dir.path()), Vec::<PathBuf>::new());
}

#[test]
fn a_signal_while_outputs_are_written_leaves_them_whole_or_absent() {
    // The trace of 821 bodies over 0.5 s is a few megabytes: the signal is
    // sent as soon as its temporary file appears, while it is written.
    // Whatever the timing, afterwards there is no temporary file, and an
    // output that exists is whole (the CSV ends with its last line).
    let scene = workspace().join("scenes/bench/pyramid_40.toml");
    let mut caught_a_write = 0;
    for attempt in 0..4 {
        let dir = tempfile::tempdir().unwrap();
        let mut child = Command::new(BIN)
            .current_dir(dir.path())
            .args(["simulate"])
            .arg(&scene)
            .args(["--until", "0.5", "--trace", "out.csv", "--svg", "out.svg"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let saw_tmp = until(Duration::from_secs(60), || {
            entries(dir.path())
                .iter()
                .any(|p| p.to_string_lossy().ends_with(".tmp"))
                || child.try_wait().ok().flatten().is_some()
        });
        assert!(saw_tmp, "attempt {attempt}: neither a write nor an end");
        let still_running = child.try_wait().unwrap().is_none();
        if still_running {
            caught_a_write += 1;
            signal(
                &child,
                if attempt % 2 == 0 {
                    libc::SIGTERM
                } else {
                    libc::SIGINT
                },
            );
        }
        wait(&mut child, Duration::from_secs(60));
        let left = entries(dir.path());
        assert!(
            left.iter().all(|p| !p.to_string_lossy().ends_with(".tmp")),
            "attempt {attempt}: a temporary file is left: {left:?}"
        );
        if let Ok(csv) = std::fs::read_to_string(dir.path().join("out.csv")) {
            let last = csv.lines().last().unwrap_or("");
            let header_fields = csv.lines().next().unwrap_or("").split(',').count();
            assert!(
                csv.ends_with('\n') && last.split(',').count() == header_fields,
                "attempt {attempt}: out.csv is cut short"
            );
        }
        if let Ok(svg) = std::fs::read_to_string(dir.path().join("out.svg")) {
            assert!(
                svg.trim_end().ends_with("</svg>"),
                "attempt {attempt}: out.svg is cut short"
            );
        }
    }
    assert!(
        caught_a_write > 0,
        "no attempt caught the harness while writing: the test checked nothing"
    );
}

#[test]
fn sigterm_during_run_leaves_the_out_folder_as_it_was() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("report");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("before.md"), "before").unwrap();
    let mut child = Command::new(BIN)
        .current_dir(root.path())
        .args(["run", "collision_slide", "--out"])
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // The report is staged next to `out`: send the signal once the staging
    // folder holds a file, while the report is being written.
    let staged = until(Duration::from_secs(120), || {
        entries(root.path()).iter().any(|p| {
            p.is_file()
                && p.components()
                    .any(|c| c.as_os_str().to_string_lossy().contains(".staging."))
        }) || child.try_wait().ok().flatten().is_some()
    });
    assert!(staged, "the run neither staged a file nor ended");
    assert!(
        child.try_wait().unwrap().is_none(),
        "the run ended before the signal"
    );
    signal(&child, libc::SIGTERM);
    let status = wait(&mut child, Duration::from_secs(60));
    killed_by(status, libc::SIGTERM);
    assert_eq!(
        entries(root.path()),
        vec![out.clone(), out.join("before.md")],
        "the interrupted run changed the folder"
    );
}
