//! What the two pendulum cases share (`pendulum`, `physical_pendulum`;
//! `docs/cases.md#pendulum`): bodies held to the world by one joint each,
//! a rigid distance joint at the centre (a rod) or a revolute joint (a
//! pin), released at rest, each measured against the exact period
//! T = 4 √(L_eq/g) K(sin(θ0/2)) of the pendulum it is
//! (`references::pendulum`: a point mass on a rod, or a rigid body about
//! its pivot, L_eq = I_pivot/(m d)), under the soft step at its defaults,
//! with rapier2d and Box2D on the same file.
//!
//! # What is measured, the same way in every engine
//!
//! From the centre's angle θ about the pivot after every step: the zero
//! crossings of its horizontal offset, each located inside its step
//! ([`crossings`]); the turning amplitudes, each the vertex of the
//! parabola through the three samples around it ([`turning_values`]); the
//! energy ½ m v² + ½ I ω² + m g y averaged over each period; and the
//! anchor separation of the joint, from the poses.
//!
//! # Rows of the soft step, and where their tolerances come from
//!
//! The soft step's error has two sources of the same order: symplectic
//! Euler per substep h (first order in its velocities, but its positions
//! are Störmer–Verlet's from a half-kicked start, so its period errs at
//! second order: (hω)²/24 on the linearised pendulum) and the softness of
//! the joints' rigid rows, whose static sink a/ω_c² and drift ½ h² a_c
//! per substep also scale as h² when the rows' frequency follows the
//! substep (Box2D's rule min(60 Hz, 1/(4h)) is 1/(4h) exactly at the
//! defaults' h = 1/240 s). The soft rows dissipate (a row stretching under
//! a tension T takes T ds of energy, and its stretch lags the tension),
//! and near the separatrix (170°) the period depends steeply on the
//! energy, so no closed bound of the softness is tight there. Every
//! accuracy row therefore takes [`RICHARDSON_FACTOR`] × the step-doubling
//! estimate of the soft step's own error: the same scene at h/2 (8
//! substeps) with its joints at 1/(4 h/2) = 120 Hz, order 2 (measured: the
//! errors fall 4.0 to 4.1 times per halving on the 10° and 90° rods),
//! plus the measurement's own error (the crossings' and turning points'
//! location inside the step). The anchor separation is bounded in closed
//! form instead, by the soft rows' sink and drift
//! ([`SoftRows::separation_bound`]), for the soft step and for Box2D,
//! whose joints are the same rows.

use super::CaseReport;
use super::joint_common::{
    Config, Engine, JointScene, Run, SoftRows, crossing_error, crossings, steps, turning_values,
};
use crate::row::{RowKind, RowSink};
use crate::tolerance::{RICHARDSON_FACTOR, richardson_error};
use anyhow::{Result, bail};
use engine::Shape;
use references::many_body::{JointKind, Pose};
use references::pendulum::{Pendulum, PhysicalPendulum};

/// How much of the case to run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Size {
    /// Full periods measured (the run lasts that many periods of the
    /// slowest pendulum, plus one).
    pub periods: usize,
    /// Whether rapier2d and Box2D run too.
    pub reference_engines: bool,
    /// Whether the work-precision and drift charts are drawn.
    pub charts: bool,
}

impl Size {
    /// The harness's run: 100 periods, every engine, the charts.
    pub const FULL: Size = Size {
        periods: 100,
        reference_engines: true,
        charts: true,
    };

    /// The test's run: 10 periods of the soft step alone.
    pub const REDUCED: Size = Size {
        periods: 10,
        reference_engines: false,
        charts: false,
    };
}

/// Runs the pendulums of `scenes/<scene>.toml` for case `case` at `size`:
/// the soft step at its defaults and at h/2 (its rows), then rapier2d and
/// Box2D (Box2D's separation rows, both engines' notes). Returns the report,
/// the scene and its pendulums (for the charts).
pub fn run_case(
    case: &str,
    scene: &str,
    size: Size,
) -> Result<(CaseReport, JointScene, Vec<Spec>)> {
    let js = JointScene::load(scene)?;
    let specs = pendulums(&js)?;
    let mut report = CaseReport::default();
    let slowest = specs.iter().map(|p| p.closed.period()).fold(0.0, f64::max);
    let duration = (size.periods as f64 + 1.0) * slowest;
    let base = Config::of(&js.scene, Engine::SoftStep)?;
    if duration > js.scene.duration() + base.dt {
        bail!(
            "scenes/{scene}.toml lasts {} s, shorter than the {duration:.1} s of {} periods",
            js.scene.duration(),
            size.periods
        );
    }
    let n = steps(duration, base.dt);
    let soft = js.run(&base, n)?;
    let half = js.run(&base.halved(), n)?;
    let (soft_sep, half_sep) = (js.largest_separations(&soft), js.largest_separations(&half));
    let measure = |run: &Run, seps: &[f64]| -> Result<Vec<Swing>> {
        specs
            .iter()
            .map(|p| Swing::measure(&js, p, run, size.periods, seps[p.joint]))
            .collect()
    };
    let swings = measure(&soft, &soft_sep)?;
    let halves = measure(&half, &half_sep)?;
    let rows_model = SoftRows::defaults(base.substep());
    let mut sink = RowSink {
        case,
        method: Engine::SoftStep.id(),
        dt: base.dt,
        rows: &mut report.rows,
    };
    for ((p, s), half) in specs.iter().zip(&swings).zip(&halves) {
        soft_rows(&mut sink, p, s, half, base.dt, size.periods, &rows_model);
    }
    report.notes.push(DOUBLING_NOTE.into());
    report.notes.push(soft_note(&specs, &swings, &halves));
    if size.reference_engines {
        for engine in [Engine::Box2d, Engine::Rapier] {
            let config = Config::of(&js.scene, engine)?;
            let run = js.run(&config, n)?;
            let seps = js.largest_separations(&run);
            let measured: Vec<Result<Swing>> = specs
                .iter()
                .map(|p| Swing::measure(&js, p, &run, size.periods, seps[p.joint]))
                .collect();
            if engine == Engine::Box2d {
                let mut sink = RowSink {
                    case,
                    method: engine.id(),
                    dt: config.dt,
                    rows: &mut report.rows,
                };
                for (p, sep) in specs.iter().zip(&seps) {
                    separation_row(&mut sink, p, *sep, &rows_model, BOX2D_ROUNDING);
                }
            }
            report.notes.push(engine_note(engine, &specs, &measured));
        }
    }
    Ok((report, js, specs))
}

/// Box2D's single precision on the separations read from its poses: its
/// positions are f32 within 4.2 m of the origin (an ulp of 4.8e-7 m) and
/// its angles f32 (1 m × 1.2e-7 rad): a few ulps, 2e-6 m.
pub const BOX2D_ROUNDING: f64 = 2e-6;

/// One pendulum of a scene.
#[derive(Debug, Clone)]
pub struct Spec {
    /// Its body's name (`rod_10`, `pin_170`, `box_90`, ...).
    pub name: String,
    /// Its body.
    pub body: usize,
    /// Its joint.
    pub joint: usize,
    /// A rod (distance joint at the centre) or a pin (revolute joint).
    pub rod: bool,
    /// The pivot (m).
    pub pivot: [f64; 2],
    /// Distance from the pivot to the centre (m).
    pub arm: f64,
    /// θ0 (rad).
    pub amplitude: f64,
    /// The closed form it swings as.
    pub closed: Pendulum,
}

impl Spec {
    /// A chart title: the joint and the release angle.
    pub fn title(&self) -> String {
        format!(
            "{} from {:.0}°",
            if self.rod { "rod" } else { "pin" },
            self.amplitude.to_degrees()
        )
    }

    /// g/L_eq (s⁻²).
    pub fn omega2(&self) -> f64 {
        self.closed.omega().powi(2)
    }

    /// The largest θ'² of the swing, 2 (g/L_eq)(1 − cos θ0) (s⁻²).
    pub fn fastest2(&self) -> f64 {
        2.0 * self.omega2() * (1.0 - self.amplitude.cos())
    }

    /// The largest acceleration the joint's load gives its error (m/s²),
    /// over the swing: along the arm the tension per unit mass,
    /// g cos θ + d θ'² (θ'² = 2 (g/L_eq)(cos θ − cos θ0)), the rod's one
    /// row; for a pin also across the arm, where the body's tangential
    /// pivot force m g sin θ k²/(d² + k²) (k² = I_c/m) times the row's
    /// inverse mass there, (1 + d²/k²)/m, is exactly g sin θ.
    pub fn load(&self, g: f64) -> f64 {
        (0..=1000)
            .map(|i| {
                let theta = self.amplitude * i as f64 / 1000.0;
                let rate2 = 2.0 * self.omega2() * (theta.cos() - self.amplitude.cos());
                let along = g * theta.cos() + self.arm * rate2;
                if self.rod {
                    along.abs()
                } else {
                    along.hypot(g * theta.sin())
                }
            })
            .fold(0.0, f64::max)
    }

    /// The largest centripetal acceleration of the anchors (m/s²): d θ'²
    /// at the bottom (the pin's anchor on the disc turns about the centre
    /// at d, the rod's centre about the pivot).
    pub fn centripetal(&self) -> f64 {
        self.arm * self.fastest2()
    }
}

/// The pendulums of a scene: each body held to the world by its own
/// joint, a rigid distance joint at its centre (a rod: the body never
/// turns, a point mass) or a revolute joint (a pin: a physical pendulum of
/// a disc or a polygon about the pivot).
pub fn pendulums(js: &JointScene) -> Result<Vec<Spec>> {
    let g = js.gravity()?;
    let mut out = Vec::new();
    for (joint, j) in js.neutral.joints.iter().enumerate() {
        let (Some(body), None) = (j.body_b, j.body_a) else {
            bail!("joint {joint} must hold a body (B) to the world (A)");
        };
        let name = js.scene.bodies()[body].name.clone();
        let b = &js.neutral.bodies[body];
        let pivot = j.anchors().0;
        let (dx, dy) = (b.position[0] - pivot[0], b.position[1] - pivot[1]);
        let arm = dx.hypot(dy);
        let amplitude = dx.atan2(-dy);
        let rod = match j.kind {
            JointKind::Distance(_) => true,
            JointKind::Revolute(_) => false,
            _ => bail!("joint {joint} is neither a rod nor a pin"),
        };
        let closed = if rod {
            Pendulum::new(arm, g, amplitude)
        } else {
            // The pivot in the body's frame, and the body's own area
            // moment computed here, not by the engine.
            let pose = Pose {
                position: b.position,
                angle: b.angle,
            };
            let body_pivot = pose.to_local(pivot);
            let physical = match &b.shape {
                Shape::Circle(c) => PhysicalPendulum::disc(c.radius, arm),
                Shape::Polygon(p) => {
                    let vertices: Vec<[f64; 2]> = p.vertices().iter().map(|v| [v.x, v.y]).collect();
                    PhysicalPendulum::polygon(&vertices, body_pivot)
                }
                Shape::Compound(_) => bail!("body '{name}' is a compound"),
                Shape::Chain(_) => bail!("body '{name}' is a chain"),
                Shape::Rounded(r) => bail!("body '{name}' is a {}", r.kind().name()),
            };
            physical.pendulum(g, amplitude)
        };
        out.push(Spec {
            name,
            body,
            joint,
            rod,
            pivot,
            arm,
            amplitude,
            closed,
        });
    }
    Ok(out)
}

/// What one run does with one pendulum.
#[derive(Debug, Clone, PartialEq)]
pub struct Swing {
    /// The first period (between the first and third zero crossings)
    /// against T(θ0), relative.
    pub first: f64,
    /// Each of the first `periods` periods against the closed form at the
    /// amplitude it has (the mean of its two turning amplitudes), the mean
    /// of those relative errors.
    pub at_amplitude: f64,
    /// The amplitude of the last measured period minus θ0 (rad).
    pub amplitude_change: f64,
    /// The mean energy over the last measured period minus that over the
    /// first, over the swing energy m g d (1 − cos θ0).
    pub energy_change: f64,
    /// The largest anchor separation over the run (m).
    pub separation: f64,
    /// The error allowance of `at_amplitude` from the amplitudes' location
    /// and their change within a period (relative).
    pub amplitude_allowance: f64,
}

impl Swing {
    /// Measures `spec` in `run` over `periods` periods.
    pub fn measure(
        js: &JointScene,
        spec: &Spec,
        run: &Run,
        periods: usize,
        separation: f64,
    ) -> Result<Swing> {
        let b = spec.body;
        let offsets: Vec<f64> = run
            .samples
            .iter()
            .map(|s| s[b].position[0] - spec.pivot[0])
            .collect();
        let angles: Vec<f64> = run
            .samples
            .iter()
            .map(|s| (s[b].position[0] - spec.pivot[0]).atan2(spec.pivot[1] - s[b].position[1]))
            .collect();
        let c = crossings(&offsets, run.dt);
        // Turning amplitude j + 1 (the release is the 0th); period k lies
        // between crossings 2k and 2k + 2 and holds turnings 2k and 2k + 1.
        let turns = turning_values(&angles);
        if c.len() < 2 * periods + 1 || turns.len() < 2 * periods {
            bail!(
                "{}: {} crossings and {} turning points, fewer than {periods} periods",
                spec.name,
                c.len(),
                turns.len()
            );
        }
        let t0 = spec.closed.period();
        let period_of = |a: f64| spec.closed_at(a).period();
        let location = turning_error(run.dt, spec.omega2(), spec.amplitude);
        let mut sum = 0.0;
        let mut allowance: f64 = 0.0;
        for k in 0..periods {
            let (a1, a2) = (turns[2 * k], turns[2 * k + 1]);
            let a = 0.5 * (a1 + a2);
            sum += (c[2 * k + 2] - c[2 * k]) / period_of(a) - 1.0;
            // ln T(A): its slope and curvature by central differences.
            let e = 1e-4 * (std::f64::consts::PI - a).min(a);
            let (lo, mid, hi) = (
                period_of(a - e).ln(),
                period_of(a).ln(),
                period_of(a + e).ln(),
            );
            let slope = (hi - lo) / (2.0 * e);
            let curvature = (hi - 2.0 * mid + lo) / (e * e);
            allowance =
                allowance.max(slope.abs() * location + 0.5 * curvature.abs() * (a1 - a2).powi(2));
        }
        let (m, i) = js.mass(b);
        let g = js.gravity()?;
        let energy = |k: usize| -> f64 {
            let s = &run.samples[k][b];
            0.5 * m * (s.velocity[0].powi(2) + s.velocity[1].powi(2))
                + 0.5 * i * s.angular_velocity.powi(2)
                + m * g * s.position[1]
        };
        let mean_energy = |from: f64, to: f64| -> f64 {
            let (k0, k1) = ((from / run.dt).ceil() as usize, (to / run.dt) as usize);
            (k0..=k1).map(energy).sum::<f64>() / (k1 + 1 - k0) as f64
        };
        let last = periods - 1;
        let swing_energy = m * g * spec.arm * (1.0 - spec.amplitude.cos());
        Ok(Swing {
            first: (c[2] - c[0]) / t0 - 1.0,
            at_amplitude: sum / periods as f64,
            amplitude_change: 0.5 * (turns[2 * last] + turns[2 * last + 1]) - spec.amplitude,
            energy_change: (mean_energy(c[2 * last], c[2 * last + 2]) - mean_energy(c[0], c[2]))
                / swing_energy,
            separation,
            amplitude_allowance: allowance,
        })
    }
}

impl Spec {
    /// The closed form of this pendulum released from `amplitude` (rad).
    fn closed_at(&self, amplitude: f64) -> Pendulum {
        Pendulum::new(self.closed.length, self.closed.gravity, amplitude)
    }

    /// The crossing-location error of one crossing (s), [`crossing_error`]
    /// with |x'''/x'| = g/L_eq + θ'² at the bottom (x = d sin θ: x''' =
    /// d (θ''' − θ'³) there, θ''' = −(g/L_eq) θ').
    fn crossing_error(&self, dt: f64) -> f64 {
        crossing_error(dt, self.omega2() + self.fastest2())
    }
}

/// A bound (rad) on a turning amplitude read as the vertex of the parabola
/// through three samples `dt` apart: the parabola errs by at most
/// max|θ'''| (1.5 dt)³/6 within the window, and θ''' = −(g/L) cos θ θ'
/// with |θ'| ≤ (g/L) sin A · 1.5 dt there, so by (g/L)² sin A (1.5 dt)⁴/6.
fn turning_error(dt: f64, omega2: f64, amplitude: f64) -> f64 {
    omega2 * omega2 * amplitude.sin() * (1.5 * dt).powi(4) / 6.0
}

/// The step-doubling tolerance of a soft-step value `h` whose value at h/2
/// is `half`: [`RICHARDSON_FACTOR`] × |(h − half)/(1 − 2⁻²)|.
fn doubled(h: f64, half: f64) -> f64 {
    RICHARDSON_FACTOR * richardson_error(h, half, 2).abs()
}

const DOUBLING: &str = "1.5 x the step-doubling (Richardson, order 2) estimate of the soft \
     step's own error, from the scene at h/2 = 1/480 s with its joints at 1/(4 h/2) = 120 Hz \
     (see the notes); 1.5 is a chosen margin, covering a next-order term up to 2^2 - 1 = 3 x the \
     leading one (harness/src/tolerance.rs)";

/// The case note that explains [`DOUBLING`].
const DOUBLING_NOTE: &str = "Tolerances of the soft step's accuracy rows: 1.5 x the step-doubling \
     (Richardson) estimate of its own error at order 2, from the same scene at h/2 = 1/480 s (8 \
     substeps) with its joints at 1/(4 h/2) = 120 Hz. That is the defaults' family: Box2D's joint \
     frequency min(60 Hz, 1/(4h)) is 1/(4h) exactly at h = 1/240 s. Order 2 because symplectic \
     Euler's positions are Störmer–Verlet's (from a start half a kick later, so its period errs \
     by (hω)²/24 on the linearised pendulum) and the soft rows' static sink a/ω_c² and drift \
     ½h²a_c per substep scale as h² along the family (each row prints its value at h/2 beside \
     the value at h: their ratio is the measured fall per halving). The soft rows also dissipate (a row stretching under \
     a tension T takes T ds, and its stretch lags the tension by a few substeps), which near the \
     separatrix changes the period a lot: no closed bound of the softness is tight there, the \
     step doubling is. The separations are bounded in closed form.";

#[allow(clippy::too_many_arguments)]
fn soft_rows(
    sink: &mut RowSink<'_>,
    p: &Spec,
    s: &Swing,
    half: &Swing,
    dt: f64,
    periods: usize,
    rows: &SoftRows,
) {
    let name = &p.name;
    let t0 = p.closed.period();
    let crossing = p.crossing_error(dt);
    let closed = if p.rod {
        format!("a point mass on a rod of L = {:.6} m", p.closed.length)
    } else {
        format!(
            "a rigid body about its pivot: L_eq = I_pivot/(m d) = {:.6} m",
            p.closed.length
        )
    };
    sink.within(
        RowKind::Consistency,
        &format!("period_first_{name}"),
        s.first,
        0.0,
        doubled(s.first, half.first) + 2.0 * crossing / t0,
        format!(
            "first period (first to third zero crossing) over T(θ0) = 4 √(L/g) K(sin(θ0/2)) = \
             {t0:.12} s ({closed}), minus 1 (h/2: {:+.3e}). Tolerance: {DOUBLING}; plus two \
             crossings located inside their steps, dt³(g/L + θ'²max)/8 = {crossing:.1e} s each",
            half.first
        ),
    );
    sink.within(
        RowKind::Consistency,
        &format!("period_{name}"),
        s.at_amplitude,
        0.0,
        doubled(s.at_amplitude, half.at_amplitude) + 2.0 * crossing / t0 + s.amplitude_allowance,
        format!(
            "mean over the first {periods} periods of each period over the closed form at the \
             amplitude it has then (the mean of its two turning amplitudes; the soft rows \
             dissipate, so the amplitude decays), minus 1 (h/2: {:+.3e}). Tolerance: \
             {DOUBLING}; plus the crossings' location and the amplitudes' (vertex of the \
             parabola through three samples, (g/L)² sin A (1.5 dt)⁴/6 rad, times |d ln T/dA|) \
             and the decay within a period (½ |d² ln T/dA²| ΔA²): {:.1e}",
            half.at_amplitude, s.amplitude_allowance
        ),
    );
    let location = turning_error(dt, p.omega2(), p.amplitude);
    sink.within(
        RowKind::Consistency,
        &format!("amplitude_{name}"),
        s.amplitude_change,
        0.0,
        doubled(s.amplitude_change, half.amplitude_change) + location,
        format!(
            "amplitude of period {periods} (the mean of its turning amplitudes) minus θ0 = {:.1}° \
             (rad; h/2: {:+.3e} rad). Tolerance: {DOUBLING}; plus the turning points' location, \
             {location:.1e} rad",
            p.amplitude.to_degrees(),
            half.amplitude_change
        ),
    );
    sink.within(
        RowKind::Consistency,
        &format!("energy_{name}"),
        s.energy_change,
        0.0,
        doubled(s.energy_change, half.energy_change),
        format!(
            "mean energy ½mv² + ½Iω² + mgy over period {periods} minus that over the first, over \
             the swing energy m g d (1 − cos θ0) (h/2: {:+.3e}; averaging over a period removes \
             symplectic Euler's first-order energy oscillation, whose integral over a period is \
             0). Tolerance: {DOUBLING}",
            half.energy_change
        ),
    );
    separation_row(sink, p, s.separation, rows, 0.0);
}

fn separation_row(sink: &mut RowSink<'_>, p: &Spec, separation: f64, rows: &SoftRows, extra: f64) {
    let g = p.closed.gravity;
    let (load, centripetal) = (p.load(g), p.centripetal());
    let bound = rows.separation_bound(load, centripetal) + extra;
    let what = if p.rod {
        "| |anchor B − anchor A| − L |, the rod's length error"
    } else {
        "|anchor B − anchor A|, the pin's opening"
    };
    let rounding = if extra > 0.0 {
        format!(" + {extra:.0e} m for Box2D's single-precision poses")
    } else {
        String::new()
    };
    sink.at_most(
        RowKind::Validation,
        &format!("separation_{}", p.name),
        separation,
        0.0,
        bound,
        format!(
            "largest {what} over the run (m), from the poses. Bound: the soft rows' \
             (a_load + a_c (1 + 1/(2 a3)))/ω_c² (docs/joints.md: the static sink plus the \
             drift ½h²a_c per substep of which the bias removes h²ω_c²a3) with the largest \
             load a_load = {load:.3} m/s² and centripetal a_c = {centripetal:.3} m/s² of the \
             swing, ω_c = 2π × 60 Hz, a3 = {:.4}{rounding}",
            rows.a3
        ),
    );
}

fn soft_note(specs: &[Spec], swings: &[Swing], halves: &[Swing]) -> String {
    let items: Vec<String> = specs
        .iter()
        .zip(swings.iter().zip(halves))
        .map(|(p, (s, h))| {
            format!(
                "{}: first period {:+.2e} (h/2 {:+.2e}), at its amplitude {:+.2e}, amplitude \
                 {:+.3}° (h/2 {:+.3}°), energy {:+.2e} of the swing's",
                p.name,
                s.first,
                h.first,
                s.at_amplitude,
                s.amplitude_change.to_degrees(),
                h.amplitude_change.to_degrees(),
                s.energy_change
            )
        })
        .collect();
    format!(
        "Soft step at its defaults (dt = 1/60 s, 4 substeps, joints at 60 Hz, ζ = 2), and at \
         h/2 with its joints at 120 Hz: {}. The soft rows dissipate: a row whose anchors \
         stretch under a tension T loses T·ds of energy, and the stretch lags the tension by a \
         few substeps (the bias removes only h²ω_c²a3 ≈ 25 % of it per substep), so each \
         swing loses a little; near the separatrix that shortens the period a lot. At its \
         amplitude the period is still the elliptic integral's to the rows' softness.",
        items.join("; ")
    )
}

fn engine_note(engine: Engine, specs: &[Spec], measured: &[Result<Swing>]) -> String {
    let items: Vec<String> = specs
        .iter()
        .zip(measured)
        .map(|(p, m)| match m {
            Ok(s) => format!(
                "{}: first period {:+.2e}, at its amplitude {:+.2e}, amplitude {:+.3}°, energy \
                 {:+.2e}, separation {:.2e} m",
                p.name,
                s.first,
                s.at_amplitude,
                s.amplitude_change.to_degrees(),
                s.energy_change,
                s.separation
            ),
            Err(e) => format!("{}: not measured ({e:#})", p.name),
        })
        .collect();
    let why = match engine {
        Engine::Box2d => {
            "Box2D's joints are the soft step's rows (60 Hz, ζ = 2, relaxed, warm-started) in \
             f32, so it loses energy the same way; its separations are rows above (the same \
             bound); its periods are informational (its own step doubling would keep its joints \
             at 60 Hz: Box2D fixes their frequency)"
        }
        _ => {
            "rapier's joints are rigid (1e6 Hz, ζ = 1) and not warm-started, its rod a \
             position motor kept in the relax pass: its rods keep their energy far better than \
             the soft rows, its revolute pins lose more of theirs at large amplitudes; \
             informational (no bound derived for its solver)"
        }
    };
    format!(
        "{} on the same file (dt = 1/60 s, 4 substeps): {}. {why}.",
        engine.label(),
        items.join("; ")
    )
}
