//! The worker pool of a run: independent jobs (a case, a piece of the
//! studies, a scene of the short benchmark) on one worker thread per core,
//! the longest expected first, so that the workers end together.
//!
//! Scheduling: the jobs are started in decreasing order of their expected
//! cost (longest processing time first, ties in the order given), each by
//! the first worker that is free. A job whose cost is unknown counts as
//! short. The order changes only when a job starts, never what it computes:
//! a job shares no state with another, so its result is the bits of a
//! serial run; the results are returned in the order the jobs were given.
//!
//! Threads: the workers are plain threads, not rayon's global pool, which
//! has one thread ([`references::serial_rayon`]: rapier2d, built with
//! `parallel`, then steps serially and gives the bits of a serial run).
//! Each job runs inside a one-thread rayon pool of its own, so whatever it
//! runs through rayon stays serial and waits on no other job.
//!
//! Timing: a job that times code (a sweep point, a benchmark scene, a
//! case's ms per step) is timed on its own worker while the other workers
//! run other jobs: on one core of its own when there are as many workers
//! as cores, sharing the memory system with the others.

use anyhow::{Context, Result};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// One job of a run.
pub struct Job<'a, T> {
    /// What it is, for the log (`case pendulum`, `sweep spring`).
    pub label: String,
    /// Its expected wall time on one quiet core (s): only the order in
    /// which jobs start depends on it.
    pub cost: f64,
    /// The work.
    pub run: Box<dyn FnOnce() -> Result<T> + Send + 'a>,
}

impl<'a, T> Job<'a, T> {
    /// A job `label` of expected cost `cost` (s) doing `run`.
    pub fn new(
        label: impl Into<String>,
        cost: f64,
        run: impl FnOnce() -> Result<T> + Send + 'a,
    ) -> Self {
        Self {
            label: label.into(),
            cost,
            run: Box::new(run),
        }
    }

    /// The same job with its result mapped by `f` (to gather jobs of
    /// different kinds into one run).
    pub fn map<U>(self, f: impl FnOnce(T) -> U + Send + 'a) -> Job<'a, U>
    where
        T: 'a,
    {
        let run = self.run;
        Job {
            label: self.label,
            cost: self.cost,
            run: Box::new(move || run().map(f)),
        }
    }
}

/// What a job returned, and how long it took.
#[derive(Debug)]
pub struct Done<T> {
    /// Its result (the job's label added to an error).
    pub result: Result<T>,
    /// Its wall time (s).
    pub seconds: f64,
}

/// CPU time the calling thread has used so far (s); `None` where the
/// platform does not say. On a machine shared with other work a job's wall
/// time includes the time it waited for a core; its CPU time does not, and
/// is what the log prints beside it to plan the order of the jobs.
fn thread_cpu() -> Option<f64> {
    #[cfg(unix)]
    {
        let mut t = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `t` is a valid timespec for the call to fill.
        let ok = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) } == 0;
        ok.then_some(t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64)
    }
    #[cfg(not(unix))]
    {
        None
    }
}

/// The expected cost (s) of the job `label` from a table of measured
/// costs, `default` for a job the table does not list.
pub fn estimated_cost(table: &[(&str, f64)], label: &str, default: f64) -> f64 {
    table
        .iter()
        .find(|(l, _)| *l == label)
        .map_or(default, |(_, s)| *s)
}

/// The order in which `costs` start: decreasing cost, ties in the order
/// given (longest processing time first).
pub fn start_order(costs: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..costs.len()).collect();
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]));
    order
}

/// How many workers a run of `jobs` jobs uses: one per core, no more than
/// there are jobs.
pub fn workers(jobs: usize) -> usize {
    std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(jobs.max(1))
}

/// Runs `jobs` on [`workers`] worker threads, longest expected first;
/// `done` is called after each job (progress). Returns every job's result,
/// in the order of `jobs`.
pub fn run<'a, T: Send>(jobs: Vec<Job<'a, T>>, done: impl Fn(&str) + Sync) -> Vec<Done<T>> {
    let costs: Vec<f64> = jobs.iter().map(|j| j.cost).collect();
    let order = start_order(&costs);
    let slots: Vec<Mutex<Option<Job<'a, T>>>> =
        jobs.into_iter().map(|j| Mutex::new(Some(j))).collect();
    let results: Vec<Mutex<Option<Done<T>>>> = slots.iter().map(|_| Mutex::new(None)).collect();
    let next = AtomicUsize::new(0);
    let worker = || {
        loop {
            let k = next.fetch_add(1, Ordering::Relaxed);
            let Some(&i) = order.get(k) else { break };
            let job = slots[i]
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .take()
                .expect("each job is taken once");
            let label = job.label.clone();
            let (finished, cpu) = run_one(job);
            match cpu {
                Some(cpu) => {
                    tracing::info!("{label} in {:.2} s ({cpu:.2} s of CPU)", finished.seconds)
                }
                None => tracing::info!("{label} in {:.2} s", finished.seconds),
            }
            done(&label);
            *results[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(finished);
        }
    };
    std::thread::scope(|scope| {
        for _ in 0..workers(slots.len()) {
            scope.spawn(worker);
        }
    });
    results
        .into_iter()
        .map(|slot| {
            slot.into_inner()
                .unwrap_or_else(|e| e.into_inner())
                .unwrap_or_else(|| Done {
                    result: Err(anyhow::anyhow!("a job did not run")),
                    seconds: 0.0,
                })
        })
        .collect()
}

/// Runs one job inside a one-thread rayon pool, timing it (wall time,
/// and the CPU time of the thread it ran on); a panic becomes the job's
/// error.
fn run_one<T: Send>(job: Job<'_, T>) -> (Done<T>, Option<f64>) {
    let started = Instant::now();
    let label = job.label;
    let run = job.run;
    let mut cpu = None;
    let result = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .context("starting a one-thread pool for a job")
        .and_then(|pool| {
            let timed = || {
                let before = thread_cpu();
                let result = run();
                (result, before.zip(thread_cpu()).map(|(a, b)| b - a))
            };
            // A panic is the job's error, not the end of the run.
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| pool.install(timed)))
                .map(|(result, used)| {
                    cpu = used;
                    result
                })
                .unwrap_or_else(|panic| {
                    let why = panic
                        .downcast_ref::<&str>()
                        .map(|s| s.to_string())
                        .or_else(|| panic.downcast_ref::<String>().cloned())
                        .unwrap_or_default();
                    Err(anyhow::anyhow!("panicked: {why}"))
                })
        })
        .with_context(|| label.clone());
    let done = Done {
        result,
        seconds: started.elapsed().as_secs_f64(),
    };
    (done, cpu)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_longest_start_first_and_ties_keep_their_order() {
        assert_eq!(start_order(&[1.0, 5.0, 0.2, 5.0, 3.0]), vec![1, 3, 4, 0, 2]);
        assert_eq!(start_order(&[]), Vec::<usize>::new());
    }

    #[test]
    fn results_come_back_in_the_order_given_with_the_errors_labelled() {
        let jobs: Vec<Job<u32>> = (0..7u32)
            .map(|i| {
                Job::new(format!("job {i}"), f64::from(i % 3), move || {
                    anyhow::ensure!(i != 4, "four refused");
                    Ok(i * 10)
                })
            })
            .collect();
        let done = run(jobs, |_| {});
        for (i, d) in done.iter().enumerate() {
            match &d.result {
                Ok(v) => assert_eq!(*v, i as u32 * 10),
                Err(e) => {
                    assert_eq!(i, 4);
                    assert_eq!(format!("{e:#}"), "job 4: four refused");
                }
            }
        }
    }
}
