//! Box2D's log, collapsed: Box2D prints some messages once per step (its
//! broad phase's "Pair buffer capacity of N exceeded, too many overlaps"
//! on a pile of coincident boxes, thousands of lines in one run). Routed
//! through boxdd's process-global log hook, each distinct message is
//! printed once, on stderr, and counted; [`repeated`] gives the counts so
//! that a caller can say how often each came.
//!
//! The hook is installed with Box2D's foundation, the first time a world
//! is built ([`config`]), and stays for the process (boxdd freezes the
//! foundation's configuration at its first initialisation).

use boxdd::{FoundationConfig, FoundationLogHook};
use std::sync::{Arc, Mutex, OnceLock};

/// Each distinct message with the number of times Box2D logged it.
static SEEN: Mutex<Vec<(String, u64)>> = Mutex::new(Vec::new());

fn log_line(message: &str) {
    let message = message.trim_end().to_owned();
    let mut seen = SEEN.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(entry) = seen.iter_mut().find(|(m, _)| *m == message) {
        entry.1 += 1;
        return;
    }
    eprintln!("Box2D: {message} (repeats of this message are counted, not printed)");
    seen.push((message, 1));
}

/// The foundation configuration of every Box2D world of this crate: one
/// unit per metre, Box2D's default, and the collapsing log hook (the same
/// `Arc` every time, as boxdd requires of repeated initialisations).
pub(crate) fn config() -> FoundationConfig {
    static HOOK: OnceLock<Arc<FoundationLogHook>> = OnceLock::new();
    let hook = HOOK.get_or_init(|| Arc::new(log_line)).clone();
    FoundationConfig::default().with_log_hook(hook)
}

/// Every message Box2D logged more than once, with its count, in the order
/// first seen.
pub fn repeated() -> Vec<(String, u64)> {
    let seen = SEEN.lock().unwrap_or_else(|e| e.into_inner());
    seen.iter().filter(|(_, n)| *n > 1).cloned().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_repeated_message_is_counted() {
        log_line("test message of the log module\n");
        log_line("test message of the log module");
        let counts = repeated();
        assert!(
            counts
                .iter()
                .any(|(m, n)| m == "test message of the log module" && *n == 2),
            "{counts:?}"
        );
    }
}
