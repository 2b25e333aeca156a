//! The simulation on its own thread, so that stepping and drawing overlap
//! on two cores: the window sends [`Command`]s down a channel and takes
//! the newest [`Frame`] when it draws. Frames are exchanged, not copied:
//! the thread fills its spare frame, swaps it into the shared slot, and
//! the window swaps its old one back, so no buffer is reallocated.

use super::frame::Frame;
use super::simulation::{Command, Simulation};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, channel};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How often a paused simulation looks at its channel (it wakes at once
/// for a command anyway).
const IDLE_WAIT: Duration = Duration::from_millis(250);
/// How often a running simulation looks at its clock and its channel at
/// least, and publishes at most (twice the window's 60 frames per second).
const TICK: Duration = Duration::from_millis(8);

/// The newest frame and whether the window has taken it yet.
#[derive(Debug, Default)]
struct Slot {
    frame: Frame,
    fresh: bool,
}

/// The simulation's thread.
#[derive(Debug)]
pub struct PhysicsThread {
    commands: Sender<Command>,
    slot: Arc<Mutex<Slot>>,
    handle: Option<JoinHandle<()>>,
}

impl PhysicsThread {
    /// Builds the simulation with `build` on its own thread (a reference
    /// engine of `--compare` may not be sent between threads) and runs it
    /// there; returns `build`'s error if it fails.
    pub fn spawn(
        build: impl FnOnce() -> anyhow::Result<Simulation> + Send + 'static,
    ) -> anyhow::Result<Self> {
        let (commands, inbox) = channel();
        let slot = Arc::new(Mutex::new(Slot::default()));
        let shared = Arc::clone(&slot);
        let (built, outcome) = channel();
        let handle = std::thread::Builder::new()
            .name("view physics".into())
            .spawn(move || match build() {
                Ok(sim) => {
                    let _ = built.send(Ok(()));
                    run(sim, &inbox, &shared);
                }
                Err(e) => {
                    let _ = built.send(Err(e));
                }
            })?;
        match outcome.recv() {
            Ok(Ok(())) => {}
            Ok(Err(e)) => {
                let _ = handle.join();
                return Err(e);
            }
            Err(_) => anyhow::bail!("the view's physics thread ended while building the world"),
        }
        Ok(Self {
            commands,
            slot,
            handle: Some(handle),
        })
    }

    /// Sends a command (ignored once the thread has ended).
    pub fn send(&self, command: Command) {
        let _ = self.commands.send(command);
    }

    /// Swaps the newest frame into `frame` if there is one the window has
    /// not drawn; returns whether it did.
    pub fn take_frame(&self, frame: &mut Frame) -> bool {
        let mut slot = self.slot.lock().unwrap_or_else(PoisonError::into_inner);
        if !slot.fresh {
            return false;
        }
        std::mem::swap(&mut slot.frame, frame);
        slot.fresh = false;
        true
    }

    /// Asks the thread to end and waits for it at most `patience` (a step
    /// of a huge exact-model world may not end soon; the process may then
    /// exit without it).
    pub fn stop(mut self, patience: Duration) {
        self.send(Command::Quit);
        let Some(handle) = self.handle.take() else {
            return;
        };
        let deadline = Instant::now() + patience;
        while !handle.is_finished() && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(5));
        }
        if handle.is_finished() {
            let _ = handle.join();
        }
    }
}

fn run(mut sim: Simulation, inbox: &Receiver<Command>, slot: &Mutex<Slot>) {
    let mut spare = Frame::default();
    let mut last_publish = Instant::now();
    loop {
        let now = Instant::now();
        let wait = match sim.next_step_in(now) {
            Some(step) => step.min(TICK),
            None if sim.is_running() => Duration::ZERO,
            None => IDLE_WAIT,
        };
        match inbox.recv_timeout(wait) {
            Ok(Command::Quit) | Err(RecvTimeoutError::Disconnected) => return,
            Ok(command) => {
                sim.apply(command);
                while let Ok(more) = inbox.try_recv() {
                    if matches!(more, Command::Quit) {
                        return;
                    }
                    sim.apply(more);
                }
            }
            Err(RecvTimeoutError::Timeout) => {}
        }
        sim.advance(Instant::now());
        if sim.is_dirty() && (!sim.is_running() || last_publish.elapsed() >= TICK) {
            sim.publish(&mut spare);
            last_publish = Instant::now();
            let mut shared = slot.lock().unwrap_or_else(PoisonError::into_inner);
            std::mem::swap(&mut shared.frame, &mut spare);
            shared.fresh = true;
        }
    }
}
