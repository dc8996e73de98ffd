//! The per-particle wall contacts `fix multicontact/halfspace` gathers for one primitive wall
//! or one mesh (LIGGGHTS's `contactproperty/atom/wall` fixes `multicontactData_<ID>`).
//!
//! LIGGGHTS keeps them in one run of memory: at each rebuild every particle, in atom
//! order, reserves as many slots as it may need (one for a primitive wall it is near, one
//! per listed triangle of a mesh) right after the particle before it. A particle adds its
//! contacts of the evaluation from the start of its reservation on, so one that adds more
//! than it reserved (a particle that came near a primitive wall after the rebuild) writes
//! into the slots of the next particle with a reservation, which then overwrites them with
//! its own. The wall force loop finds a particle's radius change at a wall by scanning its
//! reservation for the partner: as many slots as the particle would reserve now, whatever
//! was last written there (slots are reset only at rebuilds). [`WallStore`] keeps this
//! layout, so the half-space step and the wall loops read the same values as LIGGGHTS.
//!
//! The store lays itself out anew at the first evaluation after each pair-list build of a
//! run, and once more after the run's setup evaluation has gathered and changed its
//! entries (LIGGGHTS's store clears itself in its own setup, after the fix's pass): the
//! walls of a setup evaluation find no radius change.

use std::collections::HashMap;

use crate::engine::contact::multicontact::Entry;

/// One wall's (or one mesh's) gathered contacts: the partner (1 for a primitive wall, the
/// triangle ID for a mesh) and entry of each slot, and each particle's reservation.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WallStore {
    /// Atom IDs of the particles, in index order, that `start` and `count` belong to.
    ids: Vec<i64>,
    /// Each particle's first slot.
    start: Vec<usize>,
    /// Each particle's entries added this evaluation.
    count: Vec<usize>,
    /// The first slot after the last reservation.
    end: usize,
    /// Partner of each slot (-1: reset at a rebuild; 0 where never written).
    partner: Vec<i32>,
    /// Entry of each slot: surface position (m) and normal force (N), after the half-space
    /// step the radius change (m).
    data: Vec<Entry>,
    /// Laid out anew at the next evaluation (a new store).
    pending: bool,
    /// The pair-list build of the last evaluation.
    last_build: Option<u64>,
}

impl WallStore {
    /// An empty store; its first evaluation rebuilds it.
    pub fn new() -> Self {
        WallStore {
            pending: true,
            ..WallStore::default()
        }
    }

    /// Does the evaluation after pair-list build `build` rebuild the reservations? At the
    /// first evaluation of a new store and at each step after a list rebuild during a run
    /// (`setup`: the run's setup evaluation, whose own list build does not count).
    pub fn due(&mut self, build: u64, setup: bool) -> bool {
        let due = self.pending || (!setup && self.last_build != Some(build));
        self.pending = false;
        self.last_build = Some(build);
        due
    }

    /// Start an evaluation: no particle has entries. Records follow the particles by atom
    /// ID (`ids` in index order); with `rebuild`, particle `i` reserves `reserve(i)` slots,
    /// in index order, and its slots are reset.
    pub fn clear(&mut self, ids: &[i64], rebuild: bool, reserve: impl Fn(usize) -> usize) {
        if self.ids != ids {
            let at: HashMap<i64, usize> = self
                .ids
                .iter()
                .zip(&self.start)
                .map(|(&id, &s)| (id, s))
                .collect();
            self.start = ids
                .iter()
                .map(|id| at.get(id).copied().unwrap_or(self.end))
                .collect();
            self.ids = ids.to_vec();
        }
        self.count.clear();
        self.count.resize(ids.len(), 0);
        if !rebuild {
            return;
        }
        let mut next = 0;
        for i in 0..ids.len() {
            let n = reserve(i);
            self.start[i] = next;
            self.grow(next + n);
            self.partner[next..next + n].fill(-1);
            self.data[next..next + n].fill([0.0; 4]);
            next += n;
        }
        self.end = next;
    }

    /// Make room for slots up to `len` (fresh slots hold zeros).
    fn grow(&mut self, len: usize) {
        if self.partner.len() < len {
            self.partner.resize(len, 0);
            self.data.resize(len, [0.0; 4]);
        }
    }

    /// Add a contact of particle `i` with `partner`: the next slot from its start.
    pub fn add(&mut self, i: usize, partner: i32, entry: Entry) {
        let at = self.start[i] + self.count[i];
        self.grow(at + 1);
        self.partner[at] = partner;
        self.data[at] = entry;
        self.count[i] += 1;
    }

    /// The slots of particle `i`'s entries of this evaluation.
    pub fn slots(&self, i: usize) -> std::ops::Range<usize> {
        let s = self.start.get(i).copied().unwrap_or(self.end);
        s..s + self.count.get(i).copied().unwrap_or(0)
    }

    /// The entry in slot `k`.
    pub fn entry(&self, k: usize) -> Entry {
        self.data[k]
    }

    /// Set the radius change (m) in slot `k`, in place of the force.
    pub fn set_change(&mut self, k: usize, change: f64) {
        self.data[k][3] = change;
    }

    /// The radius change (m) of particle `i` at its contact with `partner`, looked up in the
    /// first `scan` slots from its start (None: no such slot).
    pub fn change(&self, i: usize, partner: i32, scan: usize) -> Option<f64> {
        let s = *self.start.get(i)?;
        (s..s + scan)
            .take_while(|&k| k < self.partner.len())
            .find(|&k| self.partner[k] == partner)
            .map(|k| self.data[k][3])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_particle_without_a_reservation_shares_the_next_ones_slot() {
        let mut s = WallStore::new();
        assert!(s.due(1, true), "a new store is laid out at setup");
        // particles 0 and 2 near the wall, 1 not
        s.clear(&[10, 11, 12], true, |i| usize::from(i != 1));
        s.add(0, 1, [1.0, 0.0, 0.0, 5.0]);
        s.add(1, 1, [2.0, 0.0, 0.0, 6.0]);
        assert_eq!(s.slots(1), 1..2);
        s.add(2, 1, [3.0, 0.0, 0.0, 7.0]);
        // particle 1's entry now reads particle 2's values
        assert_eq!(s.entry(s.slots(1).start), [3.0, 0.0, 0.0, 7.0]);
        s.set_change(1, 0.25);
        assert_eq!(s.change(2, 1, 1), Some(0.25));
        assert_eq!(
            s.change(1, 1, 0),
            None,
            "scans only what it would reserve now"
        );
        assert_eq!(s.change(1, 1, 1), Some(0.25));
        // the next evaluation keeps slots until a rebuild; records follow the atoms
        assert!(!s.due(1, false));
        s.clear(&[12, 10, 11], false, |_| 0);
        assert_eq!(s.change(0, 1, 1), Some(0.25), "atom 12 keeps its slot");
        assert_eq!(s.change(1, 1, 1), Some(5.0));
        assert!(s.due(2, false), "a new list build rebuilds");
        assert!(!s.due(3, true), "a setup's own build does not");
    }
}
