//! Contact history between the pair list and the particles (LIGGGHTS's contact-history
//! fix before and after a migration): before particles move, each listed pair's history is
//! written into the partner lists of its particles on this rank (seen from each of them);
//! after the new list is built, each pair takes its history back from the list of one of
//! its owned particles. A particle's list moves with it ([`super::migrate`]).

use crate::engine::decomp::pack::PartnerHistory;
use crate::engine::neighbor::Pair;

/// The history values seen from the pair's other particle: the values `flips` marks (the
/// vectors) change sign.
fn flipped(values: &[f64], flips: &[bool]) -> Vec<f64> {
    values
        .iter()
        .zip(flips)
        .map(|(&v, &f)| if f { -v } else { v })
        .collect()
}

impl PartnerHistory {
    /// Partner lists of the owned particles (indices below `nlocal`) from a pair list and
    /// its history (`flips.len()` values per pair, seen from the pair's first particle):
    /// each pair is recorded on its first particle and, flipped, on its second, whichever
    /// of them this rank owns. Pairs with zero history (no contact) are left out.
    pub fn from_pairs(
        pairs: &[Pair],
        history: &[f64],
        ids: &[i64],
        nlocal: usize,
        flips: &[bool],
    ) -> PartnerHistory {
        let width = flips.len();
        let mut h = PartnerHistory::new(width, nlocal);
        if width == 0 {
            return h;
        }
        for (k, p) in pairs.iter().enumerate() {
            let values = &history[k * width..(k + 1) * width];
            if values.iter().all(|&v| v == 0.0) {
                continue;
            }
            let (i, j) = (p.i as usize, p.j as usize);
            if i < nlocal {
                h.insert(i, ids[j], values);
            }
            if j < nlocal {
                h.insert(j, ids[i], &flipped(values, flips));
            }
        }
        h
    }

    /// History of each pair of a new list (seen from its first particle), from the partner
    /// list of its first particle if owned (below `nlocal`), else of its second, flipped;
    /// zeros for pairs not in contact before. If two images of the same partner touch one
    /// particle (a box narrower than two diameters), both get the first record. `flips` as
    /// for [`Self::from_pairs`].
    pub fn to_pairs(&self, pairs: &[Pair], ids: &[i64], nlocal: usize, flips: &[bool]) -> Vec<f64> {
        let width = self.width;
        let mut out = vec![0.0; pairs.len() * width];
        if width == 0 {
            return out;
        }
        for (k, p) in pairs.iter().enumerate() {
            let (i, j) = (p.i as usize, p.j as usize);
            let dst = &mut out[k * width..(k + 1) * width];
            if i < nlocal {
                if let Some(v) = self.get(i, ids[j]) {
                    dst.copy_from_slice(v);
                }
            } else if j < nlocal {
                if let Some(v) = self.get(j, ids[i]) {
                    dst.copy_from_slice(&flipped(v, flips));
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::neighbor::carry_history;

    fn pair(i: u32, j: u32) -> Pair {
        Pair {
            i,
            j,
            shift: [0.0; 3],
        }
    }

    #[test]
    fn through_the_partner_lists_as_the_serial_carry() {
        let flips = [true, false, true];
        let ids = [10, 20, 30, 40];
        let old = [pair(0, 1), pair(1, 2), pair(0, 2), pair(2, 3)];
        let hist = [
            1.0, 2.0, 3.0, //
            4.0, 5.0, 6.0, //
            -7.0, 8.0, 0.5, //
            0.0, 0.0, 0.0,
        ];
        // new list: one pair turned round, one gone, one new
        let new = [pair(1, 0), pair(1, 2), pair(3, 0), pair(2, 0)];
        let serial = carry_history(&old, &hist, &new, &ids, &ids, &flips, |_| true);
        let lists = PartnerHistory::from_pairs(&old, &hist, &ids, 4, &flips);
        assert_eq!(lists.get(2, 10), Some(&[7.0, 8.0, -0.5][..]));
        assert_eq!(lists.get(3, 30), None);
        let back = lists.to_pairs(&new, &ids, 4, &flips);
        assert_eq!(back, serial);
        assert_eq!(&back[..3], &[-1.0, 2.0, -3.0]);
        // a ghost first (index 4 copies ID 20 and is not owned): the owned side's list
        let ids5 = [10, 20, 30, 40, 20];
        let ghost_first = lists.to_pairs(&[pair(4, 0)], &ids5, 4, &flips);
        assert_eq!(ghost_first, vec![-1.0, 2.0, -3.0]);
    }
}
