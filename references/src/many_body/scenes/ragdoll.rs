//! Box2D v3.2's 11-bone ragdoll (`shared/human.c`, `CreateHuman`) and the
//! `rain` benchmark of ragdolls falling onto rows of tiles
//! (`shared/benchmarks.c`, `CreateRain`, `StepRain`).

use super::{BENCHMARK_DT, BENCHMARK_GRAVITY, BENCHMARK_SUBSTEPS};
use crate::many_body::{JointKind, ManyBodyScene, Motor, SceneBody, SceneJoint, Spring};
use engine::{Compound, CompoundPart, ConvexPolygon, Shape};
use nalgebra::Vector2;
use std::f64::consts::PI;

/// Number of bones (bodies) of a ragdoll.
pub const BONES: usize = 11;

/// Friction of the bones' shapes (`shapeDef.material.friction = 0.2f`).
pub const BONE_FRICTION: f64 = 0.2;

/// The ragdoll's parameters, as `CreateHuman` takes them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RagdollParams {
    /// Where the feet stand: the bones are placed relative to it, m.
    pub position: [f64; 2],
    /// Length scale s (1: 1.6 m tall).
    pub scale: f64,
    /// Joint friction torque before the per-bone friction scale, N·m
    /// (each joint's motor of speed 0 has maximum torque
    /// friction scale × `friction_torque` × s).
    pub friction_torque: f64,
    /// Joint spring frequency, Hz (0: no spring).
    pub hertz: f64,
    /// Joint spring damping ratio.
    pub damping_ratio: f64,
    /// Collision group of the bones (Box2D's group index −`group`): the
    /// bones of a ragdoll never collide with each other, nor with the
    /// bones of another ragdoll of the same group.
    pub group: u32,
}

impl RagdollParams {
    /// The ragdolls of Box2D's `rain` benchmark at `position` in `group`:
    /// scale 1, joint friction 0.05 N·m, springs 5 Hz with ζ = 0.5.
    pub fn rain(position: [f64; 2], group: u32) -> Self {
        Self {
            position,
            scale: 1.0,
            friction_torque: 0.05,
            hertz: 5.0,
            damping_ratio: 0.5,
            group,
        }
    }
}

/// One bone of `CreateHuman`: its parent, body origin (y above the feet),
/// capsule (segment end heights in the body and radius), pivot height,
/// joint limits (multiples of π), reference angle (rad) and friction scale;
/// lengths in units of the scale s.
struct Bone {
    parent: Option<usize>,
    y: f64,
    capsule: (f64, f64, f64),
    pivot: f64,
    limits: [f64; 2],
    reference: f64,
    friction_scale: f64,
    foot: bool,
}

/// `CreateHuman`'s bones in its order (hip, torso, head, upper and lower
/// left leg, upper and lower right leg, upper and lower left arm, upper and
/// lower right arm), values as in `human.c`.
const SKELETON: [Bone; BONES] = {
    const fn bone(
        parent: Option<usize>,
        y: f64,
        capsule: (f64, f64, f64),
        pivot: f64,
        limits: [f64; 2],
        friction_scale: f64,
    ) -> Bone {
        Bone {
            parent,
            y,
            capsule,
            pivot,
            limits,
            reference: 0.0,
            friction_scale,
            foot: false,
        }
    }
    [
        bone(None, 0.95, (-0.02, 0.02, 0.095), 0.0, [0.0, 0.0], 1.0),
        bone(Some(0), 1.2, (-0.135, 0.135, 0.09), 1.0, [-0.25, 0.0], 0.5),
        bone(
            Some(1),
            1.475,
            (-0.038, 0.039, 0.075),
            1.4,
            [-0.3, 0.1],
            0.25,
        ),
        bone(
            Some(0),
            0.775,
            (-0.125, 0.125, 0.06),
            0.9,
            [-0.05, 0.4],
            1.0,
        ),
        Bone {
            foot: true,
            ..bone(
                Some(3),
                0.475,
                (-0.155, 0.125, 0.045),
                0.625,
                [-0.5, -0.02],
                0.5,
            )
        },
        bone(
            Some(0),
            0.775,
            (-0.125, 0.125, 0.06),
            0.9,
            [-0.05, 0.4],
            1.0,
        ),
        Bone {
            foot: true,
            ..bone(
                Some(5),
                0.475,
                (-0.155, 0.125, 0.045),
                0.625,
                [-0.5, -0.02],
                0.5,
            )
        },
        bone(
            Some(1),
            1.225,
            (-0.125, 0.125, 0.035),
            1.35,
            [-0.1, 0.8],
            0.5,
        ),
        Bone {
            reference: 0.25 * PI,
            ..bone(Some(7), 0.975, (-0.125, 0.125, 0.03), 1.1, [-0.2, 0.3], 0.1)
        },
        bone(
            Some(1),
            1.225,
            (-0.125, 0.125, 0.035),
            1.35,
            [-0.1, 0.8],
            0.5,
        ),
        Bone {
            reference: 0.25 * PI,
            ..bone(Some(9), 0.975, (-0.125, 0.125, 0.03), 1.1, [-0.2, 0.3], 0.1)
        },
    ]
};

/// A capsule (the segment from (0, y1) to (0, y2), radius r) as the
/// convex octagon inscribed in it: each half-disc cap replaced by half a
/// regular hexagon (vertices at 0°, 60°, 120°, 180° about the cap's
/// centre). Box2D's polygons take at most 8 vertices; the octagon's area
/// is 2r(y2 − y1) + (3√3/2) r², against the capsule's 2r(y2 − y1) + π r².
fn capsule_octagon(y1: f64, y2: f64, r: f64) -> ConvexPolygon {
    let (c, s) = (0.5 * r, 0.5 * 3f64.sqrt() * r);
    ConvexPolygon::new(vec![
        Vector2::new(r, y1),
        Vector2::new(r, y2),
        Vector2::new(c, y2 + s),
        Vector2::new(-c, y2 + s),
        Vector2::new(-r, y2),
        Vector2::new(-r, y1),
        Vector2::new(-c, y1 - s),
        Vector2::new(c, y1 - s),
    ])
    .expect("a convex octagon")
}

/// Box2D's ragdoll (`CreateHuman`) as 11 bodies and 10 revolute joints,
/// appended to `bodies` and `joints` (the joints' body indices account for
/// the bodies already there). Returns the index of its first bone (the
/// hip).
///
/// As in `human.c`: bones are dynamic, at rest, angle 0, density 1 kg/m²,
/// friction 0.2, at the heights of `human.c` × s above `position`;
/// each bone but the hip is joined to its parent at its pivot by a
/// revolute joint with Box2D's limits (the lower arms' joint angle is
/// measured from a reference angle of π/4, so they start 0.05π below
/// their lower limit, as in Box2D), a motor of speed 0 and maximum torque
/// friction scale × `friction_torque` × s (joint friction), and a spring
/// of `hertz` and `damping_ratio` toward angle 0 when `hertz` > 0; the
/// bones of one ragdoll share `group` and never collide with each other.
///
/// Differences from Box2D's ragdoll, which this description cannot carry:
/// - capsules become inscribed octagons (each half-disc cap replaced by
///   half a regular hexagon, 8 vertices, Box2D's maximum): each bone
///   is lighter than Box2D's by the capsule caps' missing area
///   (π − 3√3/2) r², 10 % of the hip, 2–4 % of the limbs;
/// - the foot (a rounded quadrilateral of radius 0.015 s on the lower leg,
///   friction 0.05, colliding only with the ground) is its quadrilateral
///   without the rounding, part of the lower leg's compound shape: it has
///   the leg's friction 0.2 and collides with other ragdolls;
/// - no linear damping (Box2D gives the head and the lower arms 0.1 s⁻¹);
/// - each body's origin is its shape's centroid (the compounds and the
///   head's slightly off-centre capsule are re-centred), not Box2D's body
///   origin; the joints' anchors, in world coordinates, are unchanged.
pub fn ragdoll(
    params: &RagdollParams,
    bodies: &mut Vec<SceneBody>,
    joints: &mut Vec<SceneJoint>,
) -> usize {
    let s = params.scale;
    let [px, py] = params.position;
    let first = bodies.len();
    let foot = ConvexPolygon::convex_hull(&[
        Vector2::new(-0.03 * s, -0.185 * s),
        Vector2::new(0.11 * s, -0.185 * s),
        Vector2::new(0.11 * s, -0.16 * s),
        Vector2::new(-0.03 * s, -0.14 * s),
    ])
    .expect("a convex quadrilateral");
    for bone in &SKELETON {
        let (y1, y2, r) = bone.capsule;
        let leg = capsule_octagon(y1 * s, y2 * s, r * s);
        let shape = if bone.foot {
            let part =
                |p: ConvexPolygon| CompoundPart::new(Vector2::zeros(), 0.0, Shape::Polygon(p));
            Shape::Compound(Compound::new(vec![part(leg), part(foot.clone())]).expect("two parts"))
        } else {
            Shape::Polygon(leg)
        };
        let centroid = shape.frame_centroid().unwrap_or_else(Vector2::zeros);
        let origin = [px, py + bone.y * s];
        let mut body = SceneBody::dynamic(
            shape.centered(),
            [origin[0] + centroid.x, origin[1] + centroid.y],
            1.0,
        );
        body.friction = BONE_FRICTION;
        body.collision_group = Some(params.group);
        bodies.push(body);
        if let Some(parent) = bone.parent {
            let mut j = SceneJoint::revolute(
                Some(first + parent),
                Some(bodies.len() - 1),
                [px, py + bone.pivot * s],
                bone.reference,
            );
            if let JointKind::Revolute(rj) = &mut j.kind {
                rj.limits = Some([bone.limits[0] * PI, bone.limits[1] * PI]);
                rj.motor = Some(Motor {
                    speed: 0.0,
                    max_force: bone.friction_scale * params.friction_torque * s,
                });
                if params.hertz > 0.0 {
                    rj.spring = Some(Spring {
                        hertz: params.hertz,
                        damping_ratio: params.damping_ratio,
                        target: 0.0,
                    });
                }
            }
            joints.push(j);
        }
    }
    first
}

/// The size of a [`rain`] scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RainParams {
    /// Rows of tiles and of ragdoll groups (`RAIN_ROW_COUNT`).
    pub rows: usize,
    /// Groups per row (`RAIN_COLUMN_COUNT`).
    pub columns: usize,
    /// Ragdolls per group (`RAIN_GROUP_SIZE`).
    pub group_size: usize,
    /// Tiles per row minus one (`gridCount`: the row spans
    /// `grid_count` × 0.5 m).
    pub grid_count: usize,
}

impl RainParams {
    /// Box2D's release build: 5 rows, 40 columns, groups of 5 (1000
    /// ragdolls, 11 000 bodies), 501 tiles per row.
    pub const BOX2D: RainParams = RainParams {
        rows: 5,
        columns: 40,
        group_size: 5,
        grid_count: 500,
    };
    /// Box2D's debug build: 3 rows, 10 columns, groups of 2 (60 ragdolls),
    /// 201 tiles per row.
    pub const BOX2D_DEBUG: RainParams = RainParams {
        rows: 3,
        columns: 10,
        group_size: 2,
        grid_count: 200,
    };
}

/// Side of a rain tile, m (`gridSize`).
pub const RAIN_TILE: f64 = 0.5;

/// Box2D's `rain` benchmark with every ragdoll spawned at t = 0.
///
/// Tiles: `rows` rows of `grid_count` + 1 static 0.5 m boxes (friction
/// 0.6) side by side, row i centred at y = 45 i m, from
/// x = −grid_count/4 m in steps of 0.5 m (they are the shapes of one static
/// body in Box2D; one body each here). Ragdolls ([`ragdoll`],
/// [`RagdollParams::rain`]): `rows` × `columns` groups of `group_size`,
/// group (row i, column j) with its first ragdoll's feet at
/// x = −span/2 + (span/columns)(j + 0.5), y = 40 + 45 i (span =
/// grid_count/2 m), the others 0.5 m apart to its right; the k-th
/// ragdoll of every group is in collision group k + 1, as Box2D's group
/// indices −(k + 1): ragdolls of the same rank never collide with each
/// other, in any group. Bodies: the tiles first (row by row), then the
/// ragdolls group by group (row-major), 11 bones each.
///
/// The spawn scheme differs from Box2D's, which is not a fixed scene:
/// there a new column of groups (one per row) appears every 8 steps
/// (every 32 in its debug build) until all `columns` exist, after which
/// the oldest column is destroyed and re-created every 8 steps, so the
/// body count ramps up then stays constant while ragdolls keep falling.
/// Here every group exists from step 0 at the place Box2D spawns it, and
/// none is destroyed: each row of ragdolls falls 40 m onto its row of
/// tiles, lands after about 2.8 s and piles up; the body count is
/// constant, so per-step times compare directly.
pub fn rain(params: &RainParams) -> ManyBodyScene {
    let mut bodies = Vec::new();
    let mut joints = Vec::new();
    let tile = Shape::rectangle(RAIN_TILE, RAIN_TILE).expect("positive extents");
    for i in 0..params.rows {
        let y = 45.0 * i as f64;
        let x0 = -0.5 * params.grid_count as f64 * RAIN_TILE;
        for j in 0..=params.grid_count {
            bodies.push(SceneBody::fixed(
                tile.clone(),
                [x0 + j as f64 * RAIN_TILE, y],
            ));
        }
    }
    let span = params.grid_count as f64 * RAIN_TILE;
    let spacing = span / params.columns as f64;
    for i in 0..params.rows {
        for j in 0..params.columns {
            let mut x = -0.5 * span + spacing * (j as f64 + 0.5);
            let y = 40.0 + 45.0 * i as f64;
            for k in 0..params.group_size {
                ragdoll(
                    &RagdollParams::rain([x, y], k as u32 + 1),
                    &mut bodies,
                    &mut joints,
                );
                x += 0.5;
            }
        }
    }
    ManyBodyScene {
        gravity: BENCHMARK_GRAVITY,
        dt: BENCHMARK_DT,
        substeps: BENCHMARK_SUBSTEPS,
        bodies,
        joints,
    }
}
