//! Load balancing of the brick decomposition (LAMMPS's `balance` and `fix balance`, which
//! LIGGGHTS 3.8.0 lacks): the grid stays a grid of bricks, and the cutting planes along the
//! chosen axes move so that each slab of bricks holds an even share of the particles'
//! weight. The `shift` style moves each cut by bisection: at each iteration the weight below
//! every cut is tallied (summed over the ranks), each cut's bracket `[lo, hi]` (the weight
//! below `lo` at most its target, the weight below `hi` at least it) narrows to the cut
//! tried or to any other cut tried that falls inside it, and the cut moves to the middle of
//! its bracket. Positions are compared with the planes exactly as a brick's ownership test
//! compares them, so the tallies are the counts the ranks will own.
//!
//! The weights a rank passes are its own particles' (a sum over ranks makes the totals) or,
//! between runs when every rank holds the whole set, all of them with a sum that does
//! nothing: both give the same cuts. Counts are whole numbers, so the sums are exact and
//! the cuts the same on every rank count.

use crate::engine::decomp::decomposition::Decomposition;

/// The `shift` style's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Shift {
    /// The axes balanced, in order (0 = x).
    pub dims: Vec<usize>,
    /// The most bisection iterations per axis.
    pub niter: usize,
    /// Balancing stops once the imbalance factor is at most this (dimensionless, >= 1).
    pub stopthresh: f64,
}

/// What a balance did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Outcome {
    /// Bisection iterations made over every axis.
    pub iterations: usize,
    /// The largest load of a rank before (weight: particles for count weights).
    pub max_before: f64,
    /// The largest load of a rank after.
    pub max_after: f64,
    /// The imbalance factor before (largest load over the average, dimensionless).
    pub imbalance_before: f64,
    /// The imbalance factor after.
    pub imbalance_after: f64,
}

/// The load (summed weight `w` of the particles at `x`) of every rank's brick, by rank,
/// after `sum` (a sum over the ranks, or nothing when every rank holds the whole set).
/// Particles outside the box count for no rank.
pub fn loads(dec: &Decomposition, x: &[[f64; 3]], w: &[f64], sum: &dyn Fn(&mut [f64])) -> Vec<f64> {
    let mut load = vec![0.0; dec.size()];
    for (xi, wi) in x.iter().zip(w) {
        if let Some(r) = dec.owner_of(*xi) {
            load[r] += wi;
        }
    }
    sum(&mut load);
    load
}

/// The largest load and the imbalance factor (largest over average; 1 without any load).
pub fn imbalance(load: &[f64]) -> (f64, f64) {
    let max = load.iter().copied().fold(0.0, f64::max);
    let total: f64 = load.iter().sum();
    if max > 0.0 && total > 0.0 {
        (max, max / (total / load.len() as f64))
    } else {
        (max, 1.0)
    }
}

/// The weight below each of the planes `planes` (length, ascending) along `dim`.
fn weight_below(
    dim: usize,
    planes: &[f64],
    x: &[[f64; 3]],
    w: &[f64],
    sum: &dyn Fn(&mut [f64]),
) -> Vec<f64> {
    // a particle below plane k is below every later one: bin by the first plane above it
    let mut bins = vec![0.0; planes.len() + 1];
    for (xi, wi) in x.iter().zip(w) {
        let k = planes.partition_point(|&p| p <= xi[dim]);
        bins[k] += wi;
    }
    sum(&mut bins);
    let mut below = Vec::with_capacity(planes.len());
    let mut acc = 0.0;
    for b in &bins[..planes.len()] {
        acc += b;
        below.push(acc);
    }
    below
}

/// The imbalance of the slabs along one axis whose cuts have weight `below` under them,
/// out of `total`.
fn slab_imbalance(below: &[f64], total: f64) -> f64 {
    let n = below.len() + 1;
    let mut max: f64 = 0.0;
    let mut last = 0.0;
    for &b in below.iter().chain([&total]) {
        max = max.max(b - last);
        last = b;
    }
    if total > 0.0 {
        max / (total / n as f64)
    } else {
        1.0
    }
}

/// LAMMPS's `shift` balance: move the cuts of `dec` along `settings.dims` so that the
/// weight `w` of the particles at `x` spreads evenly over the slabs (see the module's
/// description); adjacent cuts end at least `min_gap` (length, per axis: the neighbour skin)
/// apart where the box is long enough. `sum` sums a vector over the ranks. Returns the
/// iterations made; the loads before and after are the caller's (see [`loads`]).
pub fn shift(
    dec: &mut Decomposition,
    x: &[[f64; 3]],
    w: &[f64],
    sum: &dyn Fn(&mut [f64]),
    settings: &Shift,
    min_gap: f64,
) -> usize {
    let ndims = settings.dims.len().max(1) as f64;
    // each axis stops when its slabs are even to within the n-th root of the threshold, so
    // that n axes together are within it
    let per_axis = settings.stopthresh.powf(1.0 / ndims);
    let mut total = [w.iter().sum::<f64>()];
    sum(&mut total);
    let total = total[0];
    let mut iterations = 0;
    if total <= 0.0 {
        return 0;
    }
    for &dim in &settings.dims {
        let p = dec.procs[dim];
        if p < 2 {
            continue;
        }
        let (lo, len) = (dec.box_lo[dim], dec.length(dim));
        let plane = |c: f64| lo + len * c;
        let target: Vec<f64> = (1..p).map(|i| total * i as f64 / p as f64).collect();
        let mut cuts: Vec<f64> = dec.splits[dim][1..p].to_vec();
        let planes: Vec<f64> = cuts.iter().map(|&c| plane(c)).collect();
        let mut below = weight_below(dim, &planes, x, w, sum);
        // each cut's bracket from the cuts as they stand and the box's sides
        let mut bracket: Vec<(f64, f64)> = vec![(0.0, 1.0); p - 1];
        let narrow = |bracket: &mut [(f64, f64)], cuts: &[f64], below: &[f64]| {
            for (i, b) in bracket.iter_mut().enumerate() {
                for (&c, &s) in cuts.iter().zip(below) {
                    if s <= target[i] && c > b.0 && c <= b.1 {
                        b.0 = c;
                    }
                    if s >= target[i] && c < b.1 && c >= b.0 {
                        b.1 = c;
                    }
                }
            }
        };
        narrow(&mut bracket, &cuts, &below);
        for _ in 0..settings.niter {
            if slab_imbalance(&below, total) <= per_axis {
                break;
            }
            let mut last = 0.0;
            for (c, b) in cuts.iter_mut().zip(&bracket) {
                *c = (0.5 * (b.0 + b.1)).max(last);
                last = *c;
            }
            let planes: Vec<f64> = cuts.iter().map(|&c| plane(c)).collect();
            below = weight_below(dim, &planes, x, w, sum);
            narrow(&mut bracket, &cuts, &below);
            iterations += 1;
        }
        // bricks at least the skin thick where the box allows it
        let gap = if len > 0.0 { min_gap / len } else { 0.0 };
        if gap > 0.0 && gap * (p as f64) < 1.0 {
            let mut last = 0.0;
            for c in cuts.iter_mut() {
                *c = c.max(last + gap);
                last = *c;
            }
            let mut next = 1.0;
            for c in cuts.iter_mut().rev() {
                *c = c.min(next - gap);
                next = *c;
            }
        }
        let mut splits = dec.splits.clone();
        splits[dim][1..p].copy_from_slice(&cuts);
        dec.set_splits(&splits);
        let load = loads(dec, x, w, sum);
        if imbalance(&load).1 <= settings.stopthresh {
            break;
        }
    }
    iterations
}

/// LAMMPS's time weights: each rank's particles weigh its measured cost per particle
/// (`cost[r] / count[r]`, time), stretched by `factor` (the largest weight becomes
/// `factor` times itself, the smallest stays, those between move in proportion); a rank
/// without particles weighs nothing. None when no rank has a cost yet (count weights then).
pub fn time_weights(cost: &[f64], count: &[f64], factor: f64) -> Option<Vec<f64>> {
    if cost.iter().all(|&c| c <= 0.0) {
        return None;
    }
    let mut w: Vec<f64> = cost
        .iter()
        .zip(count)
        .map(|(&c, &n)| if n > 0.0 { c / n } else { 0.0 })
        .collect();
    if factor != 1.0 {
        let held = || w.iter().copied().filter(|&v| v > 0.0);
        let lo = held().fold(f64::INFINITY, f64::min);
        let hi = held().fold(0.0, f64::max);
        if lo < hi {
            let new_hi = hi * factor;
            for v in w.iter_mut().filter(|v| **v > 0.0) {
                *v = lo + (*v - lo) / (hi - lo) * (new_hi - lo);
            }
        }
    }
    Some(w)
}

/// How particles are weighed for balancing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Weight {
    /// Each particle weighs 1 (the particle count).
    Count,
    /// LAMMPS's `weight time FACTOR`: each rank's particles weigh its measured pair and
    /// neighbour time per particle, stretched by FACTOR (see [`time_weights`]).
    Time(f64),
}

/// What a balance leaves for the runs that follow: the cuts and the cost each rank measured
/// in the last run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Kept {
    /// The grid the cuts belong to (ranks along x, y, z).
    pub procs: [usize; 3],
    /// The cuts along each axis (fractions of the box length; None: uniform).
    pub splits: Option<[Vec<f64>; 3]>,
    /// Each rank's pair and neighbour time in the last run (time), by rank.
    pub costs: Vec<f64>,
    /// Each rank's particles at the end of the last run, by rank.
    pub counts: Vec<f64>,
    /// The cuts of the last run (fractions), which the costs belong to.
    pub run_splits: Option<[Vec<f64>; 3]>,
}

/// `fix balance`: rebalance every `every` steps (a neighbour-list build is forced then) or,
/// with `every` 0, at every build; only when the imbalance factor exceeds `thresh`.
#[derive(Debug, Clone, PartialEq)]
pub struct BalanceFix {
    /// Steps between rebalances (0: at every neighbour-list build).
    pub every: i64,
    /// The imbalance factor above which a rebalance is made (dimensionless).
    pub thresh: f64,
    /// The shift settings.
    pub shift: Shift,
    /// How particles are weighed.
    pub weight: Weight,
    /// The last rebalance (its values are the fix's `f_ID` and `f_ID[1..3]`).
    pub last: Outcome,
    /// The pair and neighbour time of this rank at the last rebalance (time).
    pub clock: f64,
}

impl BalanceFix {
    /// Whether a rebalance is due at the neighbour-list build of `step` (and forces one
    /// when `every` is set).
    pub fn due(&self, step: i64) -> bool {
        self.every == 0 || step % self.every == 0
    }

    /// Whether the fix forces a neighbour-list build at `step`.
    pub fn forces_build(&self, step: i64) -> bool {
        self.every > 0 && step % self.every == 0
    }

    /// Record a look that made no rebalance (one rank, or balanced enough): the loads as
    /// they stand.
    pub fn record_unchanged(&mut self, max: f64, imbalance: f64) {
        self.last = Outcome {
            iterations: 0,
            max_before: max,
            max_after: max,
            imbalance_before: imbalance,
            imbalance_after: imbalance,
        };
    }
}

impl crate::engine::fixes::FixStyle for BalanceFix {
    fn name(&self) -> &str {
        "balance"
    }

    fn setup(
        &mut self,
        p: &crate::engine::particles::Particles,
        _at: &crate::engine::fixes::FixStep,
    ) {
        // one process holds every particle: the imbalance is 1 (ranks record their own
        // after this, at their setup)
        self.record_unchanged(p.len() as f64, 1.0);
    }

    fn global_freq(&self) -> i64 {
        self.every.max(1)
    }

    /// `f_ID`: the imbalance factor after the last rebalance; `f_ID[1]` the most particles
    /// (weight) on a rank, `f_ID[2]` the iterations, `f_ID[3]` the factor before it.
    fn value(&self, index: Option<usize>) -> Option<f64> {
        let o = &self.last;
        match index {
            None => Some(o.imbalance_after),
            Some(1) => Some(o.max_after),
            Some(2) => Some(o.iterations as f64),
            Some(3) => Some(o.imbalance_before),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::comm::{Comm, Reduce};
    use crate::util::comm_threads::ThreadRanks;

    /// 300 points on [0, 1)^3: two thirds in x < 0.25, the rest spread over the box.
    fn heap() -> Vec<[f64; 3]> {
        let mut s = 99u64;
        let mut r = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..300)
            .map(|k| {
                let x = if k % 3 == 2 { r() } else { 0.25 * r() };
                [x, r(), r()]
            })
            .collect()
    }

    #[test]
    fn shift_evens_the_counts_of_three_slabs() {
        let x = heap();
        let w = vec![1.0; x.len()];
        let mut dec = Decomposition::cartesian([3, 1, 1], 0, [0.0; 3], [1.0; 3], [false; 3]);
        let none = |_: &mut [f64]| {};
        let (max0, imb0) = imbalance(&loads(&dec, &x, &w, &none));
        assert!(imb0 > 2.0, "{imb0}");
        let settings = Shift {
            dims: vec![0],
            niter: 30,
            stopthresh: 1.02,
        };
        let it = shift(&mut dec, &x, &w, &none, &settings, 0.0);
        let load = loads(&dec, &x, &w, &none);
        let (max1, imb1) = imbalance(&load);
        assert!(imb1 <= 1.02, "{load:?}");
        assert!(max1 < max0 && it > 0 && it <= 30);
        assert_eq!(load.iter().sum::<f64>(), 300.0);
        // the cuts moved towards the heap, in order
        let s = &dec.splits[0];
        assert!(
            s[0] == 0.0 && s[1] < 0.25 && s[1] < s[2] && s[3] == 1.0,
            "{s:?}"
        );
    }

    #[test]
    fn the_same_cuts_from_each_ranks_share_as_from_the_whole_set() {
        let x = heap();
        let settings = Shift {
            dims: vec![0, 1],
            niter: 20,
            stopthresh: 1.05,
        };
        let mut whole = Decomposition::cartesian([2, 2, 1], 0, [0.0; 3], [1.0; 3], [false; 3]);
        let w = vec![1.0; x.len()];
        shift(&mut whole, &x, &w, &|_: &mut [f64]| {}, &settings, 0.0);
        let out = ThreadRanks::run(4, |c| {
            let mut dec =
                Decomposition::cartesian([2, 2, 1], c.rank(), [0.0; 3], [1.0; 3], [false; 3]);
            let mine: Vec<[f64; 3]> = x.iter().copied().filter(|p| dec.owns(*p)).collect();
            let w = vec![1.0; mine.len()];
            let sum = |v: &mut [f64]| c.all_reduce_f64(v, Reduce::Sum);
            shift(&mut dec, &mine, &w, &sum, &settings, 0.0);
            dec.splits
        });
        assert!(out.iter().all(|s| *s == whole.splits));
    }

    #[test]
    fn cuts_kept_a_skin_apart() {
        // every point in a thin sheet: the cuts would meet there
        let x: Vec<[f64; 3]> = (0..100)
            .map(|k| [0.5 + 1e-6 * k as f64, 0.5, 0.5])
            .collect();
        let w = vec![1.0; x.len()];
        let mut dec = Decomposition::cartesian([4, 1, 1], 0, [0.0; 3], [2.0, 1.0, 1.0], [true; 3]);
        let settings = Shift {
            dims: vec![0],
            niter: 40,
            stopthresh: 1.0,
        };
        shift(&mut dec, &x, &w, &|_: &mut [f64]| {}, &settings, 0.1);
        let s = &dec.splits[0];
        assert!(s.windows(2).all(|p| p[1] - p[0] >= 0.05 - 1e-12), "{s:?}");
    }

    #[test]
    fn time_weights_stretched_by_the_factor() {
        let w = time_weights(&[4.0, 2.0, 0.0], &[2.0, 2.0, 0.0], 1.0).expect("weights");
        assert_eq!(w, vec![2.0, 1.0, 0.0]);
        let w = time_weights(&[4.0, 2.0, 0.0], &[2.0, 2.0, 0.0], 2.0).expect("weights");
        assert_eq!(w, vec![4.0, 1.0, 0.0]);
        assert!(time_weights(&[0.0, 0.0], &[3.0, 1.0], 1.0).is_none());
        assert_eq!(imbalance(&[3.0, 1.0]), (3.0, 1.5));
        assert_eq!(imbalance(&[0.0, 0.0]), (0.0, 1.0));
    }
}
