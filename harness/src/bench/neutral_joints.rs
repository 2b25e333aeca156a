//! A scene file's joints as the reference engines take them: the engine's
//! [`JointDef`]s (anchors in world or body coordinates, an optional
//! reference angle, rest lengths taken from the anchors when not given)
//! turned into the neutral [`SceneJoint`]s of `references::many_body`,
//! whose anchors are world points at t = 0 and whose reference angle and
//! lengths are explicit. A target (mouse) joint has no neutral form: it is
//! refused with the joint's name.

use anyhow::{Result, bail};
use engine::{Anchor, BodyState, Distance, JointDef, JointKind, JointSpring};
use references::many_body::joints::{
    DistanceJoint, DistanceMode, JointKind as Neutral, Motor, MotorJoint, PrismaticJoint,
    RevoluteJoint, SceneJoint, Softness, Spring, WeldJoint, WheelJoint,
};

/// The neutral joints of `defs`, for bodies whose states at t = 0 are
/// `states` (indexed like the scene's bodies).
pub fn neutral_joints<'a>(
    defs: impl IntoIterator<Item = &'a JointDef>,
    states: &[BodyState],
) -> Result<Vec<SceneJoint>> {
    defs.into_iter().map(|d| neutral_joint(d, states)).collect()
}

/// The world point (m) of an anchor of body `body` at t = 0.
fn world(anchor: Anchor, body: Option<usize>, states: &[BodyState]) -> [f64; 2] {
    let p = match anchor {
        Anchor::World(p) => p,
        Anchor::Local(local) => engine::joints::world_point(body, local, states),
    };
    [p.x, p.y]
}

fn angle(body: Option<usize>, states: &[BodyState]) -> f64 {
    body.map_or(0.0, |b| states[b].angle)
}

fn spring(s: JointSpring, target: f64) -> Spring {
    Spring {
        hertz: s.hertz,
        damping_ratio: s.damping_ratio,
        target,
    }
}

fn limits(l: Option<(f64, f64)>) -> Option<[f64; 2]> {
    l.map(|(lo, hi)| [lo, hi])
}

/// Lower and upper length limits, `None` when neither binds (0 and ∞).
fn length_limits(min: f64, max: f64) -> Option<[f64; 2]> {
    (min > 0.0 || max.is_finite()).then_some([min, max])
}

fn neutral_joint(def: &JointDef, states: &[BodyState]) -> Result<SceneJoint> {
    let (a, b) = (def.body_a, def.body_b);
    let anchor_a = world(def.anchor_a, a, states);
    let anchor_b = world(def.anchor_b, b, states);
    // Unset, the reference angle is the bodies' relative angle at creation
    // (the engine's rule, and Box2D's).
    let reference_angle = def
        .reference_angle
        .unwrap_or_else(|| angle(b, states) - angle(a, states));
    let distance =
        ((anchor_b[0] - anchor_a[0]).powi(2) + (anchor_b[1] - anchor_a[1]).powi(2)).sqrt();
    let kind = match def.kind {
        JointKind::Revolute(r) => Neutral::Revolute(RevoluteJoint {
            anchor_a,
            anchor_b,
            reference_angle,
            limits: limits(r.limits),
            motor: r.motor.map(|m| Motor {
                speed: m.speed,
                max_force: m.max_torque,
            }),
            spring: r.spring.map(|s| spring(s, r.spring_target)),
        }),
        JointKind::Prismatic(p) => Neutral::Prismatic(PrismaticJoint {
            anchor_a,
            anchor_b,
            axis: [p.axis.x, p.axis.y],
            limits: limits(p.limits),
            motor: p.motor.map(|m| Motor {
                speed: m.speed,
                max_force: m.max_force,
            }),
            spring: p.spring.map(|s| spring(s, p.spring_target)),
        }),
        JointKind::Distance(d) => Neutral::Distance(DistanceJoint {
            anchor_a,
            anchor_b,
            mode: match d {
                Distance::Rigid { length } => DistanceMode::Rigid {
                    length: length.unwrap_or(distance),
                },
                Distance::Rope {
                    min_length,
                    max_length,
                } => DistanceMode::Rope {
                    min_length,
                    max_length,
                },
                Distance::Spring {
                    length,
                    spring: s,
                    min_length,
                    max_length,
                } => DistanceMode::Spring {
                    spring: spring(s, length.unwrap_or(distance)),
                    limits: length_limits(min_length, max_length),
                },
            },
        }),
        JointKind::Weld(w) => {
            let softness = match (w.linear_spring, w.angular_spring) {
                (None, None) => None,
                (Some(s), None) | (None, Some(s)) => Some(s),
                (Some(l), Some(r)) if l == r => Some(l),
                (Some(_), Some(_)) => bail!(
                    "joint '{}': a weld with different linear and angular springs has no counterpart in the reference engines (one softness for both)",
                    def.name
                ),
            };
            Neutral::Weld(WeldJoint {
                anchor: anchor_a,
                softness: softness.map(|s| Softness {
                    hertz: s.hertz,
                    damping_ratio: s.damping_ratio,
                }),
            })
        }
        JointKind::Wheel(w) => Neutral::Wheel(WheelJoint {
            anchor_a,
            anchor_b,
            axis: [w.axis.x, w.axis.y],
            spring: w.spring.map(|s| Softness {
                hertz: s.hertz,
                damping_ratio: s.damping_ratio,
            }),
            limits: limits(w.limits),
            motor: w.motor.map(|m| Motor {
                speed: m.speed,
                max_force: m.max_torque,
            }),
        }),
        JointKind::Motor(m) => {
            let soft = |s: JointSpring| Softness {
                hertz: s.hertz,
                damping_ratio: s.damping_ratio,
            };
            Neutral::Motor(MotorJoint {
                anchor_a,
                anchor_b,
                linear_offset: [m.linear_offset.x, m.linear_offset.y],
                angular_offset: m.angular_offset,
                max_force: m.max_force,
                max_torque: m.max_torque,
                linear: soft(m.linear_spring),
                angular: soft(m.angular_spring),
            })
        }
        JointKind::Target(_) => bail!(
            "joint '{}': a target joint pulls toward a moving point, which the reference engines' descriptions do not carry",
            def.name
        ),
    };
    Ok(SceneJoint {
        body_a: a,
        body_b: b,
        kind,
        collide_connected: def.collide_connected,
    })
}

#[cfg(test)]
mod tests {
    use crate::bench::convert::many_body_scene;
    use references::box2d_world::Box2dWorld;
    use references::many_body::{BodySample, ManyBodyEngine, ManyBodyScene};
    use references::rapier_many::RapierManyWorld;

    fn initial_samples(scene: &ManyBodyScene) -> Vec<BodySample> {
        scene
            .bodies
            .iter()
            .map(|b| BodySample {
                position: b.position,
                angle: b.angle,
                velocity: b.velocity,
                angular_velocity: b.angular_velocity,
            })
            .collect()
    }

    /// The jointed scene files convert with every joint, each held where
    /// the file puts it (anchors coincide, rods at their length) at t = 0
    /// (but in Falling Hinges, whose hinges start open by design, as in
    /// Box2D's test), and are connected for half a second in both reference engines:
    /// every separation under 1 cm (the soft joint rows of Box2D sag by
    /// g/ω² ≈ 0.07 mm per link at 60 Hz; a joint lost or misplaced in the
    /// conversion would open by the links' sizes, decimetres).
    /// The `joint_grid` generator converts to the references' builder of
    /// Box2D's `CreateJointGrid` (an independent transcription of the same
    /// layout): the same bodies in the same order and the same joints, to
    /// the bit (every coordinate is a whole or half metre).
    #[test]
    fn the_joint_grid_generator_is_box2ds_layout() {
        let n = 10;
        let text = format!(
            "[simulation]\ndt = 0.016666666666666666\nduration = 1.0\ngravity = [0.0, -10.0]\n\n[contact]\nfriction = 0.6\n\n[[generate]]\ntype = \"joint_grid\"\ncolumns = {n}\nrows = {n}\n"
        );
        let scene = scene::Scene::parse_str("grid.toml", &text).unwrap();
        let ours = many_body_scene(&scene).unwrap();
        let reference = references::many_body::joint_grid(n);
        assert_eq!(ours.bodies, reference.bodies);
        assert_eq!(ours.joints, reference.joints);
        assert_eq!((ours.dt, ours.substeps), (reference.dt, reference.substeps));
        assert_eq!(ours.gravity, reference.gravity);
    }

    #[test]
    fn jointed_scenes_convert_and_hold_in_both_engines() {
        for id in ["examples/chain", "examples/ragdoll", "falling_hinges"] {
            let scene = crate::scenes::load(id).unwrap();
            let neutral = many_body_scene(&scene).unwrap();
            assert_eq!(neutral.joints.len(), scene.joint_count(), "{id}");
            assert!(!neutral.joints.is_empty(), "{id}");
            for (k, j) in neutral
                .joint_states(&initial_samples(&neutral))
                .iter()
                .enumerate()
            {
                let starts_open = id == "falling_hinges";
                assert!(
                    starts_open || j.separation < 1e-9,
                    "{id}: joint {k} starts open: {j:?}"
                );
            }
            let engines: Vec<Box<dyn ManyBodyEngine>> = vec![
                Box::new(Box2dWorld::new(&neutral).unwrap()),
                Box::new(RapierManyWorld::new(&neutral).unwrap()),
            ];
            for mut e in engines {
                for _ in 0..30 {
                    e.step().unwrap();
                }
                let mut samples = Vec::new();
                e.samples(&mut samples).unwrap();
                let worst = neutral
                    .joint_states(&samples)
                    .iter()
                    .map(|j| j.separation)
                    .fold(0.0, f64::max);
                assert!(
                    worst < 0.01,
                    "{id} in {}: a joint opened by {worst} m",
                    e.name()
                );
            }
        }
    }
}
