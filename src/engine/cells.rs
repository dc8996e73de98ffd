//! Cell-ordered neighbour search for the fast path. Particles are sorted by the cell they sit
//! in (cells at least one interaction cutoff wide, z slowest), so each cell's particles are
//! one contiguous index range and the particles a pair loop touches together sit together
//! in memory. The half list is then built from those ranges in parallel, each particle's
//! partners found independently, and comes out the same for any number of threads.

use crate::util::team::{stage, stage_chunks, Shards};

use crate::engine::domain::Domain;
use crate::engine::neighbor::Pair;

/// A grid of cells over the particles' extent (the box along periodic dimensions).
#[derive(Debug, Clone, PartialEq)]
pub struct CellGrid {
    lo: [f64; 3],
    inv: [f64; 3],
    /// Cells per dimension.
    pub n: [usize; 3],
    /// Periodic dimensions with at least three cells (wrapped; fewer cells need the
    /// general search).
    wrap: [bool; 3],
    length: [f64; 3],
    /// Per cell (flat index), its place in memory order: cells go tile by tile (cubes of
    /// [`TILE_EDGE`] cells, tiles and the cells inside each x fastest), so a run of
    /// particles in memory is a compact piece of space rather than a thin slab.
    rank: Vec<u32>,
}

/// Edge of the tiles that order cells in memory (cells): about a thousand particles of a
/// dense bed, the fast path's summation block, so a block is a compact piece of space.
pub const TILE_EDGE: usize = 8;

/// At most this many cells along one dimension (a particle far out in a shrink-wrapped box
/// makes the cells wider instead of the grid huge).
const MAX_CELLS: usize = 1 << 10;

impl CellGrid {
    /// Cells of at least `cutoff` (length) over `x`'s extent, or the box along periodic
    /// dimensions. None if a periodic dimension is too short for three cells.
    pub fn new(x: &[[f64; 3]], cutoff: f64, domain: &Domain) -> Option<CellGrid> {
        let cutoff = cutoff.max(f64::MIN_POSITIVE);
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in x {
            for d in 0..3 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
        let mut grid = CellGrid {
            lo,
            inv: [0.0; 3],
            n: [1; 3],
            wrap: [false; 3],
            length: [0.0; 3],
            rank: Vec::new(),
        };
        for (d, hi) in hi.iter_mut().enumerate() {
            if domain.periodic(d) {
                grid.lo[d] = domain.lo[d];
                *hi = domain.hi[d];
                grid.length[d] = domain.length(d);
            }
            let span = (*hi - grid.lo[d]).max(0.0);
            if !span.is_finite() {
                return None;
            }
            let n = ((span / cutoff).floor() as usize).clamp(1, MAX_CELLS);
            grid.n[d] = n;
            grid.inv[d] = if span > 0.0 { n as f64 / span } else { 0.0 };
            if domain.periodic(d) {
                if n < 3 {
                    return None;
                }
                grid.wrap[d] = true;
            }
        }
        // particles flung far apart would ask for up to 2^30 cells: coarsen the widest
        // non-periodic dimensions to a few cells per particle
        let limit = (8 * x.len()).max(1 << 15);
        while grid.n.iter().product::<usize>() > limit {
            let widest = (0..3)
                .filter(|&d| !domain.periodic(d) && grid.n[d] > 1)
                .max_by_key(|&d| grid.n[d]);
            let Some(d) = widest else { break };
            grid.n[d] = grid.n[d].div_ceil(2);
            grid.inv[d] = grid.n[d] as f64 / (hi[d] - grid.lo[d]).max(0.0);
        }
        grid.rank = grid.tile_ranks(TILE_EDGE);
        Some(grid)
    }

    /// Each cell's place in memory order with tiles of `t` cells a side (flat index ->
    /// rank; a permutation of the cells).
    fn tile_ranks(&self, t: usize) -> Vec<u32> {
        let n = self.n;
        let mut rank = vec![0u32; self.len()];
        let mut next = 0u32;
        for tz in (0..n[2]).step_by(t) {
            for ty in (0..n[1]).step_by(t) {
                for tx in (0..n[0]).step_by(t) {
                    for z in tz..(tz + t).min(n[2]) {
                        for y in ty..(ty + t).min(n[1]) {
                            for x in tx..(tx + t).min(n[0]) {
                                rank[self.flat([x, y, z])] = next;
                                next += 1;
                            }
                        }
                    }
                }
            }
        }
        rank
    }

    /// A cell's place in memory order.
    #[inline]
    fn ranked(&self, c: [usize; 3]) -> usize {
        self.rank[self.flat(c)] as usize
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.n[0] * self.n[1] * self.n[2]
    }

    /// True for a grid without cells (never: a grid has at least one).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The cell coordinates of `x` (clamped into the grid).
    #[inline]
    pub fn coords(&self, x: &[f64; 3]) -> [usize; 3] {
        std::array::from_fn(|d| {
            let k = (x[d] - self.lo[d]) * self.inv[d];
            (k.max(0.0) as usize).min(self.n[d] - 1)
        })
    }

    /// The flat index of cell coordinates (x fastest).
    #[inline]
    pub fn flat(&self, c: [usize; 3]) -> usize {
        (c[2] * self.n[1] + c[1]) * self.n[0] + c[0]
    }

    /// The order that sorts particles by cell, cells in memory order (new index -> old
    /// index; stable inside a cell), and the first index of each cell (by rank) in that
    /// order (`len() + 1` entries).
    pub fn sort(&self, x: &[[f64; 3]]) -> (Vec<usize>, Vec<u32>) {
        let mut cells = vec![0u32; x.len()];
        let shards = Shards::new(&mut cells);
        stage_chunks(x.len(), 4096, true, |_, r| {
            // SAFETY: the chunks of a stage are disjoint
            let out = unsafe { shards.range(r.clone()) };
            for (c, p) in out.iter_mut().zip(&x[r]) {
                *c = self.ranked(self.coords(p)) as u32;
            }
        });
        let mut start = vec![0u32; self.len() + 1];
        for &c in &cells {
            start[c as usize + 1] += 1;
        }
        for k in 0..self.len() {
            start[k + 1] += start[k];
        }
        let mut fill = start.clone();
        let mut order = vec![0usize; x.len()];
        for (i, &c) in cells.iter().enumerate() {
            order[fill[c as usize] as usize] = i;
            fill[c as usize] += 1;
        }
        (order, start)
    }

    /// The half list of particles sorted by cell (`start` from [`Self::sort`] for the
    /// current positions): every pair closer than `reach[i] + reach[j] + skin`, listed once
    /// from its lower index, grouped by that index. `shift` brings x\[j\] next to x\[i\].
    pub fn half_list(
        &self,
        x: &[[f64; 3]],
        reach: &[f64],
        skin: f64,
        start: &[u32],
        chunk: usize,
    ) -> Vec<Pair> {
        let n = x.len();
        let tasks = n.div_ceil(chunk.max(1));
        let cols = Columns::new(x, reach);
        let mut parts: Vec<Vec<Pair>> = vec![Vec::new(); tasks];
        let slots = Shards::new(&mut parts);
        let wide = crate::engine::contact::real::lanes_supported();
        stage(tasks, true, |c| {
            // SAFETY: each task fills its own slot
            let slot = unsafe { slots.range(c..c + 1) };
            slot[0] = {
                let range = c * chunk..((c + 1) * chunk).min(n);
                // room for a settled bed's listed partners (about six per particle), so
                // the list seldom grows by copying
                let mut out = Vec::with_capacity(8 * range.len());
                // particles sorted by cell: neighbours share their cell's stencil
                let mut stencil = Stencil::default();
                for i in range {
                    let cell = self.coords(&x[i]);
                    if stencil.cell != Some(cell) {
                        self.stencil(cell, start, &mut stencil);
                    }
                    #[cfg(target_arch = "x86_64")]
                    if wide {
                        // SAFETY: the processor has AVX2 (checked at run time)
                        unsafe { partners_avx2(i, &cols, skin, &stencil, &mut out) };
                        continue;
                    }
                    let _ = wide;
                    partners(i, &cols, skin, &stencil, &mut out);
                }
                out
            };
        });
        let mut pairs = Vec::with_capacity(parts.iter().map(Vec::len).sum());
        for p in parts {
            pairs.extend_from_slice(&p);
        }
        pairs
    }

    /// The particle ranges (from `start`) and periodic shifts of the cells around `c`
    /// (itself included), z slowest then y then x, as `stencil`.
    fn stencil(&self, c: [usize; 3], start: &[u32], stencil: &mut Stencil) {
        stencil.cell = Some(c);
        stencil.len = 0;
        // per axis, the cells at offsets -1, 0, +1 that exist: (index, periodic shift)
        let mut along = [[(0usize, 0.0f64); 3]; 3];
        let mut count = [0usize; 3];
        for d in 0..3 {
            let m = self.n[d] as i64;
            for o in -1i64..=1 {
                let k = c[d] as i64 + o;
                let cell = if (0..m).contains(&k) {
                    (k as usize, 0.0)
                } else if self.wrap[d] {
                    let shift = if k < 0 {
                        -self.length[d]
                    } else {
                        self.length[d]
                    };
                    (k.rem_euclid(m) as usize, shift)
                } else {
                    continue;
                };
                along[d][count[d]] = cell;
                count[d] += 1;
            }
        }
        for z in &along[2][..count[2]] {
            for y in &along[1][..count[1]] {
                let row = (z.0 * self.n[1] + y.0) * self.n[0];
                for x in &along[0][..count[0]] {
                    let f = self.rank[row + x.0] as usize;
                    let (a, b, shift) = (start[f], start[f + 1], [x.1, y.1, z.1]);
                    // a cell whose particles follow the previous range's with the same shift
                    // extends it: the same partners in the same order, one loop fewer
                    if let Some(last) = stencil.cells[..stencil.len].last_mut() {
                        if last.1 == a && last.2 == shift {
                            last.1 = b;
                            continue;
                        }
                    }
                    stencil.cells[stencil.len] = (a, b, shift);
                    stencil.len += 1;
                }
            }
        }
    }
}

/// The cells around one cell: (first particle, one past the last, periodic shift (m)) of
/// each, in the order the half list visits them.
#[derive(Debug, Clone, Copy, Default)]
struct Stencil {
    /// The cell these are around.
    cell: Option<[usize; 3]>,
    cells: [(u32, u32, [f64; 3]); 27],
    len: usize,
}

/// Values past the last particle in each [`Columns`] column (NaN), so a vector of four
/// starting at any particle stays inside the column.
const PAD: usize = 3;

/// The `n` values of `v` followed by [`PAD`] NaNs.
fn padded(n: usize, v: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut c = Vec::with_capacity(n + PAD);
    c.extend(v);
    c.resize(n + PAD, f64::NAN);
    c
}

/// Positions (m) and reaches (m) of the particles as separate columns, so four
/// consecutive particles load as one vector each.
struct Columns {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
    reach: Vec<f64>,
}

impl Columns {
    fn new(x: &[[f64; 3]], reach: &[f64]) -> Columns {
        Columns {
            x: padded(x.len(), x.iter().map(|p| p[0])),
            y: padded(x.len(), x.iter().map(|p| p[1])),
            z: padded(x.len(), x.iter().map(|p| p[2])),
            reach: padded(x.len(), reach[..x.len()].iter().copied()),
        }
    }

    /// Number of particles (the columns hold [`PAD`] more values).
    fn len(&self) -> usize {
        self.x.len() - PAD
    }

    /// Is j within `reach[i] + reach[j] + skin` of i, j moved by `shift`? (The arithmetic
    /// the four-at-a-time search repeats lane by lane.)
    #[inline(always)]
    fn near(&self, i: usize, j: usize, shift: [f64; 3], skin: f64) -> bool {
        let del = [
            self.x[j] + shift[0] - self.x[i],
            self.y[j] + shift[1] - self.y[i],
            self.z[j] + shift[2] - self.z[i],
        ];
        let cut = self.reach[i] + self.reach[j] + skin;
        del[0] * del[0] + del[1] * del[1] + del[2] * del[2] < cut * cut
    }
}

/// The partners of i that one stencil range offers: j from `a` (but above i) to `b`.
#[inline(always)]
fn above(i: usize, a: u32, b: u32) -> std::ops::Range<usize> {
    (a as usize).max(i + 1)..(b as usize).max(i + 1)
}

/// Append the partners j > i of particle i, from the stencil of its cell.
fn partners(i: usize, cols: &Columns, skin: f64, stencil: &Stencil, out: &mut Vec<Pair>) {
    for &(a, b, shift) in &stencil.cells[..stencil.len] {
        for j in above(i, a, b) {
            if cols.near(i, j, shift, skin) {
                out.push(Pair {
                    i: i as u32,
                    j: j as u32,
                    shift,
                });
            }
        }
    }
}

/// [`partners`] four candidates at a time (the same arithmetic per candidate, so the same
/// list in the same order).
///
/// # Safety
/// The processor must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn partners_avx2(
    i: usize,
    cols: &Columns,
    skin: f64,
    stencil: &Stencil,
    out: &mut Vec<Pair>,
) {
    use std::arch::x86_64::*;
    let n = cols.len();
    let padded = n + PAD;
    assert!(
        i < n
            && cols.x.len() == padded
            && cols.y.len() == padded
            && cols.z.len() == padded
            && cols.reach.len() == padded
    );
    let (xi, yi, zi) = (
        _mm256_set1_pd(cols.x[i]),
        _mm256_set1_pd(cols.y[i]),
        _mm256_set1_pd(cols.z[i]),
    );
    let base = _mm256_set1_pd(cols.reach[i]);
    let skin4 = _mm256_set1_pd(skin);
    for &(a, b, shift) in &stencil.cells[..stencil.len] {
        let range = above(i, a, b);
        let end = range.end.min(n);
        let (sx, sy, sz) = (
            _mm256_set1_pd(shift[0]),
            _mm256_set1_pd(shift[1]),
            _mm256_set1_pd(shift[2]),
        );
        let mut j = range.start;
        while j < end {
            // four candidates at a time; the last one to three read a whole vector past
            // them (the columns are padded) with the lanes beyond `end` masked off
            // SAFETY: j < end <= n and the columns hold n + PAD values
            let (x, y, z, r) = unsafe {
                (
                    _mm256_loadu_pd(cols.x.as_ptr().add(j)),
                    _mm256_loadu_pd(cols.y.as_ptr().add(j)),
                    _mm256_loadu_pd(cols.z.as_ptr().add(j)),
                    _mm256_loadu_pd(cols.reach.as_ptr().add(j)),
                )
            };
            let dx = _mm256_sub_pd(_mm256_add_pd(x, sx), xi);
            let dy = _mm256_sub_pd(_mm256_add_pd(y, sy), yi);
            let dz = _mm256_sub_pd(_mm256_add_pd(z, sz), zi);
            let cut = _mm256_add_pd(_mm256_add_pd(base, r), skin4);
            let rsq = _mm256_add_pd(
                _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)),
                _mm256_mul_pd(dz, dz),
            );
            let near =
                _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(rsq, _mm256_mul_pd(cut, cut)));
            let mut mask = near & ((1 << (end - j).min(4)) - 1);
            while mask != 0 {
                let k = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                out.push(Pair {
                    i: i as u32,
                    j: (j + k) as u32,
                    shift,
                });
            }
            j += 4;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::domain::parse_boundary;
    use crate::engine::neighbor::NeighborList;

    #[test]
    fn sorted_half_list_equals_the_general_one() {
        let mut domain = Domain::default();
        domain.boundary = parse_boundary(&["p", "f", "p"]).unwrap();
        domain.create([0.0; 3], [1.0, 1.0, 0.5]);
        let mut r = crate::util::random::RanPark::new(12345).unwrap();
        let x: Vec<[f64; 3]> = (0..600)
            .map(|_| [r.uniform(), r.uniform(), 0.5 * r.uniform()])
            .collect();
        let reach = vec![0.04; x.len()];
        let grid = CellGrid::new(&x, 0.1, &domain).unwrap();
        let (order, start) = grid.sort(&x);
        let sorted: Vec<[f64; 3]> = order.iter().map(|&k| x[k]).collect();
        let pairs = grid.half_list(&sorted, &reach, 0.02, &start, 37);
        let mut general = NeighborList::default();
        general.build(&sorted, &reach, 0.02, &domain, None);
        let key = |p: &Pair| (p.i, p.j, p.shift.map(f64::to_bits));
        let mut a: Vec<_> = pairs.iter().map(key).collect();
        let mut b: Vec<_> = general.pairs.iter().map(key).collect();
        a.sort();
        b.sort();
        assert_eq!(a, b);
        // grouped by i, partners above i, the same for any chunking
        assert!(pairs.windows(2).all(|w| w[0].i <= w[1].i));
        assert!(pairs.iter().all(|p| p.j > p.i));
        assert_eq!(pairs, grid.half_list(&sorted, &reach, 0.02, &start, 1000));
        // a periodic box too short for three cells needs the general search
        assert!(CellGrid::new(&x, 0.3, &domain).is_none());
    }

    #[test]
    fn four_at_a_time_partner_search_lists_what_the_one_by_one_search_lists() {
        let mut domain = Domain::default();
        domain.boundary = parse_boundary(&["p", "p", "f"]).unwrap();
        domain.create([0.0; 3], [1.0, 0.7, 0.5]);
        let mut r = crate::util::random::RanPark::new(4711).unwrap();
        let x: Vec<[f64; 3]> = (0..900)
            .map(|_| [r.uniform(), 0.7 * r.uniform(), 0.5 * r.uniform()])
            .collect();
        let reach: Vec<f64> = (0..x.len()).map(|_| 0.02 + 0.02 * r.uniform()).collect();
        let grid = CellGrid::new(&x, 0.1, &domain).unwrap();
        let (order, start) = grid.sort(&x);
        let sorted: Vec<[f64; 3]> = order.iter().map(|&k| x[k]).collect();
        let reach: Vec<f64> = order.iter().map(|&k| reach[k]).collect();
        let cols = Columns::new(&sorted, &reach);
        let (mut one, mut four) = (Vec::new(), Vec::new());
        let mut stencil = Stencil::default();
        for (i, xi) in sorted.iter().enumerate() {
            grid.stencil(grid.coords(xi), &start, &mut stencil);
            partners(i, &cols, 0.01, &stencil, &mut one);
            #[cfg(target_arch = "x86_64")]
            if is_x86_feature_detected!("avx2") {
                // SAFETY: AVX2 checked just above
                unsafe { partners_avx2(i, &cols, 0.01, &stencil, &mut four) };
                continue;
            }
            partners(i, &cols, 0.01, &stencil, &mut four);
        }
        assert!(one.len() > 1000, "{} pairs", one.len());
        assert!(one.iter().any(|p| p.shift != [0.0; 3]));
        assert_eq!(one, four);
    }

    #[test]
    fn tiles_order_every_cell_once_and_keep_each_tile_together() {
        let mut domain = Domain::default();
        domain.boundary = parse_boundary(&["f", "f", "f"]).unwrap();
        domain.create([0.0; 3], [1.0; 3]);
        let x = vec![[0.0, 0.0, 0.0], [0.99, 0.69, 0.49]];
        let grid = CellGrid::new(&x, 0.1, &domain).unwrap();
        assert_eq!(grid.n, [9, 6, 4]);
        let rank = grid.tile_ranks(4);
        let mut seen = rank.clone();
        seen.sort();
        assert!(seen.iter().enumerate().all(|(k, &r)| r as usize == k));
        // the first tile is cells x, y, z < 4: ranks 0..64, x fastest inside it
        assert_eq!(rank[grid.flat([0, 0, 0])], 0);
        assert_eq!(rank[grid.flat([3, 0, 0])], 3);
        assert_eq!(rank[grid.flat([0, 1, 0])], 4);
        assert_eq!(rank[grid.flat([3, 3, 3])], 63);
        // then the next tile along x
        assert_eq!(rank[grid.flat([4, 0, 0])], 64);
    }
}
