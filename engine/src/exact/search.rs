//! The first contact event inside a trial step (seed §7.2, Fig. 7.7–7.8):
//! the time of impact of a pair that interpenetrates by the end of the step,
//! by the seed's bisection of the step or by conservative advancement, of a
//! pair apart at both ends whose motion could have touched in between (a
//! body crossing a thin one, [`ToiMethod::Swept`]), by conservative
//! advancement; the time a resting point leaves, by bisection; and the time
//! a sliding contact stops, by root finding. Every probe is the
//! integrator's own step from the start of the trial step, of a shorter
//! length, so the event lies on the method's solution.

use super::ode::WorldOde;
use super::pipeline::{ContactPipeline, PROJECTION_SLOP, joint_set};
use crate::body::{Body, BodyState};
use crate::collision::proximity;
use crate::contact::ToiMethod;
use crate::contact::resting::{FrictionMode, RestingPair, pose};
use crate::contact::rows::BodyView;
use crate::error::{EngineError, Result};
use crate::integrators::Integrator;
use crate::profile::{Phase, Profiler};
use crate::root_finding::illinois;
use nalgebra::Vector2;

use crate::tunables::STICK_TIME_TOLERANCE;

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
        let method = self.settings.toi_method;
        let ca = method == ToiMethod::ConservativeAdvancement;
        let swept = (method != ToiMethod::Bisection).then_some((states_a.as_slice(), h));
        let pairs = self.candidates(bodies, &states_b, eps, swept, joint_set(sys), profiler);
        // The earliest event so far: a search that can only end later is
        // abandoned (its bracket's early end passed it), so when several
        // pairs meet in one step the searches after the first are short.
        let mut earliest: Option<f64> = None;
        let max_it = self.settings.max_toi_iterations;
        // Every candidate's separations at both ends, searched in the order
        // of a linear estimate of their event time, the likely first first.
        let started = profiler.start();
        let mut checks: Vec<(usize, usize, f64, f64, f64)> = pairs
            .into_iter()
            .map(|(a, b)| {
                let (sa, sb) = (
                    bodies[a].shape.as_ref().expect("collidable"),
                    bodies[b].shape.as_ref().expect("collidable"),
                );
                let d_end = proximity(sa, &pose(&states_b[a]), sb, &pose(&states_b[b])).distance;
                let d_start = proximity(sa, &pose(&states_a[a]), sb, &pose(&states_a[b])).distance;
                let estimate = if d_start > d_end {
                    (d_start.max(0.0) / (d_start - d_end)).min(1.0)
                } else {
                    0.0
                };
                (a, b, d_start, d_end, estimate)
            })
            .collect();
        checks.sort_by(|x, y| x.4.total_cmp(&y.4));
        profiler.stop(Phase::Narrow, started);
        let result = (|| -> Result<()> {
            for (a, b, d_start, d_end, _) in checks {
                let before = earliest.unwrap_or(f64::INFINITY);
                let (sa, sb) = (
                    bodies[a].shape.as_ref().expect("collidable"),
                    bodies[b].shape.as_ref().expect("collidable"),
                );
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
                // The bound on the speed at which the pair's points approach
                // (m/s) at `st`, and its larger value at both ends of the step.
                let (ra, rb) = (sa.rotation_radius(), sb.rotation_radius());
                let speed_bound = move |st: &[BodyState]| {
                    (st[b].velocity - st[a].velocity).norm()
                        + st[a].angular_velocity.abs() * ra
                        + st[b].angular_velocity.abs() * rb
                };
                let bound = || speed_bound(&states_a).max(speed_bound(&states_b));
                // Apart at both ends, but fast enough for its motion to
                // have gone deep in between: d(s) ≥ max(d₀ − B s,
                // d₁ − B (h − s)) ≥ (d₀ + d₁ − B h)/2 over the step. Deep
                // means a quarter of the thinner shape's inner radius (a
                // body passing through another overlaps it by at least
                // about the thinner's half-thickness on the way): grazes
                // shallower than that are left to the seed's search, as the
                // bound, loose for a turning body near a contact, would make
                // conservative advancement creep.
                let deep = 0.25 * sa.inner_radius().min(sb.inner_radius());
                let may_touch_inside = method == ToiMethod::Swept
                    && separated
                    && !sinks
                    && d_start + d_end + 2.0 * deep.max(eps) <= bound() * h;
                let advances = separated && (ca || may_touch_inside);
                if !(sinks && (separated || touching)) && !advances {
                    continue;
                }
                let started = profiler.start();
                profiler.profile.toi_searches += 1;
                let mut evaluations = 0u64;
                // The separation (m) and the speed bound (m/s) at s.
                let mut probe_at = |s: f64| -> Result<(f64, f64)> {
                    evaluations += 1;
                    probe.resize(y_a.len(), 0.0);
                    integrator.single_step(sys, t, y_a, s, probe)?;
                    layout.unpack(probe, &mut probe_states);
                    Ok((
                        proximity(sa, &pose(&probe_states[a]), sb, &pose(&probe_states[b]))
                            .distance,
                        speed_bound(&probe_states),
                    ))
                };
                let band = (-eps, eps);
                let found = if advances && !ca {
                    // How fast the speed bound can grow (m/s²), from its
                    // terms' changes over the step (constant accelerations).
                    let growth = ((states_b[b].velocity - states_b[a].velocity)
                        - (states_a[b].velocity - states_a[a].velocity))
                        .norm()
                        / h
                        + (states_b[a].angular_velocity - states_a[a].angular_velocity).abs() * ra
                            / h
                        + (states_b[b].angular_velocity - states_a[b].angular_velocity).abs() * rb
                            / h;
                    let start = (d_start, speed_bound(&states_a));
                    let limits = (h.min(before), eps, max_it);
                    match advance_accelerating(&mut probe_at, start, growth, limits)? {
                        Advance::Found(s) => Some(s),
                        Advance::Clear | Advance::Later => None,
                        // Creeping (the bound is loose): look for an
                        // overlap on a grid of the rest of the step.
                        Advance::Stalled(from) => {
                            let mut found = None;
                            let mut lo = from;
                            for k in 1..=SWEEP_SAMPLES {
                                let s = from + (h - from) * k as f64 / SWEEP_SAMPLES as f64;
                                if lo >= before {
                                    break;
                                }
                                if probe_at(s)?.0 < -eps {
                                    let mut d = |s| probe_at(s).map(|(d, _)| d);
                                    found = bisect(&mut d, (lo, s), band, (max_it, before), t)?;
                                    break;
                                }
                                lo = s;
                            }
                            found
                        }
                        Advance::Overshot(lo, hi) => {
                            let mut d = |s| probe_at(s).map(|(d, _)| d);
                            bisect(&mut d, (lo, hi), band, (max_it, before), t)?
                        }
                    }
                } else {
                    let mut d = |s| probe_at(s).map(|(d, _)| d);
                    if advances {
                        match advance(&mut d, d_start, bound(), (h, before), eps, max_it, t)? {
                            Advance::Found(s) => Some(s),
                            Advance::Stalled(_) => unreachable!("only the swept search stalls"),
                            Advance::Later | Advance::Clear if !sinks => None,
                            Advance::Later => None,
                            // A miss while the end overlaps: the seed's
                            // bisection.
                            Advance::Clear => bisect(&mut d, (0.0, h), band, (max_it, before), t)?,
                            // The speed bound did not hold (speeds not
                            // convex over the step): bisect the bracket it
                            // jumped.
                            Advance::Overshot(lo, hi) => {
                                bisect(&mut d, (lo, hi), band, (max_it, before), t)?
                            }
                        }
                    } else if separated {
                        bisect(&mut d, (0.0, h), band, (max_it, before), t)?
                    } else {
                        let band = (reference - 2.0 * eps, reference - eps);
                        bisect(&mut d, (0.0, h), band, (max_it, before), t)?
                    }
                };
                profiler.profile.toi_evaluations += evaluations;
                profiler.stop(Phase::Toi, started);
                earlier(&mut earliest, found);
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
                    let before = earliest.unwrap_or(f64::INFINITY);
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
                    let band = (-2.0 * eps, -eps);
                    let found = bisect(&mut minus_separation, (0.0, h), band, (max_it, before), t)?;
                    profiler.profile.toi_evaluations += evaluations;
                    profiler.stop(Phase::Toi, started);
                    earlier(&mut earliest, found);
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
                earlier(&mut earliest, Some(s));
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
/// ulp of time), the later end is returned. `None` once the interval's
/// early end reaches `before` (s): the event found would come later than
/// one already known. Errors after `max_iterations` halvings.
fn bisect(
    g: &mut impl FnMut(f64) -> Result<f64>,
    (mut lo, mut hi): (f64, f64),
    band: (f64, f64),
    (max_iterations, before): (usize, f64),
    t: f64,
) -> Result<Option<f64>> {
    let mut last = f64::NAN;
    for _ in 0..max_iterations {
        if lo >= before {
            return Ok(None);
        }
        let mid = lo + 0.5 * (hi - lo);
        if !(mid > lo && mid < hi) {
            return Ok(Some(hi));
        }
        let d = g(mid)?;
        last = d;
        if d >= band.0 && d <= band.1 {
            return Ok(Some(mid));
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

/// Keeps the earlier of `earliest` and `found`.
fn earlier(earliest: &mut Option<f64>, found: Option<f64>) {
    if let Some(s) = found {
        *earliest = Some(earliest.map_or(s, |e| e.min(s)));
    }
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
    /// Still apart by more than ε after the iterations allowed, at this
    /// offset (s).
    Stalled(f64),
    /// Not touching before a time at which another event is already known.
    Later,
}

use crate::tunables::SWEEP_SAMPLES;

/// Conservative advancement on the integrated path with a speed bound that
/// grows: from separation d and speed bound c (m/s) at s (`g` gives both),
/// with the bound growing at most at `growth` (m/s²), the gap cannot close
/// before τ with c τ + growth τ²/2 = d; step by τ until d ≤ ε or past `h`.
/// A pair that starts nearly at rest and accelerates (a body let fall onto
/// another from a hair's breadth) then arrives in a few steps, where a
/// bound fixed at the step's largest speed creeps towards it by d/c. After
/// `max_iterations` without reaching ε it reports where it stalled.
fn advance_accelerating(
    g: &mut impl FnMut(f64) -> Result<(f64, f64)>,
    (d0, c0): (f64, f64),
    growth: f64,
    (h, eps, max_iterations): (f64, f64, usize),
) -> Result<Advance> {
    let (mut previous, mut s, mut d, mut c) = (0.0, 0.0, d0, c0);
    for _ in 0..max_iterations {
        if d < -eps {
            return Ok(Advance::Overshot(previous, s));
        }
        if d <= eps {
            return Ok(Advance::Found(s));
        }
        // The root of growth τ²/2 + c τ − d, in the form without
        // cancellation.
        let tau = 2.0 * d / (c + (c * c + 2.0 * growth * d).sqrt());
        if !(tau > 0.0 && tau.is_finite()) {
            return Ok(Advance::Clear);
        }
        let next = s + tau;
        if next >= h {
            return Ok(Advance::Clear);
        }
        if next == s {
            break;
        }
        (previous, s) = (s, next);
        (d, c) = g(s)?;
    }
    Ok(Advance::Stalled(s))
}

/// Conservative advancement on the integrated path: from separation `d0`
/// at 0, step by d / `bound` until d ≤ ε or past `h`.
fn advance(
    g: &mut impl FnMut(f64) -> Result<f64>,
    d0: f64,
    bound: f64,
    (h, before): (f64, f64),
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
        if next >= before {
            return Ok(Advance::Later);
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
