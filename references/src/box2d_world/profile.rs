//! Box2D's own timers of its last step (`b2World_GetProfile`, through
//! boxdd's `World::profile`), in ms, by Box2D's names for them.
//!
//! Box2D zeroes its `b2Profile` at the start of every `b2World_Step` and
//! times each stage with its tick counter (`b2GetTicks`, always compiled
//! in, release builds too), so a reading holds the last step only; a
//! caller sums the readings over the steps it wants. How the fields nest,
//! as read in the vendored 3.2 sources (`src/physics_world.c`
//! `b2World_Step`, `src/solver.c` `b2Solve` and `b2SolverTask`,
//! `src/island.c`):
//!
//! - `step` = `pairs` + `collide` + `solve` + `sensors`, plus the code
//!   between them;
//! - `pairs`: `b2UpdateBroadPhasePairs`, new pairs of the moved proxies
//!   and their contacts; with one worker it also runs the rebuild of the
//!   dynamic tree inline (`b2UpdateTreesTask`, queued with Box2D's default
//!   task function, which runs a task at once); with more, that rebuild
//!   runs alongside and is waited for in `refit`;
//! - `collide`: `b2Collide`, every contact's manifold, begin and end of
//!   touching, contacts whose boxes parted destroyed;
//! - `solve` = `solver_setup` + `constraints` + `transforms` +
//!   `joint_events` + `hit_events` + `refit` + `bullets` +
//!   `sensor_hits` + `sleep_islands`;
//! - `constraints` (the solver's stages on the workers) ⊇
//!   `prepare_constraints` (joints and contacts) +
//!   `integrate_velocities` + `warm_start` + `solve_impulses` +
//!   `integrate_positions` + `relax_impulses` (each summed over the
//!   substeps) + `apply_restitution` + `store_impulses`, timed on the
//!   orchestrating thread, which waits for the workers at the end of each
//!   stage;
//! - `transforms`: `b2FinalizeBodiesTask`, body transforms, shape boxes and
//!   the sweeps of fast bodies against static ones (continuous);
//!   `refit`: enlarged boxes into the broad phase; `bullets`: the bullets'
//!   sweeps;
//! - `split_islands` is not a part of the sum: it runs inside
//!   `solver_setup` with one worker and alongside `constraints` with more
//!   (and only when sleeping is on; the benchmark turns it off).

use boxdd::Profile;

/// Box2D's timers, every field of `b2Profile` by its snake-case name, in
/// the order of the struct.
pub const FIELDS: [&str; 23] = [
    "step",
    "pairs",
    "collide",
    "solve",
    "solver_setup",
    "constraints",
    "prepare_constraints",
    "integrate_velocities",
    "warm_start",
    "solve_impulses",
    "integrate_positions",
    "relax_impulses",
    "apply_restitution",
    "store_impulses",
    "split_islands",
    "transforms",
    "sensor_hits",
    "joint_events",
    "hit_events",
    "refit",
    "bullets",
    "sleep_islands",
    "sensors",
];

/// The fields whose sum is the step's timed work, each counted once (the
/// module documentation: `step`, `solve` and `constraints` hold others;
/// `split_islands` is inside `solver_setup` or runs alongside).
pub const LEAVES: [&str; 19] = [
    "pairs",
    "collide",
    "solver_setup",
    "prepare_constraints",
    "integrate_velocities",
    "warm_start",
    "solve_impulses",
    "integrate_positions",
    "relax_impulses",
    "apply_restitution",
    "store_impulses",
    "transforms",
    "joint_events",
    "hit_events",
    "refit",
    "bullets",
    "sensor_hits",
    "sleep_islands",
    "sensors",
];

/// Every timer of `p` (ms), named as in [`FIELDS`].
pub fn fields(p: &Profile) -> [(&'static str, f64); 23] {
    let values = [
        p.step,
        p.pairs,
        p.collide,
        p.solve,
        p.solver_setup,
        p.constraints,
        p.prepare_constraints,
        p.integrate_velocities,
        p.warm_start,
        p.solve_impulses,
        p.integrate_positions,
        p.relax_impulses,
        p.apply_restitution,
        p.store_impulses,
        p.split_islands,
        p.transforms,
        p.sensor_hits,
        p.joint_events,
        p.hit_events,
        p.refit,
        p.bullets,
        p.sleep_islands,
        p.sensors,
    ];
    std::array::from_fn(|i| (FIELDS[i], f64::from(values[i])))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_leaf_is_a_field_and_the_sums_are_not_leaves() {
        for leaf in LEAVES {
            assert!(FIELDS.contains(&leaf), "{leaf}");
        }
        for sum in ["step", "solve", "constraints", "split_islands"] {
            assert!(!LEAVES.contains(&sum), "{sum}");
        }
        // Every other field is a leaf.
        assert_eq!(LEAVES.len() + 4, FIELDS.len());
    }
}
