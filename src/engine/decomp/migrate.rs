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

/// Move every owned particle of `p` that left this rank's sub-domain straight to the rank
/// whose sub-domain holds it, however far (after a `balance` moved the cuts, LAMMPS's
/// irregular communication), with its contact history `hist`. One exchange with every
/// other rank, in rounds (round k: to rank `me + k`, from rank `me - k`), so arrivals come
/// in rank order; a particle outside every sub-domain is lost, as in [`migrate`]. Returns
/// the number of particles this rank received.
pub fn migrate_anywhere(
    comm: &impl Comm,
    dec: &Decomposition,
    p: &mut Particles,
    mut hist: Option<&mut PartnerHistory>,
) -> Result<usize, DecompError> {
    let n = dec.size();
    let mut out: Vec<Writer> = (0..n).map(|_| Writer::default()).collect();
    let mut i = 0;
    while i < p.len() {
        if dec.owns(p.x[i]) {
            i += 1;
            continue;
        }
        if let Some(r) = dec.owner_of(p.x[i]).filter(|&r| r != dec.me) {
            pack_particle(&mut out[r], p, i, [0.0; 3], hist.as_deref());
        }
        p.fill_from_last(i);
        if let Some(h) = hist.as_deref_mut() {
            h.fill_from_last(i);
        }
    }
    let mut received = 0;
    for k in 1..n {
        let to = (dec.me + k) % n;
        let from = (dec.me + n - k) % n;
        let incoming = comm.send_recv_bytes(to, from, &out[to].bytes);
        let mut r = Reader::new(&incoming);
        while !r.done() {
            unpack_particle(&mut r, p, hist.as_deref_mut())?;
            received += 1;
        }
    }
    Ok(received)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::comm::Reduce;
    use crate::util::comm_threads::ThreadRanks;

    #[test]
    fn one_sub_domain_per_axis_or_lost_as_in_liggghts() {
        // four bricks along x over 0..4; rank 0 holds three particles that move
        let out = ThreadRanks::run(4, |c| {
            let dec = Decomposition::cartesian(
                [4, 1, 1],
                c.rank(),
                [0.0; 3],
                [4.0, 1.0, 1.0],
                [false; 3],
            );
            let mut p = Particles::default();
            if c.rank() == 0 {
                p.push(1, 1, [1.5, 0.5, 0.5], 0.1, 1.0); // next brick: arrives
                p.push(2, 1, [2.5, 0.5, 0.5], 0.1, 1.0); // two bricks away: lost
                p.push(3, 1, [-0.5, 0.5, 0.5], 0.1, 1.0); // out of the box: lost
                p.push(4, 1, [0.5, 0.5, 0.5], 0.1, 1.0); // stays
            }
            let got = migrate(c, &dec, &mut p, None).expect("migrate");
            let total = c.all_reduce_i64(p.len() as i64, Reduce::Sum);
            (p.id.clone(), got, total)
        });
        assert_eq!(out[0].0, vec![4]);
        assert_eq!((out[1].0.clone(), out[1].1), (vec![1], 1));
        assert!(out[2].0.is_empty() && out[3].0.is_empty());
        assert_eq!(out[0].2, 2);
    }

    #[test]
    fn anywhere_after_the_cuts_moved() {
        // four bricks along x over 0..4, cut at 0.1, 0.2, 0.3 of the box after a balance
        let out = ThreadRanks::run(4, |c| {
            let mut dec = Decomposition::cartesian(
                [4, 1, 1],
                c.rank(),
                [0.0; 3],
                [4.0, 1.0, 1.0],
                [false; 3],
            );
            dec.set_splits(&[
                vec![0.0, 0.1, 0.2, 0.3, 1.0],
                vec![0.0, 1.0],
                vec![0.0, 1.0],
            ]);
            let mut p = Particles::default();
            if c.rank() == 0 {
                p.push(1, 1, [3.5, 0.5, 0.5], 0.1, 1.0); // three bricks away
                p.push(2, 1, [0.2, 0.5, 0.5], 0.1, 1.0); // stays
                p.push(3, 1, [-0.5, 0.5, 0.5], 0.1, 1.0); // out of the box: lost
                p.push(4, 1, [0.6, 0.5, 0.5], 0.1, 1.0); // next brick
            }
            let got = migrate_anywhere(c, &dec, &mut p, None).expect("migrate");
            (p.id.clone(), got)
        });
        assert_eq!(out[0], (vec![2], 0));
        assert_eq!(out[1], (vec![4], 1));
        assert!(out[2].0.is_empty());
        assert_eq!(out[3], (vec![1], 1));
    }

    #[test]
    fn across_the_periodic_face_to_the_last_rank() {
        let out = ThreadRanks::run(3, |c| {
            let dec =
                Decomposition::cartesian([3, 1, 1], c.rank(), [0.0; 3], [3.0, 1.0, 1.0], [true; 3]);
            let mut p = Particles::default();
            if c.rank() == 0 {
                // wrapped from just below 0 to just below 3
                p.push(7, 1, [2.99, 0.5, 0.5], 0.1, 1.0);
                p.image[0] = [-1, 0, 0];
            }
            migrate(c, &dec, &mut p, None).expect("migrate");
            (p.id.clone(), p.image.clone())
        });
        assert_eq!(out[2], (vec![7], vec![[-1, 0, 0]]));
        assert!(out[0].0.is_empty() && out[1].0.is_empty());
    }
}
