//! Fix styles as modules: [`FixStyle`] is what a style may do in LIGGGHTS's phases of a run,
//! each hook a no-op unless the style overrides it. The engine calls the hooks of every fix
//! held as [`FixKind::Style`](super::FixKind::Style) where the phase runs, in the order the
//! fixes were defined, interleaved with the other fixes of that phase exactly as LIGGGHTS
//! orders a phase (Modify's lists are in fix order). A hook is called once per fix and
//! phase, never per particle: a style loops over the particles itself.
//!
//! A style is one file under `commands/fix/` (its arguments, its state, this trait) and one
//! row in that folder's table.

use crate::engine::contact::MaterialInput;
use crate::engine::domain::Domain;
use crate::engine::error::EngineError;
use crate::engine::particles::Particles;
use crate::engine::region::Regions;
use crate::engine::sim::{Simulation, VariableSource};

use super::Fix;

/// What a phase hook is told about the fix and the step.
#[derive(Debug, Clone, Copy)]
pub struct FixStep<'a> {
    /// Group bits of the fix (particle `i` is in the group when `p.mask[i] & group != 0`).
    pub group: u32,
    /// The step being made (at `setup`: the step the run starts from).
    pub step: i64,
    /// The time step (time).
    pub dt: f64,
    /// The box (for unwrapping positions across periodic faces).
    pub domain: &'a Domain,
    /// The per-atom pair virial of this step's force evaluation (xx yy zz xy xz yz; force
    /// length), empty when it was not tallied (given at `end_of_step` and `setup_values`).
    pub virial: &'a [[f64; 6]],
    /// LIGGGHTS's largest contact distance, `cutneighmax - skin` (length; given at
    /// `end_of_step` and `setup_values`, else 0).
    pub contact: f64,
    /// The neighbour skin (length; given at `end_of_step` and `setup_values`, else 0).
    pub skin: f64,
    /// The deck's regions (given at `end_of_step` and `setup_values`, else None).
    pub regions: Option<&'a Regions>,
    /// The largest squared node speed of the moving meshes of the last mesh wall
    /// (length^2/time^2; given at `end_of_step` and `setup_values`, else 0).
    pub mesh_vmax_sqr: f64,
}

impl<'a> FixStep<'a> {
    /// A step of fix `group` at `step` with time step `dt` (time) in `domain`, with no
    /// virial and no contact distance (what every phase but `end_of_step` and
    /// `setup_values` gets).
    pub fn plain(group: u32, step: i64, dt: f64, domain: &'a Domain) -> Self {
        FixStep {
            group,
            step,
            dt,
            domain,
            virial: &[],
            contact: 0.0,
            skin: 0.0,
            regions: None,
            mesh_vmax_sqr: 0.0,
        }
    }
}

/// The shape of a style's per-atom values (`f_ID` / `f_ID[N]` in dumps, atom-style
/// variables and computes that read fixes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PerAtomShape {
    /// No per-atom values.
    None,
    /// One value per atom, read as `f_ID` (LIGGGHTS's `size_peratom_cols` 0).
    Vector,
    /// This many columns per atom, read as `f_ID[1..N]`.
    Array(usize),
}

/// What a style may read in [`FixStyle::evaluate`]: the deck's variables and regions as they
/// stand at this force evaluation.
pub trait StepInputs {
    /// The value of equal-style variable `name`.
    fn equal(&mut self, name: &str) -> Result<f64, EngineError>;
    /// The values of atom-style variable `name`, one per particle in particle order.
    fn atom(&mut self, name: &str) -> Result<Vec<f64>, EngineError>;
    /// Whether the point `x` (length) is inside region `region` (its index among the
    /// deck's regions, as `Regions::find` gives it).
    fn in_region(&self, region: usize, x: [f64; 3]) -> bool;
    /// [`StepInputs::in_region`] for every point of `xs`.
    fn in_region_each(&self, region: usize, xs: &[[f64; 3]]) -> Vec<bool> {
        xs.iter().map(|&x| self.in_region(region, x)).collect()
    }
    /// `text` with its `$` references to the deck's variables substituted (`fix print`);
    /// by default only a text without `$` passes.
    fn substitute(&mut self, text: &str) -> Result<String, EngineError> {
        if text.contains('$') {
            return Err(EngineError::Invalid(format!(
                "cannot substitute variables in '{text}' here"
            )));
        }
        Ok(text.to_string())
    }
}

/// What a style's [`FixStyle::init`] may read of the run's other fixes.
#[derive(Debug, Clone, Copy)]
pub struct FixInit<'a> {
    /// The uniform accelerations the run's fixes add (length/time^2; see
    /// [`FixStyle::acceleration`]), in fix order.
    pub accelerations: &'a [[f64; 3]],
    /// The largest bounding radius of the first particle distribution fix (length; 0
    /// without one), which `fix diam/max` reads.
    pub first_distribution_bound: f64,
}

/// What a style's [`FixStyle::init_pair`] reads at the pair style's init.
#[derive(Debug, Clone, Copy)]
pub struct PairInit<'a> {
    /// Whether a granular pair style is defined.
    pub pair_gran: bool,
    /// The material properties as `fix property/global` defines them.
    pub materials: &'a MaterialInput,
    /// The thermo interval (steps).
    pub thermo_every: i64,
    /// The thermo keywords (`f_ID[2]` ...).
    pub thermo_keywords: &'a [&'a str],
    /// The pair style's surface model (`default`, `multicontact`), None without a pair
    /// style.
    pub pair_surface: Option<&'a str>,
    /// The surface model of every `fix wall/gran`, in fix order.
    pub wall_surfaces: &'a [&'a str],
}

/// What the `post_force` phase tells a style that keeps its own lists of the pair list's
/// particles (granular walls; see [`FixStyle::post_force_among`]).
#[derive(Debug, Clone, Copy)]
pub struct ForcePass {
    /// Whether contact histories advance (false in a run's setup force evaluation).
    pub update: bool,
    /// The pair list's build count and skin (length).
    pub list: (u64, f64),
    /// Whether mesh neighbour lists use the full skin (moving meshes or a changing box).
    pub moving_skin: bool,
}

/// A style's state as [`std::any::Any`], so the fixes that read another fix's state find it
/// by its type ([`FixKind::style_as`](super::FixKind::style_as)). Every `'static` type has it
/// through the blanket impl below: a style writes nothing for it.
pub trait AsAny: std::any::Any {
    /// The style's state, to read.
    fn any_ref(&self) -> &dyn std::any::Any;
    /// The style's state, to change.
    fn any_mut(&mut self) -> &mut dyn std::any::Any;
}

impl<T: std::any::Any> AsAny for T {
    fn any_ref(&self) -> &dyn std::any::Any {
        self
    }

    fn any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

/// A fix style: the phases it hooks and the values it offers. Every hook has a default that
/// does nothing (or offers nothing), so a style writes only what it does.
pub trait FixStyle: AsAny + Send {
    /// The style's name as decks write it (`viscous`).
    fn name(&self) -> &str;

    /// LIGGGHTS's `init` checks at the start of every run (and of a dry run's `run`): an
    /// error stops the run with LIGGGHTS's message. `dimension` is 2 or 3.
    fn check(&self, _p: &Particles, _group: u32, _dimension: u32) -> Result<(), EngineError> {
        Ok(())
    }

    /// LIGGGHTS's `init` of a style that reads the pair style and the materials (at the
    /// pair style's init, the first of a run's checks): an error stops the run.
    fn init_pair(&mut self, _pair: &PairInit) -> Result<(), EngineError> {
        Ok(())
    }

    /// The `geometric_prefactor` of `fix multicontact/halfspace` (dimensionless), which
    /// `pair_style gran ... surface multicontact` reads (None: another style).
    fn multicontact_prefactor(&self) -> Option<f64> {
        None
    }

    /// How often the style computes its global values (steps), for LIGGGHTS's "not
    /// computed at compatible time" checks.
    fn global_freq(&self) -> i64 {
        1
    }

    /// LIGGGHTS's `init` of a style that reads the run's other fixes (`fix buoyancy` takes
    /// the gravity), after [`FixStyle::check`]: an error stops the run with LIGGGHTS's message.
    fn init(&mut self, _run: &FixInit) -> Result<(), EngineError> {
        Ok(())
    }

    /// At the start of every run, before the setup force evaluation: state the style keeps
    /// for the run (LIGGGHTS's `init`/`setup` bookkeeping).
    fn setup(&mut self, _p: &Particles, _at: &FixStep) {}

    /// Whether the style changes particle radii during runs (`fix adapt`: the neighbour
    /// lists then allow for growing particles).
    fn changes_radii(&self) -> bool {
        false
    }

    /// The part of the run the fast path leaves to the exact path's code because of this
    /// style, as its note names it (None: the style runs on the fast path).
    fn unaccelerated(&self) -> Option<&'static str> {
        None
    }

    /// Whether the style has `pre_force` work at `step` (`setup`: the run's setup force
    /// evaluation, LIGGGHTS's `setup_pre_force`): only then are
    /// [`FixStyle::pre_force_evaluate`] and [`FixStyle::pre_force`] called.
    fn pre_force_due(&self, _step: i64, _setup: bool) -> bool {
        false
    }

    /// Before `pre_force`: read the variables the style needs. While it runs the fix itself
    /// is out of the fix list (its `f_ID` values cannot be read).
    fn pre_force_evaluate(
        &mut self,
        _p: &Particles,
        _at: &FixStep,
        _inputs: &mut dyn StepInputs,
    ) -> Result<(), EngineError> {
        Ok(())
    }

    /// `pre_force`: after the neighbour lists, before the forces (`fix adapt` sets radii).
    fn pre_force(&mut self, _p: &mut Particles, _at: &FixStep) {}

    /// `initial_integrate`: the first half of a velocity-Verlet step (before the forces).
    fn initial_integrate(&mut self, _p: &mut Particles, _at: &FixStep) {}

    /// Whether the style reads variables or regions in a step: only then is its
    /// [`FixStyle::evaluate`] called (runs without such styles pay nothing for it).
    fn evaluates(&self) -> bool {
        false
    }

    /// Before `post_force`, after the pair forces of every force evaluation (the setup one
    /// too): read the variables and regions the style needs for this step. While it runs the
    /// fix itself is out of the fix list (its `f_ID` values cannot be read).
    fn evaluate(
        &mut self,
        _p: &Particles,
        _at: &FixStep,
        _inputs: &mut dyn StepInputs,
    ) -> Result<(), EngineError> {
        Ok(())
    }

    /// `post_force`: after the pair and wall forces (also in the setup force evaluation, as
    /// LIGGGHTS's `setup` of force fixes runs their `post_force`).
    fn post_force(&mut self, _p: &mut Particles, _at: &FixStep) {}

    /// Whether the style's phase hooks read the pair list's state or the other fixes
    /// (granular walls, rigid clumps): then the `*_among` hooks run in its place of each
    /// phase instead of the plain ones.
    fn among_fixes(&self) -> bool {
        false
    }

    /// `post_force` of a style that [`FixStyle::among_fixes`]: `fixes` is the whole fix
    /// list, this fix's own slot lent out ([`FixKind::Lent`](super::FixKind::Lent)) while
    /// the hook runs; `pass` the pair list's state.
    fn post_force_among(
        &mut self,
        _fixes: &mut [Fix],
        p: &mut Particles,
        at: &FixStep,
        _pass: &ForcePass,
    ) {
        self.post_force(p, at)
    }

    /// `initial_integrate` of a style that [`FixStyle::among_fixes`] (`fixes` as in
    /// [`FixStyle::post_force_among`]).
    fn initial_integrate_among(&mut self, _fixes: &mut [Fix], p: &mut Particles, at: &FixStep) {
        self.initial_integrate(p, at)
    }

    /// `final_integrate` of a style that [`FixStyle::among_fixes`] (`fixes` as in
    /// [`FixStyle::post_force_among`]).
    fn final_integrate_among(&mut self, _fixes: &mut [Fix], p: &mut Particles, at: &FixStep) {
        self.final_integrate(p, at)
    }

    /// `final_integrate`: the second half of the step (after the forces).
    fn final_integrate(&mut self, _p: &mut Particles, _at: &FixStep) {}

    /// `end_of_step`: after the step, before output (the style decides its own interval).
    fn end_of_step(&mut self, _p: &mut Particles, _at: &FixStep) {}

    /// `end_of_step` on several MPI ranks, over this rank's own particles: `min` replaces
    /// each value of a slice by its minimum over all ranks (every rank gets the same). By
    /// default [`FixStyle::end_of_step`] (styles that act on each particle alone).
    fn end_of_step_ranks(&mut self, p: &mut Particles, at: &FixStep, _min: &dyn Fn(&mut [f64])) {
        self.end_of_step(p, at)
    }

    /// Whether the style writes output at the end of `step`: only then is its
    /// [`FixStyle::end_of_step_output`] called.
    fn outputs_at(&self, _step: i64) -> bool {
        false
    }

    /// At `end_of_step`, right after [`FixStyle::end_of_step`]: output that reads the deck's
    /// variables (`fix print`), written to `out` (screen and log) or the style's own files.
    /// While it runs the fix itself is out of the fix list (its `f_ID` values cannot be read).
    fn end_of_step_output(
        &mut self,
        _at: &FixStep,
        _inputs: &mut dyn StepInputs,
        _out: &mut dyn FnMut(&str),
    ) -> Result<(), EngineError> {
        Ok(())
    }

    /// The global value `f_ID` (index None) or `f_ID[i]` (1-based) for thermo, variables and
    /// `fix ave/time`; None when the style has no such value.
    fn value(&self, _index: Option<usize>) -> Option<f64> {
        None
    }

    /// The style has a global scalar `f_ID` besides a per-atom vector of the same name: a
    /// variable reads the scalar, as LIGGGHTS's variables take a fix's global scalar
    /// before its per-atom values (atom-style ones too).
    fn scalar_before_per_atom(&self) -> bool {
        false
    }

    /// Whether the global value `f_ID` (index None) or `f_ID[i]` is extensive (LIGGGHTS's
    /// extscalar/extvector: `thermo_modify norm yes` divides it by the atom count).
    fn extensive(&self, _index: Option<usize>) -> bool {
        false
    }

    /// The shape of the per-atom values [`FixStyle::per_atom`] gives.
    fn per_atom_shape(&self) -> PerAtomShape {
        PerAtomShape::None
    }

    /// The per-atom values, row by row in particle order (one row of the shape's width per
    /// particle).
    fn per_atom(&self, _p: &Particles) -> Vec<f64> {
        Vec::new()
    }

    /// The global state written to restart files (None: the style writes none).
    fn restart_state(&self) -> Option<Vec<u8>> {
        None
    }

    /// Take the state a restart file holds for this fix (its ID and style matched).
    fn restore_state(&mut self, _state: &[u8]) -> Result<(), RestoreError> {
        Err(RestoreError::Unsupported(format!(
            "fix {} taking its state from a restart file",
            self.name()
        )))
    }

    /// The per-atom state written to restart files: the values each particle writes
    /// (LIGGGHTS's `maxsize_restart`, the count included) and each particle's values in
    /// particle order (None: the style writes none).
    fn restart_per_atom(&self, _p: &Particles) -> Option<(i32, Vec<Vec<f64>>)> {
        None
    }

    /// Whether the style keeps per-particle state that copies of the particles
    /// (`replicate`) could not take over.
    fn keeps_per_atom_state(&self) -> bool {
        self.per_atom_shape() != PerAtomShape::None
    }

    /// The uniform acceleration the style adds to its group (`fix gravity`; length/time^2):
    /// clumps, `fix buoyancy` and the speed estimate read it (None: the style adds none).
    fn acceleration(&self) -> Option<[f64; 3]> {
        None
    }

    /// Whether the style holds its group's particles still (`fix freeze`: contacts treat
    /// them as infinitely heavy).
    fn holds_still(&self) -> bool {
        false
    }

    /// Whether the style may evaluate variables or computes inside a step (so per-atom
    /// computes must be current on every step).
    fn reads_computes(&self) -> bool {
        false
    }

    /// Whether the style reads the per-atom pair virial at the end of `step` (it is then
    /// tallied in that step's force evaluation).
    fn wants_virial(&self, _step: i64) -> bool {
        false
    }

    /// LIGGGHTS's `setup(vflag)` of a fix that evaluates there: after the setup force
    /// evaluation, with the other fixes' setup output.
    fn setup_values(&mut self, _p: &Particles, _at: &FixStep) {}

    /// The global array value `f_ID[i][j]` (1-based) for variables, `in_run` while a run is
    /// in progress; None when the style has no global array (Some(Err) carries LIGGGHTS's
    /// error for this access).
    fn array_value(&self, _i: usize, _j: usize, _in_run: bool) -> Option<Result<f64, EngineError>> {
        None
    }

    /// The style's state for fixes and outputs that read it by type
    /// ([`FixKind::style_as`](super::FixKind::style_as)): the style itself, which every style
    /// has through [`AsAny`] without writing this.
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self.any_ref())
    }

    /// [`FixStyle::as_any`], to change.
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(self.any_mut())
    }

    /// Whether `f_ID[i][j]` of the style is refused as not supported yet rather than with
    /// LIGGGHTS's "Mismatched fix in variable formula".
    fn array_unsupported(&self) -> bool {
        false
    }

    /// Whether `thermo_style` refuses `f_ID` / `f_ID[i]` of the style when the keyword is
    /// given (LIGGGHTS's "Thermo fix does not compute scalar|vector": the style computes
    /// neither); styles answering no are checked when the value is read.
    fn refuses_thermo(&self) -> bool {
        false
    }

    /// Whether the style has `end_of_step` work on the whole simulation at `step` (a step
    /// count): only then is [`FixStyle::end_of_step_sim`] called.
    fn end_of_step_sim_due(&self, _step: i64) -> bool {
        false
    }

    /// `end_of_step` of a style that reads or changes the whole simulation (averages of
    /// computes, fixes and variables; the box of `fix deform`), after
    /// [`FixStyle::end_of_step`]. `k` is the fix's index in `sim.fixes`, where
    /// [`FixStyle::stand_in`] holds its place meanwhile.
    fn end_of_step_sim(
        &mut self,
        _sim: &mut Simulation,
        _k: usize,
        _vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        Ok(())
    }

    /// The pass of a run's setup, after the insertions, in which [`FixStyle::setup_sim`]
    /// runs (None: the style has no such setup).
    fn setup_pass(&self) -> Option<SetupPass> {
        None
    }

    /// LIGGGHTS's `init` and `setup` of a style that reads the whole simulation (a schedule
    /// left behind restarted, a sample due now), in its [`FixStyle::setup_pass`]; `k` as in
    /// [`FixStyle::end_of_step_sim`].
    fn setup_sim(
        &mut self,
        _sim: &mut Simulation,
        _k: usize,
        _vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        Ok(())
    }

    /// What the fix list holds in the fix's place while [`FixStyle::end_of_step_sim`] or
    /// [`FixStyle::setup_sim`] runs (None: a placeholder whose values cannot be read).
    fn stand_in(&self) -> Option<Box<dyn FixStyle>> {
        None
    }
}

/// Why a style cannot take the state a restart file holds for it
/// ([`FixStyle::restore_state`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum RestoreError {
    /// The stored state is malformed; what is wrong with it (`empty`, `too short`). The
    /// caller names the fix and the file.
    #[error("{0}")]
    Malformed(String),
    /// A stored value LIGGGHTS refuses, in LIGGGHTS's words (a generator state it cannot
    /// seed from).
    #[error("{0}")]
    Refused(String),
    /// The style does not take its state from restart files yet; the feature as the deck
    /// names it.
    #[error("{0}: not supported yet")]
    Unsupported(String),
}

impl From<crate::util::random::SeedError> for RestoreError {
    fn from(e: crate::util::random::SeedError) -> RestoreError {
        RestoreError::Refused(e.to_string())
    }
}

/// The passes of a run's setup in which styles sample with the whole simulation
/// ([`FixStyle::setup_sim`]): the passes in this order, each over the fixes in fix order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum SetupPass {
    /// Snapshots of computes, fixes and variables (`fix store/state`).
    Snapshots,
    /// Per-atom time averages (`fix ave/atom`).
    AtomAverages,
    /// Per-bin averages (`fix ave/spatial`).
    SpatialAverages,
    /// Histograms (`fix ave/histo`).
    Histograms,
    /// Time averages of global values (`fix ave/time`), after the styles' `setup_values`.
    TimeAverages,
}

impl SetupPass {
    /// The passes before the styles' `setup_values`, in the order a run's setup makes them.
    pub const BEFORE_VALUES: [SetupPass; 4] = [
        SetupPass::Snapshots,
        SetupPass::AtomAverages,
        SetupPass::SpatialAverages,
        SetupPass::Histograms,
    ];
}

/// The deck's variables and regions as a running simulation answers [`StepInputs`].
struct SimulationInputs<'a> {
    sim: &'a Simulation,
    vars: &'a mut dyn VariableSource,
}

impl StepInputs for SimulationInputs<'_> {
    fn equal(&mut self, name: &str) -> Result<f64, EngineError> {
        self.vars.equal(self.sim, name)
    }

    fn atom(&mut self, name: &str) -> Result<Vec<f64>, EngineError> {
        self.vars.atom(self.sim, name)
    }

    fn in_region(&self, region: usize, x: [f64; 3]) -> bool {
        self.sim.regions.matches(region, x)
    }

    fn in_region_each(&self, region: usize, xs: &[[f64; 3]]) -> Vec<bool> {
        self.sim.regions.matches_each(region, xs)
    }

    fn substitute(&mut self, text: &str) -> Result<String, EngineError> {
        self.vars.substitute(self.sim, text)
    }
}

impl Simulation {
    /// The `evaluate` hook of every module fix style that [`FixStyle::evaluates`], in fix
    /// order, before the `post_force` phase.
    pub(crate) fn evaluate_fix_styles(
        &mut self,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        for k in 0..self.fixes.len() {
            if !matches!(&self.fixes[k].kind, super::FixKind::Style(s) if s.evaluates()) {
                continue;
            }
            let clock = self.fixes[k].clock.start();
            let kind = std::mem::replace(&mut self.fixes[k].kind, super::FixKind::Lent);
            let super::FixKind::Style(mut style) = kind else {
                unreachable!("checked above")
            };
            let at = FixStep::plain(self.fixes[k].group, self.step, self.dt, &self.domain);
            let mut inputs = SimulationInputs {
                sim: &*self,
                vars: &mut *vars,
            };
            let result = style.evaluate(&self.particles, &at, &mut inputs);
            self.fixes[k].kind = super::FixKind::Style(style);
            self.fixes[k].clock.stop(clock);
            result?;
        }
        Ok(())
    }

    /// The `end_of_step_output` hook of module fix style `k` (see
    /// [`FixStyle::end_of_step_output`]).
    pub(crate) fn fix_style_output(
        &mut self,
        k: usize,
        out: &mut dyn FnMut(&str),
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let kind = std::mem::replace(&mut self.fixes[k].kind, super::FixKind::Lent);
        let super::FixKind::Style(mut style) = kind else {
            self.fixes[k].kind = kind;
            return Ok(());
        };
        let at = FixStep::plain(self.fixes[k].group, self.step, self.dt, &self.domain);
        let mut inputs = SimulationInputs {
            sim: &*self,
            vars: &mut *vars,
        };
        let result = style.end_of_step_output(&at, &mut inputs, out);
        self.fixes[k].kind = super::FixKind::Style(style);
        result
    }

    /// The `pre_force` hooks of every module fix style due now, in fix order (`setup`: the
    /// run's setup force evaluation).
    pub(crate) fn pre_force_fix_styles(
        &mut self,
        setup: bool,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = self.step;
        for k in 0..self.fixes.len() {
            if !matches!(&self.fixes[k].kind, super::FixKind::Style(s) if s.pre_force_due(step, setup))
            {
                continue;
            }
            let clock = self.fixes[k].clock.start();
            let kind = std::mem::replace(&mut self.fixes[k].kind, super::FixKind::Lent);
            let super::FixKind::Style(mut style) = kind else {
                unreachable!("checked above")
            };
            let at = FixStep::plain(self.fixes[k].group, step, self.dt, &self.domain);
            let mut inputs = SimulationInputs {
                sim: &*self,
                vars: &mut *vars,
            };
            let result = style.pre_force_evaluate(&self.particles, &at, &mut inputs);
            if result.is_ok() {
                style.pre_force(&mut self.particles, &at);
            }
            self.fixes[k].kind = super::FixKind::Style(style);
            self.fixes[k].clock.stop(clock);
            result?;
        }
        Ok(())
    }

    /// The `init_pair` hook of every module fix style, in fix order.
    pub(crate) fn init_pair_fix_styles(
        &mut self,
        materials: &MaterialInput,
    ) -> Result<(), EngineError> {
        if !self
            .fixes
            .iter()
            .any(|f| matches!(f.kind, super::FixKind::Style(_)))
        {
            return Ok(());
        }
        let keywords: Vec<&str> = self
            .thermo
            .fields
            .iter()
            .map(|f| f.keyword.as_str())
            .collect();
        let walls: Vec<String> = self
            .fixes
            .iter()
            .filter_map(|f| Some(f.kind.wall_selection()?.surface.clone()))
            .collect();
        let wall_surfaces: Vec<&str> = walls.iter().map(String::as_str).collect();
        let pair_surface = self.pair_selection.as_ref().map(|s| s.surface.clone());
        let pair = PairInit {
            pair_gran: self.pair_selection.is_some(),
            materials,
            thermo_every: self.thermo.every,
            thermo_keywords: &keywords,
            pair_surface: pair_surface.as_deref(),
            wall_surfaces: &wall_surfaces,
        };
        for fix in &mut self.fixes {
            if let super::FixKind::Style(s) = &mut fix.kind {
                s.init_pair(&pair)?;
            }
        }
        Ok(())
    }

    /// Run `hook` on module fix style `k` with the whole simulation at hand, the style's
    /// [`FixStyle::stand_in`] in its place in the fix list meanwhile (nothing for a fix of
    /// another kind).
    pub(crate) fn with_fix_style(
        &mut self,
        k: usize,
        hook: impl FnOnce(&mut dyn FixStyle, &mut Simulation) -> Result<(), EngineError>,
    ) -> Result<(), EngineError> {
        let super::FixKind::Style(s) = &self.fixes[k].kind else {
            return Ok(());
        };
        let stand_in = s
            .stand_in()
            .map_or(super::FixKind::Lent, super::FixKind::Style);
        let super::FixKind::Style(mut style) = std::mem::replace(&mut self.fixes[k].kind, stand_in)
        else {
            unreachable!("checked above")
        };
        let result = hook(&mut *style, self);
        self.fixes[k].kind = super::FixKind::Style(style);
        result
    }

    /// The `end_of_step_sim` hook of module fix style `k` when it is due at this step.
    pub(crate) fn fix_style_end_of_step_sim(
        &mut self,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = self.step;
        if !matches!(&self.fixes[k].kind, super::FixKind::Style(s) if s.end_of_step_sim_due(step)) {
            return Ok(());
        }
        self.with_fix_style(k, |s, sim| s.end_of_step_sim(sim, k, vars))
    }

    /// The `setup_sim` hooks of the module fix styles, pass by pass (of `passes`), each
    /// pass in fix order.
    pub(crate) fn setup_fix_style_passes(
        &mut self,
        passes: &[SetupPass],
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        for &pass in passes {
            for k in 0..self.fixes.len() {
                if !matches!(&self.fixes[k].kind, super::FixKind::Style(s) if s.setup_pass() == Some(pass))
                {
                    continue;
                }
                self.with_fix_style(k, |s, sim| s.setup_sim(sim, k, vars))?;
            }
        }
        Ok(())
    }

    /// The `init` hook of every module fix style, in fix order, at a run's init.
    pub(crate) fn init_fix_styles(&mut self) -> Result<(), EngineError> {
        let accelerations: Vec<[f64; 3]> = self
            .fixes
            .iter()
            .filter_map(|f| match &f.kind {
                super::FixKind::Style(s) => s.acceleration(),
                _ => None,
            })
            .collect();
        let run = FixInit {
            accelerations: &accelerations,
            first_distribution_bound: super::first_distribution_bound(&self.fixes),
        };
        for fix in &mut self.fixes {
            if let super::FixKind::Style(s) = &mut fix.kind {
                s.init(&run)?;
            }
        }
        Ok(())
    }

    /// The `setup` hook of every module fix style, in fix order, at the start of a run.
    pub(crate) fn setup_fix_styles(&mut self) {
        let at = FixStep::plain(0, self.step, self.dt, &self.domain);
        for fix in &mut self.fixes {
            if let super::FixKind::Style(s) = &mut fix.kind {
                s.setup(
                    &self.particles,
                    &FixStep {
                        group: fix.group,
                        ..at
                    },
                );
            }
        }
    }
}
