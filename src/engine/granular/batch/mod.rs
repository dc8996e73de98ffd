//! The batched pair kernel: touching pairs are gathered four at a time into SIMD lanes and
//! run through the contact model once per batch ([`ContactModel::pair_force_lanes`]). Each
//! lane computes exactly what the one-pair kernel computes, so results do not depend on how
//! pairs are batched or split between threads; the caller adds them up in its own order.
//!
//! Particle data are first packed into one 96-byte record per particle ([`Packed`]), so a
//! lane's data comes from three aligned loads instead of a dozen scattered ones. On x86-64
//! processors with AVX2 the loops are compiled a second time with 256-bit vectors and chosen
//! at run time; the arithmetic (no fused multiply-add) is the same either way.

use crate::engine::contact::real::Real;
use crate::engine::contact::{
    CoeffLanes, CoeffWideLanes, Coeffs, CohesionModel, ContactModel, F64x4, F64x8, Material,
    NormalModel, PairCoeffs, PairLanes, PairLanesOutput, RollingModel, TangentialModel, LANES,
    WIDE_LANES,
};
use crate::engine::neighbor::Pair;
use crate::engine::particles::Particles;

mod touching;
pub use touching::touching_entries;

/// What one touching pair contributes: forces (N) and torques (N m) on both particles.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairResult {
    /// Force on i (N).
    pub fi: [f64; 3],
    /// Force on j (N).
    pub fj: [f64; 3],
    /// Torque on i (N m).
    pub ti: [f64; 3],
    /// Torque on j (N m).
    pub tj: [f64; 3],
    /// Overlap as a fraction of the smaller radius (for the blow-up guard).
    pub overlap_ratio: f64,
}

/// The largest history a contact model keeps (hooke/hysteresis 1 + tangential 3 + rolling 3).
pub const MAX_HISTORY: usize = 8;

/// One particle as the kernel reads it: x y z radius | vx vy vz mass | wx wy wz frozen
/// (frozen is 1.0 for particles of a frozen group, else 0.0).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(32))]
pub struct Record(pub [f64; 12]);

/// One particle's sphere as the touching test reads it: x y z (m), radius (m).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(32))]
pub struct Sphere(pub [f64; 4]);

/// The particle records of one force evaluation (rebuilt from the particle arrays).
#[derive(Debug, Clone, Default)]
pub struct Packed {
    /// One record per particle.
    pub records: Vec<Record>,
    /// The records' first four fields again, a third of the size: the touching test runs
    /// over every listed pair and finds these in cache more often.
    pub spheres: Vec<Sphere>,
}

impl Packed {
    /// Pack the particles; `frozen` are the group bits of frozen particles.
    pub fn fill(&mut self, p: &Particles, frozen: u32) {
        let n = p.len();
        // every record is overwritten below: keep the old values rather than clear
        self.records.resize(n, Record::default());
        self.spheres.resize(n, Sphere::default());
        let write = |start: usize, out: (&mut [Record], &mut [Sphere])| {
            #[cfg(target_arch = "x86_64")]
            if crate::engine::contact::real::lanes_supported() {
                // SAFETY: the processor has AVX2 (checked at run time)
                unsafe { fill_range_avx2(p, frozen, start, out) };
                return;
            }
            fill_range(p, frozen, start, out);
        };
        if crate::engine::integrate::parallel(n) {
            const PART: usize = 2048;
            let records = crate::util::team::Shards::new(&mut self.records);
            let spheres = crate::util::team::Shards::new(&mut self.spheres);
            crate::util::team::stage_chunks(n, PART, true, |_, r| {
                // SAFETY: the chunks of a stage are disjoint
                let out = unsafe { (records.range(r.clone()), spheres.range(r.clone())) };
                write(r.start, out)
            });
        } else {
            write(0, (&mut self.records, &mut self.spheres));
        }
    }
}

/// [`fill_range`] with 256-bit moves.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn fill_range_avx2(
    p: &Particles,
    frozen: u32,
    start: usize,
    out: (&mut [Record], &mut [Sphere]),
) {
    fill_range(p, frozen, start, out);
}

/// The records and spheres of the particles from `start` on, as many as `out` holds.
#[inline(always)]
fn fill_range(
    p: &Particles,
    frozen: u32,
    start: usize,
    (out, spheres): (&mut [Record], &mut [Sphere]),
) {
    let end = start + out.len();
    let cols = (
        &p.x[start..end],
        &p.v[start..end],
        &p.omega[start..end],
        &p.radius[start..end],
        &p.mass[start..end],
        &p.mask[start..end],
    );
    for (k, (rec, sphere)) in out.iter_mut().zip(spheres.iter_mut()).enumerate() {
        let (x, v, w) = (cols.0[k], cols.1[k], cols.2[k]);
        let fz = if cols.5[k] & frozen != 0 { 1.0 } else { 0.0 };
        rec.0 = [
            x[0], x[1], x[2], cols.3[k], v[0], v[1], v[2], cols.4[k], w[0], w[1], w[2], fz,
        ];
        sphere.0 = [x[0], x[1], x[2], cols.3[k]];
    }
}

/// How many batches of eight ahead the kernel asks for the records and history it will
/// read: the second particle of a pair and the pair's history are scattered loads the
/// processor cannot foresee, and on beds larger than the caches (50 000 spheres) waiting
/// for them took a fifth of the kernel's time. Any distance from two to eight measured
/// the same.
const PREFETCH_BATCHES: usize = 4;

/// Prefetch only from this many particles on (1.5 MB of records): on a 10 000-sphere bed
/// the data are in cache already and the extra instructions cost 5 %.
const PREFETCH_FROM: usize = 16 * 1024;

/// Ask for the cache lines the kernel will read for `entries` (indices into `pairs`, all
/// below `pairs.len()`): the second particle's record and the pair's history. A hint
/// only: results do not change.
#[inline(always)]
fn prefetch_entries(
    entries: &[u32],
    pairs: &[Pair],
    rec: &[Record],
    history: &[f64],
    width: usize,
) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let last = rec.len().saturating_sub(1);
        for &k in entries {
            let k = k as usize;
            let Some(q) = pairs.get(k) else { continue };
            let j = rec
                .as_ptr()
                .wrapping_add((q.j as usize).min(last))
                .cast::<i8>();
            let h = history.as_ptr().wrapping_add(k * width).cast::<i8>();
            // SAFETY: prefetching is a hint that never faults, whatever the address
            unsafe {
                // a record is 96 bytes on a 32-byte boundary: two lines cover it
                _mm_prefetch::<_MM_HINT_T0>(j);
                _mm_prefetch::<_MM_HINT_T0>(j.wrapping_add(64));
                if width > 0 {
                    // a history may straddle two lines
                    _mm_prefetch::<_MM_HINT_T0>(h);
                    _mm_prefetch::<_MM_HINT_T0>(h.wrapping_add(8 * width - 8));
                }
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (entries, pairs, rec, history, width);
}

/// The coefficients of a run with one atom type: the same in every lane.
#[derive(Debug, Clone, Copy)]
struct CoeffSplat<'a>(&'a PairCoeffs);

impl Coeffs<F64x4> for CoeffSplat<'_> {
    #[inline(always)]
    fn get<F: Fn(&PairCoeffs) -> f64>(&self, f: F) -> F64x4 {
        F64x4([f(self.0); LANES])
    }
}

impl Coeffs<F64x8> for CoeffSplat<'_> {
    #[inline(always)]
    fn get<F: Fn(&PairCoeffs) -> f64>(&self, f: F) -> F64x8 {
        F64x8([f(self.0); WIDE_LANES])
    }
}

/// Where a batch's coefficients come from.
trait CoeffSource {
    type Lanes<'b>: Coeffs<F64x4>
    where
        Self: 'b;
    type WideLanes<'b>: Coeffs<F64x8>
    where
        Self: 'b;
    /// The coefficients of the pairs (i\[k\], j\[k\]); `kinds` are the particles' atom types.
    fn lanes<'b>(
        &'b self,
        material: &'b Material,
        kinds: &[u32],
        i: [usize; LANES],
        j: [usize; LANES],
    ) -> Self::Lanes<'b>;
    /// The same for a wide batch of eight pairs.
    fn wide_lanes<'b>(
        &'b self,
        material: &'b Material,
        kinds: &[u32],
        i: [usize; WIDE_LANES],
        j: [usize; WIDE_LANES],
    ) -> Self::WideLanes<'b>;
}

/// One atom type: every pair has the same coefficients.
struct OneType<'a>(&'a PairCoeffs);

impl CoeffSource for OneType<'_> {
    type Lanes<'b>
        = CoeffSplat<'b>
    where
        Self: 'b;
    type WideLanes<'b>
        = CoeffSplat<'b>
    where
        Self: 'b;
    #[inline(always)]
    fn lanes<'b>(
        &'b self,
        _: &'b Material,
        _: &[u32],
        _: [usize; LANES],
        _: [usize; LANES],
    ) -> CoeffSplat<'b> {
        CoeffSplat(self.0)
    }
    #[inline(always)]
    fn wide_lanes<'b>(
        &'b self,
        _: &'b Material,
        _: &[u32],
        _: [usize; WIDE_LANES],
        _: [usize; WIDE_LANES],
    ) -> CoeffSplat<'b> {
        CoeffSplat(self.0)
    }
}

/// Several atom types: each lane looks its pair up.
struct ByType;

impl CoeffSource for ByType {
    type Lanes<'b> = CoeffLanes<'b>;
    type WideLanes<'b> = CoeffWideLanes<'b>;
    #[inline(always)]
    fn wide_lanes<'b>(
        &'b self,
        material: &'b Material,
        kinds: &[u32],
        i: [usize; WIDE_LANES],
        j: [usize; WIDE_LANES],
    ) -> CoeffWideLanes<'b> {
        // written out, not `from_fn`: an out-of-line closure would lose the kernel's vector code
        let pair = |k: usize| material.pair(kinds[i[k]] as usize, kinds[j[k]] as usize);
        CoeffWideLanes([
            pair(0),
            pair(1),
            pair(2),
            pair(3),
            pair(4),
            pair(5),
            pair(6),
            pair(7),
        ])
    }
    #[inline(always)]
    fn lanes<'b>(
        &'b self,
        material: &'b Material,
        kinds: &[u32],
        i: [usize; LANES],
        j: [usize; LANES],
    ) -> CoeffLanes<'b> {
        // written out, not `from_fn`: an out-of-line closure would lose the kernel's vector code
        let pair = |k: usize| material.pair(kinds[i[k]] as usize, kinds[j[k]] as usize);
        CoeffLanes([pair(0), pair(1), pair(2), pair(3)])
    }
}

/// The model, coefficients and settings the batched loops need.
pub struct Kernel<'a, N, T, C, R> {
    /// The composed contact model.
    pub model: &'a ContactModel<N, T, C, R>,
    /// Per-type-pair coefficients.
    pub material: &'a Material,
    /// Number of atom types.
    pub ntypes: usize,
    /// Time step (s).
    pub dt: f64,
    /// Advance and store history.
    pub update: bool,
}

/// A batch's overlaps (m) and smaller radii (m): the overlap ratios the blow-up guard
/// watches, divided out only where they are needed.
#[derive(Debug, Clone, Copy)]
pub struct Overlaps {
    /// Overlap of each lane (m).
    pub deltan: F64x4,
    /// The smaller radius of each lane's pair (m).
    pub smaller: F64x4,
}

impl Overlaps {
    /// The overlap ratio of lane `k` (overlap over the smaller radius).
    #[inline(always)]
    pub fn ratio(&self, k: usize) -> f64 {
        self.deltan.0[k] / self.smaller.0[k]
    }

    /// The overlap ratios of the four lanes.
    #[inline(always)]
    pub fn ratios(&self) -> F64x4 {
        self.deltan / self.smaller
    }

    /// Bits of the lanes whose ratio may exceed `w`: every lane whose ratio does, and
    /// perhaps a few within round-off of it (a multiplication instead of a division).
    #[inline(always)]
    pub fn may_exceed(&self, w: f64) -> u32 {
        if w.is_nan() {
            // nothing compares greater than NaN
            return 0;
        }
        if w <= 0.0 {
            return 0b1111;
        }
        // a margin far above the few roundings on either side
        let below = w * (1.0 - 1e-12);
        self.deltan.gt(self.smaller * F64x4::splat(below)).bits()
    }
}

/// Where the results of a batch go.
pub trait Sink {
    /// Take the result of list entry `entry` (called in the order of the entries).
    fn take(&mut self, entry: usize, pair: &Pair, result: &PairResult);

    /// Take a batch's results: lane k is entry `batch[k]` (`pairs[k]`), `overlaps` its
    /// overlaps and smaller radii. By default, lane by lane through
    /// [`Sink::take`].
    #[inline(always)]
    fn take_batch(
        &mut self,
        batch: &[u32],
        pairs: &[&Pair; LANES],
        out: &PairLanesOutput,
        overlaps: &Overlaps,
    ) {
        let ratio = overlaps.ratios();
        for (k, &entry) in batch.iter().enumerate() {
            let pick = |v: &[F64x4; 3]| [v[0].0[k], v[1].0[k], v[2].0[k]];
            let result = PairResult {
                fi: pick(&out.fi),
                fj: pick(&out.fj),
                ti: pick(&out.ti),
                tj: pick(&out.tj),
                overlap_ratio: ratio.0[k],
            };
            self.take(entry as usize, pairs[k], &result);
        }
    }
}

/// The periodic shifts of four pairs as x, y, z lanes, or `None` when all are zero (the
/// usual case: nothing to add, so positions stay exactly the particles').
#[inline(always)]
fn shifts(pr: &[&Pair; LANES]) -> Option<[F64x4; 3]> {
    if !any_shift(pr) {
        return None;
    }
    Some(std::array::from_fn(|d| F64x4(pr.map(|q| q.shift[d]))))
}

/// Does any of four pairs carry a shift component other than +-0? On x86-64 one OR of
/// the four 32-byte pairs and one test (the indices and the sign bits masked out).
#[inline(always)]
fn any_shift(pr: &[&Pair; LANES]) -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::*;
        const _: () = assert!(std::mem::size_of::<Pair>() == 32);
        // SAFETY: a Pair is 32 bytes (i, j, then the three shift doubles); lanes code runs
        // only where the processor has AVX2 (see F64x4)
        unsafe {
            let load = |p: &Pair| _mm256_loadu_si256(std::ptr::from_ref(p).cast());
            let q = [load(pr[0]), load(pr[1]), load(pr[2]), load(pr[3])];
            let all = _mm256_or_si256(_mm256_or_si256(q[0], q[1]), _mm256_or_si256(q[2], q[3]));
            let bits = i64::MAX;
            let mask = _mm256_set_epi64x(bits, bits, bits, 0);
            _mm256_testz_si256(all, mask) == 0
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        let bits = pr.iter().fold(0u64, |acc, q| {
            acc | q.shift[0].to_bits() | q.shift[1].to_bits() | q.shift[2].to_bits()
        });
        bits << 1 != 0
    }
}

/// Four records' 12 fields as lanes.
///
/// # Safety
/// Every index must be below `rec.len()`.
#[inline(always)]
unsafe fn transpose(rec: &[Record], idx: [usize; LANES]) -> [F64x4; 12] {
    debug_assert!(idx.iter().all(|&n| n < rec.len()));
    // SAFETY: the caller's indices are inside the records
    let r: [&[f64; 12]; LANES] = idx.map(|n| unsafe { &rec.get_unchecked(n).0 });
    #[cfg(target_arch = "x86_64")]
    {
        // SAFETY: lanes code runs only where the processor has AVX (see F64x4)
        unsafe { transpose_avx(r) }
    }
    #[cfg(not(target_arch = "x86_64"))]
    std::array::from_fn(|f| F64x4([r[0][f], r[1][f], r[2][f], r[3][f]]))
}

/// [`transpose`] as three 4 x 4 transposes of aligned 256-bit loads (the same values).
///
/// # Safety
/// The processor must support AVX.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
unsafe fn transpose_avx(r: [&[f64; 12]; LANES]) -> [F64x4; 12] {
    use std::arch::x86_64::*;
    let mut out = [F64x4::default(); 12];
    for g in 0..3 {
        // SAFETY: a Record is 32-byte aligned and 96 bytes long: three aligned quads (loads
        // written out, not `map`: an out-of-line closure would lose the vector code)
        let load = |rec: &[f64; 12]| unsafe { _mm256_load_pd(rec.as_ptr().add(4 * g)) };
        let q = [load(r[0]), load(r[1]), load(r[2]), load(r[3])];
        let t0 = _mm256_unpacklo_pd(q[0], q[1]);
        let t1 = _mm256_unpackhi_pd(q[0], q[1]);
        let t2 = _mm256_unpacklo_pd(q[2], q[3]);
        let t3 = _mm256_unpackhi_pd(q[2], q[3]);
        let cols = [
            _mm256_permute2f128_pd::<0x20>(t0, t2),
            _mm256_permute2f128_pd::<0x20>(t1, t3),
            _mm256_permute2f128_pd::<0x31>(t0, t2),
            _mm256_permute2f128_pd::<0x31>(t1, t3),
        ];
        for (k, c) in cols.into_iter().enumerate() {
            // SAFETY: F64x4 is 32-byte aligned
            unsafe { _mm256_store_pd(out[4 * g + k].0.as_mut_ptr(), c) };
        }
    }
    out
}

/// The two records' fields of a batch's pairs as the contact model's input (`xj` already
/// shifted to the image nearest i).
#[inline(always)]
fn pair_lanes_of<S: Real>(
    a: &[S; 12],
    b: &[S; 12],
    xj: [S; 3],
    dt: f64,
    update_history: bool,
) -> PairLanes<S> {
    PairLanes {
        xi: [a[0], a[1], a[2]],
        xj,
        radi: a[3],
        radj: b[3],
        vi: [a[4], a[5], a[6]],
        vj: [b[4], b[5], b[6]],
        mi: a[7],
        mj: b[7],
        omegai: [a[8], a[9], a[10]],
        omegaj: [b[8], b[9], b[10]],
        frozen_i: a[11].ne(S::default()),
        frozen_j: b[11].ne(S::default()),
        dt,
        update_history,
    }
}

/// The two halves of a wide batch's pairs.
#[inline(always)]
fn split_pairs<'p>(pr: &[&'p Pair; WIDE_LANES]) -> ([&'p Pair; LANES], [&'p Pair; LANES]) {
    ([pr[0], pr[1], pr[2], pr[3]], [pr[4], pr[5], pr[6], pr[7]])
}

/// The two halves of a wide batch's particle indices.
#[inline(always)]
fn split_indices(i: &[usize; WIDE_LANES]) -> ([usize; LANES], [usize; LANES]) {
    ([i[0], i[1], i[2], i[3]], [i[4], i[5], i[6], i[7]])
}

/// The two halves of a wide batch's results, as two batches of four.
#[inline(always)]
fn split_output(out: &PairLanesOutput<F64x8>) -> (PairLanesOutput, PairLanesOutput) {
    let mut lo = PairLanesOutput::default();
    let mut hi = PairLanesOutput::default();
    for d in 0..3 {
        (lo.fi[d], hi.fi[d]) = out.fi[d].halves();
        (lo.fj[d], hi.fj[d]) = out.fj[d].halves();
        (lo.ti[d], hi.ti[d]) = out.ti[d].halves();
        (lo.tj[d], hi.tj[d]) = out.tj[d].halves();
    }
    (lo.deltan, hi.deltan) = out.deltan.halves();
    (lo, hi)
}

impl<'a, N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>
    Kernel<'a, N, T, C, R>
{
    /// The kernel of `model` with `material`'s coefficients for a step of `dt` (s);
    /// `update` advances and stores history.
    pub fn new(
        model: &'a ContactModel<N, T, C, R>,
        material: &'a Material,
        dt: f64,
        update: bool,
    ) -> Self {
        Kernel {
            model,
            material,
            ntypes: material.ntypes(),
            dt,
            update,
        }
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> Kernel<'_, N, T, C, R> {
    /// Compute the pairs `entries` (indices into `pairs`, all touching), four at a time,
    /// and hand each result to `sink` in the order of `entries`. `history` is the list's
    /// history from entry 0 of `pairs` (`width` doubles per entry), updated in place.
    pub fn run<S: Sink>(
        &self,
        packed: &Packed,
        kinds: &[u32],
        pairs: &[Pair],
        entries: &[u32],
        history: &mut [f64],
        sink: &mut S,
    ) {
        if self.ntypes == 1 || self.material.same_for_all() {
            let one = OneType(self.material.pair(1, 1));
            self.dispatch(&one, packed, kinds, pairs, entries, history, sink);
        } else {
            self.dispatch(&ByType, packed, kinds, pairs, entries, history, sink);
        }
    }

    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn dispatch<Q: CoeffSource, S: Sink>(
        &self,
        coeffs: &Q,
        packed: &Packed,
        kinds: &[u32],
        pairs: &[Pair],
        entries: &[u32],
        history: &mut [f64],
        sink: &mut S,
    ) {
        if !crate::engine::contact::real::lanes_supported() {
            self.run_scalar(packed, kinds, pairs, entries, history, sink);
            return;
        }
        #[cfg(target_arch = "x86_64")]
        {
            if crate::engine::contact::real::wide_lanes_supported() {
                // SAFETY: the processor supports AVX2 and AVX-512F (checked at run time).
                unsafe { self.run_avx512(coeffs, packed, kinds, pairs, entries, history, sink) };
                return;
            }
            // SAFETY: the processor supports AVX2 (checked at run time).
            unsafe { self.run_avx2(coeffs, packed, kinds, pairs, entries, history, sink) };
        }
        #[cfg(not(target_arch = "x86_64"))]
        self.run_lanes(coeffs, packed, kinds, pairs, entries, history, sink);
    }

    /// The pairs one at a time with `f64` arithmetic (processors without AVX): each result
    /// is the one a lane would compute.
    fn run_scalar<S: Sink>(
        &self,
        packed: &Packed,
        kinds: &[u32],
        pairs: &[Pair],
        entries: &[u32],
        history: &mut [f64],
        sink: &mut S,
    ) {
        let width = self.model.history_len();
        let rec = &packed.records;
        for &entry in entries {
            let e = entry as usize;
            let pair = &pairs[e];
            let (i, j) = (pair.i as usize, pair.j as usize);
            let (a, b) = (&rec[i].0, &rec[j].0);
            let input = crate::engine::contact::PairInput {
                xi: [a[0], a[1], a[2]],
                xj: [
                    b[0] + pair.shift[0],
                    b[1] + pair.shift[1],
                    b[2] + pair.shift[2],
                ],
                radi: a[3],
                radj: b[3],
                mi: a[7],
                mj: b[7],
                frozen_i: a[11] != 0.0,
                frozen_j: b[11] != 0.0,
                vi: [a[4], a[5], a[6]],
                vj: [b[4], b[5], b[6]],
                omegai: [a[8], a[9], a[10]],
                omegaj: [b[8], b[9], b[10]],
                dt: self.dt,
                update_history: self.update,
                coeffs: self.material.pair(kinds[i] as usize, kinds[j] as usize),
            };
            let out = self
                .model
                .pair_force(&input, &mut history[e * width..(e + 1) * width]);
            let result = PairResult {
                fi: out.fi,
                fj: out.fj,
                ti: out.ti,
                tj: out.tj,
                overlap_ratio: out.deltan / a[3].min(b[3]),
            };
            sink.take(e, pair, &result);
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[allow(clippy::too_many_arguments)]
    #[target_feature(enable = "avx2")]
    unsafe fn run_avx2<Q: CoeffSource, S: Sink>(
        &self,
        coeffs: &Q,
        packed: &Packed,
        kinds: &[u32],
        pairs: &[Pair],
        entries: &[u32],
        history: &mut [f64],
        sink: &mut S,
    ) {
        self.run_lanes(coeffs, packed, kinds, pairs, entries, history, sink);
    }

    /// Eight pairs at a time while eight are left, then four at a time.
    #[cfg(target_arch = "x86_64")]
    #[allow(clippy::too_many_arguments)]
    #[target_feature(enable = "avx2,avx512f")]
    unsafe fn run_avx512<Q: CoeffSource, S: Sink>(
        &self,
        coeffs: &Q,
        packed: &Packed,
        kinds: &[u32],
        pairs: &[Pair],
        entries: &[u32],
        history: &mut [f64],
        sink: &mut S,
    ) {
        let wide = entries.len() / WIDE_LANES * WIDE_LANES;
        self.run_wide(
            coeffs,
            packed,
            kinds,
            pairs,
            &entries[..wide],
            history,
            sink,
        );
        self.run_lanes(
            coeffs,
            packed,
            kinds,
            pairs,
            &entries[wide..],
            history,
            sink,
        );
    }

    /// The pairs `entries` eight at a time (`entries.len()` a multiple of eight), each
    /// half of a wide batch handed to `sink` as a batch of four.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn run_wide<Q: CoeffSource, S: Sink>(
        &self,
        coeffs: &Q,
        packed: &Packed,
        kinds: &[u32],
        pairs: &[Pair],
        entries: &[u32],
        history: &mut [f64],
        sink: &mut S,
    ) {
        let width = self.model.history_len();
        let rec = &packed.records;
        assert!(width <= MAX_HISTORY);
        if entries.is_empty() {
            return;
        }
        assert!(!rec.is_empty());
        let last = rec.len() - 1;
        let far = rec.len() >= PREFETCH_FROM;
        let mut hist = [F64x8::default(); MAX_HISTORY];
        let top = entries.iter().copied().max().unwrap_or(0) as usize;
        assert!(top < pairs.len() && (top + 1) * width <= history.len());
        for (n, batch) in entries.chunks_exact(WIDE_LANES).enumerate() {
            let Ok(full) = <&[u32; WIDE_LANES]>::try_from(batch) else {
                continue;
            };
            let soon = (n + PREFETCH_BATCHES) * WIDE_LANES;
            if let (true, Some(later)) = (far, entries.get(soon..soon + WIDE_LANES)) {
                prefetch_entries(later, pairs, rec, history, width);
            }
            let e: [usize; WIDE_LANES] = full.map(|k| k as usize);
            // SAFETY: e[k] <= top < pairs.len()
            let pr: [&Pair; WIDE_LANES] = e.map(|k| unsafe { pairs.get_unchecked(k) });
            let i: [usize; WIDE_LANES] = pr.map(|q| (q.i as usize).min(last));
            let j: [usize; WIDE_LANES] = pr.map(|q| (q.j as usize).min(last));
            let (pr_lo, pr_hi) = split_pairs(&pr);
            let (i_lo, i_hi) = split_indices(&i);
            let (j_lo, j_hi) = split_indices(&j);
            // SAFETY: i[k], j[k] <= last < rec.len()
            let (a_lo, a_hi, b_lo, b_hi) = unsafe {
                (
                    transpose(rec, i_lo),
                    transpose(rec, i_hi),
                    transpose(rec, j_lo),
                    transpose(rec, j_hi),
                )
            };
            let mut a = [F64x8::default(); 12];
            let mut b = [F64x8::default(); 12];
            for f in 0..12 {
                a[f] = F64x8::from_halves(a_lo[f], a_hi[f]);
                b[f] = F64x8::from_halves(b_lo[f], b_hi[f]);
            }
            let mut xj = [b[0], b[1], b[2]];
            let (s_lo, s_hi) = (shifts(&pr_lo), shifts(&pr_hi));
            if s_lo.is_some() || s_hi.is_some() {
                let zero = [F64x4::default(); 3];
                let (s_lo, s_hi) = (s_lo.unwrap_or(zero), s_hi.unwrap_or(zero));
                for d in 0..3 {
                    xj[d] += F64x8::from_halves(s_lo[d], s_hi[d]);
                }
            }
            let lanes = pair_lanes_of(&a, &b, xj, self.dt, self.update);
            let c = coeffs.wide_lanes(self.material, kinds, i, j);
            for (h, slot) in hist.iter_mut().enumerate().take(width) {
                // SAFETY: e[k] <= top and h < width (checked above)
                *slot = F64x8(e.map(|k| unsafe { *history.get_unchecked(k * width + h) }));
            }
            let out = self.model.pair_force_lanes(&lanes, &c, &mut hist[..width]);
            for (k, &entry) in e.iter().enumerate() {
                for (h, slot) in hist.iter().enumerate().take(width) {
                    // SAFETY: as above
                    unsafe { *history.get_unchecked_mut(entry * width + h) = slot.0[k] };
                }
            }
            let smaller = F64x8::select(a[3].lt(b[3]), a[3], b[3]);
            let (out_lo, out_hi) = split_output(&out);
            let (sm_lo, sm_hi) = smaller.halves();
            let (dn_lo, dn_hi) = out.deltan.halves();
            sink.take_batch(
                &batch[..LANES],
                &pr_lo,
                &out_lo,
                &Overlaps {
                    deltan: dn_lo,
                    smaller: sm_lo,
                },
            );
            sink.take_batch(
                &batch[LANES..],
                &pr_hi,
                &out_hi,
                &Overlaps {
                    deltan: dn_hi,
                    smaller: sm_hi,
                },
            );
        }
    }

    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn run_lanes<Q: CoeffSource, S: Sink>(
        &self,
        coeffs: &Q,
        packed: &Packed,
        kinds: &[u32],
        pairs: &[Pair],
        entries: &[u32],
        history: &mut [f64],
        sink: &mut S,
    ) {
        let width = self.model.history_len();
        let rec = &packed.records;
        assert!(width <= MAX_HISTORY);
        if entries.is_empty() {
            return;
        }
        // particle indices are clamped to the records (a conditional move each, no branch),
        // so the unchecked loads below stay inside them
        assert!(!rec.is_empty());
        let last = rec.len() - 1;
        let far = rec.len() >= PREFETCH_FROM;
        let mut hist = [F64x4::default(); MAX_HISTORY];
        // every entry's pair and history lie inside `pairs` and `history` (one check for
        // all entries)
        let top = entries.iter().copied().max().unwrap_or(0) as usize;
        assert!(top < pairs.len() && (top + 1) * width <= history.len());
        for (n, batch) in entries.chunks(LANES).enumerate() {
            let soon = (n + 2 * PREFETCH_BATCHES) * LANES;
            if let (true, Some(later)) = (far, entries.get(soon..soon + LANES)) {
                prefetch_entries(later, pairs, rec, history, width);
            }
            // pad a short last batch with copies of its first pair (results dropped)
            let e: [usize; LANES] = match <&[u32; LANES]>::try_from(batch) {
                Ok(full) => full.map(|k| k as usize),
                Err(_) => std::array::from_fn(|k| batch[k.min(batch.len() - 1)] as usize),
            };
            // SAFETY: e[k] <= top < pairs.len()
            let pr: [&Pair; LANES] = e.map(|k| unsafe { pairs.get_unchecked(k) });
            let i: [usize; LANES] = pr.map(|q| (q.i as usize).min(last));
            let j: [usize; LANES] = pr.map(|q| (q.j as usize).min(last));
            // SAFETY: i[k], j[k] <= last < rec.len()
            let (a, b) = unsafe { (transpose(rec, i), transpose(rec, j)) };
            let mut xj = [b[0], b[1], b[2]];
            if let Some(shift) = shifts(&pr) {
                for (x, s) in xj.iter_mut().zip(shift) {
                    *x += s;
                }
            }
            let lanes = pair_lanes_of(&a, &b, xj, self.dt, self.update);
            let c = coeffs.lanes(self.material, kinds, i, j);
            for (h, slot) in hist.iter_mut().enumerate().take(width) {
                // SAFETY: e[k] <= top and h < width (checked above)
                *slot = F64x4(e.map(|k| unsafe { *history.get_unchecked(k * width + h) }));
            }
            let out = self.model.pair_force_lanes(&lanes, &c, &mut hist[..width]);
            for (k, &entry) in batch.iter().enumerate() {
                for (h, slot) in hist.iter().enumerate().take(width) {
                    // SAFETY: as above
                    unsafe { *history.get_unchecked_mut(entry as usize * width + h) = slot.0[k] };
                }
            }
            // radii are finite and positive: the lane-wise smaller one, as f64::min gives it
            let smaller = F64x4::select(a[3].lt(b[3]), a[3], b[3]);
            let overlaps = Overlaps {
                deltan: out.deltan,
                smaller,
            };
            sink.take_batch(batch, &pr, &out, &overlaps);
        }
    }
}

#[cfg(test)]
mod tests;
