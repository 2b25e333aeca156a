//! rapier-specific checks: the parameters the module documentation claims,
//! the colliders as rapier holds them.

use super::*;
use crate::many_body::{SceneBody, pyramid};
use engine::{Circle, ConvexPolygon};
use nalgebra::Vector2;
use rapier2d_f64::geometry::ShapeType;

#[test]
fn parameters_are_defaults_but_dt_and_substeps() {
    let mut scene = pyramid(2);
    scene.dt = 0.01;
    scene.substeps = 8;
    let w = RapierManyWorld::new(&scene).unwrap();
    let p = &w.world().integration_parameters;
    let d = IntegrationParameters::default();
    assert_eq!((p.dt, p.num_solver_iterations), (0.01, 8));
    assert_eq!(p.contact_softness, d.contact_softness);
    assert_eq!(p.static_contact_softness, d.static_contact_softness);
    assert_eq!(p.normalized_max_linear_velocity, 400.0);
    assert!(p.contact_recycling && !p.friction_in_bias_pass);
    for (_, rb) in w.world().bodies.iter() {
        // can_sleep(false) sets both sleep thresholds to −1 ("never").
        let a = rb.activation();
        assert!(a.normalized_linear_threshold < 0.0 && a.angular_threshold < 0.0);
    }
    let text = w.configuration();
    for needle in [
        "30 Hz",
        "60 Hz",
        "3 m/s",
        "sleeping off",
        "single thread",
        "f64",
    ] {
        assert!(text.contains(needle), "{needle} missing from: {text}");
    }
}

#[test]
fn colliders_have_the_scene_shapes_and_mixing_rules() {
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
    let w = RapierManyWorld::new(&scene).unwrap();
    let colliders: Vec<_> = w.world().colliders.iter().map(|(_, c)| c).collect();
    assert_eq!(colliders.len(), 3);
    for c in &colliders {
        assert_eq!(
            c.friction_combine_rule(),
            CoefficientCombineRule::GeometricMean
        );
        assert_eq!(c.restitution_combine_rule(), CoefficientCombineRule::Max);
    }
    let ground = colliders[0]
        .shape()
        .as_cuboid()
        .expect("the ground is a cuboid");
    assert_eq!((ground.half_extents.x, ground.half_extents.y), (100.0, 1.0));
    assert_eq!(colliders[1].shape().as_ball().map(|b| b.radius), Some(0.3));
    assert_eq!(colliders[2].shape().shape_type(), ShapeType::ConvexPolygon);
    let kept: Vec<[f64; 2]> = colliders[2]
        .shape()
        .as_convex_polygon()
        .unwrap()
        .points()
        .iter()
        .map(|p| [p.x, p.y])
        .collect();
    let given: Vec<[f64; 2]> = triangle.vertices().iter().map(|v| [v.x, v.y]).collect();
    assert_eq!(kept, given, "vertices kept exactly, in order");
}

/// A static segment and a dynamic capsule and rounded box are held by
/// rapier with the engine's exact mass and inertia, given explicitly
/// (parry's own: the core's for a round polygon, 1.9 % low for this
/// capsule's inertia, checked below): exact but for rapier's own
/// bookkeeping, a few f64 roundings, 1e-13 relative.
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
    let mut w = RapierManyWorld::new(&scene).unwrap();
    let masses = w.mass_properties().unwrap();
    // parry's capsule inertia, which the explicit one replaces: its half
    // discs' parallel-axis term is ρπr²(h²/4 + 3hr/8) where the exact one
    // is ρπr²(h²/4 + 4hr/3π), lower by ρπr²·h·r(4/3π − 3/8), ρ = 2.
    let parry = crate::parry_queries::to_parry_shape(&capsule).mass_properties(2.0);
    let exact = 2.0 * capsule.area() * capsule.inertia_per_unit_mass();
    let (h, r, pi) = (1.0, 0.25, std::f64::consts::PI);
    let shortfall = 2.0 * pi * r * r * h * r * (4.0 / (3.0 * pi) - 0.375);
    let parry_inertia = parry.principal_inertia();
    assert!(
        (exact - parry_inertia - shortfall).abs() <= 1e-13 * exact,
        "{parry_inertia} + {shortfall} vs {exact}"
    );
    for (body, shape) in [(2, &capsule), (3, &rounded)] {
        let mass = 2.0 * shape.area();
        let inertia = mass * shape.inertia_per_unit_mass();
        let got = masses[body];
        assert!(
            (got.mass - mass).abs() <= 1e-13 * mass,
            "{body}: {}",
            got.mass
        );
        assert!(
            (got.inertia - inertia).abs() <= 1e-13 * inertia,
            "{body}: {} vs {inertia}",
            got.inertia
        );
    }
}
