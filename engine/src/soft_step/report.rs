//! The soft step's reports to the program: touch, hit and sensor events
//! from the collide stage's touching changes, and the contact data read
//! after a step (see [`super::contact_events`] for what each means).

use super::contact_events::{
    ContactData, ContactPointData, HitEvent, PreSolveContact, SensorEvent, ShapeId, StepEvents,
    TouchEvent,
};
use super::contacts::{Contact, TouchChange};
use super::shape_data::ShapeData;
use super::{SoftStep, geometry::Collider};
use nalgebra::Vector2;

impl SoftStep {
    /// The id of collider `c`.
    fn shape_id(&self, c: usize) -> ShapeId {
        shape_id(&self.colliders[c], &self.shape_data[c])
    }

    /// Records that contact `index`, touching, ends now (destroyed, or its
    /// body removed).
    pub(super) fn contact_ended(&mut self, index: usize) {
        let c = &self.contacts.contacts[index];
        let (a, b) = (self.shape_id(c.a), self.shape_id(c.b));
        if c.sensor {
            let event = self.sensor_event(c, a, b);
            self.events.sensor_ended.push(event);
        } else {
            self.events.touch_ended.push(TouchEvent { a, b });
        }
    }

    fn sensor_event(&self, c: &Contact, a: ShapeId, b: ShapeId) -> SensorEvent {
        if self.shape_data[c.a].sensor {
            SensorEvent {
                sensor: a,
                visitor: b,
            }
        } else {
            SensorEvent {
                sensor: b,
                visitor: a,
            }
        }
    }

    /// The touching changes of this step's collide stage as events, with
    /// the hits of the pairs that began touching (after the solve, whose
    /// impulses say which points pushed).
    pub(super) fn report_touches(&mut self) {
        let threshold = self.settings.hit_event_threshold;
        for k in 0..self.contacts.changes.len() {
            let (index, began) = match self.contacts.changes[k] {
                TouchChange::Began(index) => (index, true),
                TouchChange::Ended(index) => (index, false),
            };
            let c = &self.contacts.contacts[index];
            let (a, b) = (self.shape_id(c.a), self.shape_id(c.b));
            let sensor = c.sensor.then(|| self.sensor_event(c, a, b));
            let events: &mut StepEvents = &mut self.events;
            if let Some(event) = sensor {
                if began {
                    events.sensor_began.push(event);
                } else {
                    events.sensor_ended.push(event);
                }
                continue;
            }
            if !began {
                events.touch_ended.push(TouchEvent { a, b });
                continue;
            }
            events.touch_began.push(TouchEvent { a, b });
            // Box2D's hit: the fastest approaching point that pushed.
            let mut hit: Option<(f64, Vector2<f64>)> = None;
            for p in &c.points[..c.count] {
                let speed = -p.normal_velocity;
                let faster = hit.map_or(threshold, |(s, _)| s);
                if speed > faster && p.total_normal_impulse > 0.0 {
                    hit = Some((speed, p.point));
                }
            }
            if let Some((approach_speed, point)) = hit {
                events.hits.push(HitEvent {
                    a,
                    b,
                    point,
                    normal: c.normal,
                    approach_speed,
                });
            }
        }
        self.contacts.changes.clear();
    }

    /// Replaces the program's hooks.
    pub(crate) fn set_hooks(&mut self, hooks: Option<Box<dyn super::ContactHooks>>) {
        self.hooks.0 = hooks;
    }

    /// The events of the last world step.
    pub(crate) fn step_events(&self) -> &StepEvents {
        &self.events
    }

    /// Every touching non-sensor pair with its manifold and last impulses.
    pub(crate) fn contact_data(&self) -> impl Iterator<Item = ContactData> + '_ {
        self.contacts
            .contacts
            .iter()
            .filter(|c| c.touching && !c.sensor && c.count > 0)
            .map(|c| {
                let mut points = [ContactPointData::default(); 2];
                for (q, p) in points.iter_mut().zip(&c.points[..c.count]) {
                    *q = ContactPointData {
                        point: p.point,
                        separation: p.separation,
                        normal_impulse: p.normal_impulse,
                        tangent_impulse: p.tangent_impulse,
                        total_normal_impulse: p.total_normal_impulse,
                        normal_velocity: p.normal_velocity,
                    };
                }
                ContactData {
                    a: self.shape_id(c.a),
                    b: self.shape_id(c.b),
                    normal: c.normal,
                    count: c.count,
                    points,
                    rolling_impulse: c.rolling_impulse,
                }
            })
    }
}

/// The id of a collider from its data.
fn shape_id(c: &Collider, d: &ShapeData) -> ShapeId {
    ShapeId {
        body: c.body,
        part: d.part,
    }
}

/// What the pre-solve hook sees of `contact`.
pub(super) fn pre_solve_view(
    contact: &Contact,
    (colliders, data): (&[Collider], &[ShapeData]),
) -> PreSolveContact {
    let mut points = [(Vector2::zeros(), 0.0); 2];
    for (q, p) in points.iter_mut().zip(&contact.points[..contact.count]) {
        *q = (p.point, p.separation);
    }
    PreSolveContact {
        a: shape_id(&colliders[contact.a], &data[contact.a]),
        b: shape_id(&colliders[contact.b], &data[contact.b]),
        normal: contact.normal,
        count: contact.count,
        points,
    }
}
