//! Contact history across particles removed between runs (`delete_atoms`), as LIGGGHTS
//! 3.8.0 carries it.
//!
//! Before deleting, LIGGGHTS moves its list's history into per-atom partner arrays (its
//! contact-history fix's `pre_exchange`), reading the list by particle slot and recording
//! each touching partner by the ID in the partner's slot (for a periodic image, its owner's
//! ID at the list build). The arrays then travel with their particles as each deleted
//! particle's slot is filled by the last one, and `compress yes` renumbers the IDs without
//! touching the recorded ones. The next list build looks each new pair up among its first
//! particle's partners by the second one's current ID, first match first. A second
//! deletion before that build reads the same, now stale, list by slot again.

use crate::engine::mirror_history::Sides;
use crate::engine::neighbor::{Mirror, Pair};

/// One recorded partner: its ID and where its values come from (from a mirror, index in
/// the old entries or mirrors, negated).
type Partner = (i64, (bool, usize, bool));

/// LIGGGHTS's partner arrays between a removal and the next list build.
#[derive(Debug, Clone, Default)]
pub struct Removal {
    /// The ID each particle slot last held (slots past the current end keep theirs).
    slot_ids: Vec<i64>,
    /// Per old list entry: its particles touched at the last force evaluation.
    touching: Vec<bool>,
    /// Per old mirror: the same.
    mirror_touching: Vec<bool>,
    /// Per particle now: its recorded partners, in LIGGGHTS's order.
    partners: Vec<Vec<Partner>>,
}

impl Removal {
    /// The partner arrays after removing the particles flagged in `remove` (each removed
    /// slot filled by the last particle): `old` is the list the last force evaluation used
    /// (`old_ids`: IDs by slot at its build), `ids` the IDs by slot before the removal,
    /// `touching` gives the old entries' and mirrors' contact flags. A second removal
    /// before the next list build continues from `earlier`.
    pub fn record(
        earlier: Option<Removal>,
        old: &Sides,
        old_ids: &[i64],
        ids: &[i64],
        remove: &[bool],
        touching: impl FnOnce() -> (Vec<bool>, Vec<bool>),
    ) -> Removal {
        let mut r = earlier.unwrap_or_else(|| {
            let (touching, mirror_touching) = touching();
            Removal {
                touching,
                mirror_touching,
                ..Removal::default()
            }
        });
        if r.slot_ids.len() < ids.len() {
            r.slot_ids.resize(ids.len(), 0);
        }
        r.slot_ids[..ids.len()].copy_from_slice(ids);
        r.partners = partners(old, &r, ids.len(), old_ids);
        let mut n = ids.len();
        for i in crate::state::particles::slots_filled_from_last(remove, n) {
            r.slot_ids[i] = r.slot_ids[n - 1];
            r.partners[i] = std::mem::take(&mut r.partners[n - 1]);
            n -= 1;
        }
        r.partners.truncate(n);
        r
    }
}

impl Removal {
    /// The particles were reordered (`order`: new index -> old index, as an atom sort):
    /// their partner arrays follow them.
    pub fn permute(&mut self, order: &[usize]) {
        let mut old = std::mem::take(&mut self.partners);
        self.partners = order
            .iter()
            .map(|&k| old.get_mut(k).map(std::mem::take).unwrap_or_default())
            .collect();
    }
}

/// The list a removal's history goes to.
pub struct NewList<'a> {
    /// Its pairs.
    pub pairs: &'a [Pair],
    /// Its mirrors (pairs across periodic faces seen from their second particle).
    pub mirrors: &'a [Mirror],
    /// Whether pairs across periodic faces have mirrors (the exact path's lists).
    pub mirrored: bool,
    /// Each particle's place in the exact path's order, where the particles are held in
    /// another (the fast path's).
    pub exact_rank: Option<&'a [f64]>,
}

/// The histories of the new entries and mirrors after a removal (`ids`: IDs by slot now;
/// `flips`: which history values are vectors that flip sign seen from the other particle).
///
/// LIGGGHTS looks a pair inside the box up from its lower slot (its half list holds each
/// such pair once, from the lower index). A list without mirrors (the fast path's) may hold
/// a pair from either side: its pairs inside the box are looked up from the lower slot too,
/// and the values turned to the entry's side, so both paths carry the same history
/// (`exact_rank`: each particle's place in the exact path's order, where the particles are
/// held in another).
pub fn carry_after_removal(
    old: &Sides,
    removal: &Removal,
    new: &NewList,
    ids: &[i64],
    flips: &[bool],
) -> (Vec<f64>, Vec<f64>) {
    let (new_pairs, new_mirrors) = (new.pairs, new.mirrors);
    let (new_mirrored, exact_rank) = (new.mirrored, new.exact_rank);
    let width = flips.len();
    let mut out = vec![0.0; new_pairs.len() * width];
    let mut out_m = vec![0.0; new_mirrors.len() * width];
    if width == 0 {
        return (out, out_m);
    }
    let fill = |dst: &mut [f64], i: u32, j: u32, from_lower: bool| {
        // the lower slot in the exact path's order (the fast path keeps its rank)
        let rank = |k: u32| exact_rank.map_or(k as f64, |r| r[k as usize]);
        let (i, j, turned) = if from_lower && rank(j) < rank(i) {
            (j, i, true)
        } else {
            (i, j, false)
        };
        let Some(list) = removal.partners.get(i as usize) else {
            return;
        };
        let key = ids[j as usize];
        let Some(&(_, (mirror, k, negated))) = list.iter().find(|p| p.0 == key) else {
            return;
        };
        let negated = negated != turned;
        let src = if mirror {
            &old.mirror_history[k * width..(k + 1) * width]
        } else {
            &old.history[k * width..(k + 1) * width]
        };
        for ((d, s), &flip) in dst.iter_mut().zip(src).zip(flips) {
            *d = if negated && flip { -s } else { *s };
        }
    };
    for (dst, p) in out.chunks_mut(width).zip(new_pairs) {
        // the fast path holds one history for both sides of a pair across a periodic face
        // too: it takes its lower side's
        let inside = p.shift == [0.0; 3];
        fill(
            dst,
            p.i,
            p.j,
            !new_mirrored && (inside || exact_rank.is_some()),
        );
    }
    for (dst, m) in out_m.chunks_mut(width).zip(new_mirrors) {
        fill(dst, m.pair.i, m.pair.j, false);
    }
    (out, out_m)
}

/// LIGGGHTS's partner arrays of the `now` slots, read from the old list in its order (each
/// slot's entries, a mirror just before the entry it precedes), partners recorded by the
/// ID in their slot (`r.slot_ids`) or, for an image, by its owner's ID at the build.
fn partners(old: &Sides, r: &Removal, now: usize, old_ids: &[i64]) -> Vec<Vec<Partner>> {
    let mut partners: Vec<Vec<Partner>> = vec![Vec::new(); now];
    let owned_key = |x: usize| r.slot_ids.get(x).copied().unwrap_or(0);
    let image_key = |x: usize| old_ids.get(x).copied().unwrap_or(0);
    let mut push = |slot: usize, partner: Partner| {
        if let Some(list) = partners.get_mut(slot) {
            list.push(partner);
        }
    };
    let mut mirrors: Vec<usize> = (0..old.mirrors.len()).collect();
    mirrors.sort_by_key(|&m| old.mirrors[m].at);
    let mut next_mirror = mirrors.iter().peekable();
    for e in 0..=old.pairs.len() {
        while let Some(&&m) = next_mirror.peek() {
            if old.mirrors[m].at as usize > e {
                break;
            }
            next_mirror.next();
            if r.mirror_touching.get(m).copied().unwrap_or(false) {
                let p = &old.mirrors[m].pair;
                push(p.i as usize, (image_key(p.j as usize), (true, m, false)));
            }
        }
        let Some(p) = old.pairs.get(e) else { break };
        if !r.touching.get(e).copied().unwrap_or(false) {
            continue;
        }
        let (i, j) = (p.i as usize, p.j as usize);
        if p.shift == [0.0; 3] {
            push(i, (owned_key(j), (false, e, false)));
            push(j, (owned_key(i), (false, e, true)));
        } else {
            // an image partner: only the owned side keeps it (without mirrors, the image's
            // owner keeps the negated values as its own)
            push(i, (image_key(j), (false, e, false)));
            if !old.mirrored {
                push(j, (image_key(i), (false, e, true)));
            }
        }
    }
    partners
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pair(i: u32, j: u32) -> Pair {
        Pair {
            i,
            j,
            shift: [0.0; 3],
        }
    }

    fn carry(
        old: &Sides,
        r: &Removal,
        p: Pair,
        mirrored: bool,
        ids: &[i64],
        flips: &[bool],
    ) -> (Vec<f64>, Vec<f64>) {
        let new = NewList {
            pairs: &[p],
            mirrors: &[],
            mirrored,
            exact_rank: None,
        };
        carry_after_removal(old, r, &new, ids, flips)
    }

    fn sides<'a>(pairs: &'a [Pair], history: &'a [f64]) -> Sides<'a> {
        Sides {
            pairs,
            mirrors: &[],
            mirrored: false,
            history,
            mirror_history: &[],
        }
    }

    #[test]
    fn partners_travel_with_their_particles_keyed_by_the_old_ids() {
        // slots 0, 1, 2 hold IDs 1, 2, 3; (0,1) and (1,2) touch with values 1 and 2
        let pairs = [pair(0, 1), pair(1, 2)];
        let old = sides(&pairs, &[1.0, 2.0]);
        // slot 0 removed: ID 3 moves into slot 0
        let r = Removal::record(
            None,
            &old,
            &[1, 2, 3],
            &[1, 2, 3],
            &[true, false, false],
            || (vec![true, true], vec![]),
        );
        // without compress: the new pair (ID 2, ID 3) finds ID 3's partner ID 2, negated
        let (h, _) = carry(&old, &r, pair(1, 0), true, &[3, 2], &[true]);
        assert_eq!(h, vec![2.0], "seen from ID 2, as its own entry (1,2)");
        let (h, _) = carry(&old, &r, pair(0, 1), true, &[3, 2], &[true]);
        assert_eq!(h, vec![-2.0], "seen from ID 3: negated");
        // compress renumbers ID 3 to 1: ID 2's partners are still recorded as 1 (the
        // deleted particle) and 3, so the pair takes the deleted particle's values
        let (h, _) = carry(&old, &r, pair(1, 0), true, &[1, 2], &[true]);
        assert_eq!(h, vec![-1.0]);
        // and the particle now called 1 (formerly 3) recorded partner 2: found
        let (h, _) = carry(&old, &r, pair(0, 1), true, &[1, 2], &[true]);
        assert_eq!(h, vec![-2.0]);
    }

    #[test]
    fn partners_follow_a_sort_of_the_particles() {
        let pairs = [pair(0, 1)];
        let old = sides(&pairs, &[3.0]);
        let mut r = remove_third(&old, true);
        // IDs 1 and 2 swap slots: the pair is found from ID 1, now in slot 1
        r.permute(&[1, 0]);
        let (h, _) = carry(&old, &r, pair(1, 0), true, &[2, 1], &[true]);
        assert_eq!(h, vec![3.0]);
        let (h, _) = carry(&old, &r, pair(0, 1), true, &[2, 1], &[true]);
        assert_eq!(h, vec![-3.0]);
    }

    /// IDs 1, 2, 3 in slots 0, 1, 2; the third removed; `touching`: whether the pair (0, 1)
    /// touched at the last evaluation.
    fn remove_third(old: &Sides, touching: bool) -> Removal {
        Removal::record(
            None,
            old,
            &[1, 2, 3],
            &[1, 2, 3],
            &[false, false, true],
            || (vec![touching], vec![]),
        )
    }

    #[test]
    fn a_list_without_mirrors_looks_pairs_up_from_the_lower_slot() {
        // (0,1) touching with value 1, recorded as ID 2 for slot 0 and negated as ID 1 for
        // slot 1; compress renumbers so slot 1's partner key 1 now names slot 0's particle
        // from both sides alike
        let pairs = [pair(0, 1)];
        let old = sides(&pairs, &[1.0]);
        let r = remove_third(&old, true);
        let (h, _) = carry(&old, &r, pair(1, 0), false, &[1, 2], &[true]);
        assert_eq!(
            h,
            vec![-1.0],
            "looked up from slot 0, turned to slot 1's side"
        );
        let (h, _) = carry(&old, &r, pair(0, 1), false, &[1, 2], &[true]);
        assert_eq!(h, vec![1.0]);
    }

    #[test]
    fn only_pairs_touching_at_the_last_evaluation_are_recorded() {
        let pairs = [pair(0, 1)];
        let old = sides(&pairs, &[4.0]);
        let r = remove_third(&old, false);
        let (h, _) = carry(&old, &r, pair(0, 1), true, &[1, 2], &[true]);
        assert_eq!(h, vec![0.0]);
    }

    #[test]
    fn a_removed_slot_is_filled_by_the_last_particle() {
        // IDs 1..5; remove slots 1 and 4: slot 1 takes the last (ID 5, itself removed),
        // then the next last (ID 4); a second removal reads slots by the IDs left there
        let old = sides(&[], &[]);
        let ids = [1, 2, 3, 4, 5];
        let r = Removal::record(
            None,
            &old,
            &ids,
            &ids,
            &[false, true, false, false, true],
            || (vec![], vec![]),
        );
        assert_eq!(r.slot_ids, vec![1, 4, 3, 4, 5]);
        assert_eq!(r.partners.len(), 3);
    }
}
