//! The step loop of a run on several ranks: the setup, each step's phases in LIGGGHTS's
//! order (the list decision over every rank, forward communication or a build, the pair
//! forces of this rank's pairs and the fixes on its particles), the fixes' end of step.

use super::*;

impl Simulation {
    /// `run N` on more than one rank (see the module's description).
    pub(in crate::engine::sim) fn run_ranks(
        &mut self,
        nsteps: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let comm = self.comm.take().ok_or("no ranks to run on")?;
        let result = self.run_ranks_with(&comm, nsteps, out, vars);
        self.comm = Some(comm);
        result
    }

    pub(super) fn run_ranks_with(
        &mut self,
        comm: &RankComm,
        nsteps: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        if !self.domain.exists {
            return Err("Run command before simulation box is defined".into());
        }
        self.init_pair()?;
        self.check_meshes_in_box()?;
        if self.contact_factor() != 1.0 {
            return Err(EngineError::Invalid(
                "a wet pair model on more than one MPI rank: not supported yet".into(),
            ));
        }
        let (first, last, started) = self.begin_run(nsteps)?;
        self.setup_fix_styles();
        // every rank holds the whole set here: the computes' run-start state is global
        self.setup_compute_styles();
        self.rank_setup_insertions(comm, out)?;
        let mut st = self.rank_setup(comm)?;
        self.rank_mesh_setup()?;
        self.rank_forces(&mut st, false, true);
        self.zero_mesh_velocities(false);
        if comm.rank() == 0 {
            // LIGGGHTS's proc 0 says the history fix took its state from a restart file
            self.say_history_restored(out);
        }
        self.has_run = true;
        self.restart_in_progress = false;
        self.restart_fixes.clear();
        self.restart_peratom.clear();
        self.restart_move_origins.clear();
        self.restart_mesh_history.clear();
        self.thermo.run_start = first;
        self.thermo.run_last = last;
        self.thermo.prepare_run(self.box_changes());
        if comm.rank() == 0 {
            self.thermo.header(out);
        }
        self.loop_clock = Some(std::time::Instant::now());
        self.stats = RunStats::default();
        self.rank_output(comm, &mut st, true, last, out, vars)?;
        for _ in 0..nsteps {
            self.step += 1;
            fixes::initial_integrate(
                &mut self.fixes,
                &mut self.particles,
                self.step,
                self.dt,
                &self.domain,
            );
            fixes::move_meshes(&mut self.fixes, self.dt);
            let clock = std::time::Instant::now();
            // an insertion (at steps every rank knows alike) makes the list again, as a
            // changed atom count does on one process
            let rebuilt = if self.insertion_due() {
                self.rank_insert(comm, &mut st, out)?;
                true
            } else {
                let rebuilt = self.rank_decide(comm, &mut st);
                if rebuilt {
                    let hist = self.owned_contacts(&st);
                    self.rank_build(comm, &mut st, hist, true, false)?;
                }
                rebuilt
            };
            if rebuilt {
                self.stats.builds += 1;
                self.stats.neigh += clock.elapsed().as_secs_f64();
            } else {
                self.particles.extend_from(&st.ghosts);
                let p = &mut self.particles;
                forward_with(comm, &st.dec, &st.plan, p, false, &mut st.swap)?;
                self.stats.comm += clock.elapsed().as_secs_f64();
            }
            self.refresh_moving_meshes(rebuilt);
            let clock = std::time::Instant::now();
            let tally = self.virial_wanted(last);
            self.rank_forces(&mut st, true, tally);
            self.stats.pair += clock.elapsed().as_secs_f64();
            fixes::final_integrate(
                &mut self.fixes,
                &mut self.particles,
                self.step,
                self.dt,
                &self.domain,
            );
            // particles reach another rank only at builds (and the run's setup build)
            let arrived = rebuilt || self.step == first + 1;
            self.rank_end_of_step(comm, out, vars, arrived)?;
            let clock = std::time::Instant::now();
            self.rank_output(comm, &mut st, false, last, out, vars)?;
            self.rank_periodic_restart(comm, &st)?;
            self.stats.output += clock.elapsed().as_secs_f64();
        }
        self.run_bounds = None;
        self.loop_clock = None;
        self.atime += (self.step - self.atime_step) as f64 * self.dt;
        self.atime_step = self.step;
        let loop_time = started.elapsed().as_secs_f64();
        let stats = self.rank_statistics(comm, &st, loop_time);
        self.keep_run_balance(comm, &st.dec, st.nlocal);
        self.rank_gather_all(comm, &st)?;
        out(&format!(
            "Loop time of {} on {} procs for {} steps with {} atoms\n\n",
            crate::util::format::g(loop_time),
            comm.size(),
            nsteps,
            self.particles.len()
        ));
        out(&stats);
        Ok(())
    }

    /// The `end_of_step` phase on ranks: the streams' carried particles this rank owns
    /// moved (`arrived`: particles may have come from other ranks since the last step),
    /// then each module fix style over this rank's particles, extremes reduced over the
    /// ranks; rank 0 writes what the styles print.
    pub(super) fn rank_end_of_step(
        &mut self,
        comm: &RankComm,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
        arrived: bool,
    ) -> Result<(), EngineError> {
        let (step, dt, skin) = (self.step, self.dt, self.neighbor.skin);
        let contact = self.neighbor.cutneighmax - skin;
        let mesh_vmax_sqr = self.moving_mesh_vmax_sqr();
        let min = |values: &mut [f64]| comm.all_reduce_f64(values, Reduce::Min);
        // each rank carries its own particles of the streams to their release
        self.move_stream_particles(Some(arrived));
        for k in 0..self.fixes.len() {
            let fix = &mut self.fixes[k];
            if let FixKind::Style(s) = &mut fix.kind {
                let at = fixes::FixStep {
                    group: fix.group,
                    step,
                    dt,
                    domain: &self.domain,
                    virial: &[],
                    contact,
                    skin,
                    regions: Some(&self.regions),
                    mesh_vmax_sqr,
                };
                s.end_of_step_ranks(&mut self.particles, &at, &min);
                if s.outputs_at(step) {
                    // `fix print` reads the deck's variables: rank 0 evaluates them over
                    // every rank's particles gathered, as thermo does
                    if s.name() == "print" {
                        self.rank_print_output(comm, k, out, vars)?;
                    } else if comm.rank() == 0 {
                        self.fix_style_output(k, out, vars)?;
                    } else {
                        // what rank 0 prints, the others drop
                        self.fix_style_output(k, &mut |_: &str| {}, vars)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// The output of fix `k` (a `fix print`) written by rank 0 alone, with every rank's
    /// particles (this rank's owned ones at the end of a step) gathered there for its
    /// variables; the other ranks evaluate nothing (LIGGGHTS's proc 0 alone prints). A
    /// failure on rank 0 fails every rank.
    fn rank_print_output(
        &mut self,
        comm: &RankComm,
        k: usize,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let mut w = Writer::default();
        for i in 0..self.particles.len() {
            pack_particle(&mut w, &self.particles, i, [0.0; 3], None);
        }
        let result = match comm.gather_bytes(&w.bytes) {
            Some(all) => {
                let mut full = empty_like(&self.particles);
                let unpacked = all.iter().try_for_each(|bytes| {
                    let mut r = Reader::new(bytes);
                    while !r.done() {
                        unpack_particle(&mut r, &mut full, None)?;
                    }
                    Ok::<(), DecompError>(())
                });
                match unpacked {
                    Ok(()) => {
                        std::mem::swap(&mut self.particles, &mut full);
                        let printed = self.fix_style_output(k, out, vars);
                        std::mem::swap(&mut self.particles, &mut full);
                        printed
                    }
                    Err(e) => Err(e.into()),
                }
            }
            None => Ok(()),
        };
        let failed = comm.all_reduce_i64(i64::from(result.is_err()), Reduce::Max) > 0;
        match result {
            Err(e) => Err(e),
            Ok(()) if failed => Err(EngineError::Invalid(format!(
                "fix {} failed on rank 0",
                self.fixes[k].id
            ))),
            Ok(()) => Ok(()),
        }
    }

    /// LIGGGHTS's rebuild decision, the same on every rank: the delay and every settings,
    /// then whether any rank's particle moved more than half the skin.
    pub(super) fn rank_decide(&mut self, comm: &RankComm, st: &mut RankState) -> bool {
        st.ago += 1;
        // a `fix balance` rebalancing at this step forces a build (every rank alike), and so
        // does a `restart` file due now, as on one process
        if self.balance_forces_build() || self.restart_due() {
            return true;
        }
        // a moving mesh's node went more than half the skin since the last build (every
        // rank moves the same meshes alike)
        if self.mesh_rebuild_at == Some(self.step) {
            return true;
        }
        let n = &self.neighbor;
        if st.ago < n.delay || !st.ago.is_multiple_of(n.every) {
            return false;
        }
        if !n.check {
            return true;
        }
        let limit = (0.5 * n.skin) * (0.5 * n.skin);
        let x = &self.particles.x[..st.nlocal];
        let moved = x.iter().zip(&st.built).any(|(a, b)| {
            let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
            d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > limit
        });
        let rebuild = comm.all_reduce_i64(i64::from(moved), Reduce::Max) > 0;
        if rebuild && st.ago == n.every.max(n.delay) {
            self.stats.dangerous += 1;
        }
        rebuild
    }

    /// Pair forces on owned particles and ghosts (the ghosts behind the owned particles;
    /// their forces are not used), then the ghosts set apart and the forcing fixes run on
    /// the owned particles; `update` false in the setup evaluation.
    /// `want_virial`: tally the per-atom pair virial if a `compute stress/atom` reads it (an
    /// owned particle's is whole: every pair with an owned particle is computed on its rank).
    pub(super) fn rank_forces(&mut self, st: &mut RankState, update: bool, want_virial: bool) {
        let tally = want_virial && self.computes.iter().any(|c| c.style().reads_virial());
        self.virial.clear();
        self.virial_step = tally.then_some(self.step);
        if tally {
            self.virial.resize(self.particles.len(), [0.0; 6]);
        }
        // `pair_modify compute no`: the pair style leaves the forces alone
        let compute = self.pair_compute;
        match self.pair.as_mut().filter(|_| compute) {
            Some(pair) => pair.compute(
                &mut self.particles,
                &st.pairs,
                &mut st.history,
                self.dt,
                update,
                tally.then_some(&mut self.virial[..]),
                &SumOrder::ListOrder,
                None,
            ),
            None => self.particles.clear_forces(),
        }
        if st.fresh {
            self.particles.copy_tail_into(st.nlocal, &mut st.ghosts);
            st.fresh = false;
        }
        if self
            .computes
            .iter()
            .any(|c| c.style().reads_pair_contacts())
        {
            let (v, omega) = &mut st.ghost_motion;
            v.clear();
            v.extend_from_slice(&self.particles.v[st.nlocal..]);
            omega.clear();
            omega.extend_from_slice(&self.particles.omega[st.nlocal..]);
        }
        self.particles.truncate(st.nlocal);
        self.virial.truncate(st.nlocal);
        // the mesh lists use the full skin when the box can change, as on one process
        let moving_skin = self.box_changes();
        fixes::post_force(
            &mut self.fixes,
            &mut self.particles,
            (self.step, &self.domain),
            self.dt,
            update,
            (st.builds, self.neighbor.skin),
            moving_skin,
        );
    }
}
