//! Capsules, segments, rounded boxes and rounded polygons in scene files:
//! built with their exact mass, and every bad value a located error
//! (file, field, line).

use scene::{ErrorKind, Scene, SceneError};

/// Parses `text` as `bad.toml` and returns the error it must give.
fn error(text: &str) -> SceneError {
    match Scene::parse_str("bad.toml", text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

#[track_caller]
fn check(e: &SceneError, kind: ErrorKind, field: &str, line: usize) {
    assert_eq!(e.kind(), kind, "{e}");
    assert_eq!(e.field(), Some(field), "{e}");
    assert_eq!(e.line(), Some(line), "{e}");
    assert!(
        e.to_string().starts_with(&format!("bad.toml:{line}:")),
        "{e}"
    );
}

const SIMULATION: &str = "[simulation]\ndt = 0.1\nduration = 1.0\n";

/// A one-body scene: lines 1–3 simulation, 4 blank, 5 `[[bodies]]`, 6 the
/// name, `extra` from line 7 on.
fn body(extra: &str) -> String {
    format!("{SIMULATION}\n[[bodies]]\nname = \"b\"\n{extra}")
}

#[test]
fn the_four_kinds_build_with_their_mass() {
    let text = body(
        "density = 2.0\nshape = { type = \"capsule\", length = 1.0, radius = 0.25 }\n\n\
         [[bodies]]\nname = \"ground\"\nkind = \"static\"\n\
         shape = { type = \"segment\", a = [-5.0, 0.0], b = [5.0, 0.0] }\n\n\
         [[bodies]]\nname = \"tile\"\ndensity = 1.0\n\
         shape = { type = \"box\", width = 0.6, height = 0.3, radius = 0.05 }\n\n\
         [[bodies]]\nname = \"gem\"\ndensity = 1.0\n\
         shape = { type = \"polygon\", vertices = [[0, 0], [1, 0], [0, 1]], radius = 0.1 }\n",
    );
    let scene = Scene::parse_str("ok.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    let kinds: Vec<&str> = scene
        .bodies()
        .iter()
        .map(|b| b.shape.as_ref().unwrap().kind_name())
        .collect();
    assert_eq!(
        kinds,
        ["capsule", "segment", "rounded polygon", "rounded polygon"]
    );
    // Capsule: mass = ρ (2 r L + π r²) = 2 (0.5 + π/16).
    let (capsule, _) = engine::Body::from_def(&scene.bodies()[0]).unwrap();
    let mass = 2.0 * (0.5 + std::f64::consts::PI / 16.0);
    assert!((capsule.mass - mass).abs() < 1e-15, "{}", capsule.mass);
    // A zero radius is the sharp shape.
    let sharp = Scene::parse_str(
        "ok.toml",
        &body("density = 1.0\nshape = { type = \"box\", width = 1, height = 1, radius = 0 }\n"),
    )
    .unwrap();
    assert_eq!(
        sharp.bodies()[0].shape.as_ref().unwrap().kind_name(),
        "polygon"
    );
}

#[test]
fn bad_values_are_located() {
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"capsule\", length = 1.0, radius = -0.25 }\n",
    ));
    check(&e, ErrorKind::InvalidValue, "bodies[0].shape.radius", 8);
    assert!(e.message().contains("capsule radius"), "{e}");
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"capsule\", length = 0.0, radius = 0.25 }\n",
    ));
    check(&e, ErrorKind::InvalidValue, "bodies[0].shape.length", 8);
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"box\", width = 1, height = 1, radius = -0.1 }\n",
    ));
    check(&e, ErrorKind::InvalidValue, "bodies[0].shape.radius", 8);
    let e = error(&body(
        "kind = \"static\"\nshape = { type = \"segment\", a = [1.0, 2.0], b = [1.0, 2.0] }\n",
    ));
    check(&e, ErrorKind::InvalidValue, "bodies[0].shape.b", 8);
    assert!(e.message().contains("distinct"), "{e}");
    // A concave outline cannot be rounded.
    let e = error(&body(
        "density = 1.0\nshape = { type = \"polygon\", vertices = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], radius = 0.1 }\n",
    ));
    check(&e, ErrorKind::InvalidValue, "bodies[0].shape.radius", 8);
    assert!(e.message().contains("concave"), "{e}");
}

#[test]
fn a_dynamic_segment_is_refused_at_its_type() {
    let e = error(&body(
        "density = 1.0\nshape = { type = \"segment\", a = [0.0, 0.0], b = [1.0, 0.0] }\n",
    ));
    check(&e, ErrorKind::InvalidValue, "bodies[0].shape.type", 8);
    assert!(e.message().contains("no mass"), "{e}");
}

#[test]
fn both_contact_models_take_them() {
    for model in ["", "model = \"exact\"\n", "model = \"soft_step\"\n"] {
        let text = format!(
            "[simulation]\ndt = 0.01\nduration = 1.0\n\n[contact]\n{model}\n[[bodies]]\nname = \"pill\"\n\
             mass = 1.0\nshape = {{ type = \"capsule\", length = 1.0, radius = 0.25 }}\n"
        );
        Scene::parse_str("ok.toml", &text).expect("both contact models collide capsules");
    }
}
