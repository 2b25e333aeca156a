//! The generators of the jointed benchmarks (`scenes/bench/joint_grid.toml`,
//! `scenes/bench/ragdoll_rain.toml`): the joint grid, a static grid (the
//! rain's tiles) and ragdolls sharing collision groups; the bench files
//! load with their counts, and every bad value is a located error.

use engine::BodyKind;
use scene::{ErrorKind, Scene, SceneError};
use std::path::PathBuf;

fn scenes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

/// Lines 1–3 `[simulation]`, 5 `[[generate]]`, 6 its type, then `extra`
/// from line 7.
fn generator(kind: &str, extra: &str) -> String {
    format!("[simulation]\ndt = 0.01\nduration = 1.0\n\n[[generate]]\ntype = \"{kind}\"\n{extra}")
}

fn error(text: &str) -> SceneError {
    match Scene::parse_str("bad.toml", text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

#[track_caller]
fn check(e: &SceneError, field: &str, line: usize, words: &str) {
    assert_eq!(e.kind(), ErrorKind::InvalidValue, "{e}");
    assert_eq!(e.field(), Some(field), "{e}");
    assert_eq!(e.line(), Some(line), "{e}");
    assert!(
        e.to_string().starts_with(&format!("bad.toml:{line}:")),
        "{e}"
    );
    assert!(
        e.message().contains(words),
        "'{}' lacks '{words}'",
        e.message()
    );
}

#[test]
fn the_bench_files_load_with_their_bodies_and_joints() {
    for (file, bodies, joints) in [
        // 60 × 60 circles; 60 × 59 vertical and 59 × 60 horizontal joints
        // less the 6 between the 7 static circles.
        ("bench/joint_grid.toml", 3600, 2 * 60 * 59 - 6),
        ("bench/full/joint_grid.toml", 10_000, 2 * 100 * 99 - 6),
        // 201 tiles, two walls of 40 tiles, 200 ragdolls of 11 bones and
        // 10 joints.
        ("bench/ragdoll_rain.toml", 201 + 2 * 40 + 200 * 11, 200 * 10),
        (
            "bench/full/ragdoll_rain.toml",
            5 * 501 + 1000 * 11,
            1000 * 10,
        ),
    ] {
        let scene = Scene::load(scenes().join(file)).unwrap();
        assert_eq!(
            (scene.bodies().len(), scene.joint_count()),
            (bodies, joints),
            "{file}"
        );
        assert!(matches!(
            scene.contact(),
            Some(engine::ContactModel::SoftStep(_))
        ));
    }
}

#[test]
fn a_static_grid_is_grey_tiles_and_a_joint_grid_hangs_from_grey_circles() {
    let text = format!(
        "{}\n[[generate]]\ntype = \"grid\"\nname = \"tile\"\nkind = \"static\"\nrows = 1\ncolumns = 3\nspacing = [0.5, 1.0]\nsize = [0.5, 0.5]\nrandom_angle = false\n\n[contact]\n",
        generator("joint_grid", "columns = 9\nrows = 2\n")
    );
    let scene = Scene::parse_str("ok.toml", &text).unwrap();
    let kinds: Vec<BodyKind> = scene.bodies().iter().map(|b| b.kind).collect();
    // Column k, row i is body 2k + i: the top row's middle 7 (k = 1 … 7)
    // are static; then the 3 tiles.
    let fixed: Vec<usize> = (0..kinds.len())
        .filter(|&i| kinds[i] == BodyKind::Static)
        .collect();
    assert_eq!(fixed, vec![2, 4, 6, 8, 10, 12, 14, 18, 19, 20]);
    let grey = scene::Colour::STATIC;
    for (i, colour) in scene.colours().iter().enumerate() {
        assert_eq!(*colour == grey, fixed.contains(&i), "body {i}");
    }
    // 9 vertical and 8 × 2 horizontal pairs, less the 6 between static
    // circles.
    assert_eq!(scene.joint_count(), 9 + 16 - 6);
    let tiles = &scene.bodies()[18..];
    assert!(
        tiles
            .iter()
            .all(|b| b.state.angle == 0.0 && b.density.is_none())
    );
    assert_eq!(tiles[2].state.position.x, 1.0);
}

#[test]
fn ragdolls_share_their_collision_groups_without_neighbours_in_one() {
    let scene = Scene::parse_str(
        "ok.toml",
        &generator(
            "ragdoll",
            "repeat = [6, 3]\nrepeat_spacing = [1.0, 2.0]\ncollision_groups = 5\n",
        ),
    )
    .unwrap();
    let group = |c: usize, r: usize| scene.bodies()[11 * (6 * r + c)].collision_group();
    let mut groups: Vec<_> = (0..6)
        .flat_map(|c| (0..3).map(move |r| (c, r)))
        .map(|(c, r)| group(c, r))
        .collect();
    for c in 0..6 {
        for r in 0..3 {
            // Every bone of a ragdoll in its group.
            let first = 11 * (6 * r + c);
            assert!(
                scene.bodies()[first..first + 11]
                    .iter()
                    .all(|b| b.collision_group() == group(c, r))
            );
            // No neighbour (side by side, above, diagonal) in the same one.
            for (dc, dr) in [(1, 0), (0, 1), (1, 1), (-1, 1)] {
                let (c2, r2) = (c as i64 + dc, r as i64 + dr);
                if (0..6).contains(&c2) && (0..3).contains(&r2) {
                    assert_ne!(group(c, r), group(c2 as usize, r2 as usize));
                }
            }
        }
    }
    groups.sort();
    groups.dedup();
    assert_eq!(groups.len(), 5);
}

#[test]
fn bad_joint_grids_static_grids_and_groups_are_located() {
    let e = error(&generator("joint_grid", "columns = 0\nrows = 3\n"));
    check(&e, "generate[0].columns", 7, "between 1");
    let e = error(&generator(
        "joint_grid",
        "columns = 4\nrows = 3\nfixed = 5\n",
    ));
    check(&e, "generate[0].fixed", 9, "from 0 to the 4 columns");
    let e = error(&generator(
        "joint_grid",
        "columns = 4\nrows = 3\nradius = -0.4\n",
    ));
    check(&e, "generate[0].radius", 9, "must be > 0");
    let e = error(&generator(
        "joint_grid",
        "columns = 4\nrows = 3\nspacing = 0.0\n",
    ));
    check(&e, "generate[0].spacing", 9, "must be > 0");
    let e = error(&generator(
        "grid",
        "kind = \"static\"\nrows = 1\ncolumns = 2\nspacing = [1.0, 1.0]\nvelocity = [0.0, -1.0]\n",
    ));
    check(&e, "generate[0].velocity", 11, "never move");
    let e = error(&generator(
        "ragdoll",
        "repeat = [2, 1]\ncollision_groups = 3\n",
    ));
    check(
        &e,
        "generate[0].collision_groups",
        8,
        "at most one per ragdoll",
    );
    let e = error(&generator("ragdoll", "collision_groups = 0\n"));
    check(&e, "generate[0].collision_groups", 7, "between 1");
}
