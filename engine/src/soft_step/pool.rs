//! A persistent pool of worker threads for the soft step's parallel stages
//! (after Box2D v3's solver: workers that stay awake between the stages of
//! a step and meet at spinning barriers, rather than a task per stage).
//!
//! [`Pool::run`] hands one job to every thread, the caller's included as
//! thread 0, and returns when all have finished it; inside a job,
//! [`Worker::sync`] is a barrier of all the threads (the step between two
//! colours of the solver). Nothing is allocated per job: the job is a
//! borrowed closure, the barrier two counters. Waiting threads spin a
//! while, then yield, then (workers between jobs only) park until the next
//! job wakes them, so an idle pool costs no CPU.
//!
//! Determinism is the jobs' business: each thread writes data no other
//! thread reads or writes in the same phase, and the split of the work
//! depends only on the thread count and the data ([`Worker::share`]).

use std::cell::UnsafeCell;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::thread::{self, JoinHandle};

/// A job: called once per thread with that thread's [`Worker`].
type Job<'a> = dyn Fn(&Worker<'_>) + Sync + 'a;

/// Spins before a waiting thread starts yielding (about 10–50 µs).
const SPINS: u32 = 2000;
/// Yields before an idle worker parks.
const YIELDS: u32 = 2000;

/// What the threads share.
struct Shared {
    threads: usize,
    /// Bumped by each new job (and by the drop, with `quit`).
    epoch: AtomicUsize,
    /// The current job, set before `epoch` is bumped and cleared after
    /// every worker reported done.
    job: UnsafeCell<Option<*const Job<'static>>>,
    /// Workers that finished the current job.
    done: AtomicUsize,
    /// Whether a worker's job panicked.
    panicked: AtomicBool,
    quit: AtomicBool,
    /// Per worker, whether it is parked (or about to park).
    parked: Vec<AtomicBool>,
    /// The barrier: arrivals of this round and the round number.
    arrived: AtomicUsize,
    round: AtomicUsize,
}

// SAFETY: `job` is written only by the thread calling `Pool::run` while no
// worker reads it (before the epoch is bumped, after all reported done);
// the job it points to is `Sync`.
unsafe impl Sync for Shared {}
// SAFETY: as above; the pointer is only dereferenced during `Pool::run`.
unsafe impl Send for Shared {}

/// One thread's view of a job: its index, the thread count and the
/// barrier.
pub(crate) struct Worker<'a> {
    /// 0 for the calling thread, 1.. for the pool's.
    pub index: usize,
    shared: &'a Shared,
}

impl Worker<'_> {
    /// The number of threads running the job.
    #[cfg(test)]
    pub fn threads(&self) -> usize {
        self.shared.threads
    }

    /// This thread's share of `0..n`: contiguous, in thread order, sizes
    /// differing by at most one (a function of `n` and the thread count
    /// only).
    pub fn share(&self, n: usize) -> std::ops::Range<usize> {
        let t = self.shared.threads;
        (self.index * n / t)..((self.index + 1) * n / t)
    }

    /// Waits until every thread of the job has reached this call (with
    /// acquire–release ordering: what any thread wrote before it is seen
    /// by all after it).
    pub fn sync(&self) {
        let s = self.shared;
        if s.threads == 1 {
            return;
        }
        let round = s.round.load(Ordering::Acquire);
        if s.arrived.fetch_add(1, Ordering::AcqRel) + 1 == s.threads {
            s.arrived.store(0, Ordering::Relaxed);
            s.round.fetch_add(1, Ordering::AcqRel);
            return;
        }
        let mut waited = 0u32;
        while s.round.load(Ordering::Acquire) == round {
            backoff(&mut waited);
        }
    }
}

/// One round of waiting: spin, then yield.
#[inline]
fn backoff(waited: &mut u32) {
    if *waited < SPINS {
        std::hint::spin_loop();
    } else {
        thread::yield_now();
    }
    *waited = waited.saturating_add(1);
}

/// Threads for the soft step's parallel stages (`threads − 1` workers; the
/// caller is the last). Cloning gives an empty cell: a clone makes its own
/// pool when it first needs one.
pub(crate) struct Pool {
    shared: Arc<Shared>,
    workers: Vec<JoinHandle<()>>,
}

impl Pool {
    /// A pool of `threads` (≥ 1) threads: starts `threads − 1` workers.
    pub(crate) fn new(threads: usize) -> Self {
        let threads = threads.max(1);
        let shared = Arc::new(Shared {
            threads,
            epoch: AtomicUsize::new(0),
            job: UnsafeCell::new(None),
            done: AtomicUsize::new(0),
            panicked: AtomicBool::new(false),
            quit: AtomicBool::new(false),
            parked: (0..threads).map(|_| AtomicBool::new(false)).collect(),
            arrived: AtomicUsize::new(0),
            round: AtomicUsize::new(0),
        });
        let workers = (1..threads)
            .map(|index| {
                let shared = Arc::clone(&shared);
                thread::Builder::new()
                    .name(format!("etalon2d-{index}"))
                    .spawn(move || work(&shared, index))
                    .expect("the system refused a worker thread")
            })
            .collect();
        Self { shared, workers }
    }

    /// The number of threads (workers and the caller).
    pub(crate) fn threads(&self) -> usize {
        self.shared.threads
    }

    /// Runs `job` on every thread, the caller as thread 0; returns when
    /// all have finished. A panic in any thread's job is raised here once
    /// all have stopped.
    pub(crate) fn run(&self, job: &Job<'_>) {
        let s = &*self.shared;
        if s.threads == 1 {
            job(&Worker {
                index: 0,
                shared: s,
            });
            return;
        }
        // SAFETY (lifetime erased): the pointer is cleared below, after
        // every worker has reported done, before `job`'s borrow ends (also
        // when thread 0's part panics: the guard waits first).
        let erased: *const Job<'static> =
            unsafe { std::mem::transmute::<*const Job<'_>, *const Job<'static>>(job) };
        // SAFETY: no worker reads `job` now (all reported the last job done).
        unsafe { *s.job.get() = Some(erased) };
        s.done.store(0, Ordering::Relaxed);
        s.epoch.fetch_add(1, Ordering::SeqCst);
        for (k, handle) in self.workers.iter().enumerate() {
            if s.parked[k + 1].load(Ordering::SeqCst) {
                handle.thread().unpark();
            }
        }
        /// Waits for the workers, even while unwinding.
        struct Wait<'a>(&'a Shared);
        impl Drop for Wait<'_> {
            fn drop(&mut self) {
                let s = self.0;
                let mut waited = 0u32;
                while s.done.load(Ordering::Acquire) < s.threads - 1 {
                    backoff(&mut waited);
                }
                // SAFETY: every worker is done with the job.
                unsafe { *s.job.get() = None };
            }
        }
        let wait = Wait(s);
        job(&Worker {
            index: 0,
            shared: s,
        });
        drop(wait);
        if s.panicked.swap(false, Ordering::AcqRel) {
            panic!("a soft-step worker thread panicked");
        }
    }
}

/// A worker's loop: wait for a job, run it, report done.
fn work(s: &Shared, index: usize) {
    let mut seen = 0;
    loop {
        let mut waited = 0u32;
        loop {
            let epoch = s.epoch.load(Ordering::Acquire);
            if s.quit.load(Ordering::Acquire) {
                return;
            }
            if epoch != seen {
                seen = epoch;
                break;
            }
            if waited < SPINS + YIELDS {
                backoff(&mut waited);
            } else {
                s.parked[index].store(true, Ordering::SeqCst);
                if s.epoch.load(Ordering::SeqCst) == seen && !s.quit.load(Ordering::SeqCst) {
                    thread::park();
                }
                s.parked[index].store(false, Ordering::SeqCst);
            }
        }
        // SAFETY: set before the epoch was bumped (acquired above); kept
        // until this worker reports done.
        let job = unsafe { (*s.job.get()).expect("a job with the new epoch") };
        // SAFETY: the job outlives this call (`Pool::run` waits for it).
        let job = unsafe { &*job };
        let ran = catch_unwind(AssertUnwindSafe(|| job(&Worker { index, shared: s })));
        if ran.is_err() {
            s.panicked.store(true, Ordering::Release);
        }
        s.done.fetch_add(1, Ordering::AcqRel);
    }
}

impl Drop for Pool {
    fn drop(&mut self) {
        self.shared.quit.store(true, Ordering::SeqCst);
        self.shared.epoch.fetch_add(1, Ordering::SeqCst);
        for handle in &self.workers {
            handle.thread().unpark();
        }
        for handle in self.workers.drain(..) {
            let _ = handle.join();
        }
    }
}

impl std::fmt::Debug for Pool {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Pool({} threads)", self.threads())
    }
}

/// The soft step's pool, made on first use for the settings' thread
/// count (none for one thread); a clone starts empty.
#[derive(Debug, Default)]
pub(crate) struct PoolCell(Option<Arc<Pool>>);

impl Clone for PoolCell {
    fn clone(&self) -> Self {
        Self(None)
    }
}

impl PoolCell {
    /// The pool for `threads` (> 1) threads, made (or remade, when the
    /// count changed) now; `None` for one thread (the pool, if any, is
    /// let go).
    pub(crate) fn get(&mut self, threads: usize) -> Option<Arc<Pool>> {
        if threads <= 1 {
            self.0 = None;
            return None;
        }
        if self.0.as_ref().is_none_or(|p| p.threads() != threads) {
            self.0 = Some(Arc::new(Pool::new(threads)));
        }
        self.0.clone()
    }
}

/// A slice that the threads of a job share, each reading and writing
/// elements no other thread writes in the same phase (between two
/// [`Worker::sync`]). Copy; borrows the slice for `'a`.
#[derive(Clone, Copy)]
pub(crate) struct SharedSlice<'a, T> {
    ptr: *mut T,
    len: usize,
    _slice: std::marker::PhantomData<&'a mut [T]>,
}

// SAFETY: the callers' discipline above (disjoint writes per phase).
unsafe impl<T: Send> Sync for SharedSlice<'_, T> {}
// SAFETY: as above.
unsafe impl<T: Send> Send for SharedSlice<'_, T> {}

impl<'a, T> SharedSlice<'a, T> {
    /// Shares `slice` for the job.
    pub(crate) fn new(slice: &'a mut [T]) -> Self {
        Self {
            ptr: slice.as_mut_ptr(),
            len: slice.len(),
            _slice: std::marker::PhantomData,
        }
    }

    /// The number of elements.
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Elements `range`, for this thread alone.
    ///
    /// # Safety
    /// No other thread reads or writes them until the next barrier.
    #[allow(clippy::mut_from_ref)]
    pub(crate) unsafe fn slice(&self, range: std::ops::Range<usize>) -> &'a mut [T] {
        assert!(range.start <= range.end && range.end <= self.len);
        // SAFETY: in bounds (checked); exclusive by the caller's promise.
        unsafe { std::slice::from_raw_parts_mut(self.ptr.add(range.start), range.len()) }
    }

    /// Element `i`, read.
    ///
    /// # Safety
    /// No other thread writes it until the next barrier.
    pub(crate) unsafe fn get(&self, i: usize) -> &'a T {
        assert!(i < self.len);
        // SAFETY: in bounds (checked); not written meanwhile by the
        // caller's promise.
        unsafe { &*self.ptr.add(i) }
    }

    /// Element `i`, for this thread alone.
    ///
    /// # Safety
    /// No other thread reads or writes it until the next barrier.
    #[allow(clippy::mut_from_ref)]
    pub(crate) unsafe fn get_mut(&self, i: usize) -> &'a mut T {
        assert!(i < self.len);
        // SAFETY: in bounds (checked); exclusive by the caller's promise.
        unsafe { &mut *self.ptr.add(i) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_thread_runs_each_job_and_the_barrier_orders_phases() {
        for threads in 1..=4 {
            let pool = Pool::new(threads);
            let mut data = vec![0usize; 1000];
            for round in 0..50 {
                let shared = SharedSlice::new(&mut data);
                pool.run(&|w: &Worker<'_>| {
                    // Phase 1: each thread its share; phase 2: the
                    // neighbour's share, which phase 1 wrote.
                    let mine = w.share(shared.len());
                    // SAFETY: shares are disjoint.
                    for x in unsafe { shared.slice(mine) } {
                        *x += round;
                    }
                    w.sync();
                    let next = Worker {
                        index: (w.index + 1) % w.threads(),
                        shared: w.shared,
                    }
                    .share(shared.len());
                    for i in next {
                        // SAFETY: nobody writes in this phase.
                        assert_eq!(unsafe { *shared.get(i) }, (0..=round).sum::<usize>());
                    }
                    w.sync();
                });
            }
        }
    }
}
