//! Bad input through the real binary: every mistake of the issue on scene
//! files gets a clear message on stderr naming the file, the field and the
//! line (or the command-line option), exit code 2, no panic, no output
//! file written, and the scene file left as it was.

use std::path::PathBuf;
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_harness");

/// A valid head: `[simulation]` and the start of one body named `plate`
/// (line 5 is `[[bodies]]`, line 6 its name, line 7 the next line).
const HEAD: &str = "[simulation]\ndt = 0.01\nduration = 1.0\n\n[[bodies]]\nname = \"plate\"\n";

struct Run {
    code: Option<i32>,
    stderr: String,
    dir: tempfile::TempDir,
}

/// Writes `text` as `scene.toml` in a fresh folder and runs
/// `harness simulate scene.toml --trace out.csv <extra>` there.
fn simulate(text: &str, extra: &[&str]) -> Run {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("scene.toml"), text).expect("write scene");
    let output: Output = Command::new(BIN)
        .current_dir(dir.path())
        .args(["simulate", "scene.toml", "--trace", "out.csv"])
        .args(extra)
        .output()
        .expect("run the harness binary");
    Run {
        code: output.status.code(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
        dir,
    }
}

impl Run {
    /// Exit code 2, no panic, no output, the scene untouched, and stderr
    /// holding every one of `needles`.
    fn refused(&self, scene: &str, needles: &[&str]) {
        assert_eq!(self.code, Some(2), "exit code; stderr:\n{}", self.stderr);
        assert!(
            !self.stderr.contains("panicked"),
            "a panic:\n{}",
            self.stderr
        );
        assert!(!self.stderr.contains("RUST_BACKTRACE"), "{}", self.stderr);
        for needle in needles {
            assert!(
                self.stderr.contains(needle),
                "stderr lacks {needle:?}:\n{}",
                self.stderr
            );
        }
        assert!(!self.path("out.csv").exists(), "an output was written");
        let kept = std::fs::read_to_string(self.path("scene.toml")).expect("scene still there");
        assert_eq!(kept, scene, "the scene file changed");
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }
}

fn refused(scene: &str, needles: &[&str]) {
    simulate(scene, &[]).refused(scene, needles);
}

#[test]
fn malformed_toml_names_the_line() {
    refused(
        "[simulation\ndt = 0.01\n",
        &["scene.toml:1:", "expected `]`"],
    );
}

#[test]
fn an_unknown_field_is_named_with_its_line() {
    let scene = format!("{HEAD}mass = 1.0\nmas = 2.0\n");
    refused(
        &scene,
        &["scene.toml:8:", "bodies[0].mas", "unknown field `mas`"],
    );
}

#[test]
fn a_self_intersecting_polygon_names_the_body_and_the_edges() {
    let scene = format!(
        "{HEAD}mass = 1.0\nshape = {{ type = \"polygon\", vertices = [[0, 0], [2, 0], [0, 2], [2, 2]] }}\n"
    );
    refused(
        &scene,
        &[
            "scene.toml:8:",
            "bodies[0].shape.vertices[1]",
            "'plate'",
            "self-intersecting outline: edge 1 crosses or touches edge 3 at vertex 1",
        ],
    );
}

#[test]
fn a_clockwise_polygon_names_the_body_and_the_vertex() {
    let scene = format!(
        "{HEAD}mass = 1.0\nshape = {{ type = \"polygon\", vertices = [[0, 0], [0, 1], [1, 0]] }}\n"
    );
    refused(
        &scene,
        &[
            "scene.toml:8:",
            "bodies[0].shape.vertices[",
            "'plate'",
            "clockwise",
            "at vertex",
        ],
    );
}

#[test]
fn a_mass_at_or_below_zero_is_refused() {
    for mass in ["0.0", "-3.0"] {
        let scene = format!("{HEAD}mass = {mass}\n");
        refused(&scene, &["scene.toml:7:8", "bodies[0].mass", "must be > 0"]);
    }
}

#[test]
fn a_density_at_or_below_zero_is_refused() {
    let scene = format!("{HEAD}density = 0.0\nshape = {{ type = \"circle\", radius = 1.0 }}\n");
    refused(
        &scene,
        &["scene.toml:7:", "bodies[0].density", "must be > 0"],
    );
}

#[test]
fn a_step_at_or_below_zero_in_the_file_is_refused() {
    for dt in ["0.0", "-0.01"] {
        let scene = format!(
            "[simulation]\ndt = {dt}\nduration = 1.0\n[[bodies]]\nname = \"p\"\nmass = 1.0\n"
        );
        refused(&scene, &["scene.toml:2:6", "simulation.dt", "must be > 0"]);
    }
}

#[test]
fn nan_is_refused() {
    let scene = format!("{HEAD}mass = 1.0\nposition = [nan, 0.0]\n");
    refused(
        &scene,
        &[
            "scene.toml:8:",
            "bodies[0].position[0]",
            "not a finite number",
        ],
    );
}

#[test]
fn infinity_is_refused() {
    let scene = format!("{HEAD}mass = 1.0\nvelocity = [0.0, -inf]\n");
    refused(
        &scene,
        &[
            "scene.toml:8:",
            "bodies[0].velocity[1]",
            "not a finite number",
        ],
    );
}

#[test]
fn a_force_on_a_missing_body_is_refused() {
    let scene = format!(
        "{HEAD}mass = 1.0\n\n[[forces]]\ntype = \"drag\"\nbody = \"ghost\"\ncoefficient = 0.1\n"
    );
    refused(
        &scene,
        &[
            "scene.toml:11:",
            "forces[0].body",
            "no body is named 'ghost'",
        ],
    );
}

#[test]
fn a_run_of_more_than_1e8_steps_is_refused_before_it_starts() {
    let scene = "[simulation]\ndt = 1e-9\nduration = 1.0\n[[bodies]]\nname = \"p\"\nmass = 1.0\n";
    refused(scene, &["scene.toml:2:", "simulation.dt", "1e8"]);
}

const GOOD: &str =
    "[simulation]\ndt = 0.01\nduration = 1.0\n[[bodies]]\nname = \"p\"\nmass = 1.0\n";

#[test]
fn an_unknown_method_on_the_command_line_is_refused() {
    simulate(GOOD, &["--method", "rk5"])
        .refused(GOOD, &["--method", "rk5", "rk4", "dormand_prince"]);
}

#[test]
fn a_command_line_step_at_or_below_zero_is_refused() {
    for dt in ["0", "-0.5", "nan", "inf"] {
        simulate(GOOD, &["--dt", dt]).refused(GOOD, &["--dt", dt]);
    }
    simulate(GOOD, &["--until", "-1"]).refused(GOOD, &["--until", "must be > 0"]);
}

#[test]
fn a_command_line_step_needing_more_than_1e8_steps_is_refused() {
    simulate(GOOD, &["--dt", "1e-12"]).refused(GOOD, &["scene.toml", "--dt", "1e8"]);
    simulate(GOOD, &["--until", "1e7", "--dt", "0.01"])
        .refused(GOOD, &["scene.toml", "--until", "1e8"]);
}

#[test]
fn a_missing_file_is_reported_once() {
    let run = simulate(GOOD, &[]);
    let output = Command::new(BIN)
        .current_dir(run.dir.path())
        .args(["simulate", "nowhere.toml"])
        .output()
        .expect("run");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("nowhere.toml: cannot read the scene file"),
        "{stderr}"
    );
    let cause = if cfg!(windows) {
        "os error"
    } else {
        "(os error 2)"
    };
    assert_eq!(stderr.matches(cause).count(), 1, "said twice:\n{stderr}");
}

#[test]
fn an_output_over_the_scene_file_is_refused() {
    let run = simulate(GOOD, &["--svg", "scene.toml"]);
    run.refused(GOOD, &["--svg scene.toml", "scene file itself"]);
    let run = simulate(GOOD, &["--gif", "no_such_folder/out.gif"]);
    run.refused(GOOD, &["--gif", "does not exist"]);
}

#[test]
fn an_output_whose_extension_is_another_format_is_refused() {
    // `--svg a.png` would write SVG text into a .png: refused before the
    // run, naming the option, the path and the extension it needs.
    let run = simulate(GOOD, &["--svg", "a.png"]);
    run.refused(
        GOOD,
        &[
            "--svg a.png",
            "ends in .png",
            "does not match the format",
            ".svg",
        ],
    );
    assert!(!run.path("a.png").exists());
    let run = simulate(GOOD, &["--gif", "movie.svg"]);
    run.refused(GOOD, &["--gif movie.svg", "ends in .svg", ".gif"]);
    let run = simulate(GOOD, &["--svg", "strip"]);
    run.refused(GOOD, &["--svg strip", "has no extension", ".svg"]);
    let run = simulate(GOOD, &["--html", "replay.gif"]);
    run.refused(GOOD, &["--html replay.gif", "ends in .gif", ".html"]);
    // The `simulate` helper always asks for `--trace out.csv`: a second
    // trace path cannot be given, so the trace's own check runs alone.
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("scene.toml"), GOOD).expect("write scene");
    let output = Command::new(BIN)
        .current_dir(dir.path())
        .args(["simulate", "scene.toml", "--trace", "t.json"])
        .output()
        .expect("run the harness binary");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--trace t.json") && stderr.contains(".csv"),
        "{stderr}"
    );
    assert!(!dir.path().join("t.json").exists());
    // Any case of the right extension is accepted.
    let run = simulate(GOOD, &["--svg", "STRIP.SVG"]);
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    assert!(run.path("STRIP.SVG").exists());
}

#[test]
fn a_blow_up_is_an_error_and_writes_nothing() {
    // Explicit Euler on a stiff spring: |1 + i h w| = 1000 per step, so the
    // state overflows after about a hundred steps.
    let scene = "[simulation]\nmethod = \"explicit_euler\"\ndt = 1.0\nduration = 1000.0\n\
                 [[bodies]]\nname = \"p\"\nmass = 1.0\nposition = [1.0, 0.0]\n\
                 [[forces]]\ntype = \"spring\"\nbody = \"p\"\nanchor = [0.0, 0.0]\nstiffness = 1e6\n";
    let run = simulate(scene, &["--svg", "out.svg"]);
    run.refused(scene, &["scene.toml", "the run failed", "blow-up"]);
    assert!(!run.path("out.svg").exists());
}

/// A pendulum scene: lines 1–3 `[simulation]`, 5–8 a static `wall`,
/// 10–13 a dynamic `bob`, 15 `[[joints]]`, 16 its type, `extra` from 17.
fn jointed(kind: &str, extra: &str) -> String {
    format!(
        "[simulation]\ndt = 0.01\nduration = 0.1\n\n[[bodies]]\nname = \"wall\"\nkind = \"static\"\nposition = [0.0, 0.0]\n\n[[bodies]]\nname = \"bob\"\nmass = 1.0\nposition = [1.0, 0.0]\n\n[[joints]]\ntype = \"{kind}\"\n{extra}"
    )
}

#[test]
fn every_bad_joint_definition_is_refused_at_its_field() {
    let cases: [(String, &[&str]); 9] = [
        (
            jointed("revolute", "body_b = \"bobb\"\nanchor = [0.0, 0.0]\n"),
            &["scene.toml:17:", "joints[0].body_b", "no body is named 'bobb'"],
        ),
        (
            jointed("revolute", "body_a = \"bob\"\nbody_b = \"bob\"\nanchor = [0.0, 0.0]\n"),
            &["scene.toml:18:", "joints[0].body_b", "to itself"],
        ),
        (
            jointed("prismatic", "body_b = \"bob\"\nanchor = [1.0, 0.0]\naxis = [0.0, 0.0]\n"),
            &["scene.toml:19:", "joints[0].axis", "no direction"],
        ),
        (
            jointed("revolute", "body_b = \"bob\"\nanchor = [0.0, 0.0]\nlimits = [1.0, -1.0]\n"),
            &["scene.toml:19:", "joints[0].limits", "[lower, upper]"],
        ),
        (
            jointed(
                "distance",
                "body_b = \"bob\"\nanchor_a = [0.0, 0.0]\nanchor_b = [1.0, 0.0]\nspring = { hertz = -2.0 }\n",
            ),
            &["scene.toml:20:", "joints[0].spring.hertz", "must be > 0"],
        ),
        (
            jointed("revolute", "body_b = \"bob\"\nanchor = [0.0, 0.0]\nmotor_speed = 1.0\n"),
            &["scene.toml:19:", "joints[0].motor_speed", "unknown field"],
        ),
        (
            format!(
                "{}\n[contact]\nmodel = \"exact\"\n",
                jointed(
                    "revolute",
                    "body_b = \"bob\"\nanchor = [0.0, 0.0]\nlimits = [-0.5, 0.5]\n"
                )
            ),
            &["scene.toml:15:", "joints[0]", "angle limits", "soft_step"],
        ),
        (
            jointed("weld", "body_a = \"wall\"\nanchor = [0.0, 0.0]\n"),
            &["scene.toml:17:", "joints[0].body_a", "dynamic"],
        ),
        (
            "[simulation]\ndt = 0.01\nduration = 0.1\n\n[[generate]]\ntype = \"chain\"\ncount = 2\nstart = [0.0, 0.0]\nend = [3.0, 0.0]\n".to_owned(),
            &["scene.toml:9:", "generate[0].end", "shorter"],
        ),
    ];
    for (scene, needles) in &cases {
        refused(scene, needles);
    }
}
