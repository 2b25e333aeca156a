//! The live view as a person uses it (`harness view`, docs/view.md; built
//! with `--features view`, so `cargo test --workspace` leaves it out):
//!
//! - headless, `--screenshot` draws each body where the engine's state
//!   (`--state-out`) puts it, through the camera written with it;
//! - in a real window under Xvfb, xdotool presses the mouse on a box,
//!   drags it up and to the right and holds it there, presses Space
//!   (pause) and S (one step); the state the view writes on D says the
//!   step count moved by exactly one and the box's centre is where the
//!   cursor took it, and a screenshot of the window (`xwd`) shows the box's
//!   colour there and none where it started.
//!
//! Without Xvfb, xdotool or xwd (Debian: `xvfb`, `xdotool`, `x11-apps`;
//! winit also needs `libxkbcommon-x11-0`) the window test says so and
//! passes; `.ci/run` installs them. Every process is killed after
//! [`PATIENCE`].

use harness::view::drag::DRAG_HERTZ;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_harness");
/// The longest any wait lasts before the test fails (the machine may be
/// busy compiling).
const PATIENCE: Duration = Duration::from_secs(60);
/// The window's size (px).
const WINDOW: (u32, u32) = (800, 600);
/// The box's colour in the scene.
const BOX: [u8; 3] = [0xd6, 0x27, 0x28];
/// Gravity (m/s²) of the scene.
const G: f64 = 10.0;

/// A ground and one 1 m box resting on it, under the soft step.
const SCENE: &str = r##"
[simulation]
dt = 0.016666666666666666
duration = 100.0
gravity = [0.0, -10.0]

[contact]
friction = 0.6

[[bodies]]
name = "ground"
kind = "static"
shape = { type = "box", width = 12.0, height = 1.0 }
position = [0.0, -0.5]
colour = "#7f7f7f"

[[bodies]]
name = "box"
density = 1.0
shape = { type = "box", width = 1.0, height = 1.0 }
position = [0.0, 0.5]
colour = "#d62728"
"##;

/// Ends a child process when dropped (a failed assertion included): by
/// SIGTERM, so that Xvfb removes its lock and socket, then SIGKILL after a
/// second.
struct Killed(Child);

impl Drop for Killed {
    fn drop(&mut self) {
        if let Ok(pid) = i32::try_from(self.0.id()) {
            // SAFETY: signalling our own child, which has not been reaped.
            unsafe { libc::kill(pid, libc::SIGTERM) };
        }
        let started = Instant::now();
        while started.elapsed() < Duration::from_secs(1) {
            if let Ok(Some(_)) = self.0.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn write_scene(dir: &Path) -> PathBuf {
    let path = dir.join("drag.toml");
    std::fs::write(&path, SCENE).unwrap();
    path
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The camera of a state file: pixel of a world point.
fn to_screen(state: &Value, x: f64, y: f64) -> (f64, f64) {
    let c = &state["camera"];
    let (cx, cy) = (
        c["centre"][0].as_f64().unwrap(),
        c["centre"][1].as_f64().unwrap(),
    );
    let scale = c["scale"].as_f64().unwrap();
    let (w, h) = (c["width"].as_f64().unwrap(), c["height"].as_f64().unwrap());
    (0.5 * w + (x - cx) * scale, 0.5 * h - (y - cy) * scale)
}

fn to_world(state: &Value, px: f64, py: f64) -> (f64, f64) {
    let c = &state["camera"];
    let (cx, cy) = (
        c["centre"][0].as_f64().unwrap(),
        c["centre"][1].as_f64().unwrap(),
    );
    let scale = c["scale"].as_f64().unwrap();
    let (w, h) = (c["width"].as_f64().unwrap(), c["height"].as_f64().unwrap());
    (cx + (px - 0.5 * w) / scale, cy - (py - 0.5 * h) / scale)
}

fn body<'a>(state: &'a Value, name: &str) -> &'a Value {
    state["bodies"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["name"] == name)
        .unwrap_or_else(|| panic!("no body '{name}' in {state}"))
}

fn xy(body: &Value) -> (f64, f64) {
    (body["x"].as_f64().unwrap(), body["y"].as_f64().unwrap())
}

#[test]
fn the_screenshot_draws_each_body_where_the_engine_has_it() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_scene(dir.path());
    let png_path = dir.path().join("shot.png");
    let state_path = dir.path().join("state.json");
    let out = Command::new(BIN)
        .args([
            "view",
            scene.to_str().unwrap(),
            "--steps",
            "30",
            "--size",
            "640x400",
        ])
        .arg("--screenshot")
        .arg(&png_path)
        .arg("--state-out")
        .arg(&state_path)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let state = read_json(&state_path);
    assert_eq!(state["steps"], 30);
    let (x, y) = xy(body(&state, "box"));
    // 30 steps at rest on the ground: the soft step's contact holds it
    // within its slop (5 mm) of y = 0.5.
    assert!(
        x.abs() < 0.005 && (y - 0.5).abs() < 0.005,
        "box at ({x}, {y})"
    );
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(&png_path).unwrap(),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut pixels).unwrap();
    assert_eq!((info.width, info.height), (640, 400));
    let at = |px: f64, py: f64| {
        let i = 3 * (py as usize * info.width as usize + px as usize);
        [pixels[i], pixels[i + 1], pixels[i + 2]]
    };
    let (px, py) = to_screen(&state, x, y);
    assert_eq!(at(px, py), BOX, "the box's centre, pixel ({px}, {py})");
    let (gx, gy) = to_screen(&state, 4.0, -0.5);
    assert_eq!(at(gx, gy), [0x7f, 0x7f, 0x7f], "the ground at (4, -0.5) m");
    let (ax, ay) = to_screen(&state, 2.0, 1.5);
    assert_ne!(at(ax, ay), BOX, "above the ground, 2 m right of the box");
}

/// A ground and a box dropped tilted onto it, under the soft step (the
/// scene of `--compare box2d`'s test: the box falls, lands and tumbles).
const COMPARE_SCENE: &str = r##"
[simulation]
dt = 0.016666666666666666
duration = 100.0
gravity = [0.0, -10.0]

[contact]
friction = 0.6

[[bodies]]
name = "ground"
kind = "static"
shape = { type = "box", width = 12.0, height = 1.0 }
position = [0.0, -0.5]
colour = "#7f7f7f"

[[bodies]]
name = "box"
density = 1.0
shape = { type = "box", width = 1.0, height = 1.0 }
position = [0.0, 1.5]
angle = 0.4
colour = "#d62728"
"##;

/// The test scene built by hand in Box2D through the adapter, stepped
/// `steps` times: the bodies' (x, y, angle).
fn box2d_by_hand(steps: usize) -> Vec<[f64; 3]> {
    use references::box2d_world::Box2dWorld;
    use references::many_body::{BodyKind, ManyBodyEngine, ManyBodyScene, SceneBody};
    let rectangle = |w, h| engine::Shape::rectangle(w, h).unwrap();
    let ground = SceneBody {
        kind: BodyKind::Static,
        ..SceneBody::dynamic(rectangle(12.0, 1.0), [0.0, -0.5], 0.0)
    };
    let tilted = SceneBody {
        angle: 0.4,
        ..SceneBody::dynamic(rectangle(1.0, 1.0), [0.0, 1.5], 1.0)
    };
    // The soft step's defaults the scene leaves: 4 substeps, friction 0.6
    // (the scene's), restitution 0.
    let scene = ManyBodyScene {
        gravity: [0.0, -10.0],
        dt: 0.016666666666666666,
        substeps: 4,
        bodies: vec![ground, tilted],
        joints: Vec::new(),
    };
    let mut world = Box2dWorld::new(&scene).unwrap();
    for _ in 0..steps {
        world.step().unwrap();
    }
    let mut samples = Vec::new();
    world.samples(&mut samples).unwrap();
    samples
        .iter()
        .map(|s| [s.position[0], s.position[1], s.angle])
        .collect()
}

#[test]
fn the_compare_screenshot_draws_both_engines_and_box2d_moves_as_its_adapter() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("compare.toml");
    std::fs::write(&scene, COMPARE_SCENE).unwrap();
    let png_path = dir.path().join("shot.png");
    let state_path = dir.path().join("state.json");
    const STEPS: usize = 50;
    let out = Command::new(BIN)
        .args(["view", scene.to_str().unwrap(), "--compare", "box2d"])
        .args(["--steps", &STEPS.to_string(), "--size", "800x400"])
        .arg("--screenshot")
        .arg(&png_path)
        .arg("--state-out")
        .arg(&state_path)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let state = read_json(&state_path);
    let reference = &state["reference"];
    assert_eq!(state["steps"], STEPS);
    assert_eq!(reference["steps"], STEPS, "in sync: as many steps");
    assert_eq!(reference["substeps"], 4);
    // The view's Box2D bodies are those of the adapter stepped alone from
    // the scene written by hand: Box2D is deterministic on one thread, so
    // the same bits, read back from JSON (serde_json's parser may round
    // the last bit: 2 ulps allowed).
    let expected = box2d_by_hand(STEPS);
    let got = reference["bodies"].as_array().unwrap();
    assert_eq!(got.len(), expected.len());
    for (g, e) in got.iter().zip(&expected) {
        for k in 0..3 {
            let g = g[k].as_f64().unwrap();
            assert!(
                (g - e[k]).abs() <= 2.0 * f64::EPSILON * e[k].abs(),
                "view's Box2D {g} against the adapter's {}",
                e[k]
            );
        }
    }
    // The box has moved: it fell 1 m and more in 50 steps.
    assert!(expected[1][1] < 1.0, "{expected:?}");
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(&png_path).unwrap(),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut pixels).unwrap();
    assert_eq!((info.width, info.height), (800, 400));
    // The camera written is the left panel's; the right panel is the same
    // camera 400 px to the right.
    assert_eq!(state["camera"]["width"], 400);
    let at = |px: f64, py: f64| {
        let i = 3 * (py as usize * info.width as usize + px as usize);
        [pixels[i], pixels[i + 1], pixels[i + 2]]
    };
    let (x, y) = xy(body(&state, "box"));
    let (px, py) = to_screen(&state, x, y);
    assert!(px < 400.0);
    assert_eq!(at(px, py), BOX, "our box's centre, pixel ({px}, {py})");
    let (rx, ry) = to_screen(&state, expected[1][0], expected[1][1]);
    assert_eq!(
        at(rx + 400.0, ry),
        BOX,
        "Box2D's box, pixel ({rx} + 400, {ry})"
    );
    let (gx, gy) = to_screen(&state, 4.0, -0.5);
    for offset in [0.0, 400.0] {
        assert_eq!(at(gx + offset, gy), [0x7f, 0x7f, 0x7f], "the ground");
    }
    // Each half holds the box's colour: both panels drew their bodies.
    for half in [0..400, 400..800] {
        let boxes = (0..400)
            .flat_map(|y| half.clone().map(move |x| (x, y)))
            .filter(|&(x, y)| at(f64::from(x), f64::from(y)) == BOX)
            .count();
        assert!(boxes > 100, "{boxes} box pixels in {half:?}");
    }
}

#[test]
fn a_scene_the_reference_refuses_is_refused_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    // Contacts off (no [contact]) with two bodies: Box2D's adapter takes
    // one body only then.
    let scene = dir.path().join("no_contact.toml");
    std::fs::write(&scene, SCENE.replace("[contact]\nfriction = 0.6\n", "")).unwrap();
    let out = Command::new(BIN)
        .args(["view", scene.to_str().unwrap(), "--compare", "box2d"])
        .args(["--screenshot", dir.path().join("x.png").to_str().unwrap()])
        .env_remove("DISPLAY")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("--compare box2d") && err.contains("single body only"),
        "{err}"
    );
    assert!(!dir.path().join("x.png").exists());
}

/// `name` on the PATH, if any.
fn which(name: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|dir| dir.join(name))
        .find(|p| p.is_file())
}

/// Runs a command with `DISPLAY`, killing it after [`PATIENCE`]; its
/// stdout.
fn run(display: &str, program: &Path, args: &[&str]) -> String {
    let mut child = Killed(
        Command::new(program)
            .args(args)
            .env("DISPLAY", display)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap(),
    );
    let started = Instant::now();
    loop {
        if let Some(status) = child.0.try_wait().unwrap() {
            let mut out = String::new();
            let mut err = String::new();
            use std::io::Read;
            child
                .0
                .stdout
                .take()
                .unwrap()
                .read_to_string(&mut out)
                .unwrap();
            child
                .0
                .stderr
                .take()
                .unwrap()
                .read_to_string(&mut err)
                .unwrap();
            assert!(status.success(), "{program:?} {args:?}: {status}: {err}");
            return out;
        }
        assert!(
            started.elapsed() < PATIENCE,
            "{program:?} {args:?} did not end"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Waits until `ready` says yes, for at most [`PATIENCE`].
fn wait_for(what: &str, mut ready: impl FnMut() -> bool) {
    let started = Instant::now();
    while !ready() {
        assert!(started.elapsed() < PATIENCE, "gave up waiting for {what}");
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// An Xvfb on a display number it finds free, once it accepts
/// connections (`-displayfd`: it writes the number when ready), and the
/// number.
fn start_xvfb(xvfb: &Path) -> (String, Killed) {
    use std::io::BufRead;
    let mut server = Killed(
        Command::new(xvfb)
            .args([
                "-displayfd",
                "1",
                "-screen",
                "0",
                "1024x768x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap(),
    );
    let stdout = server.0.stdout.take().unwrap();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = std::io::BufReader::new(stdout).read_line(&mut line);
        let _ = tx.send(line);
    });
    let line = rx
        .recv_timeout(PATIENCE)
        .expect("Xvfb did not say its display");
    let number: u32 = line
        .trim()
        .parse()
        .unwrap_or_else(|_| panic!("Xvfb said '{line}'"));
    (format!(":{number}"), server)
}

/// An `xwd` picture (ZPixmap, 24 or 32 bits per pixel, true colour).
struct Xwd {
    width: usize,
    height: usize,
    bytes_per_line: usize,
    bytes_per_pixel: usize,
    lsb_first: bool,
    masks: [u32; 3],
    data: Vec<u8>,
}

impl Xwd {
    fn parse(bytes: &[u8]) -> Self {
        let field = |i: usize| u32::from_be_bytes(bytes[4 * i..4 * i + 4].try_into().unwrap());
        let header = field(0) as usize;
        assert_eq!(field(2), 2, "xwd: a ZPixmap");
        let bits = field(11) as usize;
        assert!(bits == 24 || bits == 32, "xwd: {bits} bits per pixel");
        let colours = field(19) as usize;
        let start = header + 12 * colours;
        Self {
            width: field(4) as usize,
            height: field(5) as usize,
            bytes_per_line: field(12) as usize,
            bytes_per_pixel: bits / 8,
            lsb_first: field(7) == 0,
            masks: [field(14), field(15), field(16)],
            data: bytes[start..].to_vec(),
        }
    }

    fn rgb(&self, x: usize, y: usize) -> [u8; 3] {
        assert!(
            x < self.width && y < self.height,
            "({x}, {y}) outside the picture"
        );
        let i = y * self.bytes_per_line + x * self.bytes_per_pixel;
        let raw = &self.data[i..i + self.bytes_per_pixel];
        let mut v = 0u32;
        for k in 0..self.bytes_per_pixel {
            let byte = if self.lsb_first {
                raw[self.bytes_per_pixel - 1 - k]
            } else {
                raw[k]
            };
            v = (v << 8) | u32::from(byte);
        }
        self.masks.map(|m| ((v & m) >> m.trailing_zeros()) as u8)
    }
}

#[test]
fn a_box_dragged_with_the_mouse_goes_where_the_cursor_took_it() {
    let tools = ["Xvfb", "xdotool", "xwd"].map(which);
    let [Some(xvfb), Some(xdotool), Some(xwd)] = tools else {
        println!(
            "skipped: the window test needs Xvfb, xdotool and xwd (Debian: xvfb, xdotool, \
             x11-apps; and libxkbcommon-x11-0 for winit); .ci/run installs them"
        );
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let scene = write_scene(dir.path());
    let state_path = dir.path().join("state.json");
    let (display, _server) = start_xvfb(&xvfb);
    let size = format!("{}x{}", WINDOW.0, WINDOW.1);
    let log = dir.path().join("view.log");
    let mut view = Killed(
        Command::new(BIN)
            .args([
                "view",
                scene.to_str().unwrap(),
                "--size",
                &size,
                "--state-out",
            ])
            .arg(&state_path)
            .env("DISPLAY", &display)
            .env_remove("WAYLAND_DISPLAY")
            .stdout(Stdio::null())
            .stderr(std::fs::File::create(&log).unwrap())
            .spawn()
            .unwrap(),
    );
    let xdo = |args: &[&str]| run(&display, &xdotool, args);
    let search = || {
        let out = Command::new(&xdotool)
            .args(["search", "--name", "harness view"])
            .env("DISPLAY", &display)
            .output()
            .unwrap();
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .next()
            .map(str::to_owned)
    };
    let mut window = None;
    wait_for("the view's window", || {
        if let Some(status) = view.0.try_wait().unwrap() {
            panic!(
                "the view ended ({status}): {}",
                std::fs::read_to_string(&log).unwrap()
            );
        }
        window = search();
        window.is_some()
    });
    let window = window.unwrap();
    xdo(&["windowfocus", &window]);
    // D writes the state; each new state is told by its file appearing.
    let dump = || {
        let _ = std::fs::remove_file(&state_path);
        xdo(&["key", "d"]);
        wait_for("the state file", || state_path.exists());
        read_json(&state_path)
    };
    // Let the first frames be drawn and the box settle.
    std::thread::sleep(Duration::from_millis(1500));
    let before = dump();
    assert_eq!(before["running"], true, "{before}");
    let (x0, y0) = xy(body(&before, "box"));
    let (px0, py0) = to_screen(&before, x0, y0);
    let (press_x, press_y) = (px0.round(), py0.round());
    // The cursor's end: 3 m right and 2 m up, to a whole pixel.
    let (px1, py1) = to_screen(&before, x0 + 3.0, y0 + 2.0);
    let (px1, py1) = (px1.round(), py1.round());
    let scale = before["camera"]["scale"].as_f64().unwrap();
    let pixel = |v: f64| format!("{}", v as i64);
    xdo(&[
        "mousemove",
        "--window",
        &window,
        &pixel(press_x),
        &pixel(press_y),
    ]);
    std::thread::sleep(Duration::from_millis(200));
    xdo(&["mousedown", "1"]);
    for k in 1..=20 {
        let f = f64::from(k) / 20.0;
        let x = press_x + f * (px1 - press_x);
        let y = press_y + f * (py1 - press_y);
        xdo(&[
            "mousemove",
            "--window",
            &window,
            &pixel(x.round()),
            &pixel(y.round()),
        ]);
        std::thread::sleep(Duration::from_millis(30));
    }
    // Held at the end long enough for the pull (5 Hz, ζ = 0.7: its
    // transient decays as exp(−ζ 2π f t), e^-33 after 1.5 s) to settle.
    std::thread::sleep(Duration::from_millis(2500));
    xdo(&["key", "space"]);
    std::thread::sleep(Duration::from_millis(300));
    let paused = dump();
    assert_eq!(paused["running"], false, "Space pauses: {paused}");
    assert_eq!(paused["dragging"], 1, "the box is held: {paused}");
    xdo(&["key", "s"]);
    std::thread::sleep(Duration::from_millis(300));
    let stepped = dump();
    let steps = |s: &Value| s["steps"].as_u64().unwrap();
    assert_eq!(steps(&stepped), steps(&paused) + 1, "S takes one step");
    // Where the cursor is, in the world (the view's own mapping, written
    // with the state).
    let (tx, ty) = to_world(&stepped, px1, py1);
    let (x, y) = xy(body(&stepped, "box"));
    // The box hangs from the pull: a spring of ω = 2π·5 Hz holding its
    // weight stretches g/ω² (10 mm); the grabbed point is within half a
    // pixel's diagonal of the centre, and the pixels are whole.
    let omega = 2.0 * std::f64::consts::PI * DRAG_HERTZ;
    let tolerance = 2.0 * G / (omega * omega) + 1.5 / scale;
    let miss = ((x - tx).powi(2) + (y - ty).powi(2)).sqrt();
    assert!(
        miss <= tolerance,
        "box at ({x:.4}, {y:.4}) m, cursor at ({tx:.4}, {ty:.4}) m: {miss:.4} m apart > {tolerance:.4} m"
    );
    // The screen: the box's colour under the cursor, none where it was.
    let shot = dir.path().join("window.xwd");
    run(
        &display,
        &xwd,
        &["-id", &window, "-silent", "-out", shot.to_str().unwrap()],
    );
    let picture = Xwd::parse(&std::fs::read(&shot).unwrap());
    assert_eq!(
        (picture.width, picture.height),
        (WINDOW.0 as usize, WINDOW.1 as usize)
    );
    // A point of the box a quarter metre from its centre (where the drag's
    // marks are), in the box's frame.
    let angle = body(&stepped, "box")["angle"].as_f64().unwrap();
    let (s, c) = angle.sin_cos();
    let (qx, qy) = (x + 0.25 * c + 0.25 * s, y + 0.25 * s - 0.25 * c);
    let (bx, by) = to_screen(&stepped, qx, qy);
    assert_eq!(
        picture.rgb(bx as usize, by as usize),
        BOX,
        "the box where the engine has it"
    );
    assert_ne!(
        picture.rgb(px0 as usize, py0 as usize),
        BOX,
        "the box has left where it was"
    );
    xdo(&["mouseup", "1"]);
    xdo(&["key", "q"]);
    let started = Instant::now();
    let status = loop {
        if let Some(status) = view.0.try_wait().unwrap() {
            break status;
        }
        assert!(started.elapsed() < PATIENCE, "Q did not close the view");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(
        status.success(),
        "{}",
        std::fs::read_to_string(&log).unwrap()
    );
}
