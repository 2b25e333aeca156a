//! The Markdown of the studies in `reports/README.md`: each figure and
//! table with two lines on what it shows.

use crate::report::{fmt_num, markdown_table};
use crate::stability::Axis;
use crate::study::{Section, SpeedComparison, StudyResults};
use references::rapier_world::{RapierSettings, configuration_summary};
use std::fmt::Write as _;

fn figures(study: &StudyResults, section: Section) -> String {
    study
        .figures
        .iter()
        .filter(|f| f.section == section)
        .map(|f| format!("![{}]({})\n", f.file, f.file))
        .collect::<Vec<_>>()
        .join("\n")
}

fn rows_with(study: &StudyResults, check_prefix: &str) -> Vec<crate::row::Row> {
    study
        .rows
        .iter()
        .filter(|r| r.check.starts_with(check_prefix))
        .cloned()
        .collect()
}

/// The studies' sections.
pub fn markdown(study: &StudyResults) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "## speed against accuracy\n");
    md.push_str(
        "Each method on each smooth case, the step halved level by level (Dormand-Prince: its tolerance from 1e-3 to 1e-12), \
         error against the reference versus CPU time (left) and derivative evaluations (right, machine-independent). \
         Down and to the left is better; rapier2d-f64 is dashed.\n\n",
    );
    let _ = writeln!(
        md,
        "rapier2d-f64 configuration: {}\n",
        configuration_summary(&RapierSettings::new(0.01))
    );
    for speed in &study.speed {
        md.push_str(&speed_paragraph(study, speed));
    }
    md.push_str(&figures(study, Section::WorkPrecision));
    md.push('\n');
    let _ = writeln!(
        md,
        "Most accurate stable point of each method, per case (full data: `sweeps.json`):\n\n| case | method | h (s) or tol | max error | CPU (s) | evaluations |\n|---|---|---|---|---|---|"
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
    let _ = writeln!(md, "\n## convergence\n");
    md.push_str(
        "Observed order p = log2(e(h)/e(h/2)) from the asymptotic range only (stable points with max error between 1e-10 and 1e-2 of the solution's size; \
         the median of the finest three halvings), against the nominal order, within +/- 0.1 (CASES.md). \
         The dashed guides have slopes 1, 2 and 4.\n\n",
    );
    md.push_str(&markdown_table(&rows_with(study, "order")));
    md.push('\n');
    let slopes: Vec<String> = study
        .dp_slopes
        .iter()
        .map(|(c, s)| format!("{c} {s:.2}"))
        .collect();
    let _ = writeln!(
        md,
        "Dormand-Prince's error against its tolerance (slope of log error on log tol, informational): {}.\n",
        slopes.join(", ")
    );
    md.push_str(&figures(study, Section::Convergence));
    let _ = writeln!(md, "\n## stability\n");
    md.push_str(
        "The largest stable step of each method, found by bisection on h with the engine's blow-up detection (a typed `BlowUp` error: \
         non-finite state or energy past a bound) and, for weak growth, the rise of the energy from one half of a long run to the next. \
         Imaginary axis: the spring, in units of hw; real axis: Hoffman's test, in units of |h lambda|. Within 1 % of CASES.md.\n\n",
    );
    let _ = writeln!(
        md,
        "| method | axis | measured | theory |\n|---|---|---|---|"
    );
    for l in &study.limits {
        let axis = if l.axis == Axis::Imaginary {
            "imaginary (h w)"
        } else {
            "real (|h lambda|)"
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
        let _ = writeln!(md, "| {} | {axis} | {measured} | {theory} |", l.method);
    }
    md.push('\n');
    let stab: Vec<crate::row::Row> = study
        .rows
        .iter()
        .filter(|r| {
            r.check.starts_with("stability")
                || r.check.starts_with("stable")
                || r.check.starts_with("growth")
        })
        .cloned()
        .collect();
    md.push_str(&markdown_table(&stab));
    md.push_str(
        "\nThe seed's figures 4.2 and 4.3 recreated (explicit Euler on Hoffman's test just inside and outside |1 + h lambda| = 1), \
         and the spring just inside and outside the limits of velocity Verlet (hw = 2) and RK4 (hw = 2 sqrt 2):\n\n",
    );
    md.push_str(&figures(study, Section::Failures));
    let _ = writeln!(md, "\n## energy\n");
    md.push_str(
        "The seed spring at h = 0.2 s over 5720 s: the symplectic methods' energy error stays in a band, RK4's decays as |R(i h w)|^(2n). \
         Rows against CASES.md's bands:\n\n",
    );
    md.push_str(&markdown_table(&rows_with(study, "energy")));
    md.push('\n');
    md.push_str(&figures(study, Section::Energy));
    let _ = writeln!(md, "\n## trajectories\n");
    md.push_str(
        "The seed's figures 5.2 and 6.2-6.5 recreated: the reference, the engine (each scene's own method and step) and rapier2d-f64 \
         (4 substeps, same step), with the error against time below. rapier2d-f64 holds external forces over its substeps, so the spring \
         grows at 4 substeps (its step matrix has determinant 1 + 3/8 (h w)^2 > 1).\n\n",
    );
    md.push_str(&figures(study, Section::Trajectories));
    let _ = writeln!(md, "\nStudies took {:.1} s.", study.seconds);
    md
}

/// The paragraph of one speed comparison.
fn speed_paragraph(study: &StudyResults, speed: &SpeedComparison) -> String {
    let target = speed.target;
    let mut md = String::new();
    let _ = writeln!(
        md,
        "**Speed to reach {target:e} on `{}`** (max {}):",
        speed.case, speed.error_label
    );
    match (&speed.engine_best, &speed.rapier_best) {
        (Some(e), Some(r)) => {
            let _ = writeln!(
                md,
                "the engine's cheapest run is {} at h = {} s ({} s); rapier2d-f64's cheapest is {} at dt = {} s ({} s): rapier2d-f64 takes {:.1}x the engine's CPU time.\n",
                e.method,
                fmt_num(e.h),
                fmt_num(e.cpu_seconds),
                r.method,
                fmt_num(r.h),
                fmt_num(r.cpu_seconds),
                r.cpu_seconds / e.cpu_seconds
            );
        }
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
            let _ = writeln!(
                md,
                "the engine's cheapest run is {} at h = {} s ({} s CPU); **rapier2d-f64 did not reach it within the sweep**: its most accurate run, {} at dt = {} s, errs by {} ({} s CPU). Its observed order there is {:.2}, so reaching {target:e} would take about {:.1e} times more steps.\n",
                e.method,
                fmt_num(e.h),
                fmt_num(e.cpu_seconds),
                best.map_or("-".into(), |b| b.method.clone()),
                best.map_or("-".into(), |b| fmt_num(b.h)),
                best.map_or("-".into(), |b| fmt_num(b.error)),
                best.map_or("-".into(), |b| fmt_num(b.cpu_seconds)),
                order,
                factor,
            );
        }
        _ => {
            let _ = writeln!(md, "no engine run reached it within the sweep.\n");
        }
    }
    md
}
