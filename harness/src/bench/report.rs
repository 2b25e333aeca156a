//! `reports/benchmarks.md` and `reports/benchmarks.json`: per scene and
//! engine, ms per step (minimum, median and maximum over the repeats), the
//! ratio to this engine, contact counts and quality figures; the machine,
//! the commit, each engine's build (precision, SIMD path taken on this
//! CPU, threads, compiler flags) and settings; the targets with their
//! measured figures, and for a missed speed target against Box2D and a
//! missed quality target what would close it; per scene, this engine and Box2D stage by stage
//! ([`super::stages`]); the peak memory of the large scenes; the charts.

use super::contact_precision::CaseResult;
use super::measure::{BenchSettings, SceneResult, Steps};
use super::memory::PeakMemory;
use super::stages::{BOUNDARIES, OUTSIDE, PROFILED_REPEATS, STAGES, StageComparison};
use super::targets::{Target, box2d_targets, scaling_slope, targets};
use anyhow::Result;
use std::fmt::Write as _;
use std::path::Path;

/// A Markdown table of `rows` under `headers`, pipes in cells escaped.
fn table(headers: &[&str], rows: &[Vec<String>]) -> String {
    let line = |cells: &mut dyn Iterator<Item = String>| {
        let cells: Vec<String> = cells.map(|c| c.replace('|', "\\|")).collect();
        format!("| {} |\n", cells.join(" | "))
    };
    let mut out = line(&mut headers.iter().map(|h| h.to_string()));
    out += &line(&mut headers.iter().map(|_| "---".to_string()));
    for r in rows {
        out += &line(&mut r.iter().cloned());
    }
    out
}

/// Targets as a table: target, measured, verdict, and, when a target
/// there was missed with a profile to explain it, what would close it.
fn verdict_table(targets: &[Target]) -> String {
    let closing = targets.iter().any(|t| t.to_close.is_some());
    let rows: Vec<Vec<String>> = targets
        .iter()
        .map(|t| {
            let mut cells = vec![
                t.target.clone(),
                t.measured.clone(),
                if t.met { "met" } else { "**not met**" }.into(),
            ];
            if closing {
                cells.push(t.to_close.clone().unwrap_or_default());
            }
            cells
        })
        .collect();
    let mut headers = vec!["target", "measured", "verdict"];
    if closing {
        headers.push("what would close it");
    }
    table(&headers, &rows)
}

/// How the target tables explain a missed speed target.
const CLOSING: &str = " A speed target not met says what would close it: the ms per step this \
     engine must lose (its minimum less the target's multiple of Box2D's minimum), and the \
     stages in which this engine's profiled run is slower than Box2D's, largest first, with \
     by how much (each scene's stage table, under Results).";

/// A signed difference (ms) with a real minus sign.
fn signed(x: f64) -> String {
    let text = format!("{x:+.3}");
    text.replacen('-', "−", 1)
}

/// The stage table of one comparison: stage, this engine, Box2D, the
/// difference, then the total (the profiled runs' wall time per step).
fn stage_table(c: &StageComparison) -> String {
    let mut rows: Vec<Vec<String>> = c
        .stages
        .iter()
        .map(|s| {
            vec![
                s.stage.to_string(),
                format!("{:.3}", s.ours_ms),
                format!("{:.3}", s.box2d_ms),
                signed(s.ours_ms - s.box2d_ms),
            ]
        })
        .collect();
    let (ours, box2d): (f64, f64) = c
        .stages
        .iter()
        .fold((0.0, 0.0), |(a, b), s| (a + s.ours_ms, b + s.box2d_ms));
    rows.push(vec![
        "**step** (the profiled run's wall time)".into(),
        format!("{ours:.3}"),
        format!("{box2d:.3}"),
        signed(ours - box2d),
    ]);
    table(
        &["stage", "this engine (ms)", "Box2D (ms)", "difference (ms)"],
        &rows,
    )
}

/// The correspondence of the stages, in words, from [`STAGES`].
fn correspondence() -> String {
    STAGES
        .iter()
        .map(|(stage, ours, box2d)| {
            format!(
                "{stage}: ours {} ~ Box2D {}",
                ours.join(" + "),
                box2d.join(" + ")
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

fn opt(v: Option<f64>) -> String {
    v.map_or("–".into(), |x| format!("{x:.3e}"))
}

/// What the report shows besides the scenes' rows.
#[derive(Debug, Clone, Default)]
pub struct Extras {
    /// Engines left out, with the reason.
    pub notes: Vec<String>,
    /// Peak memory of the large scenes (empty when not measured).
    pub memory: Vec<PeakMemory>,
}

/// Writes the two files into `dir`, with the charts' file names to link.
pub fn write(
    dir: &Path,
    results: &[SceneResult],
    settings: BenchSettings,
    charts: &[(String, String)],
    precision: &[CaseResult],
    extras: &Extras,
) -> Result<()> {
    std::fs::create_dir_all(dir)?;
    let rows: Vec<_> = results.iter().flat_map(|r| r.rows.clone()).collect();
    std::fs::write(
        dir.join("benchmarks.json"),
        serde_json::to_string_pretty(&rows)? + "\n",
    )?;
    let mut md = String::new();
    writeln!(
        md,
        "# Benchmarks: this engine, rapier2d-f64 and Box2D v3, side by side\n"
    )?;
    writeln!(
        md,
        "Machine: {}. Commit: {}. Build profile: {}. Every figure below was measured in one run \
         of the harness (`{}`).\n",
        crate::provenance::machine(),
        crate::provenance::commit(),
        crate::provenance::profile(),
        command(settings)
    )?;
    let steps = match settings.steps {
        Steps::Fixed(n) => format!("{n} timed steps"),
        Steps::Box2d => "Box2D's own step count for the scene (its `benchmark/main.c`; 500 for \
                         the scenes it does not have), all but the first timed, as Box2D times \
                         them"
            .to_string(),
    };
    writeln!(
        md,
        "Protocol (Box2D's): dt = 1/60 s, {} substeps, gravity (0, −10) m/s² (none in `smash`), \
         sleeping off; every engine on one thread, then (when the run asks for more) this \
         engine, rapier2d (its `parallel` feature, in a rayon pool of that size) and Box2D (its \
         built-in scheduler, boxdd's `worker_count`) again on that many threads. For each of {} repeats, each engine builds the \
         scene afresh, takes step 0 untimed, then the timed steps: {steps}; the engines run \
         alternately (the Box2D builds other than the harness's as child processes, in their \
         turn), each repeat starting one engine further along the list. ms per step: the minimum over the repeats, with the median and the maximum. The \
         ratio is the engine's minimum over this engine's at the same thread count. CPU/wall: the \
         process's CPU time (every thread, `getrusage`) over the wall time of the timed steps, \
         in the fastest repeat (1: one busy thread; 2: two). The machine may be shared: compare \
         ratios, not absolute times across runs.\n",
        results.first().map_or(4, |r| r.rows[0].substeps),
        settings.repeats,
    )?;
    writeln!(md, "## The engines' builds\n")?;
    if let Some(r) = results.first() {
        let rows: Vec<Vec<String>> = r
            .rows
            .iter()
            .map(|b| {
                vec![
                    b.engine.clone(),
                    b.precision.clone(),
                    b.simd.clone(),
                    b.threads.to_string(),
                    b.build.clone(),
                ]
            })
            .collect();
        md.push_str(&table(
            &[
                "engine",
                "precision",
                "SIMD path on this CPU",
                "threads",
                "build",
            ],
            &rows,
        ));
        md.push('\n');
    }
    for note in &extras.notes {
        writeln!(md, "- {note}")?;
    }
    if !settings.box2d_sse2 {
        writeln!(
            md,
            "Box2D's SSE2 build is measured by `harness bench --box2d-sse2` (a second build of \
             Box2D, compiled before the timing); this run did not ask for it.\n"
        )?;
    }
    if !settings.box2d_double {
        writeln!(
            md,
            "Box2D's double-precision build is measured by `harness bench --box2d-double`; this \
             run did not ask for it.\n"
        )?;
    }
    writeln!(md, "## Targets\n")?;
    let t = targets(results);
    if t.iter().any(|t| !t.met) {
        writeln!(
            md,
            "{}\n",
            super::quality_probe::explained(settings.quality_probes).trim()
        )?;
    }
    md.push_str(&verdict_table(&t));
    let lead = box2d_targets(results);
    if !lead.is_empty() {
        let met = lead.iter().filter(|t| t.met).count();
        writeln!(
            md,
            "\n### The single-thread lead over Box2D's release build\n\n\
             Targets: this engine at most 0.9× the ms per step of Box2D built as it ships (f32, \
             AVX2, -O3, NDEBUG) on every scene, one thread each, the same substeps; and every \
             quality figure at least as good as Box2D's (no worse by more than 1 % or 1e-6 in \
             the figure's unit). Met: {met} of {}.{}{}\n",
            lead.len(),
            CLOSING,
            super::quality_probe::explained(settings.quality_probes)
        )?;
        md.push_str(&verdict_table(&lead));
    }
    let threaded = super::targets::thread_targets(results);
    if !threaded.is_empty() {
        writeln!(
            md,
            "\n### Threads\n\n\
             Targets (issue 21): this engine on 2 threads at least 1.7× faster than on 1 on \
             large_pyramid, and ahead of Box2D's 2-worker time on every scene. The results do \
             not depend on the thread count (the same bits: engine test `falling_hinges`).{} \
             The speed-up target, if missed, says the ms per step this engine must lose on 2 \
             threads (its 2-thread minimum less its 1-thread minimum over 1.7) and the stages \
             of its own profiled runs that fall short of 1.7× (their 2-thread time less their \
             1-thread time over 1.7), largest first.\n",
            CLOSING
        )?;
        md.push_str(&verdict_table(&threaded));
    }
    let slopes: Vec<String> = results
        .first()
        .map(|r| {
            r.rows
                .iter()
                .enumerate()
                .filter_map(|(i, row)| {
                    scaling_slope(results, i).map(|s| format!("{} {s:.3}", row.engine))
                })
                .collect()
        })
        .unwrap_or_default();
    writeln!(
        md,
        "\nSlope of log(ms per step) against log(bodies) over the pyramid series (1 is linear): \
         {}.\n",
        slopes.join(", ")
    )?;
    for (file, caption) in charts {
        writeln!(md, "![{caption}]({file})\n")?;
    }
    writeln!(md, "## Results\n")?;
    writeln!(
        md,
        "Quality figures after the last timed step, the same for every engine: the watched top \
         body's sink below its starting height and its sideways drift, the fastest dynamic body, \
         and the deepest overlap of any pair that can collide, computed from the poses (exact \
         geometry, the same code for every engine; bodies of one collision group or held by a \
         joint never collide). In the scenes with joints, also from the poses through the \
         scene's joints: the largest separation of the two anchors a joint holds together (a \
         revolute joint's point) and the largest excess of a joint's angle over its limits.\n"
    )?;
    if results.iter().any(|r| !r.stages.is_empty()) {
        writeln!(
            md,
            "Stage by stage: after its timed repeats, this engine and the linked Box2D each run the \
         scene again, profiled (built afresh, step 0 untimed, then the same steps; {} runs each, \
         alternating, the fastest kept): this \
         engine's phase timers and Box2D's own (`b2Profile`, which holds the last step and is read \
         after each one) summed over the steps and divided by them, mapped onto common stages: \
         {}. Box2D's `step`, `solve` and `constraints` hold the others and are not counted \
         again. \"{OUTSIDE}\" is the profiled run's wall time per step less its stages \
         (the call into the engine, the timers' own cost, work no timer covers), so each column \
         adds up to that wall time. Where the boundaries differ: {}\n",
            settings.repeats.clamp(1, PROFILED_REPEATS),
            correspondence(),
            BOUNDARIES.join(" ")
        )?;
    }
    for r in results {
        writeln!(md, "### {}\n", r.scene.id)?;
        let jointed = r.rows.iter().any(|b| b.joints > 0);
        let rows: Vec<Vec<String>> = r
            .rows
            .iter()
            .map(|b| {
                let mut cells = vec![
                    b.engine.clone(),
                    b.threads.to_string(),
                    b.bodies.to_string(),
                    format!("{:.3}", b.ms_per_step_min),
                    format!("{:.3}", b.ms_per_step_median),
                    format!("{:.3}", b.ms_per_step_max),
                    format!("{:.2}", b.ratio_to_engine),
                    if b.cpu_over_wall > 0.0 {
                        format!("{:.2}", b.cpu_over_wall)
                    } else {
                        "–".into()
                    },
                    b.touching_pairs.to_string(),
                    b.points.to_string(),
                    opt(b.top_sink),
                    opt(b.top_drift),
                    format!("{:.3e}", b.fastest_at_end),
                    format!("{:.3e}", b.deepest_overlap),
                ];
                if jointed {
                    cells.extend([
                        b.joints.to_string(),
                        opt(b.joint_separation_max),
                        opt(b.joint_limit_excess_max),
                    ]);
                }
                cells
            })
            .collect();
        let mut headers = vec![
            "engine",
            "threads",
            "bodies",
            "ms/step (min)",
            "ms/step (median)",
            "ms/step (max)",
            "ratio",
            "CPU/wall",
            "touching pairs",
            "points",
            "top sink (m)",
            "top drift (m)",
            "fastest (m/s)",
            "deepest overlap (m)",
        ];
        if jointed {
            headers.extend([
                "joints",
                "largest joint separation (m)",
                "largest limit excess (rad)",
            ]);
        }
        md.push_str(&table(&headers, &rows));
        if !r.profile.is_empty() {
            let total: f64 = r.profile.iter().map(|p| p.1).sum();
            let phases: Vec<String> = r
                .profile
                .iter()
                .map(|(name, ms)| format!("{name} {ms:.3} ms ({:.0} %)", 100.0 * ms / total))
                .collect();
            writeln!(
                md,
                "\nThis engine's step, phase by phase (its fastest profiled run): {}.\n",
                phases.join(", ")
            )?;
        }
        for c in &r.stages {
            writeln!(
                md,
                "This engine and {} stage by stage, {} (ms per step, each engine's fastest profiled run):\n",
                r.rows
                    .iter()
                    .find(|b| {
                        b.threads == c.threads
                            && b.engine.starts_with("Box2D")
                            && b.stages.is_some()
                    })
                    .map_or("Box2D", |b| b.engine.as_str()),
                if c.threads == 1 {
                    "one thread each".to_string()
                } else {
                    format!("{} threads each (Box2D: {} workers)", c.threads, c.threads)
                }
            )?;
            md.push_str(&stage_table(c));
            md.push('\n');
        }
    }
    if !extras.memory.is_empty() {
        writeln!(md, "## Peak memory of the large scenes\n")?;
        writeln!(
            md,
            "Peak resident set size of `harness simulate` run alone on the scene, read from the \
             kernel's resource usage of that child process (`wait4`, `ru_maxrss`; Linux counts \
             the larger of the child's peak and the harness's own, so a reading not above the \
             harness's own peak is printed as a bound); MB = 10⁶ bytes. With no output asked the \
             run keeps nothing per step; `--trace` streams its rows to the file as the run goes; \
             so the peak is the world's and does not grow with the steps: `container_1000`'s pile, \
             at rest from about step 600, at 600 and at 6000 steps, and `container_10k`'s pile at \
             1000 and at 3000 steps. `container_10k` at 100 steps is a rain of falling bodies, \
             so its peak differs from the pile's by the contact state the soft step holds, not by \
             the steps (its traces at 100 steps, every step, and at 1000, every 10th, hold the \
             same rows).\n"
        )?;
        let rows: Vec<Vec<String>> = extras
            .memory
            .iter()
            .map(|m| {
                vec![
                    format!("`{}`", m.command),
                    m.bodies.to_string(),
                    m.steps.to_string(),
                    if m.exact {
                        format!("{:.0}", m.peak_mb)
                    } else {
                        format!("at most {:.0}", m.peak_mb)
                    },
                ]
            })
            .collect();
        md.push_str(&table(
            &["command", "bodies", "steps", "peak memory (MB)"],
            &rows,
        ));
        md.push('\n');
    }
    writeln!(md, "## What a contact model's accuracy costs\n")?;
    writeln!(
        md,
        "The validation contact cases (docs/cases.md) in every model and engine at the scene's \
         step (0.01 s): the error against the closed form and the wall time of the whole run \
         (minimum of {} runs). An error of exactly 0 is drawn in the band labelled 0 under the \
         log axis.\n",
        super::contact_precision::REPEATS,
    )?;
    for case in precision {
        writeln!(md, "### {} — {}\n", case.case, case.error_label)?;
        let rows: Vec<Vec<String>> = case
            .points
            .iter()
            .map(|p| {
                vec![
                    p.model.to_string(),
                    p.substeps.to_string(),
                    format!("{:.3e}", p.seconds),
                    format!("{:.3e}", p.error),
                ]
            })
            .collect();
        md.push_str(&table(
            &["model", "substeps", "wall time (s)", "error"],
            &rows,
        ));
        md.push('\n');
    }
    writeln!(md, "## The engines and their settings\n")?;
    if let Some(r) = results.first() {
        for (name, config) in &r.configurations {
            writeln!(md, "- **{name}**: {config}")?;
        }
    }
    writeln!(
        md,
        "\nWhat differs between them:\n\n{}\n",
        references::many_body::ENGINE_DIFFERENCES
            .iter()
            .map(|d| format!("- {d}"))
            .collect::<Vec<_>>()
            .join("\n")
    )?;
    std::fs::write(dir.join("benchmarks.md"), md)?;
    Ok(())
}

/// The command that writes a report of `settings`.
fn command(settings: BenchSettings) -> String {
    let mut c = match settings.steps {
        Steps::Box2d => "cargo run --release -p harness -- bench".to_string(),
        Steps::Fixed(_) => "cargo run --release -p harness".to_string(),
    };
    if settings.full {
        c += " --full";
    }
    if settings.box2d_sse2 {
        c += " --box2d-sse2";
    }
    if settings.box2d_double {
        c += " --box2d-double";
    }
    c
}

/// Marker lines between which the harness writes the README's benchmark
/// table.
pub const README_MARKERS: (&str, &str) = ("<!-- bench:start -->", "<!-- bench:end -->");

/// Rewrites the benchmark table between [`README_MARKERS`] in `readme`
/// (when the file has them): per scene, bodies and ms per step of the three
/// engines with their ratios to this engine's. Returns whether it did.
pub fn update_readme(readme: &Path, results: &[SceneResult]) -> Result<bool> {
    let Ok(text) = std::fs::read_to_string(readme) else {
        return Ok(false);
    };
    let (start, end) = README_MARKERS;
    let (Some(a), Some(b)) = (text.find(start), text.find(end)) else {
        return Ok(false);
    };
    let rows: Vec<Vec<String>> = results
        .iter()
        .map(|r| {
            let mut cells = vec![
                r.scene.id.to_string(),
                r.rows[0].bodies.to_string(),
                r.rows[0].steps.to_string(),
            ];
            for (i, row) in r.rows.iter().enumerate() {
                cells.push(if i == 0 {
                    format!("{:.3}", row.ms_per_step_min)
                } else {
                    format!("{:.3} ({:.2}×)", row.ms_per_step_min, row.ratio_to_engine)
                });
            }
            cells
        })
        .collect();
    let mut headers = vec!["scene", "bodies", "timed steps"];
    let names: Vec<String> = results
        .first()
        .map(|r| {
            r.rows
                .iter()
                .map(|row| format!("{} ms/step", super::short(&row.engine)))
                .collect()
        })
        .unwrap_or_default();
    headers.extend(names.iter().map(String::as_str));
    let table = table(&headers, &rows);
    let new = format!("{}{start}\n{table}{}", &text[..a], &text[b..]);
    if new != text {
        crate::simulate::write_atomically(readme, new.as_bytes())?;
    }
    Ok(true)
}
