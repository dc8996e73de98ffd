//! The fast path's pair pass by blocks of particles: each block finds and computes its
//! touching entries and adds them to its own particles, keeping what it owes other blocks'
//! particles in list order; those contributions are then added block by block. The sums do
//! not depend on the number of threads.

use super::*;
use crate::engine::contact::{F64x4, PairLanesOutput, LANES};

/// One block's forces (N), torques (N m) and, on steps that tally them, virials (N m).
type BlockForces<'a> = (
    &'a mut [[f64; 3]],
    &'a mut [[f64; 3]],
    Option<&'a mut [[f64; 6]]>,
);

/// A contribution to a particle of another block: particle index, force (N), torque (N m).
#[derive(Debug, Clone, Copy, Default)]
pub struct Foreign {
    j: u32,
    f: [f64; 3],
    t: [f64; 3],
}

/// One block's contributions to other blocks' particles (buffers reused between steps).
#[derive(Debug, Clone, Default)]
pub struct Owed {
    /// In the order they were made.
    made: Vec<Foreign>,
    /// Their half virials (force length), in the same order, on steps that tally them.
    made_virial: Vec<[f64; 6]>,
    /// The same grouped as `by_block`.
    virial_by_block: Vec<[f64; 6]>,
    /// The same grouped by the block of the particle, each group in the order made.
    by_block: Vec<Foreign>,
    /// Where each block's group starts in `by_block` (one more value than blocks).
    start: Vec<u32>,
}

impl Owed {
    /// Group `made` by block (a counting sort: two passes, no comparisons).
    fn group(&mut self, blocks: usize) {
        let block = |c: &Foreign| c.j as usize / BLOCK_PARTICLES;
        self.start.clear();
        self.start.resize(blocks + 2, 0);
        for c in &self.made {
            self.start[block(c) + 2] += 1;
        }
        for t in 2..blocks + 2 {
            self.start[t] += self.start[t - 1];
        }
        // start[t + 1] is where block t's group begins: place each one there, in order
        self.by_block.clear();
        self.by_block.resize(self.made.len(), Foreign::default());
        let virial = self.made_virial.len() == self.made.len();
        self.virial_by_block.clear();
        if virial {
            self.virial_by_block.resize(self.made.len(), [0.0; 6]);
        }
        for (n, c) in self.made.iter().enumerate() {
            let at = &mut self.start[block(c) + 1];
            self.by_block[*at as usize] = *c;
            if virial {
                self.virial_by_block[*at as usize] = self.made_virial[n];
            }
            *at += 1;
        }
        // start[t + 1] is now where block t's group ends, so start[t] where it begins
        self.start.pop();
    }

    /// The contributions to block `t`'s particles, in the order they were made.
    fn to_block(&self, t: usize) -> &[Foreign] {
        match (self.start.get(t), self.start.get(t + 1)) {
            (Some(&a), Some(&b)) => &self.by_block[a as usize..b as usize],
            _ => &[],
        }
    }

    /// The half virials of [`Self::to_block`] (empty on steps that do not tally them).
    fn virial_to_block(&self, t: usize) -> &[[f64; 6]] {
        match (self.start.get(t), self.start.get(t + 1)) {
            (Some(&a), Some(&b)) if !self.virial_by_block.is_empty() => {
                &self.virial_by_block[a as usize..b as usize]
            }
            _ => &[],
        }
    }
}

/// Positions of all particles (m) and one block's per-particle virials (N m), on steps that
/// tally the virial.
type BlockVirial<'a> = Option<(&'a [[f64; 3]], &'a mut [[f64; 6]])>;

/// One block's sums: its own particles' forces and torques from its list entries (first
/// particles all in the block), and its contributions to other blocks' particles, kept in
/// list order.
struct BlockSums<'a> {
    /// First particle of the block.
    lo: usize,
    f: &'a mut [[f64; 3]],
    torque: &'a mut [[f64; 3]],
    /// Positions of all particles and the block's per-particle virials, on steps that
    /// tally the virial.
    virial: BlockVirial<'a>,
    foreign: &'a mut Owed,
    worst: Option<(f64, u32, u32)>,
}

impl BlockSums<'_> {
    /// Add one side of a pair to particle `n`: force (N), torque (N m) and, when tallied,
    /// half the pair's virial `w`.
    #[inline(never)]
    fn add(&mut self, n: usize, f: [f64; 3], t: [f64; 3], w: &[f64; 6]) {
        match n.checked_sub(self.lo).filter(|&k| k < self.f.len()) {
            Some(k) => {
                for d in 0..3 {
                    self.f[k][d] += f[d];
                    self.torque[k][d] += t[d];
                }
                if let Some((_, v)) = self.virial.as_mut() {
                    add6(&mut v[k], w);
                }
            }
            None => self.owe(n, f, t, w),
        }
    }

    /// Keep a contribution to particle `n` of another block for the second pass: force
    /// (N), torque (N m) and, when tallied, half the pair's virial `w`.
    #[inline(always)]
    fn owe(&mut self, n: usize, f: [f64; 3], t: [f64; 3], w: &[f64; 6]) {
        self.foreign.made.push(Foreign { j: n as u32, f, t });
        if self.virial.is_some() {
            self.foreign.made_virial.push(*w);
        }
    }

    /// Half the virial of a pair whose force on i is `fi` (zeros when not tallied).
    #[inline(always)]
    fn half_virial(&self, pair: &Pair, fi: [f64; 3]) -> [f64; 6] {
        match &self.virial {
            Some((x, _)) => half_virial(x, pair, fi),
            None => [0.0; 6],
        }
    }
}

impl batch::Sink for BlockSums<'_> {
    #[inline(always)]
    fn take_batch(
        &mut self,
        batch: &[u32],
        pairs: &[&Pair; LANES],
        out: &PairLanesOutput,
        overlaps: &batch::Overlaps,
    ) {
        let len = self.f.len().min(self.torque.len());
        for (k, pair) in pairs.iter().enumerate().take(batch.len()) {
            let (i, j) = (pair.i as usize, pair.j as usize);
            let (ki, kj) = (i.wrapping_sub(self.lo), j.wrapping_sub(self.lo));
            let pick = |v: &[F64x4; 3]| [v[0].0[k], v[1].0[k], v[2].0[k]];
            if ki < len && kj < len {
                // both particles in the block (most contacts)
                // SAFETY: ki, kj < len (just checked)
                unsafe { add_lane(self.f, self.torque, (ki, kj), out, k) };
                if let Some((x, v)) = self.virial.as_mut() {
                    let w = half_virial(x, pair, pick(&out.fi));
                    add6(&mut v[ki], &w);
                    add6(&mut v[kj], &w);
                }
            } else if ki < len {
                // i in the block (the list groups entries by i), j in another block
                let w = self.half_virial(pair, pick(&out.fi));
                let (fi, ti) = (pick(&out.fi), pick(&out.ti));
                for d in 0..3 {
                    self.f[ki][d] += fi[d];
                    self.torque[ki][d] += ti[d];
                }
                if let Some((_, v)) = self.virial.as_mut() {
                    add6(&mut v[ki], &w);
                }
                self.owe(j, pick(&out.fj), pick(&out.tj), &w);
            } else {
                let w = self.half_virial(pair, pick(&out.fi));
                self.add(i, pick(&out.fi), pick(&out.ti), &w);
                self.add(j, pick(&out.fj), pick(&out.tj), &w);
            }
        }
        self.worst = worst_of_batch(self.worst, batch.len(), pairs, overlaps);
    }

    #[inline(always)]
    fn take(&mut self, _: usize, pair: &Pair, res: &PairResult) {
        let w = self.half_virial(pair, res.fi);
        self.add(pair.i as usize, res.fi, res.ti, &w);
        self.add(pair.j as usize, res.fj, res.tj, &w);
        if self.worst.is_none_or(|w| res.overlap_ratio > w.0) {
            self.worst = Some((res.overlap_ratio, pair.i, pair.j));
        }
    }
}

/// One block's work: its list entries, its touching entries (buffer), its entries'
/// history and its sums.
type BlockJob<'a> = (
    std::ops::Range<usize>,
    &'a mut Vec<u32>,
    &'a mut [f64],
    BlockSums<'a>,
);

/// Cut forces, torques, history and (when tallied) virials into the blocks' jobs: block `b`
/// owns particles `b * BLOCK_PARTICLES..` and list entries `starts[b]..starts[b + 1]`.
#[allow(clippy::too_many_arguments)]
fn block_jobs<'a>(
    x: &'a [[f64; 3]],
    mut f: &'a mut [[f64; 3]],
    mut t: &'a mut [[f64; 3]],
    mut h: &'a mut [f64],
    virial: Option<&'a mut [[f64; 6]]>,
    width: usize,
    starts: &[u32],
    parts: &'a mut [Vec<u32>],
    foreign: &'a mut [Owed],
) -> Vec<BlockJob<'a>> {
    let tally = virial.is_some();
    let mut w: &mut [[f64; 6]] = virial.unwrap_or_default();
    let mut jobs = Vec::with_capacity(parts.len());
    for (b, (touch, out)) in parts.iter_mut().zip(foreign.iter_mut()).enumerate() {
        let own = BLOCK_PARTICLES.min(f.len());
        let (fb, rest) = std::mem::take(&mut f).split_at_mut(own);
        f = rest;
        let (tb, rest) = std::mem::take(&mut t).split_at_mut(own);
        t = rest;
        let (s, e) = (starts[b] as usize, starts[b + 1] as usize);
        let (hb, rest) = std::mem::take(&mut h).split_at_mut((e - s) * width);
        h = rest;
        let virial = if tally {
            let (wb, rest) = std::mem::take(&mut w).split_at_mut(own);
            w = rest;
            Some((x, wb))
        } else {
            None
        };
        let sums = BlockSums {
            lo: b * BLOCK_PARTICLES,
            f: fb,
            torque: tb,
            virial,
            foreign: out,
            worst: None,
        };
        jobs.push((s..e, touch, hb, sums));
    }
    jobs
}

/// Add what the blocks owe each other's particles: each block adds the contributions to
/// its particles in block order (blocks on the engine's threads when `parallel`).
fn add_owed(
    foreign: &[Owed],
    f: &mut [[f64; 3]],
    torque: &mut [[f64; 3]],
    virial: Option<&mut [[f64; 6]]>,
    parallel: bool,
) {
    let owed = |(t, (f, torque, mut w)): (usize, BlockForces)| {
        let lo = (t * BLOCK_PARTICLES) as u32;
        for out in foreign {
            let half = out.virial_to_block(t);
            for (n, c) in out.to_block(t).iter().enumerate() {
                let k = (c.j - lo) as usize;
                for d in 0..3 {
                    f[k][d] += c.f[d];
                    torque[k][d] += c.t[d];
                }
                if let (Some(w), Some(h)) = (w.as_deref_mut(), half.get(n)) {
                    add6(&mut w[k], h);
                }
            }
        }
    };
    match virial {
        _ if parallel => {
            let n = f.len();
            let (fs, ts) = (Shards::new(f), Shards::new(torque));
            let ws = virial.map(Shards::new);
            crate::util::team::stage_chunks(n, BLOCK_PARTICLES, true, |t, r| {
                // SAFETY: each task takes its own block's particles
                let (f, torque) = unsafe { (fs.range(r.clone()), ts.range(r.clone())) };
                let w = ws.as_ref().map(|w| unsafe { w.range(r.clone()) });
                owed((t, (f, torque, w)));
            });
        }
        Some(w) => f
            .chunks_mut(BLOCK_PARTICLES)
            .zip(torque.chunks_mut(BLOCK_PARTICLES))
            .zip(w.chunks_mut(BLOCK_PARTICLES))
            .map(|((f, t), w)| (f, t, Some(w)))
            .enumerate()
            .for_each(owed),
        None => f
            .chunks_mut(BLOCK_PARTICLES)
            .zip(torque.chunks_mut(BLOCK_PARTICLES))
            .map(|(f, t)| (f, t, None))
            .enumerate()
            .for_each(owed),
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairGran<N, T, C, R> {
    /// The fast path's pair pass ([`SumOrder::Blocks`]): each block of particles finds and
    /// computes its touching entries and adds them to its own particles (blocks on the
    /// engine's threads), then contributions to other blocks' particles are added in block
    /// order. No step depends on the number of threads.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn compute_blocks(
        &mut self,
        p: &mut Particles,
        pairs: &[Pair],
        history: &mut [f64],
        dt: f64,
        update: bool,
        mut virial: Option<&mut [[f64; 6]]>,
        starts: &[u32],
    ) {
        let kernel = batch::Kernel::new(&self.model, &self.material, dt, update);
        let packed = &self.packed;
        let width = self.model.history_len();
        let blocks = starts.len() - 1;
        let mut parts = std::mem::take(&mut self.parts);
        parts.resize_with(blocks, Vec::new);
        let mut foreign = std::mem::take(&mut self.foreign);
        foreign.resize_with(blocks, Owed::default);
        // each block owns its particles' forces, its entries' history and its buffers
        let jobs = block_jobs(
            &p.x,
            &mut p.f,
            &mut p.torque,
            history,
            virial.as_deref_mut(),
            width,
            starts,
            &mut parts,
            &mut foreign,
        );
        let kinds = &p.kind;
        let run = |(range, touch, h, mut sums): BlockJob| {
            let part = &pairs[range];
            sums.f.fill([0.0; 3]);
            sums.torque.fill([0.0; 3]);
            touch.clear();
            sums.foreign.made.clear();
            sums.foreign.made_virial.clear();
            batch::touching_entries(packed, part, 0, touch);
            kernel.run(packed, kinds, part, touch, h, &mut sums);
            sums.foreign.group(blocks);
            sums.worst
        };
        let parallel = rayon::current_num_threads() > 1 && blocks > 1 && !crate::util::team::held();
        let worst: Vec<Option<(f64, u32, u32)>> = if parallel {
            let mut jobs: Vec<_> = jobs.into_iter().map(Some).collect();
            let mut worst = vec![None; blocks];
            let (js, ws) = (Shards::new(&mut jobs), Shards::new(&mut worst));
            crate::util::team::stage(blocks, parallel, |b| {
                // SAFETY: each task takes its own block's job and result slot
                let (job, slot) = unsafe { (js.range(b..b + 1), ws.range(b..b + 1)) };
                if let Some(job) = job[0].take() {
                    slot[0] = run(job);
                }
            });
            worst
        } else {
            jobs.into_iter().map(run).collect()
        };
        // contributions between blocks (the same sums as one pass over the lists)
        if foreign.iter().any(|out| !out.made.is_empty()) {
            add_owed(&foreign, &mut p.f, &mut p.torque, virial, parallel);
        }
        // the worst overlap, first in block order among equals
        self.worst = worst.into_iter().fold(None, later_worst);
        // only their number is read (the run's summary): no list of them is made
        self.touching.clear();
        self.block_contacts = Some(parts.iter().map(Vec::len).sum());
        self.parts = parts;
        self.foreign = foreign;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contributions_grouped_by_block_keep_the_order_they_were_made_in() {
        let b = BLOCK_PARTICLES as u32;
        let targets = [3 * b + 1, b, 3 * b + 1, 2 * b + 7, b + 5, 3 * b, b];
        let mut owed = Owed::default();
        for (k, &j) in targets.iter().enumerate() {
            let f = [k as f64, 0.0, 0.0];
            owed.made.push(Foreign { j, f, t: f });
        }
        owed.group(4);
        assert!(owed.to_block(0).is_empty());
        let order = |t: usize| -> Vec<(u32, f64)> {
            owed.to_block(t).iter().map(|c| (c.j, c.f[0])).collect()
        };
        assert_eq!(order(1), vec![(b, 1.0), (b + 5, 4.0), (b, 6.0)]);
        assert_eq!(order(2), vec![(2 * b + 7, 3.0)]);
        assert_eq!(
            order(3),
            vec![(3 * b + 1, 0.0), (3 * b + 1, 2.0), (3 * b, 5.0)]
        );
        assert!(owed.to_block(4).is_empty());
        // a second step reuses the buffers
        owed.made.clear();
        owed.group(4);
        assert!((0..4).all(|t| owed.to_block(t).is_empty()));
    }
}
