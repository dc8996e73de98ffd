//! The step loop of `run N`: the run's checks and setup (forces, fix state, output), the
//! velocity-Verlet steps in LIGGGHTS's order of phases, and the end-of-run report.

use super::*;

impl Simulation {
    /// `run N`: a setup force evaluation, then N velocity-Verlet steps with output.
    pub fn run(
        &mut self,
        nsteps: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.run_with_setup(nsteps, true, out, vars)
    }

    /// `run N pre yes|no`: with `pre no` after the first run, the atoms, neighbour list and
    /// forces of the last step are kept (LIGGGHTS then only sets up output).
    pub fn run_with_setup(
        &mut self,
        nsteps: i64,
        pre: bool,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        // on ranks, those sharing this machine share out its cores
        self.accel.settle_threads();
        if self.comm.as_ref().is_some_and(|c| c.size() > 1) {
            // each rank runs on its own thread (ranks never wait on one another's threads)
            return self.run_ranks(nsteps, out, vars);
        }
        let accel = self.accel.clone();
        let team = self.accel.team();
        let mut job = crate::engine::accel::Handed((self, out, vars));
        accel.run_on_engine_thread(move || {
            let (sim, out, vars) = job.get();
            // the per-step stages on the team's threads, which stay awake between them
            let _team = crate::util::team::activate(team.as_deref());
            sim.run_here(nsteps, pre, &mut **out, &mut **vars)
        })
    }

    /// `run_with_setup` on the thread it is called from.
    fn run_here(
        &mut self,
        nsteps: i64,
        pre: bool,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let (first, last, started) = self.init_run(nsteps)?;
        if pre || !self.has_run {
            self.setup_forces(vars)?;
        }
        self.has_run = true;
        self.setup_fix_state(out, vars)?;
        self.setup_output(first, last, out, vars)?;
        let result = self.steps_tuned(nsteps, last, out, vars);
        crate::util::team::hold(false);
        result?;
        self.finish_run(nsteps, started, out);
        Ok(())
    }

    /// The run's steps; with a team of threads and fewer than [`crate::util::tuner::TUNE_BELOW`] particles, the
    /// stages go to the team or stay on this thread, whichever measured faster (the same
    /// results either way; see [`crate::util::tuner`]).
    fn steps_tuned(
        &mut self,
        nsteps: i64,
        last: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        use crate::util::tuner::{Tuner, TUNE_BELOW};
        let team = crate::util::team::is_active();
        // the last run's choice and schedule carry on (a deck's runs are mostly one scene)
        let mut tuner: Tuner = std::mem::take(&mut self.accel.tuner);
        let mut result = Ok(());
        for _ in 0..nsteps {
            if !team || self.particles.len() >= TUNE_BELOW {
                crate::util::team::hold(false);
                result = self.step_once(last, out, vars);
            } else {
                crate::util::team::hold(tuner.alone());
                let clock = std::time::Instant::now();
                result = self.step_once(last, out, vars);
                tuner.record(clock.elapsed().as_secs_f64());
            }
            if result.is_err() {
                break;
            }
        }
        self.accel.tuner = tuner;
        result
    }

    /// LIGGGHTS's `init` of a run of `nsteps`: the pair style, models and fixes checked
    /// and prepared. The run's first and last steps and its start time.
    fn init_run(&mut self, nsteps: i64) -> Result<(i64, i64, std::time::Instant), EngineError> {
        if !self.domain.exists {
            return Err("Run command before simulation box is defined".into());
        }
        self.init_pair()?;
        self.init_liquid()?;
        self.init_heat()?;
        self.list_run_fixes();
        self.check_meshes_in_box()?;
        let (first, last, started) = self.begin_run(nsteps)?;
        self.setup_deform(first)?;
        self.init_fix_styles()?;
        self.setup_fix_styles();
        self.setup_compute_styles();
        self.accel.settle_threads();
        if self.accel.fast {
            self.start_order_record();
        }
        Ok((first, last, started))
    }

    /// The part of a run's `init` every run shares (one process or several ranks): the run's
    /// step bounds, the time origin, the neighbour cutoff, the run checks and the motion
    /// guard's watch reset. The run's first and last steps and its start time.
    pub(super) fn begin_run(
        &mut self,
        nsteps: i64,
    ) -> Result<(i64, i64, std::time::Instant), EngineError> {
        let first = self.step;
        let last = self.step + nsteps;
        self.run_bounds = Some((
            self.ramp_bounds.0.unwrap_or(first),
            self.ramp_bounds.1.unwrap_or(last),
        ));
        self.atime_step = self.step;
        let started = std::time::Instant::now();
        self.neighbor.cutneighmax = self.liggghts_cutneighmax();
        self.check_run_init()?;
        self.energy_watch = None;
        self.guard_notes = GuardNotes::default();
        Ok((first, last, started))
    }

    /// The setup force evaluation (skipped by `run N pre no` after a first run): atoms in
    /// the box, lists, meshes, then the forces without advancing contact history.
    fn setup_forces(&mut self, vars: &mut dyn VariableSource) -> Result<(), EngineError> {
        self.pbc_and_box()?;
        self.build_mesh_topology()?;
        if self.sort_every > 0 {
            self.sort_particles();
        }
        self.build_neighbors();
        self.servo_bins();
        self.refresh_all_mesh_surfaces();
        self.refresh_moving_meshes(true);
        self.zero_mesh_velocities(true);
        self.mesh_stress_phase(StressPhase::Setup)?;
        self.pre_force_fix_styles(true, vars)?;
        // LIGGGHTS's setup evaluation does not advance contact history
        self.compute_forces(false, true, vars)?;
        self.setup_clump_forces();
        self.zero_mesh_velocities(false);
        self.guard_motion(true)?;
        self.guard_forces()
    }

    /// The fixes' setup after the forces: servo, mass flow, tracers, the restart state
    /// taken (and said), insertions and the averaging fixes.
    fn setup_fix_state(
        &mut self,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.servo_setup()?;
        self.massflow_lists(true)?;
        self.before_step_compute_styles();
        if let Some(m) = self.new_margin() {
            guard_say(&m);
        }
        if self.accel.fast {
            self.say_unaccelerated(out);
        }
        self.say_history_restored(out);
        self.restart_in_progress = false;
        self.restart_fixes.clear();
        self.restart_peratom.clear();
        self.restart_move_origins.clear();
        self.restart_mesh_history.clear();
        self.say_clump_energy(out);
        self.setup_insertions(out)?;
        self.setup_fix_style_passes(&fixes::SetupPass::BEFORE_VALUES, vars)?;
        self.setup_fix_values();
        self.setup_fix_style_passes(&[fixes::SetupPass::TimeAverages], vars)
    }

    /// LIGGGHTS's note that the pair style's history fix, created at the first run, takes
    /// its state from the restart file.
    pub(super) fn say_history_restored(&self, out: Sink<'_>) {
        if self.pair.as_ref().is_some_and(|p| p.history_width() > 0) {
            // the pair style's history fix is created (and restored) at the first run
            let id = ("contacthistory".to_string(), "contacthistory".to_string());
            if self
                .restart_fixes
                .iter()
                .any(|g| g.id == id.0 && g.style == id.1)
            {
                out("Resetting global state of Fix contacthistory Style contacthistory from restart file info\n");
            }
            if self.restart_peratom.contains(&id) {
                out("Resetting per-atom state of Fix contacthistory Style contacthistory from restart file info\n");
            }
        }
    }

    /// The run's output setup: the thermo header and first line, the setup dumps, the
    /// loop's clock and statistics.
    fn setup_output(
        &mut self,
        first: i64,
        last: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.thermo.run_start = first;
        self.thermo.run_last = last;
        self.thermo.prepare_run(self.box_changes());
        let thermo_file = &mut self.extras.thermo_file;
        self.thermo.header(&mut |s: &str| {
            out(s);
            crate::engine::extras::tee(thermo_file, s)
        });
        self.thermo_line(out, vars)?;
        self.write_dumps(true, vars)?;
        self.loop_clock = Some(std::time::Instant::now());
        self.stats = RunStats::default();
        let timed = self.extras.modify_timing > 0;
        for f in &mut self.fixes {
            f.clock = crate::engine::fix_timing::FixClock {
                on: timed,
                seconds: 0.0,
            };
        }
        if let Some(o) = self.observer.as_mut() {
            o.run_started(first, last, self.particles.len());
        }
        Ok(())
    }

    /// One velocity-Verlet step of a run ending at step `last`.
    fn step_once(
        &mut self,
        last: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.step += 1;
        self.first_half(out, vars)?;
        // LIGGGHTS inserts in pre_exchange: after the first half-step, before the list
        // decision (a changed atom count forces the rebuild)
        self.insert_particles(out)?;
        self.insert_streams(out)?;
        let rebuilt = self.decide();
        if rebuilt {
            self.rebuild()?;
        }
        self.refresh_moving_meshes(rebuilt);
        self.mesh_stress_phase(StressPhase::PreForce)?;
        self.pre_force_fix_styles(false, vars)?;
        let tally = self.virial_wanted(last);
        self.compute_forces(true, tally, vars)?;
        self.guard_forces()?;
        self.second_half(out, vars)?;
        self.step_output(last, out, vars)
    }

    /// The first half of a step: moves, the first half-kick and drift, moving meshes, mass
    /// flow and tracers.
    fn first_half(
        &mut self,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.resolve_move_fixes(vars)?;
        fixes::initial_integrate(
            &mut self.fixes,
            &mut self.particles,
            self.step,
            self.dt,
            &self.domain,
        );
        self.liquid_initial_integrate();
        fixes::move_meshes(&mut self.fixes, self.dt);
        self.servo_initial_integrate();
        self.massflow_phase(out)?;
        self.before_step_compute_styles();
        // a runaway shows first in the half-kicked velocities, before atoms are wrapped or lost
        self.guard_motion(false)
    }

    /// A neighbour-list rebuild: atoms leaving through mass-flow meshes go, the rest are
    /// wrapped (and sorted when due), then the lists are built.
    fn rebuild(&mut self) -> Result<(), EngineError> {
        self.massflow_delete();
        let mut comm = self.stats.comm;
        timed(&mut comm, || self.pbc_and_box())?;
        self.stats.comm = comm;
        let mut neigh = self.stats.neigh;
        timed(&mut neigh, || {
            if self.sort_every > 0 && self.step >= self.next_sort {
                self.sort_particles();
            }
            self.build_neighbors();
        });
        self.stats.neigh = neigh;
        self.stats.builds += 1;
        self.massflow_lists(false)?;
        self.servo_bins();
        Ok(())
    }

    /// The second half of a step: the second half-kick, the mesh and servo phases after
    /// it, and the fixes' end of step.
    fn second_half(
        &mut self,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        fixes::final_integrate(
            &mut self.fixes,
            &mut self.particles,
            self.step,
            self.dt,
            &self.domain,
        );
        self.liquid_final_integrate();
        self.mesh_stress_phase(StressPhase::EndOfStep)?;
        self.servo_final_integrate(vars)?;
        self.end_of_step(out, vars)
    }

    /// A step's output: thermo when due, dumps, restart files, the progress observer.
    fn step_output(
        &mut self,
        last: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let started_output = std::time::Instant::now();
        if self.thermo.due(self.step, last) {
            self.thermo_line(out, vars)?;
        }
        self.write_dumps(false, vars)?;
        self.periodic_restart()?;
        self.stats.output += started_output.elapsed().as_secs_f64();
        if self.step % crate::progress::OBSERVE_EVERY == 0 {
            if let Some(o) = self.observer.as_mut() {
                o.step(self.step, self.particles.len());
            }
        }
        Ok(())
    }

    /// The end of a run of `nsteps` started at `started`: the clocks stopped, the atoms'
    /// order restored, LIGGGHTS's loop time and statistics, regolith's guard summary.
    fn finish_run(&mut self, nsteps: i64, started: std::time::Instant, out: Sink<'_>) {
        if let Some(o) = self.observer.as_mut() {
            o.run_finished();
        }
        self.run_bounds = None;
        self.loop_clock = None;
        for f in &mut self.fixes {
            f.clock.on = false;
        }
        if self.accel.fast {
            self.restore_order();
        }
        self.atime += (self.step - self.atime_step) as f64 * self.dt;
        self.atime_step = self.step;
        let loop_time = self.stats_loop_time(started);
        out(&format!(
            "Loop time of {} on 1 procs for {} steps with {} atoms\n\n",
            crate::util::format::g(loop_time),
            nsteps,
            self.particles.len()
        ));
        out(&self.run_statistics(loop_time));
        self.guard_summary();
        if self.list.missed > 0 {
            out(&format!(
                "WARNING: {} neighbour-list entries of particles grown since the run started were \
                 beyond LIGGGHTS's bin stencil (cutneighmax {}) and were left out, as LIGGGHTS \
                 3.8.0 leaves them out: such particles may pass through each other. A larger \
                 neighbor skin, or a new run after the growth, finds them.\n",
                self.list.missed,
                crate::util::format::g(self.neighbor.cutneighmax)
            ));
            self.list.missed = 0;
        }
    }

    /// The fixes LIGGGHTS creates at a run's init joined to its fix list (once): the pair
    /// style's contact history, the liquid transport of a wet pair style with its per-atom
    /// arrays, the multiple-contact stores; then any fix regolith added itself.
    fn list_run_fixes(&mut self) {
        let list = &mut self.modify_list;
        let width = self.pair.as_ref().map_or(0, |p| p.history_width());
        if width > 0 {
            list.ensure("contacthistory", "contacthistory", None);
        }
        if self
            .pair_selection
            .as_ref()
            .is_some_and(|s| s.cohesion == crate::engine::wet::EASO)
        {
            list.ensure("liquidtransfer", "transportequation/scalar", None);
        }
        for f in &self.fixes {
            list.ensure(&f.id, &f.style, None);
        }
        if self
            .pair_selection
            .as_ref()
            .is_some_and(|s| s.surface == "multicontact")
        {
            list.ensure("multicontactData_", "contactproperty/atom", None);
            list.ensure("nneighs_full", "property/atom", None);
        }
    }
}
