//! Copying a world into a [`Frame`]: the states and sleep flags every
//! frame; the joints, the contact points and the paths only while their
//! overlay is on.
//!
//! The contact points are the narrow phase's manifolds of the shapes as
//! they are now (`engine::validation::collision`, the engine's own
//! functions, over a sort-and-sweep of the bodies' boxes), touching or
//! within [`CONTACT_MARGIN`]: the contacts the next step will solve, not
//! the solver's stored points (which the engine keeps private).

use super::frame::{ContactMark, Frame, JointLine};
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
    if needs.contacts {
        contacts(world, joined, &mut frame.contacts);
    }
    frame.paths.clear();
    frame.paths.extend(
        paths
            .iter()
            .map(|(id, p)| (*id, p.iter().copied().collect())),
    );
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
