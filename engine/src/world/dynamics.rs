//! The model a world runs, held as an enum (so that a world stays `Clone`
//! and serializable) and seen by the world as the trait
//! [`ContactModelStep`] of `contact_model.rs`: [`Dynamics::step_model`] is
//! the one place the variants are told apart for the world's calls. Kept
//! apart from `contact_model.rs` so that the models, which implement the
//! trait, and this enum, which holds them, import each other in one
//! direction only.

use crate::contact_model::ContactModelStep;
use crate::exact::ExactModel;
use crate::soft_step::SoftStep;
use std::ops::{Deref, DerefMut};

/// The model a world runs, with its state (an enum rather than a boxed
/// trait object so that a world stays `Clone` and serializable).
#[derive(Debug, Clone)]
pub(crate) enum Dynamics {
    /// The exact model; also a world without contacts.
    Exact(Box<ExactModel>),
    /// The soft step.
    SoftStep(Box<SoftStep>),
}

impl Dynamics {
    /// The model as the world sees it: the one place the variants are
    /// told apart for the world's calls.
    pub(crate) fn step_model(&self) -> &(dyn ContactModelStep + 'static) {
        match self {
            Dynamics::Exact(m) => m.as_ref(),
            Dynamics::SoftStep(s) => s.as_ref(),
        }
    }

    /// [`Dynamics::step_model`], mutable.
    pub(crate) fn step_model_mut(&mut self) -> &mut (dyn ContactModelStep + 'static) {
        match self {
            Dynamics::Exact(m) => m.as_mut(),
            Dynamics::SoftStep(s) => s.as_mut(),
        }
    }
}

impl Deref for Dynamics {
    type Target = dyn ContactModelStep;

    fn deref(&self) -> &Self::Target {
        self.step_model()
    }
}

impl DerefMut for Dynamics {
    fn deref_mut(&mut self) -> &mut Self::Target {
        self.step_model_mut()
    }
}
