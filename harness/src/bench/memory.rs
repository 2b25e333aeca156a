//! Peak memory of the large scenes: `harness simulate <scene>` (no output
//! asked, the command's defaults) run as a child process of this harness
//! binary, its peak resident set size read from the kernel's resource
//! usage of that one child (`wait4`'s `ru_maxrss`, in KiB on Linux), so
//! nothing of the benchmark process itself is counted. Timings of the run
//! are not taken from it (the machine is shared; the benchmark's own
//! protocol times steps).

use anyhow::{Context, Result, bail};
use serde::Serialize;
use std::path::Path;
use std::process::{Command, Stdio};

/// The scenes measured: the largest of the benchmark and of the scenes
/// folder, at their own duration.
pub const SCENES: &[&str] = &["bench/large_pyramid", "container_1000", "container_10k"];

/// One scene's peak memory.
#[derive(Debug, Clone, Serialize)]
pub struct PeakMemory {
    /// Scene file, relative to the scenes folder.
    pub scene: String,
    /// Bodies of the scene.
    pub bodies: usize,
    /// Steps of its run (its duration over its step).
    pub steps: u64,
    /// Peak resident set size of the `simulate` process (MB, 10⁶ bytes).
    pub peak_mb: f64,
    /// The command measured.
    pub command: String,
}

/// Measures every scene of [`SCENES`]; `Ok(None)` where the platform gives
/// no per-child peak (not Linux).
pub fn measure_all() -> Result<Option<Vec<PeakMemory>>> {
    if !cfg!(target_os = "linux") {
        return Ok(None);
    }
    let exe = std::env::current_exe().context("locating the harness binary")?;
    SCENES
        .iter()
        .map(|s| measure(&exe, s))
        .collect::<Result<_>>()
        .map(Some)
}

/// Peak memory of `exe simulate` (the harness binary `exe`) on scene `id`
/// (relative to the scenes folder).
pub fn measure(exe: &Path, id: &str) -> Result<PeakMemory> {
    let scene = crate::scenes::load(id)?;
    let path = crate::scenes::path_of(id);
    let child = Command::new(exe)
        .arg("simulate")
        .arg(&path)
        .stdout(Stdio::null())
        .stderr(Stdio::inherit())
        .spawn()
        .with_context(|| format!("running {} simulate {}", exe.display(), path.display()))?;
    let (status, max_rss_kib) = wait_with_peak(child)?;
    if status != 0 {
        bail!(
            "harness simulate {} exited with status {status}",
            path.display()
        );
    }
    Ok(PeakMemory {
        scene: id.to_string(),
        bodies: scene.bodies().len(),
        steps: engine::step_count(scene.duration(), scene.dt()).unwrap_or(0),
        peak_mb: max_rss_kib as f64 * 1024.0 / 1e6,
        command: format!("harness simulate scenes/{id}.toml"),
    })
}

/// Waits for `child` and returns its exit status and its peak resident set
/// size (KiB).
#[cfg(target_os = "linux")]
fn wait_with_peak(child: std::process::Child) -> Result<(i32, i64)> {
    let pid = child.id() as libc::pid_t;
    let mut status: libc::c_int = 0;
    // SAFETY: an all-zero `rusage` is a valid value of the plain C struct.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `pid` is our own child, not yet waited for (the `Child` is
    // dropped without waiting, which neither waits nor kills), and both
    // pointers are to live locals of the right types.
    let got = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    if got != pid {
        bail!(
            "waiting for child {pid}: {}",
            std::io::Error::last_os_error()
        );
    }
    let code = if libc::WIFEXITED(status) {
        libc::WEXITSTATUS(status)
    } else {
        -1
    };
    drop(child);
    Ok((code, usage.ru_maxrss))
}

#[cfg(not(target_os = "linux"))]
fn wait_with_peak(mut child: std::process::Child) -> Result<(i32, i64)> {
    let status = child.wait()?;
    bail!("peak memory is read on Linux only (exit {status})")
}
