//! World ray casts in Box2D (`b2World_CastRayClosest` through boxdd's
//! `Query::cast_ray_closest`), for the query benchmark. Box2D casts a
//! segment (origin plus translation) in f32 through its broad-phase trees.

use super::{Box2dWorld, engine_error};
use crate::many_body::ManyBodyError;
use boxdd::{Position, QueryFilter};

impl Box2dWorld {
    /// Box2D's closest hit of the segment from `origin` to
    /// `origin + translation` (m), as the distance from the origin (m);
    /// `None` on a miss. Box2D skips shapes containing the origin.
    pub fn cast_ray_closest(
        &self,
        origin: [f64; 2],
        translation: [f64; 2],
    ) -> Result<Option<f64>, ManyBodyError> {
        let query = self.world.query().map_err(engine_error)?;
        let hit = query
            .cast_ray_closest(
                Position::new(
                    origin[0] as boxdd::WorldScalar,
                    origin[1] as boxdd::WorldScalar,
                ),
                [translation[0] as f32, translation[1] as f32],
                QueryFilter::default(),
            )
            .map_err(engine_error)?;
        let length = translation[0].hypot(translation[1]);
        Ok(hit.map(|h| f64::from(h.fraction) * length))
    }
}
