//! Box2D-specific checks: the world settings the module documentation
//! claims, as Box2D reports them; the shapes as Box2D holds them; polygons
//! it cannot hold unchanged.

use super::*;
use crate::many_body::{SceneBody, pyramid};
use engine::{Circle, ConvexPolygon};
use nalgebra::Vector2;

/// One f32 rounding of a value of magnitude ≤ 1 (2⁻²⁴).
const EPS32: f64 = f32::EPSILON as f64 / 2.0;

#[test]
fn world_settings_are_box2d_defaults_with_sleeping_off_and_one_worker() {
    let w = Box2dWorld::new(&pyramid(2)).unwrap();
    let s = w.world_settings().unwrap();
    assert!(!s.sleeping);
    assert_eq!(s.workers, 1);
    assert!(s.continuous && s.warm_starting);
    // The defaults are f32 expressions of f32 constants (the recycle
    // distance is 10 × 0.005f): at most three roundings each.
    let close = |got: f64, want: f64| (got - want).abs() <= 3.0 * EPS32 * want;
    assert!(close(
        s.restitution_threshold,
        defaults::RESTITUTION_THRESHOLD
    ));
    assert!(close(
        s.maximum_linear_speed,
        defaults::MAXIMUM_LINEAR_SPEED
    ));
    assert!(close(
        s.contact_recycle_distance,
        defaults::CONTACT_RECYCLE_DISTANCE
    ));
    let text = w.configuration();
    for needle in [
        "30.000 Hz",
        "60.000 Hz",
        "3 m/s",
        "sleeping off",
        "one worker",
        "f32",
    ] {
        assert!(text.contains(needle), "{needle} missing from: {text}");
    }
}

#[test]
fn disabling_recycling_sets_the_distance_to_zero() {
    let mut w = Box2dWorld::new(&pyramid(1)).unwrap();
    w.disable_contact_recycling().unwrap();
    assert_eq!(w.world_settings().unwrap().contact_recycle_distance, 0.0);
}

#[test]
fn shapes_are_held_as_given_to_f32() {
    let mut scene = pyramid(0);
    let triangle = ConvexPolygon::new(vec![
        Vector2::new(0.0, 0.0),
        Vector2::new(1.2, 0.0),
        Vector2::new(0.0, 0.9),
    ])
    .unwrap()
    .centered();
    scene.bodies.push(SceneBody::dynamic(
        Shape::Circle(Circle::new(0.3).unwrap()),
        [0.0, 2.0],
        1.0,
    ));
    scene.bodies.push(SceneBody::dynamic(
        Shape::Polygon(triangle.clone()),
        [3.0, 2.0],
        1.0,
    ));
    let mut w = Box2dWorld::new(&scene).unwrap();
    match w.shape_geometry(1).unwrap() {
        ShapeGeometry::Circle { radius } => assert!((radius - 0.3).abs() <= EPS32 * 0.3),
        other => panic!("{other:?}"),
    }
    // The ground is b2MakeBox(100, 1): corners exactly ±100, ±1.
    match w.shape_geometry(0).unwrap() {
        ShapeGeometry::Polygon { vertices } => {
            assert_eq!(vertices.len(), 4);
            assert!(
                vertices
                    .iter()
                    .all(|v| v[0].abs() == 100.0 && v[1].abs() == 1.0)
            );
        }
        other => panic!("{other:?}"),
    }
    // The triangle: Box2D's hull may start at another vertex; every
    // vertex is one of ours rounded to f32 (coordinates ≤ 0.8 m).
    match w.shape_geometry(2).unwrap() {
        ShapeGeometry::Polygon { vertices } => {
            assert_eq!(vertices.len(), 3);
            for v in triangle.vertices() {
                let found = vertices
                    .iter()
                    .any(|q| (q[0] - v.x).abs() <= EPS32 && (q[1] - v.y).abs() <= EPS32);
                assert!(found, "{v:?} not in {vertices:?}");
            }
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_thin_card_is_held_as_box2ds_box_in_any_placement() {
    // Box2D's Card House card, 2 mm × 0.4 m (b2MakeBox(0.001, 0.2)),
    // given as vertices turned by 25°: about its centre on a dynamic body,
    // about an offset centre on a static one. No hull (which welds points
    // closer than 5 mm): b2MakeOffsetBox.
    let (hw, hh, angle) = (0.001, 0.2, 25f64.to_radians());
    let card = |centre: Vector2<f64>| {
        let (s, c) = angle.sin_cos();
        let corner = |x: f64, y: f64| centre + Vector2::new(c * x - s * y, s * x + c * y);
        ConvexPolygon::new(vec![
            corner(-hw, -hh),
            corner(hw, -hh),
            corner(hw, hh),
            corner(-hw, hh),
        ])
        .unwrap()
    };
    let centred = card(Vector2::zeros());
    let offset = card(Vector2::new(0.1, 0.05));
    let mut scene = pyramid(0);
    scene.bodies.push(SceneBody::dynamic(
        Shape::Polygon(centred.clone()),
        [0.0, 2.0],
        1.0,
    ));
    scene
        .bodies
        .push(SceneBody::fixed(Shape::Polygon(offset.clone()), [3.0, 2.0]));
    let mut w = Box2dWorld::new(&scene).unwrap();
    for (body, card) in [(1, &centred), (2, &offset)] {
        match w.shape_geometry(body).unwrap() {
            ShapeGeometry::Polygon { vertices } => {
                assert_eq!(vertices.len(), 4);
                // Box2D rotates its f32 half extents by its f32 rotation
                // and adds its f32 centre: a few roundings of coordinates
                // ≤ 0.3 m.
                for v in card.vertices() {
                    let found = vertices.iter().any(|q| {
                        (q[0] - v.x).abs() <= 4.0 * EPS32 && (q[1] - v.y).abs() <= 4.0 * EPS32
                    });
                    assert!(found, "body {body}: {v:?} not in {vertices:?}");
                }
            }
            other => panic!("{other:?}"),
        }
    }
    // A quadrilateral that is not a rectangle still goes through the hull.
    let kite = ConvexPolygon::new(vec![
        Vector2::new(0.0, -0.3),
        Vector2::new(0.2, 0.0),
        Vector2::new(0.0, 0.5),
        Vector2::new(-0.2, 0.0),
    ])
    .unwrap();
    assert!(rectangle(&kite).is_none());
    assert!(rectangle(&offset).is_some());
}

#[test]
fn polygons_box2d_would_change_are_refused() {
    let ring = |n: usize, r: f64| {
        let v = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                Vector2::new(r * a.cos(), r * a.sin())
            })
            .collect();
        Shape::Polygon(ConvexPolygon::new(v).unwrap())
    };
    let mut scene = pyramid(0);
    scene
        .bodies
        .push(SceneBody::dynamic(ring(9, 0.5), [0.0, 2.0], 1.0));
    let e = Box2dWorld::new(&scene).err().unwrap();
    assert!(
        e.to_string().contains("body 1") && e.to_string().contains("at most 8"),
        "{e}"
    );
    // Eight vertices 2 mm apart: Box2D welds points closer than 5 mm.
    scene.bodies[1].shape = ring(8, 0.0026);
    let e = Box2dWorld::new(&scene).err().unwrap();
    assert!(e.to_string().contains("0.005 m"), "{e}");
    // Eight well-spaced vertices are fine.
    scene.bodies[1].shape = ring(8, 0.5);
    assert!(Box2dWorld::new(&scene).is_ok());
}

#[test]
fn values_beyond_f32_are_refused() {
    let mut scene = pyramid(1);
    scene.bodies[1].position[0] = 1e39;
    let e = Box2dWorld::new(&scene).err().unwrap();
    assert!(e.to_string().contains("body 1: position x"), "{e}");
    scene.bodies[1].position[0] = 0.0;
    scene.bodies[1].density = 1e39;
    let e = Box2dWorld::new(&scene).err().unwrap();
    assert!(
        e.to_string().contains("body 1") && e.to_string().contains("mass"),
        "{e}"
    );
}

#[test]
fn scene_values_beyond_f32_are_refused_as_scene_values() {
    let mut scene = pyramid(1);
    scene.dt = 1e-50;
    let e = Box2dWorld::new(&scene).err().unwrap();
    assert!(e.to_string().starts_with("many-body scene: dt = "), "{e}");
    scene.dt = 1.0 / 60.0;
    scene.gravity[1] = -1e40;
    let e = Box2dWorld::new(&scene).err().unwrap();
    assert!(
        e.to_string().starts_with("many-body scene: gravity y"),
        "{e}"
    );
}

/// A static segment, a dynamic capsule and a dynamic rounded box are held
/// by Box2D. The capsule's mass and inertia are Box2D's own (its capsule
/// formula: rectangle plus two half discs, in f32), against the engine's
/// exact ones: about twenty f32 roundings of values of this size, so
/// 32·2⁻²⁴ relative. The rounded box gets the engine's mass data
/// explicitly (Box2D approximates a rounded polygon's): one f32 rounding.
#[test]
fn capsule_segment_and_rounded_box_are_held_with_their_mass() {
    let mut scene = pyramid(0);
    scene.bodies.push(SceneBody::fixed(
        Shape::segment(Vector2::new(-5.0, 3.0), Vector2::new(5.0, 3.0)).unwrap(),
        [0.0, 0.0],
    ));
    let capsule = Shape::capsule(1.0, 0.25).unwrap();
    let rounded = Shape::rounded_box(0.8, 0.4, 0.05).unwrap();
    scene
        .bodies
        .push(SceneBody::dynamic(capsule.clone(), [0.0, 5.0], 2.0));
    scene
        .bodies
        .push(SceneBody::dynamic(rounded.clone(), [2.0, 5.0], 2.0));
    let mut w = Box2dWorld::new(&scene).unwrap();
    let masses = w.mass_properties().unwrap();
    for (body, shape, roundings) in [(2, &capsule, 32.0), (3, &rounded, 2.0)] {
        let mass = 2.0 * shape.area();
        let inertia = mass * shape.inertia_per_unit_mass();
        let got = masses[body];
        assert!(
            (got.mass - mass).abs() <= roundings * EPS32 * mass,
            "{body}: {} vs {mass}",
            got.mass
        );
        assert!(
            (got.inertia - inertia).abs() <= roundings * EPS32 * inertia,
            "{body}: {} vs {inertia}",
            got.inertia
        );
    }
}
