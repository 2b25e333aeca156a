//! Graph colouring of the contact constraints (after Box2D v3's
//! `constraint_graph.c`): each step, every touching constraint gets a
//! colour such that no two constraints of a colour share a dynamic body.
//!
//! Why: the constraints of one colour are independent (solving one does not
//! change the velocities another reads), so the wide solver
//! ([`super::wide_solver`]) can solve four of them at once in lanes and get
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
//! the colours.

use crate::body::BodyId;

/// Number of colours (Box2D's `B2_GRAPH_COLOR_COUNT − 1`; its last colour
/// is the overflow, a list here).
pub(crate) const COLOURS: usize = 23;

/// Colours open to constraints between two dynamic bodies (Box2D's
/// `B2_DYNAMIC_COLOR_COUNT`): the last ones are kept for constraints with a
/// static or kinematic body.
pub(crate) const DYNAMIC_COLOURS: usize = COLOURS - 3;

/// The colours of one step: per colour, the items (contact indices) it
/// holds, in the order they were added; and the overflow.
#[derive(Debug, Default)]
pub(crate) struct Colouring {
    /// Per world body, a bit per colour: set when a constraint of that
    /// colour holds the body (dynamic bodies only).
    used: Vec<u32>,
    /// Per colour, its items.
    pub colours: Vec<Vec<usize>>,
    /// Items that found no free colour.
    pub overflow: Vec<usize>,
}

/// Colours `0..DYNAMIC_COLOURS` as bits.
const DYNAMIC_MASK: u32 = (1 << DYNAMIC_COLOURS) - 1;
/// Colours `1..COLOURS` as bits.
const STATIC_MASK: u32 = ((1 << COLOURS) - 1) & !1;

impl Colouring {
    /// Empties every colour, ready for `body_count` bodies (nothing is
    /// allocated once the lists have grown to the scene's size).
    pub(crate) fn clear(&mut self, body_count: usize) {
        self.used.clear();
        self.used.resize(body_count, 0);
        self.colours.resize_with(COLOURS, Vec::new);
        for list in &mut self.colours {
            list.clear();
        }
        self.overflow.clear();
    }

    /// Adds `item`, a constraint on the dynamic bodies among `a` and `b`
    /// (`None` for a static or kinematic body; at least one is dynamic),
    /// to the first colour free of both, or to the overflow.
    pub(crate) fn add(&mut self, item: usize, a: Option<BodyId>, b: Option<BodyId>) {
        let colour = match (a, b) {
            (Some(a), Some(b)) => {
                // The lowest colour whose bit is clear in both bodies.
                let free = !(self.used[a] | self.used[b]) & DYNAMIC_MASK;
                (free != 0).then(|| free.trailing_zeros() as usize)
            }
            (Some(one), None) | (None, Some(one)) => {
                // The highest free colour, down to colour 1.
                let free = !self.used[one] & STATIC_MASK;
                (free != 0).then(|| 31 - free.leading_zeros() as usize)
            }
            (None, None) => Some(COLOURS - 1),
        };
        match colour {
            Some(c) => {
                for body in [a, b].into_iter().flatten() {
                    self.used[body] |= 1 << c;
                }
                self.colours[c].push(item);
            }
            None => self.overflow.push(item),
        }
    }

    /// The colours' items, colour after colour (the solve order).
    pub(crate) fn in_order(&self) -> impl Iterator<Item = &[usize]> {
        self.colours.iter().map(Vec::as_slice)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The colour of each item, `None` for the overflow.
    fn colours_of(c: &Colouring, items: usize) -> Vec<Option<usize>> {
        (0..items)
            .map(|item| c.colours.iter().position(|list| list.contains(&item)))
            .collect()
    }

    #[test]
    fn no_colour_holds_a_dynamic_body_twice() {
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
        for (item, &(a, b)) in pairs.iter().enumerate() {
            c.add(item, a, b);
        }
        assert!(c.overflow.is_empty());
        for list in &c.colours {
            let mut seen = Vec::new();
            for &item in list {
                for body in [pairs[item].0, pairs[item].1].into_iter().flatten() {
                    assert!(!seen.contains(&body), "body {body} twice in a colour");
                    seen.push(body);
                }
            }
        }
        // The chain alternates between colours 0 and 1; the ground
        // contacts take the last colour, free of the chain's.
        let colours = colours_of(&c, pairs.len());
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
            c.add(i, Some(0), Some(i + 1));
        }
        assert_eq!(c.overflow, [n - 2, n - 1]);
        // Clearing starts afresh without the old bits.
        c.clear(n + 1);
        c.add(0, Some(0), Some(1));
        assert_eq!(c.colours[0], [0]);
        assert!(c.overflow.is_empty());
    }
}
