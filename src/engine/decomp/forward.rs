//! Forward and reverse communication over a [`GhostPlan`] (LIGGGHTS's `Comm::forward_comm`
//! with ghost velocities, and `Comm::reverse_comm`). Forward: the swaps in order, owners'
//! positions (shifted across periodic faces as when the ghosts were made), velocities,
//! angular velocities and, when asked, radii copied to their ghosts. Reverse: the swaps
//! backwards, ghosts' forces and torques added to the particles they were copied from (a
//! ghost of a ghost reaches its owner through the intermediate ghost).

use crate::engine::decomp::borders::GhostPlan;
use crate::engine::decomp::decomposition::Decomposition;
use crate::engine::decomp::pack::{DecompError, Reader, Writer};
use crate::engine::particles::Particles;
use crate::util::comm::Comm;

/// Send `out` along a swap (`to`, `from`); the bytes themselves when the swap is with this
/// rank alone.
fn swap_bytes(comm: &impl Comm, me: usize, to: usize, from: usize, out: Vec<u8>) -> Vec<u8> {
    if to == me && from == me {
        out
    } else {
        comm.send_recv_bytes(to, from, &out)
    }
}

/// Buffers of forward communication, kept between steps so a step allocates nothing.
#[derive(Debug, Clone, Default)]
pub struct SwapBuffers {
    /// Values sent along the current swap.
    send: Vec<f64>,
    /// Values received along it.
    recv: Vec<f64>,
}

/// Copy owners' positions (length), velocities (length/time), angular velocities (1/time)
/// and, with `radius`, radii (length) to their ghosts.
pub fn forward(
    comm: &impl Comm,
    dec: &Decomposition,
    plan: &GhostPlan,
    p: &mut Particles,
    radius: bool,
) -> Result<(), DecompError> {
    forward_with(comm, dec, plan, p, radius, &mut SwapBuffers::default())
}

/// [`forward`] with buffers kept by the caller. A swap with this rank alone (a periodic
/// axis with one rank along it) copies particle to ghost directly; a swap with another rank
/// sends one message of doubles, whose count both sides know from the ghost plan.
pub fn forward_with(
    comm: &impl Comm,
    dec: &Decomposition,
    plan: &GhostPlan,
    p: &mut Particles,
    radius: bool,
    buf: &mut SwapBuffers,
) -> Result<(), DecompError> {
    let stride = if radius { 10 } else { 9 };
    for s in &plan.swaps {
        let shift = f64::from(s.pbc) * dec.length(s.dim);
        if s.first_recv + s.n_recv > p.len() {
            return Err(DecompError::PlanMismatch {
                ghosts: s.first_recv + s.n_recv,
                particles: p.len(),
            });
        }
        if s.send_to == dec.me && s.recv_from == dec.me {
            if s.send.len() != s.n_recv {
                return Err(DecompError::PlanMismatch {
                    ghosts: s.send.len(),
                    particles: s.n_recv,
                });
            }
            for (k, &i) in s.send.iter().enumerate() {
                let g = s.first_recv + k;
                let mut x = p.x[i];
                x[s.dim] += shift;
                p.x[g] = x;
                p.v[g] = p.v[i];
                p.omega[g] = p.omega[i];
                if radius {
                    p.radius[g] = p.radius[i];
                }
            }
            continue;
        }
        buf.send.clear();
        for &i in &s.send {
            let mut x = p.x[i];
            x[s.dim] += shift;
            buf.send.extend_from_slice(&x);
            buf.send.extend_from_slice(&p.v[i]);
            buf.send.extend_from_slice(&p.omega[i]);
            if radius {
                buf.send.push(p.radius[i]);
            }
        }
        buf.recv.resize(s.n_recv * stride, 0.0);
        comm.send_recv_f64(s.send_to, s.recv_from, &buf.send, &mut buf.recv);
        let ghosts = s.first_recv..s.first_recv + s.n_recv;
        for (g, v) in ghosts.zip(buf.recv.chunks_exact(stride)) {
            p.x[g] = [v[0], v[1], v[2]];
            p.v[g] = [v[3], v[4], v[5]];
            p.omega[g] = [v[6], v[7], v[8]];
            if radius {
                p.radius[g] = v[9];
            }
        }
    }
    Ok(())
}

/// Add ghosts' forces (force) and torques (force x length) to the particles they copy,
/// the swaps replayed backwards; ghosts keep their values. Sums in LIGGGHTS's order, which
/// depends on the rank count: see [`reverse_contributions`] for a sum that does not.
pub fn reverse(
    comm: &impl Comm,
    dec: &Decomposition,
    plan: &GhostPlan,
    p: &mut Particles,
) -> Result<(), DecompError> {
    for s in plan.swaps.iter().rev() {
        let mut out = Writer::default();
        for g in s.first_recv..s.first_recv + s.n_recv {
            out.vec3(p.f[g]);
            out.vec3(p.torque[g]);
        }
        let incoming = swap_bytes(comm, dec.me, s.recv_from, s.send_to, out.bytes);
        let mut r = Reader::new(&incoming);
        for &i in &s.send {
            let (f, t) = (r.vec3()?, r.vec3()?);
            for d in 0..3 {
                p.f[i][d] += f[d];
                p.torque[i][d] += t[d];
            }
        }
    }
    Ok(())
}

/// One pair's force and torque on one particle, named by the pair's other particle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contribution {
    /// ID of the other particle of the pair.
    pub partner: i64,
    /// Force (force).
    pub f: [f64; 3],
    /// Torque (force x length).
    pub torque: [f64; 3],
}

/// Move each ghost's list of contributions to its owner, the swaps replayed backwards:
/// `lists` has one list per particle (owned, then ghosts); ghosts' lists end up empty and
/// owners' lists hold every contribution computed for them on any rank.
pub fn reverse_contributions(
    comm: &impl Comm,
    dec: &Decomposition,
    plan: &GhostPlan,
    lists: &mut [Vec<Contribution>],
) -> Result<(), DecompError> {
    for s in plan.swaps.iter().rev() {
        let mut out = Writer::default();
        for list in &mut lists[s.first_recv..s.first_recv + s.n_recv] {
            out.u32(list.len() as u32);
            for c in list.drain(..) {
                out.i64(c.partner);
                out.vec3(c.f);
                out.vec3(c.torque);
            }
        }
        let incoming = swap_bytes(comm, dec.me, s.recv_from, s.send_to, out.bytes);
        let mut r = Reader::new(&incoming);
        for &i in &s.send {
            for _ in 0..r.u32()? {
                let partner = r.i64()?;
                let (f, torque) = (r.vec3()?, r.vec3()?);
                lists[i].push(Contribution { partner, f, torque });
            }
        }
    }
    Ok(())
}

/// The force (force) and torque (force x length) of a particle's contributions added in a
/// canonical order, by partner ID (ties by value bits), from zero: the same bits for any
/// rank count and any order the contributions arrived in.
pub fn canonical_sum(list: &mut [Contribution]) -> ([f64; 3], [f64; 3]) {
    list.sort_by(|a, b| {
        let bits = |c: &Contribution| c.f.map(f64::to_bits);
        a.partner.cmp(&b.partner).then(bits(a).cmp(&bits(b)))
    });
    let mut f = [0.0; 3];
    let mut t = [0.0; 3];
    for c in list.iter() {
        for d in 0..3 {
            f[d] += c.f[d];
            t[d] += c.torque[d];
        }
    }
    (f, t)
}
