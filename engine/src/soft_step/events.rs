//! Events (landing, apex, …) under the soft step: located inside each
//! substep by linear interpolation between its start and end states, exact
//! for positions (they move linearly in a substep).

use super::SoftStep;
use super::bodies::SolverBody;
use crate::body::{BodyId, BodyState};
use crate::events::EventRecord;
use crate::world_core::WorldCore;

impl SoftStep {
    /// Events crossed during the substep `(t_a, t_b)`, located by linear
    /// interpolation between its start and end states; returns whether a
    /// terminal one stopped the world (its state written to `core`).
    pub(super) fn locate_events(
        &mut self,
        core: &mut WorldCore,
        (t_a, t_b): (f64, f64),
        found: &mut Vec<EventRecord>,
    ) -> bool {
        let state_at = |records: &[SolverBody], id: BodyId| {
            let r = &records[id + 1];
            let s = core.states[id];
            if self.sims[id].moving() {
                BodyState {
                    position: s.position + r.dp,
                    angle: s.angle + r.dtheta,
                    velocity: r.v,
                    angular_velocity: r.w,
                }
            } else {
                s
            }
        };
        let mut hits: Vec<(f64, usize)> = Vec::new();
        for (index, spec) in core.events.iter().enumerate() {
            let ga = spec.quantity.of(&state_at(&self.substep_start, spec.body)) - spec.level;
            let gb = spec.quantity.of(&state_at(&self.bodies, spec.body)) - spec.level;
            if spec.crossing.detects(ga, gb) {
                let f = if gb == ga { 1.0 } else { ga / (ga - gb) };
                hits.push((f, index));
            }
        }
        if hits.is_empty() {
            return false;
        }
        hits.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut stop: Option<(f64, Vec<BodyState>)> = None;
        let interpolate = |f: f64| -> Vec<BodyState> {
            (0..core.states.len())
                .map(|id| {
                    let (a, b) = (
                        state_at(&self.substep_start, id),
                        state_at(&self.bodies, id),
                    );
                    BodyState {
                        position: a.position + f * (b.position - a.position),
                        angle: a.angle + f * (b.angle - a.angle),
                        velocity: a.velocity + f * (b.velocity - a.velocity),
                        angular_velocity: a.angular_velocity
                            + f * (b.angular_velocity - a.angular_velocity),
                    }
                })
                .collect()
        };
        for (f, index) in hits {
            let t = if f >= 1.0 { t_b } else { t_a + f * (t_b - t_a) };
            let states = interpolate(f);
            let spec = &core.events[index];
            let terminal = spec.terminal;
            found.push(EventRecord {
                name: spec.name.clone(),
                t,
                states: states.clone(),
            });
            if terminal {
                stop = Some((t, states));
                break;
            }
        }
        match stop {
            Some((t, states)) => {
                core.states = states;
                core.time = t;
                core.stopped = true;
                true
            }
            None => false,
        }
    }
}
