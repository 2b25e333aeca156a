//! Progress bars and logging for the harness binary.
//!
//! - [`bar`]: an [`indicatif`] bar on stderr for long runs and sweeps,
//!   *hidden* when stderr is not a terminal (CI logs, pipes, tests), so it
//!   never pollutes captured output. Tick it in chunks ([`Ticker`]) rather
//!   than per step: a step of a small scene costs well under a microsecond.
//! - [`init_tracing`]: logs through [`tracing`] to stderr, filtered by the
//!   `RUST_LOG` environment variable (`tracing_subscriber::EnvFilter`
//!   syntax, e.g. `RUST_LOG=harness=debug`), default `warn`.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use tracing_subscriber::EnvFilter;

/// The default log filter when `RUST_LOG` is unset or invalid.
pub const DEFAULT_LOG_FILTER: &str = "warn";

/// Installs the global `tracing` subscriber: human-readable lines on stderr,
/// coloured only on a terminal, filtered by `RUST_LOG` (default
/// [`DEFAULT_LOG_FILTER`]). Calling it twice is harmless (the second call
/// does nothing).
pub fn init_tracing() {
    let filter =
        EnvFilter::try_from_default_env().unwrap_or_else(|_| EnvFilter::new(DEFAULT_LOG_FILTER));
    // `try_init` fails only if a subscriber is already set: keep that one.
    let _ = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_ansi(std::io::stderr().is_terminal())
        .with_target(false)
        .try_init();
}

/// Whether progress bars are drawn: stderr is a terminal.
pub fn enabled() -> bool {
    std::io::stderr().is_terminal()
}

/// A progress bar of `len` units labelled `message` on stderr, or a hidden
/// one when stderr is not a terminal. Finish it with
/// [`ProgressBar::finish_and_clear`].
pub fn bar(len: u64, message: impl Into<String>) -> ProgressBar {
    if !enabled() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    let style = ProgressStyle::with_template(
        "{msg} [{bar:32}] {human_pos}/{human_len} ({percent}%) {elapsed} elapsed, ETA {eta}",
    )
    .map(|s| s.progress_chars("=> "))
    .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar.set_message(message.into());
    bar
}

/// Counts units of work and advances a [`ProgressBar`] every `chunk` of
/// them, so that a tight loop pays one branch per unit.
#[derive(Debug)]
pub struct Ticker {
    bar: ProgressBar,
    pending: u64,
    chunk: u64,
}

impl Ticker {
    /// Wraps `bar`, advancing it every `chunk` (≥ 1) units.
    pub fn new(bar: ProgressBar, chunk: u64) -> Self {
        Self {
            bar,
            pending: 0,
            chunk: chunk.max(1),
        }
    }

    /// A bar of `len` units for a loop; hidden (and free) when `len` is
    /// below `min_len` or stderr is not a terminal. Ticks about 1000 times
    /// over the run.
    pub fn for_loop(len: u64, min_len: u64, message: impl Into<String>) -> Self {
        let bar = if len >= min_len {
            bar(len, message)
        } else {
            ProgressBar::hidden()
        };
        Self::new(bar, (len / 1000).max(1))
    }

    /// One more unit done.
    #[inline]
    pub fn tick(&mut self) {
        self.pending += 1;
        if self.pending >= self.chunk {
            self.bar.inc(self.pending);
            self.pending = 0;
        }
    }

    /// Removes the bar from the terminal.
    pub fn finish(self) {
        self.bar.inc(self.pending);
        self.bar.finish_and_clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hidden_ticker_counts_without_drawing() {
        let mut t = Ticker::new(ProgressBar::hidden(), 3);
        for _ in 0..10 {
            t.tick();
        }
        assert_eq!(t.bar.position(), 9);
        assert_eq!(t.pending, 1);
        t.finish();
    }

    #[test]
    fn init_tracing_twice_is_harmless() {
        init_tracing();
        init_tracing();
    }
}
