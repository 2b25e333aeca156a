//! Chain shapes in scene files (issue 19): a good one builds, a bad one is
//! a located error (file, field, line).

use scene::{ErrorKind, Scene, SceneError};

fn error(text: &str) -> SceneError {
    match Scene::parse_str("bad.toml", text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

const SIMULATION: &str = "[simulation]\ndt = 0.1\nduration = 1.0\n\n[contact]\n";

/// Lines 1–5 the simulation and contact tables, 6 blank, 7 `[[bodies]]`,
/// 8 the name, `extra` from line 9 on.
fn ground(extra: &str) -> String {
    format!("{SIMULATION}\n[[bodies]]\nname = \"ground\"\n{extra}")
}

#[test]
fn a_chain_on_a_static_body_builds_with_its_segments() {
    let text = ground(
        "kind = \"static\"\nshape = { type = \"chain\", points = [[3, 0], [2, 0], [1, 0], [0, 0], [-1, 0]] }\n",
    );
    let scene = Scene::parse_str("good.toml", &text).expect("a good chain");
    let Some(engine::Shape::Chain(c)) = &scene.bodies()[0].shape else {
        panic!("not a chain");
    };
    assert!(!c.is_loop());
    assert_eq!(c.segments().len(), 2);
    scene.build_world(None).expect("the soft step takes it");
}

#[test]
fn a_chain_on_a_dynamic_body_is_located_at_its_type() {
    let e = error(&ground(
        "density = 1.0\nshape = { type = \"chain\", points = [[3, 0], [2, 0], [1, 0], [0, 0]] }\n",
    ));
    assert_eq!(e.kind(), ErrorKind::InvalidValue, "{e}");
    assert_eq!(e.field(), Some("bodies[0].shape.type"), "{e}");
    assert_eq!(e.line(), Some(10), "{e}");
    assert!(e.message().contains("static"), "{e}");
}

#[test]
fn a_bad_chain_point_is_located_by_its_index() {
    // The third point is 1 mm from the second: under the 5 mm slop.
    let e = error(&ground(
        "kind = \"static\"\nshape = { type = \"chain\", points = [[3, 0], [2, 0], [1.999, 0], [0, 0]] }\n",
    ));
    assert_eq!(e.kind(), ErrorKind::InvalidValue, "{e}");
    assert_eq!(e.field(), Some("bodies[0].shape.points[2]"), "{e}");
    assert_eq!(e.line(), Some(10), "{e}");
    // Too few points: the list is named.
    let e = error(&ground(
        "kind = \"static\"\nshape = { type = \"chain\", points = [[3, 0], [2, 0]], loop = true }\n",
    ));
    assert_eq!(e.field(), Some("bodies[0].shape.points"), "{e}");
}

#[test]
fn a_chain_cannot_be_a_compound_part() {
    let e = error(&ground(
        "kind = \"static\"\nshape = { type = \"compound\", parts = [{ shape = { type = \"chain\", points = [[3, 0], [2, 0], [1, 0], [0, 0]] } }] }\n",
    ));
    assert_eq!(
        e.field(),
        Some("bodies[0].shape.parts[0].shape.type"),
        "{e}"
    );
}
