//! Where methods fail, drawn: the seed's figures 4.2 and 4.3 (explicit
//! Euler on Hoffman's stiff test at h = 0.0019, 0.0021, 0.003), and the
//! spring just inside and just outside the limits of velocity Verlet
//! (hω = 1.99, 2.01) and RK4 (hω = 2.82, 2.84).

use super::{Chart, Series, method_style, save_svg};
use crate::cases::FigureOutput;
use crate::scenes;
use anyhow::{Context, Result};
use engine::{Method, integrate_fixed};
use references::{Hoffman, SpringOscillator};
use std::path::Path;

/// Writes `<dir>/failure_<id>_euler.svg`: explicit Euler on Hoffman's
/// test (scene `id`, a `[linear_test]`).
pub fn hoffman_euler(dir: &Path, id: &str) -> Result<FigureOutput> {
    let file = format!("failure_{id}_euler.svg");
    let exact = Hoffman::seed();
    let ode = scenes::load(id)?
        .linear_test()
        .with_context(|| format!("scenes/{id}.toml must hold a [linear_test]"))?;
    let t_end: f64 = 0.1;
    let mut panels = Vec::new();
    for h in [0.0019, 0.0021, 0.003] {
        let n = (t_end / h).ceil() as usize;
        let mut sys = ode;
        let sol = integrate_fixed(&mut sys, Method::ExplicitEuler, 0.0, &[ode.y0], h, n)?;
        let engine: Vec<(f64, f64)> = sol.t.iter().zip(&sol.y).map(|(&t, y)| (t, y[0])).collect();
        let reference: Vec<(f64, f64)> = (0..=400)
            .map(|i| {
                let t = t_end * i as f64 / 400.0;
                (t, exact.exact(t))
            })
            .collect();
        panels.push(Chart {
            title: format!(
                "explicit Euler, h = {h} (|1 + hλ| = {:.2})",
                (1.0 + h * exact.lambda).abs()
            ),
            x_label: "t (s)".into(),
            y_label: "y".into(),
            series: vec![
                Series::reference("exact t + 2 - e^(-1000t)", reference),
                Series::new("explicit Euler", method_style("explicit_euler"), engine),
            ],
            y_range: Some((-1.0, 5.0)),
            ..Chart::default()
        });
    }
    save_svg(&dir.join(&file), &panels, 3, (520, 420))?;
    Ok(FigureOutput::file(file))
}

/// Writes `<dir>/failure_<id>_limits.svg`: the seed spring (scene `id`)
/// just inside and outside two methods' limits.
pub fn spring_limits(dir: &Path, id: &str) -> Result<FigureOutput> {
    let file = format!("failure_{id}_limits.svg");
    let exact = SpringOscillator::seed();
    let amplitude = exact.x0 - exact.rest_length;
    let mut panels = Vec::new();
    for (method, hw) in [
        (Method::VelocityVerlet, 1.99),
        (Method::VelocityVerlet, 2.01),
        (Method::Rk4, 2.82),
        (Method::Rk4, 2.84),
    ] {
        let h = hw / exact.omega();
        let mut world = scenes::world(id, method)?;
        let steps = 150u32;
        let mut pts = vec![(0.0, 1.0)];
        for i in 1..=steps {
            world.step_to(f64::from(i) * h)?;
            pts.push((
                f64::from(i),
                (world.states()[0].position.x - exact.rest_length) / amplitude,
            ));
        }
        panels.push(Chart {
            title: format!("{} at hω = {hw}", method.id()),
            x_label: "step n".into(),
            y_label: "(x - l0) / A".into(),
            series: vec![Series::new(method.id(), method_style(method.id()), pts).line()],
            y_range: Some((-3.0, 3.0)),
            ..Chart::default()
        });
    }
    save_svg(&dir.join(&file), &panels, 2, (600, 380))?;
    Ok(FigureOutput::file(file))
}
