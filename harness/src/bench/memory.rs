//! Peak memory of the large scenes: `harness simulate <scene>` (no output
//! asked, the command's defaults) run as a child process of this harness
//! binary, its peak resident set size read from the kernel's resource
//! usage of that one child (`wait4`'s `ru_maxrss`, in KiB on Linux), so
//! no other process is counted. A caveat of Linux's accounting: a child's
//! `ru_maxrss` can include the peak of the address space it leaves at
//! `exec`, which for a child started by `fork` is a copy of the parent's
//! (a reading of 73 MB for `container_1000` taken after the benchmark's
//! scenes, against 40 MB taken alone, was seen). So the harness also reads
//! its own peak (`getrusage(RUSAGE_SELF)`): a reading above it is the
//! child's peak; one at or below it is printed as a bound only. The
//! benchmark measures memory before its scenes, while its own peak is
//! small. Timings of the run are not taken
//! from it (the benchmark's own protocol times steps).

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
    /// Peak resident set size of the `simulate` process (MB, 10⁶ bytes),
    /// or, when `exact` is false, an upper bound of it (the harness's own
    /// peak at the start of the child).
    pub peak_mb: f64,
    /// Whether `peak_mb` is the child's peak itself (above the harness's
    /// own peak) rather than a bound.
    pub exact: bool,
    /// The harness's own peak after the child (MB).
    pub harness_mb: f64,
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
    let own_kib = own_peak_kib()?;
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
        exact: max_rss_kib > own_kib,
        harness_mb: own_kib as f64 * 1024.0 / 1e6,
        command: format!("harness simulate scenes/{id}.toml"),
    })
}

/// This process's own peak resident set size (KiB), which a child's
/// reading includes (see the module documentation). It only grows, so read
/// after the child it bounds the value the child started with.
#[cfg(target_os = "linux")]
fn own_peak_kib() -> Result<i64> {
    // SAFETY: an all-zero `rusage` is a valid value of the plain C struct.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: a live local of the right type.
    if unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut usage) } != 0 {
        bail!("getrusage: {}", std::io::Error::last_os_error());
    }
    Ok(usage.ru_maxrss)
}

#[cfg(not(target_os = "linux"))]
fn own_peak_kib() -> Result<i64> {
    bail!("peak memory is read on Linux only")
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
