//! The warning of a run whose shapes overlap while contacts are off: a
//! scene without a `[contact]` table lets shapes pass through each other
//! (the engine models no more than the scene asks for), which a user who
//! drops a box on a ground did not mean. After the run, the recorded
//! samples are searched for the first time two shapes overlap, and
//! `simulate` says which, when, and how to turn contacts on.

use super::Recorded;
use engine::World;
use engine::validation::collision::{Aabb, SweepAndPrune, proximity};
use nalgebra::Isometry2;

/// Most samples searched (spread evenly over the run): enough to catch a
/// fall through a ground, cheap for thousands of bodies.
const SAMPLES_SEARCHED: usize = 200;

/// The first overlap of two shapes (at least one on a moving body) among
/// the recorded samples: its time (s) and the two bodies' indices. `None`
/// when the world has a contact model or nothing overlaps.
pub fn first_overlap(world: &World, rec: &Recorded) -> Option<(f64, usize, usize)> {
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
    let stride = rec.states.len().div_ceil(SAMPLES_SEARCHED).max(1);
    let mut sweep = SweepAndPrune::new();
    for (t, states) in rec.times.iter().zip(&rec.states).step_by(stride) {
        let poses: Vec<Isometry2<f64>> = shaped
            .iter()
            .map(|&i| Isometry2::new(states[i].position, states[i].angle))
            .collect();
        let boxes: Vec<Aabb> = shaped
            .iter()
            .zip(&poses)
            .map(|(&i, pose)| Aabb::of_shape(bodies[i].shape.as_ref().expect("shaped"), pose))
            .collect();
        for (a, b) in sweep.pairs(&boxes) {
            let (ia, ib) = (shaped[a], shaped[b]);
            if !bodies[ia].is_dynamic() && !bodies[ib].is_dynamic() {
                continue;
            }
            let (sa, sb) = (bodies[ia].shape.as_ref()?, bodies[ib].shape.as_ref()?);
            if proximity(sa, &poses[a], sb, &poses[b]).distance < 0.0 {
                return Some((*t, ia.min(ib), ia.max(ib)));
            }
        }
    }
    None
}
