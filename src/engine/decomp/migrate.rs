//! Migration (LIGGGHTS's `Comm::exchange`): owned particles that left this rank's
//! sub-domain move to the rank that now holds them, with every per-particle array and
//! their contact history. Axis by axis (x, then y, then z), a leaving particle is sent to
//! both neighbours along the axis (one if there are two ranks on it) and kept by the one
//! whose sub-domain holds it; so a particle may move at most one sub-domain per axis
//! between migrations, and one outside every sub-domain is lost, as in LIGGGHTS.

use crate::engine::decomp::decomposition::Decomposition;
use crate::engine::decomp::pack::{
    pack_particle, peek_position, unpack_particle, DecompError, PartnerHistory, Reader, Writer,
};
use crate::engine::particles::Particles;
use crate::util::comm::Comm;

/// Move the owned particles `p` (no ghosts: positions already wrapped into a periodic
/// box) and their contact history `hist` (one entry per particle, or None) to the ranks
/// whose sub-domains hold them. A leaving particle's slot is filled by the last particle,
/// and arrivals are appended, as LIGGGHTS does. Returns the number of particles this rank
/// received.
pub fn migrate(
    comm: &impl Comm,
    dec: &Decomposition,
    p: &mut Particles,
    mut hist: Option<&mut PartnerHistory>,
) -> Result<usize, DecompError> {
    let mut received = 0;
    for dim in 0..3 {
        let (lo, hi) = (dec.sub_lo[dim], dec.sub_hi[dim]);
        let mut out = Writer::default();
        let mut i = 0;
        while i < p.len() {
            let c = p.x[i][dim];
            if c < lo || c >= hi {
                pack_particle(&mut out, p, i, [0.0; 3], hist.as_deref());
                p.fill_from_last(i);
                if let Some(h) = hist.as_deref_mut() {
                    h.fill_from_last(i);
                }
            } else {
                i += 1;
            }
        }
        let incoming = match dec.procs[dim] {
            1 => out.bytes,
            n => {
                let [low, high] = dec.neighbors[dim];
                let mut got = comm.send_recv_bytes(low, high, &out.bytes);
                if n > 2 {
                    got.extend(comm.send_recv_bytes(high, low, &out.bytes));
                }
                got
            }
        };
        let mut r = Reader::new(&incoming);
        while !r.done() {
            let (x, end) = peek_position(&mut r)?;
            if x[dim] >= lo && x[dim] < hi {
                unpack_particle(&mut r, p, hist.as_deref_mut())?;
                received += 1;
            }
            r.seek(end);
        }
    }
    Ok(received)
}
