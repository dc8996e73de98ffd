//! Load balancing (LAMMPS's `balance` command between runs and `fix balance` during them,
//! the brick grid's cuts moved; see `engine::decomp::balance`). Between runs every rank
//! holds the whole set, so the `balance` command computes the same cuts on every rank from
//! every particle with no messages; the next run's bricks follow them. `fix balance`
//! rebalances at a run's setup the same way and, during the run, at neighbour-list builds
//! from each rank's own particles (sums over the ranks), the particles then migrating
//! straight to their new ranks. On one process there is one brick: the imbalance is 1.

use super::*;
use crate::engine::decomp::balance::{self, BalanceFix, Outcome, Shift, Weight};
use crate::engine::decomp::Decomposition;
use crate::util::format::g_precision;

/// How a `balance` command places the cuts along one axis.
#[derive(Debug, Clone, PartialEq)]
pub enum Cuts {
    /// The cuts stay.
    Keep,
    /// Evenly spaced (`x uniform`).
    Uniform,
    /// At these fractions of the box length (the interior cuts, ascending in (0, 1)).
    At(Vec<f64>),
}

/// A `balance` command.
#[derive(Debug, Clone, PartialEq)]
pub struct BalanceRequest {
    /// Balance only when the imbalance factor is at least this (dimensionless).
    pub thresh: f64,
    /// The `shift` style's settings (None: the cuts of `cuts`).
    pub shift: Option<Shift>,
    /// The `x`/`y`/`z` styles' cuts, per axis.
    pub cuts: [Cuts; 3],
    /// How particles are weighed.
    pub weight: Weight,
}

impl Simulation {
    /// The ranks' grid over the box as rank `me` sees it (one brick on one process), with the
    /// cuts a balance left when they belong to this grid.
    pub(super) fn balanced_grid(&self, me: usize) -> Result<Decomposition, EngineError> {
        // the ranks of the run (a dry run knows their number, not a communicator)
        let size = self.procs.nprocs.max(1) as usize;
        let periodic = [0, 1, 2].map(|d| self.domain.periodic(d));
        let (lo, hi) = (self.domain.lo, self.domain.hi);
        let mut dec = if size > 1 {
            let prd = [0, 1, 2].map(|d| self.domain.length(d));
            let grid = crate::engine::procmap::choose_grid(&self.procs, prd)?;
            if grid.procs.iter().product::<i64>() != size as i64 {
                return Err(EngineError::Invalid(format!(
                    "the processor grid {:?} does not hold the {size} ranks of the run",
                    grid.procs
                )));
            }
            Decomposition::new(&self.procs, &grid, me, lo, hi, periodic)
        } else {
            Decomposition::cartesian([1, 1, 1], 0, lo, hi, periodic)
        };
        if let Some(s) = &self.balance.splits {
            if self.balance.procs == dec.procs {
                dec.set_splits(s);
            }
        }
        Ok(dec)
    }

    /// The weight of every particle of the whole set (held by every rank between runs):
    /// 1 each, or the cost per particle of the rank whose brick held it in the last run
    /// (count weights when no run measured any).
    fn whole_set_weights(&self, dec: &Decomposition, weight: Weight) -> Vec<f64> {
        let n = self.particles.len();
        let Weight::Time(factor) = weight else {
            return vec![1.0; n];
        };
        let k = &self.balance;
        let by_rank = balance::time_weights(&k.costs, &k.counts, factor)
            .filter(|w| w.len() == dec.size() && k.procs == dec.procs);
        let Some(by_rank) = by_rank else {
            return vec![1.0; n];
        };
        let mut old = dec.clone();
        match &k.run_splits {
            Some(s) => old.set_splits(s),
            None => old.set_splits(
                &dec.procs
                    .map(crate::engine::decomp::decomposition::uniform_splits),
            ),
        }
        let held: Vec<f64> = by_rank.iter().copied().filter(|&w| w > 0.0).collect();
        let mean = held.iter().sum::<f64>() / held.len().max(1) as f64;
        self.particles
            .x
            .iter()
            .map(|&x| {
                let w = old.owner_of(x).map_or(0.0, |r| by_rank[r]);
                if w > 0.0 {
                    w
                } else {
                    mean
                }
            })
            .collect()
    }

    /// The `balance` command: the cuts of the grid moved (kept for the next runs) and
    /// LAMMPS's report (`Balancing ...`, then, when the imbalance factor reached the
    /// threshold, the iterations, the largest load and the imbalance factor before and
    /// after, and the cuts).
    pub fn balance_command(&mut self, req: &BalanceRequest) -> Result<String, EngineError> {
        self.pbc_and_box()?;
        // every rank computes the whole grid's cuts alike: rank 0's view serves
        let mut dec = self.balanced_grid(0)?;
        let w = self.whole_set_weights(&dec, req.weight);
        let x = &self.particles.x;
        let none = |_: &mut [f64]| {};
        let (max0, imb0) = balance::imbalance(&balance::loads(&dec, x, &w, &none));
        let mut text = String::from("Balancing ...\n");
        if imb0 < req.thresh {
            return Ok(text);
        }
        let iterations = match &req.shift {
            Some(shift) => balance::shift(&mut dec, x, &w, &none, shift, self.neighbor.skin),
            None => {
                let mut splits = dec.splits.clone();
                for d in 0..3 {
                    let p = dec.procs[d];
                    match &req.cuts[d] {
                        Cuts::Keep => {}
                        Cuts::Uniform => {
                            splits[d] = crate::engine::decomp::decomposition::uniform_splits(p)
                        }
                        Cuts::At(c) => {
                            if c.len() + 1 != p {
                                return Err(EngineError::Invalid(format!(
                                    "balance {}: {} cuts given for {p} processors along it (expected {})",
                                    ["x", "y", "z"][d],
                                    c.len(),
                                    p - 1
                                )));
                            }
                            splits[d] = [0.0]
                                .into_iter()
                                .chain(c.iter().copied())
                                .chain([1.0])
                                .collect();
                        }
                    }
                }
                dec.set_splits(&splits);
                0
            }
        };
        let (max1, imb1) = balance::imbalance(&balance::loads(&dec, x, &w, &none));
        self.balance.procs = dec.procs;
        self.balance.splits = Some(dec.splits.clone());
        text.push_str(&format!("  iteration count = {iterations}\n"));
        if let Weight::Time(f) = req.weight {
            text.push_str(&format!("  time weight factor: {}\n", g_precision(f, 8)));
        }
        text.push_str(&format!(
            "  initial/final maximal load/proc = {} {}\n  initial/final imbalance factor  = {} {}\n",
            g_precision(max0, 8),
            g_precision(max1, 8),
            g_precision(imb0, 8),
            g_precision(imb1, 8)
        ));
        for (d, name) in ["x", "y", "z"].iter().enumerate() {
            text.push_str(&format!("  {name} cuts:"));
            for c in &dec.splits[d] {
                text.push_str(&format!(" {}", g_precision(*c, 8)));
            }
            text.push('\n');
        }
        Ok(text)
    }

    /// The index of the first `fix balance` (None without one).
    pub(super) fn balance_fix(&self) -> Option<usize> {
        self.fixes
            .iter()
            .position(|f| f.kind.style_as::<BalanceFix>().is_some())
    }

    /// Whether a `fix balance` forces a neighbour-list build at this step.
    pub(super) fn balance_forces_build(&self) -> bool {
        self.fixes.iter().any(|f| {
            f.kind
                .style_as::<BalanceFix>()
                .is_some_and(|b| b.forces_build(self.step))
        })
    }

    /// `fix balance` at a run's setup on ranks, every rank holding the whole set (wrapped
    /// into the box): the cuts of `dec` moved when the imbalance factor exceeds the fix's
    /// threshold. No time has been measured in the run yet: the particles weigh 1 each.
    pub(super) fn balance_at_setup(&mut self, dec: &mut Decomposition) {
        let Some(k) = self.balance_fix() else {
            return;
        };
        let x = &self.particles.x;
        let w = vec![1.0; x.len()];
        let none = |_: &mut [f64]| {};
        let outcome = {
            let Some(fix) = self.fixes[k].kind.style_as::<BalanceFix>() else {
                return;
            };
            rebalance(dec, x, &w, &none, fix, self.neighbor.skin)
        };
        if let Some(fix) = self.fixes[k].kind.style_as_mut::<BalanceFix>() {
            fix.last = outcome;
            fix.clock = self.stats.pair + self.stats.neigh;
        }
    }

    /// `fix balance` at a neighbour-list build during a run on ranks, from this rank's own
    /// particles (`x`, wrapped into the box) with sums over the ranks: whether the cuts of
    /// `dec` moved (the particles must then migrate to any rank).
    pub(super) fn balance_during_run(
        &mut self,
        comm: &crate::util::comm::RankComm,
        dec: &mut Decomposition,
    ) -> bool {
        use crate::util::comm::{Comm, Reduce};
        let Some(k) = self.balance_fix() else {
            return false;
        };
        let Some(fix) = self.fixes[k].kind.style_as::<BalanceFix>() else {
            return false;
        };
        if !fix.due(self.step) {
            return false;
        }
        let n = self.particles.len();
        let clock = self.stats.pair + self.stats.neigh;
        let mine = match fix.weight {
            Weight::Count => 1.0,
            Weight::Time(factor) => {
                let size = comm.size();
                let mut cost = vec![0.0; size];
                let mut count = vec![0.0; size];
                cost[comm.rank()] = clock - fix.clock;
                count[comm.rank()] = n as f64;
                comm.all_reduce_f64(&mut cost, Reduce::Sum);
                comm.all_reduce_f64(&mut count, Reduce::Sum);
                balance::time_weights(&cost, &count, factor)
                    .and_then(|w| w.get(comm.rank()).copied())
                    .filter(|&w| w > 0.0)
                    .unwrap_or(1.0)
            }
        };
        let w = vec![mine; n];
        let sum = |v: &mut [f64]| comm.all_reduce_f64(v, Reduce::Sum);
        let thresh = fix.thresh;
        let outcome = rebalance(dec, &self.particles.x, &w, &sum, fix, self.neighbor.skin);
        if let Some(fix) = self.fixes[k].kind.style_as_mut::<BalanceFix>() {
            fix.last = outcome;
            fix.clock = clock;
        }
        outcome.imbalance_before > thresh
    }

    /// The end of a run on ranks: the cuts it ended with and each rank's pair and neighbour
    /// time and particle count, kept for a later `balance ... weight time`.
    pub(super) fn keep_run_balance(
        &mut self,
        comm: &crate::util::comm::RankComm,
        dec: &Decomposition,
        nlocal: usize,
    ) {
        use crate::util::comm::{Comm, Reduce};
        let size = comm.size();
        let mut cost = vec![0.0; size];
        let mut count = vec![0.0; size];
        cost[comm.rank()] = self.stats.pair + self.stats.neigh;
        count[comm.rank()] = nlocal as f64;
        comm.all_reduce_f64(&mut cost, Reduce::Sum);
        comm.all_reduce_f64(&mut count, Reduce::Sum);
        let k = &mut self.balance;
        k.procs = dec.procs;
        k.splits = Some(dec.splits.clone());
        k.run_splits = Some(dec.splits.clone());
        k.costs = cost;
        k.counts = count;
    }
}

/// One look of `fix balance`: the cuts of `dec` moved by its shift settings when the
/// imbalance factor of the weights `w` (summed over the ranks by `sum`) exceeds its
/// threshold; what it found.
fn rebalance(
    dec: &mut Decomposition,
    x: &[[f64; 3]],
    w: &[f64],
    sum: &dyn Fn(&mut [f64]),
    fix: &BalanceFix,
    skin: f64,
) -> Outcome {
    let (max0, imb0) = balance::imbalance(&balance::loads(dec, x, w, sum));
    if imb0 <= fix.thresh {
        return Outcome {
            iterations: 0,
            max_before: max0,
            max_after: max0,
            imbalance_before: imb0,
            imbalance_after: imb0,
        };
    }
    let iterations = balance::shift(dec, x, w, sum, &fix.shift, skin);
    let (max1, imb1) = balance::imbalance(&balance::loads(dec, x, w, sum));
    Outcome {
        iterations,
        max_before: max0,
        max_after: max1,
        imbalance_before: imb0,
        imbalance_after: imb1,
    }
}

impl Simulation {
    /// The ranks along x, y, z of the grid a `balance` works on (1, 1, 1 on one process).
    pub fn balance_procs(&self) -> Result<[usize; 3], EngineError> {
        Ok(self.balanced_grid(0)?.procs)
    }
}
