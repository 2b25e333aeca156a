//! What the command-line tests share: the workspace's root and a run of the
//! real `harness` binary with its exit code and output.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The workspace's root (scenes/, README.md).
pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A finished run of the binary.
pub struct Done {
    pub code: Option<i32>,
    pub stdout: String,
    pub stderr: String,
}

/// Runs `harness args...` in `dir` and waits for it.
pub fn harness(dir: &Path, args: &[&str]) -> Done {
    let output = Command::new(env!("CARGO_BIN_EXE_harness"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run the harness binary");
    Done {
        code: output.status.code(),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}
