//! Fuzz target on the stable toolchain: arbitrary and mutated scene text
//! through `Scene::parse_str`, and, when it loads, `build_world` (or the
//! `[linear_test]` ODE) and a few steps. Each case must hold:
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
//! text. The bytes go through `Scene::parse_bytes`, as a file's would.
//!
//! `cargo test -p harness --test fuzz_scenes` runs [`DEFAULT_CASES`] cases
//! (a few seconds in the debug test profile). A longer run:
//!
//! ```text
//! FUZZ_CASES=100000 cargo test --release -p harness --test fuzz_scenes -- --nocapture
//! ```
//!
//! (`FUZZ_SEED=n` picks another deterministic sequence.) Every failing case
//! is counted by kind and the first few are printed with their text (panics
//! first, or those whose reason starts with `FUZZ_SHOW`), so one run reports
//! all the kinds of failure, not just the first.

use engine::Method;
use engine::time_grid::grid_time;
use harness::progress::Ticker;
use harness::simulate::{RunLimits, record};
use indicatif::ProgressBar;
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use scene::Scene;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

/// Cases run by a plain `cargo test`.
const DEFAULT_CASES: u64 = 300;
/// Steps taken on each scene that loads: enough to cross a first step and
/// a force switch, small enough that a case costs milliseconds.
const STEPS: u64 = 3;
/// Failing cases printed in full (the rest are counted).
const SHOWN: usize = 8;

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

/// A fuzz input: a seed file with edits, or random text.
#[derive(Debug, Clone)]
enum Input {
    Mutated(usize, Vec<Mutation>),
    Random(String),
}

fn input() -> impl Strategy<Value = Input> {
    prop_oneof![
        9 => (any::<usize>(), prop::collection::vec(mutation(), 1..5))
            .prop_map(|(seed, edits)| Input::Mutated(seed, edits)),
        1 => "[\\[\\]a-z_=\"., \n{}#0-9-]{0,160}".prop_map(Input::Random),
    ]
}

/// The project's scene files, in a fixed order.
fn seeds() -> Vec<String> {
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
    for (k, (states, energy)) in recorded.states.iter().zip(&recorded.energies).enumerate() {
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

#[test]
fn mutated_and_random_scenes_are_refused_clearly_or_run_finite() {
    let cases: u64 = std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(DEFAULT_CASES);
    let seed: u64 = std::env::var("FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0x5ce4e);
    let mut seed_bytes = [0u8; 32];
    seed_bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let seeds = seeds();
    let strategy = input();
    let mut failures: Vec<(String, String)> = Vec::new();
    let (mut loaded, mut refused) = (0u64, 0u64);
    for _ in 0..cases {
        let tree = strategy.new_tree(&mut runner).expect("a case");
        let bytes = bytes_of(&tree.current(), &seeds);
        let outcome = catch_unwind(AssertUnwindSafe(|| check(&bytes)))
            .unwrap_or_else(|_| (None, Err("panicked".to_owned())));
        match outcome.0 {
            Some(true) => loaded += 1,
            Some(false) => refused += 1,
            None => {}
        }
        if let Err(why) = outcome.1 {
            failures.push((why, String::from_utf8_lossy(&bytes).into_owned()));
        }
    }
    println!(
        "fuzz: {cases} cases ({loaded} loaded, {refused} refused), {} failures",
        failures.len()
    );
    let mut kinds: std::collections::BTreeMap<String, usize> = Default::default();
    for (why, _) in &failures {
        let kind: String = why
            .split([':', '=', '\n'])
            .next()
            .unwrap_or("")
            .chars()
            .filter(|c| !c.is_ascii_digit())
            .collect();
        *kinds.entry(kind).or_default() += 1;
    }
    for (kind, count) in &kinds {
        println!("  {count:>6}  {kind}");
    }
    // Panics first: they are the worst.
    failures.sort_by_key(|(why, _)| {
        !why.starts_with(std::env::var("FUZZ_SHOW").as_deref().unwrap_or("panicked"))
    });
    for (why, text) in failures.iter().take(SHOWN) {
        println!("--- {why}\n{text}\n");
    }
    assert!(
        failures.is_empty(),
        "{} of {cases} cases failed; first: {}",
        failures.len(),
        failures[0].0
    );
}
