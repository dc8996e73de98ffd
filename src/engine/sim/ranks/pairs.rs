//! The pair search on a rank: every pair with an owned particle, listed by sum key (the
//! cell of a grid over the whole box, then the atom ID) so each particle sums its contacts
//! in the same order whatever the rank count.

use super::*;

/// The cells of the sum keys: a grid over the whole box (the same on every rank), in
/// row-major order (x fastest).
#[derive(Debug, Clone, Copy)]
pub(super) struct KeyGrid {
    /// Lower corner of the box (length).
    lo: [f64; 3],
    /// Cells per length along each axis (1/length).
    inv: [f64; 3],
    /// Cells along each axis.
    dims: [u64; 3],
}

impl KeyGrid {
    /// Cells about `cell` wide (length) over the box `lo`..`hi`.
    pub(super) fn new(lo: [f64; 3], hi: [f64; 3], cell: f64) -> KeyGrid {
        let dims = [0, 1, 2].map(|d| {
            let n = ((hi[d] - lo[d]) / cell).floor();
            if n.is_finite() && n >= 1.0 {
                n.min(1e5) as u64
            } else {
                1
            }
        });
        let inv = [0, 1, 2].map(|d| {
            let len = hi[d] - lo[d];
            if len > 0.0 {
                dims[d] as f64 / len
            } else {
                0.0
            }
        });
        KeyGrid { lo, inv, dims }
    }

    /// The cell of position `x` (outside the box: the nearest cell).
    pub(super) fn cell(&self, x: [f64; 3]) -> u64 {
        // a conversion truncates, which is the floor for the cells at or above zero
        let c = [0, 1, 2].map(|d| {
            let t = (x[d] - self.lo[d]) * self.inv[d];
            if t >= 0.0 {
                (t as u64).min(self.dims[d] - 1)
            } else {
                0
            }
        });
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }
}

/// Every pair closer than the radii plus `skin` with at least one owned particle (below
/// `nlocal`): owned pairs once, an owned particle and a ghost once; the lower sum key
/// (`cells`, then ID) first (an owned particle before its own periodic image), sorted by
/// the two keys, then by the positions' bits (images of one partner).
pub(super) fn rank_pairs(p: &Particles, nlocal: usize, skin: f64, cells: &[u64]) -> Vec<Pair> {
    let n = p.len().min(cells.len());
    if nlocal == 0 {
        return Vec::new();
    }
    let key = |k: usize| (cells[k], p.id[k]);
    let bins = Bins::new(p, skin);
    let mut found: Vec<Found> = Vec::with_capacity(8 * nlocal);
    for i in 0..nlocal {
        let c = bins.cell_of(p.x[i]);
        // the three cells along x of each of the nine rows around i are one run of `order`
        for m in 0..9 {
            let row = [c[1] + m % 3 - 1, c[2] + m / 3 - 1];
            for &j in bins.row_members(c[0], row) {
                let j = j as usize;
                if j == i || (j < nlocal && j < i) || j >= n {
                    continue;
                }
                let d = [0, 1, 2].map(|k| p.x[i][k] - p.x[j][k]);
                let cut = p.radius[i] + p.radius[j] + skin;
                if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < cut * cut {
                    let ghost_first = p.id[j] != p.id[i] && key(j) < key(i);
                    let (a, b) = if ghost_first { (j, i) } else { (i, j) };
                    found.push((key(a), key(b), a as u32, b as u32));
                }
            }
        }
    }
    // by the two keys; two images of one partner (the same keys) by their positions' bits
    let bits = |k: u32| p.x[k as usize].map(f64::to_bits);
    let cmp = |q: &Found, r: &Found| {
        (q.0, q.1)
            .cmp(&(r.0, r.1))
            .then_with(|| (bits(q.3), bits(q.2)).cmp(&(bits(r.3), bits(r.2))))
    };
    let pair = |q: Found| Pair {
        i: q.2,
        j: q.3,
        shift: [0.0; 3],
    };
    if !(1..nlocal).all(|k| key(k - 1) < key(k)) {
        found.sort_unstable_by(cmp);
        return found.into_iter().map(pair).collect();
    }
    // owned particles stored by key (as a build leaves them): the entries led by an owned
    // particle come in its order and need sorting only within each particle's group; those
    // led by a ghost are sorted apart and merged in
    let (mut owned, mut ghost): (Vec<Found>, Vec<Found>) =
        found.into_iter().partition(|q| (q.2 as usize) < nlocal);
    for group in owned.chunk_by_mut(|q, r| q.2 == r.2) {
        group.sort_unstable_by(cmp);
    }
    ghost.sort_unstable_by(cmp);
    let mut out = Vec::with_capacity(owned.len() + ghost.len());
    let mut rest = ghost.into_iter().peekable();
    for q in owned {
        while let Some(g) = rest.next_if(|g| cmp(g, &q).is_lt()) {
            out.push(pair(g));
        }
        out.push(pair(q));
    }
    out.extend(rest.map(pair));
    out
}

/// A listed pair as the search finds it: the sum keys of its first and second particle
/// (cell, ID) and their indices.
type Found = ((u64, i64), (u64, i64), u32, u32);

/// The particles binned in cubic cells a largest pair cutoff wide, as one array sorted by
/// cell (a counting sort), for the pair search.
struct Bins {
    /// Lower corner of cell (0, 0, 0) (length).
    lo: [f64; 3],
    /// Cell edge (length).
    cell: f64,
    /// Cells per direction.
    dims: [i64; 3],
    /// Where each cell's particles start in `order` (one more entry than cells).
    start: Vec<u32>,
    /// Particle indices, cell by cell.
    order: Vec<u32>,
}

impl Bins {
    /// Bin every particle of `p` in cells of the largest diameter plus `skin`, fewer
    /// and larger when the particles' extent would need more than eight per particle.
    fn new(p: &Particles, skin: f64) -> Bins {
        let rmax = p.radius.iter().copied().fold(0.0, f64::max);
        let mut cell = (2.0 * rmax + skin).max(f64::MIN_POSITIVE);
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for x in &p.x {
            for d in 0..3 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
        let limit = (8 * p.len()).max(64) as f64;
        let count = |cell: f64| [0, 1, 2].map(|d| ((hi[d] - lo[d]) / cell).floor() + 1.0);
        while count(cell).iter().product::<f64>() > limit {
            cell *= 2.0;
        }
        // a blown-up extent (not finite) gets one cell: the blow-up guard stops such a run
        let dims = count(cell).map(|c| {
            if c.is_finite() && c >= 1.0 {
                c as i64
            } else {
                1
            }
        });
        let mut bins = Bins {
            lo,
            cell,
            dims,
            start: Vec::new(),
            order: Vec::new(),
        };
        let total = (dims[0] * dims[1] * dims[2]) as usize;
        let index: Vec<u32> =
            p.x.iter()
                .map(|&x| bins.index(bins.cell_of(x)).unwrap_or(0) as u32)
                .collect();
        bins.start = vec![0; total + 1];
        for &c in &index {
            bins.start[c as usize + 1] += 1;
        }
        for c in 0..total {
            bins.start[c + 1] += bins.start[c];
        }
        let mut at = bins.start.clone();
        bins.order = vec![0; p.len()];
        for (j, &c) in index.iter().enumerate() {
            bins.order[at[c as usize] as usize] = j as u32;
            at[c as usize] += 1;
        }
        bins
    }

    /// The cell (possibly outside the grid) holding position `x`.
    fn cell_of(&self, x: [f64; 3]) -> [i64; 3] {
        [0, 1, 2].map(|d| {
            let t = (x[d] - self.lo[d]) / self.cell;
            // a conversion truncates: the floor at or above zero, without a library call
            if t >= 0.0 {
                t as i64
            } else {
                t.floor() as i64
            }
        })
    }

    /// The array index of cell `c`, None outside the grid.
    fn index(&self, c: [i64; 3]) -> Option<usize> {
        let inside = (0..3).all(|d| c[d] >= 0 && c[d] < self.dims[d]);
        inside.then(|| ((c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]) as usize)
    }

    /// The particles of the cells `cx - 1 ..= cx + 1` along x (those inside the grid) in
    /// row `row` (y, z), cell by cell; none when the row is outside the grid.
    fn row_members(&self, cx: i64, row: [i64; 2]) -> &[u32] {
        let (lo, hi) = ((cx - 1).max(0), (cx + 1).min(self.dims[0] - 1));
        if lo > hi {
            return &[];
        }
        match (
            self.index([lo, row[0], row[1]]),
            self.index([hi, row[0], row[1]]),
        ) {
            (Some(a), Some(b)) => &self.order[self.start[a] as usize..self.start[b + 1] as usize],
            _ => &[],
        }
    }
}

/// Does listed `pair` touch (centres closer than the radii summed)?
pub(super) fn pair_touches(p: &Particles, pair: &Pair) -> bool {
    let (i, j) = (pair.i as usize, pair.j as usize);
    let d = [0, 1, 2].map(|c| p.x[i][c] - p.x[j][c]);
    let radsum = p.radius[i] + p.radius[j];
    d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < radsum * radsum
}

#[cfg(test)]
mod tests {
    use super::super::tests::cloud;
    use super::*;

    #[test]
    fn the_cell_search_lists_every_pair_within_reach_once_by_key() {
        let p = cloud(800);
        let (nlocal, skin) = (500, 0.0005);
        let grid = KeyGrid::new([0.0; 3], [0.02, 0.02, 0.01], 0.0025);
        let cells: Vec<u64> = p.x.iter().map(|&x| grid.cell(x)).collect();
        assert_eq!(grid.dims, [8, 8, 4]);
        let key = |k: usize| (cells[k], p.id[k]);
        let pairs = rank_pairs(&p, nlocal, skin, &cells);
        let mut want = Vec::new();
        for i in 0..p.len() {
            for j in i + 1..p.len() {
                if i >= nlocal && j >= nlocal {
                    continue;
                }
                let d = [0, 1, 2].map(|k| p.x[i][k] - p.x[j][k]);
                let cut = p.radius[i] + p.radius[j] + skin;
                if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < cut * cut {
                    want.push(if key(j) < key(i) { (j, i) } else { (i, j) });
                }
            }
        }
        let mut got: Vec<(usize, usize)> =
            pairs.iter().map(|q| (q.i as usize, q.j as usize)).collect();
        let keys = |v: &[(usize, usize)]| -> Vec<((u64, i64), (u64, i64))> {
            v.iter().map(|&(a, b)| (key(a), key(b))).collect()
        };
        // listed in key order, the lower key first
        let listed = keys(&got);
        assert!(listed.windows(2).all(|w| w[0] < w[1]));
        assert!(listed.iter().all(|&(a, b)| a < b));
        got.sort_unstable();
        want.sort_unstable();
        assert!(want.len() > 1000, "{} pairs", want.len());
        assert_eq!(got, want);
        // owned particles stored by key, as a build leaves them: the same list by the merge
        let mut order: Vec<usize> = (0..nlocal).collect();
        order.sort_unstable_by_key(|&k| key(k));
        order.extend(nlocal..p.len());
        let mut q = p.clone();
        q.permute(&order);
        let cells_q: Vec<u64> = q.x.iter().map(|&x| grid.cell(x)).collect();
        let merged = rank_pairs(&q, nlocal, skin, &cells_q);
        let as_ids = |v: &[Pair], p: &Particles| -> Vec<(i64, i64)> {
            v.iter()
                .map(|e| (p.id[e.i as usize], p.id[e.j as usize]))
                .collect()
        };
        assert_eq!(as_ids(&merged, &q), as_ids(&pairs, &p));
    }
}
