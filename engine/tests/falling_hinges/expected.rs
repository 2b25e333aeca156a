// Falling Hinges (Box2D's determinism test) run to rest: the expected
// figures and how they are measured (the hash is the engine's public
// `World::state_hash`), in one place. Included (`include!`)
// by engine/tests/falling_hinges.rs (the world built in Rust),
// scene/tests/joints.rs (scenes/falling_hinges.toml) and the harness's
// `falling_hinges` case (harness/src/cases/falling_hinges.rs, the main
// run): when the soft step's results change on purpose, update the two
// constants here, and only here.

/// The step (0-based count of steps of 1/60 s taken) at which every box
/// slept.
const REST_STEP: usize = 276;
/// `World::state_hash` of the world at rest: FNV-1a of the x, y and angle
/// bits of every body in id order, the ground (body 0) included.
const HINGES_HASH: u64 = 0xe339_d38e_a838_9b4d;

/// Where to update the constants, for the failure messages.
const UPDATE: &str = "if the soft step's results changed on purpose (a new solve order, a new \
                      default), update REST_STEP and HINGES_HASH in \
                      engine/tests/falling_hinges/expected.rs from this message, and say why \
                      in the commit";

/// Steps `world` (of 1/60 s) until every body but the ground (body 0)
/// sleeps, at most 2000 steps: the step count then, `None` if they never
/// all slept.
fn run_to_rest(world: &mut engine::World) -> Option<usize> {
    let bodies = world.bodies().len();
    for step in 0..2000 {
        if (1..bodies).all(|id| world.is_asleep(id)) {
            return Some(step);
        }
        world
            .step(1.0 / 60.0)
            .expect("the falling hinges step without error");
    }
    None
}
