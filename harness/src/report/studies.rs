//! The pages of the studies, `studies/<name>.md` in the report folder:
//! speed against accuracy, convergence, stability, energy, trajectories.
//! Each page says in a few lines what its figures and tables show; its rows
//! are keyed to where their conditions come from.

use super::format::{cell, fmt_num, wrap};
use super::table;
use crate::row::Row;
use crate::stability::Axis;
use crate::study::{Section, SpeedComparison, StudyResults};
use references::rapier_world::{RapierSettings, configuration_summary};
use std::fmt::Write as _;

/// One page of the studies.
#[derive(Debug, Clone)]
pub struct StudyPage<'a> {
    /// File name inside `studies/`.
    pub file: &'static str,
    /// Title.
    pub title: &'static str,
    /// One line on what it shows, for the report's summary.
    pub summary: &'static str,
    /// Its rows.
    pub rows: Vec<&'a Row>,
    /// The page.
    pub markdown: String,
}

/// The head of a page: its title, a link back, and its introduction
/// wrapped.
fn head(title: &str, intro: &str) -> String {
    format!(
        "# {title}\n\n[← validation report](../README.md)\n\n{}\n",
        wrap(intro, "", "")
    )
}

/// The figures of `section`, linked from a page of `studies/`.
fn figures(study: &StudyResults, section: Section) -> String {
    study
        .figures
        .iter()
        .filter(|f| f.section == section)
        .map(|f| format!("![{} ({})](../{})\n\n", f.file, f.case, f.file))
        .collect()
}

/// Every page of the studies.
pub fn pages(study: &StudyResults) -> Vec<StudyPage<'_>> {
    vec![
        speed(study),
        convergence(study),
        stability(study),
        energy(study),
        trajectories(study),
    ]
}

fn speed(study: &StudyResults) -> StudyPage<'_> {
    let mut md = head(
        "Speed against accuracy",
        "Each method on each swept case, the step halved level by level (Dormand-Prince: its \
         tolerance from 1e-3 to 1e-12), error against the case's reference versus the wall time of a run (left, the minimum \
         over repeated runs) and, for this engine's methods, derivative evaluations (right, \
         machine-independent; rapier2d-f64 evaluates its forces once a step and holds them over \
         its substeps, so it appears only on the left). Down and to the left is better; \
         rapier2d-f64 is dashed.",
    );
    md.push_str(&wrap(
        &format!(
            "rapier2d-f64 configuration: {}",
            configuration_summary(&RapierSettings::new(0.01))
        ),
        "",
        "",
    ));
    md.push('\n');
    for speed in &study.speed {
        md.push_str(&speed_paragraph(study, speed));
        md.push('\n');
    }
    md.push_str("## Figures\n\n");
    md.push_str(&figures(study, Section::WorkPrecision));
    md.push_str("## Most accurate run of each method\n\n");
    let references: Vec<String> = study
        .sweeps
        .iter()
        .map(|s| format!("`{}` against {}", s.case, s.reference))
        .collect();
    md.push_str(&wrap(
        &format!(
            "The most accurate stable point of each method, per case (every point: \
             `sweeps.json`). The references: {}.",
            references.join("; ")
        ),
        "",
        "",
    ));
    md.push_str(
        "\n| case | method | h (s) or tol | max error | time (s) | evaluations |\n\
         |---|---|---|---|---|---|\n",
    );
    for sweep in &study.sweeps {
        let mut labels: Vec<&str> = sweep.points.iter().map(|p| p.method.as_str()).collect();
        labels.dedup();
        for label in labels {
            let best = sweep
                .points
                .iter()
                .filter(|p| p.method == label && p.stable)
                .min_by(|a, b| a.max_error.total_cmp(&b.max_error));
            if let Some(p) = best {
                let step = p.tolerance.map_or(fmt_num(p.h), |t| format!("tol {t:e}"));
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {} | {} | {} |",
                    sweep.case,
                    label,
                    step,
                    fmt_num(p.max_error),
                    fmt_num(p.cpu_seconds),
                    p.evaluations
                );
            }
        }
    }
    StudyPage {
        file: "speed.md",
        title: "Speed against accuracy",
        summary: "work-precision diagrams of every method and of rapier2d-f64",
        rows: Vec::new(),
        markdown: md,
    }
}

/// The paragraph of one speed comparison.
fn speed_paragraph(study: &StudyResults, speed: &SpeedComparison) -> String {
    let target = speed.target;
    let head = format!(
        "**Speed to reach {target:e} {} on `{}`** (max {}):",
        speed.unit, speed.case, speed.error_label
    );
    let body = match (&speed.engine_best, &speed.rapier_best) {
        (Some(e), Some(r)) => format!(
            "the engine's cheapest run is {} at h = {} s ({} s); rapier2d-f64's cheapest is {} \
             at dt = {} s ({} s): rapier2d-f64 takes {:.1}x the engine's time.",
            e.method,
            fmt_num(e.h),
            fmt_num(e.cpu_seconds),
            r.method,
            fmt_num(r.h),
            fmt_num(r.cpu_seconds),
            r.cpu_seconds / e.cpu_seconds
        ),
        (Some(e), None) => {
            let best = speed.rapier_most_accurate.as_ref();
            // The observed order of rapier's most accurate setting, from the
            // same sweep, says how far its step would have to shrink.
            let order = best
                .and_then(|b| {
                    let sweep = study.sweeps.iter().find(|s| s.case == speed.case)?;
                    Some(crate::convergence::observed_order(sweep, &b.method).order)
                })
                .unwrap_or(f64::NAN);
            let factor = best.map_or(f64::NAN, |b| (b.error / target).powf(1.0 / order));
            format!(
                "the engine's cheapest run is {} at h = {} s ({} s); **rapier2d-f64 did not \
                 reach it within the sweep**: its most accurate run, {} at dt = {} s, errs by {} {} \
                 ({} s). Its observed order there is {:.2}, so reaching {target:e} {} would \
                 take about {:.1e} times more steps.",
                e.method,
                fmt_num(e.h),
                fmt_num(e.cpu_seconds),
                best.map_or("-".into(), |b| b.method.clone()),
                best.map_or("-".into(), |b| fmt_num(b.h)),
                best.map_or("-".into(), |b| fmt_num(b.error)),
                speed.unit,
                best.map_or("-".into(), |b| fmt_num(b.cpu_seconds)),
                order,
                speed.unit,
                factor,
            )
        }
        _ => "no engine run reached it within the sweep.".to_string(),
    };
    wrap(&format!("{head} {body}"), "", "")
}

fn convergence(study: &StudyResults) -> StudyPage<'_> {
    let rows = study.rows_of(Section::Convergence);
    let mut md = head(
        "Convergence",
        "Observed order p = log2(e(h)/e(h/2)) from the asymptotic range only (stable points with \
         max error between 1e-10 and 1e-2 of the solution's size; the median of the finest three \
         halvings), against the nominal order, within +/- 0.1 (docs/cases.md). The step shown is the \
         finest used. The dashed guides of the figures have slopes 1, 2 and 4.",
    );
    md.push_str("## Observed orders\n\n");
    md.push_str(&table::markdown(&rows, true));
    let slopes: Vec<String> = study
        .dp_slopes
        .iter()
        .map(|(c, s)| format!("{c} {s:.2}"))
        .collect();
    md.push('\n');
    md.push_str(&wrap(
        &format!(
            "Dormand-Prince's error against its tolerance (slope of log error on log tol, \
             informational): {}.",
            slopes.join(", ")
        ),
        "",
        "",
    ));
    md.push_str("\n## Figures\n\n");
    md.push_str(&figures(study, Section::Convergence));
    StudyPage {
        file: "convergence.md",
        title: "Convergence",
        summary: "observed order of every fixed-step method on every swept case",
        rows,
        markdown: md,
    }
}

fn stability(study: &StudyResults) -> StudyPage<'_> {
    let rows = study.rows_of(Section::Stability);
    let mut md = head(
        "Stability",
        "The largest stable step of each method, found by bisection on h with the engine's \
         blow-up detection (a typed `BlowUp` error: non-finite state or energy past a bound) and, \
         for weak growth, the rise of the energy from one half of a long run to the next. \
         Imaginary axis: the spring, in units of h w; real axis: Hoffman's test, in units of \
         -h lambda. Within 1 % of docs/cases.md.",
    );
    md.push_str("## Limits\n\n| method | axis | measured | theory |\n|---|---|---|---|\n");
    for l in &study.limits {
        let axis = match l.axis {
            Axis::Imaginary => "imaginary (h w)",
            Axis::Real => "real (-h lambda)",
        };
        let theory = match l.theory {
            None => "none (unstable at every h)".to_string(),
            Some(t) if t.is_infinite() => "any".to_string(),
            Some(t) => fmt_num(t),
        };
        let measured = if l.measured.is_infinite() {
            "stable at 1000".to_string()
        } else if l.measured.is_nan() {
            "grows at every h".to_string()
        } else {
            fmt_num(l.measured)
        };
        let _ = writeln!(
            md,
            "| {} | {axis} | {measured} | {} |",
            l.method,
            cell(&theory)
        );
    }
    md.push_str("\n## Rows\n\n");
    md.push_str(&table::markdown(&rows, true));
    md.push_str("\n## Where methods fail\n\n");
    md.push_str(&wrap(
        "The seed's figures 4.2 and 4.3 recreated (explicit Euler on Hoffman's test just inside \
         and outside |1 + h lambda| = 1), and the spring just inside and outside the limits of \
         velocity Verlet (h w = 2) and RK4 (h w = 2 sqrt 2):",
        "",
        "",
    ));
    md.push('\n');
    md.push_str(&figures(study, Section::Failures));
    StudyPage {
        file: "stability.md",
        title: "Stability",
        summary: "largest stable step of every method on both axes, and the failures drawn",
        rows,
        markdown: md,
    }
}

fn energy(study: &StudyResults) -> StudyPage<'_> {
    let rows = study.rows_of(Section::Energy);
    let mut md = head(
        "Energy",
        "The seed spring at h = 0.2 s over 5720 s: the symplectic methods' energy error stays in a \
         band, RK4's decays as |R(i h w)|^(2n). Rows against docs/cases.md's bands.",
    );
    md.push_str("## Rows\n\n");
    md.push_str(&table::markdown(&rows, true));
    md.push_str("\n## Figures\n\n");
    md.push_str(&figures(study, Section::Energy));
    StudyPage {
        file: "energy.md",
        title: "Energy",
        summary: "energy of the spring over 5720 s against docs/cases.md's bands",
        rows,
        markdown: md,
    }
}

fn trajectories(study: &StudyResults) -> StudyPage<'_> {
    let mut md = head(
        "Trajectories",
        "The seed's figures 5.2 and 6.2-6.5 recreated: the reference, the engine (each scene's own \
         method and step) and rapier2d-f64 (4 substeps, same step), with the error against time \
         below. rapier2d-f64 holds external forces over its substeps, so the spring grows at 4 \
         substeps (its step matrix has determinant 1 + 3/8 (h w)^2 > 1).",
    );
    md.push_str("## Figures\n\n");
    md.push_str(&figures(study, Section::Trajectories));
    StudyPage {
        file: "trajectories.md",
        title: "Trajectories",
        summary: "the seed's trajectory figures with the engine and rapier2d-f64",
        rows: Vec::new(),
        markdown: md,
    }
}
