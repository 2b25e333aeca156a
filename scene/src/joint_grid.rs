//! The `joint_grid` generator: Box2D's `joint_grid` benchmark
//! (`shared/benchmarks.c`, `CreateJointGrid`): `columns` × `rows` circles
//! `spacing` apart, each joined to the circle above it and to the circle on
//! its left by a free revolute joint at the midpoint of their centres,
//! hanging from the `fixed` static circles in the middle of the top row.
//!
//! Layout, as Box2D's: column k (from 0, along +x) and row i (from 0,
//! along −y) at `origin` + (k, −i) × `spacing`; the bodies are built
//! column after column, top to bottom (body k · rows + i of the
//! generator, Box2D's creation order), and so are the joints: for each
//! circle, first its joint to the circle above (when i > 0), then its
//! joint to the circle on its left (when k > 0). The static circles are
//! those of the top row with ⌊columns/2⌋ − ⌊fixed/2⌋ ≤ k <
//! ⌊columns/2⌋ − ⌊fixed/2⌋ + fixed (Box2D's N/2 − 3 ≤ k ≤ N/2 + 3 for
//! 7). A joint between two static circles would hold nothing and is left
//! out (Box2D creates it). The circles never collide with each other
//! (they share one collision group, the id of the first circle: Box2D's
//! category 2 and mask ~2), only with the scene's other bodies.

use crate::build::{Checked, positive, xy};
use crate::error::{ErrorKind, FieldPath, Problem};
use crate::format::Xy;
use crate::generate::generated_body;
use engine::{BodyDef, BodyId, BodyState, JointDef, Revolute, Shape};
use nalgebra::Vector2;

/// Box2D's count of static circles in the top row.
pub(crate) const BOX2D_FIXED: usize = 7;

/// What a joint grid generator asks for, its counts checked.
pub(crate) struct JointGridSpec<'s> {
    pub(crate) columns: usize,
    pub(crate) rows: usize,
    pub(crate) radius: f64,
    pub(crate) spacing: f64,
    pub(crate) origin: &'s Xy,
    pub(crate) fixed: Option<i64>,
}

/// The static circles' first column and count, from `fixed` as written
/// (default Box2D's 7, or every column of a narrower grid).
fn fixed_columns(path: &FieldPath, columns: usize, fixed: Option<i64>) -> Checked<(usize, usize)> {
    let count = match fixed {
        None => BOX2D_FIXED.min(columns),
        Some(f) if f < 0 || f as u64 > columns as u64 => {
            return Err(Problem::new(
                &path.key("fixed"),
                ErrorKind::InvalidValue,
                format!(
                    "fixed is the number of static circles in the top row: from 0 to the {columns} columns, got {f}"
                ),
            ));
        }
        Some(f) => f as usize,
    };
    Ok((columns / 2 - count / 2, count))
}

/// The circles (column after column, top to bottom) and their joints, the
/// first circle being body `first` of the world.
pub(crate) fn expand(
    path: &FieldPath,
    spec: &JointGridSpec<'_>,
    (prefix, first): (&str, BodyId),
    density: f64,
) -> Checked<(Vec<BodyDef>, Vec<JointDef>)> {
    let radius = positive(&path.key("radius"), spec.radius, "radius", "m")?;
    let spacing = positive(&path.key("spacing"), spec.spacing, "spacing", "m")?;
    let origin = xy(&path.key("origin"), spec.origin)?;
    let (start, fixed) = fixed_columns(path, spec.columns, spec.fixed)?;
    let is_fixed = |k: usize, i: usize| i == 0 && (start..start + fixed).contains(&k);
    let circle = Shape::circle(radius).map_err(|e| Problem::engine(path, e))?;
    let (columns, rows) = (spec.columns, spec.rows);
    let group = u32::try_from(first).unwrap_or(u32::MAX);
    let mut bodies = Vec::with_capacity(columns * rows);
    let mut joints = Vec::with_capacity(2 * columns * rows);
    let at = |k: usize, i: usize| origin + spacing * Vector2::new(k as f64, -(i as f64));
    for k in 0..columns {
        for i in 0..rows {
            let index = k * rows + i;
            let fixed_here = is_fixed(k, i);
            bodies.push(
                generated_body(
                    format!("{prefix}_{index}"),
                    circle.clone(),
                    (density, fixed_here),
                    BodyState {
                        position: at(k, i),
                        ..BodyState::default()
                    },
                )
                .with_collision_group(group),
            );
            let mut join = |other: usize, other_fixed: bool, anchor: Vector2<f64>| {
                if fixed_here && other_fixed {
                    return;
                }
                joints.push(JointDef::revolute(
                    &format!("{prefix}_j{}", joints.len()),
                    Some(first + other),
                    Some(first + index),
                    anchor,
                    Revolute::default(),
                ));
            };
            let p = at(k, i);
            if i > 0 {
                join(
                    index - 1,
                    is_fixed(k, i - 1),
                    p + Vector2::new(0.0, 0.5 * spacing),
                );
            }
            if k > 0 {
                join(
                    index - rows,
                    is_fixed(k - 1, i),
                    p - Vector2::new(0.5 * spacing, 0.0),
                );
            }
        }
    }
    Ok((bodies, joints))
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::BodyKind;

    fn spec(columns: usize, rows: usize, fixed: Option<i64>) -> JointGridSpec<'static> {
        const ORIGIN: Xy = Xy { x: 0.0, y: 0.0 };
        JointGridSpec {
            columns,
            rows,
            radius: 0.4,
            spacing: 1.0,
            origin: &ORIGIN,
            fixed,
        }
    }

    #[test]
    fn the_grid_hangs_from_the_middle_of_its_top_row() {
        let path = FieldPath::root().key("generate").index(0);
        // 10 × 3: Box2D's fixed columns 5 − 3 … 5 + 3 of the top row.
        let (bodies, joints) = expand(&path, &spec(10, 3, None), ("g", 2), 1.0).unwrap();
        assert_eq!(bodies.len(), 30);
        let fixed: Vec<usize> = (0..30)
            .filter(|&b| bodies[b].kind == BodyKind::Static)
            .collect();
        assert_eq!(fixed, (2..=8).map(|k| 3 * k).collect::<Vec<_>>());
        // Every vertical (10 × 2) and horizontal (9 × 3) pair, less the 6
        // between neighbouring static circles.
        assert_eq!(joints.len(), 20 + 27 - 6);
        // Body 4 is column 1, row 1, at (1, −1): joined to the one above
        // (body 3) and to its left (body 1), at the midpoints.
        assert_eq!(bodies[4].state.position, Vector2::new(1.0, -1.0));
        let of = |b: usize| -> Vec<(Option<usize>, Vector2<f64>)> {
            joints
                .iter()
                .filter(|j| j.body_b == Some(2 + b))
                .map(|j| match j.anchor_a {
                    engine::Anchor::World(p) => (j.body_a, p),
                    engine::Anchor::Local(_) => panic!("world anchors"),
                })
                .collect()
        };
        assert_eq!(
            of(4),
            vec![
                (Some(2 + 3), Vector2::new(1.0, -0.5)),
                (Some(2 + 1), Vector2::new(0.5, -1.0))
            ]
        );
        assert!(bodies.iter().all(|b| b.collision_group() == Some(2)));
        // A narrow grid hangs from its whole top row by default; more
        // static circles than columns is refused at `fixed`.
        let (bodies, _) = expand(&path, &spec(3, 2, None), ("g", 0), 1.0).unwrap();
        assert_eq!(
            bodies.iter().filter(|b| b.kind == BodyKind::Static).count(),
            3
        );
        let e = expand(&path, &spec(3, 2, Some(4)), ("g", 0), 1.0).unwrap_err();
        assert_eq!(e.path.to_string(), "generate[0].fixed");
    }
}
