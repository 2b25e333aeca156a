//! Islands of touching dynamic bodies, kept persistently, and the sleeping
//! of islands at rest (after Box2D v3's `island.c`).
//!
//! Two dynamic bodies that begin touching merge their islands (the smaller
//! into the larger, so a body changes island O(log n) times at most). A
//! contact that stops touching only marks its island as maybe split: the
//! island is split into its connected parts when it wants to sleep, the
//! only time the split matters. Static and kinematic bodies belong to no
//! island (they do not carry an impulse from one body to another).
//!
//! An island sleeps when every one of its bodies has moved slower than the
//! sleep threshold for the time to sleep: its bodies are no longer
//! integrated, collided or solved, until a moving body begins touching one
//! of them. Islands are kept only while sleeping is on.

use crate::body::BodyId;

/// No island.
const NONE: u32 = u32::MAX;

#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Island {
    bodies: Vec<BodyId>,
    /// Contacts inside it that stopped touching since it was built.
    removals: u32,
    asleep: bool,
}

/// The islands of a world's dynamic bodies.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Islands {
    island_of: Vec<u32>,
    islands: Vec<Island>,
    free: Vec<u32>,
    // Scratch for splitting.
    #[cfg_attr(feature = "serde", serde(skip))]
    parent: Vec<usize>,
}

impl Islands {
    /// Registers body `id` (the next one): a dynamic body gets an island of
    /// its own.
    pub(crate) fn add_body(&mut self, id: BodyId, dynamic: bool) {
        debug_assert_eq!(id, self.island_of.len());
        self.island_of.push(NONE);
        if dynamic {
            let island = self.new_island();
            self.islands[island].bodies.push(id);
            self.island_of[id] = island as u32;
        }
    }

    fn new_island(&mut self) -> usize {
        match self.free.pop() {
            Some(i) => i as usize,
            None => {
                self.islands.push(Island::default());
                self.islands.len() - 1
            }
        }
    }

    /// The island of a dynamic body.
    pub(crate) fn island(&self, id: BodyId) -> Option<usize> {
        let i = self.island_of[id];
        (i != NONE).then_some(i as usize)
    }

    /// Two dynamic bodies began touching: one island.
    pub(crate) fn link(&mut self, a: BodyId, b: BodyId) {
        let (Some(ia), Some(ib)) = (self.island(a), self.island(b)) else {
            return;
        };
        if ia == ib {
            return;
        }
        let (big, small) = if self.islands[ia].bodies.len() >= self.islands[ib].bodies.len() {
            (ia, ib)
        } else {
            (ib, ia)
        };
        let moved = std::mem::take(&mut self.islands[small].bodies);
        for &body in &moved {
            self.island_of[body] = big as u32;
        }
        self.islands[big].bodies.extend_from_slice(&moved);
        self.islands[big].removals += self.islands[small].removals;
        self.islands[small] = Island {
            bodies: moved,
            ..Island::default()
        };
        self.islands[small].bodies.clear();
        self.free.push(small as u32);
    }

    /// Two dynamic bodies stopped touching: their island may have split.
    pub(crate) fn unlink(&mut self, a: BodyId) {
        if let Some(i) = self.island(a) {
            self.islands[i].removals += 1;
        }
    }

    /// The bodies of island `i`.
    pub(crate) fn bodies(&self, i: usize) -> &[BodyId] {
        &self.islands[i].bodies
    }

    /// Takes body `id` out of its island (the body was removed).
    pub(crate) fn remove_body(&mut self, id: BodyId) {
        if let Some(i) = self.island(id) {
            self.islands[i].bodies.retain(|&b| b != id);
            self.islands[i].removals += 1;
            self.island_of[id] = NONE;
        }
    }

    /// Body `id`'s kind changed: out of its island, and into one of its
    /// own if it is now `dynamic`.
    pub(crate) fn reset_body(&mut self, id: BodyId, dynamic: bool) {
        self.remove_body(id);
        if dynamic {
            let island = self.new_island();
            self.islands[island].bodies.push(id);
            self.island_of[id] = island as u32;
        }
    }

    /// The islands in use (with at least one body): index, bodies, asleep.
    pub(crate) fn in_use(&self) -> impl Iterator<Item = (usize, &[BodyId], bool)> + '_ {
        self.islands
            .iter()
            .enumerate()
            .filter(|(_, island)| !island.bodies.is_empty())
            .map(|(i, island)| (i, island.bodies.as_slice(), island.asleep))
    }

    pub(crate) fn set_asleep(&mut self, i: usize, asleep: bool) {
        self.islands[i].asleep = asleep;
    }

    /// The awake islands in use whose every body satisfies `at_rest`.
    /// Islands with removed contacts are split first, so that only the
    /// parts really at rest are returned. `touching` lists the pairs of
    /// dynamic bodies in contact now.
    pub(crate) fn resting(
        &mut self,
        at_rest: impl Fn(BodyId) -> bool,
        touching: &[(BodyId, BodyId)],
        out: &mut Vec<usize>,
    ) {
        out.clear();
        for i in 0..self.islands.len() {
            let island = &self.islands[i];
            if island.asleep || island.bodies.is_empty() {
                continue;
            }
            if !island.bodies.iter().all(|&b| at_rest(b)) {
                continue;
            }
            if island.removals > 0 {
                let first_new = self.islands.len();
                self.split(i, touching);
                // The parts are all at rest: the whole was.
                out.push(i);
                out.extend(first_new..self.islands.len());
            } else {
                out.push(i);
            }
        }
    }

    /// Splits island `i` into its connected parts (union–find over the
    /// touching pairs); `i` keeps the first part, new islands the others.
    fn split(&mut self, i: usize, touching: &[(BodyId, BodyId)]) {
        let bodies = std::mem::take(&mut self.islands[i].bodies);
        self.parent.clear();
        self.parent.extend(0..bodies.len());
        // Local index of each body: its position in `bodies`, found through
        // a temporary mark in `island_of`.
        for (k, &b) in bodies.iter().enumerate() {
            self.island_of[b] = NONE - 1 - k as u32;
        }
        let local = |island_of: &[u32], b: BodyId| {
            let v = island_of[b];
            (v < NONE && v >= NONE - bodies.len() as u32).then(|| (NONE - 1 - v) as usize)
        };
        fn root(parent: &mut [usize], mut x: usize) -> usize {
            while parent[x] != x {
                parent[x] = parent[parent[x]];
                x = parent[x];
            }
            x
        }
        for &(a, b) in touching {
            if let (Some(la), Some(lb)) = (local(&self.island_of, a), local(&self.island_of, b)) {
                let (ra, rb) = (root(&mut self.parent, la), root(&mut self.parent, lb));
                if ra != rb {
                    self.parent[ra.max(rb)] = ra.min(rb);
                }
            }
        }
        // Part of each root: the root of body 0 stays in island i.
        let mut part_island = vec![NONE; bodies.len()];
        for (k, &body) in bodies.iter().enumerate() {
            let r = root(&mut self.parent, k);
            if part_island[r] == NONE {
                part_island[r] = if r == root(&mut self.parent, 0) {
                    i as u32
                } else {
                    let j = self.new_island();
                    j as u32
                };
            }
            let island = part_island[r];
            self.islands[island as usize].bodies.push(body);
            self.island_of[body] = island;
        }
        self.islands[i].removals = 0;
    }
}

impl super::SoftStep {
    /// The islands, read-only (for `World::islands`).
    pub(crate) fn islands(&self) -> &Islands {
        &self.islands
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linking_merges_and_splitting_separates() {
        let mut islands = Islands::default();
        for id in 0..5 {
            islands.add_body(id, id != 4);
        }
        islands.link(0, 1);
        islands.link(1, 2);
        islands.link(0, 4); // 4 is static: no island
        assert_eq!(islands.island(0), islands.island(2));
        assert_ne!(islands.island(0), islands.island(3));
        assert_eq!(islands.island(4), None);
        // 1–2 stopped touching: only 0–1 remains.
        islands.unlink(1);
        let mut out = Vec::new();
        islands.resting(|_| true, &[(0, 1)], &mut out);
        let i0 = islands.island(0).unwrap();
        assert_eq!(islands.island(1), Some(i0));
        assert_ne!(islands.island(2), Some(i0));
        let mut bodies: Vec<usize> = out
            .iter()
            .flat_map(|&i| islands.bodies(i).to_vec())
            .collect();
        bodies.sort();
        assert_eq!(bodies, [0, 1, 2, 3]);
    }

    #[test]
    fn an_island_with_a_moving_body_is_not_resting() {
        let mut islands = Islands::default();
        for id in 0..3 {
            islands.add_body(id, true);
        }
        islands.link(0, 1);
        let mut out = Vec::new();
        islands.resting(|b| b != 1, &[(0, 1)], &mut out);
        assert_eq!(out, [islands.island(2).unwrap()]);
    }
}
