//! Which part of the box each rank owns: LIGGGHTS's uniform brick split of the box over the
//! processor grid (`processors Px Py Pz`), or the cuts a `balance` moved (LAMMPS's
//! non-uniform bricks, still one logical grid), the neighbouring ranks along each axis and
//! the periodic flags. Lengths are in box units.

use crate::engine::procmap::{self, ProcGrid, Processors};
use crate::util::comm::{Comm, Reduce};

/// The smallest and largest coordinates (length) of the particles of every rank, for
/// shrink-wrapping the box (`+inf`/`-inf` when no rank has any): every rank gets the same.
pub fn global_extent(comm: &impl Comm, x: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in x {
        for d in 0..3 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    comm.all_reduce_f64(&mut lo, Reduce::Min);
    comm.all_reduce_f64(&mut hi, Reduce::Max);
    (lo, hi)
}

/// The brick decomposition of a box as one rank sees it (every rank's bricks are known).
#[derive(Debug, Clone, PartialEq)]
pub struct Decomposition {
    /// Ranks along x, y, z.
    pub procs: [usize; 3],
    /// This rank.
    pub me: usize,
    /// Grid location (0-based I, J, K) of every rank, by rank.
    pub locations: Vec<[usize; 3]>,
    /// Box lower corner (length).
    pub box_lo: [f64; 3],
    /// Box upper corner (length).
    pub box_hi: [f64; 3],
    /// Whether each direction is periodic.
    pub periodic: [bool; 3],
    /// This rank's sub-domain lower corner (length).
    pub sub_lo: [f64; 3],
    /// This rank's sub-domain upper corner (length).
    pub sub_hi: [f64; 3],
    /// The ranks next to this one along each axis, `[low side, high side]`; the grid wraps
    /// around in every direction, periodic or not, as LIGGGHTS's Cartesian map does.
    pub neighbors: [[usize; 2]; 3],
    /// The cutting planes along each axis as fractions of the box length (dimensionless):
    /// `procs[d] + 1` values from 0 to 1, `i / procs[d]` for the uniform split.
    pub splits: [Vec<f64>; 3],
}

/// The uniform cuts of `p` bricks along an axis (fractions of the box length): `i / p`.
pub fn uniform_splits(p: usize) -> Vec<f64> {
    (0..=p)
        .map(|i| if i == p { 1.0 } else { i as f64 / p as f64 })
        .collect()
}

impl Decomposition {
    /// Rank `me`'s view of the grid LIGGGHTS chose (`p`, `grid`) over the box `lo`..`hi`.
    pub fn new(
        p: &Processors,
        grid: &ProcGrid,
        me: usize,
        lo: [f64; 3],
        hi: [f64; 3],
        periodic: [bool; 3],
    ) -> Decomposition {
        let n = grid.procs.iter().product::<i64>().max(1) as usize;
        let locations = (0..n)
            .map(|r| procmap::location(p, grid, r as i64).map(|v| v.max(0) as usize))
            .collect();
        let procs = grid.procs.map(|v| v.max(1) as usize);
        Decomposition::from_locations(procs, locations, me, lo, hi, periodic)
    }

    /// Rank `me`'s view of a grid `procs` whose ranks sit at `locations` (by rank).
    pub fn from_locations(
        procs: [usize; 3],
        locations: Vec<[usize; 3]>,
        me: usize,
        lo: [f64; 3],
        hi: [f64; 3],
        periodic: [bool; 3],
    ) -> Decomposition {
        let mut d = Decomposition {
            procs,
            me,
            locations,
            box_lo: lo,
            box_hi: hi,
            periodic,
            sub_lo: lo,
            sub_hi: hi,
            neighbors: [[me; 2]; 3],
            splits: procs.map(uniform_splits),
        };
        d.set_box(lo, hi);
        let at = d.at();
        for dim in 0..3 {
            let p = procs[dim];
            for (side, step) in [(0, p - 1), (1, 1)] {
                let mut there = at;
                there[dim] = (at[dim] + step) % p;
                d.neighbors[dim][side] = d.rank_at(there).unwrap_or(me);
            }
        }
        d
    }

    /// A grid `procs` with ranks numbered as MPI's Cartesian map numbers them (z fastest).
    pub fn cartesian(
        procs: [usize; 3],
        me: usize,
        lo: [f64; 3],
        hi: [f64; 3],
        periodic: [bool; 3],
    ) -> Decomposition {
        let n = procs.iter().product::<usize>();
        let locations = (0..n)
            .map(|r| {
                [
                    r / (procs[1] * procs[2]),
                    (r / procs[2]) % procs[1],
                    r % procs[2],
                ]
            })
            .collect();
        Decomposition::from_locations(procs, locations, me, lo, hi, periodic)
    }

    /// This rank's grid location.
    pub fn at(&self) -> [usize; 3] {
        self.locations[self.me]
    }

    /// The rank at grid location `at` (None outside the grid).
    pub fn rank_at(&self, at: [usize; 3]) -> Option<usize> {
        self.locations.iter().position(|l| *l == at)
    }

    /// Number of ranks.
    pub fn size(&self) -> usize {
        self.locations.len()
    }

    /// Box length along `dim` (length).
    pub fn length(&self, dim: usize) -> f64 {
        self.box_hi[dim] - self.box_lo[dim]
    }

    /// New box bounds (after shrink-wrapping): every rank's brick follows.
    pub fn set_box(&mut self, lo: [f64; 3], hi: [f64; 3]) {
        self.box_lo = lo;
        self.box_hi = hi;
        let (sub_lo, sub_hi) = self.bounds_of(self.me);
        self.sub_lo = sub_lo;
        self.sub_hi = sub_hi;
    }

    /// Whether the cuts are the uniform split (no `balance` moved them).
    pub fn is_uniform(&self) -> bool {
        (0..3).all(|d| self.splits[d] == uniform_splits(self.procs[d]))
    }

    /// Move the cutting planes to `splits` (fractions of the box length, `procs[d] + 1`
    /// ascending values from 0 to 1 per axis); this rank's brick follows. Cuts of the wrong
    /// count are ignored (the axis keeps its cuts).
    pub fn set_splits(&mut self, splits: &[Vec<f64>; 3]) {
        for (d, cuts) in splits.iter().enumerate() {
            if cuts.len() == self.procs[d] + 1 {
                self.splits[d] = cuts.clone();
            }
        }
        self.set_box(self.box_lo, self.box_hi);
    }

    /// The plane of cut `i` along `dim` (length): the box's lower side plus the fraction of
    /// its length, the last cut exactly at the box's upper side.
    pub fn plane(&self, dim: usize, i: usize) -> f64 {
        if i >= self.procs[dim] {
            self.box_hi[dim]
        } else {
            self.box_lo[dim] + self.length(dim) * self.splits[dim][i]
        }
    }

    /// Rank `rank`'s sub-domain corners (length): the box cut along each axis at the
    /// fractions of [`Decomposition::splits`] (i/P unless balanced), the last brick ending
    /// exactly at the box's upper side.
    pub fn bounds_of(&self, rank: usize) -> ([f64; 3], [f64; 3]) {
        let at = self.locations[rank];
        let lo = [0, 1, 2].map(|d| self.plane(d, at[d]));
        let hi = [0, 1, 2].map(|d| self.plane(d, at[d] + 1));
        (lo, hi)
    }

    /// The grid location of the brick holding `x` (None outside the box).
    pub fn location_of(&self, x: [f64; 3]) -> Option<[usize; 3]> {
        let mut at = [0; 3];
        for d in 0..3 {
            let p = self.procs[d];
            if !(x[d] >= self.plane(d, 0) && x[d] < self.plane(d, p)) {
                return None;
            }
            // the first cut above x, less one
            at[d] = (1..p).take_while(|&i| self.plane(d, i) <= x[d]).count();
        }
        Some(at)
    }

    /// Whether `x` lies in this rank's sub-domain (lower faces in, upper faces out, as
    /// LIGGGHTS's migration tests it).
    pub fn owns(&self, x: [f64; 3]) -> bool {
        (0..3).all(|d| x[d] >= self.sub_lo[d] && x[d] < self.sub_hi[d])
    }

    /// The rank whose sub-domain holds `x` (None outside the box).
    pub fn owner_of(&self, x: [f64; 3]) -> Option<usize> {
        self.location_of(x).and_then(|at| self.rank_at(at))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::procmap::choose_grid;

    #[test]
    fn bricks_and_neighbours_of_a_two_by_two_grid() {
        let (lo, hi) = ([0.0; 3], [2.0, 1.0, 0.5]);
        let d = Decomposition::cartesian([2, 2, 1], 3, lo, hi, [true, false, true]);
        assert_eq!(d.at(), [1, 1, 0]);
        assert_eq!((d.sub_lo, d.sub_hi), ([1.0, 0.5, 0.0], [2.0, 1.0, 0.5]));
        // rank = I*2 + J: neighbours wrap in every direction
        assert_eq!(d.neighbors, [[1, 1], [2, 2], [3, 3]]);
        assert_eq!(d.owner_of([0.5, 0.75, 0.1]), Some(1));
        assert_eq!(d.owner_of([2.0, 0.75, 0.1]), None);
        assert!(d.owns([1.0, 0.5, 0.0]) && !d.owns([1.0, 1.0, 0.0]));
    }

    #[test]
    fn extent_over_ranks_and_bricks_that_follow_the_box() {
        use crate::util::comm_threads::ThreadRanks;
        let out = ThreadRanks::run(3, |c| {
            let r = c.rank() as f64;
            let mine = vec![[r, -r, 0.5], [0.25 * r, 2.0, -1.0 - r]];
            let x = if c.rank() == 1 { Vec::new() } else { mine };
            let (lo, hi) = global_extent(c, &x);
            let mut d =
                Decomposition::cartesian([3, 1, 1], c.rank(), [0.0; 3], [1.0; 3], [false; 3]);
            d.set_box(lo, hi);
            (lo, hi, d.sub_lo[0], d.sub_hi[0])
        });
        let (lo, hi) = ([0.0, -2.0, -3.0], [2.0, 2.0, 0.5]);
        let splits = [0.0, 2.0 / 3.0, 4.0 / 3.0, 2.0];
        for (r, o) in out.iter().enumerate() {
            assert_eq!((o.0, o.1), (lo, hi));
            assert_eq!((o.2, o.3), (splits[r], splits[r + 1]));
        }
    }

    #[test]
    fn from_the_chosen_grid() {
        let p = Processors {
            nprocs: 6,
            ..Processors::default()
        };
        let prd = [3.0, 2.0, 1.0];
        let grid = choose_grid(&p, prd).expect("grid");
        assert_eq!(grid.procs, [3, 2, 1]);
        let d = Decomposition::new(&p, &grid, 4, [0.0; 3], prd, [true; 3]);
        assert_eq!(d.at(), [2, 0, 0]);
        assert_eq!((d.sub_lo, d.sub_hi), ([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]));
        assert_eq!(d.neighbors[0], [2, 0]);
        assert_eq!(d.neighbors[1], [5, 5]);
        assert_eq!(d.neighbors[2], [4, 4]);
    }
}
