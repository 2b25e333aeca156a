//! Stage 3 of the soft step, **prepare**, and the first part of stage 6,
//! **store**: the step's contact constraints, coloured and laid out for the
//! wide solver, and their impulses written back into the contacts.
//!
//! Prepare runs two loops over the contacts, both in contact (memory)
//! order: the first picks the touching contacts with an awake body and
//! colours them ([`super::colouring`]) and sums the push demands (below;
//! on the pool's threads the two are split, thread 0 colouring while
//! thread 1 sums the demands, each body's sum in the same contact order);
//! once every colour's size is known
//! the records are laid out colour after colour, and the second loop
//! prepares each constraint straight into its lane of its colour's record
//! ([`super::wide_solver::prepare_lane`]: each field computed from the
//! contact and its bodies and written, with the per-point formulas of the
//! reference, [`super::contact_solver::prepare_point`]), or builds the
//! scalar constraint ([`super::contact_solver::prepare`]) and appends it
//! to the overflow. Box2D's `b2PrepareContactsTask` writes its lanes from
//! the contact the same way; building a whole scalar constraint first and
//! copying it lane by lane cost a fifth of the stage (docs/soft_step.md,
//! "Then prepare writes each lane straight from its contact"). On the
//! pool's threads the second loop is the same walk in contact order on
//! every thread, each preparing only the lanes of its own share of the
//! records (a colour's positions grow with the contact order, so a share
//! takes a run of each colour's constraints): the contacts are read in
//! memory order there too, and no map from lanes to constraints is built
//! serially first. What a constraint reads of its bodies comes from one
//! compact record per body ([`BodyMass`]), whose lane word
//! ([`wide_solver::lane_index`]) is made once per body and step. The
//! records of the last step are overwritten field by field, so nothing is
//! zeroed or allocated per step. Store walks the same list in the same
//! order.
//!
//! **Shared push-out.** The push-out speed bounds the bias of each
//! contact, so a body overlapping k others deeply could be pushed at k
//! times that speed, and n bodies created in one place, each pushed away
//! from every other, fan out at up to (n − 1) times it
//! (`scenes/robustness/coincident_boxes.toml`; docs/soft_step.md gives
//! what Box2D, rapier2d and this rule do with it). The first loop therefore sums, per
//! dynamic body, the bias speeds its contacts with other dynamic bodies
//! ask for (each d = min(bias rate × depth, push-out speed)), each weighted
//! by twice the body's share of the pair's inverse mass (1 for equal
//! masses, whose bodies each move at d/2; near 2 for a light body against
//! a heavy one; near 0 for the heavy one): its *push demand*. Where a
//! body's demand exceeds the push-out speed, each of those contacts' bias
//! is scaled by push-out speed / demand (the larger demand of its two
//! bodies), so that no body is pushed faster than one equal pair at the
//! full speed would push it. Contacts
//! with static or kinematic bodies keep theirs: the ground has the last
//! word. In a scene built without overlaps no sum comes near the push-out
//! speed, so nothing changes there, bit for bit (the benchmark and
//! validation scenes).

use super::bodies::{BodyMass, SolverBody, solver_body, solver_index};
use super::colouring::{Colouring, Slot};
use super::contact_solver::{self, ContactConstraint, PairMass};
use super::contacts::Contact;
use super::pool::{Pool, SharedSlice, Worker};
use super::wide_solver::{self, StepSoftness, WideConstraint, WideExtra};
use super::{SoftStep, Softness};
use crate::body::{BodyId, BodyKind};
use crate::world_core::WorldCore;

impl SoftStep {
    /// Copies the world's velocities into the solver records and resets
    /// the motion since the step began.
    #[inline(never)]
    pub(super) fn load_bodies(&mut self, core: &WorldCore) {
        // Every solver index (at most the body count) fits below the lane
        // words' flags: checked once here rather than per body.
        assert!(
            self.sims.len() <= wide_solver::INDEX as usize,
            "fewer than 2³⁰ bodies"
        );
        self.masses.clear();
        self.masses
            .extend(self.sims.iter().enumerate().map(|(id, sim)| {
                // `wide_solver::lane_index` of the body's solver index, less
                // its check of the index.
                let index = solver_index(id, sim.kind) as u32;
                let lane = index | wide_solver::fixed_flag(sim.inv_mass, sim.inv_inertia);
                BodyMass::of(sim, lane)
            }));
        // By solver index: the static dummy, then the bodies (a static
        // body's entry is never gathered: its lanes use the dummy).
        self.lane_masses.clear();
        self.lane_masses.push([0.0, 0.0]);
        self.lane_masses
            .extend(self.masses.iter().map(|m| [m.inv_mass, m.inv_inertia]));
        for (id, sim) in self.sims.iter().enumerate() {
            let record = &mut self.bodies[id + 1];
            *record = if sim.moving() {
                solver_body(&core.states[id], sim.kind)
            } else {
                SolverBody::AT_REST
            };
        }
    }

    /// Stage 3: a constraint per touching contact with an awake body,
    /// coloured ([`super::colouring`]) and packed eight by eight for the wide
    /// solver; those that found no colour stay scalar (the overflow).
    #[inline(never)]
    pub(super) fn prepare(&mut self, core: &mut WorldCore, h: f64, pool: Option<&Pool>) {
        let settings = &self.settings;
        // Contact stiffness capped at a quarter of the substep's Nyquist
        // frequency (1/(8h)), twice as stiff against static bodies.
        let hertz = settings.contact_hertz.min(0.125 / h);
        let soft = Softness::new(hertz, settings.contact_damping_ratio, h);
        let static_soft = Softness::new(2.0 * hertz, settings.contact_damping_ratio, h);
        let warm = if settings.warm_starting { 1.0 } else { 0.0 };
        let push_out = settings.push_out_speed;
        // The bias rate of a contact between two dynamic bodies (1/s).
        let rate = soft.mass_scale * soft.bias_rate;
        self.colouring.clear(self.sims.len());
        self.constrained.clear();
        self.push_demand.clear();
        self.push_demand.resize(self.sims.len(), 0.0);
        let (contacts, masses) = (&self.contacts.contacts[..], &self.masses[..]);
        let points = if let Some(pool) = pool.filter(|p| p.threads() > 1) {
            // On two threads at once, each a walk of every contact in
            // contact order: thread 0 colours the constraints, thread 1
            // sums the push demands (each body's sum in contact order, as
            // one thread adds them: the same bits); the colouring, serial,
            // no longer carries the demands' share.
            let colouring = SharedSlice::new(std::slice::from_mut(&mut self.colouring));
            let constrained = SharedSlice::new(std::slice::from_mut(&mut self.constrained));
            let demand = SharedSlice::new(&mut self.push_demand[..]);
            let points = std::sync::atomic::AtomicUsize::new(0);
            pool.run(&|w: &Worker<'_>| match w.index {
                0 => {
                    // SAFETY: only thread 0 touches the colouring and the
                    // list; only thread 1 the demands.
                    let (colouring, constrained) =
                        unsafe { (colouring.get_mut(0), constrained.get_mut(0)) };
                    let mine = colour(contacts, masses, colouring, constrained);
                    points.store(mine, std::sync::atomic::Ordering::Relaxed);
                }
                1 => {
                    // SAFETY: as above.
                    let push_demand = unsafe { demand.slice(0..demand.len()) };
                    for c in contacts {
                        if let Some((sa, sb)) = solved(c, masses) {
                            add_demand(push_demand, c, (sa, sb), (rate, push_out));
                        }
                    }
                }
                _ => {}
            });
            points.into_inner()
        } else {
            // One loop: the colouring and the demands of each contact.
            let mut points = 0;
            // Indexed through a slice taken once (through `self` the
            // compiler reloads its length after every write of the loop).
            let push_demand = &mut self.push_demand[..];
            for (index, c) in contacts.iter().enumerate() {
                if let Some((sa, sb)) = solved(c, masses) {
                    colour_one(&mut self.colouring, c, (sa, sb));
                    self.constrained.push(index);
                    points += c.count;
                    add_demand(push_demand, c, (sa, sb), (rate, push_out));
                }
            }
            points
        };
        let touching = self.constrained.len();
        let records = self.colouring.finish();
        // The records of the last step are overwritten lane by lane, every
        // field; only new ones are initialised first.
        self.wide.resize(records, WideConstraint::default());
        self.wide_extra.resize(records, WideExtra::default());
        self.constraints.clear();
        // The two softnesses the records select from (`Inputs::pair` gives
        // each constraint one of them).
        self.softness = [soft, static_soft];
        let inputs = Inputs {
            masses: &self.masses,
            contacts: &self.contacts.contacts,
            bodies: &self.bodies,
            demand: &self.push_demand,
            softness: self.softness,
            push_out,
            rate,
            warm,
        };
        if let Some(pool) = pool {
            // On the threads: each its share of the records. Each thread
            // walks the constraints in contact order, as one thread does,
            // and prepares those whose lane is in its records, so the
            // contacts are read in memory order; in colour (record) order
            // they were read a colour at a time, a sweep through the
            // contacts per colour, each lane from a contact far from the
            // last. Within a colour the positions grow with the contact
            // order, so a share of records takes a run of each colour's
            // constraints. The same constraints in another order: the same
            // bits.
            let (constrained, colouring) = (&self.constrained, &self.colouring);
            // Thread 0 looks for the overflow's constraints only if there
            // are any (a scan of every constraint, alone on its thread).
            let overflows = self.colouring.overflow() > 0;
            let rare = std::sync::atomic::AtomicBool::new(false);
            let wide = SharedSlice::new(&mut self.wide);
            let extra = SharedSlice::new(&mut self.wide_extra);
            let overflow = SharedSlice::new(std::slice::from_mut(&mut self.constraints));
            pool.run(&|w: &Worker<'_>| {
                if w.index == 0 && overflows {
                    // SAFETY: only thread 0 touches the overflow.
                    let overflow = unsafe { overflow.get_mut(0) };
                    for (i, &index) in constrained.iter().enumerate() {
                        if let Slot::Overflow(_) = colouring.slot(i) {
                            overflow.push(inputs.constraint(index));
                        }
                    }
                }
                let mine = w.share(wide.len());
                let mut mine_rare = false;
                for (i, &index) in constrained.iter().enumerate() {
                    if let Slot::Lane { record, lane } = colouring.slot(i)
                        && mine.contains(&record)
                    {
                        // SAFETY: each thread its own records.
                        let lane_records = unsafe { (wide.get_mut(record), extra.get_mut(record)) };
                        mine_rare |= inputs.prepare_lane(index, lane_records, lane);
                    }
                }
                for (record, lane) in colouring.padding() {
                    if mine.contains(&record) {
                        // SAFETY: as above.
                        let lane_records = unsafe { (wide.get_mut(record), extra.get_mut(record)) };
                        wide_solver::set_padding_lane(lane_records, lane);
                    }
                }
                if mine_rare {
                    rare.store(true, std::sync::atomic::Ordering::Relaxed);
                }
            });
            // (The pool's run returns after every thread finished.)
            self.rare = rare.into_inner();
        } else {
            // In contact order, so that the contacts are read in memory
            // order; each colour's records are written in order too. The
            // records are indexed through slices taken once (through
            // `self`, the compiler reloaded their pointers and lengths for
            // every contact: 10 instructions a constraint).
            let (wide, extra) = (&mut self.wide[..], &mut self.wide_extra[..]);
            let mut rare = false;
            for (i, &index) in self.constrained.iter().enumerate() {
                match self.colouring.slot(i) {
                    Slot::Lane { record, lane } => {
                        let lane_records = (&mut wide[record], &mut extra[record]);
                        rare |= inputs.prepare_lane(index, lane_records, lane);
                    }
                    // Overflow positions come in order.
                    Slot::Overflow(_) => self.constraints.push(inputs.constraint(index)),
                }
            }
            for (record, lane) in self.colouring.padding() {
                wide_solver::set_padding_lane((&mut wide[record], &mut extra[record]), lane);
            }
            self.rare = rare;
        }
        let profile = &mut core.profiler.profile;
        profile.contacts += self.contacts.contacts.len() as u64;
        profile.touching += touching as u64;
        profile.points += points as u64;
    }

    /// Stage 6 (first part): the impulses back into the contacts, for the
    /// next step's warm start and for the reports, in contact order.
    #[inline(never)]
    pub(super) fn store_impulses(&mut self) {
        contact_solver::store_impulses(&self.constraints, &mut self.contacts.contacts);
        for (i, &index) in self.constrained.iter().enumerate() {
            if let Slot::Lane { record, lane } = self.colouring.slot(i) {
                let contact = &mut self.contacts.contacts[index];
                wide_solver::store_lane(
                    (&self.wide[record], &self.wide_extra[record]),
                    lane,
                    contact,
                );
            }
        }
    }
}

/// What the second loop of prepare reads to make a contact's constraint:
/// the step's bodies and contacts, the push demands the first loop summed,
/// and the step's settings.
#[derive(Clone, Copy)]
struct Inputs<'a> {
    masses: &'a [BodyMass],
    contacts: &'a [Contact],
    /// The solver records, by solver index.
    bodies: &'a [SolverBody],
    /// Each dynamic body's push demand (m/s; the module documentation).
    demand: &'a [f64],
    /// Between moving bodies (or with a kinematic one), and with a static
    /// body.
    softness: StepSoftness,
    /// The settings' push-out speed (m/s).
    push_out: f64,
    /// The bias rate of a contact between two dynamic bodies (1/s).
    rate: f64,
    /// The warm-start scale (1 on, 0 off).
    warm: f64,
}

impl Inputs<'_> {
    /// Contact `index`, its bodies' solver indices and inverse masses,
    /// their lane words ([`BodyMass::lane`]), whether it takes the step's
    /// second softness (with a static body) and its push-out bound (m/s):
    /// the settings' push-out speed, scaled down when a dynamic body's
    /// demand exceeds it (the module documentation).
    #[inline(always)]
    fn pair(&self, index: usize) -> (&Contact, PairMass, (u32, u32), bool, f64) {
        let c = &self.contacts[index];
        let (sa, sb) = (&self.masses[c.body_a], &self.masses[c.body_b]);
        let mass = PairMass {
            a: (sa.lane & wide_solver::INDEX) as usize,
            b: (sb.lane & wide_solver::INDEX) as usize,
            inv_mass_a: sa.inv_mass,
            inv_inertia_a: sa.inv_inertia,
            inv_mass_b: sb.inv_mass,
            inv_inertia_b: sb.inv_inertia,
        };
        let push_out = self.push_out;
        let (static_soft, bound) = if both_dynamic(sa, sb) {
            let (da, db) = (self.demand[c.body_a], self.demand[c.body_b]);
            let most = if da > db { da } else { db };
            let bound = if most > push_out {
                demand_of(c, self.rate, push_out).max(0.0) * (push_out / most)
            } else {
                push_out
            };
            (false, bound)
        } else {
            let static_soft = sa.kind == BodyKind::Static || sb.kind == BodyKind::Static;
            (static_soft, push_out)
        };
        (c, mass, (sa.lane, sb.lane), static_soft, bound)
    }

    /// The scalar constraint of contact `index` (for the overflow).
    fn constraint(&self, index: usize) -> ContactConstraint {
        let (c, mass, _, static_soft, bound) = self.pair(index);
        let softness = self.softness[usize::from(static_soft)];
        contact_solver::prepare(c, index, mass, (softness, bound), self.bodies, self.warm)
    }

    /// Prepares the constraint of contact `index` straight into lane `l`
    /// of `records` ([`wide_solver::prepare_lane`]: the bits
    /// [`Inputs::constraint`] would hold); returns whether it is rare
    /// ([`wide_solver::is_rare`]).
    #[inline(always)]
    fn prepare_lane(
        &self,
        index: usize,
        records: (&mut WideConstraint, &mut WideExtra),
        l: usize,
    ) -> bool {
        let (c, mass, words, static_soft, bound) = self.pair(index);
        wide_solver::prepare_lane(
            records,
            l,
            c,
            (&mass, words),
            (static_soft, bound),
            self.bodies,
            self.warm,
        )
    }
}

/// The bodies of contact `c` when it gets a constraint this step (it
/// touches, is no sensor's, and a body moves), from `masses`.
#[inline(always)]
fn solved<'a>(c: &Contact, masses: &'a [BodyMass]) -> Option<(&'a BodyMass, &'a BodyMass)> {
    if c.count == 0 || c.sensor {
        return None;
    }
    let (sa, sb) = (&masses[c.body_a], &masses[c.body_b]);
    (sa.moving || sb.moving).then_some((sa, sb))
}

/// Gives contact `c`, between bodies `(sa, sb)`, its colour.
#[inline(always)]
fn colour_one(colouring: &mut Colouring, c: &Contact, (sa, sb): (&BodyMass, &BodyMass)) {
    let dynamic = |id: BodyId, s: &BodyMass| (s.kind == BodyKind::Dynamic).then_some(id);
    colouring.add(dynamic(c.body_a, sa), dynamic(c.body_b, sb));
}

/// Colours every contact of `contacts` that gets a constraint and lists
/// it in `constrained`, in contact order; returns their points.
#[inline(never)]
fn colour(
    contacts: &[Contact],
    masses: &[BodyMass],
    colouring: &mut Colouring,
    constrained: &mut Vec<usize>,
) -> usize {
    let mut points = 0;
    for (index, c) in contacts.iter().enumerate() {
        if let Some((sa, sb)) = solved(c, masses) {
            colour_one(colouring, c, (sa, sb));
            constrained.push(index);
            points += c.count;
        }
    }
    points
}

/// Adds the push demand of contact `c` between bodies `(sa, sb)` to its
/// bodies' sums in `push_demand` when both are dynamic (the module
/// documentation); `rate`: the bias rate (1/s), `push_out`: the push-out
/// speed (m/s).
#[inline(always)]
fn add_demand(
    push_demand: &mut [f64],
    c: &Contact,
    (sa, sb): (&BodyMass, &BodyMass),
    (rate, push_out): (f64, f64),
) {
    if both_dynamic(sa, sb) {
        let demand = demand_of(c, rate, push_out);
        if demand > 0.0 {
            // Each body's part of the relative push, twice its share of
            // the pair's inverse mass: 1 for equal masses (each moves at
            // half the relative speed), near 2 for a light body against a
            // heavy one, near 0 for the heavy one (pushed by many light
            // ones, it hardly moves).
            let part = 2.0 * demand / (sa.inv_mass + sb.inv_mass);
            push_demand[c.body_a] += part * sa.inv_mass;
            push_demand[c.body_b] += part * sb.inv_mass;
        }
    }
}

/// Whether both bodies are dynamic.
#[inline(always)]
fn both_dynamic(a: &BodyMass, b: &BodyMass) -> bool {
    a.kind == BodyKind::Dynamic && b.kind == BodyKind::Dynamic
}

/// The bias speed (m/s) contact `c` asks for between two dynamic bodies:
/// `rate` (1/s) times its deepest overlap, at most `push_out` (m/s).
#[inline(always)]
fn demand_of(c: &Contact, rate: f64, push_out: f64) -> f64 {
    // Plain comparisons: the values are finite (f64::min's NaN handling
    // costs instructions on every contact).
    let demand = -rate * deepest(c);
    if demand < push_out { demand } else { push_out }
}

/// The separation of the deepest point of `c` (m, negative inside; the
/// contact has one or two points).
#[inline(always)]
fn deepest(c: &Contact) -> f64 {
    let (first, second) = (c.points[0].separation, c.points[1].separation);
    if c.count == 2 && second < first {
        second
    } else {
        first
    }
}

#[cfg(test)]
mod tests {
    use crate::{BodyDef, ContactModel, Method, Shape, SoftStepSettings, World};
    use nalgebra::Vector2;

    /// A dynamic plank on the ground carrying 25 boxes side by side (1.1 m
    /// apart, out of each other's reach): the plank is in 25 pairs with
    /// dynamic bodies, more than the 20 colours open to them
    /// ([`super::super::colouring::DYNAMIC_COLOURS`]), so 5 of its
    /// constraints go to the overflow and the scalar solver every step
    /// (checked once by printing the overflow's size), the rest to the
    /// lanes. Returns the world after `steps` steps.
    fn plank_with_boxes(steps: usize) -> World {
        let mut world = World::with_model(
            Method::SemiImplicitEuler,
            ContactModel::SoftStep(SoftStepSettings::default()),
        )
        .unwrap();
        world.set_gravity(Vector2::new(0.0, -10.0)).unwrap();
        let rect = |w: f64, h: f64| Shape::rectangle(w, h).unwrap();
        world
            .add_body(BodyDef::fixed(
                "ground",
                Vector2::new(0.0, -0.5),
                Some(rect(40.0, 1.0)),
            ))
            .unwrap();
        let body = |name: &str, shape: Shape, x: f64, y: f64| {
            BodyDef {
                mass: None,
                density: Some(1.0),
                ..BodyDef::rigid(name, 1.0, shape)
            }
            .with_position(Vector2::new(x, y))
        };
        world
            .add_body(body("plank", rect(30.0, 0.5), 0.0, 0.25))
            .unwrap();
        for k in 0..25 {
            let x = (k as f64 - 12.0) * 1.1;
            world.add_body(body("box", rect(1.0, 1.0), x, 1.0)).unwrap();
        }
        for _ in 0..steps {
            world.step(1.0 / 60.0).unwrap();
        }
        world
    }

    #[test]
    fn constraints_beyond_the_colours_are_solved_by_the_overflow() {
        let world = plank_with_boxes(120);
        // Every box rests on the plank, its centre 1 m up less the sink of
        // the two soft contacts in series (a fraction of a millimetre: 0.28
        // mm under a body's own weight at 30 Hz, the plank carrying 2.7
        // times its own; 0.76 mm measured). 5 mm separates resting from a
        // contact that failed (the box would drop 0.5 m) and stays clear of
        // that sink; and at rest.
        for s in &world.states()[2..] {
            assert!((s.position.y - 1.0).abs() < 5e-3, "{s:?}");
            assert!(s.velocity.norm() < 1e-3, "{s:?}");
        }
        // The same scene gives the same bits.
        assert_eq!(world.states(), plank_with_boxes(120).states());
    }
}
