//! The scene files of `scenes/` load, build, and reproduce docs/cases.md.

use engine::{Method, Tolerance};
use scene::{Colour, Scene};
use std::path::PathBuf;

fn scenes_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

fn load(name: &str) -> Scene {
    let path = scenes_dir().join(name);
    Scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_scene_file_loads_and_builds() {
    let mut names: Vec<String> = std::fs::read_dir(scenes_dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    for expected in [
        "angular_drag.toml",
        "hoffman.toml",
        "projectile.toml",
        "projectile_drag.toml",
        "spring.toml",
        "torque.toml",
    ] {
        assert!(names.iter().any(|n| n == expected), "missing {expected}");
    }
    for name in &names {
        let scene = load(name);
        if scene.is_linear_test() {
            assert!(scene.build_world(None).is_err(), "{name}");
            let test = scene.linear_test().unwrap();
            test.solve(scene.method(), scene.dt(), scene.duration())
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        } else {
            let world = scene
                .build_world(None)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(world.bodies().len(), scene.body_names().len(), "{name}");
            assert_eq!(scene.colours().len(), scene.body_names().len(), "{name}");
        }
    }
}

#[test]
fn spring_rk4_reproduces_the_seed_run() {
    // docs/cases.md case I: RK4, h = 0.2 s, 286 steps: x(57.2) = 10.95756 m.
    let scene = load("spring.toml");
    assert_eq!(scene.method(), Method::Rk4);
    assert_eq!(scene.steps(), 286);
    let mut world = scene.build_world(None).unwrap();
    let trace = world.run(scene.duration(), scene.dt()).unwrap();
    let id = scene.body_id("mass").unwrap();
    let last = trace.last().unwrap();
    assert_eq!(last.t, 57.2);
    let x = last.states[id].position.x;
    assert!((x - 10.95756).abs() < 1e-4, "x(57.2) = {x}");
    assert_eq!(trace.samples.len(), 287);
    assert!(world.bodies()[id].inertia.is_none(), "a particle");
    assert_eq!(scene.colour_of("mass"), Some(Colour::PALETTE[0]));
}

#[test]
fn spring_builds_with_every_method_override() {
    let scene = load("spring.toml");
    let methods = Method::FIXED_STEP
        .into_iter()
        .chain([Method::DormandPrince(scene.tolerance())]);
    for method in methods {
        let mut world = scene.build_world(Some(method)).unwrap();
        assert_eq!(world.method(), method);
        world.step(0.2).unwrap();
    }
}

#[test]
fn projectile_lands_and_peaks_where_cases_md_says() {
    let scene = load("projectile.toml");
    let mut world = scene.build_world(None).unwrap();
    let trace = world.run(scene.duration(), scene.dt()).unwrap();
    let event = |name: &str| trace.events.iter().find(|e| e.name == name).unwrap();
    let landing = event("landing");
    assert!((landing.t - 8.652667222).abs() < 1e-8, "{}", landing.t);
    assert!((landing.states[0].position.x - 367.1015801).abs() < 1e-6);
    let apex = event("apex");
    assert!((apex.t - 4.326333611).abs() < 1e-8, "{}", apex.t);
    assert!((apex.states[0].position.y - 91.77539502).abs() < 1e-7);
    assert!(world.is_stopped());
    // The box: I = m (b² + h²)/12 = 5e-4 kg·m².
    let inertia = world.bodies()[0].inertia.unwrap();
    assert!((inertia - 5e-4).abs() < 1e-15, "{inertia}");
}

#[test]
fn torque_spins_the_box_in_place() {
    // docs/cases.md: theta(0.7) = 2.45 rad, theta(8.7) = 58.45 rad, omega 7 rad/s.
    let scene = load("torque.toml");
    let mut world = scene.build_world(None).unwrap();
    let trace = world.run(scene.duration(), scene.dt()).unwrap();
    let at = |t: f64| {
        trace
            .samples
            .iter()
            .find(|s| (s.t - t).abs() < 1e-9)
            .unwrap()
            .states[0]
    };
    assert!((at(0.7).angle - 2.45).abs() < 1e-9, "{}", at(0.7).angle);
    let end = at(8.7);
    assert!((end.angle - 58.45).abs() < 1e-9, "{}", end.angle);
    assert!((end.angular_velocity - 7.0).abs() < 1e-12);
    assert_eq!(end.position.norm(), 0.0, "rotation only: the box stays put");
    assert_eq!(end.velocity.norm(), 0.0);
}

#[test]
fn projectile_drag_matches_the_reference() {
    let scene = load("projectile_drag.toml");
    let mut world = scene.build_world(None).unwrap();
    let trace = world.run(scene.duration(), scene.dt()).unwrap();
    let landing = trace.events.iter().find(|e| e.name == "landing").unwrap();
    assert!((landing.t - 5.854653263330).abs() < 1e-7, "{}", landing.t);
    assert!((landing.states[0].position.x - 113.8638433141).abs() < 1e-6);
    let apex = trace.events.iter().find(|e| e.name == "apex").unwrap();
    assert!((apex.states[0].position.y - 43.00523490712).abs() < 1e-6);
}

#[test]
fn angular_drag_matches_the_closed_form() {
    let scene = load("angular_drag.toml");
    let mut world = scene.build_world(None).unwrap();
    let trace = world.run(scene.duration(), scene.dt()).unwrap();
    let end = trace.last().unwrap().states[0];
    assert!((end.angle - 1.478605506).abs() < 1e-6, "{}", end.angle);
    assert!((end.angular_velocity - 0.02050246334).abs() < 1e-8);
    assert_eq!(end.position.norm(), 0.0);
}

#[test]
fn hoffman_is_the_seed_stiff_test() {
    let scene = load("hoffman.toml");
    assert_eq!(scene.method(), Method::ExplicitEuler);
    assert_eq!(scene.dt(), 0.0019);
    let test = scene.linear_test().unwrap();
    assert_eq!(test, scene::LinearTest::hoffman());
    // Explicit Euler just inside h <= 0.002: stable, close to the exact line.
    let s = test
        .solve(scene.method(), scene.dt(), scene.duration())
        .unwrap();
    assert_eq!(*s.t.last().unwrap(), 1.0);
    let y = s.y.last().unwrap()[0];
    assert!((y - test.exact(1.0)).abs() < 1e-2, "{y}");
    // Just outside, at 0.0021 s, it grows without bound (docs/cases.md: ~-5e19).
    let s = test
        .solve(Method::ExplicitEuler, 0.0021, scene.duration())
        .unwrap();
    assert!(s.y.last().unwrap()[0].abs() > 1e15);
    // The adaptive method with the scene's tolerance follows it closely.
    let dp = Method::DormandPrince(Tolerance::uniform(1e-10));
    let s = test.solve(dp, scene.dt(), scene.duration()).unwrap();
    assert!((s.y.last().unwrap()[0] - test.exact(1.0)).abs() < 1e-8);
}

#[test]
fn static_bodies_default_to_grey_and_the_palette_counts_moving_bodies() {
    let text = "[simulation]\ndt = 0.01\nduration = 1.0\n\
                [[bodies]]\nname = \"ground\"\nkind = \"static\"\nshape = { type = \"box\", width = 4.0, height = 1.0 }\n\
                [[bodies]]\nname = \"a\"\nmass = 1.0\n\
                [[bodies]]\nname = \"b\"\nmass = 1.0\n\
                [[bodies]]\nname = \"pin\"\nkind = \"static\"\ncolour = \"#123456\"\n";
    let scene = Scene::parse_str("colours.toml", text).unwrap();
    assert_eq!(scene.colour_of("ground"), Some(Colour::STATIC));
    // The ground does not shift the cycle: the first body that moves is
    // the palette's first colour, and no moving body is grey.
    assert_eq!(scene.colour_of("a"), Some(Colour::PALETTE[0]));
    assert_eq!(scene.colour_of("b"), Some(Colour::PALETTE[1]));
    assert_eq!(scene.colour_of("pin"), Some(Colour::rgb(0x12, 0x34, 0x56)));
    assert!(!Colour::PALETTE.contains(&Colour::STATIC));
}
