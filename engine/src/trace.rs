//! The record of a run: time, every body's state and the total energy at
//! each sample, the events located, and the work done.

use crate::body::BodyState;
use crate::events::EventRecord;
use crate::integrators::Stats;

/// One sample of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// Every body's state, indexed by body id.
    pub states: Vec<BodyState>,
    /// Total energy: kinetic plus the potentials of the forces that have
    /// one (J).
    pub energy: f64,
}

/// A whole run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Trace {
    /// Samples in time order, starting with the initial state.
    pub samples: Vec<Sample>,
    /// Events in time order.
    pub events: Vec<EventRecord>,
    /// Work done by the integrator.
    pub stats: Stats,
}

impl Trace {
    /// The first event of that name, if it happened.
    pub fn event(&self, name: &str) -> Option<&EventRecord> {
        self.events.iter().find(|e| e.name == name)
    }

    /// The last sample.
    pub fn last(&self) -> Option<&Sample> {
        self.samples.last()
    }
}
