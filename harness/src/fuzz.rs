//! The fuzz target, on the stable toolchain: arbitrary and mutated scene
//! text, and random small worlds written as scene text, through
//! `Scene::parse_bytes` and, when it loads, `build_world` (or the
//! `[linear_test]` ODE) and a few steps through `simulate`'s recorder. Each
//! case must hold:
//!
//! - no panic;
//! - bounded work: at most [`STEPS`] steps of the file's `dt` are taken,
//!   and the text is at most a few kilobytes. A `dormand_prince` scene is
//!   stepped with `rk4` instead: an adaptive step's work is not bounded by
//!   the step count (a stiff scene, such as a 1e-16 kg body on a 400 N/m
//!   spring, legitimately takes 1e7 substeps per 0.01 s);
//! - no non-finite figure returned as success: after every step that
//!   succeeds, every body's state and the world's energy are finite (a
//!   `[linear_test]`'s y, its exact solution and their difference too);
//! - every refusal is located and in the user's words: a line, and none of
//!   serde's or Rust's internal names, and no number printed with dozens of
//!   digits.
//!
//! The mutations start from the project's own scene files (`scenes/` and
//! `scenes/examples/`): lines deleted, duplicated or swapped, numbers
//! replaced by extremes (1e308, -0, nan, inf, 1e-320, huge integers,
//! strings, dates), truncations at any character, bytes that are not UTF-8
//! (Latin-1 accents, UTF-16 byte-order marks, zeros); plus short random
//! text; plus random worlds: one to five circles, boxes and regular
//! polygons of random sizes, poses and velocities (overlapping or apart)
//! on a ground, under either contact model (the exact one with each of its
//! searches), with random restitution and friction.
//!
//! [`run`] runs a deterministic sequence of cases. `cargo test -p harness
//! --test fuzz_scenes` runs a bounded number; the harness's full run runs
//! more and reports the figure (case `fuzz_scenes`); a long run is one
//! command (see the test file).

use crate::progress::Ticker;
use crate::simulate::{RunLimits, record};
use engine::Method;
use engine::time_grid::grid_time;
use indicatif::ProgressBar;
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use scene::Scene;
use std::fmt::Write as _;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

/// Steps taken on each scene that loads: enough to cross a first step and
/// a force switch, small enough that a case costs milliseconds.
const STEPS: u64 = 3;

/// Values a number is replaced by: f64's extremes, TOML's special floats,
/// integers beyond i64, and values of the wrong type.
const EXTREMES: &[&str] = &[
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "-0",
    "-0.0",
    "0",
    "-1",
    "nan",
    "inf",
    "-inf",
    "1e-320",
    "-1e-320",
    "1e-200",
    "1e155",
    "1.3e154",
    "1e200",
    "99999999999999999999",
    "-99999999999999999999",
    "\"x\"",
    "true",
    "[]",
    "{}",
    "1979-05-27",
    "[1e308, -1e308]",
    "1e-16",
];

/// One edit of a scene's text. Indices are taken modulo what they index,
/// so that any generated value applies to any text.
#[derive(Debug, Clone)]
enum Mutation {
    DeleteLine(usize),
    DuplicateLine(usize),
    SwapLines(usize, usize),
    ReplaceNumber(usize, usize),
    Truncate(usize),
    InsertText(usize, String),
    InsertByte(usize, u8),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        1 => any::<usize>().prop_map(Mutation::DeleteLine),
        1 => any::<usize>().prop_map(Mutation::DuplicateLine),
        1 => (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        4 => (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::ReplaceNumber(a, b)),
        1 => any::<usize>().prop_map(Mutation::Truncate),
        1 => (any::<usize>(), "[a-z_\\[\\]{}=., 0-9\"#-]{0,24}")
            .prop_map(|(a, s)| Mutation::InsertText(a, s)),
        1 => (any::<usize>(), prop::sample::select(vec![0xE9u8, 0xFF, 0xFE, 0x00, 0x80, 0xC3]))
            .prop_map(|(a, b)| Mutation::InsertByte(a, b)),
    ]
}

/// A fuzz input: a seed file with edits, random text, or a random world.
#[derive(Debug, Clone)]
enum Input {
    Mutated(usize, Vec<Mutation>),
    Random(String),
    World(WorldSeed),
}

/// One body of a random world: shape kind, size (m), vertex count, pose
/// (m, rad), velocity (m/s), angular velocity (rad/s).
type BodySeed = (u8, f64, u8, (f64, f64), f64, (f64, f64), f64);

/// A random world: its bodies, the contact model (0 soft step, 1–3 the
/// exact model with the swept, bisection or advancement search),
/// restitution and friction.
type WorldSeed = (Vec<BodySeed>, u8, f64, f64);

fn body_seed() -> impl Strategy<Value = BodySeed> {
    (
        any::<u8>(),
        0.05f64..2.0,
        3u8..9,
        (-3.0f64..3.0, 0.0f64..6.0),
        -3.2f64..3.2,
        (-40.0f64..40.0, -40.0f64..40.0),
        -20.0f64..20.0,
    )
}

fn world_seed() -> impl Strategy<Value = WorldSeed> {
    (
        prop::collection::vec(body_seed(), 1..6),
        0u8..4,
        0.0f64..1.0,
        0.0f64..1.5,
    )
}

fn input() -> impl Strategy<Value = Input> {
    prop_oneof![
        8 => (any::<usize>(), prop::collection::vec(mutation(), 1..5))
            .prop_map(|(seed, edits)| Input::Mutated(seed, edits)),
        1 => "[\\[\\]a-z_=\"., \n{}#0-9-]{0,160}".prop_map(Input::Random),
        2 => world_seed().prop_map(Input::World),
    ]
}

/// A random world as a scene file.
fn world_text((bodies, model, restitution, friction): &WorldSeed) -> String {
    let exact = *model > 0;
    let mut text = format!(
        "[simulation]\nmethod = \"{}\"\ndt = 0.01\nduration = 0.05\n\
         [[bodies]]\nname = \"ground\"\nkind = \"static\"\n\
         shape = {{ type = \"box\", width = 20.0, height = 1.0 }}\nposition = [0.0, -0.5]\n\
         [[forces]]\ntype = \"gravity\"\ng = [0.0, -9.81]\n\
         [contact]\nmodel = \"{}\"\nrestitution = {restitution:?}\nfriction = {friction:?}\n",
        if exact { "rk4" } else { "semi_implicit_euler" },
        if exact { "exact" } else { "soft_step" },
    );
    if exact {
        let search = ["swept", "bisection", "conservative_advancement"][(*model as usize - 1) % 3];
        let _ = writeln!(text, "toi_method = \"{search}\"");
    }
    for (i, (kind, size, corners, (x, y), angle, (vx, vy), w)) in bodies.iter().enumerate() {
        let shape = match kind % 3 {
            0 => format!("{{ type = \"circle\", radius = {size:?} }}"),
            1 => format!(
                "{{ type = \"box\", width = {size:?}, height = {:?} }}",
                0.5 * size + 0.01
            ),
            _ => {
                // A regular polygon: convex and counter-clockwise.
                let n = *corners as usize;
                let vertices: Vec<String> = (0..n)
                    .map(|k| {
                        let a = std::f64::consts::TAU * k as f64 / n as f64;
                        format!("[{:?}, {:?}]", size * a.cos(), size * a.sin())
                    })
                    .collect();
                format!(
                    "{{ type = \"polygon\", vertices = [{}] }}",
                    vertices.join(", ")
                )
            }
        };
        let _ = write!(
            text,
            "[[bodies]]\nname = \"b{i}\"\nmass = {:?}\nshape = {shape}\n\
             position = [{x:?}, {y:?}]\nangle = {angle:?}\nvelocity = [{vx:?}, {vy:?}]\n\
             angular_velocity = {w:?}\n",
            1.0 + size
        );
    }
    text
}

/// The project's scene files, in a fixed order.
pub fn seeds() -> Vec<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut paths = Vec::new();
    for dir in [root.clone(), root.join("examples")] {
        for entry in std::fs::read_dir(&dir).expect("scenes folder") {
            let path = entry.expect("entry").path();
            if path.extension().is_some_and(|e| e == "toml") {
                paths.push(path);
            }
        }
    }
    paths.sort();
    paths
        .iter()
        .map(|p| std::fs::read_to_string(p).expect("read a scene"))
        .collect()
}

/// Byte ranges of the number literals in `text` (a sign, digits, `.`,
/// `_`, exponents), not counting digits inside names.
fn numbers(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts = bytes[i].is_ascii_digit()
            || (matches!(bytes[i], b'-' | b'+')
                && bytes.get(i + 1).is_some_and(u8::is_ascii_digit));
        let after_word = i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
        if starts && !after_word {
            let start = i;
            i += 1;
            while i < bytes.len()
                && (bytes[i].is_ascii_alphanumeric()
                    || matches!(bytes[i], b'.' | b'_' | b'-' | b'+'))
            {
                i += 1;
            }
            out.push((start, i));
        } else {
            i += 1;
        }
    }
    out
}

fn apply(bytes: &[u8], edit: &Mutation) -> Vec<u8> {
    if let Mutation::InsertByte(at, byte) = edit {
        let at = at % (bytes.len() + 1);
        let mut out = bytes.to_vec();
        out.insert(at, *byte);
        return out;
    }
    // The text edits work on text: bytes made invalid by an earlier edit
    // are kept as they are.
    let Ok(text) = std::str::from_utf8(bytes) else {
        return bytes.to_vec();
    };
    apply_text(text, edit).into_bytes()
}

fn apply_text(text: &str, edit: &Mutation) -> String {
    let mut lines: Vec<&str> = text.split('\n').collect();
    let n = lines.len().max(1);
    match edit {
        Mutation::DeleteLine(i) => {
            lines.remove(i % n);
            lines.join("\n")
        }
        Mutation::DuplicateLine(i) => {
            let line = lines[i % n];
            lines.insert(i % n, line);
            lines.join("\n")
        }
        Mutation::SwapLines(a, b) => {
            lines.swap(a % n, b % n);
            lines.join("\n")
        }
        Mutation::ReplaceNumber(which, value) => {
            let found = numbers(text);
            if found.is_empty() {
                return text.to_owned();
            }
            let (start, end) = found[which % found.len()];
            format!(
                "{}{}{}",
                &text[..start],
                EXTREMES[value % EXTREMES.len()],
                &text[end..]
            )
        }
        Mutation::Truncate(at) => {
            let mut at = at % (text.len() + 1);
            while !text.is_char_boundary(at) {
                at -= 1;
            }
            text[..at].to_owned()
        }
        Mutation::InsertText(at, inserted) => {
            let mut at = at % (text.len() + 1);
            while !text.is_char_boundary(at) {
                at -= 1;
            }
            format!("{}{inserted}{}", &text[..at], &text[at..])
        }
        Mutation::InsertByte(..) => text.to_owned(),
    }
}

fn bytes_of(input: &Input, seeds: &[String]) -> Vec<u8> {
    match input {
        Input::Random(text) => text.clone().into_bytes(),
        Input::World(world) => world_text(world).into_bytes(),
        Input::Mutated(seed, edits) => edits
            .iter()
            .fold(seeds[seed % seeds.len()].clone().into_bytes(), |t, e| {
                apply(&t, e)
            }),
    }
}

/// Words of serde and Rust that a user's message must not show.
const JARGON: &[&str] = &[
    "$__toml",
    "struct ",
    "enum ",
    "variant identifier",
    "i128",
    "Spec",
    "sequence",
    "map,",
    "recursion limit",
];

/// Checks one scene text: whether it loaded, and `Err` saying which
/// property failed.
fn check(bytes: &[u8]) -> (Option<bool>, Result<(), String>) {
    match Scene::parse_bytes("fuzz.toml", bytes) {
        Ok(scene) => (Some(true), check_run(&scene)),
        Err(e) => (Some(false), check_refusal(&e)),
    }
}

/// The method stepped: the file's, or `rk4` for the adaptive one, whose
/// work per step has no bound.
fn bounded(method: Method) -> Method {
    if method.is_adaptive() {
        Method::Rk4
    } else {
        method
    }
}

/// A loaded scene: a few steps, every figure finite.
fn check_run(scene: &Scene) -> Result<(), String> {
    if let Some(test) = scene.linear_test() {
        let duration = scene.duration().min(STEPS as f64 * scene.dt());
        for t in [0.0, scene.duration()] {
            if !test.exact(t).is_finite() {
                return Err(format!(
                    "loaded, and the exact solution at t = {t} s is not finite"
                ));
            }
        }
        return match test.solve(bounded(scene.method()), scene.dt(), duration) {
            Ok(solution) => {
                for (t, y) in solution.t.iter().zip(&solution.y) {
                    let error = y[0] - test.exact(*t);
                    if !(y[0].is_finite() && error.is_finite()) {
                        return Err(format!(
                            "linear test returned y = {:e}, error {error:e} at t = {t} s as success",
                            y[0]
                        ));
                    }
                }
                Ok(())
            }
            Err(_) => Ok(()),
        };
    }
    let mut world = scene
        .build_world(Some(bounded(scene.method())))
        .map_err(|e| format!("loaded, then build_world failed: {e}"))?;
    let energy = world.energy();
    if !energy.is_finite() {
        return Err(format!("loaded with a non-finite initial energy {energy}"));
    }
    // Through the recorder of `simulate`, which checks every step's
    // energy, as the command does.
    let steps = scene.steps().min(STEPS);
    let until = grid_time(0.0, scene.duration(), scene.dt(), steps, scene.steps());
    let limits = RunLimits {
        max_samples: 10,
        budget: None,
    };
    let ticker = Ticker::new(ProgressBar::hidden(), 1);
    let Ok(recorded) = record(&mut world, until, scene.dt(), &limits, ticker, |_, _, _| {}) else {
        return Ok(()); // a typed error: the run is refused, not garbage
    };
    let samples = &recorded.samples;
    for (k, (states, energy)) in samples.states.iter().zip(&samples.energies).enumerate() {
        let finite = states.iter().all(|s| {
            s.position.iter().all(|v| v.is_finite())
                && s.velocity.iter().all(|v| v.is_finite())
                && s.angle.is_finite()
                && s.angular_velocity.is_finite()
        });
        if !finite {
            return Err(format!(
                "sample {k} holds a non-finite state, returned as success"
            ));
        }
        if !energy.is_finite() {
            return Err(format!(
                "sample {k} has energy {energy} J, returned as success"
            ));
        }
    }
    Ok(())
}

fn check_refusal(e: &scene::SceneError) -> Result<(), String> {
    let shown = e.to_string();
    if e.line().is_none() {
        return Err(format!("refused without a line: {shown}"));
    }
    if let Some(word) = JARGON.iter().find(|w| shown.contains(**w)) {
        return Err(format!("refused in jargon ({word:?}): {shown}"));
    }
    let longest_digits = shown
        .split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0);
    if longest_digits > 24 {
        return Err(format!("a number of {longest_digits} digits in: {shown}"));
    }
    Ok(())
}

/// What a fuzz run found.
#[derive(Debug, Clone, Default)]
pub struct FuzzSummary {
    /// Cases run.
    pub cases: u64,
    /// Cases whose text loaded (and was stepped).
    pub loaded: u64,
    /// Cases refused with an error.
    pub refused: u64,
    /// Cases that were random worlds.
    pub worlds: u64,
    /// Random worlds that loaded (and were stepped).
    pub worlds_loaded: u64,
    /// The failures: which property failed, and the case's text.
    pub failures: Vec<(String, String)>,
}

impl FuzzSummary {
    /// The failures counted by kind (the reason up to its first number or
    /// colon).
    pub fn kinds(&self) -> std::collections::BTreeMap<String, usize> {
        let mut kinds = std::collections::BTreeMap::new();
        for (why, _) in &self.failures {
            let kind: String = why
                .split([':', '=', '\n'])
                .next()
                .unwrap_or("")
                .chars()
                .filter(|c| !c.is_ascii_digit())
                .collect();
            *kinds.entry(kind).or_default() += 1;
        }
        kinds
    }
}

/// Runs `cases` fuzz cases of the deterministic sequence `seed`, from the
/// scene files `seeds` ([`seeds`]).
pub fn run(cases: u64, seed: u64, seeds: &[String]) -> FuzzSummary {
    run_share(cases, seed, seeds, 1, 1)
}

/// Share `index` (from 1) of `count` of [`run`]'s campaign: every case of
/// the sequence is drawn (drawing is cheap, and case k depends on the
/// draws before it), and the k-th (from 0) is checked when k mod `count`
/// is `index` − 1. The shares of `count` together check exactly the cases
/// of the whole campaign, each once; `summary.cases` counts this share's.
/// An `index` out of 1..=`count` checks nothing.
pub fn run_share(cases: u64, seed: u64, seeds: &[String], index: u64, count: u64) -> FuzzSummary {
    let mut seed_bytes = [0u8; 32];
    seed_bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let strategy = input();
    let mut summary = FuzzSummary::default();
    for k in 0..cases {
        let tree = strategy.new_tree(&mut runner).expect("a case");
        if count == 0 || k % count != index.wrapping_sub(1) {
            continue;
        }
        summary.cases += 1;
        let case = tree.current();
        let world = matches!(case, Input::World(_));
        let bytes = bytes_of(&case, seeds);
        let outcome = catch_unwind(AssertUnwindSafe(|| check(&bytes)))
            .unwrap_or_else(|_| (None, Err("panicked".to_owned())));
        if world {
            summary.worlds += 1;
            summary.worlds_loaded += u64::from(outcome.0 == Some(true));
        }
        match outcome.0 {
            Some(true) => summary.loaded += 1,
            Some(false) => summary.refused += 1,
            None => {}
        }
        if let Err(why) = outcome.1 {
            summary
                .failures
                .push((why, String::from_utf8_lossy(&bytes).into_owned()));
        }
    }
    summary
}
