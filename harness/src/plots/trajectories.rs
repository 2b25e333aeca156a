//! Trajectory figures like the seed's 5.2 and 6.2–6.5: the reference, the
//! engine (the scene's own method and step) and rapier2d-f64 (4 substeps,
//! same step) overlaid, with an error-against-time panel.

use super::{Chart, Series, method_color, save_svg};
use crate::rapier_scene::rapier_problem;
use crate::scenes;
use anyhow::Result;
use plotters::style::RGBColor;
use references::rapier_world::{RapierSample, RapierSettings, run_single_body};
use references::{AngularDrag, DragReference, Projectile, SpringOscillator, TorquePulse};
use std::path::Path;

const REFERENCE: RGBColor = RGBColor(60, 60, 60);

/// The engine's and rapier2d's runs of scene `id` over `until` (s).
fn runs(id: &str, until: f64) -> Result<(String, engine::Trace, Vec<RapierSample>)> {
    let scene = scenes::load(id)?;
    let mut world = scene.build_world(None)?;
    let trace = world.run(until, scene.dt())?;
    let (body, forces) = rapier_problem(&scene)?;
    let rapier = run_single_body(&body, &forces, &RapierSettings::new(scene.dt()), until)?;
    Ok((scene.method().id().to_string(), trace, rapier))
}

fn error_panel(title: &str, unit: &str, series: Vec<Series>) -> Chart {
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
struct ScalarFigure<'a, E, R, X>
where
    E: Fn(&engine::Sample) -> f64,
    R: Fn(&RapierSample) -> f64,
    X: Fn(f64) -> f64,
{
    file: &'a str,
    title: &'a str,
    /// Scene id and run length (s).
    case: (&'a str, f64),
    /// Quantity name and unit.
    quantity: (&'a str, &'a str),
    engine_value: E,
    rapier_value: R,
    exact: X,
    y_range: Option<(f64, f64)>,
}

impl<E, R, X> ScalarFigure<'_, E, R, X>
where
    E: Fn(&engine::Sample) -> f64,
    R: Fn(&RapierSample) -> f64,
    X: Fn(f64) -> f64,
{
    fn write(&self, dir: &Path) -> Result<String> {
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
                Series::new("exact", REFERENCE, dense).plain().dashed(),
                Series::new(
                    format!("engine {method}"),
                    method_color(&method),
                    engine.clone(),
                )
                .plain(),
                Series::new(
                    "rapier2d (4 substeps)",
                    method_color("rapier2d_4sub"),
                    rap.clone(),
                )
                .plain(),
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
                    method_color(&method),
                    err(&engine),
                )
                .plain(),
                Series::new(
                    "rapier2d (4 substeps)",
                    method_color("rapier2d_4sub"),
                    err(&rap),
                )
                .plain(),
            ],
        );
        save_svg(&dir.join(self.file), &[values, errors], 1, (900, 380))?;
        Ok(self.file.to_string())
    }
}

/// Writes every trajectory figure and returns their file names.
pub fn write_all(dir: &Path) -> Result<Vec<String>> {
    let spring = SpringOscillator::seed();
    let torque = TorquePulse::seed();
    let angular = AngularDrag::seed();
    let mut files = vec![
        ScalarFigure {
            file: "trajectory_spring.svg",
            title: "spring (seed fig. 5.2): x(t)",
            case: ("spring", 57.2),
            quantity: ("x", "m"),
            engine_value: |s: &engine::Sample| s.states[0].position.x,
            rapier_value: |s: &RapierSample| s.position[0],
            exact: |t| spring.position(t),
            y_range: Some((-20.0, 120.0)),
        }
        .write(dir)?,
    ];
    files.push(
        ScalarFigure {
            file: "trajectory_torque.svg",
            title: "torque pulse (seed fig. 6.3): angular velocity",
            case: ("torque", 8.7),
            quantity: ("omega", "rad/s"),
            engine_value: |s: &engine::Sample| s.states[0].angular_velocity,
            rapier_value: |s: &RapierSample| s.angular_velocity,
            exact: |t| torque.omega(t),
            y_range: None,
        }
        .write(dir)?,
    );
    files.push(
        ScalarFigure {
            file: "trajectory_angular_drag.svg",
            title: "torque pulse with angular drag (seed fig. 6.5): angular velocity",
            case: ("angular_drag", 8.7),
            quantity: ("omega", "rad/s"),
            engine_value: |s: &engine::Sample| s.states[0].angular_velocity,
            rapier_value: |s: &RapierSample| s.angular_velocity,
            exact: |t| angular.omega(t),
            y_range: None,
        }
        .write(dir)?,
    );
    files.push(projectile_figure(dir)?);
    Ok(files)
}

/// Seed figures 6.2 and 6.4: the path with and without drag, then the
/// position error of the drag run against the DOP853 reference.
fn projectile_figure(dir: &Path) -> Result<String> {
    let file = "trajectory_projectile_drag.svg".to_string();
    let reference = DragReference::compute()?;
    let vacuum = Projectile::seed();
    let until = reference.landing_time();
    let (method, trace, rapier) = runs("projectile_drag", 5.8)?;
    let dense: Vec<(f64, f64)> = reference.step_points().map(|(_, s)| (s[0], s[1])).collect();
    let parabola: Vec<(f64, f64)> = (0..=200)
        .map(|i| vacuum.position(vacuum.landing_time() * i as f64 / 200.0))
        .map(|p| (p[0], p[1]))
        .collect();
    let engine: Vec<(f64, f64)> = trace
        .samples
        .iter()
        .map(|s| (s.states[0].position.x, s.states[0].position.y))
        .collect();
    let rap: Vec<(f64, f64)> = rapier
        .iter()
        .map(|s| (s.position[0], s.position[1]))
        .collect();
    let path = Chart {
        title: "projectile (seed figs. 6.2, 6.4): path with and without drag".into(),
        x_label: "x (m)".into(),
        y_label: "y (m)".into(),
        series: vec![
            Series::new(
                "vacuum parabola (closed form)",
                RGBColor(150, 150, 150),
                parabola,
            )
            .plain()
            .dashed(),
            Series::new("drag reference (DOP853)", REFERENCE, dense)
                .plain()
                .dashed(),
            Series::new(format!("engine {method}"), method_color(&method), engine).plain(),
            Series::new("rapier2d (4 substeps)", method_color("rapier2d_4sub"), rap).plain(),
        ],
        y_range: Some((0.0, 95.0)),
        ..Chart::default()
    };
    let err_engine: Vec<(f64, f64)> = trace
        .samples
        .iter()
        .filter(|s| s.t <= until)
        .filter_map(|s| {
            let r = reference.state_at(s.t).ok()?;
            Some((
                s.t,
                (s.states[0].position.x - r[0]).hypot(s.states[0].position.y - r[1]),
            ))
        })
        .collect();
    let err_rapier: Vec<(f64, f64)> = rapier
        .iter()
        .filter_map(|s| {
            let r = reference.state_at(s.t).ok()?;
            Some((s.t, (s.position[0] - r[0]).hypot(s.position[1] - r[1])))
        })
        .collect();
    let errors = error_panel(
        "drag projectile: position error against DOP853",
        "m",
        vec![
            Series::new(
                format!("engine {method}"),
                method_color(&method),
                err_engine,
            )
            .plain(),
            Series::new(
                "rapier2d (4 substeps)",
                method_color("rapier2d_4sub"),
                err_rapier,
            )
            .plain(),
        ],
    );
    save_svg(&dir.join(&file), &[path, errors], 1, (900, 420))?;
    Ok(file)
}
