//! Graph colouring of the contact constraints (after Box2D v3's
//! `constraint_graph.c`): each step, every touching constraint gets a
//! colour such that no two constraints of a colour share a dynamic body.
//!
//! Why: the constraints of one colour are independent (solving one does not
//! change the velocities another reads), so the wide solver
//! ([`super::wide_solver`]) can solve eight of them at once in lanes and get
//! exactly what solving them one after the other would give. Projected
//! Gauss–Seidel then runs colour after colour instead of contact after
//! contact; that is another valid order of the same iteration.
//!
//! Static and kinematic bodies do not count: the solver never changes their
//! velocity (their inverse masses are zero), so any number of constraints
//! may read them at once.
//!
//! The colouring is greedy and recomputed every step in contact order, so
//! it is deterministic (the same scene gives the same colours) and needs no
//! bookkeeping when contacts begin or end touching; it costs a few bit
//! operations per constraint (a mask of colours per body). Like Box2D, a constraint between two dynamic bodies takes
//! the first free colour among the first [`DYNAMIC_COLOURS`], one with a
//! static or kinematic body the last free colour (searching down to colour
//! 1): those are then solved last in each pass, so the ground has the last
//! word, and they fill the colours the dynamic pairs leave sparse. A
//! constraint that finds no free colour goes to the overflow list, solved
//! one at a time by the scalar solver ([`super::contact_solver`]) before
//! the colours. The revolute joints have their own colouring, where a joint
//! to the world takes the first free colour as well
//! ([`Colouring::add_in_order`]): a chain hanging from the world is then
//! solved root first, in the order added.

use super::lanes::LANES;
use crate::body::BodyId;

/// Number of colours (Box2D's `B2_GRAPH_COLOR_COUNT − 1`; its last colour
/// is the overflow, a list here).
pub(crate) const COLOURS: usize = 23;

/// Colours open to constraints between two dynamic bodies (Box2D's
/// `B2_DYNAMIC_COLOR_COUNT`): the last ones are kept for constraints with a
/// static or kinematic body.
pub(crate) const DYNAMIC_COLOURS: usize = COLOURS - 3;

/// Where the wide solver keeps a constraint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Slot {
    /// Lane `lane` of wide record `record`.
    Lane { record: usize, lane: usize },
    /// Position in the overflow list.
    Overflow(usize),
}

/// The colours of one step: per constraint (in the order they were added),
/// its colour and its position in that colour; the colours' sizes.
///
/// Colour `c` occupies the wide records from `first_record[c]` to
/// `first_record[c + 1]` (excluded), its k-th constraint in lane k mod 8
/// of record `first_record[c] + k / 8`: the records are colour after
/// colour, the solve order.
#[derive(Debug, Clone, Default)]
pub(crate) struct Colouring {
    /// Per world body, a bit per colour: set when a constraint of that
    /// colour holds the body (dynamic bodies only).
    used: Vec<u32>,
    /// Per added constraint, its colour (`COLOURS` for the overflow) and
    /// its position in it.
    placed: Vec<(u8, u32)>,
    /// Constraints per colour, then the overflow's.
    counts: [usize; COLOURS + 1],
    /// First record of each colour, and the record count at the end (set
    /// by [`Colouring::finish`]).
    first_record: [usize; COLOURS + 1],
}

/// Colours `0..DYNAMIC_COLOURS` as bits.
const DYNAMIC_MASK: u32 = (1 << DYNAMIC_COLOURS) - 1;
/// Colours `0..COLOURS` as bits.
const ALL_MASK: u32 = (1 << COLOURS) - 1;
/// Colours `1..COLOURS` as bits.
const STATIC_MASK: u32 = ((1 << COLOURS) - 1) & !1;

impl Colouring {
    /// Empties every colour, ready for `body_count` bodies (nothing is
    /// allocated once the lists have grown to the scene's size).
    pub(crate) fn clear(&mut self, body_count: usize) {
        self.used.clear();
        self.used.resize(body_count, 0);
        self.placed.clear();
        self.counts = [0; COLOURS + 1];
        self.first_record = [0; COLOURS + 1];
    }

    /// Adds the next constraint, on the dynamic bodies among `a` and `b`
    /// (`None` for a static or kinematic body; at least one is dynamic), to
    /// the first colour free of both, or to the overflow; one with a single
    /// dynamic body to the last free colour (solved last: the contacts'
    /// rule, the ground has the last word).
    #[inline]
    pub(crate) fn add(&mut self, a: Option<BodyId>, b: Option<BodyId>) {
        self.add_ordered(a, b, false);
    }

    /// Adds the next constraint like [`Colouring::add`], except that one
    /// with a single dynamic body takes the first free colour too, so that
    /// the colours keep the order added wherever they can: the joints' rule.
    /// A chain hanging from the world, added root first, is then solved
    /// root first as the scalar solver would: on the double pendulum
    /// (`scenes/double_pendulum.toml`, 20 s at 60 Hz) the root solved last
    /// doubled the energy lost (−0.19 against −0.093 m g × 1 m) and moved
    /// the rates at 1.5 s off their step-doubling estimate.
    pub(crate) fn add_in_order(&mut self, a: Option<BodyId>, b: Option<BodyId>) {
        self.add_ordered(a, b, true);
    }

    /// Inlined into the callers' loops (the contacts' colouring is serial,
    /// on the calling thread, once per touching contact): each body's mask
    /// is read once and written once, and the match on the kinds folds
    /// into the caller's.
    #[inline(always)]
    fn add_ordered(&mut self, a: Option<BodyId>, b: Option<BodyId>, in_order: bool) {
        let used = &mut self.used;
        let colour = match (a, b) {
            (Some(a), Some(b)) => {
                // The lowest colour whose bit is clear in both bodies.
                let (used_a, used_b) = (used[a], used[b]);
                let free = !(used_a | used_b) & DYNAMIC_MASK;
                if free == 0 {
                    COLOURS
                } else {
                    let c = free.trailing_zeros() as usize;
                    used[a] = used_a | 1 << c;
                    used[b] = used_b | 1 << c;
                    c
                }
            }
            (Some(one), None) | (None, Some(one)) => {
                let mask = used[one];
                let c = if in_order {
                    let free = !mask & ALL_MASK;
                    (free != 0).then(|| free.trailing_zeros() as usize)
                } else {
                    // The highest free colour, down to colour 1.
                    let free = !mask & STATIC_MASK;
                    (free != 0).then(|| 31 - free.leading_zeros() as usize)
                };
                match c {
                    Some(c) => {
                        used[one] = mask | 1 << c;
                        c
                    }
                    None => COLOURS,
                }
            }
            (None, None) => COLOURS - 1,
        };
        let position = self.counts[colour];
        self.counts[colour] += 1;
        self.placed.push((colour as u8, position as u32));
    }

    /// Lays the colours out in records once every constraint was added;
    /// returns the number of records.
    pub(crate) fn finish(&mut self) -> usize {
        let mut record = 0;
        for c in 0..COLOURS {
            self.first_record[c] = record;
            record += self.counts[c].div_ceil(LANES);
        }
        self.first_record[COLOURS] = record;
        record
    }

    /// The wide records of colour `c` (after [`Colouring::finish`]).
    pub(crate) fn records(&self, c: usize) -> std::ops::Range<usize> {
        self.first_record[c]..self.first_record[c + 1]
    }

    /// Where the `i`-th added constraint goes (after [`Colouring::finish`]).
    #[inline]
    pub(crate) fn slot(&self, i: usize) -> Slot {
        let (colour, position) = self.placed[i];
        let (colour, position) = (usize::from(colour), position as usize);
        if colour == COLOURS {
            Slot::Overflow(position)
        } else {
            Slot::Lane {
                record: self.first_record[colour] + position / LANES,
                lane: position % LANES,
            }
        }
    }

    /// The number of constraints in the overflow.
    pub(crate) fn overflow(&self) -> usize {
        self.counts[COLOURS]
    }

    /// The padding lanes, `(record, lane)`: the lanes after the last
    /// constraint of each colour in its last record.
    pub(crate) fn padding(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..COLOURS).flat_map(move |c| {
            let used = self.counts[c] % LANES;
            let last = self.first_record[c + 1].wrapping_sub(1);
            let lanes = if used == 0 { LANES..LANES } else { used..LANES };
            lanes.map(move |lane| (last, lane))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The colour of each added constraint, `None` for the overflow.
    fn colours_of(c: &Colouring) -> Vec<Option<usize>> {
        (0..c.placed.len())
            .map(|i| match c.slot(i) {
                Slot::Lane { record, .. } => Some(
                    (0..COLOURS)
                        .rfind(|&k| c.first_record[k] <= record && c.counts[k] > 0)
                        .unwrap(),
                ),
                Slot::Overflow(_) => None,
            })
            .collect()
    }

    #[test]
    fn no_record_holds_a_dynamic_body_twice() {
        // A chain of 10 bodies (pairs i, i+1) and every body on the ground.
        let mut c = Colouring::default();
        c.clear(10);
        let mut pairs = Vec::new();
        for i in 0..9 {
            pairs.push((Some(i), Some(i + 1)));
        }
        for i in 0..10 {
            pairs.push((Some(i), None));
        }
        for &(a, b) in &pairs {
            c.add(a, b);
        }
        let records = c.finish();
        assert_eq!(c.overflow(), 0);
        let mut lanes: Vec<Vec<(usize, usize)>> = vec![Vec::new(); records];
        for (i, &(a, b)) in pairs.iter().enumerate() {
            let Slot::Lane { record, lane } = c.slot(i) else {
                panic!("overflow")
            };
            for body in [a, b].into_iter().flatten() {
                assert!(
                    lanes[record].iter().all(|&(_, other)| other != body),
                    "body {body} twice in record {record}"
                );
                lanes[record].push((lane, body));
            }
        }
        // Every lane is used once; the others are padding.
        let mut taken: Vec<(usize, usize)> = (0..pairs.len())
            .map(|i| match c.slot(i) {
                Slot::Lane { record, lane } => (record, lane),
                Slot::Overflow(_) => unreachable!(),
            })
            .chain(c.padding())
            .collect();
        taken.sort();
        taken.dedup();
        assert_eq!(taken.len(), LANES * records);
        // The chain alternates between colours 0 and 1; the ground
        // contacts take the last colour, free of the chain's.
        let colours = colours_of(&c);
        assert!(colours[..9].iter().all(|&k| k == Some(0) || k == Some(1)));
        assert!(colours[9..].iter().all(|&k| k == Some(COLOURS - 1)));
    }

    #[test]
    fn a_body_in_more_pairs_than_colours_overflows() {
        // A hub touching DYNAMIC_COLOURS + 2 bodies: each pair needs its own
        // colour, so the last two overflow.
        let mut c = Colouring::default();
        let n = DYNAMIC_COLOURS + 2;
        c.clear(n + 1);
        for i in 0..n {
            c.add(Some(0), Some(i + 1));
        }
        c.finish();
        assert_eq!(c.overflow(), 2);
        assert_eq!(
            (c.slot(n - 2), c.slot(n - 1)),
            (Slot::Overflow(0), Slot::Overflow(1))
        );
        // Clearing starts afresh without the old bits.
        c.clear(n + 1);
        c.add(Some(0), Some(1));
        assert_eq!(c.finish(), 1);
        assert_eq!(c.slot(0), Slot::Lane { record: 0, lane: 0 });
        assert_eq!(c.overflow(), 0);
    }
}
