//! Neighbour lists: particles are binned in cells of the interaction cutoff, and every pair
//! closer than the cutoff plus skin is listed once (a half list) with the periodic shift
//! that brings the second particle next to the first. The list is rebuilt when a particle
//! has moved more than half the skin; between rebuilds positions are not re-wrapped, so the
//! stored shifts stay valid. Pairs come out in a fixed order for any thread count.

use crate::engine::domain::Domain;

mod history;
mod sum_order;

pub use history::carry_history;
pub(crate) use history::{ByAtom, IdIndex};
pub use sum_order::{block_starts, Incidence, SumOrder, BLOCK_PARTICLES};

/// One listed pair (laid out as written: the fast touching test reads the shift as the
/// last three of four doubles).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct Pair {
    /// Index of the first particle.
    pub i: u32,
    /// Index of the second particle (`j > i` unless the pair crosses a periodic face).
    pub j: u32,
    /// Shift added to x\[j\] to get the image nearest x\[i\] (length).
    pub shift: [f64; 3],
}

/// The second side of a listed pair across a periodic face. LIGGGHTS (newton off) lists
/// such a pair on both sides, each atom with the other's ghost image, and each side adds
/// only its own atom's force and keeps its own contact history; the exact path does the
/// same through these entries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mirror {
    /// The pair seen from its second atom (`i` is the list entry's `j`, the shift negated).
    pub pair: Pair,
    /// The list entry it mirrors.
    pub entry: u32,
    /// Its place in LIGGGHTS's order: its force is added just before list entry `at`'s
    /// (`pairs.len()`: after the last).
    pub at: u32,
}

/// A mirrored list's second sides and their contact history, for the pair pass.
pub struct Mirrored<'a> {
    /// The mirrors, ordered by `at`.
    pub mirrors: &'a [Mirror],
    /// Their contact history (`history_width` doubles per mirror).
    pub history: &'a mut [f64],
}

/// LIGGGHTS's neighbour bins (bin size about half `cutneighmax`, fitted to the box), used
/// only to order each particle's partners as LIGGGHTS's stencil walk lists them: by bin
/// (z, then y, then x) and by index within a bin. Forces on a particle are summed in its
/// partners' order, so this order keeps the round-off of LIGGGHTS's sums.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BinOrder {
    lo: [f64; 3],
    hi: [f64; 3],
    inv: [f64; 3],
    n: [i64; 3],
    cut: f64,
    /// 2d: one layer of bins in z and a stencil that stays in it.
    planar: bool,
}

impl BinOrder {
    /// Bins for the box `lo`..`hi` and LIGGGHTS's `cutneighmax` (length).
    pub fn new(lo: [f64; 3], hi: [f64; 3], cutneighmax: f64) -> BinOrder {
        BinOrder::sized(lo, hi, cutneighmax, 0.0)
    }

    /// [`BinOrder::new`] with `neigh_modify binsize` (length; 0 for half `cutneighmax`).
    pub fn sized(lo: [f64; 3], hi: [f64; 3], cutneighmax: f64, binsize: f64) -> BinOrder {
        let mut inv = [0.0; 3];
        let mut n = [1i64; 3];
        for d in 0..3 {
            let bbox = hi[d] - lo[d];
            let optimal = if binsize > 0.0 {
                binsize
            } else if cutneighmax > 0.0 {
                0.5 * cutneighmax
            } else {
                bbox
            };
            n[d] = ((bbox * (1.0 / optimal)) as i64).max(1);
            inv[d] = 1.0 / (bbox / n[d] as f64);
        }
        BinOrder {
            lo,
            hi,
            inv,
            n,
            cut: cutneighmax,
            planar: false,
        }
    }

    /// These bins as LIGGGHTS makes them in 2d: a single bin across z, the stencil flat.
    pub fn planar(mut self) -> BinOrder {
        self.planar = true;
        self.n[2] = 1;
        self.inv[2] = 1.0 / (self.hi[2] - self.lo[2]);
        self
    }

    /// Is bin `b` in LIGGGHTS's stencil around bin `a` (its bins' nearest faces closer than
    /// `cutneighmax`)? A pair farther apart than `cutneighmax` in bins beyond the stencil is
    /// never seen by LIGGGHTS, however large its radii have grown since the run started.
    pub fn in_stencil(&self, a: [i64; 3], b: [i64; 3]) -> bool {
        let mut dsq = 0.0;
        for k in 0..3 {
            // (z, y, x) order: dimension 2 - k
            let size = 1.0 / self.inv[2 - k];
            let off = b[k] - a[k];
            let d = match off {
                o if o > 0 => (o - 1) as f64 * size,
                o if o < 0 => (o + 1) as f64 * size,
                _ => 0.0,
            };
            dsq += d * d;
        }
        dsq < self.cut * self.cut
    }

    /// The bin of `x` as (z, y, x) indices (LIGGGHTS's coord2bin, before flattening).
    pub fn bin(&self, x: [f64; 3]) -> [i64; 3] {
        let mut b = [0i64; 3];
        for d in 0..3 {
            b[2 - d] = if x[d] >= self.hi[d] {
                ((x[d] - self.hi[d]) * self.inv[d]) as i64 + self.n[d]
            } else if x[d] >= self.lo[d] {
                (((x[d] - self.lo[d]) * self.inv[d]) as i64).min(self.n[d] - 1)
            } else {
                ((x[d] - self.lo[d]) * self.inv[d]) as i64 - 1
            };
        }
        b
    }
}

impl BinOrder {
    /// LIGGGHTS's stencil reach in bins along each dimension (x, y, z).
    fn reach(&self) -> [i64; 3] {
        std::array::from_fn(|d| {
            if d == 2 && self.planar {
                return 0;
            }
            let size = 1.0 / self.inv[d];
            let mut s = (self.cut * self.inv[d]) as i64;
            if (s as f64) * size < self.cut {
                // a cutoff beyond the integers (a hostile deck) saturates; the caller then
                // finds the grid too large and searches another way
                s = s.saturating_add(1);
            }
            s
        })
    }
}

/// A list entry candidate in a bin: the particle (or the periodic image of it) and the
/// image's position.
#[derive(Clone, Copy)]
struct Binned {
    j: u32,
    shift: [f64; 3],
    x: [f64; 3],
}

/// A half neighbour list.
#[derive(Debug, Clone, Default)]
pub struct NeighborList {
    /// The pairs, grouped by `i` in increasing order.
    pub pairs: Vec<Pair>,
    /// Positions at the last build (for the half-skin rebuild test).
    built_at: Vec<[f64; 3]>,
    /// Reaches (radii) at the last build (for the rebuild test when radii change).
    built_reach: Vec<f64>,
    /// Number of builds so far.
    pub builds: u64,
    /// The second sides of the pairs across periodic faces, in LIGGGHTS's order (only from
    /// the stencil walk, empty otherwise).
    pub mirrors: Vec<Mirror>,
    /// Whether the list was built with [`Self::mirrors`]: then a pair across a periodic face
    /// adds only its first atom's force, the mirror the second's.
    pub mirrored: bool,
    /// Pairs within reach that LIGGGHTS's stencil misses (particles grown beyond the run's
    /// cutoff), left out as LIGGGHTS leaves them out; counted since the last reset.
    pub missed: u64,
    /// Bin offsets and fill counters, kept between builds (a shrink-wrapped box with
    /// falling particles can hold millions of bins; allocating them anew at every build
    /// cost more time in page faults than the build itself).
    bin_start: Vec<usize>,
    bin_fill: Vec<usize>,
}

impl NeighborList {
    /// Positions of the particles when the list was last built.
    pub fn built_positions(&self) -> &[[f64; 3]] {
        &self.built_at
    }

    /// Radii (reaches) of the particles when the list was last built.
    pub fn built_reaches(&self) -> &[f64] {
        &self.built_reach
    }

    /// Take a list built elsewhere (the fast path's cell search) for positions `x` and
    /// reaches `reach`.
    pub fn assign(&mut self, pairs: Vec<Pair>, x: &[[f64; 3]], reach: &[f64]) {
        self.pairs = pairs;
        self.mirrors.clear();
        self.mirrored = false;
        self.built_at.clear();
        self.built_at.extend_from_slice(x);
        self.built_reach.clear();
        self.built_reach.extend_from_slice(reach);
        self.builds += 1;
    }

    /// Keep the listed pairs `keep` accepts (and the mirrors of the kept ones, in place).
    pub fn retain(&mut self, mut keep: impl FnMut(&Pair) -> bool) {
        if self.mirrors.is_empty() {
            self.pairs.retain(keep);
            return;
        }
        // new index of each old entry, and of the first kept entry at or after it
        let mut new_at = Vec::with_capacity(self.pairs.len() + 1);
        let mut kept = 0u32;
        let mut alive = Vec::with_capacity(self.pairs.len());
        for p in &self.pairs {
            new_at.push(kept);
            let k = keep(p);
            alive.push(k);
            kept += k as u32;
        }
        new_at.push(kept);
        self.mirrors.retain_mut(|m| {
            let live = alive[m.entry as usize] && keep(&m.pair);
            m.entry = new_at[m.entry as usize];
            m.at = new_at[m.at as usize];
            live
        });
        let mut k = 0;
        self.pairs.retain(|_| {
            k += 1;
            alive[k - 1]
        });
    }

    /// Renumber the particles of the mirrors (`new_of_old`: old index -> new index).
    pub fn renumber_mirrors(&mut self, new_of_old: &[u32]) {
        for m in &mut self.mirrors {
            m.pair.i = new_of_old[m.pair.i as usize];
            m.pair.j = new_of_old[m.pair.j as usize];
        }
    }

    /// Reorder the build positions and reaches with the particles (`order`: new index ->
    /// old index); the caller renumbers the pairs.
    pub fn permute(&mut self, order: &[usize]) {
        if self.built_at.len() == order.len() {
            self.built_at = order.iter().map(|&k| self.built_at[k]).collect();
        }
        if self.built_reach.len() == order.len() {
            self.built_reach = order.iter().map(|&k| self.built_reach[k]).collect();
        }
    }

    /// Should the list be rebuilt (LIGGGHTS `check yes`: a particle moved more than skin/2)?
    pub fn needs_rebuild(&self, x: &[[f64; 3]], skin: f64) -> bool {
        if self.built_at.len() != x.len() {
            return true;
        }
        let limit = 0.25 * skin * skin;
        x.iter().zip(&self.built_at).any(|(a, b)| {
            let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
            d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > limit
        })
    }

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
        let mut entries: Vec<(u32, [i64; 3], Binned)> = Vec::with_capacity(n + n / 4);
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
                return false;
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
        // the grid of bins (z, y, x) over every entry, with the stencil's margin
        // (saturating: bins of extreme coordinates or reach make a grid too large, refused below)
        let dims: [usize; 3] = std::array::from_fn(|k| {
            let span = hi[k].saturating_sub(lo[k]).saturating_add(1);
            span.saturating_add(sr[2 - k].saturating_mul(2)).max(1) as usize
        });
        let total = (dims[0] as u64)
            .saturating_mul(dims[1] as u64)
            .saturating_mul(dims[2] as u64);
        if total > 64 * (entries.len() as u64 + 1024) {
            return false;
        }
        let flat = |b: [i64; 3]| {
            let c: [usize; 3] = std::array::from_fn(|k| (b[k] - lo[k] + sr[2 - k]) as usize);
            (c[0] * dims[1] + c[1]) * dims[2] + c[2]
        };
        for e in entries.iter_mut() {
            e.0 = flat(e.1) as u32;
        }
        // by bin, then by particle index (images of a particle keep their creation order)
        let mut start = vec![0u32; total as usize + 1];
        for e in &entries {
            start[e.0 as usize + 1] += 1;
        }
        for k in 0..total as usize {
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
        // the stencil: bins whose nearest faces come closer than the cutoff, in (z, y, x)
        // order, as rows of consecutive bins along x (first and last offset of each row)
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
        self.pairs.clear();
        self.mirrors.clear();
        self.mirrored = (0..3).any(|d| domain.periodic(d));
        self.built_at.clear();
        self.built_at.extend_from_slice(x);
        self.built_reach.clear();
        self.built_reach.extend_from_slice(reach);
        self.builds += 1;
        // where each particle's entries start (ghost images of lower particles are found
        // in them as the entries they mirror)
        let mut first = vec![0u32; n + 1];
        for (i, &xi) in x.iter().enumerate() {
            first[i] = self.pairs.len() as u32;
            let home = flat(o.bin(xi)) as isize;
            for &(lo_bin, hi_bin) in &stencil {
                let (a, b) = ((home + lo_bin) as usize, (home + hi_bin) as usize);
                for e in &binned[start[a] as usize..start[b + 1] as usize] {
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
                    // the second side of a pair listed from ju
                    let back = e.shift.map(|v| -v);
                    let block = first[ju] as usize..first[ju + 1] as usize;
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
            first[i + 1] = self.pairs.len() as u32;
        }
        true
    }

    /// Rebuild from scratch. `reach[i]` is how far particle i interacts (its radius, for
    /// spheres); a pair is listed when its distance is below `reach[i] + reach[j] + skin`.
    /// Each particle's partners come in index order, or in LIGGGHTS's bin order if given.
    pub fn build(
        &mut self,
        x: &[[f64; 3]],
        reach: &[f64],
        skin: f64,
        domain: &Domain,
        order: Option<&BinOrder>,
    ) {
        self.pairs.clear();
        self.mirrors.clear();
        self.mirrored = false;
        self.built_at.clear();
        self.built_at.extend_from_slice(x);
        self.built_reach.clear();
        self.built_reach.extend_from_slice(reach);
        self.builds += 1;
        let n = x.len();
        if n == 0 {
            return;
        }
        let max_reach = reach.iter().copied().fold(0.0, f64::max);
        let cutoff = (2.0 * max_reach + skin).max(f64::MIN_POSITIVE);

        // bins over the particles' extent (positions may sit outside a shrink-wrapped box)
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in x {
            for d in 0..3 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
        let mut nbins = [1usize; 3];
        let mut size = [cutoff; 3];
        for d in 0..3 {
            if domain.periodic(d) {
                lo[d] = domain.lo[d];
                hi[d] = domain.hi[d];
            }
            let span = (hi[d] - lo[d]).max(0.0);
            nbins[d] = ((span / cutoff).floor() as usize).clamp(1, 1 << 10);
            size[d] = if span > 0.0 {
                span / nbins[d] as f64
            } else {
                cutoff
            };
            if size[d] < cutoff {
                nbins[d] = (nbins[d] - 1).max(1);
                size[d] = if span > 0.0 {
                    span / nbins[d] as f64
                } else {
                    cutoff
                };
            }
        }
        let bin_of = |p: &[f64; 3]| -> [usize; 3] {
            let mut b = [0usize; 3];
            for d in 0..3 {
                let k = ((p[d] - lo[d]) / size[d]).floor();
                b[d] = (k.max(0.0) as usize).min(nbins[d] - 1);
            }
            b
        };
        let flat = |b: [usize; 3]| (b[2] * nbins[1] + b[1]) * nbins[0] + b[0];
        let total = nbins[0] * nbins[1] * nbins[2];
        // counting sort of particles into bins (stable: keeps index order inside a bin)
        let mut start = std::mem::take(&mut self.bin_start);
        start.clear();
        start.resize(total + 1, 0);
        let bins: Vec<usize> = x.iter().map(|p| flat(bin_of(p))).collect();
        for &b in &bins {
            start[b + 1] += 1;
        }
        for k in 0..total {
            start[k + 1] += start[k];
        }
        let mut fill = std::mem::take(&mut self.bin_fill);
        fill.clear();
        fill.extend_from_slice(&start);
        let mut members = vec![0u32; n];
        for (i, &b) in bins.iter().enumerate() {
            members[fill[b]] = i as u32;
            fill[b] += 1;
        }

        let mut candidates: Vec<(u32, [f64; 3])> = Vec::new();
        for i in 0..n {
            let bi = bin_of(&x[i]);
            candidates.clear();
            for dz in -1i64..=1 {
                for dy in -1i64..=1 {
                    for dx in -1i64..=1 {
                        let mut b = [0usize; 3];
                        let mut shift = [0.0; 3];
                        let mut skip = false;
                        for (d, off) in [dx, dy, dz].into_iter().enumerate() {
                            let k = bi[d] as i64 + off;
                            let m = nbins[d] as i64;
                            if (0..m).contains(&k) {
                                b[d] = k as usize;
                            } else if domain.periodic(d) && m > 2 {
                                b[d] = k.rem_euclid(m) as usize;
                                shift[d] = if k < 0 {
                                    -domain.length(d)
                                } else {
                                    domain.length(d)
                                };
                            } else {
                                skip = true;
                            }
                        }
                        if skip {
                            continue;
                        }
                        let fb = flat(b);
                        for &j in &members[start[fb]..start[fb + 1]] {
                            candidates.push((j, shift));
                        }
                    }
                }
            }
            // small periodic boxes (fewer than 3 bins): take the minimum image instead
            let small_periodic = (0..3).any(|d| domain.periodic(d) && nbins[d] <= 2);
            candidates.sort_by_key(|a| a.0);
            candidates.dedup_by(|a, b| a.0 == b.0 && a.1 == b.1);
            let first = self.pairs.len();
            for &(j, mut shift) in &candidates {
                let ju = j as usize;
                // each physical pair is listed once, from its lower index
                if ju <= i {
                    continue;
                }
                let mut delta = [0.0; 3];
                for d in 0..3 {
                    delta[d] = x[ju][d] + shift[d] - x[i][d];
                }
                if small_periodic {
                    let raw = delta;
                    domain.minimum_image(&mut delta);
                    for d in 0..3 {
                        shift[d] += delta[d] - raw[d];
                    }
                }
                let cut = reach[i] + reach[ju] + skin;
                let rsq = delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2];
                if rsq < cut * cut {
                    if let Some(o) = order {
                        let xj = [0, 1, 2].map(|d| x[ju][d] + shift[d]);
                        if o.cut > 0.0
                            && rsq >= o.cut * o.cut
                            && !o.in_stencil(o.bin(x[i]), o.bin(xj))
                        {
                            self.missed += 1;
                            continue;
                        }
                    }
                    self.pairs.push(Pair {
                        i: i as u32,
                        j,
                        shift,
                    });
                }
            }
            if let Some(o) = order {
                self.pairs[first..].sort_by_cached_key(|p| {
                    let xj = x[p.j as usize];
                    (o.bin([0, 1, 2].map(|d| xj[d] + p.shift[d])), p.j)
                });
            }
        }
        self.bin_start = start;
        self.bin_fill = fill;
    }
}

#[cfg(test)]
mod tests;
