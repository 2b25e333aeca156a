//! Progress bars and logging for the harness binary.
//!
//! - [`bar`]: an [`indicatif`] bar on stderr for long runs and sweeps,
//!   *hidden* when stderr is not a terminal (CI logs, pipes, tests), so it
//!   never pollutes captured output. Tick it in chunks ([`Ticker`]) rather
//!   than per step: a step of a small scene costs well under a microsecond.
//! - [`Ticker::for_loop`]: the bar of a run whose length is known in
//!   steps, shown only once the run has lasted [`SHOW_AFTER`] (a quick run
//!   prints nothing), then redrawn every [`REDRAW`] even while one step
//!   takes long (its elapsed time keeps counting), so that a slow run never
//!   looks hung;
//! - [`Budget`]: a wall-time limit (`simulate --budget`), checked between
//!   steps;
//! - [`init_tracing`]: logs through [`tracing`] to stderr, filtered by the
//!   `RUST_LOG` environment variable (`tracing_subscriber::EnvFilter`
//!   syntax, e.g. `RUST_LOG=harness=debug`), default `warn`.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::mpsc;
use std::time::{Duration, Instant};
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
    styled(len, message, ProgressDrawTarget::stderr())
}

/// A bar of `len` units labelled `message`, drawn to `target`.
fn styled(len: u64, message: impl Into<String>, target: ProgressDrawTarget) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(len), target);
    let style = ProgressStyle::with_template(
        "{msg} [{bar:32}] {human_pos}/{human_len} ({percent}%) {elapsed} elapsed, ETA {eta}",
    )
    .map(|s| s.progress_chars("=> "))
    .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    bar.set_message(message.into());
    bar
}

/// A run's bar appears once the run has lasted this long.
pub const SHOW_AFTER: Duration = Duration::from_secs(1);
/// A shown bar is redrawn this often, by indicatif's own thread, whether
/// or not a step ended.
pub const REDRAW: Duration = Duration::from_millis(250);

/// Counts units of work and advances a [`ProgressBar`] every `chunk` of
/// them, so that a tight loop pays one branch per unit.
#[derive(Debug)]
pub struct Ticker {
    bar: ProgressBar,
    pending: u64,
    chunk: u64,
    /// Dropped when the loop ends: tells the thread that would reveal the
    /// bar that it need not.
    reveal: Option<mpsc::Sender<()>>,
}

impl Ticker {
    /// Wraps `bar`, advancing it every `chunk` (≥ 1) units.
    pub fn new(bar: ProgressBar, chunk: u64) -> Self {
        Self {
            bar,
            pending: 0,
            chunk: chunk.max(1),
            reveal: None,
        }
    }

    /// A bar of `len` units for a loop, advanced about 1000 times over the
    /// run. On a terminal it appears after [`SHOW_AFTER`] (a thread waits
    /// that long, unless the loop ends first) and is then redrawn every
    /// [`REDRAW`]; elsewhere it is hidden and costs nothing.
    pub fn for_loop(len: u64, message: impl Into<String>) -> Self {
        let chunk = (len / 1000).max(1);
        if !enabled() {
            return Self::new(ProgressBar::hidden(), chunk);
        }
        // Hidden from its creation: nothing is drawn before it is revealed.
        let bar = styled(len, message, ProgressDrawTarget::hidden());
        let shown = bar.clone();
        let (done, wait) = mpsc::channel::<()>();
        std::thread::spawn(move || {
            // Nothing is ever sent: the loop ends by dropping its sender.
            if let Err(mpsc::RecvTimeoutError::Timeout) = wait.recv_timeout(SHOW_AFTER) {
                shown.set_draw_target(ProgressDrawTarget::stderr());
                shown.enable_steady_tick(REDRAW);
            }
        });
        Self {
            reveal: Some(done),
            ..Self::new(bar, chunk)
        }
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
    pub fn finish(mut self) {
        self.reveal.take();
        self.bar.inc(self.pending);
        self.bar.finish_and_clear();
    }
}

/// A wall-time budget for a run (`simulate --budget SECONDS`), checked
/// between steps: a step under way finishes first.
#[derive(Debug, Clone, Copy)]
pub struct Budget {
    started: Instant,
    limit: Option<Duration>,
}

impl Budget {
    /// A budget of `seconds` from now (none: unlimited). The value is
    /// checked positive and finite by the command line.
    pub fn new(seconds: Option<f64>) -> Self {
        Self {
            started: Instant::now(),
            limit: seconds.and_then(|s| Duration::try_from_secs_f64(s).ok()),
        }
    }

    /// Whether the budget is spent. Reads the clock only when there is a
    /// budget.
    #[inline]
    pub fn exhausted(&self) -> bool {
        self.limit.is_some_and(|l| self.started.elapsed() >= l)
    }

    /// The limit in seconds, if any.
    pub fn seconds(&self) -> Option<f64> {
        self.limit.map(|l| l.as_secs_f64())
    }

    /// Says on stderr that the budget stopped the run after `step` of
    /// `steps` steps, at `t` (s).
    pub fn say_stopped(&self, t: f64, step: u64, steps: u64) {
        eprintln!(
            "note: stopped by --budget {} s after {step} of {steps} steps, at t = {} s; the outputs cover the part that ran",
            self.seconds().unwrap_or(0.0),
            engine::error::readable(t)
        );
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
    fn a_budget_of_nothing_is_spent_and_no_budget_never_is() {
        assert!(Budget::new(Some(1e-9)).exhausted());
        assert!(!Budget::new(None).exhausted());
        assert!(!Budget::new(Some(3600.0)).exhausted());
    }

    #[test]
    fn a_loop_ticker_off_a_terminal_is_hidden_and_counts() {
        let mut t = Ticker::for_loop(10, "test");
        for _ in 0..10 {
            t.tick();
        }
        assert_eq!(t.bar.position(), 10);
        t.finish();
    }

    #[test]
    fn init_tracing_twice_is_harmless() {
        init_tracing();
        init_tracing();
    }
}
