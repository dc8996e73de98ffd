//! Neighbour-list builds on a rank: the whole set split over the bricks at a run's setup,
//! then at each build the particles wrapped, migrated with their contact history and
//! per-atom fix state, stored by sum key, their ghosts made and the pair list built.

use super::*;

impl Simulation {
    /// The whole set wrapped into the box on every rank, the exact order recorded, and
    /// this rank's brick kept, with its ghosts and pair list made.
    pub(super) fn rank_setup(&mut self, comm: &RankComm) -> Result<RankState, EngineError> {
        self.pbc_and_box()?;
        self.natoms_expected = self.particles.len();
        let k = self.particles.extra_index(ORDER_ARRAY, 1);
        for (i, r) in self.particles.extra[k].data.iter_mut().enumerate() {
            *r = (i + 1) as f64;
        }
        // LIGGGHTS's spatial sort at the setup, recorded in the exact order as one process
        // records it (every rank holds the whole set here)
        if self.sort_every > 0 {
            self.sort_particles();
        }
        let flips = self.pair.as_ref().map_or(Vec::new(), |p| p.history_flips());
        let mut hist = self.history_rows(flips.len());
        let ids = self.particles.id.clone();
        self.attach_wall_state(&mut hist, &ids);
        // the grid with the cuts a balance left, moved again by a `fix balance` when due
        let mut dec = self.balanced_grid(comm.rank())?;
        self.balance_at_setup(&mut dec);
        let remove: Vec<bool> = self.particles.x.iter().map(|x| !dec.owns(*x)).collect();
        self.particles.retain_by(&remove);
        for what in [
            &mut hist.partners as &mut dyn RetainBy,
            &mut hist.values,
            &mut hist.attached,
        ] {
            what.retain_by(&remove);
        }
        let mut st = RankState {
            dec,
            halo: Halo::granular(self.neighbor.cutneighmax, self.neighbor.skin),
            plan: GhostPlan::default(),
            swap: SwapBuffers::default(),
            nlocal: self.particles.len(),
            pairs: Vec::new(),
            history: Vec::new(),
            flips,
            built: Vec::new(),
            ago: 0,
            builds: self.list.builds,
            ghosts: empty_like(&self.particles),
            fresh: false,
            ghost_motion: (Vec::new(), Vec::new()),
        };
        self.rank_build(comm, &mut st, hist, false, false)?;
        Ok(st)
    }

    /// The contact history of the whole set as per-particle partner lists: what
    /// `read_restart` or the last run left (`width` values per contact).
    pub(super) fn history_rows(&mut self, width: usize) -> PartnerHistory {
        let n = self.particles.len();
        let mut hist = PartnerHistory::new(width, n);
        let pending = self.pending_history.take();
        if let Some(pending) = pending.filter(|h| h.width == width && width > 0) {
            for (i, id) in self.particles.id.iter().enumerate() {
                for (partner, values) in pending.partners.get(id).into_iter().flatten() {
                    hist.insert(i, *partner, values);
                }
            }
        }
        // a fresh list; its build count goes on (walls refresh their lists by it)
        let builds = self.list.builds;
        self.list = crate::engine::neighbor::NeighborList::default();
        self.list.builds = builds;
        self.history.clear();
        self.mirror_history.clear();
        hist
    }

    /// A neighbour-list build on this rank: owned particles (ghosts already dropped)
    /// wrapped into the box, those lost through fixed faces dropped, migration with the
    /// contact history `hist` (one row per owned particle), new ghosts and pair list, and
    /// the history taken back from the partner lists. `balance`: a `fix balance` may move
    /// the cuts first (not at the setup build, which the setup balanced). `anywhere`: some
    /// particles may be far from their brick (new ones after an insertion), so every
    /// particle goes straight to its rank.
    pub(super) fn rank_build(
        &mut self,
        comm: &RankComm,
        st: &mut RankState,
        mut hist: PartnerHistory,
        balance: bool,
        anywhere: bool,
    ) -> Result<(), EngineError> {
        let p = &mut self.particles;
        // as LIGGGHTS's pbc, reset_box and exchange: periodic coordinates wrapped, the
        // shrink-wrapped faces moved to the extent of every rank's particles (the bricks
        // follow the new box), then the particles outside a fixed face lost
        let mut placed: Vec<bool> = (0..p.len())
            .map(|i| self.domain.remap(&mut p.x[i], &mut p.image[i]))
            .collect();
        if self.domain.shrinks() {
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            // a particle without a finite position is lost below; it does not stretch the box
            for x in p.x.iter().filter(|x| x.iter().all(|c| c.is_finite())) {
                for d in 0..3 {
                    lo[d] = lo[d].min(x[d]);
                    hi[d] = hi[d].max(x[d]);
                }
            }
            comm.all_reduce_f64(&mut lo, Reduce::Min);
            comm.all_reduce_f64(&mut hi, Reduce::Max);
            // no particle on any rank: the box stays (as one process leaves it)
            if lo[0] <= hi[0] {
                self.domain.shrink_wrap(lo, hi)?;
                st.dec.set_box(self.domain.lo, self.domain.hi);
            }
        }
        let mut i = 0;
        while i < p.len() {
            if !placed[i] || !self.domain.contains(p.x[i]) {
                p.fill_from_last(i);
                hist.fill_from_last(i);
                placed.swap_remove(i);
            } else {
                i += 1;
            }
        }
        // the cuts moved: particles go straight to their new ranks, however far
        let cuts_moved = balance && self.balance_during_run(comm, &mut st.dec);
        if cuts_moved || anywhere {
            let p = &mut self.particles;
            migrate_anywhere(comm, &st.dec, p, Some(&mut hist))?;
        } else {
            let p = &mut self.particles;
            migrate(comm, &st.dec, p, Some(&mut hist))?;
        }
        if self.sort_every > 0 && self.step >= self.next_sort {
            self.rank_sort_order(comm)?;
        }
        let p = &mut self.particles;
        // owned particles stored by sum key, as the pair list runs: the pass over the list
        // reads the first particles of its pairs in memory order, their partners nearby
        let grid = KeyGrid::new(self.domain.lo, self.domain.hi, self.neighbor.cutneighmax);
        let mut keyed: Vec<(u64, i64, [u64; 3], usize)> = (0..p.len())
            .map(|k| (grid.cell(p.x[k]), p.id[k], p.x[k].map(f64::to_bits), k))
            .collect();
        keyed.sort_unstable();
        let order: Vec<usize> = keyed.into_iter().map(|(.., k)| k).collect();
        p.permute(&order);
        let (mut partners, mut values) = (
            std::mem::take(&mut hist.partners),
            std::mem::take(&mut hist.values),
        );
        hist.partners = order
            .iter()
            .map(|&k| std::mem::take(&mut partners[k]))
            .collect();
        hist.values = order
            .iter()
            .map(|&k| std::mem::take(&mut values[k]))
            .collect();
        let attached: Vec<Vec<f64>> = order
            .iter()
            .map(|&k| {
                hist.attached
                    .get_mut(k)
                    .map(std::mem::take)
                    .unwrap_or_default()
            })
            .collect();
        let ids = p.id.clone();
        self.restore_wall_state(&attached, &ids)?;
        let p = &mut self.particles;
        st.nlocal = p.len();
        let natoms = comm.all_reduce_i64(st.nlocal as i64, Reduce::Sum) as usize;
        if natoms != self.natoms_expected && !self.lost_ignore {
            return Err(EngineError::Invalid(format!(
                "Lost atoms: original {} current {natoms}",
                self.natoms_expected
            )));
        }
        self.natoms_expected = natoms;
        st.plan = borders(comm, &st.dec, &st.halo, p, st.nlocal)?;
        let cells: Vec<u64> = p.x.iter().map(|&x| grid.cell(x)).collect();
        st.pairs = rank_pairs(p, st.nlocal, self.neighbor.skin, &cells);
        // `neigh_modify exclude`: types and groups travel with owned particles and ghosts
        let n = &self.neighbor;
        if n.excludes_any() {
            st.pairs
                .retain(|pair| !n.excludes(p, pair.i as usize, pair.j as usize));
        }
        st.history = hist.to_pairs(&st.pairs, &p.id, st.nlocal, &st.flips);
        let width = st.flips.len();
        if width > 0 {
            for (k, pair) in st.pairs.iter().enumerate() {
                if !pair_touches(p, pair) {
                    st.history[k * width..(k + 1) * width].fill(0.0);
                }
            }
        }
        st.built = p.x[..st.nlocal].to_vec();
        st.ago = 0;
        st.builds += 1;
        st.fresh = true;
        Ok(())
    }

    /// LIGGGHTS's spatial sort when due at a rebuild, applied to the record of the exact
    /// order as one process applies it: the whole set ordered by sort bin, then by its
    /// place in the exact order, each particle's place gathered from every rank.
    pub(super) fn rank_sort_order(&mut self, comm: &RankComm) -> Result<(), EngineError> {
        self.next_sort = (self.step / self.sort_every) * self.sort_every + self.sort_every;
        let binsize = self.sort_bin_size();
        let (lo, hi) = (self.domain.lo, self.domain.hi);
        let p = &mut self.particles;
        // the bins depend on the box alone: every rank sorts or none
        let Some(bins) = super::neighbors::sort_bins(&p.x, lo, hi, binsize, self.dimension == 2)
        else {
            return Ok(());
        };
        let k = p.extra_index(ORDER_ARRAY, 1);
        let mut w = Writer::default();
        for (&b, &r) in bins.iter().zip(&p.extra[k].data) {
            w.u32(b);
            w.f64(r);
        }
        let mut all = comm
            .gather_bytes(&w.bytes)
            .map(|v| v.concat())
            .unwrap_or_default();
        comm.broadcast_bytes(0, &mut all);
        let mut keyed = Vec::with_capacity(all.len() / 12);
        let mut r = Reader::new(&all);
        while !r.done() {
            let bin = r.u32()?;
            keyed.push((bin, r.f64()?));
        }
        keyed.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        // each old place's new one, looked up by the old place
        let mut moved: Vec<(f64, f64)> = keyed
            .iter()
            .enumerate()
            .map(|(new, &(_, old))| (old, (new + 1) as f64))
            .collect();
        moved.sort_by(|a, b| a.0.total_cmp(&b.0));
        for r in p.extra[k].data.iter_mut() {
            if let Ok(at) = moved.binary_search_by(|m| m.0.total_cmp(r)) {
                *r = moved[at].1;
            }
        }
        self.accel.next_rank = (keyed.len() + 1) as f64;
        Ok(())
    }
}
