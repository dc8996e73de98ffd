//! Contact history carried across a rebuild of the pair list, matched by atom IDs.

use super::Pair;

/// Carry per-pair contact history from the old pair list to the new one, matching pairs by
/// the atom IDs they join, as LIGGGHTS matches contact partners by tag: a pair keeps its
/// history when one of its atoms is wrapped across a periodic face. Only if the same two
/// atoms touch through two images (a box narrower than two diameters) does the periodic
/// shift decide. Pairs not in the old list start at zero, and so do those `keep` turns down
/// (they are not looked up). Runs in parallel over the new pairs with the same result for
/// any number of threads.
pub fn carry_history(
    old_pairs: &[Pair],
    old_history: &[f64],
    new_pairs: &[Pair],
    ids: &[i64],
    old_ids: &[i64],
    flips: &[bool],
    keep: impl Fn(&Pair) -> bool + Sync,
) -> Vec<f64> {
    let width = flips.len();
    let mut out = vec![0.0; new_pairs.len() * width];
    if width == 0 || old_pairs.is_empty() {
        return out;
    }
    // old entries grouped by their first atom (old index)
    let by_first = ByAtom::new(old_ids.len(), old_pairs.iter().map(|p| p.i));
    let old_index = IdIndex::new(old_ids);
    // the periodic shift seen from the lower ID to the higher one
    let oriented = |p: &Pair, ids: &[i64]| {
        let sign = if ids[p.i as usize] <= ids[p.j as usize] {
            1.0
        } else {
            -1.0
        };
        p.shift.map(|v| (v * sign + 0.0).to_bits())
    };
    let shards = crate::util::team::Shards::new(&mut out);
    crate::util::team::stage_chunks(new_pairs.len(), 4096, true, |_, r| {
        // SAFETY: the chunks of a stage are disjoint
        let out = unsafe { shards.range(r.start * width..r.end * width) };
        let new = &new_pairs[r];
        let mut found: Vec<(usize, bool)> = Vec::new();
        for (k, p) in new.iter().enumerate() {
            if !keep(p) {
                continue;
            }
            let (Some(a), Some(b)) = (
                old_index.get(ids[p.i as usize]),
                old_index.get(ids[p.j as usize]),
            ) else {
                continue;
            };
            found.clear();
            for (from, to, swapped) in [(a, b, false), (b, a, true)] {
                for &e in by_first.of(from) {
                    if old_pairs[e as usize].j as usize == to {
                        found.push((e as usize, swapped));
                    }
                }
            }
            let pick = match found.len() {
                0 => continue,
                1 => found[0],
                _ => {
                    let want = oriented(p, ids);
                    match found
                        .iter()
                        .find(|f| oriented(&old_pairs[f.0], old_ids) == want)
                    {
                        Some(f) => *f,
                        None => continue,
                    }
                }
            };
            let src = &old_history[pick.0 * width..(pick.0 + 1) * width];
            let dst = &mut out[k * width..(k + 1) * width];
            dst.copy_from_slice(src);
            if pick.1 {
                // the pair is seen from the other particle now: vectors flip sign
                for (v, &flip) in dst.iter_mut().zip(flips) {
                    if flip {
                        *v = -*v;
                    }
                }
            }
        }
    });
    out
}

/// Indices of items grouped by an atom index below `n`, each group ascending (items naming
/// an atom at or beyond `n`, gone since, are kept apart in a last group).
pub(crate) struct ByAtom {
    start: Vec<u32>,
    items: Vec<u32>,
}

impl ByAtom {
    /// Group the items (numbered in iteration order) by their atom index.
    pub(crate) fn new(n: usize, atoms: impl Iterator<Item = u32> + Clone) -> ByAtom {
        let firsts = atoms.map(move |i| (i as usize).min(n) as u32);
        let mut start = vec![0u32; n + 2];
        for i in firsts.clone() {
            start[i as usize + 1] += 1;
        }
        for k in 0..=n {
            start[k + 1] += start[k];
        }
        let mut fill = start.clone();
        let mut items = vec![0u32; start[n + 1] as usize];
        for (k, i) in firsts.enumerate() {
            items[fill[i as usize] as usize] = k as u32;
            fill[i as usize] += 1;
        }
        ByAtom { start, items }
    }

    /// The items of atom `i`, ascending.
    pub(crate) fn of(&self, i: usize) -> &[u32] {
        &self.items[self.start[i] as usize..self.start[i + 1] as usize]
    }
}

/// Atom ID to index: a table when IDs are dense, a hash map otherwise.
pub(crate) enum IdIndex {
    Dense(Vec<u32>),
    Sparse(std::collections::HashMap<i64, u32>),
}

impl IdIndex {
    /// The index of each ID in `ids`.
    pub(crate) fn new(ids: &[i64]) -> IdIndex {
        let max = ids.iter().copied().max().unwrap_or(0);
        let min = ids.iter().copied().min().unwrap_or(0);
        if min >= 0 && (max as u64) < 4 * ids.len() as u64 + 1024 {
            let mut t = vec![u32::MAX; max as usize + 1];
            for (k, &id) in ids.iter().enumerate() {
                t[id as usize] = k as u32;
            }
            IdIndex::Dense(t)
        } else {
            IdIndex::Sparse(
                ids.iter()
                    .enumerate()
                    .map(|(k, &id)| (id, k as u32))
                    .collect(),
            )
        }
    }

    /// The index of `id`, if listed.
    #[inline]
    pub(crate) fn get(&self, id: i64) -> Option<usize> {
        match self {
            IdIndex::Dense(t) => {
                let k = *t.get(usize::try_from(id).ok()?)?;
                (k != u32::MAX).then_some(k as usize)
            }
            IdIndex::Sparse(m) => m.get(&id).map(|&k| k as usize),
        }
    }
}
