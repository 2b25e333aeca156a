//! The first contact event inside a trial step (seed §7.2, Fig. 7.7–7.8):
//! the time of impact of a pair that interpenetrates by the end of the step,
//! by the seed's bisection of the step or by conservative advancement, and
//! the time a sliding contact stops, by root finding. Every probe is the
//! integrator's own step from the start of the trial step, of a shorter
//! length, so the event lies on the method's solution.

use super::pipeline::{ContactPipeline, PROJECTION_SLOP, Phase, Profiler};
use super::resting::{FrictionMode, RestingPair, pose};
use super::rows::BodyView;
use super::settings::ToiMethod;
use crate::body::{Body, BodyState};
use crate::collision::narrow_phase::rotation_radius;
use crate::collision::proximity;
use crate::error::{EngineError, Result};
use crate::integrators::Integrator;
use crate::root_finding::illinois;
use crate::world_ode::WorldOde;
use nalgebra::Vector2;

/// Relative time tolerance of the stick-time root finding (as the world's
/// event location).
const STICK_TIME_TOLERANCE: f64 = 1e-15;

impl ContactPipeline {
    /// The earliest contact event inside the trial step from `(t, y_a)`
    /// over `h` to `y_b`: a time of impact or a stick time, as an offset
    /// `s ∈ (0, h]` from `t`; `None` if the step is clear.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn first_event(
        &mut self,
        sys: &mut WorldOde<'_>,
        integrator: &mut Integrator,
        t: f64,
        y_a: &[f64],
        y_b: &[f64],
        h: f64,
        probe: &mut Vec<f64>,
        profiler: &mut Profiler,
    ) -> Result<Option<f64>> {
        let bodies = sys.bodies;
        let layout = sys.layout;
        let eps = self.settings.tolerance;
        let mut states_a = std::mem::take(&mut self.states_a);
        let mut states_b = std::mem::take(&mut self.states_b);
        let mut probe_states = std::mem::take(&mut self.probe_states);
        states_a.clone_from(sys.states);
        states_b.clone_from(sys.states);
        probe_states.clone_from(sys.states);
        layout.unpack(y_a, &mut states_a);
        layout.unpack(y_b, &mut states_b);
        let ca = self.settings.toi_method == ToiMethod::ConservativeAdvancement;
        let swept = ca.then_some((states_a.as_slice(), h));
        let pairs = self.candidates(bodies, &states_b, eps, swept, profiler);
        let mut earliest: Option<f64> = None;
        let mut keep = |s: f64| {
            earliest = Some(earliest.map_or(s, |e: f64| e.min(s)));
        };
        let max_it = self.settings.max_toi_iterations;
        let result = (|| -> Result<()> {
            for (a, b) in pairs {
                let (sa, sb) = (
                    bodies[a].shape.as_ref().expect("collidable"),
                    bodies[b].shape.as_ref().expect("collidable"),
                );
                let started = profiler.start();
                let d_end = proximity(sa, &pose(&states_b[a]), sb, &pose(&states_b[b])).distance;
                let d_start = proximity(sa, &pose(&states_a[a]), sb, &pose(&states_a[b])).distance;
                profiler.stop(Phase::Narrow, started);
                // Separated at t: the seed's search, to |d| <= ε. Touching
                // (or overlapping by less than the projection slop): the
                // first time it overlaps by ε to 2ε more than at t (a body
                // that bounced off and came back within the step, a second
                // corner coming down).
                let separated = d_start > eps;
                let reference = d_start.min(0.0);
                let touching = !separated && d_start >= -PROJECTION_SLOP * eps;
                let sinks = if separated {
                    d_end < -eps
                } else {
                    d_end < reference - eps
                };
                if !(sinks && (separated || touching)) && !(ca && separated) {
                    continue;
                }
                let started = profiler.start();
                profiler.profile.toi_searches += 1;
                let mut evaluations = 0u64;
                let mut distance_at = |s: f64| -> Result<f64> {
                    evaluations += 1;
                    probe.resize(y_a.len(), 0.0);
                    integrator.single_step(sys, t, y_a, s, probe)?;
                    layout.unpack(probe, &mut probe_states);
                    Ok(
                        proximity(sa, &pose(&probe_states[a]), sb, &pose(&probe_states[b]))
                            .distance,
                    )
                };
                let found = if separated && ca {
                    let bound = [&states_a, &states_b]
                        .iter()
                        .map(|st| {
                            (st[b].velocity - st[a].velocity).norm()
                                + st[a].angular_velocity.abs() * rotation_radius(sa)
                                + st[b].angular_velocity.abs() * rotation_radius(sb)
                        })
                        .fold(0.0, f64::max);
                    match advance(&mut distance_at, d_start, bound, h, eps, max_it, t)? {
                        Advance::Found(s) => Some(s),
                        Advance::Clear if !sinks => None,
                        // A miss while the end overlaps: the seed's bisection.
                        Advance::Clear => {
                            Some(bisect(&mut distance_at, (0.0, h), (-eps, eps), max_it, t)?)
                        }
                        // The speed bound did not hold (speeds not convex
                        // over the step): bisect the bracket it jumped.
                        Advance::Overshot(lo, hi) => {
                            Some(bisect(&mut distance_at, (lo, hi), (-eps, eps), max_it, t)?)
                        }
                    }
                } else if separated {
                    Some(bisect(&mut distance_at, (0.0, h), (-eps, eps), max_it, t)?)
                } else {
                    Some(bisect(
                        &mut distance_at,
                        (0.0, h),
                        (reference - 2.0 * eps, reference - eps),
                        max_it,
                        t,
                    )?)
                };
                profiler.profile.toi_evaluations += evaluations;
                profiler.stop(Phase::Toi, started);
                if let Some(s) = found {
                    keep(s);
                }
            }
            let resting: Vec<RestingPair> = sys
                .contacts
                .as_deref()
                .map(|c| c.pairs.clone())
                .unwrap_or_default();
            // Releases: a resting point whose separation rises above 2ε.
            // The contact set is fixed over a piece (module `persistent`),
            // so the step is cut where the point has left, between ε and
            // 2ε, and the next settle drops it.
            for p in &resting {
                let (_, end) = p.follow(&states_b);
                let (_, start) = p.follow(&states_a);
                for k in 0..p.features.count() {
                    if !(end[k].separation > 2.0 * eps && start[k].separation <= eps) {
                        continue;
                    }
                    let started = profiler.start();
                    profiler.profile.toi_searches += 1;
                    let mut evaluations = 0u64;
                    let mut minus_separation = |s: f64| -> Result<f64> {
                        evaluations += 1;
                        probe.resize(y_a.len(), 0.0);
                        integrator.single_step(sys, t, y_a, s, probe)?;
                        layout.unpack(probe, &mut probe_states);
                        Ok(-p.follow(&probe_states).1[k].separation)
                    };
                    let s = bisect(
                        &mut minus_separation,
                        (0.0, h),
                        (-2.0 * eps, -eps),
                        max_it,
                        t,
                    )?;
                    profiler.profile.toi_evaluations += evaluations;
                    profiler.stop(Phase::Toi, started);
                    keep(s);
                }
            }
            // Stick times of the sliding pairs.
            for p in resting {
                let FrictionMode::Sliding { direction } = p.friction else {
                    continue;
                };
                let started = profiler.start();
                let g_end = sliding_speed(bodies, &states_b, &p, direction, eps);
                let g_start = sliding_speed(bodies, &states_a, &p, direction, eps);
                let (Some(g_end), Some(g_start)) = (g_end, g_start) else {
                    profiler.stop(Phase::Toi, started);
                    continue;
                };
                if !(g_end <= 0.0 && g_start > 0.0) {
                    profiler.stop(Phase::Toi, started);
                    continue;
                }
                profiler.profile.toi_searches += 1;
                let mut evaluations = 0u64;
                let s = illinois(
                    |s| {
                        evaluations += 1;
                        probe.resize(y_a.len(), 0.0);
                        integrator.single_step(sys, t, y_a, s, probe)?;
                        layout.unpack(probe, &mut probe_states);
                        // Contact lost on the way: count it as stopped here.
                        Ok(sliding_speed(bodies, &probe_states, &p, direction, eps).unwrap_or(0.0))
                    },
                    0.0,
                    g_start,
                    h,
                    g_end,
                    STICK_TIME_TOLERANCE * h.max(t.abs()),
                )?;
                profiler.profile.toi_evaluations += evaluations;
                profiler.stop(Phase::Toi, started);
                keep(s);
            }
            Ok(())
        })();
        self.states_a = states_a;
        self.states_b = states_b;
        self.probe_states = probe_states;
        result.map(|()| earliest)
    }
}

/// B's tangential velocity relative to A at the centre of their manifold,
/// along `direction` (m/s); `None` when they no longer touch.
fn sliding_speed(
    bodies: &[Body],
    states: &[BodyState],
    p: &RestingPair,
    direction: Vector2<f64>,
    eps: f64,
) -> Option<f64> {
    let (m, _) = p.follow(states);
    if m.max_depth() < -eps {
        return None;
    }
    let centre = m.points().iter().map(|q| q.point).sum::<Vector2<f64>>() / m.points().len() as f64;
    let (va, vb) = (
        BodyView::new(&bodies[p.a], &states[p.a]),
        BodyView::new(&bodies[p.b], &states[p.b]),
    );
    let v = vb.point_velocity(centre - vb.position) - va.point_velocity(centre - va.position);
    let tangential = v - m.normal * m.normal.dot(&v);
    Some(direction.dot(&tangential))
}

/// The seed's bisection (Fig. 7.8) of the interval `[lo, hi]` of the step
/// on the signed distance `g`, known to be above `band.1` at `lo` and below
/// `band.0` at `hi`: halve until g(s) falls in the band. When the interval
/// can no longer be halved (the distance jumps across the band within one
/// ulp of time), the later end is returned.
fn bisect(
    g: &mut impl FnMut(f64) -> Result<f64>,
    (mut lo, mut hi): (f64, f64),
    band: (f64, f64),
    max_iterations: usize,
    t: f64,
) -> Result<f64> {
    let mut last = f64::NAN;
    for _ in 0..max_iterations {
        let mid = lo + 0.5 * (hi - lo);
        if !(mid > lo && mid < hi) {
            return Ok(hi);
        }
        let d = g(mid)?;
        last = d;
        if d >= band.0 && d <= band.1 {
            return Ok(mid);
        }
        if d > band.1 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Err(EngineError::Contact {
        t,
        reason: format!(
            "time-of-impact bisection did not reach the band [{:e}, {:e}] m in {max_iterations} \
             iterations (last separation {last:e} m at s = {lo} s)",
            band.0, band.1
        ),
    })
}

/// The outcome of conservative advancement.
enum Advance {
    /// Within ε at this offset (s).
    Found(f64),
    /// Clear over the whole step.
    Clear,
    /// The separation went below −ε between these offsets: the speed bound
    /// did not hold.
    Overshot(f64, f64),
}

/// Conservative advancement on the integrated path: from separation `d0`
/// at 0, step by d / `bound` until d ≤ ε or past `h`.
fn advance(
    g: &mut impl FnMut(f64) -> Result<f64>,
    d0: f64,
    bound: f64,
    h: f64,
    eps: f64,
    max_iterations: usize,
    t: f64,
) -> Result<Advance> {
    if !(bound > 0.0 && bound.is_finite()) {
        return Ok(Advance::Clear);
    }
    let (mut previous, mut s, mut d) = (0.0, 0.0, d0);
    for _ in 0..max_iterations {
        if d < -eps {
            return Ok(Advance::Overshot(previous, s));
        }
        if d <= eps {
            return Ok(Advance::Found(s));
        }
        let next = s + d / bound;
        if next >= h {
            return Ok(Advance::Clear);
        }
        if next == s {
            break;
        }
        (previous, s) = (s, next);
        d = g(s)?;
    }
    Err(EngineError::Contact {
        t,
        reason: format!(
            "conservative advancement did not converge in {max_iterations} iterations \
             (separation {d:e} m at s = {s} s)"
        ),
    })
}
