//! The warning of a run whose shapes overlap while contacts are off: a
//! scene without a `[contact]` table lets shapes pass through each other
//! (the engine models no more than the scene asks for), which a user who
//! drops a box on a ground did not mean. While the run goes, its samples
//! are searched for the first time two shapes overlap ([`OverlapWatch`],
//! which keeps no sample), and `simulate` says which, when, and how to
//! turn contacts on.

use engine::World;
use engine::validation::collision::{Aabb, SweepAndPrune, proximity};
use nalgebra::Isometry2;

/// Most samples searched (spread evenly over the run): enough to catch a
/// fall through a ground, cheap for thousands of bodies.
const SAMPLES_SEARCHED: u64 = 200;

/// Searches the samples of a run, as they come, for the first overlap of
/// two shapes (at least one on a moving body).
pub struct OverlapWatch {
    /// Bodies with a shape.
    shaped: Vec<usize>,
    /// Every `stride`-th sample is searched, the first included.
    stride: u64,
    /// Samples seen so far.
    seen: u64,
    sweep: SweepAndPrune,
    /// The first overlap found: time (s) and the two bodies' indices.
    found: Option<(f64, usize, usize)>,
}

impl OverlapWatch {
    /// The watch of a run of `world` that keeps `samples` samples; `None`
    /// when the world has a contact model or fewer than two shapes, one of
    /// them moving (nothing to warn about).
    pub fn new(world: &World, samples: u64) -> Option<Self> {
        if world.contact_model().is_some() {
            return None;
        }
        let bodies = world.bodies();
        let shaped: Vec<usize> = (0..bodies.len())
            .filter(|&i| bodies[i].shape.is_some())
            .collect();
        if shaped.len() < 2 || shaped.iter().all(|&i| !bodies[i].is_dynamic()) {
            return None;
        }
        Some(Self {
            shaped,
            stride: samples.div_ceil(SAMPLES_SEARCHED).max(1),
            seen: 0,
            sweep: SweepAndPrune::new(),
            found: None,
        })
    }

    /// Takes the world's current state as the next sample.
    pub fn sample(&mut self, world: &World) {
        let searched = self.found.is_none() && self.seen.is_multiple_of(self.stride);
        self.seen += 1;
        if searched {
            self.found = self.overlap(world);
        }
    }

    /// The first overlap found: its time (s) and the two bodies' indices,
    /// the smaller first.
    pub fn first(&self) -> Option<(f64, usize, usize)> {
        self.found
    }

    fn overlap(&mut self, world: &World) -> Option<(f64, usize, usize)> {
        let (bodies, states) = (world.bodies(), world.states());
        let poses: Vec<Isometry2<f64>> = self
            .shaped
            .iter()
            .map(|&i| Isometry2::new(states[i].position, states[i].angle))
            .collect();
        let boxes: Vec<Aabb> = self
            .shaped
            .iter()
            .zip(&poses)
            .map(|(&i, pose)| Aabb::of_shape(bodies[i].shape.as_ref().expect("shaped"), pose))
            .collect();
        for (a, b) in self.sweep.pairs(&boxes) {
            let (ia, ib) = (self.shaped[a], self.shaped[b]);
            if !bodies[ia].is_dynamic() && !bodies[ib].is_dynamic() {
                continue;
            }
            let (sa, sb) = (bodies[ia].shape.as_ref()?, bodies[ib].shape.as_ref()?);
            if proximity(sa, &poses[a], sb, &poses[b]).distance < 0.0 {
                return Some((world.time(), ia.min(ib), ia.max(ib)));
            }
        }
        None
    }
}
