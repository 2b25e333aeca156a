//! A body's collision filter, sensor flag and material fields (`filter`,
//! `sensor`, `rolling_resistance`, `tangent_speed`) and the `[contact]`
//! mixing rules: read into the engine's definitions, and every bad value a
//! located error.

use engine::{ContactModel, Filter, MixingRule};
use scene::{ErrorKind, Scene, SceneError};

const HEAD: &str = "[simulation]\ndt = 0.01\nduration = 1.0\n\n[contact]\n";

/// A scene with `[contact]` lines `contact` and one box with `extra`
/// lines; the box's name is on line 6 + the number of contact lines.
fn scene(contact: &str, extra: &str) -> String {
    format!(
        "{HEAD}{contact}\n[[bodies]]\nname = \"box\"\nmass = 1.0\nshape = {{ type = \"box\", width = 1.0, height = 1.0 }}\n{extra}"
    )
}

fn error(text: &str) -> SceneError {
    match Scene::parse_str("bad.toml", text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

#[track_caller]
fn check(e: &SceneError, kind: ErrorKind, field: &str, line: usize, words: &str) {
    assert_eq!(e.kind(), kind, "{e}");
    assert_eq!(e.field(), Some(field), "{e}");
    assert_eq!(e.line(), Some(line), "{e}");
    assert!(
        e.to_string().starts_with(&format!("bad.toml:{line}:")),
        "{e}"
    );
    assert!(e.message().contains(words), "{e}");
}

#[test]
fn the_fields_reach_the_body_and_the_settings() {
    let text = scene(
        "friction_mixing = \"max\"\nrestitution_mixing = \"average\"\nrolling_resistance = 0.1\nhit_event_threshold = 2.0\n",
        "filter = { category = 2, mask = 0xFFFF, group = -1 }\nsensor = true\nrolling_resistance = 0.3\ntangent_speed = -1.5\nfriction = 0.4\n",
    );
    let s = Scene::parse_str("ok.toml", &text).unwrap();
    let b = &s.bodies()[0];
    assert_eq!(
        b.filter,
        Filter {
            category: 2,
            mask: 0xFFFF,
            group: -1
        }
    );
    assert!(b.sensor);
    assert_eq!(b.rolling_resistance, Some(0.3));
    assert_eq!(b.tangent_speed, Some(-1.5));
    assert_eq!(b.friction, Some(0.4));
    let Some(ContactModel::SoftStep(settings)) = s.contact() else {
        panic!("soft step expected");
    };
    assert_eq!(settings.friction_mixing, MixingRule::Max);
    assert_eq!(settings.restitution_mixing, MixingRule::Average);
    assert_eq!(settings.rolling_resistance, 0.1);
    assert_eq!(settings.hit_event_threshold, 2.0);
    // The world builds with them.
    s.build_world(None).unwrap();
}

#[test]
fn filter_keys_are_optional_and_default_to_box2d() {
    let s = Scene::parse_str("ok.toml", &scene("", "filter = { group = 3 }\n")).unwrap();
    assert_eq!(
        s.bodies()[0].filter,
        Filter {
            group: 3,
            ..Filter::DEFAULT
        }
    );
}

#[test]
fn bad_filters_are_located() {
    // The box's fields start on line 11 (head 5 lines, no contact lines,
    // a blank, [[bodies]], name, mass, shape).
    let e = error(&scene("", "filter = { category = 0 }\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        "bodies[0].filter.category",
        11,
        "> 0",
    );
    let e = error(&scene("", "filter = { mask = -2 }\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        "bodies[0].filter.mask",
        11,
        ">= 0",
    );
    let e = error(&scene("", "filter = { categry = 2 }\n"));
    assert_eq!(e.kind(), ErrorKind::UnknownField, "{e}");
    assert_eq!(e.line(), Some(11), "{e}");
    let e = error(&scene("", "filter = { group = 1.5 }\n"));
    assert_eq!(e.kind(), ErrorKind::InvalidType, "{e}");
    assert_eq!(e.line(), Some(11), "{e}");
}

#[test]
fn bad_materials_are_located() {
    let e = error(&scene("", "rolling_resistance = -0.1\n"));
    check(
        &e,
        ErrorKind::InvalidValue,
        "bodies[0].rolling_resistance",
        11,
        ">= 0",
    );
    let e = error(&scene("", "tangent_speed = nan\n"));
    check(
        &e,
        ErrorKind::NonFinite,
        "bodies[0].tangent_speed",
        11,
        "finite",
    );
    let e = error(&scene("", "sensor = 1\n"));
    assert_eq!(e.kind(), ErrorKind::InvalidType, "{e}");
    assert_eq!(e.line(), Some(11), "{e}");
    let e = error(&scene("friction_mixing = \"median\"\n", ""));
    assert_eq!(e.kind(), ErrorKind::InvalidType, "{e}");
    assert_eq!(e.line(), Some(6), "{e}");
    let e = error(&scene("hit_event_threshold = -1.0\n", ""));
    check(
        &e,
        ErrorKind::InvalidValue,
        "contact.hit_event_threshold",
        6,
        ">= 0",
    );
}

#[test]
fn the_exact_model_refuses_them_at_their_field() {
    let text = format!(
        "{HEAD}model = \"exact\"\n\n[[bodies]]\nname = \"box\"\nmass = 1.0\nshape = {{ type = \"box\", width = 1.0, height = 1.0 }}\nsensor = true\n"
    );
    let e = error(&text);
    check(
        &e,
        ErrorKind::InvalidValue,
        "bodies[0].sensor",
        12,
        "soft_step",
    );
    let text = format!(
        "{HEAD}model = \"exact\"\nrolling_resistance = 0.2\n\n[[bodies]]\nname = \"b\"\nmass = 1.0\n"
    );
    let e = error(&text);
    check(
        &e,
        ErrorKind::InvalidValue,
        "contact.rolling_resistance",
        7,
        "soft_step",
    );
}
