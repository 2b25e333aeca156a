//! A newcomer's mistakes through the real binary: `simulate` warns about
//! scenes and options that run but are likely wrong, prints the values the
//! solver really uses, and names the right place and remedy in its
//! refusals; `--compare` with several engines runs those that take the
//! scene.

use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_harness");

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

impl Run {
    fn ok(&self) -> &Self {
        assert_eq!(self.code, Some(0), "exit code; stderr:\n{}", self.stderr);
        self
    }

    fn refused(&self) -> &Self {
        assert_eq!(self.code, Some(2), "exit code; stderr:\n{}", self.stderr);
        assert!(!self.stderr.contains("panicked"), "{}", self.stderr);
        self
    }

    fn err_has(&self, needle: &str) -> &Self {
        assert!(
            self.stderr.contains(needle),
            "stderr lacks {needle:?}:\n{}",
            self.stderr
        );
        self
    }

    fn err_lacks(&self, needle: &str) -> &Self {
        assert!(
            !self.stderr.contains(needle),
            "stderr has {needle:?}:\n{}",
            self.stderr
        );
        self
    }

    fn out_has(&self, needle: &str) -> &Self {
        assert!(
            self.stdout.contains(needle),
            "stdout lacks {needle:?}:\n{}",
            self.stdout
        );
        self
    }
}

/// `harness simulate <scene> <args>` in the workspace (a relative scene
/// path is the workspace's).
fn simulate_file(scene: &str, args: &[&str]) -> Run {
    let output = Command::new(BIN)
        .current_dir(workspace())
        .arg("simulate")
        .arg(scene)
        .args(args)
        .output()
        .expect("run the harness");
    Run {
        code: output.status.code(),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

/// `harness simulate scene.toml <args>` on `text`, in a fresh folder.
fn simulate_text(text: &str, args: &[&str]) -> Run {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let output = Command::new(BIN)
        .current_dir(dir.path())
        .args(["simulate", "scene.toml"])
        .args(args)
        .output()
        .expect("run the harness");
    Run {
        code: output.status.code(),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
    }
}

#[test]
fn gravity_given_twice_is_warned() {
    let scene = "[simulation]\ndt = 0.01\nduration = 1.0\ngravity = [0.0, -9.81]\n\n\
                 [[bodies]]\nname = \"ball\"\nmass = 1.0\n\n\
                 [[forces]]\ntype = \"gravity\"\ng = [0.0, -9.81]\n";
    simulate_text(scene, &[])
        .ok()
        .err_has("gravity is given twice, in [simulation] gravity = [0, -9.81] and in forces[0]")
        .err_has("bodies fall under their sum [0, -19.62] m/s²");
    // One of the two: no warning.
    let once = scene.replace("gravity = [0.0, -9.81]\n\n", "\n");
    simulate_text(&once, &[]).ok().err_lacks("warning");
}

#[test]
fn a_step_longer_than_the_run_and_the_energy_it_pumps_are_warned() {
    // elastic_pendulum.toml runs 12 s: --dt 20 is one step of 12 s, and
    // velocity Verlet at that step multiplies the energy's size by ~7e9.
    simulate_file("scenes/examples/elastic_pendulum.toml", &["--dt", "20"])
        .ok()
        .out_has("(1 steps)")
        .err_has("--dt 20 s is longer than the run (12 s): the run is a single step of 12 s")
        .err_has("the energy rose from")
        .err_has("velocity_verlet is unstable at dt = 20 s");
    // At its own step: no warning.
    simulate_file("scenes/examples/elastic_pendulum.toml", &[])
        .ok()
        .err_lacks("warning");
}

#[test]
fn an_unstable_method_that_does_not_overflow_is_warned() {
    // Explicit Euler at dt = 1 s on the spring (ω = 5 rad/s): |1 + iω h|² =
    // 26 per step, 58 steps: the energy grows by 31 orders of magnitude
    // but stays finite, so the run succeeds, with the warning.
    simulate_file(
        "scenes/spring.toml",
        &["--method", "explicit_euler", "--dt", "1"],
    )
    .ok()
    .err_has("the energy rose from 62500.00000 J")
    .err_has("explicit_euler is unstable at dt = 1 s");
}

#[test]
fn the_model_line_prints_the_capped_contact_stiffness() {
    // dt = 0.1 s in 4 substeps: h = 0.025 s, so the solver caps the contact
    // stiffness at 1/(8 h) = 5 Hz (engine/src/soft_step/prepare.rs); 30 Hz
    // and 20 Hz both run at 5 Hz.
    for hertz in ["30.0", "20.0"] {
        let scene = format!(
            "[simulation]\ndt = 0.1\nduration = 0.5\ngravity = [0.0, -9.81]\n\n\
             [contact]\ncontact_hertz = {hertz}\n\n\
             [[bodies]]\nname = \"ground\"\nkind = \"static\"\n\
             shape = {{ type = \"box\", width = 10.0, height = 1.0 }}\nposition = [0.0, -0.5]\n"
        );
        let requested = hertz.trim_end_matches(".0");
        simulate_text(&scene, &[]).ok().out_has(&format!(
            "contact 5 Hz (capped: {requested} Hz requested, above 1/(8 h) for the substep h = 0.025 s)"
        ));
    }
}

#[test]
fn a_method_on_a_soft_step_scene_blames_the_option() {
    // Line 9 is [contact]: the fault is --method's, not the table's.
    let scene = "# a ramp\n[simulation]\ndt = 0.01\nduration = 1.0\ngravity = [0.0, -9.81]\n\n\n\n\
                 [contact]\nfriction = 0.5\n\n[[bodies]]\nname = \"ground\"\nkind = \"static\"\n\
                 shape = { type = \"box\", width = 10.0, height = 1.0 }\n";
    simulate_text(scene, &["--method", "rk4"])
        .refused()
        .err_has("--method rk4: scene.toml runs under the soft step")
        .err_has("drop --method, or set [contact] model = \"exact\"")
        .err_lacks("scene.toml:9:1");
    simulate_text(scene, &["--method", "semi_implicit_euler"]).ok();
}

#[test]
fn a_file_without_simulation_is_told_so() {
    simulate_text("[[bodies]]\nname = \"a\"\nmass = 1.0\n", &[])
        .refused()
        .err_has("scene.toml:1:1: simulation: the file has no [simulation] table")
        .err_lacks("bodies[0].simulation");
}

#[test]
fn a_motor_without_its_largest_torque_is_located_in_the_motor() {
    let scene = "[simulation]\ndt = 0.01\nduration = 1.0\n\n[[bodies]]\nname = \"wheel\"\n\
                 mass = 1.0\nshape = { type = \"circle\", radius = 0.5 }\n\n[[joints]]\n\
                 type = \"revolute\"\nbody_b = \"wheel\"\nanchor = [0.0, 0.0]\nmotor = { speed = 1.0 }\n";
    simulate_text(scene, &[])
        .refused()
        .err_has("scene.toml:14:9: joints[0].motor.max_torque: missing field `max_torque`");
}

#[test]
fn per_body_restitution_under_the_exact_model_is_told_the_right_remedy() {
    let scene = "[simulation]\ndt = 0.01\nduration = 1.0\n\n[contact]\nmodel = \"exact\"\n\n\
                 [[bodies]]\nname = \"ball\"\nmass = 1.0\n\
                 shape = { type = \"circle\", radius = 0.5 }\nrestitution = 0.5\n";
    simulate_text(scene, &[])
        .refused()
        .err_has("bodies[0].restitution: per-body restitution needs the soft_step contact model")
        .err_has("set [contact] model = \"soft_step\", or remove it and give [contact] restitution")
        .err_lacks("add [contact]");
}

#[test]
fn a_blow_up_of_an_unstable_step_names_one_step_and_blames_the_step() {
    simulate_file(
        "scenes/spring.toml",
        &["--method", "explicit_euler", "--dt", "1", "--until", "1000"],
    )
    .refused()
    .err_has("the run failed in step 558 of 1000 (the step from t = 557 s)")
    .err_lacks("(step 557)")
    .err_has("the mark of a method unstable at this step: explicit_euler with dt = 1 s")
    .err_lacks("too large together for f64");
}

#[test]
fn compare_with_two_engines_runs_the_one_that_takes_the_scene() {
    // Box2D takes no drag; rapier's single-body adapter does.
    simulate_file(
        "scenes/examples/thrown_plate.toml",
        &["--compare", "rapier,box2d"],
    )
    .ok()
    .out_has("not compared: --compare box2d:")
    .out_has("rapier2d-f64 0.36");
}

#[test]
fn box2d_repeated_log_lines_are_printed_once_and_counted() {
    let run = simulate_file(
        "scenes/robustness/coincident_boxes.toml",
        &["--compare", "box2d"],
    );
    run.ok();
    let lines = run
        .stderr
        .lines()
        .chain(run.stdout.lines())
        .filter(|l| l.contains("Pair buffer capacity"))
        .count();
    // Once as Box2D said it, once in the count.
    assert!(lines <= 2, "{lines} lines of Box2D's log:\n{}", run.stderr);
    if lines > 0 {
        run.err_has("times in all (printed once)");
    }
}

#[test]
fn a_pile_compared_is_said_to_be_chaotic() {
    simulate_file(
        "scenes/drop_20.toml",
        &["--compare", "box2d", "--until", "0.5"],
    )
    .ok()
    .out_has("is chaotic");
}
