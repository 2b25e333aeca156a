//! What a hostile user (or a fuzzer) feeds a scene: dates, huge integers,
//! numbers at f64's limits, thin and huge polygons, other encodings,
//! special files. Each is refused at load time, located (file, field,
//! line), in the user's words, or accepted when it is valid.

use scene::{ErrorKind, Scene, SceneError};

fn error(text: &str) -> SceneError {
    match Scene::parse_str("bad.toml", text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

/// The kind, the field and the line, and none of serde's or Rust's words.
#[track_caller]
fn check(e: &SceneError, kind: ErrorKind, field: Option<&str>, line: usize) {
    assert_eq!(e.kind(), kind, "{e}");
    assert_eq!(e.field(), field, "{e}");
    assert_eq!(e.line(), Some(line), "{e}");
    let shown = e.to_string();
    for jargon in [
        "$__toml",
        "struct ",
        "enum ",
        "variant identifier",
        "i128",
        "Spec",
        "sequence",
        "map",
    ] {
        assert!(!shown.contains(jargon), "{jargon:?} in: {shown}");
    }
}

const SIMULATION: &str = "[simulation]\ndt = 0.1\nduration = 1.0\n";

/// Lines 1–3 simulation, 4 blank, 5 `[[bodies]]`, 6 name, `extra` from 7.
fn body(extra: &str) -> String {
    format!("{SIMULATION}\n[[bodies]]\nname = \"box\"\n{extra}")
}

#[test]
fn a_date_where_a_table_is_expected_is_said_plainly() {
    let e = error("simulation = 1979-05-27\n");
    check(&e, ErrorKind::InvalidType, Some("simulation"), 1);
    assert!(e.message().contains("date-time 1979-05-27"), "{e}");
    assert!(e.message().contains("the table [simulation]"), "{e}");
}

#[test]
fn a_date_where_a_number_is_expected_is_said_plainly() {
    let e = error("[simulation]\ndt = 1979-05-27\nduration = 1.0\n");
    check(&e, ErrorKind::InvalidType, Some("simulation.dt"), 2);
    assert!(
        e.message()
            .contains("expected a number, found the date-time 1979-05-27"),
        "{e}"
    );
}

#[test]
fn wrong_types_are_named_in_toml_words() {
    let e = error(&body("mass = 1.0\nshape = 3\n"));
    check(&e, ErrorKind::InvalidType, Some("bodies[0].shape"), 8);
    assert!(e.message().contains("a table with a `type`"), "{e}");
    let e = error(&body("mass = 1.0\n[[forces]]\ntype = 3\n"));
    check(&e, ErrorKind::InvalidType, Some("forces[0].type"), 9);
    let e = error("[simulation]\ndt = 0.1\nduration = 1.0\n[bodies]\nname = \"x\"\n");
    check(&e, ErrorKind::InvalidType, Some("bodies"), 4);
    assert!(e.message().contains("expected an array"), "{e}");
}

#[test]
fn an_integer_beyond_64_bits_says_so() {
    let e = error(&body("mass = 99999999999999999999\n"));
    check(&e, ErrorKind::InvalidType, Some("bodies[0].mass"), 7);
    assert!(e.message().contains("64-bit"), "{e}");
    assert!(e.message().contains("1e20"), "{e}");
}

#[test]
fn huge_and_tiny_numbers_are_printed_short() {
    let e = error(&body("mass = -1e308\n"));
    check(&e, ErrorKind::OutOfRange, Some("bodies[0].mass"), 7);
    assert!(e.message().contains("-1e308"), "{e}");
    let e = error(&body("mass = -1e-320\n"));
    assert!(e.message().contains("-1e-320"), "{e}");
    let e = error(&body("mass = -20.0\n"));
    assert!(e.message().contains("got -20 kg"), "{e}");
    for e in [
        error(&body("mass = -1e308\n")),
        error(&body("mass = -1e-320\n")),
    ] {
        assert!(e.to_string().len() < 300, "{e}");
    }
}

#[test]
fn a_bad_value_in_a_typed_table_is_located_at_its_own_line() {
    // Line 14, inside a [[forces]] table opened on line 10.
    let text = body(
        "mass = 1.0\n\n\n[[forces]]\ntype = \"gravity\"\ng = [0.0, -9.81]\n\nwindow = \"always\"\n",
    );
    let e = error(&text);
    check(&e, ErrorKind::InvalidType, Some("forces[0].window"), 14);
    assert!(e.message().contains("found the string \"always\""), "{e}");
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"circle\", radius = \"big\" }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidType,
        Some("bodies[0].shape.radius"),
        8,
    );
    assert_eq!(e.column(), Some(37), "{e}");
}

#[test]
fn thin_boxes_load_and_a_repeated_vertex_is_named() {
    for shape in [
        "{ type = \"box\", width = 1.0, height = 1e-7 }",
        "{ type = \"box\", width = 1000.0, height = 0.001 }",
    ] {
        let text = body(&format!("mass = 1.0\nshape = {shape}\n"));
        Scene::parse_str("thin.toml", &text).unwrap_or_else(|e| panic!("{e}"));
    }
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"polygon\", vertices = [[0, 0], [1, 0], [1, 0], [0, 1]] }\n",
    ));
    check(
        &e,
        ErrorKind::InvalidPolygon,
        Some("bodies[0].shape.vertices[2]"),
        8,
    );
    assert!(e.message().contains("repeated vertex"), "{e}");
}

#[test]
fn coordinates_beyond_the_arithmetic_range_are_refused_as_such() {
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"polygon\", vertices = [[-1e300, -1e300], [1e300, -1e300], [0, 1e300]] }\n",
    ));
    check(
        &e,
        ErrorKind::OutOfRange,
        Some("bodies[0].shape.vertices[0][0]"),
        8,
    );
    assert!(e.message().contains("-1e300 is too large"), "{e}");
}

#[test]
fn an_inertia_that_underflows_is_refused_at_its_shape() {
    let e = error(&body(
        "mass = 1.0\nshape = { type = \"circle\", radius = 1e-200 }\n",
    ));
    check(&e, ErrorKind::OutOfRange, Some("bodies[0].shape.radius"), 8);
    assert!(e.message().contains("1e-200 is too small"), "{e}");
    // Each number in range, their product not: I = m r²/2 = 5e-311.
    let e = error(&body(
        "mass = 1e-10\nshape = { type = \"circle\", radius = 1e-150 }\n",
    ));
    check(&e, ErrorKind::OutOfRange, Some("bodies[0].shape.radius"), 8);
    assert!(e.message().contains("moment of inertia"), "{e}");
}

#[test]
fn an_initial_energy_that_overflows_names_the_velocity() {
    let e = error(&body("mass = 1e10\nvelocity = [1e154, 0.0]\n"));
    check(&e, ErrorKind::OutOfRange, Some("bodies[0].velocity"), 8);
    assert!(e.message().contains("kinetic energy"), "{e}");
}

/// Found by the long fuzz run: a mass of 1.3e154 kg at a height of
/// 1.3e154 m under the gravity of [simulation] (each number in range, m g y
/// is not) loaded, then failed its first step with a blow-up.
#[test]
fn a_potential_energy_that_overflows_names_the_position() {
    let text = "[simulation]\ndt = 0.1\nduration = 1.0\ngravity = [0.0, -10.0]\n\n\
                [[bodies]]\nname = \"box\"\nmass = 1.3e154\nposition = [0.0, 1.3e154]\n";
    let e = error(text);
    check(&e, ErrorKind::OutOfRange, Some("bodies[0].position"), 9);
    assert!(
        e.message().contains("potential energy of body 'box'"),
        "{e}"
    );
}

#[test]
fn an_energy_that_overflows_during_the_run_is_an_error_not_nan() {
    let text = body("mass = 1.0\n[[forces]]\ntype = \"gravity\"\ng = [1e154, -1e154]\n");
    let scene = Scene::parse_str("g.toml", &text).expect("each number is in range");
    let mut world = scene.build_world(None).unwrap();
    let mut failed = None;
    for _ in 0..10 {
        match world.step(0.1) {
            Ok(_) => assert!(world.energy().is_finite(), "{}", world.energy()),
            Err(e) => {
                failed = Some(e);
                break;
            }
        }
    }
    let e = failed.expect("the energy overflows within 10 steps");
    assert!(e.to_string().contains("energy"), "{e}");
}

#[test]
fn a_tolerance_below_f64_reach_is_refused() {
    let text = "[simulation]\nmethod = \"dormand_prince\"\ndt = 0.1\nduration = 1.0\ntolerance = 1e-16\n[[bodies]]\nname = \"p\"\nmass = 1.0\n";
    let e = error(text);
    check(&e, ErrorKind::OutOfRange, Some("simulation.tolerance"), 5);
    assert!(e.message().contains("2.220446049250313e-15"), "{e}");
    let fine = text.replace("1e-16", "1e-14");
    Scene::parse_str("ok.toml", &fine).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_linear_test_whose_exact_solution_overflows_is_refused() {
    let text = "[simulation]\nmethod = \"explicit_euler\"\ndt = 0.1\nduration = 1.0\n[linear_test]\nlambda = 750.0\ny0 = 1.0\n";
    let e = error(text);
    check(&e, ErrorKind::OutOfRange, Some("linear_test.lambda"), 6);
    assert!(e.message().contains("709.78"), "{e}");
    let fine = text.replace("750.0", "700.0");
    Scene::parse_str("ok.toml", &fine).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_key_nested_a_thousand_deep_is_located() {
    let key = vec!["a"; 1000].join(".");
    let e = error(&format!("{SIMULATION}[{key}]\n"));
    check(&e, ErrorKind::Syntax, None, 4);
    assert!(e.message().contains("1000 levels"), "{e}");
}

#[test]
fn a_huge_spring_axis_is_normalised_without_overflow() {
    let text = "[simulation]\ndt = 0.1\nduration = 1.0\n[[bodies]]\nname = \"p\"\nmass = 1.0\n\
                [[forces]]\ntype = \"spring\"\nbody = \"p\"\nanchor = [0.0, 0.0]\nstiffness = 1.0\naxis = [1e150, 0.0]\n";
    let scene = Scene::parse_str("axis.toml", text).unwrap_or_else(|e| panic!("{e}"));
    scene.build_world(None).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn other_encodings_are_named_and_located() {
    let mut utf16 = vec![0xFF, 0xFE];
    utf16.extend(SIMULATION.encode_utf16().flat_map(u16::to_le_bytes));
    let e = Scene::parse_bytes("u16.toml", &utf16).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Encoding, "{e}");
    assert!(e.to_string().starts_with("u16.toml:1:1: "), "{e}");
    assert!(e.message().contains("UTF-16"), "{e}");
    let e = Scene::parse_bytes("latin1.toml", b"[simulation]\n# caf\xe9\n").unwrap_err();
    assert!(e.to_string().starts_with("latin1.toml:2:6: "), "{e}");
    assert!(e.message().contains("0xE9"), "{e}");
}

#[test]
fn only_regular_files_of_bounded_size_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let e = Scene::load(dir.path()).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Io, "{e}");
    assert!(
        e.message().contains("not a regular file but a folder"),
        "{e}"
    );
    let big = dir.path().join("big.toml");
    let file = std::fs::File::create(&big).unwrap();
    file.set_len(scene::MAX_SCENE_BYTES + 1).unwrap(); // sparse: no disk used
    let e = Scene::load(&big).unwrap_err();
    assert!(e.message().contains("more than the 16 MiB"), "{e}");
    #[cfg(unix)]
    {
        let e = Scene::load("/dev/zero").unwrap_err();
        assert!(e.message().contains("a character device"), "{e}");
        let fifo = dir.path().join("fifo.toml");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            // Opening a FIFO would block until a writer comes: never opened.
            let e = Scene::load(&fifo).unwrap_err();
            assert!(e.message().contains("named pipe"), "{e}");
        }
    }
}
