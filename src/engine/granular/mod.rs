//! The granular force loops of `pair_style gran` (over the neighbour list) and `fix
//! wall/gran` primitives (over particles). The contact mechanics live in
//! [`crate::engine::contact`]; here a selected [`ContactModel`] is wrapped once per run into
//! a loop monomorphised for its sub-models, so the hot loop has no dynamic dispatch and
//! stores exactly the history the model needs.

use rayon::prelude::*;

use crate::engine::contact::{
    AnyContactModel, CohesionModel, ContactKernel, ContactModel, F64x4, Material, MaterialInput,
    NormalModel, PairInput, PairLanesOutput, RollingModel, TangentialModel, WallInput, LANES,
};
use crate::engine::error::EngineError;
use crate::engine::neighbor::{Incidence, Mirrored, Pair, SumOrder, BLOCK_PARTICLES};
use crate::engine::particles::Particles;
use crate::engine::sim::PairInteraction;
use crate::util::team::Shards;

pub mod batch;
mod blocks;
pub use blocks::{Foreign, Owed};
mod mirrored;
pub mod multicontact;
pub mod multicontact_store;
mod multicontact_wall;
pub use batch::PairResult;
pub use multicontact::{build_multicontact, MulticontactInput};
pub use multicontact_store::WallStore;
pub use multicontact_wall::build_wall_multicontact;
mod wall;
pub mod wet;
pub use wall::{build_wall, Primitive, WallGran, WallInteraction};
pub use wet::{build_wet, WetInput};

pub use crate::engine::contact::ModelSelection as Selection;

/// A granular pair interaction: the contact model and its per-type-pair coefficients.
pub struct PairGran<N, T, C, R> {
    /// The composed contact model.
    pub model: ContactModel<N, T, C, R>,
    /// Per-type-pair coefficients.
    pub material: Material,
    /// Group bits of frozen particles (infinite mass in contacts).
    pub frozen: u32,
    /// Per-pair results of the current step (reused between steps).
    pub results: Vec<PairResult>,
    /// Indices of the touching list entries of the current step (reused between steps).
    pub touching: Vec<u32>,
    /// The particles packed for the kernel (reused between steps).
    pub packed: batch::Packed,
    /// Per list entry, its place among the touching entries (u32::MAX: apart).
    pub slot: Vec<u32>,
    /// The parallel pass's touching entries, per part of the list (indices within the part).
    pub parts: Vec<Vec<u32>>,
    /// Touching entries of the last fast-path (block) pass, which keeps no list of them
    /// (None after any other pass: [`Self::touching`] holds them).
    pub block_contacts: Option<usize>,
    /// The largest overlap of the last evaluation: (ratio to the smaller radius, i, j).
    pub worst: Option<(f64, u32, u32)>,
    /// The fast path's contributions between blocks of particles, per block (reused).
    pub foreign: Vec<Owed>,
    /// The mirrors' pairs, touching entries and results of the current step (reused).
    pub mirror_scratch: mirrored::Scratch,
}

/// Below this many listed pairs the contact loop stays on one thread (the fork-join cost of
/// a parallel pass is larger than the work); `REGOLITH_PARALLEL_PAIRS` overrides it. Either
/// way the sums are the same.
pub fn parallel_pairs() -> usize {
    static LIMIT: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *LIMIT.get_or_init(|| {
        std::env::var("REGOLITH_PARALLEL_PAIRS")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(20_000)
    })
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairGran<N, T, C, R> {
    /// The contribution of one listed pair; `h` is its history.
    #[inline(always)]
    fn pair_result(
        &self,
        p: &Particles,
        pair: &Pair,
        h: &mut [f64],
        dt: f64,
        update: bool,
    ) -> Option<PairResult> {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let xi = p.x[i];
        let xj = [
            p.x[j][0] + pair.shift[0],
            p.x[j][1] + pair.shift[1],
            p.x[j][2] + pair.shift[2],
        ];
        let (radi, radj) = (p.radius[i], p.radius[j]);
        // most listed pairs do not touch: leave before loading anything else
        let del = [xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]];
        let radsum = radi + radj;
        // a NaN distance is no contact
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(del[0] * del[0] + del[1] * del[1] + del[2] * del[2] < radsum * radsum) {
            return None;
        }
        let input = PairInput {
            xi,
            xj,
            radi,
            radj,
            mi: p.mass[i],
            mj: p.mass[j],
            frozen_i: p.mask[i] & self.frozen != 0,
            frozen_j: p.mask[j] & self.frozen != 0,
            vi: p.v[i],
            vj: p.v[j],
            omegai: p.omega[i],
            omegaj: p.omega[j],
            dt,
            update_history: update,
            coeffs: self.material.pair(p.kind[i] as usize, p.kind[j] as usize),
        };
        let out = self.model.pair_force(&input, h);
        if !out.touching {
            return None;
        }
        Some(PairResult {
            fi: out.fi,
            fj: out.fj,
            ti: out.ti,
            tj: out.tj,
            overlap_ratio: out.deltan / input.radi.min(input.radj),
        })
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairInteraction
    for PairGran<N, T, C, R>
{
    fn history_width(&self) -> usize {
        self.model.history_len()
    }

    fn history_flips(&self) -> Vec<bool> {
        self.model.history_flips()
    }

    fn worst_overlap(&self) -> Option<(f64, u32, u32)> {
        self.worst
    }

    fn contact_count(&self) -> usize {
        self.block_contacts.unwrap_or(self.touching.len())
    }

    fn contacts(
        &self,
        p: &Particles,
        pairs: &[Pair],
        history: &[f64],
        dt: f64,
        ghost: (&[[f64; 3]], &[[f64; 3]]),
    ) -> Vec<(usize, [f64; 3], [f64; 3], [f64; 3], [f64; 3])> {
        let width = self.model.history_len();
        let mut h = vec![0.0; width];
        let mut out = Vec::new();
        let mut scratch: Option<Particles> = None;
        for (k, pair) in pairs.iter().enumerate() {
            h.copy_from_slice(&history[k * width..(k + 1) * width]);
            let (i, j) = (pair.i as usize, pair.j as usize);
            let r = if pair.shift != [0.0; 3] && ghost.0.len() == p.len() {
                // the ghost side keeps the velocities of the last force evaluation
                let g = if p.id[i] < p.id[j] { i } else { j };
                let q = scratch.get_or_insert_with(|| p.clone());
                q.v[g] = ghost.0[g];
                q.omega[g] = ghost.1[g];
                let r = self.pair_result(q, pair, &mut h, dt, false);
                q.v[g] = p.v[g];
                q.omega[g] = p.omega[g];
                r
            } else {
                self.pair_result(p, pair, &mut h, dt, false)
            };
            if let Some(r) = r {
                out.push((k, r.fi, r.ti, r.fj, r.tj));
            }
        }
        out
    }

    fn compute(
        &mut self,
        p: &mut Particles,
        pairs: &[Pair],
        history: &mut [f64],
        dt: f64,
        update: bool,
        virial: Option<&mut [[f64; 6]]>,
        order: &SumOrder,
        mirrored: Option<Mirrored<'_>>,
    ) {
        self.packed.fill(p, self.frozen);
        self.block_contacts = None;
        let threads = rayon::current_num_threads();
        match order {
            SumOrder::Gathered(inc) if threads > 1 && inc.first.len() == p.len() + 1 => {
                p.clear_forces();
                self.compute_gather(p, pairs, history, dt, update, virial, inc);
                return;
            }
            SumOrder::Blocks(starts)
                if starts.len() == p.len().div_ceil(BLOCK_PARTICLES).max(1) + 1
                    && starts.last() == Some(&(pairs.len() as u32)) =>
            {
                // each block clears its own particles' sums
                self.compute_blocks(p, pairs, history, dt, update, virial, starts);
                return;
            }
            _ => {}
        }
        p.clear_forces();
        if let Some(m) = mirrored {
            self.compute_mirrored(p, pairs, history, dt, update, virial, m);
            return;
        }
        let kernel = batch::Kernel::new(&self.model, &self.material, dt, update);
        let packed = &self.packed;
        let mut touching = std::mem::take(&mut self.touching);
        touching.clear();
        let mut sink = Accumulate {
            x: &p.x,
            f: &mut p.f,
            torque: &mut p.torque,
            virial,
            worst: None,
        };
        // compute the touching pairs in batches and add each in list order
        batch::touching_entries(packed, pairs, 0, &mut touching);
        kernel.run(packed, &p.kind, pairs, &touching, history, &mut sink);
        self.worst = sink.worst;
        self.touching = touching;
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairGran<N, T, C, R> {
    /// The parallel pair loop: touching entries found and computed in parallel parts of the
    /// list, then each particle sums its own contacts in list order (the sums of a
    /// sequential pass, for any number of threads).
    #[allow(clippy::too_many_arguments)]
    fn compute_gather(
        &mut self,
        p: &mut Particles,
        pairs: &[Pair],
        history: &mut [f64],
        dt: f64,
        update: bool,
        virial: Option<&mut [[f64; 6]]>,
        inc: &Incidence,
    ) {
        let kernel = batch::Kernel::new(&self.model, &self.material, dt, update);
        let packed = &self.packed;
        let threads = rayon::current_num_threads();
        let width = self.model.history_len();
        let chunk = pairs.len().div_ceil(threads * 8).max(2048);
        let mut parts = std::mem::take(&mut self.parts);
        parts.resize_with(pairs.len().div_ceil(chunk), Vec::new);
        parts
            .par_iter_mut()
            .zip(pairs.par_chunks(chunk))
            .for_each(|(t, part)| {
                t.clear();
                batch::touching_entries(packed, part, 0, t);
            });
        let total: usize = parts.iter().map(Vec::len).sum();
        // every slot is written by its part's kernel: keep the old values rather than clear
        let mut results = std::mem::take(&mut self.results);
        results.resize(total, PairResult::default());
        let mut slot = std::mem::take(&mut self.slot);
        slot.clear();
        slot.resize(pairs.len(), u32::MAX);
        // each part owns its results, its entries' history and their slots
        {
            let mut jobs = Vec::with_capacity(parts.len());
            let (mut rest_r, mut rest_h, mut rest_s) =
                (&mut results[..], &mut history[..], &mut slot[..]);
            let mut offset = 0u32;
            for (c, part) in parts.iter().enumerate() {
                let (r, tail) = std::mem::take(&mut rest_r).split_at_mut(part.len());
                rest_r = tail;
                let len = chunk.min(pairs.len() - c * chunk);
                let (h, tail) = std::mem::take(&mut rest_h).split_at_mut(len * width);
                rest_h = tail;
                let (sl, tail) = std::mem::take(&mut rest_s).split_at_mut(len);
                rest_s = tail;
                jobs.push((c * chunk, part, r, h, sl, offset));
                offset += part.len() as u32;
            }
            let kinds = &p.kind;
            let worst_of_parts: Vec<Option<(f64, u32, u32)>> = jobs
                .into_par_iter()
                .map(|(base, part, out, h, sl, offset)| {
                    for (n, &k) in part.iter().enumerate() {
                        sl[k as usize] = offset + n as u32;
                    }
                    let mut collect = Collect {
                        out,
                        n: 0,
                        worst: None,
                    };
                    kernel.run(packed, kinds, &pairs[base..], part, h, &mut collect);
                    collect.worst
                })
                .collect();
            // the worst overlap, first in list order among equals (as the sequential pass)
            self.worst = worst_of_parts.into_iter().fold(None, later_worst);
        }
        // each particle adds its contacts: as second particle, then its own block
        gather_sums(p, pairs, inc, &slot, &results, virial, threads);
        self.results = results;
        self.slot = slot;
        self.touching.clear();
        for (c, part) in parts.iter().enumerate() {
            let base = (c * chunk) as u32;
            self.touching.extend(part.iter().map(|&k| base + k));
        }
        self.parts = parts;
    }
}

/// Each particle's sums from the computed contacts (`results`, at `slot` per list entry,
/// u32::MAX: apart): its entries as second particle, then its own, in list order (particles
/// in parallel parts).
fn gather_sums(
    p: &mut Particles,
    pairs: &[Pair],
    inc: &Incidence,
    slot: &[u32],
    results: &[PairResult],
    virial: Option<&mut [[f64; 6]]>,
    threads: usize,
) {
    let x = &p.x;
    let per = p.len().div_ceil(threads * 8).max(256);
    let add = |i: usize, f: &mut [f64; 3], t: &mut [f64; 3], w: Option<&mut [f64; 6]>| {
        let mut w = w;
        let seconds = &inc.second[inc.second_start[i] as usize..inc.second_start[i + 1] as usize];
        // as second particle (the j side of each result), then its own block (the i side)
        let entries = seconds
            .iter()
            .map(|&e| (e as usize, true))
            .chain((inc.first[i]..inc.first[i + 1]).map(|e| (e as usize, false)));
        for (e, second) in entries {
            let s = slot[e];
            if s == u32::MAX {
                continue;
            }
            let r = &results[s as usize];
            let (rf, rt) = if second {
                (&r.fj, &r.tj)
            } else {
                (&r.fi, &r.ti)
            };
            for d in 0..3 {
                f[d] += rf[d];
                t[d] += rt[d];
            }
            if let Some(w) = w.as_deref_mut() {
                add_virial(x, &pairs[e], r, w);
            }
        }
    };
    match virial {
        Some(vir) => {
            p.f.par_chunks_mut(per)
                .zip(p.torque.par_chunks_mut(per))
                .zip(vir.par_chunks_mut(per))
                .enumerate()
                .for_each(|(c, ((f, t), w))| {
                    for k in 0..f.len() {
                        add(c * per + k, &mut f[k], &mut t[k], Some(&mut w[k]));
                    }
                })
        }
        None => {
            p.f.par_chunks_mut(per)
                .zip(p.torque.par_chunks_mut(per))
                .enumerate()
                .for_each(|(c, (f, t))| {
                    for k in 0..f.len() {
                        add(c * per + k, &mut f[k], &mut t[k], None);
                    }
                })
        }
    }
}

/// The worst overlap `(ratio, i, j)` of two parts in order: the second only where larger,
/// so the first in order among equals is kept.
fn later_worst(
    first: Option<(f64, u32, u32)>,
    second: Option<(f64, u32, u32)>,
) -> Option<(f64, u32, u32)> {
    match (first, second) {
        (Some(a), Some(b)) if b.0 > a.0 => Some(b),
        (None, b) => b,
        (a, _) => a,
    }
}

/// The contact of touching particles `i` and `j` of `p` as a dry pair's sub-models start
/// from it: separation `delta` = x_i - x_j (m) at distance `r` (m), the radii (radius of i,
/// of j and their sum, m) the sub-models see, the group bits of frozen particles, the step
/// `dt` (s) and whether history advances.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn touching_contact(
    p: &Particles,
    (i, j): (usize, usize),
    delta: [f64; 3],
    r: f64,
    (radi, radj, radsum): (f64, f64, f64),
    frozen: u32,
    dt: f64,
    update: bool,
) -> crate::engine::contact::Contact {
    let rinv = 1.0 / r;
    let en = delta.map(|d| d * rinv);
    let (mi, mj) = (p.mass[i], p.mass[j]);
    let mut meff = mi * mj / (mi + mj);
    if p.mask[i] & frozen != 0 {
        meff = mj;
    }
    if p.mask[j] & frozen != 0 {
        meff = mi;
    }
    crate::engine::contact::Contact {
        is_wall: false,
        radi,
        radj,
        radsum,
        r,
        rinv,
        delta,
        en,
        mi,
        mj,
        meff,
        vi: p.v[i],
        vj: p.v[j],
        omegai: p.omega[i],
        omegaj: p.omega[j],
        dt,
        update_history: update,
        ..Default::default()
    }
}

/// Half a pair's virial (LIGGGHTS's `ev_tally_xyz` with del = x_i - x_j and F the force
/// on i) added to `w`.
#[inline(always)]
fn add_virial(x: &[[f64; 3]], pair: &Pair, res: &PairResult, w: &mut [f64; 6]) {
    add6(w, &half_virial(x, pair, res.fi));
}

/// `w += h`, component by component.
#[inline(always)]
fn add6(w: &mut [f64; 6], h: &[f64; 6]) {
    for k in 0..6 {
        w[k] += h[k];
    }
}

/// Half a pair's virial (force length): what [`add_virial`] adds to each particle, with
/// `fi` the force on i (N).
#[inline(always)]
fn half_virial(x: &[[f64; 3]], pair: &Pair, fi: [f64; 3]) -> [f64; 6] {
    let (i, j) = (pair.i as usize, pair.j as usize);
    let del = [
        x[i][0] - (x[j][0] + pair.shift[0]),
        x[i][1] - (x[j][1] + pair.shift[1]),
        x[i][2] - (x[j][2] + pair.shift[2]),
    ];
    let v = [
        del[0] * fi[0],
        del[1] * fi[1],
        del[2] * fi[2],
        del[0] * fi[1],
        del[0] * fi[2],
        del[1] * fi[2],
    ];
    v.map(|c| 0.5 * c)
}

/// The largest overlap ratio so far, first in order among equals, after a batch whose first
/// `valid` lanes are real pairs: lanes are looked at one by one only when one beats `worst`.
#[inline(always)]
fn worst_of_batch(
    mut worst: Option<(f64, u32, u32)>,
    valid: usize,
    pairs: &[&Pair; LANES],
    overlaps: &batch::Overlaps,
) -> Option<(f64, u32, u32)> {
    let lanes = (1u32 << valid.min(LANES)) - 1;
    let beaten = match worst {
        None => lanes,
        Some((w, _, _)) => overlaps.may_exceed(w) & lanes,
    };
    if beaten != 0 {
        for (k, pair) in pairs.iter().enumerate().take(valid) {
            let r = overlaps.ratio(k);
            if worst.is_none_or(|w| r > w.0) {
                worst = Some((r, pair.i, pair.j));
            }
        }
    }
    worst
}

/// Add lane `k` of a batch's forces and torques to particles `a` (the i side) and `b` (the
/// j side), i's first.
///
/// # Safety
/// `a` and `b` must be below `f.len()` and `torque.len()`.
#[inline(always)]
unsafe fn add_lane(
    f: &mut [[f64; 3]],
    torque: &mut [[f64; 3]],
    (a, b): (usize, usize),
    out: &PairLanesOutput,
    k: usize,
) {
    let sides = [(a, &out.fi, &out.ti), (b, &out.fj, &out.tj)];
    for (n, force, moment) in sides {
        let (f, t) = (f.get_unchecked_mut(n), torque.get_unchecked_mut(n));
        for d in 0..3 {
            f[d] += force[d].0[k];
            t[d] += moment[d].0[k];
        }
    }
}

/// Adds each pair's result to its particles, in the order given (the exact path's sums).
struct Accumulate<'a, 'b> {
    x: &'a [[f64; 3]],
    f: &'a mut [[f64; 3]],
    torque: &'a mut [[f64; 3]],
    virial: Option<&'b mut [[f64; 6]]>,
    worst: Option<(f64, u32, u32)>,
}

impl batch::Sink for Accumulate<'_, '_> {
    #[inline(always)]
    fn take_batch(
        &mut self,
        batch: &[u32],
        pairs: &[&Pair; LANES],
        out: &PairLanesOutput,
        overlaps: &batch::Overlaps,
    ) {
        let n = self.f.len().min(self.torque.len());
        assert!(pairs
            .iter()
            .all(|q| (q.i as usize) < n && (q.j as usize) < n));
        for (k, pair) in pairs.iter().enumerate().take(batch.len()) {
            let (i, j) = (pair.i as usize, pair.j as usize);
            if let Some(w) = self.virial.as_deref_mut() {
                let fi = [out.fi[0].0[k], out.fi[1].0[k], out.fi[2].0[k]];
                let half = half_virial(self.x, pair, fi);
                add6(&mut w[i], &half);
                add6(&mut w[j], &half);
            }
            // SAFETY: i, j < n (checked above)
            unsafe { add_lane(self.f, self.torque, (i, j), out, k) };
        }
        self.worst = worst_of_batch(self.worst, batch.len(), pairs, overlaps);
    }

    #[inline(always)]
    fn take(&mut self, _: usize, pair: &Pair, res: &PairResult) {
        add_pair(
            self.x,
            self.f,
            self.torque,
            pair,
            res,
            self.virial.as_deref_mut(),
        );
        let ratio = res.overlap_ratio;
        if self.worst.is_none_or(|w| ratio > w.0) {
            self.worst = Some((ratio, pair.i, pair.j));
        }
    }
}

/// Stores each result in turn (a parallel part's results, added up later).
struct Collect<'a> {
    out: &'a mut [PairResult],
    n: usize,
    /// The largest overlap ratio of the part, first in order among equals.
    worst: Option<(f64, u32, u32)>,
}

impl batch::Sink for Collect<'_> {
    #[inline(always)]
    fn take(&mut self, _: usize, pair: &Pair, res: &PairResult) {
        self.out[self.n] = *res;
        self.n += 1;
        if self.worst.is_none_or(|w| res.overlap_ratio > w.0) {
            self.worst = Some((res.overlap_ratio, pair.i, pair.j));
        }
    }
}

/// Add one pair's forces and torques to its two particles, and half its virial to each
/// when asked.
#[inline(always)]
fn add_pair(
    x: &[[f64; 3]],
    f: &mut [[f64; 3]],
    torque: &mut [[f64; 3]],
    pair: &Pair,
    res: &PairResult,
    virial: Option<&mut [[f64; 6]]>,
) {
    let (i, j) = (pair.i as usize, pair.j as usize);
    if let Some(w) = virial {
        let half = half_virial(x, pair, res.fi);
        add6(&mut w[i], &half);
        add6(&mut w[j], &half);
    }
    for d in 0..3 {
        f[i][d] += res.fi[d];
        torque[i][d] += res.ti[d];
    }
    for d in 0..3 {
        f[j][d] += res.fj[d];
        torque[j][d] += res.tj[d];
    }
}

/// The model of a selection and its coefficient tables, with LIGGGHTS's material checks.
pub(crate) fn model_and_material(
    sel: &Selection,
    input: &MaterialInput,
) -> Result<(AnyContactModel, Material), EngineError> {
    let model = AnyContactModel::new(sel).map_err(|e| EngineError::Invalid(e.to_string()))?;
    let material = Material::new(input, &model.properties())?;
    Ok((model, material))
}

/// Build the pair interaction for a selection: the loop is monomorphised for the selected
/// sub-models here, once per run.
pub fn build(
    sel: &Selection,
    input: &MaterialInput,
    frozen: u32,
) -> Result<Box<dyn PairInteraction>, EngineError> {
    let (model, material) = model_and_material(sel, input)?;
    struct Make(Material, u32);
    impl ContactKernel for Make {
        type Output = Box<dyn PairInteraction>;
        fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
            self,
            m: &ContactModel<N, T, C, R>,
        ) -> Self::Output {
            Box::new(PairGran {
                model: *m,
                material: self.0,
                frozen: self.1,
                results: Vec::new(),
                touching: Vec::new(),
                packed: batch::Packed::default(),
                slot: Vec::new(),
                parts: Vec::new(),
                block_contacts: None,
                worst: None,
                foreign: Vec::new(),
                mirror_scratch: Default::default(),
            })
        }
    }
    Ok(model.dispatch(Make(material, frozen)))
}
