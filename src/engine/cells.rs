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
        let mut parts: Vec<Vec<Pair>> = vec![Vec::new(); tasks];
        let slots = Shards::new(&mut parts);
        stage(tasks, true, |c| {
            // SAFETY: each task fills its own slot
            let slot = unsafe { slots.range(c..c + 1) };
            slot[0] = {
                let mut out = Vec::new();
                // particles sorted by cell: neighbours share their cell's stencil
                let mut stencil = Stencil::default();
                for i in c * chunk..((c + 1) * chunk).min(n) {
                    let cell = self.coords(&x[i]);
                    if stencil.cell != Some(cell) {
                        self.stencil(cell, start, &mut stencil);
                    }
                    partners(i, x, reach, skin, &stencil, &mut out);
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
        for dz in -1i64..=1 {
            for dy in -1i64..=1 {
                for dx in -1i64..=1 {
                    let mut cell = [0usize; 3];
                    let mut shift = [0.0; 3];
                    let mut outside = false;
                    for (d, off) in [dx, dy, dz].into_iter().enumerate() {
                        let k = c[d] as i64 + off;
                        let m = self.n[d] as i64;
                        if (0..m).contains(&k) {
                            cell[d] = k as usize;
                        } else if self.wrap[d] {
                            cell[d] = k.rem_euclid(m) as usize;
                            shift[d] = if k < 0 {
                                -self.length[d]
                            } else {
                                self.length[d]
                            };
                        } else {
                            outside = true;
                        }
                    }
                    if outside {
                        continue;
                    }
                    let f = self.ranked(cell);
                    stencil.cells[stencil.len] = (start[f], start[f + 1], shift);
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

/// Append the partners j > i of particle i, from the stencil of its cell.
#[inline]
fn partners(
    i: usize,
    x: &[[f64; 3]],
    reach: &[f64],
    skin: f64,
    stencil: &Stencil,
    out: &mut Vec<Pair>,
) {
    let xi = x[i];
    for &(a, b, shift) in &stencil.cells[..stencil.len] {
        let (a, b) = (a as usize, b as usize);
        if b <= i + 1 {
            continue;
        }
        for j in a.max(i + 1)..b {
            let xj = x[j];
            let del = [
                xj[0] + shift[0] - xi[0],
                xj[1] + shift[1] - xi[1],
                xj[2] + shift[2] - xi[2],
            ];
            let cut = reach[i] + reach[j] + skin;
            if del[0] * del[0] + del[1] * del[1] + del[2] * del[2] < cut * cut {
                out.push(Pair {
                    i: i as u32,
                    j: j as u32,
                    shift,
                });
            }
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
