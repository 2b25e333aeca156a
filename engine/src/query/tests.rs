//! World queries against brute force over every piece (the broad phase
//! must not lose a hit), the tree against the linear scan, and the input
//! errors.

use super::{RayHit, ShapeRef};
use crate::collision::convex::ConvexProxy;
use crate::collision::minkowski::{overlap, separation};
use crate::collision::ray::{contains, ray_cast};
use crate::collision::test_rng::Rng;
use crate::prelude::*;
use nalgebra::Isometry2;

/// A random circle, box or polygon (3 to 8 vertices) of size 0.2..2 m.
fn random_shape(rng: &mut Rng) -> Shape {
    match rng.int(0, 2) {
        0 => Shape::circle(rng.range(0.1, 1.0)).unwrap(),
        1 => Shape::rectangle(rng.range(0.2, 2.0), rng.range(0.2, 2.0)).unwrap(),
        _ => {
            let n = rng.int(3, 8);
            let points: Vec<Vector2<f64>> = (0..n)
                .map(|_| {
                    let a = rng.range(0.0, std::f64::consts::TAU);
                    let r = rng.range(0.3, 1.0);
                    Vector2::new(r * a.cos(), r * a.sin())
                })
                .collect();
            ConvexPolygon::convex_hull(&points)
                .map(Shape::Polygon)
                .unwrap_or_else(|_| Shape::circle(0.5).unwrap())
        }
    }
}

/// A world of `n` random bodies (dynamic, some static, one compound under
/// the soft step) in a 40 m square, no gravity.
fn random_world(seed: u64, n: usize, soft: bool) -> World {
    let mut rng = Rng::new(seed);
    let mut world = if soft {
        World::with_model(
            Method::SemiImplicitEuler,
            ContactModel::SoftStep(SoftStepSettings::default()),
        )
        .unwrap()
    } else {
        World::new(Method::SemiImplicitEuler).unwrap()
    };
    for k in 0..n {
        let position = Vector2::new(rng.range(-20.0, 20.0), rng.range(-20.0, 20.0));
        let angle = rng.range(-3.0, 3.0);
        let shape = if soft && k == 0 {
            Shape::Compound(Compound::hollow_box(2.0, 1.0, 0.2).unwrap())
        } else {
            random_shape(&mut rng)
        };
        let mut def = if rng.int(0, 3) == 0 {
            BodyDef::fixed(&format!("s{k}"), position, Some(shape))
        } else {
            BodyDef::rigid(&format!("d{k}"), 1.0, shape).with_position(position)
        };
        def.state.angle = angle;
        def.state.velocity = Vector2::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
        world.add_body(def).unwrap();
    }
    world
}

/// Every piece of the world with its proxy, by brute force.
fn pieces(world: &World) -> Vec<(ShapeRef, ConvexProxy)> {
    let mut out = Vec::new();
    for (body, b) in world.bodies().iter().enumerate() {
        let Some(shape) = &b.shape else { continue };
        let s = world.states()[body];
        for part in 0..crate::collision::convex::piece_count(shape) {
            let pose = Isometry2::new(s.position, s.angle);
            let proxy = crate::collision::convex::piece_proxy(shape, part, &pose).unwrap();
            out.push((ShapeRef { body, part }, proxy));
        }
    }
    out
}

fn brute_force_rays(world: &World, o: Vector2<f64>, d: Vector2<f64>, max: f64) -> Vec<RayHit> {
    let mut hits: Vec<RayHit> = pieces(world)
        .iter()
        .filter_map(|(s, p)| {
            ray_cast(p, o, d, max).map(|h| RayHit {
                shape: *s,
                distance: h.t,
                point: o + h.t * d,
                normal: h.normal,
            })
        })
        .collect();
    hits.sort_by(|a, b| {
        a.distance
            .total_cmp(&b.distance)
            .then(a.shape.cmp(&b.shape))
    });
    hits
}

/// Random rays, points and shapes against brute force, before and after
/// the bodies move (their fat boxes then changed in the trees).
fn check_against_brute_force(world: &World, rng: &mut Rng) {
    let all = QueryFilter::DEFAULT;
    for _ in 0..200 {
        let o = Vector2::new(rng.range(-25.0, 25.0), rng.range(-25.0, 25.0));
        let a = rng.range(0.0, std::f64::consts::TAU);
        let d = Vector2::new(a.cos(), a.sin());
        let max = rng.range(1.0, 60.0);
        // The queries normalize the direction: so does the oracle.
        let expected = brute_force_rays(world, o, 3.0 * d / (3.0 * d).norm(), max);
        assert_eq!(world.cast_ray_all(o, 3.0 * d, max, all).unwrap(), expected);
        assert_eq!(
            world.cast_ray(o, 3.0 * d, max, all).unwrap(),
            expected.first().copied()
        );

        let expected: Vec<ShapeRef> = pieces(world)
            .iter()
            .filter(|(_, p)| contains(p, o))
            .map(|(s, _)| *s)
            .collect();
        assert_eq!(world.shapes_at_point(o, all).unwrap(), expected);

        let shape = random_shape(rng);
        let pose = Isometry2::new(o, a);
        let query = ConvexProxy::of(&shape, &pose);
        let expected: Vec<ShapeRef> = pieces(world)
            .iter()
            .filter(|(_, p)| overlap(&query, p))
            .map(|(s, _)| *s)
            .collect();
        assert_eq!(world.overlap_shape(&shape, pose, all).unwrap(), expected);

        let nearest = pieces(world)
            .iter()
            .map(|(s, p)| (separation(&query, p).distance, *s))
            .filter(|(dist, _)| *dist <= 3.0)
            .min_by(|a, b| a.partial_cmp(b).unwrap());
        let found = world.closest_shape(&shape, pose, 3.0, all).unwrap();
        assert_eq!(found.map(|f| (f.distance, f.shape)), nearest);
    }
}

#[test]
fn queries_match_brute_force_under_the_soft_step() {
    let mut rng = Rng::new(0x5EED);
    let mut world = random_world(3, 120, true);
    check_against_brute_force(&world, &mut rng);
    world.run(0.5, 1.0 / 60.0).unwrap();
    check_against_brute_force(&world, &mut rng);
}

#[test]
fn the_linear_scan_matches_brute_force() {
    let mut rng = Rng::new(0x5CA7);
    let world = random_world(4, 60, false);
    check_against_brute_force(&world, &mut rng);
}

#[test]
fn shape_cast_stops_on_the_nearest_shape() {
    let mut world = World::new(Method::SemiImplicitEuler).unwrap();
    let wall = |x: f64| {
        BodyDef::fixed(
            "wall",
            Vector2::new(x, 0.0),
            Shape::rectangle(1.0, 4.0).ok(),
        )
    };
    let far = world.add_body(wall(10.0)).unwrap();
    let near = world.add_body(wall(5.0)).unwrap();
    let ball = Shape::circle(0.5).unwrap();
    let hit = world
        .cast_shape(
            &ball,
            Isometry2::translation(0.0, 1.0),
            Vector2::new(20.0, 0.0),
            QueryFilter::DEFAULT,
        )
        .unwrap()
        .unwrap();
    // The ball's edge (x = 0.5) meets the near wall's face (x = 4.5).
    assert_eq!(
        hit.shape,
        ShapeRef {
            body: near,
            part: 0
        }
    );
    assert_eq!(hit.fraction, 4.0 / 20.0);
    assert_eq!(hit.point, Vector2::new(4.5, 1.0));
    assert_eq!(hit.normal, Vector2::new(-1.0, 0.0));
    // From between the walls, leftwards: the near wall's other face.
    let hit = world
        .cast_shape(
            &ball,
            Isometry2::translation(7.5, 0.0),
            Vector2::new(-5.0, 0.0),
            QueryFilter::DEFAULT,
        )
        .unwrap()
        .unwrap();
    assert_eq!((hit.shape.body, hit.fraction), (near, 1.5 / 5.0));
    // A filter that accepts nothing sees nothing.
    let none = QueryFilter {
        category: 1,
        mask: 0,
    };
    assert!(
        world
            .cast_shape(&ball, Isometry2::identity(), Vector2::new(20.0, 0.0), none)
            .unwrap()
            .is_none()
    );
    assert!(
        world
            .overlap_aabb(
                Vector2::new(-100.0, -100.0),
                Vector2::new(100.0, 100.0),
                none
            )
            .unwrap()
            .is_empty()
    );
    let boxed = world
        .overlap_aabb(
            Vector2::new(9.4, -0.1),
            Vector2::new(9.6, 0.1),
            QueryFilter::DEFAULT,
        )
        .unwrap();
    assert_eq!(boxed, vec![ShapeRef { body: far, part: 0 }]);
}

#[test]
fn bad_query_inputs_are_refused() {
    let world = random_world(5, 5, true);
    let all = QueryFilter::DEFAULT;
    let o = Vector2::zeros();
    assert!(world.cast_ray(o, Vector2::zeros(), 1.0, all).is_err());
    assert!(
        world
            .cast_ray(Vector2::new(f64::NAN, 0.0), Vector2::x(), 1.0, all)
            .is_err()
    );
    assert!(world.cast_ray(o, Vector2::x(), -1.0, all).is_err());
    assert!(world.cast_ray(o, Vector2::x(), f64::NAN, all).is_err());
    assert!(world.cast_ray(o, Vector2::x(), f64::INFINITY, all).is_ok());
    let ball = Shape::circle(1.0).unwrap();
    let bad_pose = Isometry2::new(Vector2::new(f64::INFINITY, 0.0), 0.0);
    assert!(world.overlap_shape(&ball, bad_pose, all).is_err());
    assert!(
        world
            .cast_shape(
                &ball,
                Isometry2::identity(),
                Vector2::new(f64::NAN, 0.0),
                all
            )
            .is_err()
    );
    assert!(
        world
            .closest_shape(&ball, Isometry2::identity(), f64::INFINITY, all)
            .is_err()
    );
    assert!(
        world
            .overlap_aabb(Vector2::new(1.0, 0.0), Vector2::new(0.0, 1.0), all)
            .is_err()
    );
    assert!(
        world
            .shapes_at_point(Vector2::new(0.0, f64::NAN), all)
            .is_err()
    );
}

/// A query sees a shape by that shape's own filter: a body's, or a
/// compound part's where the part sets one (filters are a soft-step
/// feature: the exact model refuses them at `add_body`).
#[test]
fn queries_read_each_shapes_own_filter() {
    {
        let soft = true;
        let mut world = World::with_model(
            Method::SemiImplicitEuler,
            ContactModel::SoftStep(SoftStepSettings::default()),
        )
        .unwrap();
        // A wall in category 2 at x = 5, and a compound at x = 10 whose
        // only part is in category 4.
        let wall = world
            .add_body(
                BodyDef::fixed(
                    "wall",
                    Vector2::new(5.0, 0.0),
                    Some(Shape::rectangle(1.0, 4.0).unwrap()),
                )
                .with_filter(Filter {
                    category: 2,
                    ..Filter::DEFAULT
                }),
            )
            .unwrap();
        let part = CompoundPart::new(Vector2::zeros(), 0.0, Shape::rectangle(1.0, 4.0).unwrap())
            .with_overrides(ShapeOverrides {
                filter: Some(Filter {
                    category: 4,
                    ..Filter::DEFAULT
                }),
                ..ShapeOverrides::default()
            });
        let far = world
            .add_body(BodyDef::fixed(
                "far",
                Vector2::new(10.0, 0.0),
                Some(Shape::Compound(Compound::new(vec![part]).unwrap())),
            ))
            .unwrap();
        let ray = |mask: u64| {
            world
                .cast_ray(
                    Vector2::zeros(),
                    Vector2::x(),
                    50.0,
                    QueryFilter {
                        category: u64::MAX,
                        mask,
                    },
                )
                .unwrap()
                .map(|h| h.shape.body)
        };
        assert_eq!(ray(u64::MAX), Some(wall), "soft = {soft}");
        assert_eq!(
            ray(4),
            Some(far),
            "the part's category 4, past the wall's 2; soft = {soft}"
        );
        assert_eq!(ray(1), None, "no shape is in category 1; soft = {soft}");
    }
}

/// A soft-step world with a ground chain listed right to left (solid from
/// above, one solid segment from (10, 0) to (−10, 0), its end points
/// ghosts) and a unit box at rest above it, centred at (0, 3).
fn chain_world() -> (World, BodyId, BodyId) {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap();
    let points = [[11.0, 0.0], [10.0, 0.0], [-10.0, 0.0], [-11.0, 0.0]]
        .iter()
        .map(|p| Vector2::new(p[0], p[1]))
        .collect();
    let chain = Shape::chain(points, false).unwrap();
    let ground = world
        .add_body(BodyDef::fixed("ground", Vector2::zeros(), Some(chain)))
        .unwrap();
    let square = Shape::rectangle(1.0, 1.0).unwrap();
    let box_id = world
        .add_body(BodyDef::fixed("box", Vector2::new(0.0, 3.0), Some(square)))
        .unwrap();
    (world, ground, box_id)
}

#[test]
fn a_ray_hits_a_chain_from_its_solid_side_only() {
    let (world, ground, box_id) = chain_world();
    let all = QueryFilter::DEFAULT;
    let segment = ShapeRef {
        body: ground,
        part: 0,
    };
    // From above (the solid side), straight down beside the box.
    let hit = world
        .cast_ray(Vector2::new(4.0, 5.0), -Vector2::y(), 100.0, all)
        .unwrap()
        .unwrap();
    assert_eq!(hit.shape, segment);
    assert_eq!((hit.distance, hit.normal), (5.0, Vector2::y()));
    // From below (behind): the ray passes the chain and meets the box's
    // bottom face at y = 2.5.
    let hit = world
        .cast_ray(Vector2::new(0.0, -5.0), Vector2::y(), 100.0, all)
        .unwrap()
        .unwrap();
    assert_eq!(hit.shape.body, box_id);
    assert_eq!((hit.distance, hit.normal), (7.5, -Vector2::y()));
    let through = world
        .cast_ray_all(Vector2::new(0.0, -5.0), Vector2::y(), 100.0, all)
        .unwrap();
    assert_eq!(through.len(), 1);
    // Past the solid segment's end (over a ghost stretch): nothing.
    assert!(
        world
            .cast_ray(Vector2::new(10.5, 5.0), -Vector2::y(), 100.0, all)
            .unwrap()
            .is_none()
    );
}

#[test]
fn a_loop_listed_clockwise_is_hit_from_inside() {
    let mut world = World::with_model(
        Method::SemiImplicitEuler,
        ContactModel::SoftStep(SoftStepSettings::default()),
    )
    .unwrap();
    let points = [[-2.0, -2.0], [-2.0, 2.0], [2.0, 2.0], [2.0, -2.0]]
        .iter()
        .map(|p| Vector2::new(p[0], p[1]))
        .collect();
    let ring = world
        .add_body(BodyDef::fixed(
            "ring",
            Vector2::zeros(),
            Some(Shape::chain(points, true).unwrap()),
        ))
        .unwrap();
    let all = QueryFilter::DEFAULT;
    // From the centre towards +x: the right wall, segment 2 ((2, 2) to
    // (2, −2)), its normal pointing in.
    let hit = world
        .cast_ray(Vector2::zeros(), Vector2::x(), 10.0, all)
        .unwrap()
        .unwrap();
    assert_eq!(
        hit.shape,
        ShapeRef {
            body: ring,
            part: 2
        }
    );
    assert_eq!((hit.distance, hit.normal), (2.0, -Vector2::x()));
    // From outside on the right towards −x: through the right wall (seen
    // from behind), onto the left wall (segment 0) from inside.
    let hit = world
        .cast_ray(Vector2::new(5.0, 0.0), -Vector2::x(), 10.0, all)
        .unwrap()
        .unwrap();
    assert_eq!(
        hit.shape,
        ShapeRef {
            body: ring,
            part: 0
        }
    );
    assert_eq!((hit.distance, hit.normal), (7.0, Vector2::x()));
}

#[test]
fn shape_casts_overlaps_and_distances_see_chain_segments() {
    let (world, ground, _) = chain_world();
    let all = QueryFilter::DEFAULT;
    let segment = ShapeRef {
        body: ground,
        part: 0,
    };
    let ball = Shape::circle(0.5).unwrap();
    // A ball of radius 0.5 dropped from y = 5 beside the box touches the
    // chain after 4.5 m of a 10 m translation.
    let hit = world
        .cast_shape(
            &ball,
            Isometry2::translation(4.0, 5.0),
            Vector2::new(0.0, -10.0),
            all,
        )
        .unwrap()
        .unwrap();
    assert_eq!(hit.shape, segment);
    assert!((hit.fraction - 0.45).abs() < 1e-15, "{}", hit.fraction);
    assert_eq!(hit.normal, Vector2::y());
    // Nearest shape to a ball at (4, 3): the chain, 2.5 m away.
    let near = world
        .closest_shape(&ball, Isometry2::translation(4.0, 3.0), 10.0, all)
        .unwrap()
        .unwrap();
    assert_eq!(near.shape, segment);
    assert!((near.distance - 2.5).abs() < 1e-15);
    assert_eq!(near.normal, Vector2::y());
    // A box across the chain overlaps it; one above it does not.
    let across = world
        .overlap_aabb(Vector2::new(-1.0, -1.0), Vector2::new(1.0, 1.0), all)
        .unwrap();
    assert_eq!(across, vec![segment]);
    let above = world
        .overlap_aabb(Vector2::new(3.0, 0.1), Vector2::new(4.0, 1.0), all)
        .unwrap();
    assert!(above.is_empty());
    let overlapping = world
        .overlap_shape(&ball, Isometry2::translation(-3.0, 0.2), all)
        .unwrap();
    assert_eq!(overlapping, vec![segment]);
    // A point on the segment touches it; a point off it is in no shape.
    let on = world.shapes_at_point(Vector2::new(1.0, 0.0), all).unwrap();
    assert_eq!(on, vec![segment]);
    let off = world.shapes_at_point(Vector2::new(1.0, 0.5), all).unwrap();
    assert!(off.is_empty());
}
