//! Neighbour lists: particles are binned in cells of the interaction cutoff, and every pair
//! closer than the cutoff plus skin is listed once (a half list) with the periodic shift
//! that brings the second particle next to the first. The list is rebuilt when a particle
//! has moved more than half the skin; between rebuilds positions are not re-wrapped, so the
//! stored shifts stay valid. Pairs come out in a fixed order for any thread count.

mod cells;
mod history;
mod stencil;
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

    /// Start a build for positions `x` and reaches `reach`: no pairs yet, the build's
    /// positions and reaches kept, the build counted.
    fn start_build(&mut self, x: &[[f64; 3]], reach: &[f64], mirrored: bool) {
        self.pairs.clear();
        self.mirrors.clear();
        self.mirrored = mirrored;
        self.built_at.clear();
        self.built_at.extend_from_slice(x);
        self.built_reach.clear();
        self.built_reach.extend_from_slice(reach);
        self.builds += 1;
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
}

#[cfg(test)]
mod tests;
