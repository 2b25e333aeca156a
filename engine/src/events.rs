//! Events located inside a step (landing `y = 0`, apex `vy = 0`), so that
//! times, ranges and heights are not quantized to the step (docs/cases.md case
//! II: "Event times are found by root-finding on the step").
//!
//! After each accepted step from `(t_a, y_a)` to `(t_b, y_b)`, every event
//! function `g = quantity − level` is compared at both ends. On a crossing,
//! the root `s*` of `g(Φ_s(y_a))` over `s ∈ (0, h]` is found by
//! [`crate::root_finding::illinois`], where `Φ_s` is one step of the same
//! method of size `s`: the event lies on the method's own solution.

use crate::body::{BodyId, BodyState};

/// A scalar read off one body's state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Quantity {
    /// x of the centre of mass (m).
    X,
    /// y of the centre of mass (m).
    Y,
    /// Orientation (rad).
    Angle,
    /// x velocity (m/s).
    Vx,
    /// y velocity (m/s).
    Vy,
    /// Angular velocity (rad/s).
    AngularVelocity,
}

impl Quantity {
    /// The value in `state`.
    pub fn of(&self, state: &BodyState) -> f64 {
        match self {
            Quantity::X => state.position.x,
            Quantity::Y => state.position.y,
            Quantity::Angle => state.angle,
            Quantity::Vx => state.velocity.x,
            Quantity::Vy => state.velocity.y,
            Quantity::AngularVelocity => state.angular_velocity,
        }
    }
}

/// Which sign changes count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Crossing {
    /// From below the level to at-or-above it.
    Rising,
    /// From above the level to at-or-below it.
    Falling,
    /// Either way.
    Any,
}

impl Crossing {
    /// Whether `g` going from `ga` to `gb` is such a crossing.
    pub fn detects(&self, ga: f64, gb: f64) -> bool {
        let rising = ga < 0.0 && gb >= 0.0;
        let falling = ga > 0.0 && gb <= 0.0;
        match self {
            Crossing::Rising => rising,
            Crossing::Falling => falling,
            Crossing::Any => rising || falling,
        }
    }
}

/// An event to locate.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EventSpec {
    /// Name used in the records (e.g. `"landing"`).
    pub name: String,
    /// The body watched.
    pub body: BodyId,
    /// The quantity watched.
    pub quantity: Quantity,
    /// The level it crosses, in the quantity's unit.
    pub level: f64,
    /// Which crossings count.
    pub crossing: Crossing,
    /// Whether the simulation stops at this event.
    pub terminal: bool,
}

impl EventSpec {
    /// The body's centre comes down through `y = level` (m); stops the run.
    pub fn landing(body: BodyId, level: f64) -> Self {
        Self {
            name: "landing".into(),
            body,
            quantity: Quantity::Y,
            level,
            crossing: Crossing::Falling,
            terminal: true,
        }
    }

    /// The top of the trajectory: `vy` goes from positive to ≤ 0.
    pub fn apex(body: BodyId) -> Self {
        Self {
            name: "apex".into(),
            body,
            quantity: Quantity::Vy,
            level: 0.0,
            crossing: Crossing::Falling,
            terminal: false,
        }
    }

    /// `g = quantity − level` for this event.
    pub fn value(&self, states: &[BodyState]) -> f64 {
        self.quantity.of(&states[self.body]) - self.level
    }
}

/// An event found during a run.
#[derive(Debug, Clone, PartialEq)]
pub struct EventRecord {
    /// The event's name.
    pub name: String,
    /// When it happened (s).
    pub t: f64,
    /// Every body's state at that time.
    pub states: Vec<BodyState>,
}
