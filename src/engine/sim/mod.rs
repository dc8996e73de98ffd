//! The simulation state and the time loop: LIGGGHTS's Verlet order of operations
//! (setup force evaluation at every `run`, initial integrate, neighbour decision, force
//! clear, pair forces, post-force fixes, final integrate, output).

use crate::engine::domain::Domain;
use crate::engine::error::EngineError;
pub use crate::engine::fixes::FixKind;
use crate::engine::fixes::{self, Fix};
use crate::engine::neighbor::{carry_history, NeighborList, Pair};
use crate::engine::particles::Particles;
use crate::engine::region::Regions;
use crate::engine::thermo::Thermo;
use crate::io::dump::Layout;

mod balance;
mod dumps;
mod guard;
mod meshes;
mod multicontact;
mod neighbors;
mod output;
mod prepare;
mod ranks;
mod run;
mod servo;
mod streams;
mod values;

pub use balance::{BalanceRequest, Cuts};
pub(crate) use guard::GuardNotes;
pub use guard::{
    energy_runaway, ENERGY_GROWTH, ENERGY_WATCH_STEPS, MAX_OVERLAP, RUNAWAY_RADII_PER_STEP,
};
use guard::{guard_say, lost_atoms_message};
pub(crate) use meshes::no_k_finnie;

/// Neighbour-list settings (`neighbor`, `neigh_modify`); skin in length units.
#[derive(Debug, Clone, PartialEq)]
pub struct NeighborSettings {
    /// Extra distance beyond contact kept in the list (length).
    pub skin: f64,
    /// Consider rebuilding every this many steps.
    pub every: u64,
    /// Never rebuild sooner than this many steps after the last build.
    pub delay: u64,
    /// Rebuild only when something moved more than half the skin.
    pub check: bool,
    /// `neigh_modify exclude type M N`: type pairs never listed.
    pub exclude_types: Vec<(u32, u32)>,
    /// `neigh_modify exclude group A B`: group-bit pairs never listed (either order).
    pub exclude_groups: Vec<(u32, u32)>,
    /// LIGGGHTS's `cutneighmax` from the last run's setup: twice the largest radius of the
    /// atoms and particle templates plus the skin (length; sets the bin order).
    pub cutneighmax: f64,
}

impl NeighborSettings {
    /// Does `neigh_modify exclude` keep particles `i` and `j` of `p` out of the list?
    pub fn excludes(&self, p: &Particles, i: usize, j: usize) -> bool {
        let (ti, tj) = (p.kind[i], p.kind[j]);
        let (mi, mj) = (p.mask[i], p.mask[j]);
        self.exclude_types
            .iter()
            .any(|&(a, b)| (ti == a && tj == b) || (ti == b && tj == a))
            || self
                .exclude_groups
                .iter()
                .any(|&(a, b)| (mi & a != 0 && mj & b != 0) || (mi & b != 0 && mj & a != 0))
    }

    /// Does the list leave any pairs out (`neigh_modify exclude`)?
    pub fn excludes_any(&self) -> bool {
        !self.exclude_types.is_empty() || !self.exclude_groups.is_empty()
    }
}

impl Default for NeighborSettings {
    fn default() -> Self {
        // LIGGGHTS's defaults for SI units
        NeighborSettings {
            skin: 0.001,
            every: 1,
            delay: 10,
            check: true,
            exclude_types: Vec::new(),
            exclude_groups: Vec::new(),
            cutneighmax: 0.0,
        }
    }
}

/// A touching pair as `compute pair/gran/local` reports it: (pair index, force on i,
/// torque on i, force on j, torque on j).
pub type PairContact = (usize, [f64; 3], [f64; 3], [f64; 3], [f64; 3]);

/// Pairwise forces between listed particles (the granular contact model).
pub trait PairInteraction: Send {
    /// Doubles of history kept per listed pair (0 when the model keeps none).
    fn history_width(&self) -> usize;
    /// Per history value: does it change sign when the pair is seen from the other atom?
    fn history_flips(&self) -> Vec<bool>;
    /// The largest overlap of the last evaluation as (overlap / smaller radius, i, j).
    /// Pairs in contact at the last evaluation.
    fn contact_count(&self) -> usize {
        0
    }

    fn worst_overlap(&self) -> Option<(f64, u32, u32)> {
        None
    }
    /// The contact distance factor the model asks the neighbour list for: pairs apart by
    /// less than `factor (Ri + Rj)` are visited (LIGGGHTS's `contactDistanceFactor`; 1 for
    /// dry models).
    fn contact_distance_factor(&self) -> f64 {
        1.0
    }
    /// `surface multicontact`: the walls' gathered contacts the next evaluation folds into
    /// each particle's half-space step (in wall order; None for other models).
    fn multicontact_walls(&mut self) -> Option<&mut Vec<crate::engine::granular::WallStore>> {
        None
    }
    /// The touching listed pairs re-evaluated in the current state without advancing
    /// history (what `compute pair/gran/local` reports): (pair index, force on i, torque
    /// on i, force on j, torque on j).
    /// `ghost` holds velocities and angular velocities from the last force evaluation:
    /// for a pair across a periodic face the atom with the lower ID is LIGGGHTS's ghost,
    /// whose velocities were last communicated then.
    fn contacts(
        &self,
        p: &Particles,
        pairs: &[Pair],
        history: &[f64],
        dt: f64,
        ghost: (&[[f64; 3]], &[[f64; 3]]),
    ) -> Vec<PairContact>;
    /// Set `p.f`/`p.torque` to the pair forces and torques of the listed pairs (what they
    /// held before is overwritten).
    /// `update` is false in the setup evaluation: contact history is used but not advanced.
    /// With `virial`, each pair also adds half its virial del_a F_b to both particles
    /// (xx yy zz xy xz yz, force length).
    /// `order` says in which order (and how parallel) contributions are added; `mirrored`
    /// (a list built with LIGGGHTS's periodic second sides) makes a pass in list order add a
    /// pair across a periodic face to its first atom only and each mirror to its own.
    #[allow(clippy::too_many_arguments)]
    fn compute(
        &mut self,
        p: &mut Particles,
        pairs: &[Pair],
        history: &mut [f64],
        dt: f64,
        update: bool,
        virial: Option<&mut [[f64; 6]]>,
        order: &crate::engine::neighbor::SumOrder,
        mirrored: Option<crate::engine::neighbor::Mirrored<'_>>,
    );
}

/// The deck's variables as the running simulation reads them.
pub trait VariableSource {
    /// The value of equal-style variable `name`.
    fn equal(&mut self, sim: &Simulation, name: &str) -> Result<f64, EngineError>;
    /// The values of atom-style variable `name`, one per particle in particle order.
    fn atom(&mut self, sim: &Simulation, name: &str) -> Result<Vec<f64>, EngineError>;
    /// `on`: until `hold(false)`, the caller does not change the particles, so per-atom
    /// values (atom-style variables, per-atom computes) evaluated for one request may be
    /// kept for the next (the same numbers, evaluated once); `off`: forget them.
    fn hold(&mut self, on: bool) {
        let _ = on;
    }
    /// `text` with its `$x`, `${name}` and `$(formula)` references replaced.
    fn substitute(&mut self, sim: &Simulation, text: &str) -> Result<String, EngineError> {
        let _ = sim;
        if text.contains('$') {
            Err(EngineError::Invalid(format!(
                "cannot substitute variables in '{text}' here"
            )))
        } else {
            Ok(text.to_string())
        }
    }
}

/// No variables (unit tests and tools that run without a deck).
pub struct NoVariables;

impl VariableSource for NoVariables {
    fn equal(&mut self, _: &Simulation, name: &str) -> Result<f64, EngineError> {
        Err(EngineError::Invalid(format!(
            "Variable name {name} does not exist"
        )))
    }
    fn atom(&mut self, _: &Simulation, name: &str) -> Result<Vec<f64>, EngineError> {
        Err(EngineError::Invalid(format!(
            "Variable name {name} does not exist"
        )))
    }
}

/// One `dump` command.
pub struct Dump {
    /// The dump ID.
    pub id: String,
    /// Group bits of the atoms dumped.
    pub group: u32,
    /// Write every this many steps.
    pub every: i64,
    /// File name as given (a `*` is replaced by the step).
    pub file: String,
    /// Columns and formats.
    pub layout: Layout,
    /// Last step written (a step is never written twice).
    pub last_written: Option<i64>,
    /// The open file for single-file dumps.
    pub handle: Option<DumpFile>,
    /// `dump_modify first yes`: write at the first run's setup even off the interval.
    pub first: bool,
    /// `dump_modify pad N`: the step in `*` file names padded with zeros to N digits.
    pub pad: usize,
    /// The dump style: what a snapshot holds and how it reaches files.
    pub style: Box<dyn crate::engine::dump_style::DumpStyle>,
}

/// The `restart` command's periodic restart files.
#[derive(Debug, Clone, PartialEq)]
pub struct RestartOutput {
    /// Write every this many steps.
    pub every: i64,
    /// One name with `*` for the step, or two names written in turn.
    pub files: Vec<String>,
    /// Which of two files comes next.
    pub toggle: usize,
    /// Last step written.
    pub last: Option<i64>,
}

/// The open file of a single-file dump.
pub enum DumpFile {
    /// Plain text.
    Plain(std::io::BufWriter<std::fs::File>),
    /// One gzip stream for the whole run, sync-flushed after every snapshot (readable so
    /// far at any time; finished when the dump is closed).
    Gzip(flate2::write::GzEncoder<std::io::BufWriter<std::fs::File>>),
}

impl std::io::Write for DumpFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            DumpFile::Plain(f) => f.write(buf),
            DumpFile::Gzip(g) => g.write(buf),
        }
    }
    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            DumpFile::Plain(f) => f.flush(),
            DumpFile::Gzip(g) => g.flush(),
        }
    }
}

/// When the stress module of `mesh/surface/stress` acts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum StressPhase {
    /// A run's setup, before its force evaluation.
    Setup,
    /// Before a step's forces.
    PreForce,
    /// After a step's final integration.
    EndOfStep,
}

/// Everything the engine simulates.
pub struct Simulation {
    /// State of the commands added for researchers' decks (issue 15).
    pub extras: crate::engine::extras::Extras,
    /// The `processors` settings and the MPI ranks of the run.
    pub procs: crate::engine::procmap::Processors,
    /// The cuts a `balance` (or `fix balance`) left and the last run's cost per rank.
    pub balance: crate::engine::decomp::balance::Kept,
    /// An insertion fix has been defined (a check run cannot know the atoms it adds).
    pub inserts_atoms: bool,
    /// `restart N ROOT` and `restart N FILE1 FILE2` (both may be active).
    pub restart_output: [Option<RestartOutput>; 2],
    /// Pair contact history from `read_restart`, applied at the next neighbour build.
    pub pending_history: Option<crate::engine::restart_state::PendingHistory>,
    /// Particles removed between runs since the last list build: how LIGGGHTS's partner
    /// arrays will read the old list at the next build.
    pub(crate) removal: Option<crate::engine::removal_history::Removal>,
    /// The energy guard's last look: (step, kinetic energy).
    pub energy_watch: Option<(i64, f64)>,
    /// What the guards have seen in this run that does not stop it (warned once, summed up
    /// at the run's end).
    pub(crate) guard_notes: GuardNotes,
    /// The time-step margin said last (a run says it again only when it changed).
    pub margin_said: Option<String>,
    /// A dry run's time-step margins, one per `run` where it changed (`regolith check`
    /// prints them).
    pub margin_notes: Vec<String>,
    /// A run has been set up before (`run ... pre no` only skips setup after the first).
    pub has_run: bool,
    /// `read_restart` read fix states that the next run's setup consumes (LIGGGHTS's
    /// fix_restart_in_progress: some computes may still be defined at a step > 0).
    pub restart_in_progress: bool,
    /// Fix states of the restart file read last, held (as LIGGGHTS holds them) until the
    /// first run: a fix defined meanwhile with a stored ID and style takes its state.
    pub restart_fixes: Vec<crate::io::restart::GlobalFix>,
    /// (ID, style) of the per-atom fix blocks of that restart file.
    pub restart_peratom: Vec<(String, String)>,
    /// Mesh contact history of that restart file: tracker fix ID (`tracker_<mesh>`) to
    /// the history width and, per atom ID, its (triangle id, history) contacts.
    pub restart_mesh_history: std::collections::HashMap<
        String,
        (
            usize,
            std::collections::HashMap<i64, crate::engine::mesh_wall::MeshContacts>,
        ),
    >,
    /// Start positions stored by `fix move` fixes in that restart file: fix ID to the
    /// unwrapped start position (length) of each atom ID.
    pub restart_move_origins:
        std::collections::HashMap<String, std::collections::HashMap<i64, [f64; 3]>>,
    /// An insert/stream fix has created the per-atom release data (LIGGGHTS's
    /// `release_fix_insert_stream`), which restart files then carry.
    pub stream_release: bool,
    /// A moving mesh's nodes went more than half the skin since its last refresh: the
    /// neighbour lists are rebuilt at this step (LIGGGHTS's FixMesh next_reneighbor).
    pub mesh_rebuild_at: Option<i64>,
    /// An insertion fix was due at this step: LIGGGHTS rebuilds the neighbour lists (and
    /// sorts the atoms when due) at every insertion step, also when nothing was inserted.
    pub insert_rebuild_at: Option<i64>,
    /// The particles.
    pub particles: Particles,
    /// The box.
    pub domain: Domain,
    /// Regions.
    pub regions: Regions,
    /// Group names; the index is the group's bit (0 = `all`).
    pub groups: Vec<String>,
    /// Number of atom types (`create_box N`).
    pub ntypes: u32,
    /// The lattice: spacing (length) and basis points in lattice units.
    pub lattice: Option<(f64, Vec<[f64; 3]>)>,
    /// `lattice ... origin x y z`: the lattice's shift in lattice units (0 <= x < 1).
    pub lattice_origin: [f64; 3],
    /// `lattice custom`: its primitive vectors and spacings (None for the cubic styles).
    pub lattice_cell: Option<crate::engine::lattice::Cell>,
    /// Current step.
    pub step: i64,
    /// Time-step size (time units).
    pub dt: f64,
    /// Elapsed time accumulated up to step `atime_step` (LIGGGHTS's atime/atimestep).
    pub atime: f64,
    /// The step at which `atime` was last brought up to date.
    pub atime_step: i64,
    /// Neighbour settings.
    pub neighbor: NeighborSettings,
    /// The current list and the history of its pairs.
    pub list: NeighborList,
    /// Contact history of the listed pairs (`history_width` doubles per pair).
    pub history: Vec<f64>,
    /// Contact history of the list's mirrors (`history_width` doubles per mirror).
    pub mirror_history: Vec<f64>,
    pub(crate) list_ids: Vec<i64>,
    pub(crate) ago: u64,
    box_at_build: ([f64; 3], [f64; 3]),
    /// The pair interaction, built at each run from the selection and materials.
    pub pair: Option<Box<dyn PairInteraction>>,
    /// The contact models `pair_style gran` selected.
    pub pair_selection: Option<crate::engine::granular::Selection>,
    /// `pair_coeff` has set every I,I type pair.
    pub pair_coeff_set: bool,
    /// The pair forces are computed (false after `pair_modify compute no`).
    pub pair_compute: bool,
    /// Atom types whose I,I pair `pair_coeff` has set (index type - 1; LIGGGHTS's diagonal
    /// setflag, which its run init requires for every type).
    pub pair_coeff_types: Vec<bool>,
    /// `soft_particles yes` / `hard_particles yes`.
    pub soft_hard: (bool, bool),
    /// `communicate ... vel yes` (LIGGGHTS's pair gran requires it).
    pub comm_vel: bool,
    /// `newton` for pairs (on by default, as in LIGGGHTS): a pair style with contact history
    /// requires it off.
    pub newton_pair: bool,
    /// `-seedtolerant`: random seeds need not be primes above 10000.
    pub seed_tolerant: bool,
    /// regolith extension `-zero_restitution`: restitution may go down to 0.
    pub zero_restitution: bool,
    /// Fixes in definition order.
    pub fixes: Vec<Fix>,
    /// LIGGGHTS's fix list in its order: the deck's fixes and those LIGGGHTS creates itself
    /// (what `modify_timing` reports).
    pub modify_list: crate::engine::fix_timing::ModifyList,
    /// Computes in definition order.
    pub computes: Vec<crate::engine::computes::Compute>,
    /// Per-particle pair virial of the last force evaluation (xx yy zz xy xz yz, force
    /// length); empty unless a `compute stress/atom` needs it.
    pub virial: Vec<[f64; 6]>,
    /// The step whose force evaluation tallied `virial` (None: not tallied since the last).
    pub virial_step: Option<i64>,
    /// Velocities and angular velocities at the last force evaluation (kept only while a
    /// `compute pair/gran/local` exists).
    pub force_time_state: (Vec<[f64; 3]>, Vec<[f64; 3]>),
    /// When the time-stepping loop of the current run started (None during setup).
    pub loop_clock: Option<std::time::Instant>,
    /// Told of the run's progress every few steps (the terminal status line), if any.
    pub observer: Option<Box<dyn crate::progress::StepObserver>>,
    /// Thermo output settings.
    pub thermo: Thermo,
    /// Dumps.
    pub dumps: Vec<Dump>,
    /// First and last step of the run in progress (as `ramp()` sees them).
    pub run_bounds: Option<(i64, i64)>,
    /// `run ... start N stop M`: override the bounds `ramp()` uses.
    pub ramp_bounds: (Option<i64>, Option<i64>),
    /// `dimension 2|3`: 2 for LIGGGHTS's planar runs (discs in the xy plane).
    pub dimension: u32,
    /// `atom_modify sort N binsize`: reorder particles spatially every N steps (0: never).
    pub sort_every: i64,
    /// Sort bin size (length; 0: half the neighbour cutoff).
    pub sort_binsize: f64,
    /// The next step at which particles are sorted.
    next_sort: i64,
    /// `units si` or `cgs` (only the material limits and defaults differ).
    pub units: crate::engine::contact::UnitStyle,
    /// Particles lost through fixed faces are dropped silently (LIGGGHTS's default, `thermo_modify lost ignore`).
    pub lost_ignore: bool,
    /// Atom count at the last check (for the lost-atoms error).
    pub natoms_expected: usize,
    /// Engine path (exact or fast) and threads.
    pub accel: crate::engine::accel::Accel,
    /// Timers and counters of the run in progress (LIGGGHTS's end-of-run statistics).
    pub(crate) stats: RunStats,
    /// How the pair pass adds contributions (set at each list build).
    pub(crate) sum_order: crate::engine::neighbor::SumOrder,
    /// The ranks of a run on more than one MPI rank (None: one process).
    pub comm: Option<crate::util::comm::RankComm>,
}

impl Default for Simulation {
    fn default() -> Self {
        Simulation {
            extras: Default::default(),
            procs: Default::default(),
            balance: Default::default(),
            inserts_atoms: false,
            restart_output: [None, None],
            pending_history: None,
            removal: None,
            restart_in_progress: false,
            restart_fixes: Vec::new(),
            restart_peratom: Vec::new(),
            restart_move_origins: std::collections::HashMap::new(),
            restart_mesh_history: std::collections::HashMap::new(),
            stream_release: false,
            mesh_rebuild_at: None,
            insert_rebuild_at: None,
            energy_watch: None,
            guard_notes: GuardNotes::default(),
            margin_said: None,
            margin_notes: Vec::new(),
            has_run: false,
            modify_list: Default::default(),
            particles: Particles::default(),
            domain: Domain::default(),
            regions: Regions::default(),
            groups: vec!["all".to_string()],
            ntypes: 0,
            lattice: None,
            lattice_origin: [0.0; 3],
            lattice_cell: None,
            step: 0,
            dt: 0.001,
            atime: 0.0,
            atime_step: 0,
            neighbor: NeighborSettings::default(),
            list: NeighborList::default(),
            history: Vec::new(),
            mirror_history: Vec::new(),
            list_ids: Vec::new(),
            ago: 0,
            box_at_build: ([0.0; 3], [0.0; 3]),
            pair: None,
            pair_selection: None,
            pair_coeff_set: false,
            pair_compute: true,
            pair_coeff_types: Vec::new(),
            soft_hard: (false, false),
            comm_vel: false,
            newton_pair: true,
            seed_tolerant: false,
            zero_restitution: false,
            fixes: Vec::new(),
            computes: Vec::new(),
            thermo: Thermo::default(),
            dumps: Vec::new(),
            virial: Vec::new(),
            virial_step: None,
            loop_clock: None,
            observer: None,
            force_time_state: (Vec::new(), Vec::new()),
            run_bounds: None,
            ramp_bounds: (None, None),
            lost_ignore: true,
            units: crate::engine::contact::UnitStyle::Si,
            sort_every: 1000,
            dimension: 3,
            sort_binsize: 0.0,
            next_sort: 0,
            natoms_expected: 0,
            accel: crate::engine::accel::Accel::default(),
            sum_order: Default::default(),
            comm: None,
            stats: RunStats::default(),
        }
    }
}

/// Timers (s) and counters of one run, printed after it as LIGGGHTS prints them.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct RunStats {
    /// Pair forces.
    pub pair: f64,
    /// Neighbour-list builds.
    pub neigh: f64,
    /// Periodic wrapping, shrink-wrapping and lost atoms at rebuilds (LIGGGHTS's exchange).
    pub comm: f64,
    /// Thermo, dumps and restart files.
    pub output: f64,
    /// Neighbour-list builds of this run.
    pub builds: u64,
    /// Dangerous builds of this run.
    pub dangerous: u64,
}

/// The first index below `n` where `test` holds, searched on the engine's threads when there
/// are enough particles (the same answer either way).
fn first_where(n: usize, test: impl Fn(usize) -> bool + Sync) -> Option<usize> {
    first_where_in(n, 1, test)
}

/// [`first_where`] over `n` blocks of `per_block` particles each (the thread decision and
/// the grain count particles, not blocks).
fn first_where_in(
    n: usize,
    per_block: usize,
    test: impl Fn(usize) -> bool + Sync,
) -> Option<usize> {
    let parallel = crate::engine::integrate::parallel(n * per_block);
    crate::util::team::first_where(n, 1024usize.div_ceil(per_block), parallel, test)
}

/// Time `f`, adding the seconds to `acc`.
#[inline]
fn timed<R>(acc: &mut f64, f: impl FnOnce() -> R) -> R {
    let t = std::time::Instant::now();
    let r = f();
    *acc += t.elapsed().as_secs_f64();
    r
}

/// Where the time loop writes screen/log text.
pub type Sink<'a> = &'a mut dyn FnMut(&str);

impl Simulation {
    /// Does anything read the per-atom pair virial after the forces of this step of a run
    /// ending at `last`? As LIGGGHTS, it is tallied only then: thermo and dump steps, the
    /// run's last step, and every step while a fix that evaluates variables is defined.
    fn virial_wanted(&self, last: i64) -> bool {
        let step = self.step;
        self.thermo.due(step, last)
            || self
                .dumps
                .iter()
                .any(|d| d.every > 0 && step % d.every == 0)
            || self.fixes.iter().any(|f| f.kind.may_read_computes())
            || self
                .fixes
                .iter()
                .any(|f| matches!(&f.kind, FixKind::Style(s) if s.wants_virial(step)))
    }

    /// Zero forces and torques and evaluate the pair style, walls and forcing fixes;
    /// `want_virial`: tally the per-atom pair virial if a `compute stress/atom` uses it.
    fn compute_forces(
        &mut self,
        update: bool,
        want_virial: bool,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.reset_clump_forces();
        let p = &mut self.particles;
        if self.pair.is_none() || !self.pair_compute {
            // a pair style sets the forces itself (on the fast path, block by block)
            p.clear_forces();
        }
        let tally = want_virial && self.computes.iter().any(|c| c.style().reads_virial());
        self.virial.clear();
        self.virial_step = tally.then_some(self.step);
        if tally {
            self.virial.resize(p.len(), [0.0; 6]);
        }
        self.multicontact_walls_to_pair(update);
        let p = &mut self.particles;
        if let Some(pair) = self.pair.as_mut().filter(|_| self.pair_compute) {
            let virial = if tally {
                Some(&mut self.virial[..])
            } else {
                None
            };
            let (pairs, history, dt) = (&self.list.pairs, &mut self.history, self.dt);
            let order = &self.sum_order;
            let width = pair.history_width();
            self.mirror_history
                .resize(self.list.mirrors.len() * width, 0.0);
            let mirrored = self
                .list
                .mirrored
                .then_some(crate::engine::neighbor::Mirrored {
                    mirrors: &self.list.mirrors,
                    history: &mut self.mirror_history,
                });
            let started = std::time::Instant::now();
            self.accel.install(|| {
                pair.compute(p, pairs, history, dt, update, virial, order, mirrored);
            });
            if self.loop_clock.is_some() {
                self.stats.pair += started.elapsed().as_secs_f64();
            }
        }
        self.multicontact_walls_back(update);
        if self
            .computes
            .iter()
            .any(|c| c.style().reads_pair_contacts())
        {
            self.force_time_state = (self.particles.v.clone(), self.particles.omega.clone());
        }
        self.resolve_force_fixes(vars)?;
        let list = (self.list.builds, self.neighbor.skin);
        // LIGGGHTS's mesh lists use the full skin when a mesh moves or the box can change
        // (a moving mesh's own lists use the full skin as well)
        let moving_skin = self.box_changes();
        fixes::post_force(
            &mut self.fixes,
            &mut self.particles,
            (self.step, &self.domain),
            self.dt,
            update,
            list,
            moving_skin,
        );
        if update {
            self.conduct_heat();
        }
        Ok(())
    }

    fn stats_loop_time(&self, started: std::time::Instant) -> f64 {
        started.elapsed().as_secs_f64()
    }

    /// LIGGGHTS's end-of-run statistics: the time split, per-process counts (one process:
    /// regolith has no ghost atoms, periodic images are handled in the pair list) and the
    /// neighbour-list figures; plus the pairs in contact at the last step.
    fn run_statistics(&self, loop_time: f64) -> String {
        use crate::util::format::g;
        let t = &self.stats;
        let pct = |x: f64| {
            if loop_time > 0.0 {
                100.0 * x / loop_time
            } else {
                0.0
            }
        };
        // with modify_timing, the fixes' time is its own line and leaves `Other`
        let timing = self.extras.modify_timing;
        let times = |id: &str| {
            self.fixes
                .iter()
                .find(|f| f.id == id)
                .map_or(0.0, |f| f.clock.seconds)
        };
        let modify = if timing > 0 {
            self.modify_list.total(&times)
        } else {
            0.0
        };
        let other = (loop_time - t.pair - t.neigh - t.comm - t.output - modify).max(0.0);
        let mut s = String::new();
        let mut lines = vec![
            ("Pair ", t.pair),
            ("Neigh", t.neigh),
            ("Comm ", t.comm),
            ("Outpt", t.output),
        ];
        if timing > 0 {
            lines.push(("Modfy", modify));
        }
        lines.push(("Other", other));
        for (name, v) in lines {
            s.push_str(&format!("{name} time (%) = {} ({})\n", g(v), g(pct(v))));
            if name == "Modfy" && timing > 1 {
                s.push_str(&format!(
                    "  Modify   time [0] (%) = {} ({})\n",
                    g(v),
                    g(pct(v))
                ));
            }
        }
        if timing > 0 {
            s.push_str(&self.modify_list.report(&times, loop_time, timing > 1));
        }
        let n = self.particles.len();
        let neighs = self.list.pairs.len() + self.list.mirrors.len();
        let hist = "Histogram: 1 0 0 0 0 0 0 0 0 0\n";
        s.push_str(&format!("\nNlocal:    {n} ave {n} max {n} min\n{hist}"));
        s.push_str(&format!("Nghost:    0 ave 0 max 0 min\n{hist}"));
        s.push_str(&format!(
            "Neighs:    {neighs} ave {neighs} max {neighs} min\n{hist}\n"
        ));
        s.push_str(&format!("Total # of neighbors = {neighs}\n"));
        let ave = if n > 0 { neighs as f64 / n as f64 } else { 0.0 };
        s.push_str(&format!("Ave neighs/atom = {}\n", g(ave)));
        s.push_str(&format!("Neighbor list builds = {}\n", t.builds));
        s.push_str(&format!("Dangerous builds = {}\n", t.dangerous));
        if let Some(pair) = self.pair.as_ref() {
            s.push_str(&format!(
                "Contacts (touching pairs at the last step) = {}\n",
                pair.contact_count()
            ));
        }
        s.push('\n');
        s
    }

    /// `reset_timestep N`: bring the elapsed time up to date, then jump to step N.
    pub fn reset_timestep(&mut self, n: i64) {
        // insertion fixes keep their schedule's phase; insert/stream rewrites every atom's
        // release data (LIGGGHTS's FixInsert::reset_timestep and reset_releasedata)
        let old = self.step;
        let mut v_normal = None;
        for f in &mut self.fixes {
            if let Some(ins) = f.kind.insert_pack_mut() {
                if let Some(next) = &mut ins.next {
                    *next += n - old;
                }
            }
            if let Some(sf) = f.kind.stream_mut() {
                match &mut sf.state {
                    Some(st) => {
                        if let Some(next) = &mut st.next {
                            *next += n - old;
                        }
                    }
                    None => sf.start += n - old,
                }
                v_normal = Some(sf.state.as_ref().map_or([0.0; 3], |s| s.v_normal));
            }
        }
        if let Some(v_normal) = v_normal {
            if self.stream_release {
                self.reset_release_data(n, old, v_normal);
            }
        }
        self.atime += (n - self.atime_step) as f64 * self.dt;
        if self.atime < 0.0 {
            self.atime = 0.0;
        }
        self.atime_step = n;
        self.step = n;
        for d in &mut self.dumps {
            d.last_written = None;
        }
        // the integrating stream, once set up, carries what the rewritten data says
        if let Some(ki) = self.stream_integrator() {
            let pending = self.releases_pending(self.fixes[ki].group);
            if let Some(sf) = self.fixes[ki].kind.stream_mut() {
                if let Some(st) = sf.state.as_mut() {
                    st.moving = pending;
                }
            }
        }
    }
}

#[cfg(test)]
mod guard_tests {
    use super::energy_runaway;

    #[test]
    fn energy_runaway_needs_growth_and_speed() {
        // a piston kick: energy up 1e9-fold, but particles move 1 % of a radius per step
        assert!(!energy_runaway(1e-12, 1e-3, 0.01));
        // fast but steady
        assert!(!energy_runaway(1.0, 2.0, 1.5));
        // a driven bed at a large time step: a fifth of a radius per step is no runaway
        assert!(!energy_runaway(1e-6, 1.0, 0.2));
        // runaway
        assert!(energy_runaway(1e-6, 1.0, 1.2));
        // from rest nothing is compared
        assert!(!energy_runaway(0.0, 1.0, 0.9));
    }
}
