//! The `chain` generator: `count` box links of `link_length` pivot to
//! pivot, jointed end to end by revolute joints, the first link's free end
//! jointed to the world at `start`; with `end`, the last link's free end
//! jointed to the world there (the chain hangs between two anchors), else
//! the chain is laid from `start` along `direction` and its far end is
//! free (it hangs from one anchor).
//!
//! Between two anchors the chain must be at least as long as the gap; a
//! slack chain starts as a "V": the first ⌊count/2⌋ links in a straight
//! line from `start` to a vertex below the anchors, the others from there
//! to `end` (the vertex found as the intersection of the two circles of
//! those lengths). Adjacent links do not collide (their joint keeps them
//! apart); links further apart do.

use crate::build::{Checked, positive, xy};
use crate::error::{ErrorKind, FieldPath, Problem};
use crate::format::Xy;
use crate::generate::generated_body;
use engine::error::readable;
use engine::{BodyDef, BodyId, BodyState, JointDef, Revolute, Shape};
use nalgebra::Vector2;

/// What a chain generator asks for, as written.
pub(crate) struct ChainSpec<'s> {
    pub(crate) count: usize,
    pub(crate) link_length: f64,
    pub(crate) link_width: Option<f64>,
    pub(crate) start: &'s Xy,
    pub(crate) end: Option<&'s Xy>,
    pub(crate) direction: Option<&'s Xy>,
}

/// The pivots p_0 … p_count of a chain, m.
fn pivots(path: &FieldPath, spec: &ChainSpec<'_>, length: f64) -> Checked<Vec<Vector2<f64>>> {
    let n = spec.count;
    let start = xy(&path.key("start"), spec.start)?;
    let Some(end) = spec.end else {
        let u = match spec.direction {
            None => Vector2::new(0.0, -1.0),
            Some(d) => {
                let d = xy(&path.key("direction"), d)?;
                let norm = d.norm();
                if norm == 0.0 || !(d / norm).iter().all(|c| c.is_finite()) {
                    return Err(Problem::new(
                        &path.key("direction"),
                        ErrorKind::InvalidValue,
                        "the direction has no direction: give a non-zero vector",
                    ));
                }
                d / norm
            }
        };
        return Ok((0..=n).map(|k| start + (k as f64 * length) * u).collect());
    };
    if spec.direction.is_some() {
        return Err(Problem::new(
            &path.key("direction"),
            ErrorKind::InvalidValue,
            "a chain between `start` and `end` takes no `direction`: remove one of them",
        ));
    }
    let end = xy(&path.key("end"), end)?;
    let gap = (end - start).norm();
    let total = n as f64 * length;
    if gap <= 1e-9 {
        return Err(Problem::new(
            &path.key("end"),
            ErrorKind::InvalidValue,
            "`end` is `start`: give two different anchors, or no `end`",
        ));
    }
    let slack = 1e-9 * total.max(gap);
    if total < gap - slack {
        return Err(Problem::new(
            &path.key("end"),
            ErrorKind::InvalidValue,
            format!(
                "the chain, {n} links of {} m = {} m, is shorter than the {} m from start to end: add links or lengthen them",
                readable(length),
                readable(total),
                readable(gap)
            ),
        ));
    }
    // The vertex: |V − start| = m L, |V − end| = (n − m) L.
    let m = n / 2;
    let (l1, l2) = (m as f64 * length, (n - m) as f64 * length);
    let u = (end - start) / gap;
    let along = (l1 * l1 - l2 * l2 + gap * gap) / (2.0 * gap);
    let across2 = l1 * l1 - along * along;
    if across2 < -slack * total {
        return Err(Problem::new(
            &path.key("count"),
            ErrorKind::InvalidValue,
            format!(
                "{n} links cannot reach from start to end {} m away: the two halves of the chain ({m} and {} links) differ by more than the gap; use an even count or a longer gap",
                readable(gap),
                n - m
            ),
        ));
    }
    let across = across2.max(0.0).sqrt();
    let normal = Vector2::new(-u.y, u.x);
    let base = start + along * u;
    let (v1, v2) = (base + across * normal, base - across * normal);
    // The vertex below (the chain sags); for a vertical gap, to the right.
    let vertex = if (v1.y - v2.y).abs() > 1e-12 * total {
        if v1.y < v2.y { v1 } else { v2 }
    } else if v1.x > v2.x {
        v1
    } else {
        v2
    };
    let mut points = Vec::with_capacity(n + 1);
    for k in 0..=n {
        let p = if k <= m {
            if m == 0 {
                start
            } else {
                start + (k as f64 / m as f64) * (vertex - start)
            }
        } else {
            vertex + ((k - m) as f64 / (n - m) as f64) * (end - vertex)
        };
        points.push(p);
    }
    Ok(points)
}

/// The links (in order from `start`) and their joints, the first link
/// being body `first` of the world.
pub(crate) fn expand(
    path: &FieldPath,
    spec: &ChainSpec<'_>,
    (prefix, first): (&str, BodyId),
    density: f64,
) -> Checked<(Vec<BodyDef>, Vec<JointDef>)> {
    let length = positive(
        &path.key("link_length"),
        spec.link_length,
        "link_length",
        "m",
    )?;
    let width = match spec.link_width {
        None => 0.25 * length,
        Some(w) => positive(&path.key("link_width"), w, "link_width", "m")?,
    };
    let points = pivots(path, spec, length)?;
    let box_shape = Shape::rectangle(length, width).map_err(|e| Problem::engine(path, e))?;
    let mut bodies = Vec::with_capacity(spec.count);
    let mut joints = Vec::with_capacity(spec.count + 1);
    for k in 0..spec.count {
        let (a, b) = (points[k], points[k + 1]);
        let d = b - a;
        bodies.push(generated_body(
            format!("{prefix}_{k}"),
            box_shape.clone(),
            (density, false),
            BodyState {
                position: 0.5 * (a + b),
                angle: d.y.atan2(d.x),
                velocity: Vector2::zeros(),
                angular_velocity: 0.0,
            },
        ));
        let before = (k > 0).then(|| first + k - 1);
        joints.push(JointDef::revolute(
            &format!("{prefix}_j{k}"),
            before,
            Some(first + k),
            a,
            Revolute::default(),
        ));
    }
    if spec.end.is_some() {
        joints.push(JointDef::revolute(
            &format!("{prefix}_j{}", spec.count),
            Some(first + spec.count - 1),
            None,
            points[spec.count],
            Revolute::default(),
        ));
    }
    Ok((bodies, joints))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec<'s>(count: usize, start: &'s Xy, end: Option<&'s Xy>) -> ChainSpec<'s> {
        ChainSpec {
            count,
            link_length: 0.5,
            link_width: None,
            start,
            end,
            direction: None,
        }
    }

    #[test]
    fn a_slack_chain_has_links_of_its_length_sagging_below_its_anchors() {
        let (start, end) = (Xy { x: -2.0, y: 5.0 }, Xy { x: 2.0, y: 5.0 });
        let path = FieldPath::root().key("generate").index(0);
        for count in [10, 11] {
            let points = pivots(&path, &spec(count, &start, Some(&end)), 0.5).unwrap();
            assert_eq!(points.len(), count + 1);
            assert_eq!(points[0], start.vector());
            assert!((points[count] - end.vector()).norm() < 1e-12);
            for w in points.windows(2) {
                assert!(((w[1] - w[0]).norm() - 0.5).abs() < 1e-12, "{w:?}");
            }
            assert!(points[count / 2].y < 5.0 - 1.0, "{:?}", points[count / 2]);
        }
        let (bodies, joints) = expand(&path, &spec(10, &start, Some(&end)), ("c", 3), 1.0).unwrap();
        assert_eq!((bodies.len(), joints.len()), (10, 11));
        assert_eq!((joints[0].body_a, joints[0].body_b), (None, Some(3)));
        assert_eq!((joints[10].body_a, joints[10].body_b), (Some(12), None));
    }

    #[test]
    fn a_chain_too_short_for_its_anchors_is_refused() {
        let (start, end) = (Xy { x: 0.0, y: 0.0 }, Xy { x: 6.0, y: 0.0 });
        let path = FieldPath::root().key("generate").index(1);
        let e = pivots(&path, &spec(10, &start, Some(&end)), 0.5).unwrap_err();
        assert_eq!(e.path.to_string(), "generate[1].end");
        assert!(e.message.contains("shorter"), "{}", e.message);
    }
}
