//! The fuzzing report's reproducers, through the real binary: each hostile
//! input ends (a run that outlives [`HANG`] is killed and fails the test),
//! with exit code 2 and a located message in the user's words when the
//! input is at fault, never a NaN or an infinity printed as a result, and
//! nothing written on a failed run.

use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_harness");

/// A run still going after this long counts as hung. Every case here takes
/// milliseconds; the margin is for a loaded machine, not for the code.
const HANG: Duration = Duration::from_secs(120);

struct Done {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    dir: tempfile::TempDir,
}

impl Done {
    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// Exit code 2, no panic, `needles` on stderr, no `out.*` written.
    #[track_caller]
    fn refused(&self, needles: &[&str]) {
        assert_eq!(self.code, Some(2), "stderr:\n{}", self.stderr);
        assert!(!self.stderr.contains("panicked"), "{}", self.stderr);
        for needle in needles {
            assert!(
                self.stderr.contains(needle),
                "stderr lacks {needle:?}:\n{}",
                self.stderr
            );
        }
        for out in ["out.csv", "out.svg", "out.gif"] {
            assert!(!self.path(out).exists(), "{out} was written");
        }
    }

    #[track_caller]
    fn succeeded(&self) {
        assert_eq!(self.code, Some(0), "stderr:\n{}", self.stderr);
        for word in ["NaN", "inf"] {
            assert!(!self.stdout.contains(word), "{word}:\n{}", self.stdout);
        }
    }
}

/// Runs `harness <args>` in `dir`, killing it after [`HANG`].
fn run_in(dir: tempfile::TempDir, args: &[&str]) -> Done {
    let mut child = Command::new(BIN)
        .current_dir(dir.path())
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run the harness binary");
    let started = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if started.elapsed() > HANG {
            let _ = child.kill();
            panic!("harness {args:?} still running after {HANG:?}: hung");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let output = child.wait_with_output().expect("output");
    Done {
        code: output.status.code(),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
        dir,
    }
}

/// Writes `scene` as `scene.toml` in a fresh folder and runs `simulate`
/// on it with `extra` options.
fn simulate(scene: &[u8], extra: &[&str]) -> Done {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("scene.toml"), scene).expect("write scene");
    let mut args = vec!["simulate", "scene.toml"];
    args.extend(extra);
    run_in(dir, &args)
}

const HEAD: &str = "[simulation]\ndt = 0.1\nduration = 1.0\n[[bodies]]\nname = \"p\"\n";
const ALL_OUTPUTS: [&str; 6] = ["--svg", "out.svg", "--gif", "out.gif", "--trace", "out.csv"];

#[test]
fn a_run_too_narrow_to_draw_at_its_distance_is_drawn_widened_and_says_so() {
    // Before: a particle at x = 1e308 hung in plotters' key points (the
    // view's centre overflowed). Now 1e308 is refused on loading, and the
    // farthest position a scene may give is drawn with a widened view.
    let far = format!(
        "{HEAD}mass = 1.0\nposition = [1.3e154, 0.0]\n[[forces]]\ntype = \"gravity\"\ng = [0.0, -9.81]\n"
    );
    let done = simulate(far.as_bytes(), &ALL_OUTPUTS);
    done.succeeded();
    let svg = std::fs::read_to_string(done.path("out.svg")).expect("svg written");
    assert!(svg.contains("axis is widened"), "no note in the SVG");
    assert!(done.path("out.gif").exists());
    let at_limit = format!("{HEAD}mass = 1.0\nposition = [1e308, 0.0]\n");
    simulate(at_limit.as_bytes(), &ALL_OUTPUTS).refused(&[
        "scene.toml:7:13",
        "bodies[0].position[0]",
        "1e308 is too large",
    ]);
    let big_circle = format!("{HEAD}mass = 1.0\nshape = {{ type = \"circle\", radius = 1e308 }}\n");
    simulate(big_circle.as_bytes(), &["--svg", "out.svg"])
        .refused(&["bodies[0].shape.radius", "1e308 is too large"]);
}

#[test]
fn a_linear_test_that_overflows_is_refused_and_its_curve_never_hangs() {
    let scene = "[simulation]\nmethod = \"explicit_euler\"\ndt = 0.1\nduration = 1.0\n\
                 [linear_test]\nlambda = 1000.0\ny0 = 1.0\n";
    simulate(scene.as_bytes(), &["--svg", "out.svg"]).refused(&[
        "scene.toml:6:10",
        "linear_test.lambda",
        "overflows f64",
    ]);
    let scene = scene.replace("1000.0", "750.0");
    simulate(scene.as_bytes(), &["--trace", "out.csv"]).refused(&["709.78"]);
    // λ = 700: every figure finite, written; its curve reaches -1e304,
    // beyond what axes show: a clear refusal, not a hang.
    let scene = scene.replace("750.0", "700.0");
    let done = simulate(scene.as_bytes(), &["--trace", "out.csv"]);
    done.succeeded();
    let csv = std::fs::read_to_string(done.path("out.csv")).expect("trace");
    assert!(!csv.contains("inf") && !csv.contains("NaN"), "{csv}");
    simulate(scene.as_bytes(), &["--svg", "out.svg"]).refused(&["--svg", "cannot draw"]);
    simulate(scene.as_bytes(), &["--until", "2"]).refused(&["--until", "overflows f64"]);
}

#[test]
fn an_energy_that_overflows_is_an_error_not_nan() {
    let scene = format!("{HEAD}mass = 1.0\n[[forces]]\ntype = \"gravity\"\ng = [1e154, -1e154]\n");
    let done = simulate(scene.as_bytes(), &ALL_OUTPUTS);
    done.refused(&[
        "blow-up",
        "energy inf J",
        "beyond the largest finite f64, 1.8e308 J; body 'p' carries the most kinetic energy",
        "hint: the total energy is no longer a finite number (the fastest body when the step \
         began: 'p', at 1.273e154 m/s)",
    ]);
    // The guard's bound is f64's range, not its seventeen digits.
    assert!(
        !done.stderr.contains("1.7976931348623157e308"),
        "{}",
        done.stderr
    );
    // A force of 1e150 N on a lever of 1e150 m: the first step's rotational
    // energy overflows.
    let scene = format!(
        "{HEAD}mass = 1.0\nshape = {{ type = \"circle\", radius = 1.0 }}\n[[forces]]\n\
         type = \"point_force\"\nbody = \"p\"\nforce = [1e150, 1e150]\npoint = [0.0, 1e150]\n"
    );
    simulate(scene.as_bytes(), &ALL_OUTPUTS).refused(&[
        "the run failed in step 1 of 10",
        "speed 1.414e149 m/s",
        "(the fastest body when the step began: 'p', at 0 m/s)",
    ]);
    let scene = format!("{HEAD}mass = 1e10\nvelocity = [1e154, 0.0]\n");
    simulate(scene.as_bytes(), &["--trace", "out.csv"]).refused(&[
        "scene.toml:7:12",
        "bodies[0].velocity",
        "kinetic energy",
    ]);
}

#[test]
fn a_stiff_drag_under_dormand_prince_names_the_force_and_the_remedy() {
    let scene = "[simulation]\nmethod = \"dormand_prince\"\ndt = 0.01\nduration = 1.0\n\
                 [[bodies]]\nname = \"p\"\nmass = 1.0\n\
                 [[forces]]\ntype = \"gravity\"\ng = [0.0, -9.81]\n\
                 [[forces]]\ntype = \"drag\"\nbody = \"p\"\ncoefficient = 1e150\n";
    simulate(scene.as_bytes(), &["--trace", "out.csv"]).refused(&[
        "step size underflow",
        "hint: the problem is stiff: forces[1] (drag on 'p'",
        "--method implicit_euler",
    ]);
    simulate(scene.as_bytes(), &["--method", "implicit_euler"]).succeeded();
    let tight = "[simulation]\nmethod = \"dormand_prince\"\ndt = 0.01\nduration = 1.0\ntolerance = 1e-16\n\
                 [[bodies]]\nname = \"p\"\nmass = 1.0\n";
    simulate(tight.as_bytes(), &[]).refused(&[
        "scene.toml:5:13",
        "simulation.tolerance",
        "below what f64 arithmetic can reach",
    ]);
}

#[cfg(unix)]
#[test]
fn outputs_that_are_links_fifos_or_devices_are_refused() {
    let scene = format!("{HEAD}mass = 1.0\n");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.toml"), &scene).unwrap();
    std::fs::write(dir.path().join("target.csv"), "kept").unwrap();
    std::os::unix::fs::symlink("target.csv", dir.path().join("link.csv")).unwrap();
    let done = run_in(dir, &["simulate", "scene.toml", "--trace", "link.csv"]);
    done.refused(&["--trace", "link.csv is a symbolic link"]);
    let link = std::fs::symlink_metadata(done.path("link.csv")).unwrap();
    assert!(link.file_type().is_symlink(), "the link was replaced");
    assert_eq!(
        std::fs::read_to_string(done.path("target.csv")).unwrap(),
        "kept"
    );
    let fifo = done.path("fifo.csv");
    if Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        let done = run_in(done.dir, &["simulate", "scene.toml", "--svg", "fifo.csv"]);
        done.refused(&["--svg", "a named pipe"]);
    }
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.toml"), &scene).unwrap();
    run_in(dir, &["simulate", "scene.toml", "--trace", "/dev/null"]).refused(&["is a device"]);
    let null = std::fs::metadata("/dev/null").unwrap();
    assert!(!null.is_file(), "/dev/null was replaced by a file");
}

#[cfg(unix)]
#[test]
fn scene_files_that_are_not_regular_or_too_large_are_refused_unread() {
    let dir = tempfile::tempdir().unwrap();
    run_in(dir, &["simulate", "/dev/zero"]).refused(&["/dev/zero", "a character device"]);
    let dir = tempfile::tempdir().unwrap();
    let here = dir.path().to_path_buf();
    run_in(dir, &["simulate", here.to_str().unwrap()]).refused(&["a folder"]);
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.toml");
    if Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        run_in(dir, &["simulate", "pipe.toml"]).refused(&["pipe.toml", "named pipe (FIFO)"]);
    }
    let dir = tempfile::tempdir().unwrap();
    let big = std::fs::File::create(dir.path().join("big.toml")).unwrap();
    big.set_len(17 * 1024 * 1024).unwrap(); // sparse
    run_in(dir, &["simulate", "big.toml"]).refused(&["big.toml", "more than the 16 MiB"]);
}

#[test]
fn other_encodings_are_named_and_located() {
    let mut utf16 = vec![0xFF, 0xFE];
    utf16.extend(HEAD.encode_utf16().flat_map(u16::to_le_bytes));
    simulate(&utf16, &[]).refused(&["scene.toml:1:1", "UTF-16 little-endian", "FF FE"]);
    simulate(b"[simulation]\ndt = 0.1\n# caf\xe9\n", &[]).refused(&[
        "scene.toml:3:6",
        "byte 0xE9",
        "Latin-1",
    ]);
}

#[test]
fn messages_name_the_field_in_the_users_words() {
    let deep_values = format!(
        "[simulation]\ndt = 0.1\nduration = 1.0\nx = {}{}\n",
        "[".repeat(1000),
        "]".repeat(1000)
    );
    let cases: [(String, &[&str]); 17] = [
        (
            "simulation = 1979-05-27\n".into(),
            &[
                "scene.toml:1:14",
                "simulation: expected the table [simulation], found the date-time 1979-05-27",
            ],
        ),
        (
            format!("{HEAD}mass = 99999999999999999999\n"),
            &[
                "scene.toml:6:8",
                "bodies[0].mass",
                "beyond TOML's 64-bit integers",
            ],
        ),
        (
            format!("{HEAD}mass = 1.0\nshape = 3\n"),
            &[
                "bodies[0].shape",
                "expected a table with a `type`, found the integer 3",
            ],
        ),
        (
            format!("{HEAD}mass = 1.0\n[[forces]]\ntype = 3\n"),
            &["forces[0].type", "expected a name (a string)"],
        ),
        (
            format!("{HEAD}mass = -1e308\n"),
            &["scene.toml:6:8", "-1e308 is too large"],
        ),
        (
            format!(
                "{HEAD}mass = 1.0\n\n\n\n\n[[forces]]\ntype = \"gravity\"\ng = [0.0, -9.81]\nwindow = \"always\"\n"
            ),
            &[
                "scene.toml:14:10",
                "forces[0].window",
                "found the string \"always\"",
            ],
        ),
        (
            format!("{HEAD}mass = 1.0\nshape = {{ type = \"circle\", radius = 1e-200 }}\n"),
            &[
                "scene.toml:7:37",
                "bodies[0].shape.radius",
                "1e-200 is too small",
            ],
        ),
        (
            format!(
                "[simulation]\ndt = 0.1\nduration = 1.0\n[{}]\n",
                vec!["a"; 1000].join(".")
            ),
            &["scene.toml:4:1", "nested 1000 levels deep"],
        ),
        (
            deep_values,
            &["scene.toml:4:85", "nested more than 80 levels deep"],
        ),
        (
            format!("{HEAD}mass = -1e-320\n"),
            &["scene.toml:6:8", "bodies[0].mass", "-1e-320 is too small"],
        ),
        (
            format!("{HEAD}mass = 1.0\n[contact]\nmodel = \"exact\"\ntoi_method = 3\n"),
            &[
                "scene.toml:9:14",
                "contact.toi_method",
                "expected a name (a string), found the integer 3",
            ],
        ),
        (
            format!("{HEAD}mass = 1.0\nkind = {{ static = 1 }}\n"),
            &[
                "scene.toml:7:8",
                "bodies[0].kind",
                "expected a name (a string), found a table",
            ],
        ),
        (
            "[[simulation]]\ndt = 0.1\nduration = 1.0\n".into(),
            &[
                "scene.toml:1:1",
                "simulation: expected the table [simulation], found an array of tables",
            ],
        ),
        (
            "bodies = [[1.0, 2.0]]\n[simulation]\ndt = 0.1\nduration = 1.0\n".into(),
            &[
                "scene.toml:1:11",
                "bodies[0]: expected a table, found an array",
            ],
        ),
        (
            format!("{HEAD}mass = 1.0\nmass = 2.0\n"),
            &["scene.toml:7:1", "duplicate key `mass`"],
        ),
        (
            format!(
                "{HEAD}mass = 1.0\nshape = {{ type = \"polygon\", vertices = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 1.0]] }}\n"
            ),
            &["bodies[0].shape.vertices[2]", "repeated vertex"],
        ),
        (
            format!(
                "{HEAD}mass = 1.0\nshape = {{ type = \"polygon\", vertices = [[-1e300, -1e300], [1e300, -1e300], [0.0, 1e300]] }}\n"
            ),
            &["bodies[0].shape.vertices[0][0]", "-1e300 is too large"],
        ),
    ];
    for (scene, needles) in cases {
        let done = simulate(scene.as_bytes(), &["--trace", "out.csv"]);
        done.refused(needles);
        for jargon in [
            "$__toml",
            "struct ",
            "enum ",
            "variant identifier",
            "i128",
            "Spec",
            "wanted",
            "recurs",
            "sequence",
            "map",
        ] {
            assert!(!done.stderr.contains(jargon), "{jargon}: {}", done.stderr);
        }
    }
}

#[test]
fn thin_boxes_run() {
    for (w, h) in [("1.0", "1e-7"), ("1000.0", "0.001")] {
        let scene =
            format!("{HEAD}mass = 1.0\nshape = {{ type = \"box\", width = {w}, height = {h} }}\n");
        simulate(scene.as_bytes(), &["--trace", "out.csv"]).succeeded();
    }
}

#[test]
fn a_budget_stops_the_run_cleanly_and_writes_what_ran() {
    // 1e8 steps of a spring: minutes; the budget stops it after 0.2 s.
    let scene = "[simulation]\ndt = 1e-5\nduration = 1000.0\n[[bodies]]\nname = \"p\"\nmass = 1.0\n\
                 position = [1.0, 0.0]\n[[forces]]\ntype = \"spring\"\nbody = \"p\"\nanchor = [0.0, 0.0]\nstiffness = 10.0\n";
    let done = simulate(scene.as_bytes(), &["--budget", "0.2", "--trace", "out.csv"]);
    done.succeeded();
    assert!(
        done.stdout.contains("stopped by --budget"),
        "{}",
        done.stdout
    );
    assert!(
        done.stderr.contains("stopped by --budget 0.2 s"),
        "{}",
        done.stderr
    );
    let csv = std::fs::read_to_string(done.path("out.csv")).expect("trace written");
    let last_t: f64 = csv
        .lines()
        .last()
        .and_then(|l| l.split(',').next())
        .and_then(|t| t.parse().ok())
        .expect("a last row");
    assert!(last_t > 0.0 && last_t < 1000.0, "{last_t}");
    for bad in ["0", "-1", "nan"] {
        simulate(scene.as_bytes(), &["--budget", bad]).refused(&["--budget"]);
    }
}

/// `harness simulate scene.toml | head -1`: a stdout closed after the
/// first line ends the run quietly (SIGPIPE, as for `cat`), with no panic
/// on stderr.
#[test]
fn a_closed_stdout_is_not_a_panic() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/pyramid_20.toml");
    let mut child = Command::new(BIN)
        .args(["simulate", scene])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run the harness binary");
    // Close the read end at once: every line the run prints hits a closed
    // pipe.
    drop(child.stdout.take());
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        assert!(started.elapsed() < HANG, "the run hung");
        std::thread::sleep(Duration::from_millis(20));
    };
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    assert!(!stderr.contains("panicked"), "{stderr}");
    #[cfg(unix)]
    {
        use std::os::unix::process::ExitStatusExt;
        assert_eq!(
            status.signal(),
            Some(libc_sigpipe()),
            "{status:?}: {stderr}"
        );
    }
    #[cfg(not(unix))]
    let _ = status;
}

/// SIGPIPE's number on Linux and the BSDs.
#[cfg(unix)]
fn libc_sigpipe() -> i32 {
    13
}
