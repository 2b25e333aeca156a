//! Clean interruption: SIGINT (Ctrl-C) and SIGTERM (`kill`, `timeout`)
//! end any harness command without leaving a temporary file or half an
//! output behind.
//!
//! The design, in three parts:
//!
//! - [`install`] (called by `main` before any thread starts) blocks both
//!   signals in the main thread, so every thread started later inherits
//!   the block, and starts one thread that waits for them (`sigwait`).
//!   No code runs inside a signal handler: the waiting thread is an
//!   ordinary thread that may take locks and remove files.
//! - A write that must not be cut in half (a temporary file written then
//!   renamed into place, a staged report moved into place) runs while it
//!   holds the [`hold`] lock. On a signal the waiting thread takes that
//!   lock first, so it waits until such a write has finished (the output
//!   is then whole, the temporary file renamed) and no new one starts.
//! - Folders and files registered with [`remove_on_signal`] (the staging
//!   folder of a report, [`Staging`]) are removed by the waiting thread,
//!   which then ends the process by the signal's default action (the
//!   parent sees "killed by SIGTERM" as before).
//!
//! Without [`install`] (the library's tests) nothing is blocked and the
//! locks cost one uncontended mutex each.

use anyhow::{Context, Result};
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// Held during writes that must finish whole; taken by the signal thread.
static WRITING: Mutex<()> = Mutex::new(());
/// Paths removed when a signal ends the process.
static TO_REMOVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

thread_local! {
    /// This thread's nesting depth of [`hold`] and the guard of its
    /// outermost one (a write inside a held section holds it again).
    static HELD: RefCell<(usize, Option<MutexGuard<'static, ()>>)> =
        const { RefCell::new((0, None)) };
}

/// While alive, a signal waits: see the module doc. Nested holds in one
/// thread are allowed.
#[must_use = "the hold ends when this value is dropped"]
pub struct Hold(());

/// Takes the write lock (re-entrant within a thread) until the returned
/// [`Hold`] is dropped.
pub fn hold() -> Hold {
    HELD.with(|held| {
        let mut held = held.borrow_mut();
        if held.0 == 0 {
            held.1 = Some(WRITING.lock().unwrap_or_else(|e| e.into_inner()));
        }
        held.0 += 1;
    });
    Hold(())
}

impl Drop for Hold {
    fn drop(&mut self) {
        HELD.with(|held| {
            let mut held = held.borrow_mut();
            held.0 -= 1;
            if held.0 == 0 {
                held.1 = None;
            }
        });
    }
}

/// Registers `path` (a file or a folder) to be removed if a signal ends
/// the process; [`forget`] it once it no longer should be.
pub fn remove_on_signal(path: &Path) {
    let mut list = TO_REMOVE.lock().unwrap_or_else(|e| e.into_inner());
    list.push(path.to_path_buf());
}

/// Undoes [`remove_on_signal`] for `path`.
pub fn forget(path: &Path) {
    let mut list = TO_REMOVE.lock().unwrap_or_else(|e| e.into_inner());
    list.retain(|p| p != path);
}

/// Removes `path`, a file or a folder with its contents; a missing path is
/// not an error.
fn remove(path: &Path) {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.is_dir() => {
            let _ = std::fs::remove_dir_all(path);
        }
        Ok(_) => {
            let _ = std::fs::remove_file(path);
        }
        Err(_) => {}
    }
}

/// Blocks SIGINT and SIGTERM in the calling thread and starts the thread
/// that handles them (see the module doc). Call it first in `main`, before
/// any other thread exists (threads inherit the calling thread's mask).
#[cfg(unix)]
pub fn install() {
    // SAFETY: plain libc calls on a zero-initialised local signal set;
    // the mask is changed before any other thread exists.
    let set = unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        libc::sigaddset(&mut set, libc::SIGINT);
        libc::sigaddset(&mut set, libc::SIGTERM);
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return; // signals keep their default action
        }
        set
    };
    let spawned = std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            let mut signal: libc::c_int = 0;
            // SAFETY: `set` is a valid signal set; `signal` a valid out-pointer.
            while unsafe { libc::sigwait(&set, &mut signal) } != 0 {}
            let _writing = WRITING.lock().unwrap_or_else(|e| e.into_inner());
            let list = TO_REMOVE.lock().unwrap_or_else(|e| e.into_inner());
            for path in list.iter() {
                remove(path);
            }
            // Let a shown progress bar's line end before the shell prompt.
            eprintln!();
            // SAFETY: restoring the default action and re-raising the signal
            // in this thread (where it is then unblocked) ends the process as
            // the signal would have; `_exit` is the fallback.
            unsafe {
                libc::signal(signal, libc::SIG_DFL);
                libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
                libc::raise(signal);
                libc::_exit(128 + signal);
            }
        });
    if spawned.is_err() {
        // No handler thread: give the signals their default action back.
        // SAFETY: as above.
        unsafe {
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
        }
    }
}

/// Elsewhere the signals keep their default action.
#[cfg(not(unix))]
pub fn install() {}

/// A report written into a staging folder next to its destination, moved
/// into place by [`Staging::commit`] (while holding [`hold`]), and removed
/// if the run fails or a signal ends it: an interrupted run leaves the
/// destination as it was.
pub struct Staging {
    dir: PathBuf,
    dest: PathBuf,
    committed: bool,
}

impl Staging {
    /// A new empty staging folder for `dest`: `.<name>.staging.<pid>` in
    /// `dest`'s parent (the same file system, so the moves are renames;
    /// the same depth, so the report's relative links outside it resolve
    /// the same).
    pub fn new(dest: &Path) -> Result<Staging> {
        let parent = match dest.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = dest
            .file_name()
            .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
        let dir = parent.join(format!(".{name}.staging.{}", std::process::id()));
        remove(&dir);
        remove_on_signal(&dir);
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("creating the staging folder {}", dir.display()))?;
        Ok(Staging {
            dir,
            dest: dest.to_path_buf(),
            committed: false,
        })
    }

    /// Where the report is written until [`Staging::commit`].
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Moves every file of the staging folder to the same place under the
    /// destination (replacing a file there; files of the destination the
    /// run did not write stay), then removes the staging folder. Returns
    /// the [`Hold`] still held, so that the caller may finish related
    /// writes (the README) before a signal can end the process.
    pub fn commit(mut self) -> Result<Hold> {
        let held = hold();
        move_tree(&self.dir, &self.dest)?;
        remove(&self.dir);
        forget(&self.dir);
        self.committed = true;
        Ok(held)
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            remove(&self.dir);
            forget(&self.dir);
        }
    }
}

/// Moves the files under `from` to the same places under `to`.
fn move_tree(from: &Path, to: &Path) -> Result<()> {
    std::fs::create_dir_all(to).with_context(|| format!("creating {}", to.display()))?;
    for entry in std::fs::read_dir(from).with_context(|| format!("reading {}", from.display()))? {
        let entry = entry?;
        let target = to.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            move_tree(&entry.path(), &target)?;
        } else {
            std::fs::rename(entry.path(), &target)
                .with_context(|| format!("moving the report into {}", target.display()))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_committed_staging_folder_lands_in_place_and_disappears() {
        let root = tempfile::tempdir().unwrap();
        let dest = root.path().join("report");
        std::fs::create_dir_all(dest.join("kept")).unwrap();
        std::fs::write(dest.join("kept/old.md"), "old").unwrap();
        std::fs::write(dest.join("replaced.md"), "old").unwrap();
        let staging = Staging::new(&dest).unwrap();
        let staged = staging.dir().to_path_buf();
        std::fs::create_dir_all(staged.join("cases")).unwrap();
        std::fs::write(staged.join("replaced.md"), "new").unwrap();
        std::fs::write(staged.join("cases/a.md"), "a").unwrap();
        drop(staging.commit().unwrap());
        assert!(!staged.exists());
        let read = |p: &str| std::fs::read_to_string(dest.join(p)).unwrap();
        assert_eq!(read("replaced.md"), "new");
        assert_eq!(read("cases/a.md"), "a");
        assert_eq!(read("kept/old.md"), "old");
    }

    #[test]
    fn a_dropped_staging_folder_leaves_the_destination_untouched() {
        let root = tempfile::tempdir().unwrap();
        let dest = root.path().join("report");
        let staging = Staging::new(&dest).unwrap();
        std::fs::write(staging.dir().join("half.md"), "half").unwrap();
        drop(staging);
        assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 0);
    }

    #[test]
    fn holds_nest_within_a_thread() {
        let a = hold();
        let b = hold();
        drop(b);
        drop(a);
        drop(hold());
    }
}
