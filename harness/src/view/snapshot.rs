//! Copying a world into a [`Frame`]: the states and sleep flags every
//! frame; the joints, the contact points and the paths only while their
//! overlay is on.
//!
//! The contact points: under the soft step, the solver's own manifolds
//! after the last step (`World::contact_data`: every touching pair's
//! points with the normal impulse delivered over the step and the
//! friction impulse); under the exact model, which keeps no such record,
//! the narrow phase's manifolds of the shapes as they are now
//! (`engine::validation::collision`, the engine's own functions, over a
//! sort-and-sweep of the bodies' boxes), touching or within
//! [`CONTACT_MARGIN`], without impulses.
//!
//! The islands (with the sleeping overlay): the soft step's own
//! (`World::islands`), each with the union of its bodies' boxes.

use super::frame::{ContactMark, Frame, ImpulseScale, IslandMark, JointLine, NO_ISLAND};
use super::simulation::{Needs, PATH_BODIES, PATH_POINTS};
use engine::validation::collision::{Aabb, SweepAndPrune, collide};
use engine::{BodyKind, ContactModel, World};
use nalgebra::{Isometry2, Vector2};
use std::collections::HashSet;
use std::collections::VecDeque;

/// Contacts are drawn for shapes touching or closer than this (m): Box2D's
/// linear slop, the overlap the soft step leaves at rest.
pub const CONTACT_MARGIN: f64 = 0.005;
/// The most contact points drawn (a pile of 5050 boxes has about 15 000).
const MAX_CONTACTS: usize = 50_000;

/// Fills `frame` from `world`.
pub fn fill(
    frame: &mut Frame,
    world: &World,
    needs: Needs,
    paths: &[(usize, VecDeque<Vector2<f64>>)],
    joined: &HashSet<(usize, usize)>,
) {
    let n = world.bodies().len();
    frame.states.clear();
    frame.states.extend_from_slice(world.states());
    frame.removed.clear();
    frame.removed.extend((0..n).map(|id| world.is_removed(id)));
    frame.asleep.clear();
    frame.asleep.extend((0..n).map(|id| world.is_asleep(id)));
    let status = &mut frame.status;
    status.bodies = n;
    status.asleep = frame.asleep.iter().filter(|&&a| a).count();
    frame.joints.clear();
    let mut live_joints = 0;
    for id in 0..world.joint_count() {
        let Ok(joint) = world.joint(id) else {
            continue;
        };
        if joint.removed {
            continue;
        }
        live_joints += 1;
        if needs.joints {
            let centre = |b: Option<usize>| b.map(|b| world.states()[b].position);
            frame.joints.push(JointLine {
                joint_type: joint.joint_type,
                centre_a: centre(joint.body_a),
                anchor_a: joint.anchor_a,
                anchor_b: joint.anchor_b,
                centre_b: centre(joint.body_b),
            });
        }
    }
    frame.status.joints = live_joints;
    frame.contacts.clear();
    frame.status.impulse_scale = None;
    if needs.contacts {
        if world.contact_data().is_ok() {
            solver_contacts(world, &mut frame.contacts);
            frame.status.impulse_scale = impulse_scale(&frame.contacts);
        } else {
            contacts(world, joined, &mut frame.contacts);
        }
    }
    frame.island_of.clear();
    frame.islands.clear();
    frame.islands_missing = None;
    if needs.islands {
        islands(frame, world);
    }
    frame.paths.clear();
    frame.paths.extend(
        paths
            .iter()
            .map(|(id, p)| (*id, p.iter().copied().collect())),
    );
}

/// The soft step's contact points after the last step, with their
/// impulses.
fn solver_contacts(world: &World, out: &mut Vec<ContactMark>) {
    let Ok(data) = world.contact_data() else {
        return;
    };
    for c in data {
        out.extend(c.points().iter().map(|p| ContactMark {
            point: p.point,
            normal: c.normal,
            normal_impulse: Some(p.total_normal_impulse),
            tangent_impulse: Some(p.tangent_impulse),
        }));
        if out.len() >= MAX_CONTACTS {
            return;
        }
    }
}

/// The longest normal drawn (px) at the frame's largest impulse.
pub const LONGEST_NORMAL_PX: f64 = 40.0;

/// Pixels per N·s: the largest round 1, 2, 5 × 10ⁿ that draws the
/// largest normal impulse at most [`LONGEST_NORMAL_PX`] long; `None`
/// without impulses.
fn impulse_scale(contacts: &[ContactMark]) -> Option<ImpulseScale> {
    let largest = contacts
        .iter()
        .filter_map(|c| c.normal_impulse)
        .filter(|j| j.is_finite())
        .fold(0.0, f64::max);
    if contacts.iter().all(|c| c.normal_impulse.is_none()) {
        return None;
    }
    if largest <= 0.0 {
        return Some(ImpulseScale {
            px_per_newton_second: 0.0,
            largest,
        });
    }
    let ideal = LONGEST_NORMAL_PX / largest;
    let base = 10f64.powf(ideal.log10().floor());
    let px = [5.0, 2.0, 1.0]
        .iter()
        .map(|m| m * base)
        .find(|&v| v <= ideal)
        .unwrap_or(base);
    Some(ImpulseScale {
        px_per_newton_second: px,
        largest,
    })
}

/// The soft step's islands: each body's, and each island's box.
fn islands(frame: &mut Frame, world: &World) {
    let islands = match world.islands() {
        Ok(islands) => islands,
        Err(e) => {
            frame.islands_missing = Some(match e {
                engine::EngineError::Unsupported { reason, .. } => reason.to_owned(),
                other => other.to_string(),
            });
            return;
        }
    };
    frame.island_of.resize(frame.states.len(), NO_ISLAND);
    for island in islands {
        let mut lo = Vector2::repeat(f64::INFINITY);
        let mut hi = Vector2::repeat(f64::NEG_INFINITY);
        for &b in island.bodies {
            if let (Some(slot), Some(look), Some(state)) = (
                frame.island_of.get_mut(b),
                frame.looks.get(b),
                frame.states.get(b),
            ) {
                *slot = island.id.0 as u32;
                let (a, z) = look.aabb(state);
                lo = lo.inf(&a);
                hi = hi.sup(&z);
            }
        }
        if lo.x <= hi.x {
            frame.islands.push(IslandMark {
                id: island.id.0,
                lo,
                hi,
                bodies: island.bodies.len(),
                asleep: island.asleep,
            });
        }
    }
}

/// The contact points and normals of the world's shapes now; `joined`
/// holds the pairs (lower id first) a joint keeps from colliding.
fn contacts(world: &World, joined: &HashSet<(usize, usize)>, out: &mut Vec<ContactMark>) {
    let soft_step = match world.contact_model() {
        None => return,
        Some(model) => matches!(model, ContactModel::SoftStep(_)),
    };
    let bodies = world.bodies();
    let states = world.states();
    let shaped: Vec<usize> = (0..bodies.len())
        .filter(|&id| bodies[id].shape.is_some() && !world.is_removed(id))
        .collect();
    let poses: Vec<Isometry2<f64>> = shaped
        .iter()
        .map(|&id| Isometry2::new(states[id].position, states[id].angle))
        .collect();
    let boxes: Vec<Aabb> = shaped
        .iter()
        .zip(&poses)
        .map(|(&id, pose)| {
            let shape = bodies[id].shape.as_ref().expect("filtered on a shape");
            Aabb::of_shape(shape, pose).loosened(CONTACT_MARGIN)
        })
        .collect();
    for (i, j) in SweepAndPrune::new().pairs(&boxes) {
        let (a, b) = (shaped[i], shaped[j]);
        if bodies[a].kind != BodyKind::Dynamic && bodies[b].kind != BodyKind::Dynamic {
            continue;
        }
        // The bodies' filters (a compound part's own filter aside) and
        // sensors, as the soft step's pair search reads them.
        let refused = !bodies[a].filter.should_collide(&bodies[b].filter)
            || bodies[a].sensor
            || bodies[b].sensor;
        if soft_step && (refused || joined.contains(&(a.min(b), a.max(b)))) {
            continue;
        }
        let (Some(sa), Some(sb)) = (&bodies[a].shape, &bodies[b].shape) else {
            continue;
        };
        if let Some(m) = collide(sa, &poses[i], sb, &poses[j], CONTACT_MARGIN) {
            out.extend(m.contacts().map(|c| ContactMark {
                point: c.point,
                normal: c.normal,
                normal_impulse: None,
                tangent_impulse: None,
            }));
        }
        if out.len() >= MAX_CONTACTS {
            return;
        }
    }
}

/// Appends the current positions of the first [`PATH_BODIES`] dynamic
/// bodies to their paths, each kept to its last [`PATH_POINTS`].
pub fn record_paths(paths: &mut Vec<(usize, VecDeque<Vector2<f64>>)>, world: &World) {
    if paths.is_empty() {
        paths.extend(
            (0..world.bodies().len())
                .filter(|&id| world.bodies()[id].kind == BodyKind::Dynamic)
                .take(PATH_BODIES)
                .map(|id| (id, VecDeque::with_capacity(PATH_POINTS))),
        );
    }
    for (id, path) in paths.iter_mut() {
        if path.len() == PATH_POINTS {
            path.pop_front();
        }
        path.push_back(world.states()[*id].position);
    }
}
