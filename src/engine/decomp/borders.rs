//! Ghost particles (LIGGGHTS's `Comm::setup` and `Comm::borders`): copies of other ranks'
//! particles (and periodic images) within the ghost cutoff of this rank's sub-domain,
//! appended after the owned particles. Swaps go axis by axis (x, then y, then z), in each
//! the low side then the high side; ghosts received along x are passed on along y and z,
//! so edge and corner ghosts come without diagonal messages. A copy sent across a periodic
//! face is shifted by the box length; its image flags stay those of its owner. The swaps
//! are recorded in a [`GhostPlan`] that forward and reverse communication replay.

use crate::engine::decomp::decomposition::Decomposition;
use crate::engine::decomp::pack::{pack_particle, unpack_particle, DecompError, Reader, Writer};
use crate::engine::particles::Particles;
use crate::util::comm::Comm;

/// How far ghosts reach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Halo {
    /// Ghost cutoff (length): LIGGGHTS's `cutghost`, the largest neighbour cutoff plus skin
    /// (or `comm_modify cutoff`); it decides how many ranks away ghosts come from.
    pub cutghost: f64,
    /// Depth of the slab of particles sent at each face (length).
    pub slab: f64,
    /// Whether a particle's radius widens its slab (LIGGGHTS's granular rule).
    pub add_radius: bool,
}

impl Halo {
    /// Every particle within `cut` (length) of a face is sent.
    pub fn plain(cut: f64) -> Halo {
        Halo {
            cutghost: cut,
            slab: cut,
            add_radius: false,
        }
    }

    /// LIGGGHTS's granular rule for spheres: slabs of half the ghost cutoff plus half the
    /// skin (length), widened by each particle's radius, where `cutghost` is the neighbour
    /// cutoff (twice the largest radius plus the skin) or more.
    pub fn granular(cutghost: f64, skin: f64) -> Halo {
        Halo {
            cutghost,
            slab: 0.5 * cutghost + 0.5 * skin,
            add_radius: true,
        }
    }
}

/// One swap of ghosts with a neighbouring rank.
#[derive(Debug, Clone, PartialEq)]
pub struct Swap {
    /// The axis (0 = x).
    pub dim: usize,
    /// The rank this rank sends to.
    pub send_to: usize,
    /// The rank this rank receives from.
    pub recv_from: usize,
    /// Indices (owned or ghost) of the particles sent, in order.
    pub send: Vec<usize>,
    /// Box lengths added to the sent positions along `dim` (-1, 0 or 1).
    pub pbc: i32,
    /// Index of the first ghost received.
    pub first_recv: usize,
    /// Number of ghosts received.
    pub n_recv: usize,
}

/// The swaps that made this rank's ghosts, replayed by forward and reverse communication.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GhostPlan {
    /// Number of owned particles (the ghosts follow them).
    pub nlocal: usize,
    /// The swaps, in order.
    pub swaps: Vec<Swap>,
    /// Periodic images of every ghost: box lengths added to its owner's position per axis
    /// (ghost index minus `nlocal`).
    pub ghost_image: Vec<[i32; 3]>,
}

impl GhostPlan {
    /// Number of ghosts.
    pub fn nghost(&self) -> usize {
        self.ghost_image.len()
    }
}

/// The most swaps made each way along one axis.
const MAX_NEED: usize = 1 << 16;

/// How many swaps each way along each axis (LIGGGHTS's `maxneed`) and how many of them this
/// rank sends on (`sendneed`, low and high side): LIGGGHTS's count for uniform bricks, the
/// bricks walked one by one for cuts a balance moved.
fn needs(dec: &Decomposition, halo: &Halo) -> ([usize; 3], [[usize; 2]; 3]) {
    if !dec.is_uniform() {
        return needs_nonuniform(dec, halo);
    }
    let mut maxneed = [0; 3];
    let mut sendneed = [[0; 2]; 3];
    let at = dec.at();
    for d in 0..3 {
        let p = dec.procs[d];
        // a box of no length saturates (at most MAX_NEED swaps each way) rather than overflows
        let reach = (halo.cutghost * p as f64 / dec.length(d)) as usize;
        let mut need = reach.saturating_add(1).min(MAX_NEED);
        if !dec.periodic[d] {
            need = need.min(p - 1);
            let left = (at[d] + p - 1) % p;
            let right = (at[d] + 1) % p;
            sendneed[d] = [need.min(p - left - 1), need.min(right)];
        } else {
            sendneed[d] = [need; 2];
        }
        maxneed[d] = need;
    }
    (maxneed, sendneed)
}

/// How many bricks along `dim`, walking from brick `at` towards the low side (`up` false)
/// or the high side, it takes to cover the ghost cutoff (wrapping around a periodic axis;
/// a fixed one ends at the box).
fn bricks_to_cover(dec: &Decomposition, halo: &Halo, dim: usize, at: usize, up: bool) -> usize {
    let p = dec.procs[dim];
    let width = |k: usize| dec.splits[dim][k + 1] - dec.splits[dim][k];
    let reach = halo.cutghost / dec.length(dim);
    let (mut covered, mut count, mut k) = (0.0, 0, at);
    while covered < reach && count < MAX_NEED {
        k = match (up, dec.periodic[dim]) {
            (false, _) if k > 0 => k - 1,
            (false, true) => p - 1,
            (true, _) if k + 1 < p => k + 1,
            (true, true) => 0,
            _ => break,
        };
        count += 1;
        covered += width(k);
    }
    count
}

/// [`needs`] for cuts a balance moved: each brick receives from as many bricks on either
/// side as it takes to cover the ghost cutoff; every rank makes the most swaps any brick
/// needs, and sends on as many as its neighbour on that side receives.
fn needs_nonuniform(dec: &Decomposition, halo: &Halo) -> ([usize; 3], [[usize; 2]; 3]) {
    let mut maxneed = [0; 3];
    let mut sendneed = [[0; 2]; 3];
    let at = dec.at();
    for d in 0..3 {
        let p = dec.procs[d];
        if p == 1 {
            // one brick: its own periodic images, as for uniform bricks
            let reach = (halo.cutghost / dec.length(d)) as usize;
            let need = if dec.periodic[d] {
                reach.saturating_add(1).min(MAX_NEED)
            } else {
                0
            };
            maxneed[d] = need;
            sendneed[d] = [need; 2];
            continue;
        }
        let from_low = |k: usize| bricks_to_cover(dec, halo, d, k, false);
        let from_high = |k: usize| bricks_to_cover(dec, halo, d, k, true);
        maxneed[d] = (0..p)
            .map(|k| from_low(k).max(from_high(k)))
            .max()
            .unwrap_or(0);
        // the low neighbour receives from its high side what this rank sends down
        let left = (at[d] + p - 1) % p;
        let right = (at[d] + 1) % p;
        sendneed[d] = [from_high(left), from_low(right)];
        if !dec.periodic[d] {
            // no brick below the first nor above the last
            if at[d] == 0 {
                sendneed[d][0] = 0;
            }
            if at[d] == p - 1 {
                sendneed[d][1] = 0;
            }
        }
    }
    (maxneed, sendneed)
}

/// Make this rank's ghosts: `p` holds the owned particles (any ghosts after them are
/// dropped first); the ghosts are appended with zero force and torque and every other
/// array copied from their owners. Returns the swaps made.
pub fn borders(
    comm: &impl Comm,
    dec: &Decomposition,
    halo: &Halo,
    p: &mut Particles,
    nlocal: usize,
) -> Result<GhostPlan, DecompError> {
    p.truncate(nlocal);
    let (maxneed, sendneed) = needs(dec, halo);
    let at = dec.at();
    let mut plan = GhostPlan {
        nlocal,
        ..GhostPlan::default()
    };
    // periodic image of every particle, owned ones included
    let mut image = vec![[0i32; 3]; nlocal];
    const BIG: f64 = 1.0e20;
    for dim in 0..3 {
        let (sublo, subhi) = (dec.sub_lo[dim], dec.sub_hi[dim]);
        let mid = 0.5 * (sublo + subhi);
        let (mut first, mut last) = (0, 0);
        for ineed in 0..2 * maxneed[dim] {
            let low_side = ineed % 2 == 0;
            if low_side {
                first = last;
                last = p.len();
            }
            // the slab sent and the neighbour (the first swaps each way take everything
            // up to the slab's inner edge; later ones only pass on arrivals)
            let (lo, hi, send_to, recv_from, pbc) = if low_side {
                let lo = if ineed < 2 { -BIG } else { mid };
                let pbc = i32::from(at[dim] == 0);
                let [l, h] = dec.neighbors[dim];
                (lo, sublo + halo.slab, l, h, pbc)
            } else {
                let hi = if ineed < 2 { BIG } else { mid };
                let pbc = -i32::from(at[dim] == dec.procs[dim] - 1);
                let [l, h] = dec.neighbors[dim];
                (subhi - halo.slab, hi, h, l, pbc)
            };
            let mut send = Vec::new();
            if ineed / 2 < sendneed[dim][ineed % 2] {
                for i in first..last {
                    let c = p.x[i][dim];
                    let r = if halo.add_radius { p.radius[i] } else { 0.0 };
                    let inside = if low_side {
                        c >= lo && c <= hi + r
                    } else {
                        c >= lo - r && c <= hi
                    };
                    if inside {
                        send.push(i);
                    }
                }
            }
            let pbc = if dec.periodic[dim] { pbc } else { 0 };
            let mut shift = [0.0; 3];
            shift[dim] = f64::from(pbc) * dec.length(dim);
            let mut out = Writer::default();
            for &i in &send {
                pack_particle(&mut out, p, i, shift, None);
                let mut m = image[i];
                m[dim] += pbc;
                m.iter().for_each(|&v| out.i32(v));
            }
            let incoming = if send_to == dec.me && recv_from == dec.me {
                out.bytes
            } else {
                comm.send_recv_bytes(send_to, recv_from, &out.bytes)
            };
            let first_recv = p.len();
            let mut r = Reader::new(&incoming);
            while !r.done() {
                unpack_particle(&mut r, p, None)?;
                image.push([r.i32()?, r.i32()?, r.i32()?]);
            }
            let n = p.len();
            p.f[first_recv..n].fill([0.0; 3]);
            p.torque[first_recv..n].fill([0.0; 3]);
            plan.swaps.push(Swap {
                dim,
                send_to,
                recv_from,
                send,
                pbc,
                first_recv,
                n_recv: n - first_recv,
            });
        }
    }
    plan.ghost_image = image.split_off(nlocal);
    Ok(plan)
}
