//! The list built from cells of the interaction cutoff: particles sorted into cells over
//! their extent (the box across periodic dimensions), each particle's candidates taken
//! from its cell and the 26 around it, every pair within reach listed once from its lower
//! index; optionally ordered as LIGGGHTS's stencil walk lists them.

use super::{BinOrder, NeighborList, Pair};
use crate::engine::domain::Domain;

/// Cells of at least the cutoff over the particles' extent.
struct Cells {
    /// Lower corner (length).
    lo: [f64; 3],
    /// Cell edge lengths (length).
    size: [f64; 3],
    /// Cells along x, y, z.
    nbins: [usize; 3],
}

impl Cells {
    /// Cells of at least `cutoff` (length) over the positions `x` (positions may sit
    /// outside a shrink-wrapped box) and the box across periodic dimensions.
    fn new(x: &[[f64; 3]], cutoff: f64, domain: &Domain) -> Cells {
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
        // particles flung far apart (a run blowing up, a huge time step) would ask for up
        // to 2^30 cells: coarsen the widest non-periodic dimensions until there are at
        // most a few cells per particle (cells only gather candidates; the pairs found do
        // not depend on their size)
        let limit = (8 * x.len()).max(1 << 15);
        while nbins.iter().product::<usize>() > limit {
            let widest = (0..3)
                .filter(|&d| !domain.periodic(d) && nbins[d] > 1)
                .max_by_key(|&d| nbins[d]);
            let Some(d) = widest else { break };
            nbins[d] = nbins[d].div_ceil(2);
            size[d] = (hi[d] - lo[d]).max(0.0) / nbins[d] as f64;
        }
        Cells { lo, size, nbins }
    }

    /// The cell of `p` (clamped to the grid).
    fn bin_of(&self, p: &[f64; 3]) -> [usize; 3] {
        let mut b = [0usize; 3];
        for d in 0..3 {
            let k = ((p[d] - self.lo[d]) / self.size[d]).floor();
            b[d] = (k.max(0.0) as usize).min(self.nbins[d] - 1);
        }
        b
    }

    /// The flat index of cell `b`.
    fn flat(&self, b: [usize; 3]) -> usize {
        let nbins = self.nbins;
        (b[2] * nbins[1] + b[1]) * nbins[0] + b[0]
    }

    /// The number of cells.
    fn total(&self) -> usize {
        self.nbins[0] * self.nbins[1] * self.nbins[2]
    }

    /// The particles in cell `bi` and the 26 around it (across periodic faces with the
    /// shift, length), into `candidates`; `members[start[c]..start[c + 1]]` are cell c's.
    fn candidates(
        &self,
        bi: [usize; 3],
        domain: &Domain,
        start: &[usize],
        members: &[u32],
        candidates: &mut Vec<(u32, [f64; 3])>,
    ) {
        candidates.clear();
        for dz in -1i64..=1 {
            for dy in -1i64..=1 {
                for dx in -1i64..=1 {
                    let mut b = [0usize; 3];
                    let mut shift = [0.0; 3];
                    let mut skip = false;
                    for (d, off) in [dx, dy, dz].into_iter().enumerate() {
                        let k = bi[d] as i64 + off;
                        let m = self.nbins[d] as i64;
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
                    let fb = self.flat(b);
                    for &j in &members[start[fb]..start[fb + 1]] {
                        candidates.push((j, shift));
                    }
                }
            }
        }
    }
}

impl NeighborList {
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
        self.start_build(x, reach, false);
        let n = x.len();
        if n == 0 {
            return;
        }
        let max_reach = reach.iter().copied().fold(0.0, f64::max);
        let cutoff = (2.0 * max_reach + skin).max(f64::MIN_POSITIVE);
        let cells = Cells::new(x, cutoff, domain);
        let (start, fill, members) = self.sort_into_cells(x, &cells);
        // small periodic boxes (fewer than 3 bins): take the minimum image instead
        let small_periodic = (0..3).any(|d| domain.periodic(d) && cells.nbins[d] <= 2);
        let search = Search {
            x,
            reach,
            skin,
            domain,
            order,
            small_periodic,
        };
        let mut candidates: Vec<(u32, [f64; 3])> = Vec::new();
        for i in 0..n {
            cells.candidates(
                cells.bin_of(&x[i]),
                domain,
                &start,
                &members,
                &mut candidates,
            );
            candidates.sort_by_key(|a| a.0);
            candidates.dedup_by(|a, b| a.0 == b.0 && a.1 == b.1);
            let first = self.pairs.len();
            for &(j, shift) in &candidates {
                self.list_candidate(&search, i, j, shift);
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

    /// A counting sort of the particles into the cells (stable: index order inside a
    /// cell): where each cell starts, the fill counters, and the particles cell by cell.
    fn sort_into_cells(
        &mut self,
        x: &[[f64; 3]],
        cells: &Cells,
    ) -> (Vec<usize>, Vec<usize>, Vec<u32>) {
        let total = cells.total();
        let mut start = std::mem::take(&mut self.bin_start);
        start.clear();
        start.resize(total + 1, 0);
        let bins: Vec<usize> = x.iter().map(|p| cells.flat(cells.bin_of(p))).collect();
        for &b in &bins {
            start[b + 1] += 1;
        }
        for k in 0..total {
            start[k + 1] += start[k];
        }
        let mut fill = std::mem::take(&mut self.bin_fill);
        fill.clear();
        fill.extend_from_slice(&start);
        let mut members = vec![0u32; x.len()];
        for (i, &b) in bins.iter().enumerate() {
            members[fill[b]] = i as u32;
            fill[b] += 1;
        }
        (start, fill, members)
    }

    /// List candidate `j` (at `shift`, length) of particle `i` when within reach: each
    /// physical pair once, from its lower index; the minimum image in a small periodic
    /// box; a pair LIGGGHTS's stencil misses is counted and left out.
    fn list_candidate(&mut self, s: &Search, i: usize, j: u32, mut shift: [f64; 3]) {
        let (x, reach) = (s.x, s.reach);
        let ju = j as usize;
        // each physical pair is listed once, from its lower index
        if ju <= i {
            return;
        }
        let mut delta = [0.0; 3];
        for d in 0..3 {
            delta[d] = x[ju][d] + shift[d] - x[i][d];
        }
        if s.small_periodic {
            let raw = delta;
            s.domain.minimum_image(&mut delta);
            for d in 0..3 {
                shift[d] += delta[d] - raw[d];
            }
        }
        let cut = reach[i] + reach[ju] + s.skin;
        let rsq = delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2];
        if rsq < cut * cut {
            if let Some(o) = s.order {
                let xj = [0, 1, 2].map(|d| x[ju][d] + shift[d]);
                if o.cut > 0.0 && rsq >= o.cut * o.cut && !o.in_stencil(o.bin(x[i]), o.bin(xj)) {
                    self.missed += 1;
                    return;
                }
            }
            self.pairs.push(Pair {
                i: i as u32,
                j,
                shift,
            });
        }
    }
}

/// What a build searches with: positions (length), reaches (length), skin (length), the
/// box, LIGGGHTS's bins when its order is kept, and whether a periodic dimension has
/// fewer than three cells (pairs then take the minimum image).
struct Search<'a> {
    x: &'a [[f64; 3]],
    reach: &'a [f64],
    skin: f64,
    domain: &'a Domain,
    order: Option<&'a BinOrder>,
    small_periodic: bool,
}
