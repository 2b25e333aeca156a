//! `reports/benchmarks.md` and `reports/benchmarks.json`: per scene and
//! engine, ms per step (minimum and median), the ratio to this engine,
//! contact counts and quality figures; the machine, the engines and their
//! settings; the targets with their measured figures; the charts.

use super::contact_precision::CaseResult;
use super::measure::{BenchSettings, SceneResult};
use super::targets::{scaling_slope, targets};
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

fn opt(v: Option<f64>) -> String {
    v.map_or("–".into(), |x| format!("{x:.3e}"))
}

/// Writes the two files into `dir`, with the charts' file names to link.
pub fn write(
    dir: &Path,
    results: &[SceneResult],
    settings: BenchSettings,
    charts: &[(String, String)],
    precision: &[CaseResult],
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
        "Machine: {}. Build: {}. Every figure below was measured in one run of the harness \
         (`cargo run --release -p harness -- bench{}`).\n",
        crate::provenance::machine(),
        crate::provenance::profile(),
        if settings.full { " --full" } else { "" }
    )?;
    writeln!(
        md,
        "Protocol (Box2D's): dt = 1/60 s, {} substeps, gravity (0, −10) m/s² (none in `smash`), \
         sleeping off, one thread. For each of {} repeats, each engine builds the scene afresh, \
         takes step 0 untimed, then {} timed steps; the engines run alternately in this process. \
         ms per step: the minimum over the repeats (and the median). The ratio is the engine's \
         minimum over this engine's. The machine is shared and noisy: compare ratios, not \
         absolute times across runs.\n",
        results.first().map_or(4, |r| r.rows[0].substeps),
        settings.repeats,
        settings.steps
    )?;
    writeln!(md, "## Targets\n")?;
    let t = targets(results);
    let trows: Vec<Vec<String>> = t
        .iter()
        .map(|t| {
            vec![
                t.target.clone(),
                t.measured.clone(),
                if t.met { "met" } else { "**not met**" }.into(),
            ]
        })
        .collect();
    md.push_str(&table(&["target", "measured", "verdict"], &trows));
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
    for r in results {
        writeln!(md, "### {}\n", r.scene.id)?;
        let jointed = r.rows.iter().any(|b| b.joints > 0);
        let rows: Vec<Vec<String>> = r
            .rows
            .iter()
            .map(|b| {
                let mut cells = vec![
                    b.engine.clone(),
                    b.bodies.to_string(),
                    format!("{:.3}", b.ms_per_step_min),
                    format!("{:.3}", b.ms_per_step_median),
                    format!("{:.2}", b.ratio_to_engine),
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
            "bodies",
            "ms/step (min)",
            "ms/step (median)",
            "ratio",
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
                "\nThis engine's step, phase by phase (a separate profiled run): {}.\n",
                phases.join(", ")
            )?;
        }
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
            let mut cells = vec![r.scene.id.to_string(), r.rows[0].bodies.to_string()];
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
    let mut headers = vec!["scene", "bodies"];
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
