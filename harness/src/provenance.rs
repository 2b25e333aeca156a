//! Where the numbers of a report come from: machine, commit, build profile,
//! timing method. Printed at the top of `reports/README.md`.

use std::process::Command;

/// The CPU model and the number of logical CPUs, as the OS reports them.
pub fn machine() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cpus = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{model}, {cpus} logical CPUs, {}", std::env::consts::OS)
}

/// The commit the report was produced from, `+dirty` when the code (all but
/// `reports/` and `README.md`) had uncommitted changes, or "unknown" outside
/// a git checkout.
pub fn commit() -> String {
    // The workspace the harness was built from, wherever it is run.
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    let run = |args: &[&str]| {
        Command::new("git")
            .arg("-C")
            .arg(root)
            .args(args)
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    match run(&["rev-parse", "--short=12", "HEAD"]) {
        Some(hash) => {
            // The harness's own outputs (reports/, the README's table) do not
            // make the code dirty.
            let dirty = run(&[
                "status",
                "--porcelain",
                "--untracked-files=no",
                "--",
                ".",
                ":!reports",
                ":!README.md",
            ])
            .is_some_and(|s| !s.is_empty());
            if dirty { format!("{hash}+dirty") } else { hash }
        }
        None => "unknown".into(),
    }
}

/// The build profile of this binary.
pub fn profile() -> &'static str {
    if cfg!(debug_assertions) {
        "debug"
    } else {
        "release"
    }
}

/// The paragraph of provenance.
pub fn paragraph(timing_runs: usize) -> String {
    format!(
        "Machine: {}. Commit: {}. Build profile: {}. Timing: wall time of each run, minimum of up to {timing_runs} runs (fewer once the runs of one point exceed 0.5 s together), measured by the harness in this one invocation; compare times only as ratios within this report.",
        machine(),
        commit(),
        profile()
    )
}
