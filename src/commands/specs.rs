//! The declared signature of every command and style regolith runs: its positional
//! arguments, its keywords with the kinds (and physical quantities) of their values, and a
//! one-line description. The table is the one place that says what regolith runs: the
//! support lookup used by `check` reads it (see [`crate::commands::registry`]), `regolith
//! help` prints it, misspelt names in `help` get the nearest declared ones, and
//! `compat/SUPPORT.md` lists it.

use crate::commands::suggest::did_you_mean;

/// The kind of value an argument takes; reals name the physical quantity they measure (in
/// the deck's `units`, SI or cgs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Value {
    /// An integer (a count, a step number, a seed, an atom type).
    Int,
    /// A real number measuring this quantity (`""` for a pure number).
    Real(&'static str),
    /// One of these words.
    OneOf(&'static [&'static str]),
    /// The ID of something defined earlier (a region, group, fix, compute, mesh, variable).
    Id(&'static str),
    /// A file name.
    File,
    /// Any other word (a text, a format, a list).
    Word,
}

/// One argument: the name usage lines give it, and its kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Arg {
    /// The placeholder in usage lines (`X`, `SEED`).
    pub name: &'static str,
    /// What it takes.
    pub value: Value,
}

/// An optional keyword and the arguments that follow it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Keyword {
    /// The keyword as written in decks.
    pub name: &'static str,
    /// The values that follow it.
    pub args: &'static [Arg],
    /// What it sets, in one line.
    pub about: &'static str,
}

/// The declared signature of a command, or of one style of a styled command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Spec {
    /// The command (`fix`, `run`).
    pub command: &'static str,
    /// The style (`wall/gran`), for commands whose argument names one.
    pub style: Option<&'static str>,
    /// The positional arguments as a usage line.
    pub usage: &'static str,
    /// The optional keywords regolith reads.
    pub keywords: &'static [Keyword],
    /// What it does, in one line.
    pub about: &'static str,
}

pub(crate) const fn arg(name: &'static str, value: Value) -> Arg {
    Arg { name, value }
}

pub(crate) const fn kw(name: &'static str, args: &'static [Arg], about: &'static str) -> Keyword {
    Keyword { name, args, about }
}

const fn command(usage: &'static str, about: &'static str) -> Spec {
    let name = first_word(usage);
    Spec {
        command: name,
        style: None,
        usage,
        keywords: &[],
        about,
    }
}

/// The signature of a style of `command`.
pub(crate) const fn style(
    command: &'static str,
    style: &'static str,
    usage: &'static str,
    keywords: &'static [Keyword],
    about: &'static str,
) -> Spec {
    Spec {
        command,
        style: Some(style),
        usage,
        keywords,
        about,
    }
}

const fn with(spec: Spec, keywords: &'static [Keyword]) -> Spec {
    Spec { keywords, ..spec }
}

/// The text up to the first blank (a usage line's command name).
const fn first_word(text: &'static str) -> &'static str {
    let bytes = text.as_bytes();
    let mut n = 0;
    while n < bytes.len() && bytes[n] != b' ' {
        n += 1;
    }
    let (head, _) = bytes.split_at(n);
    match std::str::from_utf8(head) {
        Ok(word) => word,
        Err(_) => panic!("usage lines are ASCII"),
    }
}

pub(crate) const YES_NO: Value = Value::OneOf(&["yes", "no"]);
pub(crate) const ON_OFF: Value = Value::OneOf(&["on", "off"]);
pub(crate) const LENGTH: Value = Value::Real("length");
pub(crate) const VELOCITY: Value = Value::Real("velocity");
pub(crate) const NUMBER: Value = Value::Real("");

/// Keywords the insertion fixes share.
pub(crate) const INSERT_KEYWORDS: &[Keyword] = &[
    kw(
        "seed",
        &[arg("SEED", Value::Int)],
        "prime above 10000 seeding the random positions",
    ),
    kw(
        "distributiontemplate",
        &[arg("D", Value::Id("fix"))],
        "the particle distribution to insert",
    ),
    kw(
        "maxattempt",
        &[arg("N", Value::Int)],
        "placement attempts per particle",
    ),
    kw(
        "insert_every",
        &[arg("N", Value::Word)],
        "steps between insertions, or once",
    ),
    kw(
        "overlapcheck",
        &[arg("yes|no", YES_NO)],
        "refuse positions overlapping other particles",
    ),
    kw(
        "all_in",
        &[arg("yes|no", YES_NO)],
        "keep whole particles inside the region",
    ),
    kw(
        "orientation",
        &[arg(
            "random|template",
            Value::OneOf(&["random", "template"]),
        )],
        "random or template orientation of clumps (constant: not supported yet)",
    ),
    kw(
        "vel",
        &[arg("constant VX VY VZ", VELOCITY)],
        "initial velocity",
    ),
    kw(
        "omega",
        &[arg("constant WX WY WZ", Value::Real("angular velocity"))],
        "initial angular velocity",
    ),
    kw("start", &[arg("STEP", Value::Int)], "first insertion step"),
    kw(
        "ntry_mc",
        &[arg("N", Value::Int)],
        "Monte Carlo trials for the region volume",
    ),
    kw(
        "verbose",
        &[arg("yes|no", YES_NO)],
        "report every insertion",
    ),
];

/// Every command and style regolith runs (script-language commands are the interpreter's).
pub const SPECS: &[Spec] = &[
    command("atom_modify map array|hash [sort N BINSIZE]", "atom map and spatial sorting settings"),
    style("atom_style", "granular", "atom_style granular", &[], "spheres with radius, density, angular velocity"),
    style("atom_style", "sphere", "atom_style sphere", &[], "the same as granular"),
    command("boundary X Y Z", "boundary conditions per axis: p, f, s, m or two of them"),
    with(command("change_box GROUP x|y|z final LO HI|delta DLO DHI|scale F|volume ... boundary X Y Z | set | remap ... [units box|lattice]", "change the box bounds (length) and boundaries; remap moves the group's atoms with the box"), &[
        kw("units", &[arg("box|lattice", Value::OneOf(&["box", "lattice"]))], "lengths in box or lattice units"),
        kw("force", &[], "allow it after a restart file with per-atom fix data"),
    ]),
    command("comm_modify KEYWORD VALUE ...", "communication settings (accepted; one process)"),
    command("communicate single|multi [vel yes|no] [cutoff C]", "communication settings (accepted; one process)"),
    with(command("compute_modify ID KEYWORD VALUE ...", "change a compute's settings (thermo_temp and thermo_kin_eng exist from the start)"), &[
        kw("extra", &[arg("N", Value::Int)], "degrees of freedom subtracted from 3N in a temperature"),
        kw("dynamic", &[arg("yes|no", YES_NO)], "count the group's atoms at every evaluation"),
        kw("thermo", &[arg("yes|no", YES_NO)], "fix energies in compute pe (granular fixes add none)"),
    ]),
    command("create_atoms TYPE box|region ID|single X Y Z|random N SEED REGION", "place particles on the lattice, at a point or at random"),
    command("create_box N REGION", "define the simulation box from a region, with N atom types"),
    command("delete_atoms group|region|overlap ...", "remove particles"),
    command("dimension 2|3", "the dimension (2: discs moving in the xy plane; z periodic)"),
    command("displace_atoms GROUP move|random ...", "move particles by a displacement or at random"),
    command("replicate NX NY NZ offset OX OY OZ shift SX SY SZ", "copy the particles NX x NY x NZ times, each copy moved by multiples of the offset (length), the box grown from its corner moved by the shift"),
    with(command("dump_modify ID KEYWORD VALUE ...", "change a dump's settings"), &[
        kw("every", &[arg("N", Value::Int)], "steps between snapshots"),
        kw("first", &[arg("yes|no", YES_NO)], "write on the first step of the run"),
        kw("format", &[arg("FORMAT", Value::Word)], "C format of a line"),
        kw("pad", &[arg("N", Value::Int)], "zero-pad step numbers in file names"),
        kw("sort", &[arg("id|off", Value::OneOf(&["id", "off"]))], "order of particles"),
        kw("element", &[arg("NAME ...", Value::Word)], "element names per type"),
        kw("binary", &[arg("yes|no", YES_NO)], "custom/vtk: binary legacy files, base64 arrays in XML files"),
    ]),
    with(command("fix_modify ID KEYWORD VALUE ...", "change the settings every fix shares"), &[
        kw("energy", &[arg("yes|no", YES_NO)], "the fix's energy in compute pe (granular fixes add none; yes on gravity or addforce: not supported yet)"),
        kw("servo/integrate", &[arg("start|stop", Value::OneOf(&["start", "stop"]))], "mesh/surface/stress/servo: the servo moves or stays (without servo/: LIGGGHTS's deprecation warning)"),
        kw("servo/vel_max", &[arg("V", VELOCITY)], "mesh/surface/stress/servo: the speed limit"),
        kw("servo/target_val", &[arg("F", Value::Real("force"))], "mesh/surface/stress/servo: the force set point (resets the error integral)"),
        kw("servo/ctrlParam", &[arg("KP KI KD", NUMBER)], "mesh/surface/stress/servo: the PID gains (resets the error integral)"),
        kw("servo/ratio", &[arg("R", NUMBER)], "mesh/surface/stress/servo: the auto mode's slow speed in smallest radii per step"),
    ]),
    command("group ID region|type|id|subtract|union|intersect|variable|initialize|delete ...", "define a group of particles"),
    command("hard_particles yes|no", "refuse particles stiffer than LIGGGHTS's limit"),
    style("lattice", "bcc", "lattice bcc SCALE", &[kw("origin", &[arg("X Y Z", NUMBER)], "offset in lattice units")], "body-centred cubic lattice of spacing SCALE (length)"),
    style("lattice", "custom", "lattice custom SCALE basis X Y Z ...", &[kw("a1", &[arg("X Y Z", NUMBER)], "first primitive vector (lattice units)"), kw("a2", &[arg("X Y Z", NUMBER)], "second primitive vector"), kw("a3", &[arg("X Y Z", NUMBER)], "third primitive vector"), kw("basis", &[arg("X Y Z", NUMBER)], "a basis point (fractions of the cell, repeatable)"), kw("origin", &[arg("X Y Z", NUMBER)], "offset in lattice spacings")], "a lattice of primitive vectors a1 a2 a3 scaled by SCALE (length) with basis points"),
    style("lattice", "fcc", "lattice fcc SCALE", &[kw("origin", &[arg("X Y Z", NUMBER)], "offset in lattice units")], "face-centred cubic lattice of spacing SCALE (length)"),
    style("lattice", "none", "lattice none SCALE", &[], "no lattice; SCALE (length) is the unit of lattice lengths"),
    style("lattice", "sq", "lattice sq SCALE", &[kw("origin", &[arg("X Y 0", NUMBER)], "offset in lattice units")], "square lattice of spacing SCALE (length; 2d only)"),
    style("lattice", "sq2", "lattice sq2 SCALE", &[kw("origin", &[arg("X Y 0", NUMBER)], "offset in lattice units")], "centred square lattice of spacing SCALE (length; 2d only)"),
    style("lattice", "hex", "lattice hex SCALE", &[kw("origin", &[arg("X Y 0", NUMBER)], "offset in lattice units")], "hexagonal lattice: cell SCALE by SCALE*sqrt(3) (length; 2d only)"),
    style("lattice", "sc", "lattice sc SCALE", &[kw("origin", &[arg("X Y Z", NUMBER)], "offset in lattice units")], "simple cubic lattice of spacing SCALE (length)"),
    with(command("neigh_modify KEYWORD VALUE ...", "neighbour-list settings"), &[
        kw("delay", &[arg("N", Value::Int)], "steps before a rebuild is considered"),
        kw("every", &[arg("N", Value::Int)], "steps between rebuild checks"),
        kw("check", &[arg("yes|no", YES_NO)], "rebuild only when particles moved half the skin"),
        kw("exclude", &[arg("type|group ...", Value::Word)], "pairs left out of the list"),
        kw("binsize", &[arg("SIZE", LENGTH)], "neighbour bin size (0 for half the cutoff)"),
    ]),
    command("neighbor SKIN bin", "neighbour skin distance (length)"),
    command("newton on|off [on|off]", "Newton's third law settings (accepted)"),
    command("package fast N", "threads of the fast engine path"),
    with(command("pair_modify KEYWORD VALUE ...", "settings of the pair style"), &[
        kw("compute", &[arg("yes|no", YES_NO)], "no: the pair forces are not computed"),
        kw("mix", &[arg("geometric|arithmetic|sixthpower", Value::OneOf(&["geometric", "arithmetic", "sixthpower"]))], "mixing of coefficients (no effect on granular pair styles)"),
        kw("shift", &[arg("yes|no", YES_NO)], "energy shift at the cutoff (no effect on granular pair styles)"),
        kw("tail", &[arg("yes|no", YES_NO)], "tail corrections (no effect on granular pair styles)"),
        kw("table", &[arg("N", Value::Int)], "bits of a lookup table (no effect on granular pair styles)"),
        kw("table/disp", &[arg("N", Value::Int)], "bits of a lookup table (no effect on granular pair styles)"),
        kw("tabinner", &[arg("R", LENGTH)], "inner cutoff of a table (no effect on granular pair styles)"),
        kw("tabinner/disp", &[arg("R", LENGTH)], "inner cutoff of a table (no effect on granular pair styles)"),
    ]),
    command("pair_coeff I J", "set the type pairs I,J (N, *, N*, *N or M*N; coefficients come from fix property/global); a run needs every I,I set"),
    style("pair_style", "gran", "pair_style gran model M tangential T [cohesion C] [rolling_friction R] [surface S] [SETTING on|off ...]", &[kw("model", &[arg("M", Value::Word)], "normal contact model"), kw("tangential", &[arg("T", Value::Word)], "tangential contact model"), kw("cohesion", &[arg("C", Value::Word)], "cohesion model"), kw("rolling_friction", &[arg("R", Value::Word)], "rolling-friction model"), kw("surface", &[arg("S", Value::Word)], "surface model")], "granular contact forces between particles"),
    command("processors Px Py Pz", "processor grid (accepted; one process)"),
    with(command("balance THRESH shift DIMS NITER STOPTHRESH | balance THRESH x uniform|C1 ... [y ...] [z ...]", "move the processor grid's cuts so that each MPI rank holds an even share of the particles (LAMMPS's static balancing; one process: imbalance 1)"), &[
        kw("weight", &[arg("time", Value::OneOf(&["time"])), arg("FACTOR", NUMBER)], "weigh each rank's particles by its time per particle in the last run, stretched by FACTOR"),
    ]),
    command("read_data FILE", "read particles and box from a data file"),
    with(command("read_dump FILE NSTEP FIELD ... (x y z vx vy vz omegax omegay omegaz radius mass density ix iy iz fx fy fz; radius required)", "overwrite particles from the snapshot of step NSTEP in a native text dump (plain or .gz); the step becomes NSTEP"), &[
        kw("box", &[arg("yes|no", YES_NO)], "take the snapshot's box (default yes)"),
        kw("replace", &[arg("yes|no", YES_NO)], "overwrite the fields of particles in the snapshot (default yes)"),
        kw("purge", &[arg("yes|no", YES_NO)], "delete all particles first (needs replace no, trim no)"),
        kw("trim", &[arg("yes|no", YES_NO)], "delete particles not in the snapshot (default no)"),
        kw("add", &[arg("no", Value::OneOf(&["no"]))], "add snapshot particles not in the simulation (only no)"),
        kw("scaled", &[arg("yes|no", YES_NO)], "accepted; scaling comes from the column labels"),
        kw("wrapped", &[arg("yes|no", YES_NO)], "accepted; wrapping comes from the column labels"),
        kw("format", &[arg("native", Value::OneOf(&["native"]))], "the reader (last keyword)"),
    ]),
    command("read_restart FILE", "continue from a LIGGGHTS restart file"),
    style("region", "block", "region ID block XLO XHI YLO YHI ZLO ZHI", &[kw("side", &[arg("in|out", Value::OneOf(&["in", "out"]))], "inside or outside"), kw("units", &[arg("box|lattice", Value::OneOf(&["box", "lattice"]))], "lengths in box or lattice units")], "a box (bounds in length, INF for unbounded)"),
    style("region", "cone", "region ID cone x|y|z C1 C2 RLO RHI LO HI", &[kw("side", &[arg("in|out", Value::OneOf(&["in", "out"]))], "inside or outside")], "a truncated cone (length)"),
    style("region", "cylinder", "region ID cylinder x|y|z C1 C2 RADIUS LO HI", &[kw("side", &[arg("in|out", Value::OneOf(&["in", "out"]))], "inside or outside")], "a cylinder (length; RADIUS may be v_NAME)"),
    style("region", "intersect", "region ID intersect N REGION ...", &[kw("side", &[arg("in|out", Value::OneOf(&["in", "out"]))], "inside or outside")], "the intersection of regions"),
    style("region", "mesh/tet", "region ID mesh/tet file FILE scale S move DX DY DZ rotate AX AY AZ units box", &[], "the tetrahedra of a legacy ASCII VTK file (moved, scaled, rotated in degrees; length)"),
    style("region", "plane", "region ID plane PX PY PZ NX NY NZ", &[kw("side", &[arg("in|out", Value::OneOf(&["in", "out"]))], "inside or outside")], "the half-space behind a plane (point in length)"),
    style("region", "prism", "region ID prism XLO XHI YLO YHI ZLO ZHI XY XZ YZ", &[kw("side", &[arg("in|out", Value::OneOf(&["in", "out"]))], "inside or outside")], "a parallelepiped (length)"),
    style("region", "sphere", "region ID sphere X Y Z RADIUS", &[kw("side", &[arg("in|out", Value::OneOf(&["in", "out"]))], "inside or outside")], "a sphere (length; RADIUS may be v_NAME)"),
    style("region", "union", "region ID union N REGION ...", &[kw("side", &[arg("in|out", Value::OneOf(&["in", "out"]))], "inside or outside")], "the union of regions"),
    style("region", "wedge", "region ID wedge axis x|y|z center C1 C2 radius R bounds LO HI angle0 A0 angle DA", &[kw("side", &[arg("in|out", Value::OneOf(&["in", "out"]))], "inside or outside"), kw("units", &[arg("box|lattice", Value::OneOf(&["box", "lattice"]))], "lengths in box or lattice units")], "the part of a cylinder between two half-planes through its axis, from angle A0 over DA degrees (length; LO, HI may be INF or EDGE)"),
    command("reset_timestep N", "set the step counter"),
    command("restart 0 | restart N ROOT | restart N FILE1 FILE2", "write restart files every N steps"),
    with(command("run N", "run N time steps"), &[
        kw("upto", &[], "N is the final step, not a count"),
        kw("start", &[arg("STEP", Value::Int)], "first step for time-dependent settings"),
        kw("stop", &[arg("STEP", Value::Int)], "last step for time-dependent settings"),
        kw("pre", &[arg("yes|no", YES_NO)], "set up before the run"),
        kw("post", &[arg("yes|no", YES_NO)], "print statistics after the run"),
    ]),
    command("set atom|type|group|region ID KEYWORD VALUE ...", "change per-particle values (type, diameter, density, velocity ...)"),
    command("soft_particles yes|no", "allow particles softer than LIGGGHTS's limit"),
    command("suffix fast|off", "the fast engine path on or off"),
    command("thermo N", "print thermo output every N steps"),
    with(command("thermo_modify KEYWORD VALUE ...", "thermo output settings"), &[
        kw("norm", &[arg("yes|no", YES_NO)], "divide extensive values by the atom count"),
        kw("lost", &[arg("ignore|warn|error", Value::OneOf(&["ignore", "warn", "error"]))], "what to do with lost particles"),
        kw("format", &[arg("int|float|N FORMAT", Value::Word)], "C formats of the columns"),
        kw("flush", &[arg("yes|no", YES_NO)], "flush the output after each line"),
        kw("line", &[arg("one|multi", Value::OneOf(&["one", "multi"]))], "one or several lines per output"),
    ]),
    command("thermo_style one|multi|custom KEYWORD ...", "columns of thermo output"),
    command("timestep DT", "the time step (time)"),
    command("uncompute ID", "delete a compute"),
    command("undump ID", "delete a dump"),
    command("thermo_log FILE [append] | none", "a log of the thermo output alone"),
    command("modify_timing on|off|verbose", "per-fix timing: the fixes LIGGGHTS lists (its own among them) with their times after each run"),
    command("unfix ID", "delete a fix"),
    command("units si|cgs", "unit system of the deck"),
    command("velocity GROUP create|set|zero|ramp ...", "set particle velocities (velocity)"),
    command("write_data FILE", "write particles and box to a data file"),
    command("write_dump GROUP STYLE FILE ARGS ... [modify KEYWORD VALUE ...]", "write one dump snapshot now"),
    command("write_restart FILE", "write a LIGGGHTS restart file"),
];

/// Every declared spec: [`SPECS`], with the module fix styles' rows
/// ([`crate::commands::fix::TABLE`]) before `fix_modify`, the compute styles'
/// rows ([`crate::commands::compute::TABLE`]) before `compute_modify` and the dump
/// styles' rows ([`crate::commands::dump::TABLE`]) before `dump_modify`.
pub fn all() -> impl Iterator<Item = &'static Spec> {
    let computes = SPECS
        .iter()
        .position(|s| s.command == "compute_modify")
        .unwrap_or(SPECS.len());
    let dumps = SPECS
        .iter()
        .position(|s| s.command == "dump_modify")
        .unwrap_or(SPECS.len());
    let fixes = SPECS
        .iter()
        .position(|s| s.command == "fix_modify")
        .unwrap_or(SPECS.len());
    let fix_modules = crate::commands::fix::TABLE.specs();
    let compute_modules = crate::commands::compute::TABLE.specs();
    let dump_modules = crate::commands::dump::TABLE.specs();
    debug_assert!(
        computes <= dumps && dumps <= fixes,
        "compute styles come before dump styles, and those before fix styles, in SPECS"
    );
    SPECS[..computes]
        .iter()
        .chain(compute_modules)
        .chain(SPECS[computes..dumps].iter())
        .chain(dump_modules)
        .chain(SPECS[dumps..fixes].iter())
        .chain(fix_modules)
        .chain(SPECS[fixes..].iter())
}

/// The spec of `command` (with `style`, for styled commands).
pub fn find(command: &str, style: Option<&str>) -> Option<&'static Spec> {
    all().find(|spec| spec.command == command && spec.style == style)
}

/// Whether any spec declares styles for `command`.
pub fn is_styled(command: &str) -> bool {
    all().any(|spec| spec.command == command && spec.style.is_some())
}

/// The styles declared for `command`, in table order.
pub fn styles(command: &str) -> Vec<&'static str> {
    all()
        .filter(|spec| spec.command == command)
        .filter_map(|spec| spec.style)
        .collect()
}

/// The commands declared, each once, in table order.
pub fn commands() -> Vec<&'static str> {
    let mut names: Vec<&'static str> = Vec::new();
    for spec in all() {
        if !names.contains(&spec.command) {
            names.push(spec.command);
        }
    }
    names
}

/// A keyword's arguments as a usage fragment (`seed SEED`).
fn keyword_usage(keyword: &Keyword) -> String {
    let mut text = keyword.name.to_string();
    for a in keyword.args {
        text.push(' ');
        text.push_str(a.name);
    }
    text
}

/// What an argument's kind says in help (`length`, `yes|no`, `region ID`).
fn value_label(value: Value) -> String {
    match value {
        Value::Int => "integer".into(),
        Value::Real("") => "number".into(),
        Value::Real(quantity) => quantity.into(),
        Value::OneOf(words) => words.join("|"),
        Value::Id(what) => format!("{what} ID"),
        Value::File => "file".into(),
        Value::Word => "word".into(),
    }
}

/// The help text of one spec: usage, description and keywords.
pub fn render(spec: &Spec) -> String {
    let mut text = format!("{}\n    {}\n", spec.usage, spec.about);
    if !spec.keywords.is_empty() {
        text.push_str("keywords:\n");
        for keyword in spec.keywords {
            let kinds: Vec<String> = keyword.args.iter().map(|a| value_label(a.value)).collect();
            let kinds = if kinds.is_empty() {
                String::new()
            } else {
                format!(" [{}]", kinds.join(", "))
            };
            text.push_str(&format!(
                "  {:<32} {}{kinds}\n",
                keyword_usage(keyword),
                keyword.about
            ));
        }
    }
    text
}

/// `regolith help [COMMAND [STYLE]]`: every command, one command's styles, or one
/// signature; a name not declared gets the nearest declared ones.
pub fn help(words: &[&str]) -> Result<String, UnknownName> {
    match words {
        [] => Ok(overview()),
        [command] => {
            let command = known(command, &commands(), "command")?;
            if is_styled(command) {
                let mut text = format!("{command} styles regolith runs:\n");
                for spec in all().filter(|s| s.command == command) {
                    let name = spec.style.unwrap_or("");
                    text.push_str(&format!("  {name:<44} {}\n", spec.about));
                }
                text.push_str(&format!("`regolith help {command} STYLE` shows one.\n"));
                Ok(text)
            } else {
                Ok(render(find(command, None).expect("declared")))
            }
        }
        [command, style, ..] => {
            let command = known(command, &commands(), "command")?;
            let style = known(style, &styles(command), &format!("{command} style"))?;
            Ok(render(find(command, Some(style)).expect("declared")))
        }
    }
}

/// `word` if it is one of `names`, else an error with the nearest ones.
fn known<'a>(word: &str, names: &[&'a str], what: &str) -> Result<&'a str, UnknownName> {
    if let Some(&name) = names.iter().find(|&&n| n == word) {
        return Ok(name);
    }
    Err(UnknownName {
        what: what.to_string(),
        word: word.to_string(),
        hint: did_you_mean(word, names)
            .map(|h| format!("; {h}"))
            .unwrap_or_default(),
    })
}

/// A command or style `regolith help` was asked about that regolith does not declare.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("regolith runs no {what} '{word}'{hint}")]
pub struct UnknownName {
    /// What was looked for (`command`, `fix style`).
    pub what: String,
    /// The name given.
    pub word: String,
    /// The nearest declared names, as "; did you mean ...", or empty.
    pub hint: String,
}

/// Every command regolith runs, with its styles.
fn overview() -> String {
    let mut text = String::from(
        "Commands regolith runs (besides the script language: variable, print, if, jump, ...).\n\
         `regolith help COMMAND [STYLE]` shows one.\n",
    );
    for command in commands() {
        match find(command, None) {
            Some(spec) => text.push_str(&format!("  {command:<16} {}\n", spec.about)),
            None => text.push_str(&format!("  {command:<16} {}\n", styles(command).join(" "))),
        }
    }
    text
}

/// The table of commands and styles for `compat/SUPPORT.md` (Markdown).
pub fn markdown() -> String {
    let mut text = String::from("| command | style | what it does |\n|---|---|---|\n");
    for spec in all() {
        text.push_str(&format!(
            "| `{}` | {} | {} |\n",
            spec.command,
            spec.style.map(|s| format!("`{s}`")).unwrap_or_default(),
            spec.about.replace('|', "\\|")
        ));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn help_prints_declared_keywords() {
        let text = help(&["fix", "wall/gran"]).unwrap();
        for word in ["model M", "primitive", "mesh", "shear", "granular walls"] {
            assert!(text.contains(word), "{word}:\n{text}");
        }
        let text = help(&["fix", "insert/stream"]).unwrap();
        assert!(
            text.contains("seed SEED") && text.contains("integer"),
            "{text}"
        );
        // styles written as modules print the signature of their own file
        let text = help(&["fix", "ave/time"]).unwrap();
        assert!(
            text.contains("NEVERY NREPEAT NFREQ") && text.contains("off M"),
            "{text}"
        );
        let text = help(&["fix", "massflow/mesh"]).unwrap();
        assert!(
            text.contains("vec_side") && text.contains("delete_atoms"),
            "{text}"
        );
        assert!(help(&["run"]).unwrap().contains("upto"));
        assert!(help(&["region"]).unwrap().contains("cylinder"));
        assert!(help(&[]).unwrap().contains("wall/gran"));
    }

    #[test]
    fn typos_get_the_nearest_names() {
        let e = help(&["fix", "wall/gren"]).unwrap_err();
        assert_eq!(
            (e.what.as_str(), e.word.as_str()),
            ("fix style", "wall/gren")
        );
        assert!(e.to_string().contains("did you mean 'wall/gran'?"), "{e}");
        let e = help(&["fix", "insert/strem"]).unwrap_err().to_string();
        assert!(e.contains("'insert/stream'"), "{e}");
        let e = help(&["neigh_modfy"]).unwrap_err().to_string();
        assert!(e.contains("'neigh_modify'"), "{e}");
    }

    #[test]
    fn every_spec_is_declared_once_and_reads_well() {
        let specs: Vec<&Spec> = all().collect();
        for (i, spec) in specs.iter().enumerate() {
            assert!(
                !specs[..i]
                    .iter()
                    .any(|s| s.command == spec.command && s.style == spec.style),
                "{} {:?} declared twice",
                spec.command,
                spec.style
            );
            assert!(spec.usage.starts_with(spec.command), "{}", spec.usage);
            if let Some(style) = spec.style {
                assert!(spec.usage.contains(style), "{}", spec.usage);
            }
            assert!(!spec.about.is_empty());
        }
    }
}
