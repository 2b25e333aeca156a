// Falling Hinges (Box2D's determinism test) run to rest: the expected
// figures and how they are measured, in one place. Included (`include!`)
// by engine/tests/falling_hinges.rs (the world built in Rust),
// scene/tests/joints.rs (scenes/falling_hinges.toml) and the harness's
// `falling_hinges` case (harness/src/cases/falling_hinges.rs, the main
// run): when the soft step's results change on purpose, update the two
// constants here, and only here.

/// The step (0-based count of steps of 1/60 s taken) at which every box
/// slept.
const REST_STEP: usize = 276;
/// FNV-1a of the final poses (x, y, angle bits of every box in order).
const HINGES_HASH: u64 = 0xd725_f87a_6f54_95c1;

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

/// FNV-1a over the bits of every box's pose (x, y, angle), the ground
/// (body 0) left out.
fn pose_hash(states: &[engine::BodyState]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for s in &states[1..] {
        for x in [s.position.x, s.position.y, s.angle] {
            for b in x.to_bits().to_le_bytes() {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
    h
}
