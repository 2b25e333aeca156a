//! Where the harness reads and writes by default: its workspace (the
//! folder above `harness/`, fixed at build time like the scenes folder), so
//! a run writes the same place from whatever folder it is started in.

use std::path::{Path, PathBuf};

/// The workspace root, without `..` when it can be resolved.
pub fn root() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    std::fs::canonicalize(&dir).unwrap_or(dir)
}

/// The committed report of a full run: `reports/`.
pub fn reports_dir() -> PathBuf {
    root().join("reports")
}

/// The report of a quick full run (`run --quick`), kept out of the
/// committed one: `target/quick-report/`.
pub fn quick_report_dir() -> PathBuf {
    root().join("target").join("quick-report")
}

/// The top-level README, whose headline table a full run rewrites.
pub fn readme() -> PathBuf {
    root().join("README.md")
}

/// Whether `a` and `b` name the same folder (compared after resolving
/// both; a folder that does not exist yet is compared as written).
pub fn same_dir(a: &Path, b: &Path) -> bool {
    let resolve = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    resolve(a) == resolve(b)
}
