//! The whole set on every rank: at the end of a run (with the contact history kept by atom
//! ID for the next run) and for the `restart` files due during a run.

use super::*;

impl Simulation {
    /// The end of a run: every rank's particles and contact history on every rank, in
    /// the exact path's order (the order record dropped), the history kept by atom ID for
    /// the next run.
    pub(super) fn rank_gather_all(
        &mut self,
        comm: &RankComm,
        st: &RankState,
    ) -> Result<(), EngineError> {
        let WholeSet {
            particles: full,
            partners,
            attached,
        } = self.rank_whole_set(comm, st)?;
        // the mesh walls' contacts of the whole set, in its order
        self.restore_wall_state(&attached, &full.id)?;
        if let Some(partners) = partners {
            self.pending_history = Some(PendingHistory {
                width: st.flips.len(),
                partners,
                live: true,
            });
        }
        self.particles = full;
        self.list = crate::engine::neighbor::NeighborList::default();
        self.list.builds = st.builds;
        self.history.clear();
        self.mirror_history.clear();
        self.list_ids.clear();
        Ok(())
    }

    /// This rank's owned particles' contacts by partner ID, with their mesh walls' state:
    /// what travels with them to a new list or another rank.
    pub(super) fn owned_contacts(&self, st: &RankState) -> PartnerHistory {
        let mut hist = PartnerHistory::from_pairs(
            &st.pairs,
            &st.history,
            &st.ids(&self.particles),
            st.nlocal,
            &st.flips,
        );
        self.attach_wall_state(&mut hist, &self.particles.id[..st.nlocal]);
        hist
    }

    /// Every rank's owned particles on every rank, in the exact path's order (the order
    /// record dropped), with each particle's contacts by partner ID (None without history
    /// in the pair model); the run's own state is left as it is.
    pub(super) fn rank_whole_set(
        &self,
        comm: &RankComm,
        st: &RankState,
    ) -> Result<WholeSet, EngineError> {
        let hist = self.owned_contacts(st);
        let mine = self.pack_owned(st, Some(&hist));
        let mut all = comm
            .gather_bytes(&mine)
            .map(|v| v.concat())
            .unwrap_or_default();
        comm.broadcast_bytes(0, &mut all);
        let mut full = empty_like(&self.particles);
        let mut rows = PartnerHistory::new(hist.width, 0);
        let mut r = Reader::new(&all);
        while !r.done() {
            unpack_particle(&mut r, &mut full, Some(&mut rows))?;
        }
        let width = hist.width;
        let partners = (width > 0).then(|| {
            let mut partners = HashMap::new();
            for (i, id) in full.id.iter().enumerate() {
                let contacts: Vec<(i64, Vec<f64>)> = rows.partners[i]
                    .iter()
                    .zip(rows.values[i].chunks(width))
                    .map(|(&p, v)| (p, v.to_vec()))
                    .collect();
                if !contacts.is_empty() {
                    partners.insert(*id, contacts);
                }
            }
            partners
        });
        let mut attached = rows.attached;
        if let Some(k) = full.extra.iter().position(|e| e.name == ORDER_ARRAY) {
            let ranks = full.extra[k].data.clone();
            let mut order: Vec<usize> = (0..ranks.len()).collect();
            order.sort_by(|&a, &b| ranks[a].total_cmp(&ranks[b]));
            full.permute(&order);
            full.extra.remove(k);
            attached = order
                .iter()
                .map(|&k| attached.get_mut(k).map(std::mem::take).unwrap_or_default())
                .collect();
        }
        Ok(WholeSet {
            particles: full,
            partners,
            attached,
        })
    }

    /// The `restart` command's files due at this step, written from every rank's particles
    /// gathered in the exact path's order: one file by rank 0 (what one process holding the
    /// particles in that order writes), or for a `%` name LIGGGHTS's base file and one file
    /// per rank (as `write_restart` between runs). Positions are not re-wrapped (the run
    /// goes on), as on one process.
    pub(super) fn rank_periodic_restart(
        &mut self,
        comm: &RankComm,
        st: &RankState,
    ) -> Result<(), EngineError> {
        let paths = self.restart_paths_due();
        if paths.is_empty() {
            return Ok(());
        }
        let WholeSet {
            particles: mut full,
            partners,
            attached,
        } = self.rank_whole_set(comm, st)?;
        let mut partners = partners.unwrap_or_default();
        // each particle's contacts by partner ID, as the fast path lists them on one process
        for contacts in partners.values_mut() {
            contacts.sort_by_key(|c| c.0);
        }
        // the mesh walls' contacts of the whole set while the files are written
        let trackers = self.save_wall_trackers();
        self.restore_wall_state(&attached, &full.id)?;
        std::mem::swap(&mut self.particles, &mut full);
        let written = (|| {
            self.check_restart_size()?;
            let r = self.to_restart(&partners);
            for path in &paths {
                self.save_restart_on_ranks(comm, &r, path)?;
            }
            Ok(())
        })();
        std::mem::swap(&mut self.particles, &mut full);
        self.put_wall_trackers(trackers);
        written
    }
}
