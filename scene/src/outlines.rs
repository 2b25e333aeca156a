//! The concave polygons of a scene file and how many convex parts the
//! engine cut each into ([`engine::shape::decompose`]), for `simulate` to
//! say. Read from the file's own shapes, so a line is only ever about an
//! outline the file wrote.

use crate::format::{SceneFile, ShapeSpec};
use engine::shape::decompose::convex_parts;

/// A polygon of the scene file that is not convex, and its cut.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CutOutline {
    /// The body it belongs to.
    pub body: String,
    /// Where it is written (`bodies[3].shape`, `bodies[3].shape.parts[1].shape`).
    pub field: String,
    /// Its number of vertices.
    pub vertices: usize,
    /// The number of convex parts it became.
    pub parts: usize,
}

/// Every polygon of `file`'s bodies (alone or a compound's part) that
/// became more than one convex part, in file order. Outlines the engine
/// refuses are left out: a loaded scene has none.
pub fn cut_outlines(file: &SceneFile) -> Vec<CutOutline> {
    let mut out = Vec::new();
    for (i, body) in file.bodies.iter().enumerate() {
        if let Some(shape) = &body.shape {
            collect(&body.name, format!("bodies[{i}].shape"), shape, &mut out);
        }
    }
    out
}

fn collect(body: &str, field: String, shape: &ShapeSpec, out: &mut Vec<CutOutline>) {
    match shape {
        ShapeSpec::Polygon { vertices, .. } => {
            let points: Vec<_> = vertices.iter().map(|v| v.vector()).collect();
            if let Ok(parts) = convex_parts(&points) {
                if parts.len() > 1 {
                    out.push(CutOutline {
                        body: body.to_owned(),
                        field,
                        vertices: points.len(),
                        parts: parts.len(),
                    });
                }
            }
        }
        ShapeSpec::Compound { parts } => {
            for (k, part) in parts.iter().enumerate() {
                collect(body, format!("{field}.parts[{k}].shape"), &part.shape, out);
            }
        }
        ShapeSpec::Box { .. }
        | ShapeSpec::Circle { .. }
        | ShapeSpec::HollowBox { .. }
        | ShapeSpec::Chain { .. }
        | ShapeSpec::Capsule { .. }
        | ShapeSpec::Segment { .. } => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_l_inside_a_compound_is_named_with_its_two_parts() {
        let text = r#"
[simulation]
dt = 0.01
duration = 1.0

[[bodies]]
name = "piece"
density = 1.0
shape = { type = "compound", parts = [
  { shape = { type = "circle", radius = 0.5 } },
  { shape = { type = "polygon", vertices = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]] }, offset = [1, 0] },
] }
"#;
        let file: SceneFile = toml::from_str(text).unwrap();
        assert_eq!(
            cut_outlines(&file),
            vec![CutOutline {
                body: "piece".into(),
                field: "bodies[0].shape.parts[1].shape".into(),
                vertices: 6,
                parts: 2,
            }]
        );
    }
}
