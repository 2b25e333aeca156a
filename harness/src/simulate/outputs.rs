//! The outputs of `simulate` (`--trace`, `--svg`, `--gif`, `--html`): checked before
//! the run, written after it, each through a temporary file renamed into
//! place so that a failure never leaves half a file.
//!
//! An output path that exists must be a regular file: renaming over a
//! symbolic link would replace the link (not write where it points), over
//! a FIFO or a device node (`/dev/full`, `/dev/null`) would replace the
//! node by a regular file. Such paths are refused with the reason.

use super::SimulateArgs;
use anyhow::{Context, Result, anyhow, bail};
use std::fs::File;
use std::io::{BufWriter, Write as _};
use std::path::{Path, PathBuf};

/// Refuses an existing `path` that is not a regular file (a symbolic link,
/// a FIFO, a device, a socket); a missing path or a regular file passes.
pub fn refuse_special(path: &Path) -> Result<()> {
    let Ok(metadata) = std::fs::symlink_metadata(path) else {
        return Ok(()); // absent: created by the rename
    };
    let file_type = metadata.file_type();
    if file_type.is_file() {
        return Ok(());
    }
    let what = if file_type.is_symlink() {
        "a symbolic link (writing would replace the link itself, not its target)"
    } else if file_type.is_dir() {
        "a folder"
    } else {
        special_kind(&file_type)
    };
    bail!(
        "{} is {what}: refusing to replace it by a file; give the path of a regular file",
        path.display()
    )
}

fn special_kind(file_type: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a named pipe (FIFO)";
        }
        if file_type.is_char_device() || file_type.is_block_device() {
            return "a device";
        }
        if file_type.is_socket() {
            return "a socket";
        }
    }
    let _ = file_type;
    "not a regular file"
}

/// Writes `bytes` to `path` through a temporary file in the same folder
/// renamed into place ([`StagedFile`]), so that a failure never leaves
/// half a file (nor destroys the previous one), nor SIGINT or SIGTERM
/// ([`crate::interrupt`]).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    // A signal waits until the file is renamed into place (or removed):
    // the write is not raced by the signal thread's removals (a report's
    // staging folder emptied while a file is created in it).
    let _hold = crate::interrupt::hold();
    let mut file = StagedFile::create(path)?;
    file.writer()
        .write_all(bytes)
        .with_context(|| format!("writing {}", file.tmp.display()))?;
    file.finish()
}

/// A file written as a run goes (the `--trace` CSV, streamed), or at once
/// ([`write_atomically`]): its bytes go to a temporary file in the
/// destination folder (`.NAME.PID.tmp`), renamed into place by
/// [`StagedFile::finish`] only. Until then the destination is untouched:
/// dropped unfinished (a failed run, an error), the temporary file is
/// removed, and a SIGINT or SIGTERM removes it too (it is registered with
/// [`crate::interrupt::remove_on_signal`]); its creation and the rename
/// run under [`crate::interrupt::hold`], so a signal finds the output
/// whole or absent. Between them a signal is not held off (a streamed
/// trace lasts the run).
pub struct StagedFile {
    path: PathBuf,
    tmp: PathBuf,
    /// `None` once finished.
    file: Option<BufWriter<File>>,
}

impl StagedFile {
    /// Creates the temporary file of `path` (refused when `path` exists and
    /// is not a regular file, [`refuse_special`]).
    pub fn create(path: &Path) -> Result<Self> {
        let dir = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = path
            .file_name()
            .ok_or_else(|| anyhow!("{}: not a file path", path.display()))?;
        let tmp = dir.join(format!(
            ".{}.{}.tmp",
            name.to_string_lossy(),
            std::process::id()
        ));
        refuse_special(path)?;
        // Registered and created under the hold: a signal finds it
        // registered once it exists, never a file left behind.
        let _hold = crate::interrupt::hold();
        crate::interrupt::remove_on_signal(&tmp);
        let file = match File::create(&tmp) {
            Ok(file) => file,
            Err(e) => {
                crate::interrupt::forget(&tmp);
                return Err(anyhow!(e).context(format!("writing {}", tmp.display())));
            }
        };
        Ok(Self {
            path: path.to_path_buf(),
            tmp,
            file: Some(BufWriter::new(file)),
        })
    }

    /// Where the bytes go until [`StagedFile::finish`].
    pub fn writer(&mut self) -> &mut BufWriter<File> {
        self.file
            .as_mut()
            .expect("a staged file is written only before it is finished")
    }

    /// The temporary file's path.
    pub fn temporary(&self) -> &Path {
        &self.tmp
    }

    /// Flushes the bytes and renames the temporary file into place.
    pub fn finish(mut self) -> Result<()> {
        let file = self.file.take().expect("finished once");
        file.into_inner()
            .map_err(|e| anyhow!(e.into_error()))
            .and_then(|f| f.sync_all().map_err(|e| anyhow!(e)))
            .with_context(|| format!("writing {}", self.tmp.display()))?;
        // The destination may have become a link or a FIFO during the run.
        refuse_special(&self.path)?;
        let _hold = crate::interrupt::hold();
        std::fs::rename(&self.tmp, &self.path)
            .map_err(|e| anyhow!(e).context(format!("writing {}", self.path.display())))?;
        crate::interrupt::forget(&self.tmp);
        Ok(())
    }
}

impl Drop for StagedFile {
    /// Unfinished, or the rename failed: the temporary file goes.
    fn drop(&mut self) {
        if self.tmp.exists() {
            drop(self.file.take());
            let _ = std::fs::remove_file(&self.tmp);
        }
        crate::interrupt::forget(&self.tmp);
    }
}

/// One requested output: its option name and path.
pub(super) struct Output<'a> {
    pub(super) option: &'static str,
    pub(super) path: &'a Path,
}

pub(super) fn outputs(args: &SimulateArgs) -> Vec<Output<'_>> {
    [
        ("--trace", &args.trace),
        ("--svg", &args.svg),
        ("--gif", &args.gif),
        ("--html", &args.html),
    ]
    .into_iter()
    .filter_map(|(option, path)| path.as_deref().map(|path| Output { option, path }))
    .collect()
}

/// Where `path` would be, resolved through existing folders.
fn resolved(path: &Path) -> Option<PathBuf> {
    if let Ok(p) = path.canonicalize() {
        return Some(p);
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    Some(parent.canonicalize().ok()?.join(path.file_name()?))
}

/// Refuses outputs that would overwrite the scene file or each other, or
/// that cannot be written (missing folder, a folder in the way), before
/// any time is spent running.
pub(super) fn check_outputs(scene_path: &Path, outputs: &[Output<'_>]) -> Result<()> {
    let scene_real = scene_path.canonicalize().ok();
    let mut seen: Vec<(PathBuf, &str)> = Vec::new();
    for out in outputs {
        let shown = out.path.display();
        let parent = match out.path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        if !parent.is_dir() {
            bail!(
                "{} {shown}: the folder {} does not exist",
                out.option,
                parent.display()
            );
        }
        if out.path.is_dir() {
            bail!("{} {shown}: is a folder, not a file", out.option);
        }
        refuse_special(out.path).with_context(|| out.option)?;
        let real =
            resolved(out.path).ok_or_else(|| anyhow!("{} {shown}: not a file path", out.option))?;
        if scene_real.as_ref() == Some(&real) {
            bail!(
                "{} {shown} is the scene file itself: refusing to overwrite it; choose another path",
                out.option
            );
        }
        if let Some((_, other)) = seen.iter().find(|(p, _)| *p == real) {
            bail!(
                "{} and {other} both write {shown}: give each its own path",
                out.option
            );
        }
        seen.push((real, out.option));
        check_extension(out)?;
    }
    Ok(())
}

/// The format each output option writes: its file extension and what it is.
fn format_of(option: &str) -> (&'static str, &'static str) {
    match option {
        "--trace" => ("csv", "a CSV trace"),
        "--svg" => ("svg", "an SVG filmstrip"),
        "--html" => ("html", "an HTML replay page"),
        "--gif" => ("gif", "a GIF animation"),
        other => unreachable!("no output option {other}"),
    }
}

/// Refuses an output whose extension says another format than the option
/// writes (`--svg a.png` would put SVG text in a `.png`): the extension
/// must be the format's, in any case (`.svg`, `.SVG`).
fn check_extension(out: &Output<'_>) -> Result<()> {
    let (extension, format) = format_of(out.option);
    let given = out.path.extension().map(|e| e.to_string_lossy());
    if given
        .as_deref()
        .is_some_and(|e| e.eq_ignore_ascii_case(extension))
    {
        return Ok(());
    }
    let found = match given {
        Some(e) => format!("ends in .{e}"),
        None => "has no extension".to_owned(),
    };
    bail!(
        "{} {}: the file name {found}, which does not match the format: {} writes {format}; give a path ending in .{extension}",
        out.option,
        out.path.display(),
        out.option
    )
}

/// Writes each of `files` (built in memory: pictures, replays) to its path
/// and renames `trace` (streamed during the run: `samples` samples, every
/// `stride`-th step) into place, in the order asked, saying what was
/// written.
pub(super) fn write_all(
    trace: Option<(&Output<'_>, StagedFile)>,
    files: &[(&Output<'_>, Vec<u8>)],
    (samples, stride): (u64, u64),
) -> Result<()> {
    if let Some((out, file)) = trace {
        file.finish()
            .with_context(|| format!("{} {}", out.option, out.path.display()))?;
        println!(
            "wrote {} ({})",
            out.path.display(),
            samples_text(samples, stride)
        );
    }
    for (out, bytes) in files {
        write_atomically(out.path, bytes)
            .with_context(|| format!("{} {}", out.option, out.path.display()))?;
        let what = if out.option == "--trace" {
            // A `[linear_test]` trace, built in memory.
            samples_text(samples, stride)
        } else {
            format!("{:.1} kB", bytes.len() as f64 / 1024.0)
        };
        println!("wrote {} ({what})", out.path.display());
    }
    Ok(())
}

/// "`samples` samples, every `stride`th step" (the stride said only above 1).
fn samples_text(samples: u64, stride: u64) -> String {
    if stride > 1 {
        format!("{samples} samples, every {stride}th step")
    } else {
        format!("{samples} samples")
    }
}
