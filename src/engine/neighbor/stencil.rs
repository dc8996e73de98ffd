//! The list built by walking LIGGGHTS's bin stencil (half/bin/newtoff): every particle and
//! periodic image binned on LIGGGHTS's grid, each particle's partners taken bin by bin
//! (z, then y, then x) and by index within a bin, the second side of a pair across a
//! periodic face kept as a [`Mirror`].

use super::{BinOrder, Binned, Mirror, NeighborList, Pair};
use crate::engine::domain::Domain;

/// A binned entry: its flat bin (filled once the grid is known), its (z, y, x) bin, and the
/// particle or image.
type Entry = (u32, [i64; 3], Binned);

/// Every particle and every periodic image within the stencil's reach `sr` (bins) of the
/// box, in particle order, and the lowest and highest (z, y, x) bins they fall in. None
/// for a position that is not finite.
fn entries(
    x: &[[f64; 3]],
    domain: &Domain,
    o: &BinOrder,
    sr: [i64; 3],
) -> Option<(Vec<Entry>, [i64; 3], [i64; 3])> {
    let n = x.len();
    let mut entries: Vec<Entry> = Vec::with_capacity(n + n / 4);
    let mut lo = [i64::MAX; 3];
    let mut hi = [i64::MIN; 3];
    let mut push = |e: Binned, lo: &mut [i64; 3], hi: &mut [i64; 3]| {
        let b = o.bin(e.x);
        // (z, y, x) indices
        for k in 0..3 {
            lo[k] = lo[k].min(b[k]);
            hi[k] = hi[k].max(b[k]);
        }
        entries.push((0, b, e));
    };
    let margin: [f64; 3] = std::array::from_fn(|d| sr[d] as f64 / o.inv[d]);
    for (j, &xj) in x.iter().enumerate() {
        if xj.iter().any(|c| !c.is_finite()) {
            return None;
        }
        // images: each periodic dimension adds the copy across the near face
        let mut images: Vec<[f64; 3]> = vec![[0.0; 3]];
        for d in 0..3 {
            if !domain.periodic(d) {
                continue;
            }
            let len = domain.length(d);
            let mut extra = Vec::new();
            for s in &images {
                if xj[d] - domain.lo[d] < margin[d] {
                    let mut t = *s;
                    t[d] = len;
                    extra.push(t);
                }
                if domain.hi[d] - xj[d] <= margin[d] {
                    let mut t = *s;
                    t[d] = -len;
                    extra.push(t);
                }
            }
            images.extend(extra);
        }
        for shift in images {
            let xs = [xj[0] + shift[0], xj[1] + shift[1], xj[2] + shift[2]];
            push(
                Binned {
                    j: j as u32,
                    shift,
                    x: xs,
                },
                &mut lo,
                &mut hi,
            );
        }
    }
    Some((entries, lo, hi))
}

/// The grid of bins (z, y, x) over every entry, with the stencil's margin.
struct Grid {
    /// The lowest bin of an entry (z, y, x).
    lo: [i64; 3],
    /// The stencil's reach in bins (x, y, z).
    sr: [i64; 3],
    /// Bins along z, y, x.
    dims: [usize; 3],
    /// All bins (saturating: bins of extreme coordinates or reach make a grid too large,
    /// which the caller refuses).
    total: u64,
}

impl Grid {
    /// The grid over the bins `lo`..=`hi` with the stencil's reach `sr`.
    fn new(lo: [i64; 3], hi: [i64; 3], sr: [i64; 3]) -> Grid {
        let dims: [usize; 3] = std::array::from_fn(|k| {
            let span = hi[k].saturating_sub(lo[k]).saturating_add(1);
            span.saturating_add(sr[2 - k].saturating_mul(2)).max(1) as usize
        });
        let total = (dims[0] as u64)
            .saturating_mul(dims[1] as u64)
            .saturating_mul(dims[2] as u64);
        Grid {
            lo,
            sr,
            dims,
            total,
        }
    }

    /// The flat index of bin `b` (z, y, x).
    fn flat(&self, b: [i64; 3]) -> usize {
        let (lo, sr, dims) = (self.lo, self.sr, self.dims);
        let c: [usize; 3] = std::array::from_fn(|k| (b[k] - lo[k] + sr[2 - k]) as usize);
        (c[0] * dims[1] + c[1]) * dims[2] + c[2]
    }

    /// The stencil: bins whose nearest faces come closer than the cutoff, in (z, y, x)
    /// order, as rows of consecutive bins along x (first and last offset of each row).
    fn stencil(&self, o: &BinOrder) -> Vec<(isize, isize)> {
        let (sr, dims) = (self.sr, self.dims);
        let mut stencil: Vec<(isize, isize)> = Vec::new();
        for dz in -sr[2]..=sr[2] {
            for dy in -sr[1]..=sr[1] {
                let row: Vec<i64> = (-sr[0]..=sr[0])
                    .filter(|&dx| o.in_stencil([0, 0, 0], [dz, dy, dx]))
                    .collect();
                if let (Some(&a), Some(&b)) = (row.first(), row.last()) {
                    let base = (dz as isize * dims[1] as isize + dy as isize) * dims[2] as isize;
                    stencil.push((base + a as isize, base + b as isize));
                }
            }
        }
        stencil
    }
}

/// The entries by bin, then by particle index (images of a particle keep their creation
/// order): where each of the `total` bins starts, and the entries in that order.
fn sort_by_bin(entries: &[Entry], total: usize) -> (Vec<u32>, Vec<Binned>) {
    let mut start = vec![0u32; total + 1];
    for e in entries {
        start[e.0 as usize + 1] += 1;
    }
    for k in 0..total {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut binned = vec![
        Binned {
            j: 0,
            shift: [0.0; 3],
            x: [0.0; 3]
        };
        entries.len()
    ];
    let mut order: Vec<usize> = (0..entries.len()).collect();
    order.sort_by_key(|&k| (entries[k].0, entries[k].2.j));
    for k in order {
        let e = &entries[k];
        binned[fill[e.0 as usize] as usize] = e.2;
        fill[e.0 as usize] += 1;
    }
    (start, binned)
}

/// The binned entries and the stencil a walk reads.
struct Walk<'a> {
    grid: &'a Grid,
    start: &'a [u32],
    binned: &'a [Binned],
    stencil: &'a [(isize, isize)],
}

impl NeighborList {
    /// Rebuild in LIGGGHTS's order by walking its bin stencil, as its half/bin/newtoff
    /// build does: each particle's partners come bin by bin (z, then y, then x) and by
    /// index within a bin, periodic partners as images in the bins beyond the box; each
    /// pair once, from its lower index. The same list as [`Self::build`] with `order`, without
    /// sorting. False (nothing changed) where that build is needed instead: periodic
    /// dimensions shorter than two cutoffs (a pair could meet through two images) or
    /// particles beyond the box's bins.
    pub fn build_stencil(
        &mut self,
        x: &[[f64; 3]],
        reach: &[f64],
        skin: f64,
        domain: &Domain,
        o: &BinOrder,
    ) -> bool {
        let n = x.len();
        // a NaN cutoff lists nothing either
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if n == 0 || !(o.cut > 0.0) {
            return false;
        }
        let sr = o.reach();
        for d in 0..3 {
            if domain.periodic(d) && domain.length(d) < 2.0 * o.cut + 1e-12 * domain.length(d) {
                return false;
            }
        }
        // every particle and every periodic image within the stencil's reach of the box
        let Some((mut entries, lo, hi)) = entries(x, domain, o, sr) else {
            return false;
        };
        let grid = Grid::new(lo, hi, sr);
        if grid.total > 64 * (entries.len() as u64 + 1024) {
            return false;
        }
        for e in entries.iter_mut() {
            e.0 = grid.flat(e.1) as u32;
        }
        let (start, binned) = sort_by_bin(&entries, grid.total as usize);
        let stencil = grid.stencil(o);
        self.start_build(x, reach, (0..3).any(|d| domain.periodic(d)));
        let walk = Walk {
            grid: &grid,
            start: &start,
            binned: &binned,
            stencil: &stencil,
        };
        self.walk(x, reach, skin, o, &walk);
        true
    }

    /// Every particle's partners from the stencil walk, with the mirrors of the pairs
    /// listed from a lower particle's image.
    fn walk(&mut self, x: &[[f64; 3]], reach: &[f64], skin: f64, o: &BinOrder, w: &Walk) {
        let n = x.len();
        // where each particle's entries start (ghost images of lower particles are found
        // in them as the entries they mirror)
        let mut first = vec![0u32; n + 1];
        for (i, &xi) in x.iter().enumerate() {
            first[i] = self.pairs.len() as u32;
            let home = w.grid.flat(o.bin(xi)) as isize;
            for &(lo_bin, hi_bin) in w.stencil {
                let (a, b) = ((home + lo_bin) as usize, (home + hi_bin) as usize);
                for e in &w.binned[w.start[a] as usize..w.start[b + 1] as usize] {
                    let ju = e.j as usize;
                    // LIGGGHTS lists every ghost image; a real particle only above i
                    let image = e.shift != [0.0; 3];
                    if ju == i || (ju < i && !image) {
                        continue;
                    }
                    let delta = [e.x[0] - xi[0], e.x[1] - xi[1], e.x[2] - xi[2]];
                    let cut = reach[i] + reach[ju] + skin;
                    let rsq = delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2];
                    let listed = rsq < cut * cut;
                    if !listed {
                        continue;
                    }
                    let pair = Pair {
                        i: i as u32,
                        j: e.j,
                        shift: e.shift,
                    };
                    if ju > i {
                        self.pairs.push(pair);
                        continue;
                    }
                    self.mirror(pair, first[ju] as usize..first[ju + 1] as usize);
                }
            }
            first[i + 1] = self.pairs.len() as u32;
        }
    }

    /// `pair`, the second side of a pair listed from its `j` (whose entries are `block`):
    /// kept as the mirror of that entry, at the list's current end.
    fn mirror(&mut self, pair: Pair, block: std::ops::Range<usize>) {
        let i = pair.i as usize;
        let back = pair.shift.map(|v| -v);
        if let Some(k) = self.pairs[block.clone()]
            .iter()
            .position(|q| q.j as usize == i && q.shift == back)
        {
            self.mirrors.push(Mirror {
                pair,
                entry: (block.start + k) as u32,
                at: self.pairs.len() as u32,
            });
        }
    }
}
