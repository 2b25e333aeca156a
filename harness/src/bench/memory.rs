//! Peak memory of the large scenes: `harness simulate <scene>` (no output
//! asked, or `--trace`; [`RUNS`]) run as a child process of this harness
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
use std::ffi::OsString;
use std::path::Path;
use std::process::{Command, Stdio};

/// One measured command: a scene (relative to the scenes folder) and the
/// options after it.
#[derive(Debug, Clone, Copy)]
pub struct Measured {
    /// Scene file, relative to the scenes folder, without `.toml`.
    pub scene: &'static str,
    /// `--until` (s), or `None` for the scene's own duration.
    pub until: Option<f64>,
    /// Whether the run writes its trace (`--trace`, into a temporary
    /// folder), with `--max-samples` when given.
    pub trace: Option<Option<u64>>,
}

/// 100 steps of `container_10k` (dt = 1/60 s).
const STEPS_100: f64 = 1.6666666666666667;

/// 3000 steps of `container_10k` (dt = 1/60 s), three times its own
/// duration.
const STEPS_3000: f64 = 50.0;

/// The runs measured: the largest scenes of the benchmark and of the
/// scenes folder at their own duration, no output asked; `container_1000`
/// for ten times its duration (6000 steps, its pile at rest from about
/// step 600 on); and `container_10k` at 100, 1000 and 3000 steps without
/// output, and at 100 and 1000 with `--trace` (every step at 100; every
/// 10th at 1000, `--max-samples 101`, so that both traces hold the same
/// rows, about 150 MB each). At 100 steps its bodies still fall, at 1000
/// and 3000 they lie in a pile whose contacts the soft step holds (its
/// constraint records), so the 100-step peak differs from the others by
/// the pile's contact state, not by the steps; `container_1000`'s two
/// rows and `container_10k`'s at 1000 and 3000 steps, each pair a pile at
/// rest, show the peak independent of the number of steps.
pub const RUNS: &[Measured] = &[
    Measured {
        scene: "bench/large_pyramid",
        until: None,
        trace: None,
    },
    Measured {
        scene: "container_1000",
        until: None,
        trace: None,
    },
    Measured {
        scene: "container_1000",
        until: Some(100.0),
        trace: None,
    },
    Measured {
        scene: "container_10k",
        until: Some(STEPS_100),
        trace: None,
    },
    Measured {
        scene: "container_10k",
        until: None,
        trace: None,
    },
    Measured {
        scene: "container_10k",
        until: Some(STEPS_3000),
        trace: None,
    },
    Measured {
        scene: "container_10k",
        until: Some(STEPS_100),
        trace: Some(None),
    },
    Measured {
        scene: "container_10k",
        until: None,
        trace: Some(Some(101)),
    },
];

/// One run's peak memory.
#[derive(Debug, Clone, Serialize)]
pub struct PeakMemory {
    /// Scene file, relative to the scenes folder.
    pub scene: String,
    /// Bodies of the scene.
    pub bodies: usize,
    /// Steps of its run.
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

/// Measures every run of [`RUNS`]; `Ok(None)` where the platform gives
/// no per-child peak (not Linux).
pub fn measure_all() -> Result<Option<Vec<PeakMemory>>> {
    if !cfg!(target_os = "linux") {
        return Ok(None);
    }
    let exe = std::env::current_exe().context("locating the harness binary")?;
    RUNS.iter()
        .map(|run| measure(&exe, run))
        .collect::<Result<_>>()
        .map(Some)
}

/// Peak memory of `exe simulate` (the harness binary `exe`) on `run`.
pub fn measure(exe: &Path, run: &Measured) -> Result<PeakMemory> {
    let scene = crate::scenes::load(run.scene)?;
    let path = crate::scenes::path_of(run.scene);
    let mut args: Vec<OsString> = vec!["simulate".into(), path.into()];
    let mut shown = format!("harness simulate scenes/{}.toml", run.scene);
    let until = run.until.unwrap_or(scene.duration());
    if let Some(until) = run.until {
        args.extend(["--until".into(), until.to_string().into()]);
        shown.push_str(&format!(" --until {until}"));
    }
    // The trace goes to a file of the system's temporary folder, removed
    // after the run.
    let trace = std::env::temp_dir().join(format!("harness-memory-{}.csv", std::process::id()));
    if let Some(max_samples) = run.trace {
        args.extend(["--trace".into(), trace.clone().into()]);
        shown.push_str(" --trace out.csv");
        if let Some(n) = max_samples {
            args.extend(["--max-samples".into(), n.to_string().into()]);
            shown.push_str(&format!(" --max-samples {n}"));
        }
    }
    let peak = peak_of(exe, &args);
    let _ = std::fs::remove_file(&trace);
    let peak = peak?;
    Ok(PeakMemory {
        scene: run.scene.to_string(),
        bodies: scene.bodies().len(),
        steps: engine::step_count(until, scene.dt()).unwrap_or(0),
        peak_mb: peak.peak_mb,
        exact: peak.exact,
        harness_mb: peak.harness_mb,
        command: shown,
    })
}

/// The peak memory of one child process.
#[derive(Debug, Clone, Copy)]
pub struct ChildPeak {
    /// Its peak resident set size (MB, 10⁶ bytes), or an upper bound of it
    /// when `exact` is false.
    pub peak_mb: f64,
    /// Whether `peak_mb` is above this process's own peak, hence the
    /// child's (see the module documentation).
    pub exact: bool,
    /// This process's own peak after the child (MB).
    pub harness_mb: f64,
}

/// Runs `exe args` (stdout discarded, stderr shown) and reads its peak
/// resident set size; an exit status other than 0 is an error.
pub fn peak_of(exe: &Path, args: &[OsString]) -> Result<ChildPeak> {
    let shown = || {
        let words: Vec<_> = args.iter().map(|a| a.to_string_lossy()).collect();
        format!("{} {}", exe.display(), words.join(" "))
    };
    let child = Command::new(exe)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::inherit())
        .spawn()
        .with_context(|| format!("running {}", shown()))?;
    let (status, max_rss_kib) = wait_with_peak(child)?;
    let own_kib = own_peak_kib()?;
    if status != 0 {
        bail!("{} exited with status {status}", shown());
    }
    Ok(ChildPeak {
        peak_mb: max_rss_kib as f64 * 1024.0 / 1e6,
        exact: max_rss_kib > own_kib,
        harness_mb: own_kib as f64 * 1024.0 / 1e6,
    })
}

/// This process's own peak resident set size (KiB), which a child's
/// reading includes (see the module documentation). It only grows, so read
/// after the child it bounds the value the child started with.
#[cfg(target_os = "linux")]
pub fn own_peak_kib() -> Result<i64> {
    // SAFETY: an all-zero `rusage` is a valid value of the plain C struct.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: a live local of the right type.
    if unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut usage) } != 0 {
        bail!("getrusage: {}", std::io::Error::last_os_error());
    }
    Ok(usage.ru_maxrss)
}

#[cfg(not(target_os = "linux"))]
pub fn own_peak_kib() -> Result<i64> {
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
