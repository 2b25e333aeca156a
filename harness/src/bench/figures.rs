//! The quality figures of a benchmark run, read from the final poses and
//! velocities the same way for every engine (and for this engine's
//! probe runs, [`super::quality_probe`]): the watched top body's sink and
//! sideways drift, the fastest dynamic body, the deepest overlap of any
//! pair that can collide (exact geometry), and in a scene with joints the
//! largest joint separation and limit excess. Each has a name, with its
//! unit, by which the targets and the probes find it.

use super::measure::BenchRow;
use references::many_body::{BodyKind, BodySample, JointState, ManyBodyScene};

/// The name of the top body's sink below its start (m).
pub const TOP_SINK: &str = "top sink (m)";
/// The name of the top body's sideways drift (m).
pub const TOP_DRIFT: &str = "top drift (m)";
/// The name of the largest dynamic body speed at the end (m/s).
pub const FASTEST_AT_END: &str = "fastest at the end (m/s)";
/// The name of the deepest overlap of a pair that can collide (m).
pub const DEEPEST_OVERLAP: &str = "deepest overlap (m)";
/// The name of the largest separation of a joint's anchors (m).
pub const JOINT_SEPARATION: &str = "largest joint separation (m)";
/// The name of the largest excess over a joint's limits (rad).
pub const LIMIT_EXCESS: &str = "largest limit excess (rad)";

/// One run's quality figures (lower is better for every one).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Figures {
    /// The top body's descent below its starting height (m), if watched.
    pub top_sink: Option<f64>,
    /// The top body's sideways drift from its starting position (m).
    pub top_drift: Option<f64>,
    /// The largest dynamic body speed (m/s).
    pub fastest_at_end: f64,
    /// The deepest overlap of any pair that can collide (m); 0 for none.
    pub deepest_overlap: f64,
    /// The largest separation of a joint's anchors (m); `None` without
    /// joints.
    pub joint_separation_max: Option<f64>,
    /// The largest excess of a joint's coordinate over its limits (rad for
    /// a revolute joint); `None` without joints.
    pub joint_limit_excess_max: Option<f64>,
}

impl Figures {
    /// The figures of `samples`, the final state of `neutral`'s bodies in
    /// their order, with body `top` watched.
    pub fn of(neutral: &ManyBodyScene, top: Option<usize>, samples: &[BodySample]) -> Self {
        let (top_sink, top_drift) = match top {
            Some(i) => {
                let start = neutral.bodies[i].position;
                let end = samples[i].position;
                (Some(start[1] - end[1]), Some((end[0] - start[0]).abs()))
            }
            None => (None, None),
        };
        let fastest_at_end = neutral
            .bodies
            .iter()
            .zip(samples)
            .filter(|(b, _)| b.kind == BodyKind::Dynamic)
            .map(|(_, s)| s.speed())
            .fold(0.0, f64::max);
        let deepest_overlap = neutral.deepest_overlap(samples).map_or(0.0, |o| o.depth);
        let joints = neutral.joint_states(samples);
        let largest = |f: fn(&JointState) -> f64| {
            (!joints.is_empty()).then(|| joints.iter().map(f).fold(0.0, f64::max))
        };
        Self {
            top_sink,
            top_drift,
            fastest_at_end,
            deepest_overlap,
            joint_separation_max: largest(|j| j.separation),
            joint_limit_excess_max: largest(|j| j.limit_violation),
        }
    }

    /// The figures a row carries.
    pub fn of_row(row: &BenchRow) -> Self {
        Self {
            top_sink: row.top_sink,
            top_drift: row.top_drift,
            fastest_at_end: row.fastest_at_end,
            deepest_overlap: row.deepest_overlap,
            joint_separation_max: row.joint_separation_max,
            joint_limit_excess_max: row.joint_limit_excess_max,
        }
    }

    /// The figures it has, by name, in the report's order.
    pub fn named(&self) -> Vec<(&'static str, f64)> {
        [
            (TOP_SINK, self.top_sink),
            (TOP_DRIFT, self.top_drift),
            (FASTEST_AT_END, Some(self.fastest_at_end)),
            (DEEPEST_OVERLAP, Some(self.deepest_overlap)),
            (JOINT_SEPARATION, self.joint_separation_max),
            (LIMIT_EXCESS, self.joint_limit_excess_max),
        ]
        .into_iter()
        .filter_map(|(name, x)| x.map(|x| (name, x)))
        .collect()
    }

    /// The figure named `name`, if it has it.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.named().into_iter().find(|f| f.0 == name).map(|f| f.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_figure_is_found_by_its_name_and_a_missing_one_is_absent() {
        let f = Figures {
            top_sink: None,
            top_drift: Some(0.25),
            fastest_at_end: 1.5,
            deepest_overlap: 0.125,
            joint_separation_max: None,
            joint_limit_excess_max: Some(0.5),
        };
        let names: Vec<&str> = f.named().iter().map(|n| n.0).collect();
        assert_eq!(
            names,
            [TOP_DRIFT, FASTEST_AT_END, DEEPEST_OVERLAP, LIMIT_EXCESS]
        );
        assert_eq!(f.get(DEEPEST_OVERLAP), Some(0.125));
        assert_eq!(f.get(TOP_SINK), None);
        assert_eq!(f.get(JOINT_SEPARATION), None);
    }
}
