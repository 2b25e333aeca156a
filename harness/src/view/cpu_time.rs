//! The CPU time of the calling thread, for the frame-rate measurement
//! (`--frames`): on a machine shared with other work a thread's wall time
//! includes the time it waited for a core; its CPU time does not, and
//! says what the view itself costs.

use std::time::Duration;

/// CPU time the calling thread has used so far; `None` where the platform
/// does not say (the measurement then gives wall times only).
pub fn thread_cpu() -> Option<Duration> {
    #[cfg(unix)]
    {
        let mut t = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `t` is a valid timespec for the call to fill.
        let ok = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) } == 0;
        ok.then(|| Duration::new(t.tv_sec as u64, t.tv_nsec as u32))
    }
    #[cfg(not(unix))]
    {
        None
    }
}
