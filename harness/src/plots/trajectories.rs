//! Trajectory figures like the seed's 5.2 and 6.2–6.5: the reference, the
//! engine (the scene's own method and step) and rapier2d-f64 (4 substeps,
//! same step) overlaid, with an error-against-time panel. The cases declare
//! their figures (`Case::figures`) with [`ScalarFigure`] or their own
//! drawing on [`runs`] and [`error_panel`].

use super::{Chart, Series, method_style, save_svg};
use crate::cases::FigureOutput;
use crate::rapier_scene::rapier_problem;
use crate::scenes;
use anyhow::Result;
use references::rapier_world::{RapierSample, RapierSettings, run_single_body};
use std::path::Path;

/// The engine's and rapier2d's runs of scene `id` over `until` (s): the
/// scene's method id, the engine's trace and rapier2d's samples.
pub fn runs(id: &str, until: f64) -> Result<(String, engine::Trace, Vec<RapierSample>)> {
    let scene = scenes::load(id)?;
    let mut world = scene.build_world(None)?;
    let trace = world.run(until, scene.dt())?;
    let (body, forces) = rapier_problem(&scene)?;
    let rapier = run_single_body(&body, &forces, &RapierSettings::new(scene.dt()), until)?;
    Ok((scene.method().id().to_string(), trace, rapier))
}

/// A panel of |error| against time, log scale, in `unit`.
pub fn error_panel(title: &str, unit: &str, series: Vec<Series>) -> Chart {
    Chart {
        title: title.into(),
        x_label: "t (s)".into(),
        y_label: format!("|error| ({unit})"),
        log_y: true,
        series,
        ..Chart::default()
    }
}

/// A scalar quantity of one case, drawn as a value panel over an error panel.
pub struct ScalarFigure<'a, E, R, X>
where
    E: Fn(&engine::Sample) -> f64,
    R: Fn(&RapierSample) -> f64,
    X: Fn(f64) -> f64,
{
    /// File name in the report folder.
    pub file: &'a str,
    /// Title of the value panel.
    pub title: &'a str,
    /// Scene id and run length (s).
    pub case: (&'a str, f64),
    /// Quantity name and unit.
    pub quantity: (&'a str, &'a str),
    /// The quantity in an engine sample.
    pub engine_value: E,
    /// The quantity in a rapier2d sample.
    pub rapier_value: R,
    /// The closed form against time (s).
    pub exact: X,
    /// Fixed y range of the value panel, if any.
    pub y_range: Option<(f64, f64)>,
}

impl<E, R, X> ScalarFigure<'_, E, R, X>
where
    E: Fn(&engine::Sample) -> f64,
    R: Fn(&RapierSample) -> f64,
    X: Fn(f64) -> f64,
{
    /// Runs the engine and rapier2d and writes the figure into `dir`.
    pub fn write(&self, dir: &Path) -> Result<FigureOutput> {
        let (id, until) = self.case;
        let (quantity, unit) = self.quantity;
        let exact = &self.exact;
        let (method, trace, rapier) = runs(id, until)?;
        let dense: Vec<(f64, f64)> = (0..=1000)
            .map(|i| until * i as f64 / 1000.0)
            .map(|t| (t, exact(t)))
            .collect();
        let engine: Vec<(f64, f64)> = trace
            .samples
            .iter()
            .map(|s| (s.t, (self.engine_value)(s)))
            .collect();
        let rap: Vec<(f64, f64)> = rapier
            .iter()
            .map(|s| (s.t, (self.rapier_value)(s)))
            .collect();
        let err = |pts: &[(f64, f64)]| {
            pts.iter()
                .map(|&(t, v)| (t, (v - exact(t)).abs()))
                .collect::<Vec<_>>()
        };
        let values = Chart {
            title: self.title.into(),
            x_label: "t (s)".into(),
            y_label: format!("{quantity} ({unit})"),
            series: vec![
                Series::reference("exact", dense),
                Series::new(
                    format!("engine {method}"),
                    method_style(&method),
                    engine.clone(),
                )
                .line(),
                Series::new(
                    "rapier2d (4 substeps)",
                    method_style("rapier2d_4sub"),
                    rap.clone(),
                )
                .line(),
            ],
            y_range: self.y_range,
            ..Chart::default()
        };
        let errors = error_panel(
            &format!("{quantity}: error against the closed form"),
            unit,
            vec![
                Series::new(
                    format!("engine {method}"),
                    method_style(&method),
                    err(&engine),
                )
                .line(),
                Series::new(
                    "rapier2d (4 substeps)",
                    method_style("rapier2d_4sub"),
                    err(&rap),
                )
                .line(),
            ],
        );
        save_svg(&dir.join(self.file), &[values, errors], 1, (900, 380))?;
        Ok(FigureOutput::file(self.file))
    }
}
