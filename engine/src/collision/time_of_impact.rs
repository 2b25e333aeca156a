//! Time of impact: when, inside a step [0, h], two moving shapes first
//! come within a tolerance ε of each other (seed §7.2, Fig. 7.7–7.8).
//!
//! Over the step each body moves with constant velocities (the poses are
//! interpolated, not re-integrated): `x(t) = x0 + v t`, `θ(t) = θ0 + ω t`,
//! the rotation being about the body origin (its centre of mass). Lengths
//! are in m, times in s, angular velocities in rad/s. The separation is the
//! exact signed distance of [`proximity`]: the gap when apart, −depth when
//! overlapping.
//!
//! Two methods:
//! - [`toi_bisection`], the seed's: if the pair does not interpenetrate at
//!   the start of the step and does at its end, halve the step — recompute
//!   the state at t + Δt/2; if it interpenetrates there go back to t + Δt/4,
//!   otherwise on to t + 3Δt/4, and so on — until the distance, positive or
//!   negative, is within ε (seed Fig. 7.8). It sees only the states it
//!   samples: a pair that touches and separates again inside the step, or a
//!   fast body that passes through a thin one, is missed, and with several
//!   crossings it finds one of them, the first if the separation decreases
//!   monotonically over the step.
//! - [`toi_conservative_advancement`] (Mirtich 1996): from the current
//!   distance d and normal n, no point can close the gap faster than
//!   `|v_rel·n| + |ω_a| r_a + |ω_b| r_b` (r the shape's
//!   [`Shape::rotation_radius`]), so the pair cannot touch before `t + d/bound`;
//!   advance to it and repeat until d ≤ ε. It never steps past the first
//!   contact and does not tunnel, and returns a time at which the pair is
//!   apart by at most ε.
//!
//! Both return the time and the contact manifold at that time, computed with
//! a margin of ε so that a pair stopped just short of contact has one.

use super::manifold::{Manifold, Proximity};
use super::narrow_phase::{collide, proximity};
use super::surely_within::surely_within;
use crate::shape::{ChainSegment, Shape, cross};
use nalgebra::{Isometry2, Point2, Translation2, UnitComplex, Vector2};
use thiserror::Error;

/// A body's motion over a step: its pose at t = 0 and constant velocities.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// Pose at the start of the step (position of the body origin in m,
    /// orientation in rad).
    pub pose: Isometry2<f64>,
    /// Velocity of the body origin (m/s).
    pub linear_velocity: Vector2<f64>,
    /// Angular velocity about the body origin (rad/s), counter-clockwise
    /// positive.
    pub angular_velocity: f64,
}

impl Motion {
    /// A motion from its start pose and velocities.
    pub fn new(pose: Isometry2<f64>, linear_velocity: Vector2<f64>, angular_velocity: f64) -> Self {
        Self {
            pose,
            linear_velocity,
            angular_velocity,
        }
    }

    /// A body that does not move.
    pub fn fixed(pose: Isometry2<f64>) -> Self {
        Self::new(pose, Vector2::zeros(), 0.0)
    }

    /// The pose at time t (s): translated by `v t`, turned by `ω t` about
    /// the body origin.
    pub fn pose_at(&self, t: f64) -> Isometry2<f64> {
        Isometry2::from_parts(
            Translation2::from(self.pose.translation.vector + t * self.linear_velocity),
            UnitComplex::new(self.angular_velocity * t) * self.pose.rotation,
        )
    }

    fn is_finite(&self) -> bool {
        let p = &self.pose;
        [
            p.translation.x,
            p.translation.y,
            p.rotation.re,
            p.rotation.im,
            self.linear_velocity.x,
            self.linear_velocity.y,
            self.angular_velocity,
        ]
        .iter()
        .all(|x| x.is_finite())
    }
}

/// Settings of the time-of-impact searches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToiOptions {
    /// ε (m), > 0: the largest distance, positive or negative, at which the
    /// pair counts as touching (seed Fig. 7.7). Smaller is more precise and
    /// costs more iterations. Default 1e-9 m.
    pub tolerance: f64,
    /// Iterations (distance evaluations after the first) before giving up
    /// with [`ToiError::NoConvergence`]. Default 200.
    pub max_iterations: usize,
}

impl Default for ToiOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-9,
            max_iterations: 200,
        }
    }
}

/// Where and when a pair first touches in the step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impact {
    /// Time of impact (s), in [0, h].
    pub time: f64,
    /// Signed distance at that time (m): |separation| ≤ ε, except at t = 0
    /// for a pair already overlapping when the step starts.
    pub separation: f64,
    /// The contact manifold at that time (computed with margin ε, so its
    /// depths may be slightly negative).
    pub manifold: Manifold,
    /// Distance evaluations spent after the first.
    pub iterations: usize,
}

/// Why a time of impact could not be computed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ToiError {
    /// A step, tolerance, pose or velocity is not finite or out of its domain.
    #[error("invalid {what}: {value} (must be finite{domain})")]
    InvalidParameter {
        /// Which parameter.
        what: &'static str,
        /// The offending value (NaN for a non-finite pose or velocity).
        value: f64,
        /// The domain beyond finiteness, e.g. `" and > 0"`.
        domain: &'static str,
    },
    /// The search ran out of iterations or of floating-point resolution.
    #[error(
        "{method} did not converge: {iterations} iterations, t = {time} s, separation {separation} m"
    )]
    NoConvergence {
        /// `"bisection"` or `"conservative advancement"`.
        method: &'static str,
        /// Iterations spent.
        iterations: usize,
        /// Last time reached (s).
        time: f64,
        /// Separation there (m).
        separation: f64,
    },
}

fn validate(motions: [&Motion; 2], h: f64, options: &ToiOptions) -> Result<(), ToiError> {
    if !(h.is_finite() && h > 0.0) {
        return Err(ToiError::InvalidParameter {
            what: "step h (s)",
            value: h,
            domain: " and > 0",
        });
    }
    if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
        return Err(ToiError::InvalidParameter {
            what: "tolerance ε (m)",
            value: options.tolerance,
            domain: " and > 0",
        });
    }
    if motions.iter().any(|m| !m.is_finite()) {
        return Err(ToiError::InvalidParameter {
            what: "pose or velocity",
            value: f64::NAN,
            domain: "",
        });
    }
    Ok(())
}

/// The pair's state at time t, with the proximity already evaluated.
struct Probe<'a> {
    a: &'a Shape,
    motion_a: &'a Motion,
    b: &'a Shape,
    motion_b: &'a Motion,
}

impl Probe<'_> {
    fn proximity(&self, t: f64) -> Proximity {
        proximity(
            self.a,
            &self.motion_a.pose_at(t),
            self.b,
            &self.motion_b.pose_at(t),
        )
    }

    fn impact(&self, time: f64, p: &Proximity, tolerance: f64, iterations: usize) -> Impact {
        let (pa, pb) = (self.motion_a.pose_at(time), self.motion_b.pose_at(time));
        let margin = tolerance.max(p.distance);
        // The fallback is only reachable through round-off at |distance| ≈ ε:
        // the exact witnesses make a one-point manifold.
        let manifold =
            collide(self.a, &pa, self.b, &pb, margin).unwrap_or_else(|| p.one_point_manifold());
        Impact {
            time,
            separation: p.distance,
            manifold,
            iterations,
        }
    }
}

/// Time of impact by the seed's bisection of the step (seed Fig. 7.7–7.8).
///
/// Returns `Ok(None)` if the pair is farther apart than ε at the end of the
/// step (it may still have touched inside the step: see the module docs),
/// an impact at t = 0 if it is already within ε (or overlapping) at the
/// start, and otherwise the first bisection point whose distance is within
/// ±ε. The time is then within about ε / (approach speed) of the contact.
pub fn toi_bisection(
    a: &Shape,
    motion_a: &Motion,
    b: &Shape,
    motion_b: &Motion,
    h: f64,
    options: &ToiOptions,
) -> Result<Option<Impact>, ToiError> {
    validate([motion_a, motion_b], h, options)?;
    let eps = options.tolerance;
    let probe = Probe {
        a,
        motion_a,
        b,
        motion_b,
    };
    let start = probe.proximity(0.0);
    if start.distance <= eps {
        return Ok(Some(probe.impact(0.0, &start, eps, 0)));
    }
    let end = probe.proximity(h);
    if end.distance > eps {
        return Ok(None);
    }
    if end.distance >= -eps {
        return Ok(Some(probe.impact(h, &end, eps, 1)));
    }
    let (mut lo, mut hi) = (0.0, h);
    let mut last = end.distance;
    for iteration in 2..=options.max_iterations + 1 {
        let mid = lo + 0.5 * (hi - lo);
        if !(mid > lo && mid < hi) {
            break;
        }
        let p = probe.proximity(mid);
        last = p.distance;
        if p.distance.abs() <= eps {
            return Ok(Some(probe.impact(mid, &p, eps, iteration)));
        }
        if p.distance > eps {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Err(ToiError::NoConvergence {
        method: "bisection",
        iterations: options.max_iterations,
        time: lo,
        separation: last,
    })
}

/// Time of impact by conservative advancement (see the module docs).
///
/// Returns `Ok(None)` if the pair stays farther apart than ε over the whole
/// step [0, h], an impact at t = 0 if it is already within ε (or
/// overlapping) at the start, and otherwise the first time reached at which
/// the distance is in [0, ε] (never an overlapping state).
pub fn toi_conservative_advancement(
    a: &Shape,
    motion_a: &Motion,
    b: &Shape,
    motion_b: &Motion,
    h: f64,
    options: &ToiOptions,
) -> Result<Option<Impact>, ToiError> {
    let probe = Probe {
        a,
        motion_a,
        b,
        motion_b,
    };
    validate([motion_a, motion_b], h, options)?;
    let touch = advance(&probe, h, options)?;
    Ok(touch.map(|(time, p, iterations)| probe.impact(time, &p, options.tolerance, iterations)))
}

/// The time of [`toi_conservative_advancement`]'s impact (s), the same
/// bits, without its manifold: what the soft step's continuous sweeps
/// read (they discard the manifold, whose clipping costs as much as the
/// distance it follows). A pair certainly within ε at the start
/// (`surely_within`: a core vertex of one within ε, less a rounding
/// slack, of the other) is at t = 0 without its exact distance, which
/// would be within ε too.
pub(crate) fn toi_time_conservative_advancement(
    a: &Shape,
    motion_a: &Motion,
    b: &Shape,
    motion_b: &Motion,
    h: f64,
    options: &ToiOptions,
) -> Result<Option<f64>, ToiError> {
    validate([motion_a, motion_b], h, options)?;
    let (start_a, start_b) = (motion_a.pose_at(0.0), motion_b.pose_at(0.0));
    if surely_within(a, &start_a, b, &start_b, options.tolerance) {
        return Ok(Some(0.0));
    }
    let probe = Probe {
        a,
        motion_a,
        b,
        motion_b,
    };
    Ok(advance(&probe, h, options)?.map(|(time, _, _)| time))
}

/// Conservative advancement of `probe`'s pair over [0, h] (the inputs
/// validated): the time reached (s), the proximity there and the
/// iterations spent, or `None` if the pair stays farther apart than ε
/// (see [`toi_conservative_advancement`]).
fn advance(
    probe: &Probe<'_>,
    h: f64,
    options: &ToiOptions,
) -> Result<Option<(f64, Proximity, usize)>, ToiError> {
    let (a, motion_a, b, motion_b) = (probe.a, probe.motion_a, probe.b, probe.motion_b);
    let eps = options.tolerance;
    // A shape that does not turn adds nothing (its radius is not needed:
    // |ω| r = +0 for a finite r ≥ 0, and a + 0 = a).
    let turning = |m: &Motion, s: &Shape| {
        let w = m.angular_velocity.abs();
        if w == 0.0 {
            0.0
        } else {
            w * s.rotation_radius()
        }
    };
    let angular = turning(motion_a, a) + turning(motion_b, b);
    let relative = motion_b.linear_velocity - motion_a.linear_velocity;
    let mut t = 0.0;
    let mut p = probe.proximity(t);
    for iteration in 0..=options.max_iterations {
        if p.distance <= eps {
            return Ok(Some((t, p, iteration)));
        }
        let bound = relative.dot(&p.normal).abs() + angular;
        if bound.is_nan() || bound <= 0.0 {
            return Ok(None);
        }
        let next = t + p.distance / bound;
        if next > h {
            return Ok(None);
        }
        if next == t {
            break;
        }
        t = next;
        p = probe.proximity(t);
    }
    Err(ToiError::NoConvergence {
        method: "conservative advancement",
        iterations: options.max_iterations,
        time: t,
        separation: p.distance,
    })
}

/// Time of impact by conservative advancement of shape `a` (moving with
/// `motion_a`) against one solid segment of a chain held still at
/// `chain_pose` (its body's pose), one-sided as Box2D's continuous
/// collision reads chain segments (`b2ContinuousQueryCallback`): the pair
/// is swept only when the moving body's origin (its centre of mass)
/// starts on the segment's solid side or on its line and ends on its line
/// or behind it, having moved across it. A body that comes from behind,
/// stays in front, or slides along the line is left alone: its
/// speculative contacts act, and a one-sided ground cannot catch what
/// passes it from below. Otherwise as [`toi_conservative_advancement`]
/// against the segment (a core of its two points, radius 0).
pub fn toi_chain_segment(
    a: &Shape,
    motion_a: &Motion,
    segment: &ChainSegment,
    chain_pose: &Isometry2<f64>,
    h: f64,
    options: &ToiOptions,
) -> Result<Option<Impact>, ToiError> {
    let sweep = toi_conservative_advancement;
    across_segment(a, motion_a, segment, chain_pose, h, options, sweep)
}

/// The time of [`toi_chain_segment`]'s impact (s), the same bits, without
/// its manifold (as [`toi_time_conservative_advancement`]).
pub(crate) fn toi_time_chain_segment(
    a: &Shape,
    motion_a: &Motion,
    segment: &ChainSegment,
    chain_pose: &Isometry2<f64>,
    h: f64,
    options: &ToiOptions,
) -> Result<Option<f64>, ToiError> {
    let sweep = toi_time_conservative_advancement;
    across_segment(a, motion_a, segment, chain_pose, h, options, sweep)
}

/// A conservative-advancement sweep of shape A (moving) against shape B
/// (moving) over [0, h], with what it gives: the impact or its time.
type Sweep<T> =
    fn(&Shape, &Motion, &Shape, &Motion, f64, &ToiOptions) -> Result<Option<T>, ToiError>;

/// A sweep of the conservative advancement (`sweep`: with or without the
/// manifold) of `a` against the segment held still at `chain_pose`, when
/// `a`'s origin crosses it from its solid side ([`toi_chain_segment`]).
fn across_segment<T>(
    a: &Shape,
    motion_a: &Motion,
    segment: &ChainSegment,
    chain_pose: &Isometry2<f64>,
    h: f64,
    options: &ToiOptions,
    sweep: Sweep<T>,
) -> Result<Option<T>, ToiError> {
    match crossing_segment(motion_a, segment, chain_pose, h, options)? {
        Some(line) => sweep(a, motion_a, &line, &Motion::fixed(*chain_pose), h, options),
        None => Ok(None),
    }
}

/// The segment as a shape (a core of its two points, radius 0) when the
/// origin of the body moving with `motion_a` crosses it from its solid side over [0, h] (see
/// [`toi_chain_segment`]), else `None`.
fn crossing_segment(
    motion_a: &Motion,
    segment: &ChainSegment,
    chain_pose: &Isometry2<f64>,
    h: f64,
    options: &ToiOptions,
) -> Result<Option<Shape>, ToiError> {
    validate([motion_a, &Motion::fixed(*chain_pose)], h, options)?;
    let p1 = chain_pose * Point2::from(segment.point1);
    let p2 = chain_pose * Point2::from(segment.point2);
    let e = p2 - p1;
    let c1 = motion_a.pose.translation.vector;
    let c2 = motion_a.pose_at(h).translation.vector;
    // > 0 in front of the segment (on its right, the solid side).
    let offset1 = cross(c1 - p1.coords, e);
    let offset2 = cross(c2 - p1.coords, e);
    if offset1 < 0.0 || offset2 > 0.0 || offset1 == offset2 {
        return Ok(None);
    }
    let line = Shape::segment(segment.point1, segment.point2)
        .expect("a chain's consecutive points are at least 5 mm apart (Chain::new)");
    Ok(Some(line))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::Circle;

    fn unit_box() -> Shape {
        Shape::rectangle(1.0, 1.0).unwrap()
    }

    type Toi =
        fn(&Shape, &Motion, &Shape, &Motion, f64, &ToiOptions) -> Result<Option<Impact>, ToiError>;
    const METHODS: [(&str, Toi); 2] = [
        ("bisection", toi_bisection),
        ("conservative advancement", toi_conservative_advancement),
    ];

    /// docs/cases.md case III: a 1 m box at x = −3 moving at +1 m/s toward a
    /// fixed 1 m box at the origin touches at t = 2.0 s.
    #[test]
    fn sliding_box_touches_at_two_seconds() {
        let moving = Motion::new(
            Isometry2::translation(-3.0, 0.0),
            Vector2::new(1.0, 0.0),
            0.0,
        );
        let fixed = Motion::fixed(Isometry2::identity());
        let options = ToiOptions::default();
        for (name, toi) in METHODS {
            let hit = toi(&unit_box(), &moving, &unit_box(), &fixed, 3.0, &options)
                .unwrap()
                .unwrap_or_else(|| panic!("{name} missed"));
            // Approach speed 1 m/s: time within ε / 1 m/s.
            assert!(
                (hit.time - 2.0).abs() <= options.tolerance,
                "{name}: {}",
                hit.time
            );
            assert!(hit.separation.abs() <= options.tolerance);
            // Face on face: two points at the corners of the contact face.
            let m = hit.manifold;
            assert!((m.normal - Vector2::x()).norm() < 1e-15, "{name}: {m:?}");
            assert_eq!(m.points().len(), 2, "{name}");
            for q in m.points() {
                assert!((q.point.x + 0.5).abs() < 1e-9 && (q.point.y.abs() - 0.5).abs() < 1e-12);
                assert!(q.depth.abs() <= options.tolerance);
            }
        }
    }

    /// The first root of t + (|cos t| + |sin t|)/2 = 2.5: the rotating box's
    /// extent along x, (|cos θ| + |sin θ|)/2, reaches the face at x = −0.5.
    fn rotating_box_contact_time() -> f64 {
        let f = |t: f64| t + 0.5 * (t.cos().abs() + t.sin().abs()) - 2.5;
        let (mut lo, mut hi) = (1.5, 2.0);
        assert!(f(lo) < 0.0 && f(hi) > 0.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if f(mid) > 0.0 { hi = mid } else { lo = mid }
        }
        lo
    }

    /// docs/cases.md case III: the same with ω = 1 rad/s on the moving box
    /// touches at 1.8736370117 s (parry2d's nonlinear cast).
    #[test]
    fn sliding_and_spinning_box_touches_at_1_8736370117() {
        let exact = rotating_box_contact_time();
        assert!((exact - 1.8736370117).abs() < 1e-10, "{exact}");
        let moving = Motion::new(
            Isometry2::translation(-3.0, 0.0),
            Vector2::new(1.0, 0.0),
            1.0,
        );
        let fixed = Motion::fixed(Isometry2::identity());
        let options = ToiOptions::default();
        for (name, toi) in METHODS {
            let hit = toi(&unit_box(), &moving, &unit_box(), &fixed, 3.0, &options)
                .unwrap()
                .unwrap_or_else(|| panic!("{name} missed"));
            assert!(
                (hit.time - 1.8736370117).abs() < 1e-6,
                "{name}: {}",
                hit.time
            );
            assert!(
                (hit.time - exact).abs() < 2.0 * options.tolerance,
                "{name}: {}",
                hit.time
            );
            // A corner of the spinning box on the fixed box's left face.
            let m = hit.manifold;
            assert_eq!(m.points().len(), 1, "{name}: {m:?}");
            assert!((m.normal - Vector2::x()).norm() < 1e-12, "{name}: {m:?}");
            assert!((m.points()[0].point.x + 0.5).abs() < 1e-9);
        }
    }

    #[test]
    fn circles_meet_when_their_centres_are_a_diameter_apart() {
        // |(−3 + 2t, 0.6)| = 1 at t = 1.1 s, approach speed 2·0.8 m/s; the
        // step ends at 1.5 s with the balls overlapping (at 2 s they would
        // have grazed past each other, which bisection cannot see).
        let ball = Shape::Circle(Circle::new(0.5).unwrap());
        let moving = Motion::new(
            Isometry2::translation(-3.0, 0.6),
            Vector2::new(2.0, 0.0),
            5.0,
        );
        let fixed = Motion::fixed(Isometry2::identity());
        for (name, toi) in METHODS {
            let hit = toi(&ball, &moving, &ball, &fixed, 1.5, &ToiOptions::default())
                .unwrap()
                .unwrap();
            assert!((hit.time - 1.1).abs() < 1e-9, "{name}: {}", hit.time);
            assert!(
                (hit.manifold.normal - Vector2::new(0.8, -0.6)).norm() < 1e-9,
                "{name}"
            );
        }
    }

    #[test]
    fn bisection_misses_a_pass_through_that_advancement_catches() {
        // A 0.1 m box at 100 m/s crosses a thin wall within one 0.1 s step:
        // the end states are both separated (seed Fig. 7.8 sees nothing).
        let bullet = Shape::rectangle(0.1, 0.1).unwrap();
        let wall = Shape::rectangle(0.02, 2.0).unwrap();
        let moving = Motion::new(
            Isometry2::translation(-5.0, 0.0),
            Vector2::new(100.0, 0.0),
            0.0,
        );
        let fixed = Motion::fixed(Isometry2::identity());
        let options = ToiOptions::default();
        assert_eq!(
            toi_bisection(&bullet, &moving, &wall, &fixed, 0.1, &options),
            Ok(None)
        );
        let hit = toi_conservative_advancement(&bullet, &moving, &wall, &fixed, 0.1, &options)
            .unwrap()
            .unwrap();
        // Gap 5 − 0.05 − 0.01 = 4.94 m at 100 m/s.
        assert!((hit.time - 0.0494).abs() < 1e-11, "{}", hit.time);
    }

    #[test]
    fn receding_or_overlapping_pairs() {
        let fixed = Motion::fixed(Isometry2::identity());
        let away = Motion::new(
            Isometry2::translation(-3.0, 0.0),
            Vector2::new(-1.0, 0.0),
            2.0,
        );
        let inside = Motion::new(
            Isometry2::translation(-0.8, 0.0),
            Vector2::new(1.0, 0.0),
            0.0,
        );
        for (name, toi) in METHODS {
            let o = ToiOptions::default();
            assert_eq!(
                toi(&unit_box(), &away, &unit_box(), &fixed, 1.0, &o),
                Ok(None),
                "{name}"
            );
            let hit = toi(&unit_box(), &inside, &unit_box(), &fixed, 1.0, &o)
                .unwrap()
                .unwrap();
            assert_eq!(hit.time, 0.0, "{name}");
            assert!((hit.separation + 0.2).abs() < 1e-15, "{name}");
            assert!((hit.manifold.max_depth() - 0.2).abs() < 1e-15, "{name}");
        }
    }

    #[test]
    fn bad_inputs_are_typed_errors() {
        let fixed = Motion::fixed(Isometry2::identity());
        let nan = Motion::new(Isometry2::identity(), Vector2::new(f64::NAN, 0.0), 0.0);
        let o = ToiOptions::default();
        for (_, toi) in METHODS {
            assert!(matches!(
                toi(&unit_box(), &fixed, &unit_box(), &fixed, 0.0, &o),
                Err(ToiError::InvalidParameter { .. })
            ));
            assert!(matches!(
                toi(&unit_box(), &nan, &unit_box(), &fixed, 1.0, &o),
                Err(ToiError::InvalidParameter { .. })
            ));
            let zero = ToiOptions {
                tolerance: 0.0,
                ..o
            };
            assert!(toi(&unit_box(), &fixed, &unit_box(), &fixed, 1.0, &zero).is_err());
        }
    }

    #[test]
    fn conservative_advancement_reports_non_convergence() {
        // Spinning fast with a tiny budget of iterations.
        let moving = Motion::new(
            Isometry2::translation(-3.0, 0.0),
            Vector2::new(1.0, 0.0),
            50.0,
        );
        let fixed = Motion::fixed(Isometry2::identity());
        let o = ToiOptions {
            tolerance: 1e-12,
            max_iterations: 3,
        };
        let e = toi_conservative_advancement(&unit_box(), &moving, &unit_box(), &fixed, 3.0, &o);
        assert!(matches!(e, Err(ToiError::NoConvergence { .. })), "{e:?}");
    }

    /// A box and a capsule fired down at 300 m/s at a ground chain listed
    /// right to left (solid from above): in a step of 1/60 s each would
    /// travel 5 m, through the chain; the sweep stops both where they
    /// first touch it, within ε of the surface. Fired up from below, or
    /// moving along the chain, they are not swept.
    #[test]
    fn a_fast_box_or_capsule_stops_on_a_chain_from_its_solid_side() {
        let chain = crate::shape::Chain::new(
            vec![
                Vector2::new(11.0, 0.0),
                Vector2::new(10.0, 0.0),
                Vector2::new(-10.0, 0.0),
                Vector2::new(-11.0, 0.0),
            ],
            false,
        )
        .unwrap();
        let segment = chain.segment(0).unwrap();
        let ground = Isometry2::identity();
        let options = ToiOptions::default();
        let h = 1.0 / 60.0;
        let speed = 300.0; // m/s
        // Box: 1 m tall, its bottom 0.5 m under its centre; capsule lying
        // flat, radius 0.25 m.
        for (shape, half_height) in [
            (unit_box(), 0.5),
            (Shape::capsule(1.0, 0.25).unwrap(), 0.25),
        ] {
            let start_height = 2.0; // m, centre above the chain
            let down = Motion::new(
                Isometry2::translation(1.0, start_height),
                Vector2::new(0.0, -speed),
                0.0,
            );
            let hit = toi_chain_segment(&shape, &down, &segment, &ground, h, &options)
                .unwrap()
                .expect("the sweep catches the fast shape");
            // Touches when the centre is `half_height` above the chain:
            // at (2 − half_height) / 300 s, within ε / 300 m/s.
            // Advancement stops at a gap in [0, ε], so early by at most
            // ε / speed, plus a few roundings of the time (4 ulps).
            let exact = (start_height - half_height) / speed;
            let early = exact - hit.time;
            let rounding = 4.0 * f64::EPSILON * exact;
            assert!(early >= -rounding && early <= options.tolerance / speed + rounding);
            assert!(hit.separation >= 0.0 && hit.separation <= options.tolerance);
            // From below, the chain is not solid.
            let up = Motion::new(
                Isometry2::translation(1.0, -start_height),
                Vector2::new(0.0, speed),
                0.0,
            );
            assert!(
                toi_chain_segment(&shape, &up, &segment, &ground, h, &options)
                    .unwrap()
                    .is_none()
            );
            // Sliding fast along it, in front: left to the contacts.
            let along = Motion::new(
                Isometry2::translation(-5.0, 0.6),
                Vector2::new(speed, 0.0),
                0.0,
            );
            assert!(
                toi_chain_segment(&shape, &along, &segment, &ground, h, &options)
                    .unwrap()
                    .is_none()
            );
        }
    }

    /// The time-only sweeps give the bits of the full ones' impact times
    /// (the manifold aside, the same search), and the same misses and
    /// errors: a spinning capsule and box, a compound, a miss, a pair
    /// touching at the start, a bad step; a chain from its solid side, from
    /// below and along it.
    #[test]
    fn time_only_sweeps_give_the_full_sweeps_times() {
        let options = ToiOptions::default();
        let fixed = Motion::fixed(Isometry2::new(Vector2::new(0.3, -0.1), 0.2));
        let l_piece = Shape::Compound(
            crate::shape::Compound::new(vec![
                crate::shape::CompoundPart::new(Vector2::new(-0.5, 0.0), 0.0, unit_box()),
                crate::shape::CompoundPart::new(Vector2::new(0.5, 0.5), 0.1, unit_box()),
            ])
            .unwrap(),
        );
        let shapes = [unit_box(), Shape::capsule(1.0, 0.25).unwrap(), l_piece];
        let motions = [
            Motion::new(
                Isometry2::new(Vector2::new(-3.0, 0.2), 0.4),
                Vector2::new(2.0, 0.1),
                1.5,
            ),
            Motion::new(
                Isometry2::translation(-3.0, 0.0),
                Vector2::new(-1.0, 0.0),
                0.0,
            ),
            Motion::new(
                Isometry2::translation(0.0, 0.4),
                Vector2::new(1.0, 0.0),
                -0.7,
            ),
        ];
        // Hits inside the step, at its start, misses, errors.
        let mut kinds = [0; 4];
        for a in &shapes {
            for b in &shapes {
                for m in &motions {
                    for h in [3.0, -1.0] {
                        let full = toi_conservative_advancement(a, m, b, &fixed, h, &options);
                        let time = toi_time_conservative_advancement(a, m, b, &fixed, h, &options);
                        assert_eq!(time, full.map(|hit| hit.map(|i| i.time)));
                        kinds[match time {
                            Ok(Some(t)) if t > 0.0 => 0,
                            Ok(Some(_)) => 1,
                            Ok(None) => 2,
                            Err(_) => 3,
                        }] += 1;
                    }
                }
            }
        }
        assert!(kinds.iter().all(|&k| k > 0), "{kinds:?}");
        let chain = crate::shape::Chain::new(
            vec![
                Vector2::new(11.0, 0.0),
                Vector2::new(10.0, 0.0),
                Vector2::new(-10.0, 0.0),
                Vector2::new(-11.0, 0.0),
            ],
            false,
        )
        .unwrap();
        let segment = chain.segment(0).unwrap();
        let ground = Isometry2::new(Vector2::new(0.1, 0.0), 0.05);
        let mut chain_hits = 0;
        for velocity in [
            Vector2::new(0.5, -300.0),
            Vector2::new(0.0, 300.0),
            Vector2::<f64>::x(),
        ] {
            let y = -velocity.y.signum() * 2.0;
            let m = Motion::new(Isometry2::new(Vector2::new(1.0, y), 0.3), velocity, 2.0);
            for shape in &shapes {
                let full = toi_chain_segment(shape, &m, &segment, &ground, 1.0 / 60.0, &options);
                let time =
                    toi_time_chain_segment(shape, &m, &segment, &ground, 1.0 / 60.0, &options);
                assert_eq!(time, full.map(|hit| hit.map(|i| i.time)));
                chain_hits += usize::from(matches!(time, Ok(Some(t)) if t > 0.0));
            }
        }
        // Only the fall from the solid side is swept: one hit per shape.
        assert_eq!(chain_hits, shapes.len());
    }
}
