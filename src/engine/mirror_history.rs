//! Contact history across a rebuild of a list with periodic mirrors: LIGGGHTS (newton off)
//! keeps, per atom, each touching partner's history by the partner's ID. A pair inside the box
//! gives its first atom the values and its second the negated vectors; a pair across a
//! periodic face gives each atom the values of its own side (the list entry, the mirror).
//! A new entry or mirror then takes what its first atom kept for its second.

use crate::engine::neighbor::{ByAtom, Mirror, Pair};

/// One side of the old list: its pairs, mirrors, whether it was mirrored, and the histories
/// of its entries and mirrors (`flips.len()` doubles each).
pub struct Sides<'a> {
    /// The listed pairs.
    pub pairs: &'a [Pair],
    /// The mirrors.
    pub mirrors: &'a [Mirror],
    /// Whether pairs across periodic faces had mirrors (their second atoms kept the
    /// mirrors' values).
    pub mirrored: bool,
    /// History of the entries.
    pub history: &'a [f64],
    /// History of the mirrors.
    pub mirror_history: &'a [f64],
}

/// Where a new entry's history comes from: (from a mirror, index, negated).
type Source = (bool, usize, bool);

/// The histories of the new entries and mirrors (`ids`, `old_ids`: atom IDs by index now
/// and at the old build; `flips`: which history values are vectors that flip sign).
pub fn carry_mirrored(
    old: &Sides,
    new_pairs: &[Pair],
    new_mirrors: &[Mirror],
    ids: &[i64],
    old_ids: &[i64],
    flips: &[bool],
) -> (Vec<f64>, Vec<f64>) {
    use rayon::prelude::*;
    let width = flips.len();
    let mut out = vec![0.0; new_pairs.len() * width];
    let mut out_m = vec![0.0; new_mirrors.len() * width];
    if width == 0 || (old.pairs.is_empty() && old.mirrors.is_empty()) {
        return (out, out_m);
    }
    let n_old = old_ids.len();
    // old entries by their first and by their second atom, mirrors by their first
    let entries = ByAtom::new(n_old, old.pairs.iter().map(|p| p.i));
    let entries_by_j = ByAtom::new(n_old, old.pairs.iter().map(|p| p.j));
    let mirrors = ByAtom::new(n_old, old.mirrors.iter().map(|m| m.pair.i));
    let old_index = crate::engine::neighbor::IdIndex::new(old_ids);
    // the first old entry joining a to b (as its first and second atom), or b to a where
    // that side's values were the pair's (negated); else the first mirror from a to b
    let source = |a: usize, b: usize| -> Option<Source> {
        let direct = entries
            .of(a)
            .iter()
            .find(|&&k| old.pairs[k as usize].j as usize == b)
            .map(|&k| k as usize);
        let reverse = entries_by_j
            .of(a)
            .iter()
            .find(|&&k| {
                let p = &old.pairs[k as usize];
                p.i as usize == b && (p.shift == [0.0; 3] || !old.mirrored)
            })
            .map(|&k| k as usize);
        match (direct, reverse) {
            (Some(d), Some(r)) if r < d => Some((false, r, true)),
            (Some(d), _) => Some((false, d, false)),
            (None, Some(r)) => Some((false, r, true)),
            (None, None) => mirrors
                .of(a)
                .iter()
                .find(|&&k| old.mirrors[k as usize].pair.j as usize == b)
                .map(|&k| (true, k as usize, false)),
        }
    };
    let fill = |dst: &mut [f64], i: u32, j: u32| {
        let (Some(a), Some(b)) = (
            old_index.get(ids[i as usize]),
            old_index.get(ids[j as usize]),
        ) else {
            return;
        };
        let Some((mirror, k, negated)) = source(a, b) else {
            return;
        };
        let src = if mirror {
            &old.mirror_history[k * width..(k + 1) * width]
        } else {
            &old.history[k * width..(k + 1) * width]
        };
        for ((d, s), &flip) in dst.iter_mut().zip(src).zip(flips) {
            *d = if negated && flip { -s } else { *s };
        }
    };
    let chunk = 4096;
    out.par_chunks_mut(chunk * width)
        .zip(new_pairs.par_chunks(chunk))
        .for_each(|(out, new)| {
            for (dst, p) in out.chunks_mut(width).zip(new) {
                fill(dst, p.i, p.j);
            }
        });
    for (dst, m) in out_m.chunks_mut(width).zip(new_mirrors) {
        fill(dst, m.pair.i, m.pair.j);
    }
    (out, out_m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pair(i: u32, j: u32, sx: f64) -> Pair {
        Pair {
            i,
            j,
            shift: [sx, 0.0, 0.0],
        }
    }

    #[test]
    fn each_side_of_a_periodic_pair_keeps_its_own_history() {
        // atoms 0 and 1 across a periodic face, atoms 1 and 2 inside the box
        let pairs = [pair(0, 1, -1.0), pair(1, 2, 0.0)];
        let mirrors = [Mirror {
            pair: pair(1, 0, 1.0),
            entry: 0,
            at: 1,
        }];
        let old = Sides {
            pairs: &pairs,
            mirrors: &mirrors,
            mirrored: true,
            history: &[1.0, 2.0],
            mirror_history: &[3.0],
        };
        let ids = [10, 11, 12];
        // after a wrap atom 1 is listed first with atom 0 inside the box, and atom 2 with 1
        let new = [pair(1, 0, 0.0), pair(2, 1, 0.0)];
        let (h, m) = carry_mirrored(&old, &new, &[], &ids, &ids, &[true]);
        assert_eq!(h, vec![3.0, -2.0]);
        assert!(m.is_empty());
        // unchanged list: each side as it was
        let (h, m) = carry_mirrored(&old, &pairs, &mirrors, &ids, &ids, &[true]);
        assert_eq!((h, m), (vec![1.0, 2.0], vec![3.0]));
    }
}
