//! The CSV trace of `simulate --trace`, streamed: each kept sample's rows
//! go to the file as the run goes ([`TraceFile`]), so the trace costs one
//! buffer of memory however long the run, and the file is renamed into
//! place only when the run succeeded ([`StagedFile`]).
//!
//! One row per sample and body: `t, body, x, y, angle, vx, vy, omega,
//! energy` (s, m, rad, m/s, rad/s, J; `energy` is the world's total,
//! repeated on each body's row), numbers in Rust's shortest round-trip
//! form (they read back bit for bit), names quoted when they need it.
//! Written by hand, no csv crate.

use super::outputs::StagedFile;
use anyhow::{Context, Result};
use engine::BodyState;
use std::io::Write;
use std::path::Path;

/// The header line of a trace.
pub const HEADER: &str = "t,body,x,y,angle,vx,vy,omega,energy\n";

/// A CSV field: quoted when it holds a comma, a quote or a line break.
pub fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

/// The rows of a trace: the bodies' names, as CSV fields.
pub struct TraceRows {
    names: Vec<String>,
}

impl TraceRows {
    /// The rows of a world whose bodies are named `names`, in order.
    pub fn new(names: &[&str]) -> Self {
        Self {
            names: names.iter().map(|n| csv_field(n)).collect(),
        }
    }

    /// Writes the rows of one sample: time `t` (s), every body's state,
    /// the world's energy (J).
    pub fn write(
        &self,
        out: &mut impl Write,
        t: f64,
        states: &[BodyState],
        energy: f64,
    ) -> std::io::Result<()> {
        for (name, s) in self.names.iter().zip(states) {
            writeln!(
                out,
                "{t:?},{name},{:?},{:?},{:?},{:?},{:?},{:?},{energy:?}",
                s.position.x, s.position.y, s.angle, s.velocity.x, s.velocity.y, s.angular_velocity
            )?;
        }
        Ok(())
    }
}

/// A trace being written to its temporary file as the run goes.
pub struct TraceFile {
    rows: TraceRows,
    file: StagedFile,
}

impl TraceFile {
    /// Starts the trace of `path` (its temporary file, with the header) for
    /// bodies named `names`.
    pub fn create(path: &Path, names: &[&str]) -> Result<Self> {
        let mut file = StagedFile::create(path)?;
        file.writer()
            .write_all(HEADER.as_bytes())
            .with_context(|| format!("writing {}", file.temporary().display()))?;
        Ok(Self {
            rows: TraceRows::new(names),
            file,
        })
    }

    /// Appends the rows of one sample (see [`TraceRows::write`]).
    pub fn sample(&mut self, t: f64, states: &[BodyState], energy: f64) -> Result<()> {
        let rows = &self.rows;
        let written = rows.write(self.file.writer(), t, states, energy);
        written.with_context(|| format!("writing {}", self.file.temporary().display()))
    }

    /// The file, to be renamed into place once every output is ready.
    pub fn into_staged(self) -> StagedFile {
        self.file
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_fields_are_quoted_only_when_needed() {
        assert_eq!(csv_field("box"), "box");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
    }

    #[test]
    fn a_failed_run_leaves_neither_the_trace_nor_its_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.csv");
        let mut trace = TraceFile::create(&path, &["a"]).unwrap();
        trace.sample(0.0, &[BodyState::default()], 1.0).unwrap();
        // The temporary file is in the destination folder while the run
        // goes; the destination is not there yet.
        assert!(trace.file.temporary().exists());
        assert_eq!(trace.file.temporary().parent(), Some(dir.path()));
        assert!(!path.exists());
        drop(trace); // the run failed
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[test]
    fn a_finished_trace_is_renamed_into_place() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.csv");
        let mut trace = TraceFile::create(&path, &["a,b"]).unwrap();
        trace.sample(0.5, &[BodyState::default()], -2.0).unwrap();
        trace.into_staged().finish().unwrap();
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            format!("{HEADER}0.5,\"a,b\",0.0,0.0,0.0,0.0,0.0,0.0,-2.0\n")
        );
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}
