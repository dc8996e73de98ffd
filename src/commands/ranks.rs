//! What runs on more than one MPI rank (the first slice of the domain decomposition): a box
//! with periodic, fixed and shrink-wrapped faces, particles from `create_atoms`, `read_data`
//! or `read_restart` (set-up commands run identically on every rank), `write_restart`, `restart`,
//! `write_data` and `write_dump custom` (by rank 0 alone), `pair_style gran`,
//! `fix nve/sphere`, `nve`, `gravity`, primitive and mesh `wall/gran` (`mesh/surface`, `move/mesh`), `check/timestep/gran`, `property/global` and the
//! per-particle force fixes below, insertion (`insert/pack`, `insert/rate/region`,
//! `insert/stream` with sphere templates and discrete distributions), the computes below, `thermo` with the keywords below and
//! `c_`/`v_` values, `dump custom` and `custom/vtk` with `c_`/`v_` columns, `dump xyz`,
//! `atom`, `mesh/stl`, `local` and `local/gran/vtk`, on the fast path. Everything
//! else is refused by name before anything runs.

use crate::commands::CommandLine;
use crate::engine::sim::Simulation;

/// Commands that run as they do on one process (set-up, script and output settings).
const COMMANDS: &[&str] = &[
    "atom_style",
    "atom_modify",
    "units",
    "newton",
    "communicate",
    "comm_modify",
    "processors",
    // the grid's cuts moved for the next run (every rank holds the whole set between runs)
    "balance",
    "region",
    "create_box",
    "create_atoms",
    "read_data",
    "read_restart",
    // one file by rank 0 as one process writes it, or a `%` file per rank
    "write_restart",
    // the same files every N steps of a run, from every rank's particles gathered
    "restart",
    // files by rank 0 alone from the whole set every rank holds between runs, as one
    // process writes them
    "write_data",
    "write_dump",
    "lattice",
    "mass",
    "set",
    "group",
    "velocity",
    "displace_atoms",
    "delete_atoms",
    "neighbor",
    "neigh_modify",
    "pair_style",
    "pair_coeff",
    // `compute no|yes` (mix, shift and tail change nothing for granular pairs)
    "pair_modify",
    "fix",
    "unfix",
    "timestep",
    "thermo",
    "thermo_style",
    "thermo_modify",
    "dump",
    "dump_modify",
    "undump",
    "run",
    "reset_timestep",
    "hard_particles",
    "soft_particles",
    "suffix",
    "package",
    "echo",
    "if",
    "include",
    "jump",
    "label",
    "next",
    "print",
    "quit",
    "variable",
    "dimension",
    "boundary",
    "compute",
    "uncompute",
    // files and commands by rank 0 alone, cd and putenv on every rank (as LIGGGHTS)
    "shell",
];

/// Fix styles that run on ranks: each acts on every owned particle alone, with no sum over
/// particles (setforce and addforce with constant components).
const FIXES: &[&str] = &[
    "nve/sphere",
    "nve",
    "nve/limit",
    "nve/noforce",
    "gravity",
    "wall/gran",
    "property/global",
    "freeze",
    "setforce",
    "addforce",
    "viscous",
    "lineforce",
    "planeforce",
    // its extremes are reduced over the ranks (f_ID[1..3] in thermo)
    "check/timestep/gran",
    // prescribed motion from each atom's start position, which every rank keeps by ID
    "move",
    // the grid's cuts moved at builds, particles migrating to any rank
    "balance",
    // rank 0 prints, its variables evaluated over every rank's particles gathered
    "print",
    // every mesh whole on every rank, moved alike on each; each rank's particles carry
    // their mesh contacts with them
    "mesh/surface",
    // the same mesh, checked to be planar (an insert/stream face with all_in)
    "mesh/surface/planar",
    "move/mesh",
    // at an insertion step every rank gathers the whole set, inserts as one process does
    // (the same particles with the same IDs on each) and keeps its brick's; a stream's
    // particles are carried to their release by the rank that owns them
    "insert/pack",
    "insert/rate/region",
    "insert/stream",
    "particletemplate/sphere",
    "particledistribution/discrete",
    "particledistribution/discrete/massbased",
    "particledistribution/discrete/numberbased",
];

/// Compute styles that run on ranks: evaluated by rank 0 for thermo and dumps from every
/// rank's particles gathered (positions, velocities, spins, forces, torques, groups).
const COMPUTES: &[&str] = &[
    "ke",
    "erotate",
    "erotate/sphere",
    "reduce",
    "reduce/region",
    "com",
    "property/atom",
    "ke/atom",
    "erotate/sphere/atom",
    "gyration",
    "pe",
    "pe/atom",
    // the pair virial of each owned particle is whole on its rank, gathered with it
    "stress/atom",
    // each rank reports its own contacts (a pair across ranks from one side), gathered
    "pair/gran/local",
];

/// Thermo keywords evaluated from the particles alone (gathered on rank 0).
const THERMO: &[&str] = &[
    "step",
    "elapsed",
    "elaplong",
    "dt",
    "time",
    "cpu",
    "tpcpu",
    "spcpu",
    "cpuremain",
    "atoms",
    "ke",
    "temp",
    "vol",
    "lx",
    "ly",
    "lz",
    "xlo",
    "xhi",
    "ylo",
    "yhi",
    "zlo",
    "zhi",
    "part",
    "erotate",
    "density",
    "fmax",
    "fnorm",
    "xy",
    "xz",
    "yz",
    "xlat",
    "ylat",
    "zlat",
    "cella",
    "cellb",
    "cellc",
    "cellalpha",
    "cellbeta",
    "cellgamma",
];

/// What runs on more than one rank, as a refusal's help says it.
pub const WHAT_RUNS: &str = "on several ranks regolith runs (with -sf fast) boxes with periodic, \
    fixed and shrink-wrapped faces, write_restart, restart, write_data, write_dump custom, pair_style gran (pair_modify), neigh_modify exclude type|group, fix nve/sphere, nve/noforce, gravity, primitive and mesh wall/gran (mesh/surface, mesh/surface/planar, move/mesh), freeze, \
    setforce/addforce with constants, viscous, move, print and check/timestep/gran, insert/pack, \
    insert/rate/region and insert/stream with particletemplate/sphere and \
    particledistribution/discrete, shell, computes ke, \
    erotate/sphere, reduce, com, stress/atom, pair/gran/local and per-atom properties, thermo \
    (step, atoms, ke, c_, v_, ...), dump custom, custom/vtk, atom, xyz, mesh/stl, local and local/gran/vtk; or run it as one process (with threads: -sf fast -pk fast N)";

/// What of `cmd` does not run on more than one rank yet (None: it runs), as the words
/// the refusal names: "<what> on more than one MPI rank: not supported yet".
pub fn refusal(cmd: &CommandLine, sim: &Simulation) -> Option<String> {
    let name = cmd.name();
    let args: Vec<&str> = (0..cmd.nargs()).filter_map(|i| cmd.arg(i)).collect();
    if !COMMANDS.contains(&name) {
        return Some(name.to_string());
    }
    match name {
        "fix" => {
            let style = *args.get(2)?;
            if !FIXES.contains(&style) {
                return Some(format!("fix {style}"));
            }
            if args.iter().any(|a| a.starts_with("v_")) {
                return Some(format!("fix {style} with a variable"));
            }
            if matches!(style, "setforce" | "addforce") && args.contains(&"region") {
                return Some(format!("fix {style} with a region"));
            }
            if style == "wall/gran" && args.contains(&"multicontact") {
                return Some("fix wall/gran with surface multicontact".into());
            }
            None
        }
        "compute" => {
            let style = *args.get(2)?;
            (!COMPUTES.contains(&style)).then(|| format!("compute {style}"))
        }
        "pair_style" => match args.first() {
            Some(&"gran") => None,
            Some(s) => Some(format!("pair_style {s}")),
            None => None,
        },
        "dump" => match args.get(2) {
            // the particles every rank owns, gathered on rank 0 (one VTK piece for a
            // parallel name, as one process writes it)
            Some(&s @ ("custom" | "custom/vtk")) => {
                let columns = args.get(5..).unwrap_or(&[]);
                refused_column(sim, columns).map(|c| format!("dump {s} column {c}"))
            }
            Some(&("xyz" | "atom")) => None,
            // the meshes, whole on every rank
            Some(&("mesh/stl" | "stl")) => None,
            // the rows of local computes, every rank's gathered
            Some(&("local" | "local/gran/vtk")) => None,
            Some(s) => Some(format!("dump {s}")),
            None => None,
        },
        "write_dump" => match args.get(1) {
            Some(&"custom") => {
                let end = args
                    .iter()
                    .position(|a| *a == "modify")
                    .unwrap_or(args.len());
                let columns = args.get(3..end).unwrap_or(&[]);
                refused_column(sim, columns).map(|c| format!("write_dump custom column {c}"))
            }
            Some(s) => Some(format!("write_dump {s}")),
            None => None,
        },
        "thermo_style" => {
            let keywords = match args.first() {
                Some(&"custom") => &args[1..],
                Some(&"one") => &[][..],
                Some(s) => return Some(format!("thermo_style {s}")),
                None => return None,
            };
            // computes and variables are evaluated from the gathered particles
            // (not the pressure, which needs the pair virial)
            let gathered = |k: &str| {
                (k.starts_with("c_") && !k.starts_with("c_thermo_press"))
                    || k.starts_with("v_")
                    || fix_values_on_every_rank(sim, k)
            };
            keywords
                .iter()
                .find(|k| !THERMO.contains(k) && !gathered(k))
                .map(|k| format!("thermo keyword {k}"))
        }
        "dimension" => (args.first() != Some(&"3")).then(|| "dimension 2".to_string()),
        // `exclude type`, `group` and `none` leave pairs out on every rank alike; the
        // other exclusions are refused
        "neigh_modify" => args.windows(2).find_map(|w| {
            (w[0] == "exclude" && !matches!(w[1], "type" | "group" | "none"))
                .then(|| format!("neigh_modify exclude {}", w[1]))
        }),
        "print" => args
            .iter()
            .find(|w| matches!(**w, "file" | "append" | "universe"))
            .map(|w| format!("print {w}")),
        "run" => {
            if !sim.accel.fast {
                return Some("run on the exact path (add -sf fast)".into());
            }
            if args.contains(&"every") {
                return Some("run every".into());
            }
            let pre_no = args.windows(2).any(|w| w == ["pre", "no"]);
            pre_no.then(|| "run pre no".to_string())
        }
        _ => None,
    }
}

/// Is thermo keyword `k` a value `f_ID[i]` of a fix every rank holds whole (the extremes of
/// `check/timestep/gran`, reduced over the ranks)?
fn fix_values_on_every_rank(sim: &Simulation, k: &str) -> bool {
    let Some(id) = k.strip_prefix("f_") else {
        return false;
    };
    let id = id.split('[').next().unwrap_or(id);
    sim.fixes
        .iter()
        .any(|f| f.id == id && matches!(f.style.as_str(), "check/timestep/gran" | "balance"))
}

/// The first of a dump's `columns` that does not run on ranks: a fix's per-atom values
/// (`f_ID`), unless the fix keeps them by atom ID on every rank.
fn refused_column<'a>(sim: &Simulation, columns: &[&'a str]) -> Option<&'a str> {
    columns
        .iter()
        .copied()
        .find(|c| c.starts_with("f_") && !fix_columns_by_id(sim, c))
}

/// Is dump column `c` (`f_ID[i]`) a per-atom value of a fix that keeps it by atom ID on
/// every rank (`fix move`'s start positions), so rank 0 gives it for every gathered atom?
fn fix_columns_by_id(sim: &Simulation, c: &str) -> bool {
    let Some(id) = c.strip_prefix("f_") else {
        return false;
    };
    let id = id.split('[').next().unwrap_or(id);
    sim.fixes.iter().any(|f| f.id == id && f.style == "move")
}

/// The full refusal message of what [`refusal`] names.
pub fn message(what: &str) -> String {
    format!("{what} on more than one MPI rank")
}
