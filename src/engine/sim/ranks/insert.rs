//! Insertion on ranks (`fix insert/pack`, `insert/rate/region`, `insert/stream`): at a step
//! where an insertion fix inserts (the steps depend on the step alone, so every rank knows
//! them alike), every rank gathers the whole set in the exact path's order with its contact
//! history and per-atom fix state, runs the one-process insertion on it (the same state and
//! random streams on every rank give the same new particles with the same IDs), then keeps
//! its own particles and the new ones of its brick, and the list is built again (as one
//! process builds it when the atom count changes). The insertions' overlap checks and
//! region counts see every particle. The particles a stream carries to their release are
//! moved by the rank that owns them ([`Simulation::move_stream_particles`]).

use super::*;

impl Simulation {
    /// Does an insertion fix insert at this step (the same answer on every rank)?
    pub(super) fn insertion_due(&self) -> bool {
        let step = self.step;
        self.fixes.iter().any(|f| {
            f.kind
                .insert_pack()
                .is_some_and(|ins| ins.next == Some(step))
                || f.kind
                    .stream()
                    .and_then(|sf| sf.state.as_ref())
                    .is_some_and(|s| s.next == Some(step))
        })
    }

    /// The insertion fixes' setup at a run's start, over the whole set every rank holds
    /// then (wrapped into the box, the meshes' topology built, as one process sets them up
    /// after its setup forces); rank 0 writes what they say.
    pub(super) fn rank_setup_insertions(
        &mut self,
        comm: &RankComm,
        out: Sink<'_>,
    ) -> Result<(), EngineError> {
        let inserts = |f: &Fix| f.kind.insert_pack().is_some() || f.kind.stream().is_some();
        if !self.fixes.iter().any(inserts) {
            return Ok(());
        }
        self.pbc_and_box()?;
        self.build_mesh_topology()?;
        if comm.rank() == 0 {
            self.setup_insertions(out)
        } else {
            self.setup_insertions(&mut |_: &str| {})
        }
    }

    /// The insertions due at this step on ranks (see the module's description), with the
    /// list build that follows; rank 0 writes what they say.
    pub(super) fn rank_insert(
        &mut self,
        comm: &RankComm,
        st: &mut RankState,
        out: Sink<'_>,
    ) -> Result<(), EngineError> {
        let WholeSet {
            particles: full,
            partners,
            attached,
        } = self.rank_whole_set(comm, st)?;
        // which of the whole set this rank owned (its particles stay with it)
        let mine: std::collections::HashSet<i64> = self.particles.id
            [..st.nlocal.min(self.particles.len())]
            .iter()
            .copied()
            .collect();
        // the mesh walls' contacts of the whole set, in its order
        self.restore_wall_state(&attached, &full.id)?;
        let before = full.len();
        self.particles = full;
        if comm.rank() == 0 {
            self.insert_particles(out)?;
            self.insert_streams(out)?;
        } else {
            let quiet = &mut |_: &str| {};
            self.insert_particles(quiet)?;
            self.insert_streams(quiet)?;
        }
        // the whole set's contacts and wall state, the new particles without any
        let n = self.particles.len();
        let width = st.flips.len();
        let mut hist = PartnerHistory::new(width, n);
        if let Some(partners) = &partners {
            for (i, id) in self.particles.id.iter().enumerate() {
                for (partner, values) in partners.get(id).into_iter().flatten() {
                    hist.insert(i, *partner, values);
                }
            }
        }
        let ids = self.particles.id.clone();
        self.attach_wall_state(&mut hist, &ids);
        // the exact order recorded again: the whole set's, then the new particles in the
        // order they were inserted (as one process records them)
        let k = self.particles.extra_index(ORDER_ARRAY, 1);
        for (i, r) in self.particles.extra[k].data.iter_mut().enumerate() {
            *r = (i + 1) as f64;
        }
        self.accel.next_rank = (n + 1) as f64;
        // each rank keeps what it owned; the new particles start on rank 0, and the build
        // sends every particle straight to its brick's rank
        let first = comm.rank() == 0;
        let remove: Vec<bool> = (0..n)
            .map(|i| {
                if i < before {
                    !mine.contains(&ids[i])
                } else {
                    !first
                }
            })
            .collect();
        self.particles.retain_by(&remove);
        for what in [
            &mut hist.partners as &mut dyn RetainBy,
            &mut hist.values,
            &mut hist.attached,
        ] {
            what.retain_by(&remove);
        }
        self.natoms_expected = n;
        self.rank_build(comm, st, hist, true, true)
    }
}
