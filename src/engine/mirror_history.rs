//! Contact history across a rebuild of a list with periodic mirrors: LIGGGHTS (newton off)
//! keeps, per atom, each touching partner's history by the partner's ID. A pair inside the box
//! gives its first atom the values and its second the negated vectors; a pair across a
//! periodic face gives each atom the values of its own side (the list entry, the mirror).
//! A new entry or mirror then takes what its first atom kept for its second.

use std::collections::HashMap;

use crate::engine::neighbor::{Mirror, Pair};

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
    let width = flips.len();
    let mut out = vec![0.0; new_pairs.len() * width];
    let mut out_m = vec![0.0; new_mirrors.len() * width];
    if width == 0 {
        return (out, out_m);
    }
    // (atom ID, partner ID) -> (from a mirror, index, negated)
    let mut kept: HashMap<(i64, i64), (bool, usize, bool)> = HashMap::new();
    let id = |k: u32| old_ids.get(k as usize).copied();
    for (k, p) in old.pairs.iter().enumerate() {
        let (Some(a), Some(b)) = (id(p.i), id(p.j)) else {
            continue;
        };
        kept.entry((a, b)).or_insert((false, k, false));
        if p.shift == [0.0; 3] || !old.mirrored {
            kept.entry((b, a)).or_insert((false, k, true));
        }
    }
    for (k, m) in old.mirrors.iter().enumerate() {
        if let (Some(a), Some(b)) = (id(m.pair.i), id(m.pair.j)) {
            kept.entry((a, b)).or_insert((true, k, false));
        }
    }
    let fill = |dst: &mut [f64], i: u32, j: u32| {
        let Some(&(mirror, k, negated)) = kept.get(&(ids[i as usize], ids[j as usize])) else {
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
    for (dst, p) in out.chunks_mut(width).zip(new_pairs) {
        fill(dst, p.i, p.j);
    }
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
