//! `[[joints]]` and the chain and ragdoll generators: the example scenes
//! load and hold together, `scenes/falling_hinges.toml` gives the engine
//! test's bits, and every bad joint definition is a located error.

use scene::{ErrorKind, Scene, SceneError};
use std::path::PathBuf;

fn scenes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

/// Parses `text` as `bad.toml` and returns the error it must give.
fn error(text: &str) -> SceneError {
    match Scene::parse_str("bad.toml", text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

/// Checks the kind, the field, the line and words of the message.
#[track_caller]
fn check(e: &SceneError, kind: ErrorKind, field: &str, line: usize, words: &str) {
    assert_eq!(e.kind(), kind, "{e}");
    assert_eq!(e.field(), Some(field), "{e}");
    assert_eq!(e.line(), Some(line), "{e}");
    assert!(
        e.to_string().starts_with(&format!("bad.toml:{line}:")) && e.to_string().contains(field),
        "{e}"
    );
    assert!(
        e.message().contains(words),
        "'{}' lacks '{words}'",
        e.message()
    );
}

/// Lines 1–3 `[simulation]`, 5–8 a static `wall`, 10–13 a dynamic `bob`,
/// 15 `[[joints]]`, 16 its type, then `extra` from line 17.
fn joint(kind: &str, extra: &str) -> String {
    format!(
        "[simulation]\ndt = 0.01\nduration = 1.0\n\n[[bodies]]\nname = \"wall\"\nkind = \"static\"\nposition = [0.0, 0.0]\n\n[[bodies]]\nname = \"bob\"\nmass = 1.0\nposition = [1.0, 0.0]\n\n[[joints]]\ntype = \"{kind}\"\n{extra}"
    )
}

#[test]
fn the_example_scenes_load_with_their_joints() {
    for (file, joints) in [
        ("examples/pendulum.toml", 2),
        ("examples/chain.toml", 21),
        ("examples/ragdoll.toml", 60),
        ("falling_hinges.toml", 40),
    ] {
        let scene = Scene::load(scenes().join(file)).unwrap();
        assert_eq!(scene.joint_count(), joints, "{file}");
        let world = scene.build_world(None).unwrap();
        assert_eq!(world.joint_count(), joints, "{file}");
        assert!(matches!(
            scene.contact(),
            Some(engine::ContactModel::SoftStep(_))
        ));
    }
}

#[test]
fn the_ragdolls_hold_together_as_they_fall() {
    // Six ragdolls fall 1 to 3 m and pile up on the ground. A joint that
    // came apart would open by a bone's length (0.25 m and more); 5 cm
    // detects that, far above what the soft rigid rows give in the
    // impacts (3.1 cm measured, the bottom row's torso joints as their
    // legs stop at about 5 m/s: the rows give way by the relative speed
    // over their 60 Hz, and more where several bones load one joint; at
    // rest they sink by g/ω² = 0.07 mm). A detector, not a precision
    // figure.
    let scene = Scene::load(scenes().join("examples/ragdoll.toml")).unwrap();
    let mut world = scene.build_world(None).unwrap();
    let mut worst: f64 = 0.0;
    for _ in 0..240 {
        world.step(scene.dt()).unwrap();
        for j in 0..world.joint_count() {
            worst = worst.max(world.joint(j).unwrap().linear_error);
        }
    }
    assert!(worst < 0.05, "a pivot opened by {worst} m");
    // Every bone is down: below 1 m (a standing human's hip is at 0.95 m).
    for s in &world.states()[1..] {
        assert!(s.position.y < 1.0, "{s:?}");
    }
}

// REST_STEP, HINGES_HASH and run_to_rest, shared with the
// engine's test and the harness.
include!("../../engine/tests/falling_hinges/expected.rs");

/// `scenes/falling_hinges.toml` is engine/tests/falling_hinges.rs's world:
/// stepped the same way (one `step` of 1/60 s at a time) it comes to rest
/// at the same step with the same bits.
#[test]
fn the_falling_hinges_scene_gives_the_engine_tests_bits() {
    let scene = Scene::load(scenes().join("falling_hinges.toml")).unwrap();
    let mut world = scene.build_world(None).unwrap();
    let rest = run_to_rest(&mut world);
    let h = world.state_hash();
    assert_eq!(
        (rest, h),
        (Some(REST_STEP), HINGES_HASH),
        "scenes/falling_hinges.toml rested at {rest:?} with hash {h:#018x}; the engine's \
         test (engine/tests/falling_hinges.rs) expects {REST_STEP} and {HINGES_HASH:#018x}: \
         the file and the test's world differ, or {UPDATE}"
    );
}

#[test]
fn a_joint_naming_a_missing_body_is_located() {
    let e = error(&joint(
        "revolute",
        "body_b = \"bobb\"\nanchor = [0.0, 0.0]\n",
    ));
    check(
        &e,
        ErrorKind::UnknownBody,
        "joints[0].body_b",
        17,
        "no body is named 'bobb'",
    );
}

#[test]
fn a_joint_of_a_body_to_itself_is_located() {
    let e = error(&joint(
        "revolute",
        "body_a = \"bob\"\nbody_b = \"bob\"\nanchor = [0.0, 0.0]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].body_b",
        18,
        "to itself",
    );
}

#[test]
fn a_joint_without_a_dynamic_body_is_located() {
    let e = error(&joint("weld", "body_a = \"wall\"\nanchor = [0.0, 0.0]\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].body_a",
        17,
        "dynamic",
    );
    let e = error(&joint("weld", "body_b = \"world\"\nanchor = [0.0, 0.0]\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].body_b",
        17,
        "dynamic",
    );
}

#[test]
fn a_zero_axis_is_located() {
    let e = error(&joint(
        "prismatic",
        "body_b = \"bob\"\nanchor = [1.0, 0.0]\naxis = [0.0, 0.0]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].axis",
        19,
        "no direction",
    );
}

#[test]
fn limits_in_the_wrong_order_are_located() {
    let e = error(&joint(
        "revolute",
        "body_b = \"bob\"\nanchor = [0.0, 0.0]\nlimits = [0.5, -0.5]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].limits",
        19,
        "[lower, upper]",
    );
    let e = error(&joint(
        "revolute",
        "body_b = \"bob\"\nanchor = [0.0, 0.0]\nlimits = [-4.0, 0.5]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].limits[0]",
        19,
        "0.99π",
    );
    let e = error(&joint(
        "distance",
        "body_b = \"bob\"\nanchor_a = [0.0, 0.0]\nanchor_b = [1.0, 0.0]\nmin_length = 2.0\nmax_length = 1.0\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].min_length",
        20,
        "above max_length",
    );
}

#[test]
fn a_negative_stiffness_is_located() {
    let e = error(&joint(
        "revolute",
        "body_b = \"bob\"\nanchor = [0.0, 0.0]\nspring = { hertz = -1.0, damping_ratio = 0.5 }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].spring.hertz",
        19,
        "must be > 0",
    );
    let e = error(&joint(
        "distance",
        "body_b = \"bob\"\nanchor_a = [0.0, 0.0]\nanchor_b = [1.0, 0.0]\nspring = { hertz = 2.0, damping_ratio = -1.0 }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].spring.damping_ratio",
        20,
        ">= 0",
    );
    let e = error(&joint(
        "revolute",
        "body_b = \"bob\"\nanchor = [0.0, 0.0]\nmotor = { speed = 1.0, max_torque = 0.0 }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].motor.max_torque",
        19,
        "must be > 0",
    );
}

#[test]
fn an_unknown_option_is_located() {
    let e = error(&joint(
        "revolute",
        "body_b = \"bob\"\nanchor = [0.0, 0.0]\nmax_motor_torque = 3.0\n",
    ));
    check(
        &e,
        ErrorKind::UnknownField,
        "joints[0].max_motor_torque",
        19,
        "unknown field",
    );
    let e = error(&joint(
        "distance",
        "body_b = \"bob\"\nanchor_a = [0.0, 0.0]\nanchor_b = [1.0, 0.0]\nspring = { hertz = 2.0, target = 1.0 }\n",
    ));
    check(
        &e,
        ErrorKind::UnknownField,
        "joints[0].spring.target",
        20,
        "unknown field",
    );
    let e = error(&joint("hinge", "body_b = \"bob\"\n"));
    check(&e, ErrorKind::InvalidType, "joints[0].type", 16, "hinge");
}

#[test]
fn anchors_must_be_given_in_one_form() {
    let e = error(&joint("revolute", "body_b = \"bob\"\n"));
    check(
        &e,
        ErrorKind::MissingField,
        "joints[0].anchor",
        15,
        "anchor = [x, y]",
    );
    let e = error(&joint(
        "weld",
        "body_b = \"bob\"\nanchor = [0.0, 0.0]\nlocal_anchor_a = [0.0, 0.0]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].local_anchor_a",
        19,
        "not both",
    );
    let e = error(&joint(
        "distance",
        "body_b = \"bob\"\nanchor_a = [1.0, 0.0]\nanchor_b = [1.0, 0.0]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].anchor_b",
        19,
        "coincide",
    );
    let e = error(&joint(
        "distance",
        "body_b = \"bob\"\nanchor_a = [0.0, 0.0]\nanchor_b = [1.0, 0.0]\nmax_length = 2.0\nlength = 1.0\n",
    ));
    check(&e, ErrorKind::InvalidValue, "joints[0].length", 21, "rope");
}

#[test]
fn a_target_joint_pulls_a_dynamic_body() {
    let e = error(&joint("target", "body = \"wall\"\nmax_force = 10.0\n"));
    check(&e, ErrorKind::InvalidValue, "joints[0].body", 17, "dynamic");
    let e = error(&joint("target", "body = \"bob\"\nmax_force = -1.0\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].max_force",
        18,
        "must be > 0",
    );
    let ok = Scene::parse_str(
        "ok.toml",
        &joint(
            "target",
            "body = \"bob\"\nmax_force = 10.0\ntarget = [2.0, 0.0]\n",
        ),
    )
    .unwrap();
    assert_eq!(ok.joint_count(), 1);
}

#[test]
fn joints_under_the_exact_model_are_its_own() {
    // A pin runs under the exact model, with the scene's method.
    let text = format!(
        "{}\n[contact]\nmodel = \"exact\"\n",
        joint("revolute", "body_b = \"bob\"\nanchor = [0.0, 0.0]\n")
    )
    .replace("dt = 0.01", "method = \"rk4\"\ndt = 0.01");
    let scene = Scene::parse_str("ok.toml", &text).unwrap();
    let mut world = scene.build_world(None).unwrap();
    assert_eq!(world.method(), engine::Method::Rk4);
    world.step(0.01).unwrap();
    assert!(world.joint(0).unwrap().linear_error < 1e-12);
    // A limit it does not solve is refused at the joint, naming the option.
    let text = format!(
        "{}\n[contact]\nmodel = \"exact\"\n",
        joint(
            "revolute",
            "body_b = \"bob\"\nanchor = [0.0, 0.0]\nlimits = [-0.5, 0.5]\n"
        )
    );
    let e = error(&text);
    check(&e, ErrorKind::Engine, "joints[0]", 15, "angle limits");
    // And a scene with joints and no [contact] runs the soft step, which
    // takes no other method.
    let text = joint("revolute", "body_b = \"bob\"\nanchor = [0.0, 0.0]\n")
        .replace("dt = 0.01", "method = \"rk4\"\ndt = 0.01");
    let e = error(&text);
    check(
        &e,
        ErrorKind::InvalidValue,
        "simulation.method",
        2,
        "joints need the soft step",
    );
}

#[test]
fn joint_names_are_unique_and_world_is_the_world() {
    let text = format!(
        "{}\n[[joints]]\ntype = \"weld\"\nname = \"pin\"\nbody_b = \"bob\"\nanchor = [0.0, 0.0]\n",
        joint(
            "revolute",
            "name = \"pin\"\nbody_b = \"bob\"\nanchor = [0.0, 0.0]\n"
        )
    );
    let e = error(&text);
    check(
        &e,
        ErrorKind::DuplicateName,
        "joints[1].name",
        23,
        "already used",
    );
    let text = joint(
        "revolute",
        "body_b = \"bob\"\nbody_a = \"world\"\nanchor = [0.0, 0.0]\n",
    )
    .replace("name = \"wall\"", "name = \"world\"");
    let e = error(&text);
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].body_a",
        18,
        "rename that body",
    );
}

/// Lines 1–3 `[simulation]`, 5 `[[generate]]`, 6 its type, then `extra`.
fn generator(kind: &str, extra: &str) -> String {
    format!("[simulation]\ndt = 0.01\nduration = 1.0\n\n[[generate]]\ntype = \"{kind}\"\n{extra}")
}

#[test]
fn bad_chains_and_ragdolls_are_located() {
    let e = error(&generator(
        "chain",
        "count = 4\nlink_length = 0.5\nstart = [0.0, 0.0]\nend = [5.0, 0.0]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "generate[0].end",
        10,
        "shorter",
    );
    let e = error(&generator(
        "chain",
        "count = 4\nstart = [0.0, 0.0]\ndirection = [0.0, 0.0]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "generate[0].direction",
        9,
        "non-zero",
    );
    let e = error(&generator("chain", "count = 0\nstart = [0.0, 0.0]\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        "generate[0].count",
        7,
        "between 1",
    );
    let e = error(&generator("ragdoll", "scale = -1.0\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        "generate[0].scale",
        7,
        "must be > 0",
    );
    let e = error(&generator("ragdoll", "repeat = [2.5, 1.0]\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        "generate[0].repeat[0]",
        7,
        "whole number",
    );
    let e = error(&format!(
        "{}\n[contact]\nmodel = \"exact\"\n",
        generator("ragdoll", "scale = 1.0\n")
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "generate[0].type",
        6,
        "soft_step",
    );
}

#[test]
fn generated_bodies_can_be_jointed_by_name() {
    // A box hung from the last link of a generated chain.
    let text = format!(
        "{}\n[[bodies]]\nname = \"weight\"\nmass = 2.0\nshape = {{ type = \"box\", width = 0.3, height = 0.3 }}\nposition = [0.0, -2.15]\n\n[[joints]]\ntype = \"revolute\"\nbody_a = \"chain_3\"\nbody_b = \"weight\"\nanchor = [0.0, -2.0]\n",
        generator("chain", "count = 4\nstart = [0.0, 0.0]\n")
    );
    let scene = Scene::parse_str("ok.toml", &text).unwrap();
    assert_eq!(scene.joint_count(), 5);
    let mut world = scene.build_world(None).unwrap();
    for _ in 0..60 {
        world.step(0.01).unwrap();
    }
    let last = world.joint(0).unwrap();
    assert_eq!(last.name, "joints[0]");
    assert!(last.linear_error < 1e-3, "{last:?}");
}

#[test]
fn bad_wheel_and_motor_joints_are_located() {
    let e = error(&joint(
        "wheel",
        "body_b = \"bob\"\nanchor = [1.0, 0.0]\naxis = [0.0, 0.0]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].axis",
        19,
        "no direction",
    );
    let e = error(&joint(
        "wheel",
        "body_b = \"bob\"\nanchor = [1.0, 0.0]\nspring = { hertz = -2.0 }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].spring.hertz",
        19,
        "hertz",
    );
    let e = error(&joint(
        "motor_joint",
        "body_b = \"bob\"\nmax_force = 0.0\nmax_torque = 1.0\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        "joints[0].max_force",
        18,
        "max_force",
    );
    let e = error(&joint(
        "motor_joint",
        "body_b = \"bob\"\nmax_force = 1.0\nmax_torque = 1.0\nlinear_offset = [1.0, nan]\n",
    ));
    check(
        &e,
        ErrorKind::NonFinite,
        "joints[0].linear_offset[1]",
        20,
        "finite",
    );
    // A wheel's motor is refused under the exact model, at the joint; its
    // spring runs there.
    let exact = |extra: &str| {
        format!(
            "{}\n[contact]\nmodel = \"exact\"\n",
            joint(
                "wheel",
                &format!("body_b = \"bob\"\nanchor = [1.0, 0.0]\n{extra}")
            )
        )
        .replace("dt = 0.01", "method = \"rk4\"\ndt = 0.01")
    };
    let e = error(&exact("motor = { speed = 1.0, max_torque = 1.0 }\n"));
    check(&e, ErrorKind::Engine, "joints[0]", 16, "with a motor");
    let scene = Scene::parse_str("ok.toml", &exact("spring = { hertz = 2.0 }\n")).unwrap();
    let mut world = scene.build_world(None).unwrap();
    world.step(0.01).unwrap();
    assert!(world.joint(0).unwrap().linear_error < 1e-12);
}
