//! The simulation state and the time loop: LIGGGHTS's Verlet order of operations
//! (setup force evaluation at every `run`, initial integrate, neighbour decision, force
//! clear, pair forces, post-force fixes, final integrate, output).

use crate::engine::domain::Domain;
pub use crate::engine::fixes::FixKind;
use crate::engine::fixes::{self, Fix};
use crate::engine::neighbor::{carry_history, NeighborList, Pair};
use crate::engine::particles::Particles;
use crate::engine::region::Regions;
use crate::engine::thermo::Thermo;
use crate::io::dump::Layout;

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
    /// Add pair forces and torques to `p.f`/`p.torque` for the listed pairs.
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
    fn equal(&mut self, sim: &Simulation, name: &str) -> Result<f64, String>;
    /// The values of atom-style variable `name`, one per particle in particle order.
    fn atom(&mut self, sim: &Simulation, name: &str) -> Result<Vec<f64>, String>;
    /// `text` with its `$x`, `${name}` and `$(formula)` references replaced.
    fn substitute(&mut self, sim: &Simulation, text: &str) -> Result<String, String> {
        let _ = sim;
        if text.contains('$') {
            Err(format!("cannot substitute variables in '{text}' here"))
        } else {
            Ok(text.to_string())
        }
    }
}

/// No variables (unit tests and tools that run without a deck).
pub struct NoVariables;

impl VariableSource for NoVariables {
    fn equal(&mut self, _: &Simulation, name: &str) -> Result<f64, String> {
        Err(format!("Variable name {name} does not exist"))
    }
    fn atom(&mut self, _: &Simulation, name: &str) -> Result<Vec<f64>, String> {
        Err(format!("Variable name {name} does not exist"))
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
    /// `dump local`: (compute ID, 0-based column) per column instead of the layout's
    /// per-atom columns.
    pub local: Option<Vec<(String, usize)>>,
    /// Last step written (a step is never written twice).
    pub last_written: Option<i64>,
    /// The open file for single-file dumps.
    pub handle: Option<DumpFile>,
    /// `dump_modify first yes`: write at the first run's setup even off the interval.
    pub first: bool,
    /// `dump_modify pad N`: the step in `*` file names padded with zeros to N digits.
    pub pad: usize,
    /// The dump style.
    pub style: DumpStyle,
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

/// How a dump writes its snapshots.
#[derive(Debug, Clone, PartialEq)]
pub enum DumpStyle {
    /// `custom` (and `atom`, whose columns are fixed): `ITEM:` text; `local` dumps too.
    Text,
    /// `xyz`: count, comment line, then `element x y z`; element names per type
    /// (`dump_modify element`, else the type number).
    Xyz(Vec<String>),
    /// `custom/vtk`: legacy VTK polydata with these fields, plus a bounding-box file.
    Vtk(Vec<crate::io::vtk::Field>),
    /// `mesh/stl`: the triangles of these mesh fixes (all when empty) as ASCII STL.
    MeshStl(Vec<String>),
    /// `mesh/vtk` (`mesh/gran/VTK`): meshes with per-triangle data as legacy VTK.
    MeshVtk(crate::io::mesh_vtk::MeshDumpSpec),
    /// `local/gran/vtk`: the contacts of this local compute (ID) as VTK lines.
    LocalGranVtk(String),
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
    /// An insertion fix has been defined (a check run cannot know the atoms it adds).
    pub inserts_atoms: bool,
    /// `restart N ROOT` and `restart N FILE1 FILE2` (both may be active).
    pub restart_output: [Option<RestartOutput>; 2],
    /// Pair contact history from `read_restart`, applied at the next neighbour build.
    pub pending_history: Option<crate::engine::restart_state::PendingHistory>,
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
    /// `pair_coeff * *` was given.
    pub pair_coeff_set: bool,
    /// `soft_particles yes` / `hard_particles yes`.
    pub soft_hard: (bool, bool),
    /// `communicate ... vel yes` (LIGGGHTS's pair gran requires it).
    pub comm_vel: bool,
    /// `-seedtolerant`: random seeds need not be primes above 10000.
    pub seed_tolerant: bool,
    /// regolith extension `-zero_restitution`: restitution may go down to 0.
    pub zero_restitution: bool,
    /// Fixes in definition order.
    pub fixes: Vec<Fix>,
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
}

impl Default for Simulation {
    fn default() -> Self {
        Simulation {
            extras: Default::default(),
            inserts_atoms: false,
            restart_output: [None, None],
            pending_history: None,
            restart_in_progress: false,
            restart_fixes: Vec::new(),
            restart_peratom: Vec::new(),
            restart_move_origins: std::collections::HashMap::new(),
            restart_mesh_history: std::collections::HashMap::new(),
            stream_release: false,
            mesh_rebuild_at: None,
            energy_watch: None,
            guard_notes: GuardNotes::default(),
            margin_said: None,
            margin_notes: Vec::new(),
            has_run: false,
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
            soft_hard: (false, false),
            comm_vel: false,
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
            sort_binsize: 0.0,
            next_sort: 0,
            natoms_expected: 0,
            accel: crate::engine::accel::Accel::default(),
            sum_order: Default::default(),
            stats: RunStats::default(),
        }
    }
}

/// LIGGGHTS's sort bins (`Atom::sort`): the bin of each position, bins of `binsize` fitted
/// to the box `lo`..`hi`, x fastest; None when there is nothing to sort by (no bin size, or
/// a single bin).
fn sort_bins(x: &[[f64; 3]], lo: [f64; 3], hi: [f64; 3], binsize: f64) -> Option<Vec<u32>> {
    if binsize <= 0.0 {
        return None;
    }
    let bininv = 1.0 / binsize;
    let mut nbin = [1usize; 3];
    let mut inv = [0.0; 3];
    for d in 0..3 {
        nbin[d] = (((hi[d] - lo[d]) * bininv) as i64).max(1) as usize;
        inv[d] = nbin[d] as f64 / (hi[d] - lo[d]);
    }
    // one bin: nothing to sort; more than an int counts: refused at the run's init
    let total = nbin.iter().map(|&n| n as f64).product::<f64>();
    if total <= 1.0 || total > i32::MAX as f64 {
        return None;
    }
    let bin_of = |x: &[f64; 3]| {
        let mut b = [0usize; 3];
        for d in 0..3 {
            let k = ((x[d] - lo[d]) * inv[d]) as i64;
            b[d] = k.clamp(0, nbin[d] as i64 - 1) as usize;
        }
        ((b[2] * nbin[1] + b[1]) * nbin[0] + b[0]) as u32
    };
    Some(x.iter().map(bin_of).collect())
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
    use rayon::prelude::*;
    if crate::engine::integrate::parallel(n * per_block) {
        (0..n)
            .into_par_iter()
            .with_min_len(1024usize.div_ceil(per_block))
            .find_first(|&i| test(i))
    } else {
        (0..n).find(|&i| test(i))
    }
}

/// Time `f`, adding the seconds to `acc`.
#[inline]
fn timed<R>(acc: &mut f64, f: impl FnOnce() -> R) -> R {
    let t = std::time::Instant::now();
    let r = f();
    *acc += t.elapsed().as_secs_f64();
    r
}

/// Overlap, as a fraction of the smaller radius, beyond which the guard warns (the run goes on,
/// as LIGGGHTS's does).
pub const MAX_OVERLAP: f64 = 0.5;

/// Where the time loop writes screen/log text.
pub type Sink<'a> = &'a mut dyn FnMut(&str);

/// How often the energy guard takes a new baseline (steps); every step is compared with it.
pub const ENERGY_WATCH_STEPS: i64 = 10;
/// Kinetic-energy growth against the baseline that, with particles jumping more than their
/// radius per step, means a runaway.
pub const ENERGY_GROWTH: f64 = 1.0e4;
/// Radii per step the fastest particle must cover for an energy growth to count as a runaway.
pub const RUNAWAY_RADII_PER_STEP: f64 = 1.0;
// the cheap motion pass flags half a radius per step: the bounds must not be below it
const _: () = assert!(RUNAWAY_RADII_PER_STEP >= 0.5);

/// Energy `now` against `before` with the fastest particle covering `per_step` radii per
/// step: a runaway when the energy grew more than [`ENERGY_GROWTH`]-fold and
/// `per_step` exceeds [`RUNAWAY_RADII_PER_STEP`]. (A piston or an insertion raises the energy
/// by any factor, but its particles do not jump past their neighbours in one step.)
pub fn energy_runaway(before: f64, now: f64, per_step: f64) -> bool {
    before > 0.0 && now > ENERGY_GROWTH * before && per_step > RUNAWAY_RADII_PER_STEP
}

/// One kind of thing the guards warn about without stopping: its first occurrence, how many
/// steps showed it, and the worst case.
#[derive(Debug, Clone, Default)]
pub(crate) struct GuardNote {
    /// Steps at which it was seen.
    pub steps: u64,
    /// The worst value seen, with its step and atom IDs.
    pub worst: Option<(f64, i64, i64, i64)>,
}

impl GuardNote {
    /// Record `value` at `step` for atoms `a`, `b`; true the first time (warn then).
    fn record(&mut self, value: f64, step: i64, a: i64, b: i64) -> bool {
        self.steps += 1;
        if self.worst.is_none_or(|w| value > w.0) {
            self.worst = Some((value, step, a, b));
        }
        self.steps == 1
    }
}

/// The guards' notes of a run.
#[derive(Debug, Clone, Default)]
pub(crate) struct GuardNotes {
    /// Overlaps beyond [`MAX_OVERLAP`] of the smaller radius.
    pub overlap: GuardNote,
    /// Particles moving more than their radius in one step.
    pub jump: GuardNote,
}

/// Atoms named in a lost-atoms error (the rest are counted).
const LOST_NAMED: usize = 10;

/// LIGGGHTS's "Lost atoms: original N current M", followed by each lost atom's ID, position
/// and velocity at `step` (the first [`LOST_NAMED`] of them; LIGGGHTS only counts them).
fn lost_atoms_message(p: &Particles, lost: &[bool], remaining: usize, step: i64) -> String {
    // every digit: an atom just past a face must not print as on it
    let v3 = |a: &[f64; 3]| format!("({}, {}, {})", a[0], a[1], a[2]);
    let gone: Vec<usize> = (0..p.len()).filter(|&i| lost[i]).collect();
    let mut s = format!(
        "Lost atoms: original {} current {} (at step {step}, outside the box along a fixed face or without a finite position:",
        p.len(),
        remaining
    );
    for &i in gone.iter().take(LOST_NAMED) {
        s.push_str(&format!(
            " atom {} at x = {} with v = {};",
            p.id[i],
            v3(&p.x[i]),
            v3(&p.v[i])
        ));
    }
    if gone.len() > LOST_NAMED {
        s.push_str(&format!(" and {} more;", gone.len() - LOST_NAMED));
    }
    s.pop();
    s.push(')');
    s
}

/// A guard's warning: on standard error, so that the screen and log keep LIGGGHTS's lines
/// (a closed standard error is no reason to stop a run).
fn guard_say(text: &str) {
    use std::io::Write;
    let _ = std::io::stderr().lock().write_all(text.as_bytes());
}

impl Simulation {
    /// A cheap pass that is true whenever a motion guard could fire: a position, velocity or
    /// spin is not finite (their sum is then not finite; rarely it overflows), or a particle
    /// moves more than half its radius per step (the guards' bounds are one radius, and
    /// [`RUNAWAY_RADII_PER_STEP`] is not below it). Branch-free over blocks, no square roots.
    fn motion_flagged(&self) -> bool {
        let p = &self.particles;
        let dt = self.dt.abs();
        let dt2 = dt * dt;
        let n = p.len();
        let (x, v, w, radius) = (&p.x[..n], &p.v[..n], &p.omega[..n], &p.radius[..n]);
        let cheap = |x: &[f64; 3], v: &[f64; 3], w: &[f64; 3], r: f64| {
            let sum = x[0] + x[1] + x[2] + v[0] + v[1] + v[2] + w[0] + w[1] + w[2];
            let v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            !sum.is_finite() | ((r > 0.0) & (v2 * dt2 > 0.25 * r * r))
        };
        const BLOCK: usize = 256;
        let flagged = |b: usize| {
            let (lo, hi) = (b * BLOCK, ((b + 1) * BLOCK).min(n));
            let cols = x[lo..hi].iter().zip(&v[lo..hi]);
            let cols = cols.zip(w[lo..hi].iter().zip(&radius[lo..hi]));
            cols.fold(false, |hit, ((x, v), (w, &r))| hit | cheap(x, v, w, r))
        };
        first_where_in(p.len().div_ceil(BLOCK), BLOCK, flagged).is_some()
    }

    /// Kinetic energy and the fastest particle as (radii per step, index): one pass, on the
    /// engine's threads when there are enough particles.
    fn motion_scan(&self) -> (f64, f64, usize) {
        use rayon::prelude::*;
        let p = &self.particles;
        let dt = self.dt.abs();
        let one = |i: usize| {
            let v = p.v[i];
            let v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            let per_step = if p.radius[i] > 0.0 {
                v2.sqrt() * dt / p.radius[i]
            } else {
                0.0
            };
            (0.5 * p.mass[i] * v2, per_step, i)
        };
        let join = |a: (f64, f64, usize), b: (f64, f64, usize)| {
            let fastest = if b.1 > a.1 || (b.1 == a.1 && b.2 < a.2) {
                (b.1, b.2)
            } else {
                (a.1, a.2)
            };
            (a.0 + b.0, fastest.0, fastest.1)
        };
        if crate::engine::integrate::parallel(p.len()) {
            (0..p.len())
                .into_par_iter()
                .with_min_len(1024)
                .map(one)
                .reduce(|| (0.0, 0.0, usize::MAX), join)
        } else {
            (0..p.len()).map(one).fold((0.0, 0.0, usize::MAX), join)
        }
    }

    /// The blow-up guard on motion, run after each half-kick (before atoms are wrapped or
    /// lost): a position or velocity that is not finite, or a runaway of the kinetic energy
    /// (see [`energy_runaway`]), stops the run; a particle moving more than its radius in one
    /// step is warned about (once a run, on standard error) and the run goes on. `setup` takes the energy
    /// baseline.
    fn guard_motion(&mut self, setup: bool) -> Result<(), String> {
        let quiet = !setup
            && self.energy_watch.is_some()
            && self.step % ENERGY_WATCH_STEPS != 0
            && !self.motion_flagged();
        if quiet {
            // nothing non-finite, nobody near a radius per step: no check below can fire
            return Ok(());
        }
        let p = &self.particles;
        let finite = |i: usize| {
            p.x[i]
                .iter()
                .chain(&p.v[i])
                .chain(&p.omega[i])
                .all(|c| c.is_finite())
        };
        // the first offending particle in order, found on the engine's threads
        if let Some(i) = first_where(p.len(), |i| !finite(i)) {
            return Err(self.non_finite(i));
        }
        let (energy, per_step, fastest) = self.motion_scan();
        if !energy.is_finite() {
            // finite velocities whose squares overflow: a state no step can carry on from
            let p = &self.particles;
            let kinetic = |i: usize| {
                let v = p.v[i];
                0.5 * p.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
            };
            let i = (0..p.len())
                .find(|&i| !kinetic(i).is_finite())
                .or((fastest < p.len()).then_some(fastest))
                .unwrap_or(0);
            return Err(format!(
                "blow-up at step {}: the kinetic energy is not finite (bound: finite); atom {} has v = {:?} and mass {}, and 0.5 m |v|^2 = {}; {}",
                self.step,
                p.id[i],
                p.v[i],
                p.mass[i],
                kinetic(i),
                self.blow_up_cause(i)
            ));
        }
        if setup || self.energy_watch.is_none() {
            self.energy_watch = Some((self.step, energy));
            return Ok(());
        }
        let p = &self.particles;
        if let Some((step, e0)) = self.energy_watch {
            if energy_runaway(e0, energy, per_step) {
                return Err(format!(
                    "blow-up at step {}: kinetic energy grew {:.1e}-fold since step {} (bound: {:.0e}-fold \
                     while a particle moves more than {} radius per step) and atom {} moves {} radii per step; \
                     the time step is probably too large for the stiffness (check Young's modulus, or use fix check/timestep/gran)",
                    self.step,
                    energy / e0,
                    step,
                    ENERGY_GROWTH,
                    RUNAWAY_RADII_PER_STEP,
                    p.id[fastest],
                    crate::util::format::g(per_step)
                ));
            }
        }
        if self.step % ENERGY_WATCH_STEPS == 0 {
            self.energy_watch = Some((self.step, energy));
        }
        if per_step > 1.0 {
            let id = p.id[fastest];
            if self.guard_notes.jump.record(per_step, self.step, id, id) {
                guard_say(&format!(
                    "WARNING: step {}: atom {} moves {} radii in one time step (|v| dt > r, bound 1): \
                     contacts can be missed; the time step is probably too large for its speed. \
                     The run goes on (said once a run; counted at its end)\n",
                    self.step,
                    id,
                    crate::util::format::g(per_step)
                ));
            }
        }
        Ok(())
    }

    /// The blow-up guard on forces, run after each force evaluation: a force that is not
    /// finite stops the run; two particles overlapping by more than [`MAX_OVERLAP`] of the
    /// smaller radius are warned about (once a run, on standard error) and the run goes on.
    fn guard_forces(&mut self) -> Result<(), String> {
        let p = &self.particles;
        // a branch-free block scan first; the particle is looked for only when one is flagged
        const BLOCK: usize = 256;
        let flagged = |b: usize| {
            let block = &p.f[b * BLOCK..((b + 1) * BLOCK).min(p.len())];
            block.iter().fold(false, |hit, f| {
                hit | !f[0].is_finite() | !f[1].is_finite() | !f[2].is_finite()
            })
        };
        if first_where_in(p.len().div_ceil(BLOCK), BLOCK, flagged).is_some() {
            if let Some(i) = first_where(p.len(), |i| !p.f[i].iter().all(|c| c.is_finite())) {
                return Err(self.non_finite(i));
            }
        }
        if let Some((ratio, i, j)) = self.pair.as_ref().and_then(|m| m.worst_overlap()) {
            // a particle that insert/stream still carries feels no force; LIGGGHTS can
            // insert one overlapping a particle it had frozen (after reset_timestep)
            let carried = || {
                let (ti, tj) = (p.id[i as usize], p.id[j as usize]);
                self.fixes.iter().any(|f| match &f.kind {
                    FixKind::InsertStream(sf) => sf
                        .state
                        .as_ref()
                        .is_some_and(|s| s.moving.iter().any(|r| r.id == ti || r.id == tj)),
                    _ => false,
                })
            };
            if ratio > MAX_OVERLAP && !carried() {
                let cause = if self.step == self.atime_step {
                    "the particles were created (or read) overlapping"
                } else {
                    "the time step may be too large for the stiffness, or the particles are \
                     driven together harder than their stiffness holds"
                };
                let (a, b) = (p.id[i as usize], p.id[j as usize]);
                if self.guard_notes.overlap.record(ratio, self.step, a, b) {
                    guard_say(&format!(
                        "WARNING: step {}: atoms {a} and {b} overlap by {:.1} % of the smaller radius \
                         (more than {:.0} %); {cause}. The run goes on (said once a run; counted at its end)\n",
                        self.step,
                        ratio * 100.0,
                        MAX_OVERLAP * 100.0
                    ));
                }
            }
        }
        Ok(())
    }

    /// The time-step margin and the composed contact models (see [`crate::engine::margin`])
    /// when they differ from those said last; None when unchanged or when there is nothing
    /// to say.
    pub fn new_margin(&mut self) -> Option<String> {
        let m = self.timestep_margin() + &self.contact_models();
        if m.is_empty() || self.margin_said.as_deref() == Some(m.as_str()) {
            return None;
        }
        self.margin_said = Some(m.clone());
        Some(m)
    }

    /// At a run's end: how often the guards' warnings recurred, and the worst case.
    fn guard_summary(&mut self) {
        let notes = std::mem::take(&mut self.guard_notes);
        if let Some((v, step, a, b)) = notes.overlap.worst.filter(|_| notes.overlap.steps > 1) {
            guard_say(&format!(
                "WARNING: overlaps beyond {:.0} % of the smaller radius at {} steps of this run; the largest {:.1} % at step {step} (atoms {a} and {b})\n",
                MAX_OVERLAP * 100.0,
                notes.overlap.steps,
                v * 100.0
            ));
        }
        if let Some((v, step, a, _)) = notes.jump.worst.filter(|_| notes.jump.steps > 1) {
            guard_say(&format!(
                "WARNING: a particle moved more than its radius in one time step at {} steps of this run; the most {} radii at step {step} (atom {a})\n",
                notes.jump.steps,
                crate::util::format::g(v)
            ));
        }
    }

    fn non_finite(&self, i: usize) -> String {
        let p = &self.particles;
        format!(
            "blow-up at step {}: atom {} has a non-finite position, velocity, angular velocity or force (x = {:?}, v = {:?}, omega = {:?}, f = {:?}); {}",
            self.step,
            p.id[i],
            p.x[i],
            p.v[i],
            p.omega[i],
            p.f[i],
            self.blow_up_cause(i)
        )
    }

    /// The likeliest cause of atom `i`'s non-finite value, for the blow-up message.
    fn blow_up_cause(&self, i: usize) -> String {
        let p = &self.particles;
        let positive = |x: f64| x > 0.0;
        if !positive(p.radius[i]) || !positive(p.mass[i]) {
            return format!(
                "it has radius {} and mass {}: a particle needs a positive radius and mass",
                p.radius[i], p.mass[i]
            );
        }
        // two atoms at one point have no contact normal: their force is 0/0
        let twin = (0..p.len()).find(|&j| {
            j != i && {
                let d = [0, 1, 2].map(|k| p.x[i][k] - p.x[j][k]);
                d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= (1e-12 * p.radius[i]).powi(2)
            }
        });
        if let Some(j) = twin {
            return format!(
                "atoms {} and {} sit at the same position, so their contact has no direction (were they created on top of each other?)",
                p.id[i], p.id[j]
            );
        }
        let finite = |v: &[f64; 3]| v.iter().all(|c| c.is_finite());
        if finite(&p.x[i]) && finite(&p.v[i]) && finite(&p.omega[i]) {
            return "only the force on it is not finite: check the forces fixes add or set (an infinite value or variable?)".into();
        }
        if self.step == self.atime_step {
            // still the run's setup: nothing has been integrated yet
            return "the state the run started from already holds it (check how the atoms were created, read or set)".into();
        }
        "the time step is probably too large for the stiffness (check Young's modulus, or use fix check/timestep/gran)".into()
    }

    /// The `end_of_step` phase: fixes that check or report every N steps.
    fn end_of_step(&mut self, out: Sink<'_>, vars: &mut dyn VariableSource) -> Result<(), String> {
        self.move_streams();
        let (step, dt, skin) = (self.step, self.dt, self.neighbor.skin);
        for k in 0..self.fixes.len() {
            let fix = &mut self.fixes[k];
            match &mut fix.kind {
                FixKind::CheckTimestep(c) if step % c.every == 0 => {
                    for m in c.evaluate(&self.particles, fix.group, dt, skin) {
                        out(&format!("WARNING: {m}\n"));
                    }
                }
                FixKind::Momentum(m) if step % m.every == 0 => {
                    m.apply(&mut self.particles, fix.group, &self.domain);
                }
                FixKind::Tracer(t) if step % t.every == 0 => {
                    t.end_of_step(&mut self.particles, fix.group, &self.regions, step);
                }
                FixKind::AveTime(at) if at.next == step => {
                    let inputs = at.inputs.clone();
                    let values = inputs
                        .iter()
                        .map(|input| self.ave_input(input, vars))
                        .collect::<Result<Vec<f64>, String>>()?;
                    if let FixKind::AveTime(at) = &mut self.fixes[k].kind {
                        at.sample(step, &values)?;
                    }
                }
                FixKind::Print(pf) if step % pf.every == 0 => {
                    let text = pf.text.clone();
                    let line = vars.substitute(self, &text)?;
                    if let FixKind::Print(pf) = &mut self.fixes[k].kind {
                        pf.emit(&line, out)?;
                    }
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// One input value of `fix ave/time`.
    fn ave_input(
        &self,
        input: &fixes::AveInput,
        vars: &mut dyn VariableSource,
    ) -> Result<f64, String> {
        match input {
            fixes::AveInput::Compute(id, i) => self.compute_value(id, *i, vars),
            fixes::AveInput::Fix(id, i) => self.fix_value(id, *i),
            fixes::AveInput::Variable(name) => vars.equal(self, name),
        }
    }

    /// `fix ave/time` samples due at setup (LIGGGHTS runs end_of_step there too).
    fn setup_averages(&mut self, vars: &mut dyn VariableSource) -> Result<(), String> {
        let step = self.step;
        for k in 0..self.fixes.len() {
            let inputs = match &self.fixes[k].kind {
                FixKind::AveTime(at) if at.next == step => at.inputs.clone(),
                _ => continue,
            };
            let values = inputs
                .iter()
                .map(|input| self.ave_input(input, vars))
                .collect::<Result<Vec<f64>, String>>()?;
            if let FixKind::AveTime(at) = &mut self.fixes[k].kind {
                at.sample(step, &values)?;
            }
        }
        Ok(())
    }

    /// Value of `f_ID[i]` (1-based) for fixes with a global vector.
    pub fn fix_value(&self, id: &str, index: Option<usize>) -> Result<f64, String> {
        let fix = self
            .fixes
            .iter()
            .find(|f| f.id == id)
            .ok_or_else(|| format!("Could not find fix ID {id}"))?;
        if let Some(v) = self.heat_value(id, index) {
            return v;
        }
        match (&fix.kind, index) {
            (FixKind::CheckTimestep(c), Some(i @ 1..=3)) => Ok(c.values[i - 1]),
            (FixKind::Mesh(m), Some(i)) if m.stress.as_ref().and_then(|s| s.value(i)).is_some() => {
                Ok(m.stress.as_ref().and_then(|s| s.value(i)).unwrap_or(0.0))
            }
            (FixKind::AveTime(at), i) if at.value(i).is_some() => Ok(at.value(i).unwrap_or(0.0)),
            (FixKind::Massflow(m), Some(i)) if m.value(i).is_some() => {
                Ok(m.value(i).unwrap_or(0.0))
            }
            (FixKind::Buoyancy(b), Some(i @ 1..=3)) => Ok(b.total[i - 1]),
            (FixKind::Tracer(t), None) => Ok(t.scalar()),
            _ => Err(format!("fix {id} ({}) has no such value", fix.style)),
        }
    }

    /// Value of `c_ID` (index None) or `c_ID[i]`.
    pub fn compute_value(
        &self,
        id: &str,
        index: Option<usize>,
        vars: &mut dyn VariableSource,
    ) -> Result<f64, String> {
        let c = self
            .computes
            .iter()
            .find(|c| c.id == id)
            .ok_or_else(|| format!("Could not find thermo/variable compute ID {id}"))?;
        match index {
            None => c.scalar(self, vars),
            Some(i) => c.vector(i, self, vars),
        }
    }

    /// The per-atom values behind a dump column `c_ID` / `c_ID[N]` / `v_name`, and its
    /// column.
    fn dump_reference(
        &self,
        name: &str,
        vars: &mut dyn VariableSource,
    ) -> Result<(crate::engine::computes::PerAtom, usize), String> {
        if let Some(var) = name.strip_prefix("v_") {
            let values = vars.atom(self, var)?;
            return Ok((crate::engine::computes::PerAtom { columns: 1, values }, 0));
        }
        if let Some(body) = name.strip_prefix("f_") {
            let (id, index) = crate::util::numbers::split_reference(body)
                .ok_or_else(|| format!("Invalid attribute {name} in dump custom command"))?;
            return crate::engine::fix_columns::per_atom(self, id, index);
        }
        let body = name
            .strip_prefix("c_")
            .ok_or_else(|| format!("Invalid attribute {name} in dump custom command"))?;
        let (id, index) = crate::util::numbers::split_reference(body)
            .ok_or_else(|| format!("Invalid attribute {name} in dump custom command"))?;
        let c = self
            .computes
            .iter()
            .find(|c| c.id == id)
            .ok_or_else(|| format!("Could not find dump custom compute ID {id}"))?;
        let col = crate::engine::computes::column_of(c, index)?;
        Ok((c.per_atom(self, vars)?, col))
    }

    /// Bit mask of group `name`.
    pub fn group_bit(&self, name: &str) -> Option<u32> {
        self.groups
            .iter()
            .position(|g| g == name)
            .map(|i| 1u32 << i)
    }

    /// Simulated time at the current step (time units).
    pub fn time(&self) -> f64 {
        self.atime + (self.step - self.atime_step) as f64 * self.dt
    }

    /// LIGGGHTS's spatial sort of the particle arrays (`Atom::sort`): bins of half the
    /// neighbour cutoff over the box, x fastest, particles in their previous order inside
    /// a bin. Without a pair style LIGGGHTS refuses to sort (bin size 0); regolith then
    /// keeps the order.
    fn sort_particles(&mut self) {
        self.next_sort = (self.step / self.sort_every) * self.sort_every + self.sort_every;
        let binsize = if self.sort_binsize > 0.0 {
            self.sort_binsize
        } else {
            0.5 * self.neighbor_cutoff()
        };
        let (lo, hi) = (self.domain.lo, self.domain.hi);
        let bins = move |x: &[[f64; 3]]| sort_bins(x, lo, hi, binsize);
        if self.accel.fast {
            // the fast path keeps its own order and records the exact one
            self.sort_order_record(bins);
            return;
        }
        let Some(bins) = bins(&self.particles.x) else {
            return;
        };
        let mut order: Vec<usize> = (0..self.particles.len()).collect();
        order.sort_by_key(|&i| bins[i]);
        if order.iter().enumerate().any(|(k, &i)| k != i) {
            self.particles.permute(&order);
        }
    }

    /// LIGGGHTS's largest neighbour cutoff: for each type pair the sum of the largest radii
    /// (frozen particles only with moving ones), plus the skin; 0 without a pair style.
    pub fn neighbor_cutoff(&self) -> f64 {
        if self.pair_selection.is_none() {
            return 0.0;
        }
        let n = self.ntypes as usize + 1;
        let frozen = fixes::frozen_groups(&self.fixes);
        let (mut dynamic, mut still) = (vec![0.0f64; n], vec![0.0f64; n]);
        let p = &self.particles;
        for i in 0..p.len() {
            let t = (p.kind[i] as usize).min(n - 1);
            if p.mask[i] & frozen != 0 {
                still[t] = still[t].max(p.radius[i]);
            } else {
                dynamic[t] = dynamic[t].max(p.radius[i]);
            }
        }
        let mut cut: f64 = 0.0;
        for i in 1..n {
            for j in 1..n {
                let c = (dynamic[i] + dynamic[j])
                    .max(still[i] + dynamic[j])
                    .max(dynamic[i] + still[j]);
                cut = cut.max(c);
            }
        }
        cut + self.neighbor.skin
    }

    /// Wrap periodic coordinates, drop particles outside fixed faces, shrink-wrap the box.
    /// Wrap periodic positions, shrink-wrap the box around the atoms, drop lost atoms (LIGGGHTS's
    /// pbc, reset_box and exchange, as at a re-neighbouring or before writing a file).
    pub fn pbc_and_box(&mut self) -> Result<(), String> {
        let p = &mut self.particles;
        // a periodic coordinate that is not finite cannot be wrapped: the atom is lost
        let mut unplaced = Vec::new();
        for i in 0..p.len() {
            if !self.domain.remap(&mut p.x[i], &mut p.image[i]) {
                unplaced.push(i);
            }
        }
        // as LIGGGHTS: the box shrink-wraps around every atom first (reset_box), then atoms
        // outside a fixed face are lost (exchange)
        // around every mesh node too (LIGGGHTS's FixMesh::box_extent)
        let meshes = self.fixes.iter().filter_map(|f| match &f.kind {
            FixKind::Mesh(m) => Some(m),
            _ => None,
        });
        let nodes = meshes.flat_map(|m| m.triangles().iter().flatten());
        if self.domain.shrinks() {
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            let mut any = false;
            // an atom without a finite position is lost below; it does not stretch the box
            let placed = p.x.iter().filter(|x| x.iter().all(|c| c.is_finite()));
            for x in placed.chain(nodes) {
                any = true;
                for d in 0..3 {
                    lo[d] = lo[d].min(x[d]);
                    hi[d] = hi[d].max(x[d]);
                }
            }
            if any {
                self.domain.shrink_wrap(lo, hi)?;
            }
        }
        let mut lost: Vec<bool> = p.x.iter().map(|x| !self.domain.contains(*x)).collect();
        for i in unplaced {
            lost[i] = true;
        }
        if lost.iter().any(|&l| l) {
            if !self.lost_ignore {
                let remaining = lost.iter().filter(|&&l| !l).count();
                return Err(lost_atoms_message(p, &lost, remaining, self.step));
            }
            p.retain_by(&lost);
        }
        self.drop_broken_clumps();
        Ok(())
    }

    fn build_neighbors(&mut self) {
        let old_pairs = std::mem::take(&mut self.list.pairs);
        let old_mirrors = std::mem::take(&mut self.list.mirrors);
        let old_mirrored = self.list.mirrored;
        let old_mirror_history = std::mem::take(&mut self.mirror_history);
        let width = self.pair.as_ref().map_or(0, |p| p.history_width());
        if !(self.accel.fast && self.build_list_fast()) {
            let order = crate::engine::neighbor::BinOrder::sized(
                self.domain.lo,
                self.domain.hi,
                self.neighbor.cutneighmax,
                self.extras.neigh_binsize,
            );
            // LIGGGHTS's stencil walk; the general search where particles have grown
            // (pairs beyond the stencil are counted) or the box is too short
            let walked = !self.radii_vary()
                && std::env::var_os("REGOLITH_SORTED_LIST").is_none()
                && self.list.build_stencil(
                    &self.particles.x,
                    &self.particles.radius,
                    self.neighbor.skin,
                    &self.domain,
                    &order,
                );
            if !walked {
                self.list.build(
                    &self.particles.x,
                    &self.particles.radius,
                    self.neighbor.skin,
                    &self.domain,
                    Some(&order),
                );
            }
        }
        self.exclude_clump_pairs();
        let n = &self.neighbor;
        if !n.exclude_types.is_empty() || !n.exclude_groups.is_empty() {
            let p = &self.particles;
            self.list.retain(|pair| {
                let (i, j) = (pair.i as usize, pair.j as usize);
                let (ti, tj) = (p.kind[i], p.kind[j]);
                let (mi, mj) = (p.mask[i], p.mask[j]);
                !n.exclude_types
                    .iter()
                    .any(|&(a, b)| (ti == a && tj == b) || (ti == b && tj == a))
                    && !n
                        .exclude_groups
                        .iter()
                        .any(|&(a, b)| (mi & a != 0 && mj & b != 0) || (mi & b != 0 && mj & a != 0))
            });
        }
        let flips = self.pair.as_ref().map_or(Vec::new(), |p| p.history_flips());
        // a pair style redefined with another history layout starts its contacts afresh
        // (LIGGGHTS replaces its contact-history fix with the pair style)
        let old_width = if old_pairs.is_empty() {
            0
        } else {
            self.history.len() / old_pairs.len()
        };
        if old_width != width {
            self.history.clear();
        }
        let old_pairs = if old_width == width {
            old_pairs
        } else {
            Vec::new()
        };
        if self.list.mirrored || old_mirrored {
            let old = crate::engine::mirror_history::Sides {
                pairs: &old_pairs,
                mirrors: if old_pairs.is_empty() {
                    &[]
                } else {
                    &old_mirrors
                },
                mirrored: old_mirrored,
                history: &self.history,
                mirror_history: &old_mirror_history,
            };
            let (h, m) = crate::engine::mirror_history::carry_mirrored(
                &old,
                &self.list.pairs,
                &self.list.mirrors,
                &self.particles.id,
                &self.list_ids,
                &flips,
            );
            self.history = h;
            self.mirror_history = m;
        } else {
            self.history = self.accel.install(|| {
                carry_history(
                    &old_pairs,
                    &self.history,
                    &self.list.pairs,
                    &self.particles.id,
                    &self.list_ids,
                    &flips,
                )
            });
            self.mirror_history = vec![0.0; self.list.mirrors.len() * width];
        }
        if let Some(pending) = self.pending_history.take() {
            self.apply_pending_history(pending, width);
        }
        // as LIGGGHTS's granular list build: a pair keeps its history only if it touches
        // at the build (separated pairs keep stale values until then, and lose them now)
        if width > 0 {
            let p = &self.particles;
            for (k, pair) in self.list.pairs.iter().enumerate() {
                let (i, j) = (pair.i as usize, pair.j as usize);
                let d = [0, 1, 2].map(|c| p.x[i][c] - p.x[j][c] - pair.shift[c]);
                let radsum = p.radius[i] + p.radius[j];
                // a NaN distance is no contact
                #[allow(clippy::neg_cmp_op_on_partial_ord)]
                if !(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < radsum * radsum) {
                    self.history[k * width..(k + 1) * width].fill(0.0);
                }
            }
            for (k, m) in self.list.mirrors.iter().enumerate() {
                let (i, j) = (m.pair.i as usize, m.pair.j as usize);
                let d = [0, 1, 2].map(|c| p.x[i][c] - (p.x[j][c] + m.pair.shift[c]));
                let radsum = p.radius[i] + p.radius[j];
                #[allow(clippy::neg_cmp_op_on_partial_ord)]
                if !(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < radsum * radsum) {
                    self.mirror_history[k * width..(k + 1) * width].fill(0.0);
                }
            }
        }
        self.list_ids = self.particles.id.clone();
        self.ago = 0;
        self.box_at_build = (self.domain.lo, self.domain.hi);
        // the fast path sums by blocks of particles on any thread count; the exact path's
        // parallel sums need each particle's entries; small lists stay sequential
        use crate::engine::neighbor::{block_starts, Incidence, SumOrder};
        let (pairs, n) = (&self.list.pairs, self.particles.len());
        let threads = self.accel.thread_count() > 1;
        self.sum_order = if self.accel.fast {
            block_starts(pairs, n).map(SumOrder::Blocks)
        } else if threads
            && !self.list.mirrored
            && pairs.len() >= crate::engine::granular::parallel_pairs()
        {
            Incidence::new(pairs, n).map(SumOrder::Gathered)
        } else {
            None
        }
        .unwrap_or_default();
    }

    /// `delete_atoms overlap CUT G1 G2`: which atoms go. In memory order, an atom of G1 goes
    /// when an atom of G2 that has not gone lies closer than `cut`; across a periodic
    /// boundary only the lower ID of a pair counts as gone (LIGGGHTS's rule for ghosts).
    pub fn overlapping(&self, cut: f64, g1: u32, g2: u32) -> Result<Vec<bool>, String> {
        let p = &self.particles;
        let n = p.len();
        let mut list = crate::engine::neighbor::NeighborList::default();
        let reach = vec![0.5 * cut; n];
        let mut x = p.x.clone();
        for xi in &mut x {
            let mut image = [0; 3];
            self.domain.remap(xi, &mut image);
        }
        list.build(&x, &reach, 0.0, &self.domain, None);
        // partners of each atom, both directions: (partner, across a periodic boundary)
        let mut partners: Vec<Vec<(usize, bool)>> = vec![Vec::new(); n];
        for pair in &list.pairs {
            let (i, j) = (pair.i as usize, pair.j as usize);
            let d = [0, 1, 2].map(|k| x[i][k] - (x[j][k] + pair.shift[k]));
            if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= cut * cut || i == j {
                continue;
            }
            let periodic = pair.shift != [0.0; 3];
            partners[i].push((j, periodic));
            partners[j].push((i, periodic));
        }
        let mut gone = vec![false; n];
        for i in 0..n {
            if p.mask[i] & g1 == 0 {
                continue;
            }
            for &(j, periodic) in &partners[i] {
                if p.mask[j] & g2 == 0 {
                    continue;
                }
                if !periodic {
                    if gone[j] {
                        continue;
                    }
                } else if p.mask[i] & g2 != 0 && p.mask[j] & g1 != 0 && p.id[i] > p.id[j] {
                    continue;
                }
                gone[i] = true;
                break;
            }
        }
        Ok(gone)
    }

    /// Values of a `fix property/global` by its variable name: (style, columns, values).
    pub fn property(&self, name: &str) -> Option<(&str, usize, Vec<f64>)> {
        let fix = self.fixes.iter().rev().find(|f| {
            f.style == "property/global" && f.args.first().map(String::as_str) == Some(name)
        })?;
        let style = fix.args.get(1)?.as_str();
        let (columns, start) = match style {
            "peratomtypepair" | "atomtypepair" | "matrix" => (fix.args.get(2)?.parse().ok()?, 3),
            _ => (1, 2),
        };
        let values = fix.args[start..]
            .iter()
            .map(|w| crate::util::numbers::numeric(w).unwrap_or(0.0))
            .collect();
        Some((style, columns, values))
    }

    /// Build the contact models (pair and walls) from the current material properties.
    fn init_pair(&mut self) -> Result<(), String> {
        use crate::engine::contact::material::mix_yeff;
        use crate::engine::granular;
        let input = self.material_input();
        for k in 0..self.fixes.len() {
            if let FixKind::CheckTimestep(_) = &self.fixes[k].kind {
                if self.pair_selection.is_none() {
                    return Err(
                        "Fix check/timestep/gran can only be used together with: gran".into(),
                    );
                }
                let missing = |name: &str| {
                    format!("Could not locate a fix/property storing value(s) for {name} as requested by fix check/timestep/gran.")
                };
                let youngs = input
                    .youngs_modulus
                    .clone()
                    .ok_or_else(|| missing("youngsModulus"))?;
                let poisson = input
                    .poissons_ratio
                    .clone()
                    .ok_or_else(|| missing("poissonsRatio"))?;
                let n = self.ntypes as usize;
                if youngs.len() < n || poisson.len() < n {
                    return Err("fix check/timestep/gran: youngsModulus and poissonsRatio need one value per atom type".into());
                }
                let materials = (0..n)
                    .map(|t| {
                        let (y, nu) = (youngs[t], poisson[t]);
                        (y, nu, mix_yeff(y, y, nu, nu))
                    })
                    .collect();
                let every = self.thermo.every;
                let prefix = format!("f_{}", self.fixes[k].id);
                let in_thermo = self
                    .thermo
                    .fields
                    .iter()
                    .any(|f| f.keyword.starts_with(&prefix));
                if let FixKind::CheckTimestep(c) = &mut self.fixes[k].kind {
                    if in_thermo && every % c.every != 0 {
                        return Err("Thermo and fix not computed at compatible times".into());
                    }
                    c.materials = materials;
                }
            }
        }
        let two_d = false; // `dimension 2` is rejected at parse time
        for k in 0..self.fixes.len() {
            if let FixKind::WallGran(wall) = &self.fixes[k].kind {
                let mut sel = wall.selection.clone();
                sel.options.two_d = two_d;
                let model =
                    granular::build_wall(&sel, &input, wall.wall_type, wall.plane, wall.shear)?;
                if let FixKind::WallGran(wall) = &mut self.fixes[k].kind {
                    wall.model = Some(model);
                }
            }
        }
        for k in 0..self.fixes.len() {
            if let FixKind::MeshWall(wall) = &self.fixes[k].kind {
                let mut sel = wall.selection.clone();
                sel.options.two_d = two_d;
                let model = crate::engine::mesh_wall::build(&sel, &input)?;
                if let FixKind::MeshWall(wall) = &mut self.fixes[k].kind {
                    wall.model = Some(model);
                }
            }
        }
        let Some(mut sel) = self.pair_selection.clone() else {
            self.pair = None;
            return Ok(());
        };
        if !self.pair_coeff_set {
            return Err("All pair coeffs are not set".into());
        }
        if !self.comm_vel {
            return Err("Pair granular requires ghost atoms store velocity".into());
        }
        sel.options.two_d = two_d;
        let frozen = fixes::frozen_groups(&self.fixes);
        self.pair = Some(granular::build(&sel, &input, frozen)?);
        Ok(())
    }

    /// The material inputs from the `fix property/global` definitions (each present one,
    /// whether or not a model will ask for it).
    pub(crate) fn material_input(&self) -> crate::engine::contact::MaterialInput {
        let table = |name: &str| self.property(name).map(|(_, _, v)| v);
        let scalar = |name: &str| table(name).and_then(|v| v.first().copied());
        crate::engine::contact::MaterialInput {
            ntypes: self.ntypes as usize,
            units: self.units,
            soft_particles: self.soft_hard.0,
            hard_particles: self.soft_hard.1,
            allow_zero_restitution: self.zero_restitution,
            youngs_modulus: table("youngsModulus"),
            poissons_ratio: table("poissonsRatio"),
            coefficient_restitution: table("coefficientRestitution"),
            coefficient_friction: table("coefficientFriction"),
            coefficient_rolling_friction: table("coefficientRollingFriction"),
            coefficient_rolling_viscous_damping: table("coefficientRollingViscousDamping"),
            cohesion_energy_density: table("cohesionEnergyDensity"),
            characteristic_velocity: scalar("characteristicVelocity"),
            rolling_stiffness: scalar("rollingStiffness"),
            kn: table("kn"),
            kt: table("kt"),
            gamman: table("gamman"),
            gammat: table("gammat"),
            gamman_abs: table("gamman_abs"),
            gammat_abs: table("gammat_abs"),
            fluid_viscosity: table("FluidViscosity"),
            maximum_restitution: table("MaximumRestitution"),
            critical_stokes: table("CriticalStokes"),
            max_elastic_stiffness: table("coefficientMaxElasticStiffness"),
            adhesion_stiffness: table("coefficientAdhesionStiffness"),
            plasticity_depth: table("coefficientPlasticityDepth"),
        }
    }

    /// LIGGGHTS's `Neighbor::decide`: rebuild now?
    fn decide(&mut self) -> bool {
        // a rebuild a fix or a changed atom count forces is never dangerous
        let forced = self.mesh_rebuild_at == Some(self.step)
            || self.list.built_positions().len() != self.particles.len();
        let rebuild = self.decide_by_rules();
        // LIGGGHTS's dangerous build: a distance-triggered rebuild at the first step the
        // delay and every settings allowed (the list may have been out of date already)
        let n = &self.neighbor;
        if rebuild && !forced && n.check && self.ago == n.every.max(n.delay) {
            self.stats.dangerous += 1;
        }
        rebuild
    }

    /// The rebuild decision itself (see [`Self::decide`]).
    fn decide_by_rules(&mut self) -> bool {
        self.ago += 1;
        if self.mesh_rebuild_at == Some(self.step) {
            return true;
        }
        if self.list.built_positions().len() != self.particles.len() {
            return true;
        }
        let n = &self.neighbor;
        if self.ago < n.delay || !self.ago.is_multiple_of(n.every) {
            return false;
        }
        if !n.check {
            return true;
        }
        let mut trigger = 0.5 * n.skin;
        let periodic = (0..3).any(|d| self.domain.periodic(d));
        if self.domain.shrinks() && periodic {
            let dist = |a: [f64; 3], b: [f64; 3]| {
                ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
            };
            let d1 = dist(self.domain.lo, self.box_at_build.0);
            let d2 = dist(self.domain.hi, self.box_at_build.1);
            trigger = 0.5 * (n.skin - (d1 + d2));
        }
        let limit = trigger * trigger;
        if self.radii_vary() {
            // LIGGGHTS's test when a fix changes radii: growth eats into the skin too
            let delta = limit.sqrt();
            let p = &self.particles;
            return (0..p.len()).any(|i| {
                let (a, b) = (p.x[i], self.list.built_positions()[i]);
                let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
                let rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                let delr = p.radius[i] - self.list.built_reaches()[i];
                let delrsq = delr * delr;
                delrsq > limit || rsq > limit - 2. * delr * delta + delrsq
            });
        }
        let (x, built) = (&self.particles.x, self.list_positions());
        // blocks of particles tested without early exit (a loop the compiler vectorises)
        const BLOCK: usize = 256;
        let moved = |b: usize| {
            let (lo, hi) = (b * BLOCK, ((b + 1) * BLOCK).min(x.len()));
            let pairs = x[lo..hi].iter().zip(&built[lo..hi]);
            pairs.fold(false, |hit, (a, b)| {
                let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
                hit | (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > limit)
            })
        };
        first_where_in(x.len().div_ceil(BLOCK), BLOCK, moved).is_some()
    }

    /// LIGGGHTS's mesh setup at the first run: neighbours and active edges and corners of
    /// every `fix mesh/surface`, within the current box.
    fn build_mesh_topology(&mut self) -> Result<(), String> {
        let (lo, hi) = (self.domain.lo, self.domain.hi);
        for f in &mut self.fixes {
            if let FixKind::Mesh(m) = &mut f.kind {
                if !m.mesh.has_topology {
                    m.mesh.build_topology(lo, hi, &f.id)?;
                }
            }
        }
        Ok(())
    }

    /// The stress module's bookkeeping at a run's setup (clear triangle forces and step wear;
    /// read `k_finnie`), before a step's forces (clear them and the totals) and at the end of
    /// a step (add the step's wear, form the stresses).
    fn mesh_stress_phase(&mut self, phase: StressPhase) -> Result<(), String> {
        let k_finnie = match phase {
            StressPhase::Setup => self.property("k_finnie").map(|(_, cols, v)| {
                v.chunks(cols.max(1))
                    .map(|r| r.to_vec())
                    .collect::<Vec<_>>()
            }),
            _ => None,
        };
        for f in &mut self.fixes {
            let FixKind::Mesh(m) = &mut f.kind else {
                continue;
            };
            let Some(st) = m.stress.as_mut() else {
                continue;
            };
            match phase {
                StressPhase::Setup => {
                    st.clear_triangles();
                    match &k_finnie {
                        Some(k) => st.k_finnie = k.clone(),
                        None if st.wear_on => {
                            return Err(format!("Fix mesh/surface/stress (id {}): wear finnie needs fix property/global k_finnie peratomtypepair", f.id))
                        }
                        None => {}
                    }
                }
                StressPhase::PreForce => st.pre_force(),
                StressPhase::EndOfStep => {
                    st.end_of_step(&m.mesh.normal, &m.mesh.area);
                    if let Some(t) = st.first_non_finite() {
                        return Err(format!(
                            "blow-up at step {}: triangle {} of mesh {} has a wear or stress that is not finite (wear {}, stresses {} {}); check k_finnie and the particles' sizes and speeds",
                            self.step,
                            t + 1,
                            f.id,
                            st.wear[t],
                            st.sigma_n.get(t).copied().unwrap_or(0.0),
                            st.sigma_t.get(t).copied().unwrap_or(0.0)
                        ));
                    }
                }
            }
        }
        Ok(())
    }

    /// IDs of the meshes a `fix move/mesh` moves, with the index of their first mover.
    fn moving_meshes(&self) -> Vec<(String, usize)> {
        let mut out: Vec<(String, usize)> = Vec::new();
        for (k, f) in self.fixes.iter().enumerate() {
            if let FixKind::MoveMesh(mv) = &f.kind {
                if !out.iter().any(|(id, _)| id == &mv.mesh) {
                    out.push((mv.mesh.clone(), k));
                }
            }
        }
        out
    }

    /// LIGGGHTS's FixMesh::pre_force for moving meshes: after a re-neighbouring, recompute
    /// the surface vectors from the nodes and remember the nodes; otherwise ask for a
    /// re-neighbouring at the next step once a node has moved more than half the skin.
    fn refresh_moving_meshes(&mut self, rebuilt: bool) {
        let limit = 0.25 * self.neighbor.skin * self.neighbor.skin;
        for (id, _) in self.moving_meshes() {
            let Some(FixKind::Mesh(m)) = self
                .fixes
                .iter_mut()
                .find(|f| f.id == id && matches!(f.kind, FixKind::Mesh(_)))
                .map(|f| &mut f.kind)
            else {
                continue;
            };
            if rebuilt || m.nodes_at_refresh.len() != m.mesh.len() {
                m.mesh.recompute_surface();
                m.nodes_at_refresh = m.mesh.nodes.clone();
                continue;
            }
            let moved = m.mesh.nodes.iter().zip(&m.nodes_at_refresh).any(|(a, b)| {
                (0..3).any(|k| {
                    let d = [a[k][0] - b[k][0], a[k][1] - b[k][1], a[k][2] - b[k][2]];
                    d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > limit
                })
            });
            if moved {
                self.mesh_rebuild_at = Some(self.step + 1);
            }
        }
    }

    /// The first mover's setup zeroes its mesh's node velocities; a mesh wall defined before
    /// that mover computes its setup force with the previous run's velocities (LIGGGHTS
    /// calls the fixes' setups in definition order). `before_force`: the movers defined
    /// before every wall using their mesh; otherwise all of them.
    fn zero_mesh_velocities(&mut self, before_force: bool) {
        for (id, first) in self.moving_meshes() {
            let wall = self.fixes.iter().position(
                |f| matches!(&f.kind, FixKind::MeshWall(w) if w.meshes.iter().any(|m| m == &id)),
            );
            let mover_first = wall.is_none_or(|w| first < w);
            for f in self.fixes.iter_mut() {
                if let FixKind::Mesh(m) = &mut f.kind {
                    if f.id == id {
                        let n = m.mesh.len();
                        match &mut m.node_v {
                            Some(v) if !before_force || mover_first => {
                                v.iter_mut().for_each(|t| *t = [[0.0; 3]; 3])
                            }
                            Some(_) => {}
                            None => m.node_v = Some(vec![[[0.0; 3]; 3]; n]),
                        }
                    }
                }
            }
        }
    }

    /// LIGGGHTS's `cutneighmax` at a run's init: twice the largest radius among the atoms
    /// and the particle templates, plus the skin (length).
    pub(crate) fn liggghts_cutneighmax(&self) -> f64 {
        2.0 * self.largest_radius() + self.neighbor.skin
    }

    /// The largest radius among the atoms and the particle templates (length).
    pub fn largest_radius(&self) -> f64 {
        let atoms = self.particles.radius.iter().copied().fold(0.0, f64::max);
        let templates = self
            .fixes
            .iter()
            .filter_map(|f| match &f.kind {
                FixKind::Template(t) => Some(t.radius),
                _ => None,
            })
            .fold(0.0, f64::max);
        atoms.max(templates)
    }

    /// A dry run's `run`: LIGGGHTS's init checks of particles and neighbour bins, no step.
    pub fn check_run(&self) -> Result<(), String> {
        self.check_run_init()
    }

    /// A fix changes particle radii during runs (`fix adapt ... atom diameter`).
    fn radii_vary(&self) -> bool {
        self.fixes
            .iter()
            .any(|f| matches!(f.kind, FixKind::Adapt(_)))
    }

    /// `fix adapt ... atom diameter v_name` (LIGGGHTS's pre_force, and setup_pre_force when
    /// `setup`): every N steps set the diameters of the group's particles from the variable,
    /// keeping each particle's density.
    fn adapt_radii(&mut self, setup: bool, vars: &mut dyn VariableSource) -> Result<(), String> {
        use crate::engine::fixes::ForceValue;
        use std::f64::consts::PI;
        for k in 0..self.fixes.len() {
            let FixKind::Adapt(ad) = &self.fixes[k].kind else {
                continue;
            };
            if !setup && (ad.every == 0 || self.step % ad.every != 0) {
                continue;
            }
            let (group, scale) = (self.fixes[k].group, ad.scale);
            let values = match &ad.diameter {
                ForceValue::Equal(name) => {
                    let name = name.clone();
                    vec![vars.equal(self, &name)?; self.particles.len()]
                }
                ForceValue::Atom(name) => {
                    let name = name.clone();
                    vars.atom(self, &name)?
                }
                ForceValue::Constant(c) => vec![*c; self.particles.len()],
                ForceValue::Null => continue,
            };
            let p = &mut self.particles;
            for (i, &value) in values.iter().enumerate().take(p.len()) {
                if p.mask[i] & group == 0 {
                    continue;
                }
                let r = p.radius[i];
                let density = p.mass[i] / (4.0 * PI / 3.0 * r * r * r);
                let mut value = value;
                if scale {
                    value *= r * 2.0;
                }
                let r = 0.5 * value;
                p.radius[i] = r;
                p.mass[i] = 4.0 * PI / 3.0 * r * r * r * density;
            }
        }
        Ok(())
    }

    fn list_positions(&self) -> &[[f64; 3]] {
        self.list.built_positions()
    }

    /// Evaluate the variables and regions of `fix setforce`/`addforce` for this step.
    fn resolve_force_fixes(&mut self, vars: &mut dyn VariableSource) -> Result<(), String> {
        use crate::engine::fixes::ForceValue;
        if self.regions.list.iter().any(|r| r.is_dynamic()) {
            let mut regions = std::mem::take(&mut self.regions);
            let result = regions.reshape(Some(self.step), &mut |name| vars.equal(self, name));
            self.regions = regions;
            result?;
        }
        for k in 0..self.fixes.len() {
            let f = match &self.fixes[k].kind {
                FixKind::SetForce(f) | FixKind::AddForce(f) if f.needs_resolving() => f,
                _ => continue,
            };
            let n = self.particles.len();
            let mut columns: Vec<Option<Vec<f64>>> = Vec::with_capacity(3);
            for v in &f.values {
                columns.push(match v {
                    ForceValue::Null => None,
                    ForceValue::Constant(c) => Some(vec![*c; n]),
                    ForceValue::Equal(name) => Some(vec![vars.equal(self, name)?; n]),
                    ForceValue::Atom(name) => Some(vars.atom(self, name)?),
                });
            }
            let region = f.region;
            let mut resolved = vec![[None; 3]; n];
            for (i, r) in resolved.iter_mut().enumerate() {
                if region.is_some_and(|g| !self.regions.matches(g, self.particles.x[i])) {
                    continue;
                }
                for d in 0..3 {
                    r[d] = columns[d].as_ref().map(|c| c[i]);
                }
            }
            if let FixKind::SetForce(f) | FixKind::AddForce(f) = &mut self.fixes[k].kind {
                f.resolved = resolved;
            }
        }
        Ok(())
    }

    /// Evaluate the variables of `fix move variable` for this step (before the moves).
    fn resolve_move_fixes(&mut self, vars: &mut dyn VariableSource) -> Result<(), String> {
        use crate::engine::fixes::ForceValue;
        for k in 0..self.fixes.len() {
            let values: Vec<ForceValue> = match &self.fixes[k].kind {
                FixKind::Move(m) => match &m.motion {
                    fixes::Motion::Variable { displace, velocity } => {
                        displace.iter().chain(velocity.iter()).cloned().collect()
                    }
                    _ => continue,
                },
                _ => continue,
            };
            let n = self.particles.len();
            let mut columns: Vec<Option<Vec<f64>>> = Vec::with_capacity(6);
            for v in &values {
                columns.push(match v {
                    ForceValue::Null => None,
                    ForceValue::Constant(c) => Some(vec![*c; n]),
                    ForceValue::Equal(name) => Some(vec![vars.equal(self, name)?; n]),
                    ForceValue::Atom(name) => Some(vars.atom(self, name)?),
                });
            }
            let resolved: Vec<[Option<f64>; 6]> = (0..n)
                .map(|i| std::array::from_fn(|c| columns[c].as_ref().map(|col| col[i])))
                .collect();
            if let FixKind::Move(m) = &mut self.fixes[k].kind {
                m.resolved = resolved;
            }
        }
        Ok(())
    }

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
    }

    /// Zero forces and torques and evaluate the pair style, walls and forcing fixes;
    /// `want_virial`: tally the per-atom pair virial if a `compute stress/atom` uses it.
    fn compute_forces(
        &mut self,
        update: bool,
        want_virial: bool,
        vars: &mut dyn VariableSource,
    ) -> Result<(), String> {
        self.reset_clump_forces();
        let p = &mut self.particles;
        p.f.iter_mut().for_each(|f| *f = [0.0; 3]);
        p.torque.iter_mut().for_each(|t| *t = [0.0; 3]);
        let tally = want_virial
            && self.computes.iter().any(|c| {
                matches!(
                    c.kind,
                    crate::engine::computes::ComputeKind::StressAtom { pair: true, .. }
                )
            });
        self.virial.clear();
        self.virial_step = tally.then_some(self.step);
        if tally {
            self.virial.resize(p.len(), [0.0; 6]);
        }
        if let Some(pair) = self.pair.as_mut() {
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
        if self.computes.iter().any(|c| {
            matches!(
                c.kind,
                crate::engine::computes::ComputeKind::PairGranLocal(_)
            )
        }) {
            self.force_time_state = (self.particles.v.clone(), self.particles.omega.clone());
        }
        self.resolve_force_fixes(vars)?;
        self.resolve_buoyancy_regions();
        let list = (self.list.builds, self.neighbor.skin);
        // LIGGGHTS's mesh lists use the full skin when a mesh moves or the box can change
        // (a moving mesh's own lists use the full skin as well)
        let moving_skin = self.domain.shrinks();
        fixes::post_force(
            &mut self.fixes,
            &mut self.particles,
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

    /// `run N`: a setup force evaluation, then N velocity-Verlet steps with output.
    pub fn run(
        &mut self,
        nsteps: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), String> {
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
    ) -> Result<(), String> {
        self.accel.settle_threads();
        let accel = self.accel.clone();
        let mut job = crate::engine::accel::Handed((self, out, vars));
        accel.run_on_engine_thread(move || {
            let (sim, out, vars) = job.get();
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
    ) -> Result<(), String> {
        if !self.domain.exists {
            return Err("Run command before simulation box is defined".into());
        }
        self.init_pair()?;
        self.init_heat()?;
        self.check_meshes_in_box()?;
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
        crate::engine::buoyancy::check(&self.fixes)?;
        self.setup_momentum();
        self.accel.settle_threads();
        if self.accel.fast {
            self.start_order_record();
        }
        self.energy_watch = None;
        self.guard_notes = GuardNotes::default();
        // setup
        if pre || !self.has_run {
            self.pbc_and_box()?;
            self.build_mesh_topology()?;
            if self.sort_every > 0 {
                self.sort_particles();
            }
            self.build_neighbors();
            self.refresh_moving_meshes(true);
            self.zero_mesh_velocities(true);
            self.mesh_stress_phase(StressPhase::Setup)?;
            self.adapt_radii(true, vars)?;
            // LIGGGHTS's setup evaluation does not advance contact history
            self.compute_forces(false, true, vars)?;
            self.setup_clump_forces();
            self.zero_mesh_velocities(false);
            self.guard_motion(true)?;
            self.guard_forces()?;
        }
        self.has_run = true;
        self.massflow_lists(true)?;
        self.apply_tracer_resets();
        if let Some(m) = self.new_margin() {
            guard_say(&m);
        }
        if self.accel.fast {
            self.say_unaccelerated(out);
        }
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
        self.restart_in_progress = false;
        self.restart_fixes.clear();
        self.restart_peratom.clear();
        self.restart_move_origins.clear();
        self.restart_mesh_history.clear();
        self.say_clump_energy(out);
        self.setup_insertions(out)?;
        self.setup_averages(vars)?;
        self.thermo.run_start = first;
        self.thermo.prepare_run(self.domain.shrinks());
        let thermo_file = &mut self.extras.thermo_file;
        self.thermo.header(&mut |s: &str| {
            out(s);
            crate::engine::extras::tee(thermo_file, s)
        });
        self.thermo_line(out, vars)?;
        self.write_dumps(true, vars)?;
        self.loop_clock = Some(std::time::Instant::now());
        self.stats = RunStats::default();
        if let Some(o) = self.observer.as_mut() {
            o.run_started(first, last, self.particles.len());
        }
        for _ in 0..nsteps {
            self.step += 1;
            self.resolve_move_fixes(vars)?;
            fixes::initial_integrate(
                &mut self.fixes,
                &mut self.particles,
                self.step,
                self.dt,
                &self.domain,
            );
            fixes::move_meshes(&mut self.fixes, self.dt);
            self.massflow_phase(out)?;
            self.apply_tracer_resets();
            // a runaway shows first in the half-kicked velocities, before atoms are wrapped or lost
            self.guard_motion(false)?;
            // LIGGGHTS inserts in pre_exchange: after the first half-step, before the list
            // decision (a changed atom count forces the rebuild)
            self.insert_particles(out)?;
            self.insert_streams(out)?;
            let rebuilt = self.decide();
            if rebuilt {
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
            }
            self.refresh_moving_meshes(rebuilt);
            self.mesh_stress_phase(StressPhase::PreForce)?;
            self.adapt_radii(false, vars)?;
            let tally = self.virial_wanted(last);
            self.compute_forces(true, tally, vars)?;
            self.guard_forces()?;
            fixes::final_integrate(&mut self.fixes, &mut self.particles, self.dt, &self.domain);
            self.mesh_stress_phase(StressPhase::EndOfStep)?;
            self.end_of_step(out, vars)?;
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
        }
        if let Some(o) = self.observer.as_mut() {
            o.run_finished();
        }
        self.run_bounds = None;
        self.loop_clock = None;
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
        let other = (loop_time - t.pair - t.neigh - t.comm - t.output).max(0.0);
        let mut s = String::new();
        for (name, v) in [
            ("Pair ", t.pair),
            ("Neigh", t.neigh),
            ("Comm ", t.comm),
            ("Outpt", t.output),
            ("Other", other),
        ] {
            s.push_str(&format!("{name} time (%) = {} ({})\n", g(v), g(pct(v))));
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

    fn insert_world(&self) -> (Vec<[f64; 3]>, [bool; 3], bool) {
        let periodic = [0, 1, 2].map(|d| self.domain.periodic(d));
        (self.particles.x.clone(), periodic, self.domain.shrinks())
    }

    /// First run's setup of `fix insert/stream`: face normal, normal velocity, interval.
    fn setup_streams(&mut self, out: Sink<'_>) -> Result<(), String> {
        use crate::engine::insert::{Face, InsertStream, Velocity};
        let dt = self.dt;
        for k in 0..self.fixes.len() {
            let FixKind::InsertStream(sf) = &self.fixes[k].kind else {
                continue;
            };
            if sf.state.is_some() {
                continue;
            }
            let dist = self
                .fixes
                .iter()
                .find_map(|f| match &f.kind {
                    FixKind::Distribution(d) if f.id == sf.distribution => Some(d.clone()),
                    _ => None,
                })
                .ok_or_else(|| {
                    format!(
                        "Fix insert: could not find distribution {}",
                        sf.distribution
                    )
                })?;
            let t = sf.triangles[0];
            let mut ev = [[0.0; 3]; 2];
            for (j, e) in ev.iter_mut().enumerate() {
                let d = [0, 1, 2].map(|c| t[j + 1][c] - t[j][c]);
                let inv = 1.0 / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                *e = d.map(|c| inv * c);
            }
            let c = [
                ev[0][1] * ev[1][2] - ev[0][2] * ev[1][1],
                ev[0][2] * ev[1][0] - ev[0][0] * ev[1][2],
                ev[0][0] * ev[1][1] - ev[0][1] * ev[1][0],
            ];
            let inv = 1.0 / (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
            let mut n = c.map(|x| inv * x);
            let v = match sf.velocity {
                Velocity::Constant(v) | Velocity::Uniform(v, _) | Velocity::Gaussian(v, _) => v,
            };
            if v[0] * n[0] + v[1] * n[1] + v[2] * n[2] < 0.0 {
                n = n.map(|x| -x);
            }
            let dot = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
            let v_normal = n.map(|x| x * dot);
            let vn =
                (v_normal[0] * v_normal[0] + v_normal[1] * v_normal[1] + v_normal[2] * v_normal[2])
                    .sqrt();
            if vn < 1e-3 {
                return Err(format!("Fix insert/stream (id {}): insertion velocity projected on face normal is < 1e-3", sf.id));
            }
            let rbound = dist.max_radius;
            let (every, extrude) = match (sf.extrude, sf.every) {
                (Some(l), _) => {
                    if l < 3.0 * rbound && (sf.all_in || sf.overlapcheck) {
                        return Err(format!(
                            "Fix insert/stream (id {}): 'extrude_length' is too small",
                            sf.id
                        ));
                    }
                    let every = ((l + 1e-14) / (dt * vn)) as i32 as i64;
                    if every == 0 {
                        return Err(format!("Fix insert/stream (id {}): insertion velocity too high or extrude_length too low", sf.id));
                    }
                    (every, l)
                }
                (None, Some(e)) => {
                    if e < 1 {
                        return Err(format!(
                            "Fix insert/stream (id {}): 'insert_every' must be > 0",
                            sf.id
                        ));
                    }
                    // particles travel `duration` steps (default: insert_every) in the zone
                    let duration = sf.duration.unwrap_or(e);
                    if duration > e {
                        return Err(format!(
                            "Fix insert/stream (id {}): 'duration' > 'insert_every' not allowed",
                            sf.id
                        ));
                    }
                    let l = duration as f64 * dt * vn;
                    if l < 2.0 * rbound {
                        return Err(format!("Fix insert/stream (id {}): 'insert_every' or 'vel' is too small, or (bounding) radius of inserted particles too large", sf.id));
                    }
                    (e, l)
                }
                _ => unreachable!("checked when the fix was defined"),
            };
            // nparticles from mass, and the other rate, from the expected particle mass
            let me = dist.mass_expect;
            let total = match sf.total {
                Ok(n) => n,
                Err(mass) => {
                    if mass / me > 2.0e9 {
                        return Err(format!("Fix insert/stream (id {}): you are attempting to insert more than 2e9 particles. Reduce the mass to be inserted or increase the particle diameter", sf.id));
                    }
                    ((mass + 1e-14) / me) as i64
                }
            };
            let rates = match sf.rate {
                Ok(n) => (n, n * me),
                Err(m) => (m / me, m),
            };
            let mut face = Face::new(sf.triangles.clone());
            let (all_in, face_id) = (sf.all_in, sf.face_id.clone());
            if all_in {
                let (lo, hi) = (self.domain.lo, self.domain.hi);
                let mesh = self.fixes.iter_mut().find_map(|f| match &mut f.kind {
                    FixKind::Mesh(m) if f.id == face_id => Some((m, f.id.clone())),
                    _ => None,
                });
                if let Some((m, name)) = mesh {
                    if !m.mesh.has_topology {
                        m.mesh.build_topology(lo, hi, &name)?;
                    }
                    face.within = Some(crate::engine::insert::Within::new(&m.mesh));
                }
            }
            let moving = if self.stream_integrator() == Some(k) {
                self.releases_pending(self.fixes[k].group)
            } else {
                Vec::new()
            };
            let FixKind::InsertStream(sf) = &self.fixes[k].kind else {
                continue;
            };
            let restored = sf.restored;
            let state = InsertStream {
                id: sf.id.clone(),
                distribution: sf.distribution.clone(),
                face,
                normal: n,
                v_normal,
                p_ref: t[0],
                extrude,
                every,
                per_insertion: rates.0 * (every as f64 * dt),
                rates,
                total,
                velocity: sf.velocity,
                omega: sf.omega,
                overlapcheck: sf.overlapcheck,
                maxattempt: sf.maxattempt,
                ntry_mc: sf.ntry_mc,
                verbose: sf.verbose,
                rng: crate::util::random::RanPark::new(restored.map_or(sf.seed, |r| r.rng_state))?,
                next: Some(sf.start),
                measured: false,
                inserted: restored.map_or(0, |r| r.inserted),
                inserted_mass: restored.map_or(0.0, |r| r.mass),
                moving,
                first_step: restored.map_or(sf.start, |r| r.first_step),
            };
            for l in state.setup_lines(&dist) {
                out(&format!("{l}\n"));
            }
            if let FixKind::InsertStream(sf) = &mut self.fixes[k].kind {
                sf.state = Some(state);
            }
        }
        Ok(())
    }

    /// `fix insert/stream` insertions due at this step.
    fn insert_streams(&mut self, out: Sink<'_>) -> Result<(), String> {
        let step = self.step;
        for k in 0..self.fixes.len() {
            let due = matches!(&self.fixes[k].kind, FixKind::InsertStream(sf) if sf.state.as_ref().is_some_and(|s| s.next == Some(step)));
            if !due {
                continue;
            }
            let group = self.fixes[k].group;
            let FixKind::InsertStream(sf) = &self.fixes[k].kind else {
                unreachable!()
            };
            let dist_id = sf.distribution.clone();
            let dk = self
                .fixes
                .iter()
                .position(|f| f.id == dist_id)
                .ok_or_else(|| format!("Fix insert: could not find distribution {dist_id}"))?;
            let FixKind::Distribution(dist) = &self.fixes[dk].kind else {
                return Err(format!(
                    "Fix insert: {dist_id} is not a particle distribution"
                ));
            };
            let mut dist = dist.clone();
            let (x, periodic, box_changes) = self.insert_world();
            let (placed, lines) = {
                let world = crate::engine::insert::World {
                    x: &x,
                    radius: &self.particles.radius,
                    mass: &self.particles.mass,
                    lo: self.domain.lo,
                    hi: self.domain.hi,
                    periodic,
                    box_changes,
                };
                match &mut self.fixes[k].kind {
                    FixKind::InsertStream(sf) => sf.state.as_mut().expect("set up").insert(
                        step,
                        &mut dist,
                        &world,
                        box_changes,
                    ),
                    _ => unreachable!(),
                }
            }?;
            if let FixKind::Distribution(d) = &mut self.fixes[dk].kind {
                *d = dist.clone();
            }
            let mut tag = self.particles.max_id();
            let mut new = Vec::new();
            for (t, xp, v) in placed {
                let tpl = &dist.templates[t];
                tag += 1;
                self.particles
                    .push(tag, tpl.atom_type, xp, tpl.radius, tpl.density);
                let i = self.particles.len() - 1;
                self.particles.mass[i] = tpl.mass;
                self.particles.v[i] = v;
                self.particles.mask[i] |= group;
                new.push((tag, xp));
            }
            let dt = self.dt;
            let records = match &mut self.fixes[k].kind {
                FixKind::InsertStream(sf) => {
                    sf.state.as_mut().expect("set up").record(step, dt, &new)
                }
                _ => unreachable!(),
            };
            // the new atoms are the last ones, in the order of their records
            let first = self.particles.len() - records.len();
            self.store_releases(first, &records);
            // the integrating stream moves them, if they are in its group
            if let Some(ki) = self.stream_integrator() {
                let g = self.fixes[ki].group;
                let mask = &self.particles.mask[first..];
                if let FixKind::InsertStream(sf) = &mut self.fixes[ki].kind {
                    if let Some(state) = sf.state.as_mut() {
                        state.moving.extend(
                            records
                                .into_iter()
                                .zip(mask)
                                .filter(|(_, &m)| m & g != 0)
                                .map(|(r, _)| r),
                        );
                    }
                }
            }
            for l in lines {
                out(&format!("{l}\n"));
            }
        }
        Ok(())
    }

    /// `fix insert/stream`'s end of step: particles not yet released move at the normal
    /// velocity from where they were inserted, without forces; at the release step they
    /// get their final velocity and spin.
    fn move_streams(&mut self) {
        let (step, dt) = (self.step, self.dt);
        let mut index: Option<std::collections::HashMap<i64, usize>> = None;
        for k in 0..self.fixes.len() {
            let FixKind::InsertStream(sf) = &mut self.fixes[k].kind else {
                continue;
            };
            let Some(state) = sf.state.as_mut() else {
                continue;
            };
            if state.moving.is_empty() {
                continue;
            }
            let p = &mut self.particles;
            let map = index
                .get_or_insert_with(|| p.id.iter().enumerate().map(|(i, id)| (*id, i)).collect());
            state.moving.retain(|r| {
                let (vn, omega) = (r.v_int, r.omega);
                let Some(&i) = map.get(&r.id) else {
                    return false;
                };
                let s = step.min(r.release);
                let te = (s - r.inserted) as f64 * dt;
                p.x[i] = [0, 1, 2].map(|d| r.x[d] + vn[d] * te);
                p.f[i] = [0.0; 3];
                p.torque[i] = [0.0; 3];
                if step >= r.release {
                    p.v[i] = r.v_final;
                    p.omega[i] = omega;
                    return false;
                }
                p.v[i] = vn;
                p.omega[i] = [0.0; 3];
                true
            });
        }
    }

    /// First run's setup of `fix insert/pack`: region generator and volume.
    fn setup_insertions(&mut self, out: Sink<'_>) -> Result<(), String> {
        self.setup_streams(out)?;
        for k in 0..self.fixes.len() {
            let FixKind::InsertPack(ins) = &self.fixes[k].kind else {
                continue;
            };
            let dist_id = ins.distribution.clone();
            let Some(dk) = self.fixes.iter().position(|f| f.id == dist_id) else {
                return Err(format!("Fix insert: could not find distribution {dist_id}"));
            };
            let FixKind::Distribution(dist) = &self.fixes[dk].kind else {
                return Err(format!(
                    "Fix insert: {dist_id} is not a particle distribution"
                ));
            };
            let dist = dist.clone();
            let (x, periodic, box_changes) = self.insert_world();
            let world = crate::engine::insert::World {
                x: &x,
                radius: &self.particles.radius,
                mass: &self.particles.mass,
                lo: self.domain.lo,
                hi: self.domain.hi,
                periodic,
                box_changes,
            };
            let regions = self.regions.clone();
            let lines = match &mut self.fixes[k].kind {
                FixKind::InsertPack(ins) => ins.setup(&regions, &dist, &world, self.dt)?,
                _ => unreachable!(),
            };
            for l in lines {
                out(&format!("{l}\n"));
            }
        }
        Ok(())
    }

    /// `fix insert/pack` insertions due at this step.
    fn insert_particles(&mut self, out: Sink<'_>) -> Result<(), String> {
        let step = self.step;
        for k in 0..self.fixes.len() {
            let due =
                matches!(&self.fixes[k].kind, FixKind::InsertPack(ins) if ins.next == Some(step));
            if !due {
                continue;
            }
            let FixKind::InsertPack(ins) = &self.fixes[k].kind else {
                unreachable!()
            };
            let dist_id = ins.distribution.clone();
            let group = self.fixes[k].group;
            let dk = self
                .fixes
                .iter()
                .position(|f| f.id == dist_id)
                .ok_or_else(|| format!("Fix insert: could not find distribution {dist_id}"))?;
            let FixKind::Distribution(dist) = &self.fixes[dk].kind else {
                return Err(format!(
                    "Fix insert: {dist_id} is not a particle distribution"
                ));
            };
            let mut dist = dist.clone();
            let (x, periodic, box_changes) = self.insert_world();
            let regions = self.regions.clone();
            let (placed, lines) = {
                let world = crate::engine::insert::World {
                    x: &x,
                    radius: &self.particles.radius,
                    mass: &self.particles.mass,
                    lo: self.domain.lo,
                    hi: self.domain.hi,
                    periodic,
                    box_changes,
                };
                match &mut self.fixes[k].kind {
                    FixKind::InsertPack(ins) => ins.insert(step, &regions, &mut dist, &world),
                    _ => unreachable!(),
                }
            }?;
            let omega = match &self.fixes[k].kind {
                FixKind::InsertPack(ins) => ins.omega,
                _ => [0.0; 3],
            };
            if let FixKind::Distribution(d) = &mut self.fixes[dk].kind {
                *d = dist.clone();
            }
            let mut tag = self.particles.max_id();
            for (t, xp, v) in placed {
                let tpl = &dist.templates[t];
                if let Some(c) = &tpl.clump {
                    self.insert_clump(c, tag + 1, xp, v, omega, group)?;
                    tag += c.displace.len() as i64;
                    continue;
                }
                tag += 1;
                self.particles
                    .push(tag, tpl.atom_type, xp, tpl.radius, tpl.density);
                let i = self.particles.len() - 1;
                self.particles.mass[i] = tpl.mass;
                self.particles.v[i] = v;
                self.particles.omega[i] = omega;
                self.particles.mask[i] |= group;
            }
            for l in lines {
                out(&format!("{l}\n"));
            }
        }
        Ok(())
    }

    /// LIGGGHTS's check at setup: mesh triangles whose centre lies outside the box (along
    /// directions with fixed or periodic faces) are an error.
    fn check_meshes_in_box(&self) -> Result<(), String> {
        let d = &self.domain;
        for f in &self.fixes {
            let FixKind::Mesh(m) = &f.kind else { continue };
            let lost = m
                .triangles()
                .iter()
                .filter(|t| {
                    (0..3).any(|k| {
                        let c = (t[0][k] + t[1][k] + t[2][k]) / 3.0;
                        let fixed = d.boundary[k].iter().all(|b| {
                            matches!(
                                b,
                                crate::engine::domain::Boundary::Fixed
                                    | crate::engine::domain::Boundary::Periodic
                            )
                        });
                        fixed && !(c >= d.lo[k] && c < d.hi[k])
                    })
                })
                .count();
            if lost > 0 {
                return Err(format!(
                    "Mesh (id {}): {lost} mesh elements have been lost / left the domain. \nPlease use 'boundary m m m' or scale/translate/rotate the mesh or change its dynamics",
                    f.id
                ));
            }
        }
        Ok(())
    }

    /// Write the current state as a restart file (`write_restart`): pair history taken from
    /// the current list, then positions wrapped and the box reset as LIGGGHTS does.
    pub fn save_restart(&mut self, path: &str) -> Result<(), String> {
        self.refuse_clump_restart()?;
        self.check_restart_size()?;
        let partners = self.contact_partners();
        self.pbc_and_box()?;
        let r = self.to_restart(&partners);
        crate::io::restart::write(&r, path).map_err(|e| e.to_string())
    }

    /// The `restart` command's files, due at multiples of its interval (not at setup).
    fn periodic_restart(&mut self) -> Result<(), String> {
        let mut paths = Vec::new();
        for out in self.restart_output.iter_mut().flatten() {
            if self.step % out.every != 0 || out.last == Some(self.step) {
                continue;
            }
            out.last = Some(self.step);
            paths.push(if out.files.len() == 1 {
                out.files[0].replace('*', &self.step.to_string())
            } else {
                let p = out.files[out.toggle].clone();
                out.toggle = 1 - out.toggle;
                p
            });
        }
        if paths.is_empty() {
            return Ok(());
        }
        // written from the current state without re-wrapping (the run goes on)
        self.check_restart_size()?;
        let partners = self.contact_partners();
        let r = self.to_restart(&partners);
        for path in paths {
            crate::io::restart::write(&r, &path).map_err(|e| e.to_string())?;
        }
        Ok(())
    }

    /// `reset_timestep N`: bring the elapsed time up to date, then jump to step N.
    pub fn reset_timestep(&mut self, n: i64) {
        // insertion fixes keep their schedule's phase; insert/stream rewrites every atom's
        // release data (LIGGGHTS's FixInsert::reset_timestep and reset_releasedata)
        let old = self.step;
        let mut v_normal = None;
        for f in &mut self.fixes {
            match &mut f.kind {
                FixKind::InsertPack(ins) => {
                    if let Some(next) = &mut ins.next {
                        *next += n - old;
                    }
                }
                FixKind::InsertStream(sf) => {
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
                _ => {}
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
            if let FixKind::InsertStream(sf) = &mut self.fixes[ki].kind {
                if let Some(st) = sf.state.as_mut() {
                    st.moving = pending;
                }
            }
        }
    }

    /// The fix moving every stream's particles until release: the first insert/stream
    /// (LIGGGHTS's i_am_integrator).
    fn stream_integrator(&self) -> Option<usize> {
        self.fixes
            .iter()
            .position(|f| matches!(f.kind, FixKind::InsertStream(_)))
    }

    fn thermo_line(&mut self, out: Sink<'_>, vars: &mut dyn VariableSource) -> Result<(), String> {
        let values = self.thermo.values(self, vars)?;
        // a value that overflowed (an energy of huge, fast particles) ends the run rather
        // than printing inf or nan
        let bad = values.iter().position(|v| !v.is_finite());
        if let Some(k) = bad {
            return Err(format!(
                "blow-up at step {}: thermo keyword {} is {}; a value of the simulation overflowed (check particle sizes, densities and velocities)",
                self.step,
                self.thermo.fields[k].keyword,
                values[k]
            ));
        }
        let cpu = self.loop_clock.map_or(0.0, |t| t.elapsed().as_secs_f64());
        let thermo_file = &mut self.extras.thermo_file;
        self.thermo.line(&values, self.step, cpu, &mut |s: &str| {
            out(s);
            crate::engine::extras::tee(thermo_file, s)
        });
        Ok(())
    }

    /// Write one snapshot's text to dump `k`'s file (one file per step for `*` names,
    /// written whole through a temporary file).
    fn write_dump_text(&mut self, k: usize, step: i64, text: &[u8]) -> Result<(), String> {
        use std::io::Write;
        let dump = &mut self.dumps[k];
        let multi = dump.file.contains('*');
        let step_text = format!("{step:0width$}", width = dump.pad);
        let name = dump.file.replace('*', &step_text);
        if let Some(dir) = std::path::Path::new(&name).parent() {
            if !dir.as_os_str().is_empty() {
                std::fs::create_dir_all(dir)
                    .map_err(|e| format!("Cannot open dump file {name}: {e}"))?;
            }
        }
        // a .gz name gets gzip: a whole file per snapshot for `*` names, else one stream
        let gzip = name.ends_with(".gz");
        let packed;
        let text = if gzip && multi {
            let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
            enc.write_all(text).map_err(|e| format!("{name}: {e}"))?;
            packed = enc.finish().map_err(|e| format!("{name}: {e}"))?;
            &packed[..]
        } else {
            text
        };
        if let DumpStyle::Vtk(_) = dump.style {
            // one snapshot per file (overwritten without `*`), and the box beside it
            let mut bbox = Vec::new();
            match crate::io::vtk::Flavor::of(&dump.file) {
                Some(crate::io::vtk::Flavor::Legacy) | None => {
                    crate::io::vtk::write_bounding_box(&mut bbox, &self.domain)
                }
                Some(_) => crate::io::vtk::write_bounding_box_xml(&mut bbox, &self.domain),
            }
            .map_err(|e| e.to_string())?;
            crate::io::write_atomically(&name, text)
                .map_err(|e| format!("Cannot open dump file {name}: {e}"))?;
            let box_name = crate::io::vtk::bounding_box_name(&dump.file, &step_text);
            crate::io::write_atomically(&box_name, &bbox)
                .map_err(|e| format!("Cannot open dump file {box_name}: {e}"))?;
        } else if multi
            || matches!(
                dump.style,
                DumpStyle::MeshStl(_) | DumpStyle::MeshVtk(_) | DumpStyle::LocalGranVtk(_)
            )
        {
            crate::io::write_atomically(&name, text)
                .map_err(|e| format!("Cannot open dump file {name}: {e}"))?;
        } else {
            if dump.handle.is_none() {
                let f = std::fs::File::create(&name)
                    .map_err(|e| format!("Cannot open dump file {name}: {e}"))?;
                let f = std::io::BufWriter::new(f);
                dump.handle = Some(if gzip {
                    DumpFile::Gzip(flate2::write::GzEncoder::new(
                        f,
                        flate2::Compression::default(),
                    ))
                } else {
                    DumpFile::Plain(f)
                });
            }
            let h = dump.handle.as_mut().expect("opened above");
            h.write_all(text)
                .and_then(|_| h.flush())
                .map_err(|e| format!("{name}: {e}"))?;
        }
        Ok(())
    }

    pub(crate) fn write_dumps(
        &mut self,
        setup: bool,
        vars: &mut dyn VariableSource,
    ) -> Result<(), String> {
        let step = self.step;
        // a local compute is evaluated once per step, however many columns and dumps use it
        let mut local_rows: std::collections::HashMap<String, std::rc::Rc<(usize, Vec<f64>)>> =
            std::collections::HashMap::new();
        for k in 0..self.dumps.len() {
            let d = &self.dumps[k];
            let due = (step % d.every == 0 || (setup && d.first && d.last_written.is_none()))
                && d.last_written != Some(step);
            if !due {
                continue;
            }
            self.dumps[k].last_written = Some(step);
            if let Some(cols) = self.dumps[k].local.clone() {
                let mut data = Vec::new();
                for (cid, col) in &cols {
                    let c = self
                        .computes
                        .iter()
                        .find(|c| &c.id == cid)
                        .ok_or_else(|| format!("Could not find dump local compute ID {cid}"))?;
                    let evaluated = match local_rows.get(cid) {
                        Some(r) => r.clone(),
                        None => {
                            let r = std::rc::Rc::new(c.local(self)?);
                            local_rows.insert(cid.clone(), r.clone());
                            r
                        }
                    };
                    let ncols = evaluated.0;
                    if *col >= ncols.max(1) {
                        return Err(format!(
                            "Dump local compute vector is accessed out-of-range: c_{cid}[{}] of a compute with {ncols} column(s)",
                            col + 1
                        ));
                    }
                    data.push((evaluated, *col));
                }
                let nrows = data.first().map_or(0, |d| d.0 .1.len() / d.0 .0.max(1));
                let mut text = Vec::new();
                crate::io::dump::write_local(
                    &mut text,
                    step,
                    &self.domain,
                    &self.dumps[k].layout.names,
                    self.dumps[k].layout.format.as_deref(),
                    nrows,
                    |r, c| data[c].0 .1[r * data[c].0 .0 + data[c].1],
                )
                .map_err(|e| e.to_string())?;
                self.write_dump_text(k, step, &text)?;
                continue;
            }
            if let DumpStyle::LocalGranVtk(cid) = &self.dumps[k].style {
                let text = crate::engine::local_vtk::snapshot(self, cid)?;
                self.write_dump_text(k, step, &text)?;
                continue;
            }
            // per-atom values of the compute columns, evaluated once per snapshot
            let mut columns = Vec::new();
            for col in &self.dumps[k].layout.columns {
                if let crate::io::dump::Column::Reference(name) = col {
                    columns.push(self.dump_reference(name, vars)?);
                }
            }
            let dump = &mut self.dumps[k];
            let mut text = Vec::new();
            let p = &self.particles;
            match &dump.style {
                DumpStyle::Text => dump
                    .layout
                    .write_snapshot(&mut text, step, p, dump.group, &self.domain, |c, i| {
                        columns[c].0.get(i, columns[c].1)
                    })
                    .map_err(|e| e.to_string())?,
                DumpStyle::Xyz(elements) => {
                    use std::io::Write;
                    let atoms: Vec<usize> = (0..p.len())
                        .filter(|&i| p.mask[i] & dump.group != 0)
                        .collect();
                    let mut w = || -> std::io::Result<()> {
                        writeln!(text, "{}\nAtoms. Timestep: {step}", atoms.len())?;
                        for &i in &atoms {
                            let t = p.kind[i] as usize;
                            let element = elements
                                .get(t.wrapping_sub(1))
                                .cloned()
                                .unwrap_or_else(|| t.to_string());
                            let g = crate::util::format::g;
                            let x = p.x[i];
                            writeln!(text, "{element} {} {} {}", g(x[0]), g(x[1]), g(x[2]))?;
                        }
                        Ok(())
                    };
                    w().map_err(|e| e.to_string())?;
                }
                DumpStyle::MeshStl(ids) => {
                    let (mut triangles, mut normals) = (Vec::new(), Vec::new());
                    for f in &self.fixes {
                        if let FixKind::Mesh(m) = &f.kind {
                            if ids.is_empty() || ids.contains(&f.id) {
                                triangles.extend_from_slice(m.triangles());
                                normals.extend_from_slice(&m.mesh.normal);
                            }
                        }
                    }
                    text.extend_from_slice(
                        crate::io::stl::write_ascii(&triangles, &normals).as_bytes(),
                    );
                }
                DumpStyle::MeshVtk(spec) => {
                    let meshes: Vec<&crate::engine::fixes::MeshFix> = if spec.meshes.is_empty() {
                        self.fixes
                            .iter()
                            .filter_map(|f| match &f.kind {
                                FixKind::Mesh(m) => Some(&**m),
                                _ => None,
                            })
                            .collect()
                    } else {
                        spec.meshes
                            .iter()
                            .filter_map(|id| {
                                self.fixes.iter().find_map(|f| match &f.kind {
                                    FixKind::Mesh(m) if &f.id == id => Some(&**m),
                                    _ => None,
                                })
                            })
                            .collect()
                    };
                    let counts: Vec<(Vec<i32>, Vec<i32>, Vec<i32>)> = meshes
                        .iter()
                        .map(|m| {
                            let mm = &m.mesh;
                            let count = |v: &[bool; 3]| v.iter().filter(|&&b| b).count() as i32;
                            (
                                mm.edge_active.iter().map(count).collect(),
                                mm.corner_active.iter().map(count).collect(),
                                mm.neighbors.iter().map(|n| n.len() as i32).collect(),
                            )
                        })
                        .collect();
                    let snaps: Vec<crate::io::mesh_vtk::MeshSnapshot> = meshes
                        .iter()
                        .zip(&counts)
                        .map(|(m, c)| {
                            let st = m.stress.as_ref();
                            crate::io::mesh_vtk::MeshSnapshot {
                                nodes: &m.mesh.nodes,
                                area: Some(&m.mesh.area),
                                sigma_n: st.filter(|s| s.stress).map(|s| &s.sigma_n[..]),
                                sigma_t: st.filter(|s| s.stress).map(|s| &s.sigma_t[..]),
                                force: st.filter(|s| s.stress).map(|s| &s.f[..]),
                                wear: st.filter(|s| s.wear_on).map(|s| &s.wear[..]),
                                node_vel: m.node_v.as_deref(),
                                active_edges: Some(&c.0),
                                active_corners: Some(&c.1),
                                nneighs: Some(&c.2),
                                ..Default::default()
                            }
                        })
                        .collect();
                    crate::io::mesh_vtk::write_mesh_vtk(&mut text, spec, &snaps)
                        .map_err(|e| e.to_string())?;
                }
                // written before the per-atom columns are evaluated
                DumpStyle::LocalGranVtk(_) => {}
                DumpStyle::Vtk(fields) => {
                    let mut atoms: Vec<usize> = (0..p.len())
                        .filter(|&i| p.mask[i] & dump.group != 0)
                        .collect();
                    if dump.layout.sort_by_id {
                        atoms.sort_by_key(|&i| p.id[i]);
                    }
                    // column index -> index among the reference columns
                    let cols = &dump.layout.columns;
                    let mut reference = vec![usize::MAX; cols.len()];
                    let mut r = 0;
                    for (c, col) in cols.iter().enumerate() {
                        if let crate::io::dump::Column::Reference(_) = col {
                            reference[c] = r;
                            r += 1;
                        }
                    }
                    let domain = &self.domain;
                    let value = |c: usize, i: usize| match &cols[c] {
                        crate::io::dump::Column::Reference(_) => {
                            let (values, col) = &columns[reference[c]];
                            values.get(i, *col)
                        }
                        other => other.value(p, domain, i),
                    };
                    use crate::io::vtk::{write_particles, write_particles_xml, Flavor};
                    match Flavor::of(&dump.file) {
                        Some(f @ (Flavor::PolyData | Flavor::Unstructured)) => {
                            write_particles_xml(&mut text, f, &atoms, fields, |i| p.x[i], value)
                        }
                        _ => write_particles(&mut text, &atoms, fields, |i| p.x[i], value),
                    }
                    .map_err(|e| e.to_string())?;
                }
            }
            self.write_dump_text(k, step, &text)?;
        }
        Ok(())
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
