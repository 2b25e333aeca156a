//! `harness simulate` through the real binary: the README's example scene
//! (which must stay the file in `scenes/examples/`) writes its CSV, SVG and
//! GIF, `--compare rapier` prints the differences, and the other examples
//! and the `[linear_test]` scene run.

mod common;
use common::{harness, workspace};

const README: &str = include_str!("../../README.md");
const EXAMPLE: &str = include_str!("../../scenes/examples/thrown_plate.toml");
const EXAMPLE_PATH: &str = "scenes/examples/thrown_plate.toml";

/// The first ```toml block of the README's "Write your own scene" section.
fn readme_example() -> &'static str {
    let section = README
        .split("## Write your own scene")
        .nth(1)
        .expect("the README has a \"Write your own scene\" section");
    let start = section.find("```toml\n").expect("a toml block") + "```toml\n".len();
    let end = section[start..].find("```").expect("the block ends") + start;
    &section[start..end]
}

#[test]
fn the_readme_example_is_the_example_file() {
    assert_eq!(
        readme_example(),
        EXAMPLE,
        "README.md's example and {EXAMPLE_PATH} differ: keep them identical"
    );
    let command = format!(
        "cargo run --release -p harness -- simulate {EXAMPLE_PATH} --svg out.svg --gif out.gif --trace out.csv"
    );
    assert!(README.contains(&command), "the README lacks `{command}`");
}

#[test]
fn the_readme_example_writes_its_trace_and_pictures_and_compares_with_rapier() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = workspace().join(EXAMPLE_PATH);
    let scene = scene.to_str().expect("utf-8 path");
    let done = harness(
        dir.path(),
        &[
            "simulate",
            scene,
            "--svg",
            "out.svg",
            "--gif",
            "out.gif",
            "--trace",
            "out.csv",
            "--compare",
            "rapier",
            "--verbose",
        ],
    );
    assert_eq!(done.code, Some(0), "stderr:\n{}", done.stderr);
    assert!(!done.stderr.contains("panicked"), "{}", done.stderr);
    for needle in [
        "ended by the landing event",
        "apex",
        "landing",
        "final state:",
        "rapier2d-f64 0.36.1 against the engine",
        "x (m)",
        "omega (rad/s)",
        "rapier2d-f64 configuration:",
        "num_solver_iterations",
        "wrote out.csv",
        "wrote out.svg",
        "wrote out.gif",
    ] {
        assert!(
            done.stdout.contains(needle),
            "stdout lacks {needle:?}:\n{}",
            done.stdout
        );
    }

    let csv = std::fs::read_to_string(dir.path().join("out.csv")).expect("out.csv");
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("t,body,x,y,angle,vx,vy,omega,energy"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert!(rows.len() > 300, "{} rows", rows.len());
    assert_eq!(
        rows[0],
        [
            "0.0",
            "plate",
            "0.0",
            "0.5",
            "0.0",
            "12.5",
            "21.650635094610966",
            "2.0",
            rows[0][8]
        ]
    );
    for row in &rows {
        assert_eq!(row.len(), 9);
        assert_eq!(row[1], "plate");
        for field in [
            &row[0], &row[2], &row[3], &row[4], &row[5], &row[6], &row[7], &row[8],
        ] {
            let v: f64 = field.parse().expect("a number");
            assert!(v.is_finite());
        }
    }
    let last_y: f64 = rows.last().unwrap()[3].parse().unwrap();
    assert!(
        last_y.abs() < 1e-9,
        "the run ends at the landing, y = {last_y}"
    );

    let svg = std::fs::read_to_string(dir.path().join("out.svg")).expect("out.svg");
    assert!(svg.starts_with("<svg"), "not an SVG");
    assert!(
        svg.contains("thrown_plate.toml") && svg.contains("#D62728"),
        "no title or plate colour"
    );
    let gif = std::fs::read(dir.path().join("out.gif")).expect("out.gif");
    assert_eq!(&gif[..6], b"GIF89a");
    assert!(gif.len() < 1 << 20, "GIF of {} bytes", gif.len());
}

#[test]
fn the_scene_is_run_with_the_command_line_overrides() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = workspace().join(EXAMPLE_PATH);
    let done = harness(
        dir.path(),
        &[
            "simulate",
            scene.to_str().unwrap(),
            "--method",
            "velocity_verlet",
            "--dt",
            "0.05",
            "--until",
            "1",
            "--trace",
            "short.csv",
        ],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    assert!(
        done.stdout
            .contains("velocity_verlet, dt = 0.05 s, until 1 s (20 steps)"),
        "{}",
        done.stdout
    );
    let csv = std::fs::read_to_string(dir.path().join("short.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 21);
    assert!(csv.lines().last().unwrap().starts_with("1.0,plate,"));
}

#[test]
fn the_comparison_refuses_what_an_adapter_cannot_represent_naming_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let pendulum = workspace().join("scenes/examples/elastic_pendulum.toml");
    // Box2D collides every pair, and contacts are off in this scene: asked
    // alone, it is refused with the reason.
    let done = harness(
        dir.path(),
        &[
            "simulate",
            pendulum.to_str().unwrap(),
            "--compare",
            "box2d",
            "--svg",
            "p.svg",
        ],
    );
    assert_eq!(done.code, Some(2), "{}", done.stdout);
    assert!(done.stderr.contains("--compare box2d"), "{}", done.stderr);
    assert!(done.stderr.contains("contacts are off"), "{}", done.stderr);
    assert!(!done.stderr.contains("panicked"));
    assert!(!dir.path().join("p.svg").exists());
    // Asked with rapier, which takes the scene, rapier runs and Box2D is
    // named with the same reason.
    let done = harness(
        dir.path(),
        &[
            "simulate",
            pendulum.to_str().unwrap(),
            "--compare",
            "rapier,box2d",
        ],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    assert!(
        done.stdout.contains("not compared: --compare box2d:")
            && done.stdout.contains("contacts are off"),
        "{}",
        done.stdout
    );
    assert!(
        done.stdout.contains("rapier2d-f64 0.36") && done.stdout.contains("against the engine"),
        "{}",
        done.stdout
    );
    // A force the adapter does not take is named as the scene says it.
    let text = std::fs::read_to_string(&pendulum).unwrap().replace(
        "type = \"spring\"\n",
        "type = \"spring\"\nwindow = [0.0, 1.0]\n",
    );
    std::fs::write(dir.path().join("windowed.toml"), text).unwrap();
    let done = harness(
        dir.path(),
        &["simulate", "windowed.toml", "--compare", "rapier"],
    );
    assert_eq!(done.code, Some(2), "{}", done.stdout);
    assert!(
        done.stderr
            .contains("forces[1] (spring on 'ball' to an anchor with a window [0, 1] s) is not supported by the rapier adapter"),
        "{}",
        done.stderr
    );
    assert!(
        !done.stderr.contains("Spring {"),
        "no Debug dump: {}",
        done.stderr
    );
}

/// The rows of a comparison's table: quantity, max |diff| and body.
fn comparison_rows(stdout: &str, engine: &str) -> Vec<(String, f64, String)> {
    let section = stdout
        .split(&format!("{engine} against the engine"))
        .nth(1)
        .unwrap_or_else(|| panic!("no {engine} comparison:\n{stdout}"));
    section
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("quantity"))
        .skip(1)
        .take_while(|l| l.contains(" (m") || l.contains(" (rad"))
        .map(|l| {
            let (name, rest) = l
                .trim_start()
                .split_at(l.trim_start().find(')').unwrap() + 1);
            let mut fields = rest.split_whitespace();
            let diff = fields.next().unwrap().parse().unwrap();
            (name.to_owned(), diff, fields.next().unwrap().to_owned())
        })
        .collect()
}

#[test]
fn a_pendulum_with_a_static_bar_is_compared_with_rapier_in_short_numbers() {
    let dir = tempfile::tempdir().expect("temp dir");
    let pendulum = workspace().join("scenes/examples/elastic_pendulum.toml");
    let done = harness(
        dir.path(),
        &[
            "simulate",
            pendulum.to_str().unwrap(),
            "--compare",
            "rapier",
            "--until",
            "2",
        ],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    assert!(
        done.stdout.contains(
            "rapier2d-f64 0.36.1 against the engine, t in [0, 2] s (400 steps of 0.005 s; 4 substeps):"
        ),
        "{}",
        done.stdout
    );
    assert!(
        done.stdout.contains("the static body never moves"),
        "{}",
        done.stdout
    );
    // The configuration paragraph only with --verbose.
    assert!(
        !done.stdout.contains("num_solver_iterations"),
        "{}",
        done.stdout
    );
    assert!(
        done.stdout.contains("--verbose prints how"),
        "{}",
        done.stdout
    );
    let rows = comparison_rows(&done.stdout, "rapier2d-f64 0.36.1");
    assert_eq!(rows.len(), 6, "{rows:?}");
    // Only the moving ball is compared; the two integrators differ
    // (velocity Verlet against rapier's symplectic Euler with the force
    // held over the step), but both follow the same pendulum: within a
    // few centimetres over 2 s, far below its 1 m swing.
    for (name, diff, body) in &rows {
        assert_eq!(body, "ball", "{name}");
        assert!(diff.is_finite(), "{name}");
    }
    assert!(rows[0].1 > 0.0 && rows[0].1 < 0.1, "{rows:?}");
}

#[test]
fn a_collision_scene_is_compared_with_rapier_and_box2d() {
    let dir = tempfile::tempdir().expect("temp dir");
    let head_on = workspace().join("scenes/collision_head_on.toml");
    let done = harness(
        dir.path(),
        &[
            "simulate",
            head_on.to_str().unwrap(),
            "--compare",
            "rapier,box2d",
            "--html",
            "head_on.html",
        ],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    for engine in ["rapier2d-f64 0.36.1", "Box2D 3.2 (boxdd 0.6)"] {
        let rows = comparison_rows(&done.stdout, engine);
        assert_eq!(rows.len(), 6, "{engine}: {rows:?}");
        // Both engines end with the discs apart at their exchanged speeds
        // (e = 1: -1 and +1 m/s); an impact located a step later or
        // earlier moves a disc by at most (2 - (-1)) m/s × 0.01 s = 3 cm.
        assert!(rows[0].1 <= 0.03 + 1e-9, "{engine}: {rows:?}");
        // Nothing moves off the x axis.
        assert_eq!(rows[1].1, 0.0, "{engine}: {rows:?}");
    }
    // The replay holds the three runs.
    let html = std::fs::read_to_string(dir.path().join("head_on.html")).unwrap();
    for label in [
        "this engine (rk4",
        "rapier2d-f64 0.36.1 (4 substeps",
        "Box2D 3.2 (boxdd 0.6) (4 substeps",
    ] {
        assert!(html.contains(label), "no run {label:?} in the page");
    }
}

#[test]
fn a_soft_step_pile_is_compared_with_rapier_and_box2d() {
    // Three boxes at rest on a static ground under the soft step, 1 s.
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = "[simulation]\ndt = 0.016666666666666666\nduration = 1.0\ngravity = [0.0, -10.0]\n\
                 [contact]\nfriction = 0.6\n\
                 [[bodies]]\nname = \"ground\"\nkind = \"static\"\nshape = { type = \"box\", width = 20.0, height = 1.0 }\nposition = [0.0, -0.5]\n\
                 [[generate]]\ntype = \"pyramid\"\nbase = 2\nbox_size = 1.0\n";
    std::fs::write(dir.path().join("pile.toml"), scene).unwrap();
    let done = harness(
        dir.path(),
        &[
            "simulate",
            "pile.toml",
            "--compare",
            "rapier",
            "--compare",
            "box2d",
        ],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    for engine in ["rapier2d-f64 0.36.1", "Box2D 3.2 (boxdd 0.6)"] {
        let rows = comparison_rows(&done.stdout, engine);
        assert_eq!(rows.len(), 6, "{engine}: {rows:?}");
        // Every engine's soft contacts let a resting box sink by about
        // g/(2π f)² (0.07 mm on the ground at 60 Hz, 0.28 mm between
        // boxes at 30 Hz): resting poses differ by a fraction of a
        // millimetre; 1 mm bounds it.
        assert!(rows[1].1 < 1e-3, "{engine}: {rows:?}");
        assert!(rows[1].2.starts_with("pyramid_"), "{engine}: {rows:?}");
    }
}

#[test]
fn a_jointed_scene_is_compared_with_rapier_and_box2d() {
    // The chain example: 20 links on 21 revolute joints between two world
    // anchors 8 m apart, a ball dropped into it, 5 s.
    let dir = tempfile::tempdir().expect("temp dir");
    let chain = workspace().join("scenes/examples/chain.toml");
    let done = harness(
        dir.path(),
        &[
            "simulate",
            chain.to_str().unwrap(),
            "--compare",
            "rapier,box2d",
        ],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    for engine in ["rapier2d-f64 0.36.1", "Box2D 3.2 (boxdd 0.6)"] {
        assert!(
            done.stdout.contains(&format!(
                "{engine} against the engine, t in [0, 5] s (300 steps"
            )),
            "{}",
            done.stdout
        );
        let rows = comparison_rows(&done.stdout, engine);
        assert_eq!(rows.len(), 6, "{engine}: {rows:?}");
        // Every point of a 10 m chain hung from anchors 8 m apart lies in
        // the ellipse with those foci and major axis 10 m: within
        // √(5² − 4²) = 3 m of the anchors' height, and the ball rests in
        // it; so two engines that both hold the joints differ by at most
        // 6 m in y. A chain whose joints were lost in the conversion would
        // fall freely, ½ g t² = 123 m in 5 s.
        assert!(rows[1].1 <= 6.0, "{engine}: {rows:?}");
    }
    assert_eq!(
        done.stdout.matches("21 joints converted").count(),
        2,
        "{}",
        done.stdout
    );
}

#[test]
fn box2ds_card_house_is_compared_with_box2d() {
    // Box2D's own Card House sample: 40 cards 2 mm thick. Box2D's hull
    // welds points closer than 5 mm and would refuse them; the adapter
    // builds each card with Box2D's box constructor, as the sample does.
    let dir = tempfile::tempdir().expect("temp dir");
    let cards = workspace().join("scenes/card_house.toml");
    let done = harness(
        dir.path(),
        &["simulate", cards.to_str().unwrap(), "--compare", "box2d"],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    let rows = comparison_rows(&done.stdout, "Box2D 3.2 (boxdd 0.6)");
    assert_eq!(rows.len(), 6, "{rows:?}");
    assert!(rows.iter().all(|r| r.2.starts_with("card_")), "{rows:?}");
    // The house stands in both engines for the 4 s: their cards settle
    // differently by millimetres, while a falling house moves its cards
    // by a good part of their 0.4 m height; 2 cm tells the two apart.
    assert!(rows[0].1 < 0.02 && rows[1].1 < 0.02, "{rows:?}");
}

#[test]
fn a_target_joint_is_not_compared_and_is_named() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = "[simulation]\ndt = 0.01\nduration = 0.1\n\n[[bodies]]\nname = \"bob\"\nmass = 1.0\nshape = { type = \"circle\", radius = 0.1 }\nposition = [1.0, 0.0]\n\n[[joints]]\ntype = \"target\"\nname = \"hand\"\nbody = \"bob\"\nmax_force = 10.0\ntarget = [2.0, 0.0]\n";
    std::fs::write(dir.path().join("bob.toml"), scene).unwrap();
    for engine in ["rapier", "box2d"] {
        let done = harness(dir.path(), &["simulate", "bob.toml", "--compare", engine]);
        assert_eq!(done.code, Some(2), "{}", done.stdout);
        assert!(
            done.stderr.contains("joint 'hand': a target joint"),
            "{}",
            done.stderr
        );
        assert!(!done.stderr.contains("panicked"), "{}", done.stderr);
    }
}

#[test]
fn a_linear_test_scene_gives_its_curve_and_refuses_an_animation() {
    let dir = tempfile::tempdir().expect("temp dir");
    let hoffman = workspace().join("scenes/hoffman.toml");
    let hoffman = hoffman.to_str().unwrap();
    let done = harness(
        dir.path(),
        &["simulate", hoffman, "--svg", "h.svg", "--trace", "h.csv"],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    assert!(done.stdout.contains("exact"), "{}", done.stdout);
    let csv = std::fs::read_to_string(dir.path().join("h.csv")).unwrap();
    assert!(csv.starts_with("t,y,exact,error\n"));
    assert!(
        std::fs::read_to_string(dir.path().join("h.svg"))
            .unwrap()
            .starts_with("<svg")
    );

    let done = harness(dir.path(), &["simulate", hoffman, "--gif", "h.gif"]);
    assert_eq!(done.code, Some(2));
    assert!(
        done.stderr.contains("no bodies to animate"),
        "{}",
        done.stderr
    );
    let done = harness(
        dir.path(),
        &["simulate", hoffman, "--method", "velocity_verlet"],
    );
    assert_eq!(done.code, Some(2));
    assert!(done.stderr.contains("first order"), "{}", done.stderr);
}

#[test]
fn every_example_scene_loads_and_runs() {
    let dir = workspace().join("scenes/examples");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).expect("scenes/examples") {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let scene = scene::Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let mut world = scene.build_world(None).unwrap_or_else(|e| panic!("{e}"));
        let trace = world
            .run(scene.duration(), scene.dt())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(trace.samples.len() > 10, "{}", path.display());
        count += 1;
    }
    assert!(count >= 3, "{count} examples");
}

#[test]
fn a_long_run_draws_no_progress_bar_when_stderr_is_not_a_terminal() {
    // 300 000 steps: above the bar's threshold (200 000), cheap (a free
    // particle); the trace keeps 101 samples.
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = "[simulation]\nmethod = \"explicit_euler\"\ndt = 1e-5\nduration = 3.0\n\
                 [[bodies]]\nname = \"p\"\nmass = 1.0\nvelocity = [1.0, 0.0]\n";
    std::fs::write(dir.path().join("long.toml"), scene).unwrap();
    let done = harness(
        dir.path(),
        &[
            "simulate",
            "long.toml",
            "--trace",
            "long.csv",
            "--max-samples",
            "101",
        ],
    );
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    assert_eq!(done.stderr, "", "stderr should stay empty");
    assert!(done.stdout.contains("300000 steps"), "{}", done.stdout);
    assert!(
        done.stdout.contains("101 samples, every 3000th step"),
        "{}",
        done.stdout
    );
    let csv = std::fs::read_to_string(dir.path().join("long.csv")).unwrap();
    assert_eq!(csv.lines().count(), 102);
}

/// A scene's contact model is printed with its settings, and a pile's
/// final state is a summary, not a line per body. A pyramid of base 4 (10
/// boxes) plus its ground lists its 11 bodies; one of base 5 (15 boxes) is
/// summarised.
#[test]
fn the_contact_model_is_printed_and_a_pile_is_summarised() {
    let temp = tempfile::tempdir().expect("temp dir");
    let dir = temp.path().to_path_buf();
    for (base, listed) in [(4, true), (5, false)] {
        let scene = dir.join(format!("pyramid_{base}.toml"));
        std::fs::write(
            &scene,
            format!(
                "[simulation]\ndt = 0.0166666666666666666\nduration = 0.1\ngravity = [0.0, -10.0]\n\
                 [contact]\nmodel = \"soft_step\"\n\
                 [[bodies]]\nname = \"ground\"\nkind = \"static\"\nshape = {{ type = \"box\", width = 20.0, height = 1.0 }}\nposition = [0.0, -0.5]\n\
                 [[generate]]\ntype = \"pyramid\"\nbase = {base}\nbox_size = 1.0\ndensity = 1.0\n"
            ),
        )
        .unwrap();
        let done = harness(&dir, &["simulate", scene.to_str().unwrap()]);
        assert_eq!(done.code, Some(0), "{}", done.stderr);
        assert!(
            done.stdout
                .contains("dt = 0.0166667 s, until 0.1 s (6 steps)"),
            "{}",
            done.stdout
        );
        assert!(
            done.stdout
                .contains("contacts: soft_step (4 substeps, contact 30 Hz, damping ratio 10,"),
            "{}",
            done.stdout
        );
        let per_body_lines = done.stdout.lines().filter(|l| l.contains(": x = ")).count();
        if listed {
            assert_eq!(per_body_lines, 11, "{}", done.stdout);
        } else {
            assert_eq!(per_body_lines, 0, "{}", done.stdout);
            assert!(
                done.stdout
                    .contains("final state of 16 bodies (15 dynamic; every body's state: --trace)"),
                "{}",
                done.stdout
            );
            assert!(
                done.stdout.contains("  fastest: pyramid_"),
                "{}",
                done.stdout
            );
        }
    }
}

/// A box that falls through a ground because the scene has no `[contact]`
/// table is warned about (on stderr, naming both bodies and the fix); with
/// `[contact]` it lands and nothing is said.
#[test]
fn overlapping_shapes_without_contacts_are_warned_about() {
    let temp = tempfile::tempdir().expect("temp dir");
    let body = "[simulation]\ndt = 0.01\nduration = 2.0\n\
        [[bodies]]\nname = \"ground\"\nkind = \"static\"\nshape = { type = \"box\", width = 10.0, height = 1.0 }\nposition = [0.0, -0.5]\n\
        [[bodies]]\nname = \"box\"\nmass = 1.0\nshape = { type = \"box\", width = 1.0, height = 1.0 }\nposition = [0.0, 3.0]\n\
        [[forces]]\ntype = \"gravity\"\ng = [0.0, -9.81]\n";
    for (contacts, warned) in [("", true), ("[contact]\n", false)] {
        let scene = temp.path().join("fall.toml");
        std::fs::write(&scene, format!("{contacts}{body}")).unwrap();
        let done = harness(temp.path(), &["simulate", scene.to_str().unwrap()]);
        assert_eq!(done.code, Some(0), "{}", done.stderr);
        let warning = "bodies 'ground' and 'box' overlap at t = ";
        assert_eq!(done.stderr.contains(warning), warned, "{}", done.stderr);
        if warned {
            assert!(
                done.stderr.contains("but contacts are off")
                    && done.stderr.contains("add `[contact]`"),
                "{}",
                done.stderr
            );
        }
    }
}

#[test]
fn a_jointed_scene_prints_its_model_and_joints_and_draws_them() {
    let dir = tempfile::tempdir().expect("temp dir");
    let pendulum = workspace().join("scenes/examples/pendulum.toml");
    let pendulum = pendulum.to_str().expect("a UTF-8 path");
    let done = harness(dir.path(), &["simulate", pendulum, "--svg", "out.svg"]);
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    assert!(
        done.stdout
            .contains("(360 steps)\ncontacts: soft_step (4 substeps,"),
        "{}",
        done.stdout
    );
    assert!(
        done.stdout.contains("sleeping off); 2 joints\n"),
        "{}",
        done.stdout
    );
    // Each joint is drawn with a dot at each anchor: 2 joints, 2 anchors,
    // in each of the filmstrip's 6 frames.
    let svg = std::fs::read_to_string(dir.path().join("out.svg")).expect("the SVG");
    let dots = svg
        .matches("r=\"2\" opacity=\"1\" fill=\"#464646\"")
        .count();
    assert_eq!(dots, 6 * 2 * 2, "joint anchors drawn");
}

#[test]
fn the_falling_hinges_trace_is_the_same_bytes_on_one_and_two_threads() {
    // The soft step's parallel stages give the serial stages' bits
    // (docs/soft_step.md, "Threads"): the traces are compared byte for
    // byte, over 2 s (the boxes land, the hinges swing and collide).
    let dir = tempfile::tempdir().unwrap();
    let scene = workspace().join("scenes/falling_hinges.toml");
    let scene = scene.to_str().unwrap();
    let mut traces = Vec::new();
    for threads in ["1", "2"] {
        let trace = dir.path().join(format!("trace_{threads}.csv"));
        let done = harness(
            dir.path(),
            &[
                "simulate",
                scene,
                "--until",
                "2",
                "--threads",
                threads,
                "--trace",
                trace.to_str().unwrap(),
            ],
        );
        assert_eq!(done.code, Some(0), "{}\n{}", done.stdout, done.stderr);
        traces.push(std::fs::read(&trace).unwrap());
    }
    assert!(traces[0].len() > 10_000, "a trace of every body and step");
    assert!(
        traces[0] == traces[1],
        "the traces on 1 and 2 threads differ"
    );
    // A count of 0 is refused with the flag named.
    let done = harness(dir.path(), &["simulate", scene, "--threads", "0"]);
    assert_ne!(done.code, Some(0));
    assert!(done.stderr.contains("--threads"), "{}", done.stderr);
}
