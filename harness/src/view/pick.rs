//! Which body is under the cursor: the last dynamic body (drawn on top)
//! whose shape contains the point, or whose centre is within the pick
//! tolerance for a particle.

use super::frame::BodyLook;
use engine::{BodyKind, BodyState};
use nalgebra::{Rotation2, Vector2};

/// The id of the dynamic body under world point `p` (m); a particle counts
/// when `p` is within `tolerance` (m) of it. `None` when there is none.
pub fn body_at(
    looks: &[BodyLook],
    states: &[BodyState],
    removed: &[bool],
    p: Vector2<f64>,
    tolerance: f64,
) -> Option<usize> {
    (0..looks.len()).rev().find(|&id| {
        let look = &looks[id];
        if look.kind != BodyKind::Dynamic || removed.get(id).copied().unwrap_or(false) {
            return false;
        }
        let state = &states[id];
        let local = Rotation2::new(-state.angle) * (p - state.position);
        if look.is_particle() {
            return local.norm() <= tolerance;
        }
        if local.norm() > look.radius + tolerance {
            return false;
        }
        look.circles.iter().any(|(c, r)| (local - c).norm() <= *r)
            || look.polygons.iter().any(|poly| contains(poly, local))
    })
}

/// Whether the counter-clockwise convex polygon `poly` contains `q`.
fn contains(poly: &[Vector2<f64>], q: Vector2<f64>) -> bool {
    (0..poly.len()).all(|i| {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let (e, d) = (b - a, q - a);
        e.x * d.y - e.y * d.x >= 0.0
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use engine::{Body, BodyDef, Shape};

    #[test]
    fn a_point_inside_a_turned_box_picks_it_and_one_outside_does_not() {
        let def = BodyDef::rigid("b", 1.0, Shape::rectangle(2.0, 0.5).unwrap())
            .with_position(Vector2::new(3.0, 1.0))
            .with_rotation(std::f64::consts::FRAC_PI_2, 0.0);
        let (body, state) = Body::from_def(&def).unwrap();
        let looks = [BodyLook::of(&body, 0)];
        // Turned by 90°: 0.5 m wide in x, 2 m tall in y.
        let at = |x, y| body_at(&looks, &[state], &[false], Vector2::new(x, y), 0.0);
        assert_eq!(at(3.0, 1.9), Some(0));
        assert_eq!(at(3.4, 1.0), None);
    }
}
