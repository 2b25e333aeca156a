//! The replay page in a real browser: `simulate --html` writes the page of
//! a collision case through the real binary, headless Chromium (Debian's
//! `chromium` package) loads it, plays it to t = 1.25 s (`#play=1.25`, in
//! virtual time, so the test does not wait for it), and
//!
//! - a screenshot shows each body's colour where the trace (`--trace`,
//!   every digit) puts its centre at that time, mapped through the page's
//!   documented view transform (`harness/src/replay/mod.rs`), and the
//!   background where no body, path or label is: around both bodies, and
//!   where the first body started (it has left);
//! - the DOM after playing shows the time reached and, for the pinned
//!   body, a state readout that matches the trace.
//!
//! Without Chromium the test says so and passes (`.ci/run` installs it).
//! Every browser run is killed after [`BROWSER_TIMEOUT`].

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_harness");
/// The longest a browser run may take before it is killed: a run takes
/// about a second; the bound leaves room for a machine busy compiling.
const BROWSER_TIMEOUT: Duration = Duration::from_secs(90);
/// The window (CSS px, device pixel ratio 1 in headless mode).
const WINDOW: (u32, u32) = (1000, 700);
/// The page's fixed boxes and fill share (`harness::replay`).
const HEADER_PX: f64 = harness::replay::HEADER_PX;
const SIDE_PX: f64 = harness::replay::SIDE_PX;
const FOOTER_PX: f64 = harness::replay::FOOTER_PX;
const FILL: f64 = harness::replay::FILL;
/// The time the page is played to (s): after the impact at 1.0285 s.
const T: f64 = 1.25;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Chromium on the PATH, if any.
fn chromium() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|dir| ["chromium", "chromium-browser"].map(|name| dir.join(name)))
        .find(|p| p.is_file())
}

/// Runs the browser on `url` with `extra` flags, its stdout into a file;
/// kills its process group after [`BROWSER_TIMEOUT`]. Returns stdout.
fn browse(browser: &Path, dir: &Path, name: &str, url: &str, extra: &[String]) -> String {
    use std::os::unix::process::CommandExt;
    let profile = dir.join(format!("profile-{name}"));
    let out_path = dir.join(format!("{name}.stdout"));
    let err_path = dir.join(format!("{name}.stderr"));
    let mut child = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--force-device-scale-factor=1",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("--window-size={},{}", WINDOW.0, WINDOW.1))
        // Virtual time: the page's clock runs as fast as the machine can;
        // the run ends when the page has no timer left (it stops at T).
        .arg("--virtual-time-budget=20000")
        .args(extra)
        .arg(url)
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap())
        .process_group(0)
        .spawn()
        .expect("start chromium");
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait for chromium") {
            break Some(status);
        }
        if started.elapsed() > BROWSER_TIMEOUT {
            break None;
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    // The browser's helpers are in its process group: end them all, by
    // the group's id (the child's pid).
    let group = format!("-{}", child.id());
    let _ = Command::new("kill").args(["-KILL", "--", &group]).status();
    let _ = child.wait();
    let stderr = std::fs::read_to_string(&err_path).unwrap_or_default();
    match status {
        None => {
            panic!("chromium ({name}) did not finish within {BROWSER_TIMEOUT:?}; stderr:\n{stderr}")
        }
        Some(s) if !s.success() => panic!("chromium ({name}) failed: {s}; stderr:\n{stderr}"),
        Some(_) => std::fs::read_to_string(&out_path).unwrap_or_default(),
    }
}

/// The state of `body` at time `t` from the CSV trace, interpolated
/// linearly between the samples around `t`: x, y, vx, vy.
fn trace_state(csv: &str, body: &str, t: f64) -> [f64; 4] {
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|f| f[1] == body)
        .map(|f| {
            [0, 2, 3, 5, 6]
                .map(|i| f[i].parse::<f64>().unwrap())
                .to_vec()
        })
        .collect();
    let k = rows
        .iter()
        .position(|r| r[0] >= t)
        .expect("t within the run");
    if rows[k][0] == t || k == 0 {
        return [rows[k][1], rows[k][2], rows[k][3], rows[k][4]];
    }
    let (a, b) = (&rows[k - 1], &rows[k]);
    let s = (t - a[0]) / (b[0] - a[0]);
    [1, 2, 3, 4].map(|i| a[i] + (b[i] - a[i]) * s)
}

/// The replay's data, read from the page.
fn page_data(html: &str) -> serde_json::Value {
    let tag = "<script id=\"replay-data\" type=\"application/json\">";
    let start = html.find(tag).expect("the data element") + tag.len();
    let end = start + html[start..].find("</script>").unwrap();
    serde_json::from_str(&html[start..end]).expect("the data is JSON")
}

/// The page's documented view transform for a canvas of `w × h` CSS px at
/// (0, HEADER_PX), one panel, zoom 1, no pan: world (x, y) to page pixels.
struct View {
    scale: f64,
    centre: (f64, f64),
    canvas: (f64, f64, f64, f64),
}

impl View {
    fn new(box_: [f64; 4], w: f64, h: f64) -> Self {
        let scale = FILL * (w / (box_[2] - box_[0])).min(h / (box_[3] - box_[1]));
        Self {
            scale,
            centre: (0.5 * (box_[0] + box_[2]), 0.5 * (box_[1] + box_[3])),
            canvas: (0.0, HEADER_PX, w, h),
        }
    }

    fn pixel(&self, x: f64, y: f64) -> (u32, u32) {
        let (left, top, w, h) = self.canvas;
        let px = left + w / 2.0 + self.scale * (x - self.centre.0);
        let py = top + h / 2.0 - self.scale * (y - self.centre.1);
        (px.floor() as u32, py.floor() as u32)
    }
}

fn hex(colour: &str) -> [u8; 3] {
    let n = u32::from_str_radix(colour.trim_start_matches('#'), 16).unwrap();
    [(n >> 16) as u8, (n >> 8) as u8, n as u8]
}

/// The value of the readout cell `key` of run 0, as displayed.
fn readout(dom: &str, key: &str) -> f64 {
    let tag = format!("data-run=\"0\" data-key=\"{key}\">");
    let start = dom
        .find(&tag)
        .unwrap_or_else(|| panic!("no readout of {key}:\n{dom}"))
        + tag.len();
    let end = start + dom[start..].find('<').unwrap();
    dom[start..end]
        .parse()
        .unwrap_or_else(|_| panic!("readout {key} = {:?}", &dom[start..end]))
}

/// An attribute's value in the first element carrying it.
fn attribute(dom: &str, name: &str) -> String {
    let tag = format!(" {name}=\"");
    let start = dom.find(&tag).unwrap_or_else(|| panic!("no {name}")) + tag.len();
    let end = start + dom[start..].find('"').unwrap();
    dom[start..end].to_owned()
}

#[test]
fn the_replay_of_a_collision_plays_in_chromium_and_shows_the_trace() {
    let Some(browser) = chromium() else {
        println!(
            "SKIPPED: no chromium on the PATH: the replay page was not checked in a browser \
             (install Debian's package: apt-get install -y chromium)"
        );
        return;
    };
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = workspace().join("scenes/collision_head_on.toml");
    let page = dir.path().join("head_on.html");
    let trace = dir.path().join("head_on.csv");
    let done = Command::new(BIN)
        .args(["simulate", scene.to_str().unwrap(), "--html"])
        .arg(&page)
        .arg("--trace")
        .arg(&trace)
        .output()
        .expect("run the harness");
    assert!(
        done.status.success(),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let html = std::fs::read_to_string(&page).unwrap();
    let csv = std::fs::read_to_string(&trace).unwrap();
    let data = page_data(&html);
    let view_box: [f64; 4] = serde_json::from_value(data["view"].clone()).unwrap();
    let url = format!("file://{}#play={T}&speed=1&body=m1", page.display());

    // --- the screenshot ---------------------------------------------------
    let shot = dir.path().join("shot.png");
    browse(
        &browser,
        dir.path(),
        "screenshot",
        &url,
        &[format!("--screenshot={}", shot.display())],
    );
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&shot).unwrap()));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut pixels).expect("PNG pixels");
    assert_eq!((info.width, info.height), WINDOW, "screenshot size");
    let channels = info.color_type.samples();
    let at = |(x, y): (u32, u32)| -> [u8; 3] {
        let i = (y as usize * info.width as usize + x as usize) * channels;
        [pixels[i], pixels[i + 1], pixels[i + 2]]
    };
    let (w, h) = (
        WINDOW.0 as f64 - SIDE_PX,
        WINDOW.1 as f64 - HEADER_PX - FOOTER_PX,
    );
    let view = View::new(view_box, w, h);
    // Canvas fills are drawn opaque in the body's sRGB colour and the
    // screenshot is taken in sRGB without colour management: a pixel
    // inside a body is exactly its colour (antialiasing touches only the
    // outline).
    let close = |got: [u8; 3], want: [u8; 3]| got == want;
    let bodies = data["bodies"].as_array().unwrap();
    let white = [255, 255, 255];
    for (index, name) in [(0, "m1"), (1, "m2")] {
        let colour = hex(bodies[index]["colour"].as_str().unwrap());
        let radius = bodies[index]["radius"].as_f64().unwrap();
        let [x, y, _, _] = trace_state(&csv, name, T);
        // Inside: the centre, and 0.85 r out along the four diagonals (the
        // rim tick that shows the turn points along +x, the path runs
        // along y = 0, the name stands above). Outside: 1.2 r out along
        // the diagonals, nothing is drawn. The 0.15-0.2 r margins (9 px
        // and more) dwarf the outline's antialiasing (1 px), and a body
        // drawn as little as 0.2 r (12 px) off fails one of them.
        let d = std::f64::consts::FRAC_1_SQRT_2;
        let mut inside = vec![(0.0, 0.0)];
        let mut outside = Vec::new();
        for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
            inside.push((0.85 * d * sx * radius, 0.85 * d * sy * radius));
            outside.push((1.2 * d * sx * radius, 1.2 * d * sy * radius));
        }
        for (dx, dy) in inside {
            let p = view.pixel(x + dx, y + dy);
            assert!(
                close(at(p), colour),
                "{name} at ({}, {}) m = pixel {p:?}: {:?}, expected its colour {colour:?}",
                x + dx,
                y + dy,
                at(p)
            );
        }
        for (dx, dy) in outside {
            let p = view.pixel(x + dx, y + dy);
            assert_eq!(at(p), white, "{name}: background beside it at pixel {p:?}");
        }
    }
    // Where m1 started, 0.35 m off the path's line: it has left.
    let [x0, y0, _, _] = trace_state(&csv, "m1", 0.0);
    let p = view.pixel(x0, y0 + 0.35);
    assert_eq!(
        at(p),
        white,
        "m1's start at pixel {p:?} should be empty by t = {T} s"
    );

    // --- the DOM after playing ---------------------------------------------
    let dom = browse(
        &browser,
        dir.path(),
        "dom",
        &url,
        &["--dump-dom".to_string()],
    );
    let shown_t: f64 = attribute(&dom, "data-t").parse().unwrap();
    assert_eq!(shown_t, T, "the page stops at the fragment's time");
    assert!(dom.contains("t = 1.250 s of 2.000 s"), "time shown:\n{dom}");
    assert_eq!(attribute(&dom, "data-body"), "m1");
    // The canvas reports the documented transform for its own size.
    let (cw, ch): (f64, f64) = (
        attribute(&dom, "data-width").parse().unwrap(),
        attribute(&dom, "data-height").parse().unwrap(),
    );
    let scale: f64 = attribute(&dom, "data-scale").parse().unwrap();
    let expected = View::new(view_box, cw, ch).scale;
    assert!(
        (scale - expected).abs() <= 1e-9 * expected,
        "{scale} vs {expected}"
    );
    assert_eq!(attribute(&dom, "data-top"), HEADER_PX.to_string());
    // The readout against the trace. The page interpolates positions
    // between kept samples within its stated tolerance and rounds to its
    // quantum (half a quantum each for storage and display); after the
    // impact the velocity is constant, so interpolating it is exact.
    let run = &data["runs"][0];
    let tolerance = data["tolerance"].as_f64().unwrap();
    let (q_p, q_v) = (
        run["q"]["p"].as_f64().unwrap(),
        run["q"]["v"].as_f64().unwrap(),
    );
    let [x, y, vx, vy] = trace_state(&csv, "m1", T);
    for (key, want, bound) in [
        ("x", x, tolerance + q_p),
        ("y", y, tolerance + q_p),
        ("vx", vx, q_v),
        ("vy", vy, q_v),
    ] {
        let got = readout(&dom, key);
        assert!(
            (got - want).abs() <= bound,
            "readout {key} = {got}, trace {want} (± {bound})"
        );
    }
    // Kinetic energy ½ m v² of the 1 kg disc, shown to 6 significant digits.
    let kinetic = readout(&dom, "kinetic");
    assert!(
        (kinetic - 0.5 * (vx * vx + vy * vy)).abs() <= 1e-5,
        "{kinetic}"
    );
}
