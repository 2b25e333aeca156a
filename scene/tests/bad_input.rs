//! Every bad input is a `SceneError` naming the file, the field and the
//! line, never a panic: one test per kind of mistake.

use scene::{ErrorKind, Scene, SceneError};

/// Parses `text` as `bad.toml` and returns the error it must give.
fn error(text: &str) -> SceneError {
    match Scene::parse_str("bad.toml", text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

/// Checks the kind, the field and the line, and that `Display` shows them.
#[track_caller]
fn check(e: &SceneError, kind: ErrorKind, field: Option<&str>, line: Option<usize>) {
    assert_eq!(e.kind(), kind, "{e}");
    assert_eq!(e.field(), field, "{e}");
    assert_eq!(e.line(), line, "{e}");
    let shown = e.to_string();
    assert!(shown.starts_with("bad.toml"), "{shown}");
    if let Some(line) = line {
        assert!(shown.starts_with(&format!("bad.toml:{line}:")), "{shown}");
    }
    if let Some(field) = field {
        assert!(shown.contains(field), "{shown}");
    }
}

const SIMULATION: &str = "[simulation]\ndt = 0.1\nduration = 1.0\n";

/// A one-body scene (lines 1–3 simulation, 4 blank, 5 `[[bodies]]`, 6 name)
/// with `extra` lines from line 7 on.
fn body(extra: &str) -> String {
    format!("{SIMULATION}\n[[bodies]]\nname = \"box\"\n{extra}")
}

#[test]
fn malformed_toml_is_a_syntax_error_with_its_line() {
    // The array opened on line 3 is never closed: reported at its line's end.
    let e = error("[simulation]\ndt = 0.1\nduration = [1.0\n");
    check(&e, ErrorKind::Syntax, None, Some(3));
    let e = error("[simulation]\ndt = 0.1\ndt = 0.2\nduration = 1\n");
    check(&e, ErrorKind::Syntax, None, Some(3));
    assert!(e.message().contains("duplicate"), "{e}");
}

#[test]
fn unknown_field_is_named_with_its_line() {
    let e = error(&body("mass = 1.0\nmas = 2.0\n"));
    check(&e, ErrorKind::UnknownField, Some("bodies[0].mas"), Some(8));
    let e = error("[simulation]\ndt = 0.1\nduration = 1.0\nstep = 3\n");
    check(
        &e,
        ErrorKind::UnknownField,
        Some("simulation.step"),
        Some(4),
    );
}

#[test]
fn unknown_field_of_a_shape_is_named() {
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"box\", width = 1, heigth = 2 }\n",
    ));
    check(
        &e,
        ErrorKind::UnknownField,
        Some("bodies[0].shape.heigth"),
        Some(8),
    );
    assert!(e.message().contains("height"), "suggests the fields: {e}");
}

#[test]
fn unknown_force_type_is_refused() {
    let text = body("mass = 1.0\n\n[[forces]]\ntype = \"magnet\"\nbody = \"box\"\n");
    let e = error(&text);
    check(&e, ErrorKind::InvalidType, Some("forces[0].type"), Some(10));
}

#[test]
fn missing_field_is_named() {
    let e = error("[simulation]\nduration = 1.0\n\n[[bodies]]\nname = \"a\"\nmass = 1\n");
    check(&e, ErrorKind::MissingField, Some("simulation.dt"), Some(1));
}

#[test]
fn wrong_type_is_refused() {
    let e = error(&body("mass = \"heavy\"\n"));
    check(&e, ErrorKind::InvalidType, Some("bodies[0].mass"), Some(7));
}

#[test]
fn a_vector_must_have_exactly_two_numbers() {
    let e = error(&body("mass = 1.0\nposition = [1.0, 2.0, 3.0]\n"));
    check(
        &e,
        ErrorKind::InvalidType,
        Some("bodies[0].position"),
        Some(8),
    );
    let e = error(&body("mass = 1.0\nvelocity = [1.0]\n"));
    check(
        &e,
        ErrorKind::InvalidType,
        Some("bodies[0].velocity"),
        Some(8),
    );
}

#[test]
fn self_intersecting_polygon_names_the_body_and_the_edge() {
    // A bow tie: edge 0, (0, 0) to (2, 2), crosses edge 2, (2, 0) to (0, 2).
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"polygon\", vertices = [\n  [0, 0],\n  [2, 2],\n  [2, 0],\n  [0, 2],\n] }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidPolygon,
        Some("bodies[0].shape.vertices[0]"),
        Some(9),
    );
    assert!(e.message().contains("'box'"), "{e}");
    assert!(e.message().contains("self-intersecting"), "{e}");
    assert!(
        e.message().contains("edge 0 crosses or touches edge 2"),
        "{e}"
    );
}

#[test]
fn a_concave_polygon_is_cut_into_convex_parts() {
    let scene = scene::Scene::parse_str(
        "l.toml",
        &body(
            "density = 1.0\nshape = { type = \"polygon\", vertices = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]] }\n",
        ),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let Some(engine::Shape::Compound(c)) = &scene.bodies()[0].shape else {
        panic!("an L is a compound")
    };
    assert_eq!(c.parts().len(), 2);
    // Area 3 m², density 1 kg/m².
    let (built, _) = engine::Body::from_def(&scene.bodies()[0]).unwrap();
    assert!((built.mass - 3.0).abs() < 1e-15, "{}", built.mass);
}

#[test]
fn a_bad_compound_part_is_located() {
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"compound\", parts = [\n  { shape = { type = \"box\", width = 1, height = 1 } },\n  { shape = { type = \"circle\", radius = -1 }, offset = [1, 0] },\n] }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("bodies[0].shape.parts[1].shape.radius"),
        Some(10),
    );
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"compound\", parts = [\n  { shape = { type = \"compound\", parts = [] } },\n] }\n",
    ));
    assert_eq!(
        e.field(),
        Some("bodies[0].shape.parts[0].shape.type"),
        "{e}"
    );
    assert!(e.message().contains("list its parts in this one"), "{e}");
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"compound\", parts = [] }\n",
    ));
    assert_eq!(e.field(), Some("bodies[0].shape.parts"), "{e}");
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"compound\", parts = [\n  { shape = { type = \"polygon\", vertices = [[0, 0], [1, 1], [1, 0], [0, 1]] }, angle = 0.5 },\n] }\n",
    ));
    assert!(
        e.field()
            .unwrap()
            .starts_with("bodies[0].shape.parts[0].shape.vertices["),
        "{e}"
    );
    assert_eq!(e.line(), Some(9));
}

#[test]
fn clockwise_polygon_is_refused() {
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"polygon\", vertices = [[0, 0], [0, 1], [1, 0]] }\n",
    ));
    assert_eq!(e.kind(), ErrorKind::InvalidPolygon, "{e}");
    assert!(
        e.field().unwrap().starts_with("bodies[0].shape.vertices["),
        "{e}"
    );
    assert_eq!(e.line(), Some(8));
    assert!(e.message().contains("clockwise"), "{e}");
    assert!(e.message().contains("'box'"), "{e}");
}

#[test]
fn polygon_with_two_vertices_is_refused() {
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"polygon\", vertices = [[0, 0], [1, 0]] }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidPolygon,
        Some("bodies[0].shape.vertices"),
        Some(8),
    );
}

#[test]
fn zero_or_negative_mass_is_refused() {
    for mass in ["0.0", "-20"] {
        let e = error(&body(&format!("mass = {mass}\n")));
        check(&e, ErrorKind::InvalidValue, Some("bodies[0].mass"), Some(7));
        assert!(e.message().contains("> 0"), "{e}");
    }
}

#[test]
fn zero_or_negative_density_is_refused() {
    let e = error(&body(
        "density = -1.0\nshape = { type = \"circle\", radius = 1 }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("bodies[0].density"),
        Some(7),
    );
}

#[test]
fn zero_or_negative_dt_is_refused() {
    for dt in ["0.0", "-0.1"] {
        let e = error(&format!(
            "[simulation]\nduration = 1.0\ndt = {dt}\n\n[[bodies]]\nname = \"a\"\nmass = 1\n"
        ));
        check(&e, ErrorKind::InvalidValue, Some("simulation.dt"), Some(3));
    }
}

#[test]
fn zero_duration_is_refused() {
    let e = error("[simulation]\ndt = 0.1\nduration = 0\n[[bodies]]\nname = \"a\"\nmass = 1\n");
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("simulation.duration"),
        Some(3),
    );
}

#[test]
fn nan_is_refused() {
    let e = error(&body("mass = nan\n"));
    check(&e, ErrorKind::NonFinite, Some("bodies[0].mass"), Some(7));
    assert!(e.message().contains("NaN"), "{e}");
}

#[test]
fn infinity_is_refused() {
    let e = error(&body("mass = 1.0\nposition = [0.0,\n  inf]\n"));
    check(
        &e,
        ErrorKind::NonFinite,
        Some("bodies[0].position[1]"),
        Some(9),
    );
    let e = error("[simulation]\ndt = -inf\nduration = 1.0\n");
    check(&e, ErrorKind::NonFinite, Some("simulation.dt"), Some(2));
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"box\", width = 1, height = 1 }\n\n[[forces]]\ntype = \"torque\"\nbody = \"box\"\ntorque = 1.0\nwindow = [0, inf]\n",
    ));
    check(
        &e,
        ErrorKind::NonFinite,
        Some("forces[0].window[1]"),
        Some(14),
    );
}

#[test]
fn force_naming_a_missing_body_is_refused() {
    let text =
        body("mass = 1.0\n\n[[forces]]\ntype = \"drag\"\nbody = \"bxo\"\ncoefficient = 0.003\n");
    let e = error(&text);
    check(&e, ErrorKind::UnknownBody, Some("forces[0].body"), Some(11));
    assert!(
        e.message().contains("'bxo'") && e.message().contains("'box'"),
        "{e}"
    );
}

#[test]
fn spring_naming_a_missing_other_body_is_refused() {
    let text = body(
        "mass = 1.0\n\n[[forces]]\ntype = \"spring\"\nbody = \"box\"\nother_body = \"ghost\"\nstiffness = 1\n",
    );
    let e = error(&text);
    check(
        &e,
        ErrorKind::UnknownBody,
        Some("forces[0].other_body"),
        Some(12),
    );
}

#[test]
fn event_naming_a_missing_body_is_refused() {
    let e = error(&body(
        "mass = 1.0\n\n[[events]]\ntype = \"apex\"\nbody = \"ball\"\n",
    ));
    check(&e, ErrorKind::UnknownBody, Some("events[0].body"), Some(11));
}

#[test]
fn more_than_1e8_steps_is_refused() {
    let e =
        error("[simulation]\ndt = 1e-9\nduration = 1.0\n\n[[bodies]]\nname = \"a\"\nmass = 1\n");
    check(&e, ErrorKind::TooManySteps, Some("simulation.dt"), Some(2));
    assert!(e.message().contains("1e8"), "{e}");
}

#[test]
fn unknown_method_lists_the_known_ones() {
    let e = error(
        "[simulation]\nmethod = \"rk5\"\ndt = 0.1\nduration = 1\n[[bodies]]\nname = \"a\"\nmass = 1\n",
    );
    check(
        &e,
        ErrorKind::InvalidType,
        Some("simulation.method"),
        Some(2),
    );
    assert!(e.message().contains("velocity_verlet"), "{e}");
}

#[test]
fn duplicate_body_names_are_refused() {
    let e = error(&body(
        "mass = 1.0\n\n[[bodies]]\nname = \"box\"\nmass = 2.0\n",
    ));
    check(
        &e,
        ErrorKind::DuplicateName,
        Some("bodies[1].name"),
        Some(10),
    );
}

#[test]
fn mass_and_density_together_are_refused() {
    let e = error(&body(
        "mass = 1.0\ndensity = 2.0\nshape = { type = \"circle\", radius = 1 }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("bodies[0].density"),
        Some(8),
    );
}

#[test]
fn dynamic_body_without_mass_is_refused() {
    let e = error(&body("position = [0, 0]\n"));
    check(&e, ErrorKind::MissingField, Some("bodies[0].mass"), Some(5));
}

#[test]
fn static_body_with_a_velocity_is_refused() {
    let e = error(&body("kind = \"static\"\nvelocity = [1, 0]\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("bodies[0].velocity"),
        Some(8),
    );
}

#[test]
fn a_particle_cannot_rotate_or_take_a_torque() {
    let e = error(&body("mass = 1.0\nangular_velocity = 2.0\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("bodies[0].angular_velocity"),
        Some(8),
    );
    let e = error(&body(
        "mass = 1.0\n\n[[forces]]\ntype = \"torque\"\nbody = \"box\"\ntorque = 0.005\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("forces[0].body"),
        Some(11),
    );
    assert!(e.message().contains("particle"), "{e}");
}

#[test]
fn torque_needs_torque_or_lever_and_force() {
    let shape = "mass = 1.0\nshape = { type = \"box\", width = 1, height = 1 }\n\n[[forces]]\ntype = \"torque\"\nbody = \"box\"\n";
    let e = error(&body(&format!("{shape}lever = [1, 0]\n")));
    check(
        &e,
        ErrorKind::MissingField,
        Some("forces[0].force"),
        Some(10),
    );
    let e = error(&body(&format!("{shape}torque = 1\nforce = [1, 0]\n")));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("forces[0].force"),
        Some(14),
    );
}

#[test]
fn window_ending_before_it_starts_is_refused() {
    let e = error(&body(
        "mass = 1.0\n\n[[forces]]\ntype = \"gravity\"\ng = [0, -9.8]\nwindow = [0.7, 0.2]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("forces[0].window"),
        Some(12),
    );
}

#[test]
fn spring_with_a_zero_axis_is_refused() {
    let e = error(&body(
        "mass = 1.0\n\n[[forces]]\ntype = \"spring\"\nbody = \"box\"\nanchor = [0, 0]\nstiffness = 1\naxis = [0, 0]\n",
    ));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("forces[0].axis"),
        Some(14),
    );
}

#[test]
fn bad_colour_is_refused() {
    let e = error(&body("mass = 1.0\ncolour = \"blue\"\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("bodies[0].colour"),
        Some(8),
    );
}

#[test]
fn restitution_outside_zero_one_is_refused() {
    let e = error(&body("mass = 1.0\n\n[contact]\nrestitution = 1.5\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("contact.restitution"),
        Some(10),
    );
}

#[test]
fn a_scene_with_nothing_to_simulate_is_refused() {
    let e = error(SIMULATION);
    check(&e, ErrorKind::MissingField, Some("bodies"), Some(1));
}

#[test]
fn linear_test_with_bodies_is_refused() {
    let e = error(&body(
        "mass = 1.0\n\n[linear_test]\nlambda = -1000\ny0 = 1\n",
    ));
    check(&e, ErrorKind::InvalidValue, Some("bodies"), Some(5));
}

#[test]
fn linear_test_with_a_symplectic_method_is_refused() {
    let e = error(
        "[simulation]\nmethod = \"velocity_verlet\"\ndt = 0.001\nduration = 1\n[linear_test]\nlambda = -1000\ny0 = 1\n",
    );
    check(
        &e,
        ErrorKind::InvalidValue,
        Some("simulation.method"),
        Some(2),
    );
}

#[test]
fn linear_test_with_nan_is_refused() {
    let e = error("[simulation]\ndt = 0.001\nduration = 1\n[linear_test]\nlambda = nan\ny0 = 1\n");
    check(
        &e,
        ErrorKind::NonFinite,
        Some("linear_test.lambda"),
        Some(5),
    );
}

#[test]
fn building_a_world_from_a_linear_test_is_an_error() {
    let scene = Scene::parse_str(
        "h.toml",
        "[simulation]\ndt = 0.001\nduration = 1\n[linear_test]\nlambda = -1000\ny0 = 1\n",
    )
    .unwrap();
    let e = scene.build_world(None).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::WrongSceneKind, "{e}");
}

#[test]
fn bad_method_override_is_an_error_not_a_panic() {
    let scene = Scene::parse_str("ok.toml", &body("mass = 1.0\n")).unwrap();
    let bad = engine::Method::DormandPrince(engine::Tolerance::uniform(-1.0));
    let e = scene.build_world(Some(bad)).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Engine, "{e}");
    assert!(std::error::Error::source(&e).is_some());
}

#[test]
fn missing_file_is_an_io_error_naming_the_path() {
    let path = std::env::temp_dir().join("scene-tests-no-such-file.toml");
    let e = Scene::load(&path).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Io);
    assert_eq!(e.line(), None);
    assert!(
        e.to_string().starts_with(&path.display().to_string()),
        "{e}"
    );
}

#[test]
fn errors_from_a_file_name_the_file() {
    let dir = std::env::temp_dir().join(format!("scene-tests-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("negative_mass.toml");
    std::fs::write(&path, body("mass = -1.0\n")).unwrap();
    let e = Scene::load(&path).unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    let expected = format!("{}:7:8: bodies[0].mass: ", path.display());
    assert!(e.to_string().starts_with(&expected), "{e}");
    assert_eq!(e.origin(), path.display().to_string());
}
