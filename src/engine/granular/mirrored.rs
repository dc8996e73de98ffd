//! The exact path's pair pass on a list with periodic mirrors: LIGGGHTS (newton off) computes
//! a pair across a periodic face once from each side, each side with its own contact history,
//! and adds each side's force to its own atom where that atom's list reaches the pair. The
//! entries and the mirrors are computed as separate batches (each contact depends only on its
//! own inputs), then added in LIGGGHTS's order.

use super::{add6, batch, half_virial, later_worst, Collect, PairGran, PairResult};
use crate::engine::contact::{CohesionModel, NormalModel, RollingModel, TangentialModel};
use crate::engine::neighbor::{Mirrored, Pair};
use crate::engine::particles::Particles;

/// Touching entries computed before their forces are added (a buffer that stays in cache).
const ROUND: usize = 1024;

/// Buffers of the mirrors' pass, reused between steps.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    pairs: Vec<Pair>,
    touching: Vec<u32>,
    results: Vec<PairResult>,
}

/// Add one side of a contact (force N, torque N m) to atom `n`, and half the pair's virial
/// (N m) when tallied.
#[inline(always)]
fn add_side(
    p: &mut Particles,
    n: usize,
    f: &[f64; 3],
    t: &[f64; 3],
    virial: &mut Option<&mut [[f64; 6]]>,
    w: &[f64; 6],
) {
    for d in 0..3 {
        p.f[n][d] += f[d];
        p.torque[n][d] += t[d];
    }
    if let Some(v) = virial.as_deref_mut() {
        add6(&mut v[n], w);
    }
}

/// Add a contact's side to its first atom, and to its second where the pair lies inside the
/// box and `both` (a mirror adds only its own first atom's side).
#[inline(always)]
fn add_pair(
    p: &mut Particles,
    q: &Pair,
    r: &PairResult,
    virial: &mut Option<&mut [[f64; 6]]>,
    both: bool,
) {
    let w = if virial.is_some() {
        half_virial(&p.x, q, r.fi)
    } else {
        [0.0; 6]
    };
    add_side(p, q.i as usize, &r.fi, &r.ti, virial, &w);
    if both && q.shift == [0.0; 3] {
        add_side(p, q.j as usize, &r.fj, &r.tj, virial, &w);
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairGran<N, T, C, R> {
    /// The pass: entries inside the box add to both atoms, entries across a periodic face
    /// to their first atom, each mirror to its own first atom, in list order with each
    /// mirror just before the entry it is placed at. Contacts are computed a round of
    /// [`ROUND`] touching entries (and the mirrors placed among them) at a time and added
    /// right away, so the results wait in a small buffer rather than one of every contact.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn compute_mirrored(
        &mut self,
        p: &mut Particles,
        pairs: &[Pair],
        history: &mut [f64],
        dt: f64,
        update: bool,
        mut virial: Option<&mut [[f64; 6]]>,
        m: Mirrored<'_>,
    ) {
        let kernel = batch::Kernel::new(&self.model, &self.material, dt, update);
        let packed = &self.packed;
        // the list's and the mirrors' touching entries
        let mut touching = std::mem::take(&mut self.touching);
        touching.clear();
        batch::touching_entries(packed, pairs, 0, &mut touching);
        let mut sc = std::mem::take(&mut self.mirror_scratch);
        sc.pairs.clear();
        sc.pairs.extend(m.mirrors.iter().map(|x| x.pair));
        sc.touching.clear();
        batch::touching_entries(packed, &sc.pairs, 0, &mut sc.touching);
        let mut results = std::mem::take(&mut self.results);
        let (mut worst, mut worst_side) = (None, None);
        let mirror_at = |b: usize| m.mirrors[sc.touching[b] as usize].at;
        // the next touching mirror to add
        let mut b = 0usize;
        let mut rounds = touching.chunks(ROUND);
        loop {
            let round = rounds.next().unwrap_or_default();
            // the mirrors placed up to this round's last entry (all of them after the last)
            let mut b_end = b;
            while b_end < sc.touching.len()
                && round.last().is_none_or(|&last| mirror_at(b_end) <= last)
            {
                b_end += 1;
            }
            results.resize(round.len(), PairResult::default());
            let mut main = Collect {
                out: &mut results,
                n: 0,
                worst: None,
            };
            kernel.run(packed, &p.kind, pairs, round, history, &mut main);
            worst = later_worst(worst, main.worst);
            sc.results.resize(b_end - b, PairResult::default());
            let mut side = Collect {
                out: &mut sc.results,
                n: 0,
                worst: None,
            };
            let placed = &sc.touching[b..b_end];
            kernel.run(packed, &p.kind, &sc.pairs, placed, m.history, &mut side);
            worst_side = later_worst(worst_side, side.worst);
            // add in LIGGGHTS's order: each touching mirror just before its entry
            let b0 = b;
            for (a, &e) in round.iter().enumerate() {
                while b < b_end && mirror_at(b) <= e {
                    let q = &sc.pairs[sc.touching[b] as usize];
                    add_pair(p, q, &sc.results[b - b0], &mut virial, false);
                    b += 1;
                }
                add_pair(p, &pairs[e as usize], &results[a], &mut virial, true);
            }
            for b in b..b_end {
                let q = &sc.pairs[sc.touching[b] as usize];
                add_pair(p, q, &sc.results[b - b0], &mut virial, false);
            }
            b = b_end;
            if round.is_empty() {
                break;
            }
        }
        self.worst = later_worst(worst, worst_side);
        self.results = results;
        self.touching = touching;
        self.mirror_scratch = sc;
    }
}
