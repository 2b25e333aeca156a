//! `harness simulate` through the real binary: the README's example scene
//! (which must stay the file in `scenes/examples/`) writes its CSV, SVG and
//! GIF, `--compare rapier` prints the differences, and the other examples
//! and the `[linear_test]` scene run.

use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_harness");
const README: &str = include_str!("../../README.md");
const EXAMPLE: &str = include_str!("../../scenes/examples/thrown_plate.toml");
const EXAMPLE_PATH: &str = "scenes/examples/thrown_plate.toml";

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

struct Done {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

fn harness(dir: &Path, args: &[&str]) -> Done {
    let output = Command::new(BIN)
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run the harness binary");
    Done {
        code: output.status.code(),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

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
        ],
    );
    assert_eq!(done.code, Some(0), "stderr:\n{}", done.stderr);
    assert!(!done.stderr.contains("panicked"), "{}", done.stderr);
    for needle in [
        "ended by the landing event",
        "apex",
        "landing",
        "final state:",
        "rapier2d-f64 against the engine",
        "x (m)",
        "omega (rad/s)",
        "rapier configuration:",
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
fn the_rapier_comparison_refuses_what_rapier_cannot_run() {
    let dir = tempfile::tempdir().expect("temp dir");
    let pendulum = workspace().join("scenes/examples/elastic_pendulum.toml");
    let done = harness(
        dir.path(),
        &[
            "simulate",
            pendulum.to_str().unwrap(),
            "--compare",
            "rapier",
            "--svg",
            "p.svg",
        ],
    );
    assert_eq!(done.code, Some(2), "{}", done.stdout);
    assert!(done.stderr.contains("--compare rapier"), "{}", done.stderr);
    assert!(done.stderr.contains("one dynamic body"), "{}", done.stderr);
    assert!(!done.stderr.contains("panicked"));
    assert!(!dir.path().join("p.svg").exists());
    // One body on a joint: rapier would run it free.
    let scene = "[simulation]\ndt = 0.01\nduration = 0.1\n\n[[bodies]]\nname = \"bob\"\nmass = 1.0\nposition = [1.0, 0.0]\n\n[[joints]]\ntype = \"distance\"\nbody_b = \"bob\"\nanchor_a = [0.0, 0.0]\nanchor_b = [1.0, 0.0]\n";
    std::fs::write(dir.path().join("bob.toml"), scene).unwrap();
    let done = harness(dir.path(), &["simulate", "bob.toml", "--compare", "rapier"]);
    assert_eq!(done.code, Some(2), "{}", done.stdout);
    assert!(done.stderr.contains("has joints"), "{}", done.stderr);
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

#[test]
fn a_jointed_scene_prints_its_model_and_joints_and_draws_them() {
    let dir = tempfile::tempdir().expect("temp dir");
    let pendulum = workspace().join("scenes/examples/pendulum.toml");
    let pendulum = pendulum.to_str().expect("a UTF-8 path");
    let done = harness(dir.path(), &["simulate", pendulum, "--svg", "out.svg"]);
    assert_eq!(done.code, Some(0), "{}", done.stderr);
    assert!(
        done.stdout
            .contains("(360 steps); contacts soft_step, 4 substeps; 2 joints"),
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
