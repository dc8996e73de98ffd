//! Runs on more than one MPI rank (the first slice of the domain decomposition, fast path
//! only). Each rank owns the particles of its brick of the box (LIGGGHTS's `processors`
//! grid) and keeps ghost copies of the particles within the ghost cutoff of it. Pairs
//! follow LIGGGHTS's granular `newton off` rule: a rank computes every pair with at least
//! one particle it owns, so a pair of an owned particle and a ghost is computed on both
//! ranks, each keeping its own copy of the contact history; forces reach owned particles
//! without reverse communication. Each particle has a sum key at every list build: the cell
//! of a grid over the whole box that holds it, then its ID. Pairs are listed with the lower
//! key first and sorted by the two keys, so each particle adds its contacts in the order of
//! its partners' keys, whatever the rank count (the keys come from positions, which are the
//! same on every grid); owned particles are stored by key, cell by cell, so the pass over
//! the list reads its particles in memory order and their partners nearby.
//!
//! Every step the ghosts' positions and velocities are refreshed (forward communication);
//! at each neighbour-list build particles are wrapped into the box, the shrink-wrapped faces
//! move to the extent of every rank's particles (the bricks follow the box), particles
//! migrate with their contact history and per-atom fix state, and the ghosts are made
//! again. Thermo and dumps see every rank's particles gathered on rank 0 (in rank order, as
//! LIGGGHTS gathers a dump); a local compute's rows are each rank's own contacts, gathered likewise (a pair
//! across ranks reported from one side: across a periodic face from the particle with the
//! larger ID, as LIGGGHTS does, otherwise from the particle first in the exact path's
//! order, as one process does; LIGGGHTS's spatial sort is recorded in that order as on one
//! process, so the pairs are reported from the same side whatever the rank count). At the
//! end of a run every rank gets the whole set back in the exact path's order with the
//! contact history, so the commands between runs act identically on every rank. At an
//! insertion step every rank gathers the whole set likewise, inserts as one process does
//! (the same new particles with the same IDs on every rank), keeps its own and builds.
//!
//! The parts: `run` (the step loop), `build` (setup and list builds), `pairs` (the pair
//! search by sum key), `meshes` (mesh walls), `output` (thermo, dumps, statistics),
//! `gather` (the whole set on every rank) and `insert` (insertion).

mod build;
mod gather;
mod insert;
mod meshes;
mod output;
mod pairs;
mod run;

use super::*;
use crate::engine::accel::ORDER_ARRAY;
use crate::engine::decomp::pack::{pack_particle, unpack_particle, Reader, Writer};
use crate::engine::decomp::Decomposition;
use crate::engine::decomp::SwapBuffers;
use crate::engine::decomp::{borders, forward_with, migrate, migrate_anywhere, GhostPlan, Halo};
use crate::engine::decomp::{DecompError, PartnerHistory};
use crate::engine::dump_style::SharedLocalRows;
use crate::engine::neighbor::SumOrder;
use crate::engine::particles::PerAtom;
use crate::engine::restart_state::PendingHistory;
use crate::util::comm::{Comm, RankComm, Reduce};
use pairs::{pair_touches, rank_pairs, KeyGrid};
use std::collections::HashMap;

/// This rank's part of a run on several ranks.
struct RankState {
    /// The bricks.
    dec: Decomposition,
    /// How far ghosts reach.
    halo: Halo,
    /// The ghost swaps of the last build.
    plan: GhostPlan,
    /// Forward communication's buffers.
    swap: SwapBuffers,
    /// Owned particles (the ghosts follow them in the particle arrays).
    nlocal: usize,
    /// Pairs with at least one owned particle, the lower ID first, sorted by ID.
    pairs: Vec<Pair>,
    /// Their contact history (`flips.len()` values per pair, seen from the first particle).
    history: Vec<f64>,
    /// Which history values change sign seen from the other particle.
    flips: Vec<bool>,
    /// Owned positions at the last build (length).
    built: Vec<[f64; 3]>,
    /// Steps since the last build.
    ago: u64,
    /// Builds so far (walls refresh their own lists with it).
    builds: u64,
    /// The ghosts, kept apart while the fixes act on the owned particles and copied
    /// behind them for the pair forces (their positions and velocities refreshed then).
    ghosts: Particles,
    /// The ghosts behind the owned particles were made by the last build (not copied
    /// from `ghosts`), so they are copied there when set apart.
    fresh: bool,
    /// The ghosts' velocities (length/time) and angular velocities (1/time) at the last
    /// force evaluation, kept while a `compute pair/gran/local` reads them.
    ghost_motion: (Vec<[f64; 3]>, Vec<[f64; 3]>),
}

impl RankState {
    /// Atom IDs of the owned particles `owned` (the first `nlocal`) and of the ghosts.
    fn ids(&self, owned: &Particles) -> Vec<i64> {
        let mut ids = owned.id[..self.nlocal.min(owned.len())].to_vec();
        ids.extend_from_slice(&self.ghosts.id);
        ids
    }
}

impl From<DecompError> for EngineError {
    fn from(e: DecompError) -> Self {
        EngineError::Invalid(e.to_string())
    }
}

/// One particle's pair contacts: (partner ID, history values) each.
type Contacts = Vec<(i64, Vec<f64>)>;

/// Every rank's owned particles gathered on every rank, in the exact path's order.
struct WholeSet {
    /// The particles (the order record dropped).
    particles: Particles,
    /// Each particle's pair contacts by partner ID (None without history in the pair model).
    partners: Option<HashMap<i64, Contacts>>,
    /// Each particle's per-atom fix state that travels with it, in the particles' order.
    attached: Vec<Vec<f64>>,
}

/// Velocities (length/time) and angular velocities (1/time) of particles.
type Motion = (Vec<[f64; 3]>, Vec<[f64; 3]>);

/// No particles, with the per-atom arrays of `like`.
fn empty_like(like: &Particles) -> Particles {
    Particles {
        extra: like
            .extra
            .iter()
            .map(|e| PerAtom {
                name: e.name.clone(),
                width: e.width,
                data: Vec::new(),
                fill: e.fill.clone(),
            })
            .collect(),
        ..Particles::default()
    }
}

/// Vectors whose rows follow the particles when some are removed.
trait RetainBy {
    /// Remove the rows for which `remove` is true, keeping the others' order.
    fn retain_by(&mut self, remove: &[bool]);
}

impl<T> RetainBy for Vec<T> {
    fn retain_by(&mut self, remove: &[bool]) {
        let mut k = 0;
        self.retain(|_| {
            let keep = !remove.get(k).copied().unwrap_or(false);
            k += 1;
            keep
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Particles on a jittered grid with mixed radii (IDs in reverse order of storage).
    pub(super) fn cloud(n: usize) -> Particles {
        let mut p = Particles::default();
        let mut s = 12345u64;
        let mut r = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..n {
            let x = [r() * 0.02, r() * 0.02, r() * 0.01];
            p.push((n - k) as i64, 1, x, 0.0008 + 0.0006 * r(), 2500.0);
        }
        p
    }

    #[test]
    fn ghosts_set_apart_and_copied_back_are_the_same_rows() {
        let mut p = cloud(50);
        let k = p.extra_index("history_w", 3);
        for (n, v) in p.extra[k].data.iter_mut().enumerate() {
            *v = n as f64;
        }
        let whole = p.clone();
        let mut ghosts = empty_like(&p);
        p.copy_tail_into(30, &mut ghosts);
        p.truncate(30);
        assert_eq!((p.len(), ghosts.len()), (30, 20));
        p.extend_from(&ghosts);
        assert_eq!(p.x, whole.x);
        assert_eq!(p.id, whole.id);
        assert_eq!(p.extra, whole.extra);
        // an array made while the ghosts were apart gets its fill values for them
        p.truncate(30);
        let k = p.extra_index("new", 2);
        p.extra[k].fill = vec![7.0, 8.0];
        p.extend_from(&ghosts);
        assert_eq!(p.extra[k].data.len(), 100);
        assert_eq!(&p.extra[k].data[98..], &[7.0, 8.0]);
    }
}
