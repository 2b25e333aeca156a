//! World ray casts in rapier2d (`PhysicsWorld::cast_ray`: its query
//! pipeline over the BVH broad phase), for the query benchmark.

use super::RapierManyWorld;
use rapier2d_f64::math::Vector;
use rapier2d_f64::parry::query::Ray;

impl RapierManyWorld {
    /// rapier's closest hit of the ray from `origin` along the unit
    /// `direction` within `max_distance` (m), as the distance (m); `None`
    /// on a miss. Solid shapes: a ray starting inside one hits it at 0.
    pub fn cast_ray(
        &self,
        origin: [f64; 2],
        direction: [f64; 2],
        max_distance: f64,
    ) -> Option<f64> {
        let ray = Ray::new(
            Vector::new(origin[0], origin[1]),
            Vector::new(direction[0], direction[1]),
        );
        self.world
            .cast_ray(&ray, max_distance, true, Default::default())
            .map(|(_, distance)| distance)
    }
}
