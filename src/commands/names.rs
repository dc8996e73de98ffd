//! Every command and style name that Debian's LIGGGHTS 3.8.0 (`liggghts` 3.8.0, Debian build of
//! 2022-01-26) accepts, and the error it prints for a name it does not know.
//!
//! Generated once from the binary's own list (`liggghts -h`), the built-in commands of
//! `Input::execute_command` (src/input.cpp), and the manual (Section_commands.html,
//! Section_gran_models.html, atom_style.html, dump.html, region.html, run_style.html). Every name
//! was cross-checked against its registration macro in the LIGGGHTS sources (`FixStyle(...)`,
//! `NORMAL_MODEL(...)`, ...) and then fed to the binary one by one: a list holds exactly the names
//! the binary does not reject with its "unknown name" error. Kinds `-h` does not print (min, bond,
//! angle, dihedral, improper, kspace and dump-reader styles) and keywords that sit where a style
//! goes (`none`, `off`, `region ID delete`) were found the same way. Internal upper-case styles
//! (`fix ... STORE`) are left out, as `-h` leaves them out. All lists are sorted (byte order) and
//! free of duplicates.

/// Commands: the built-ins of `Input::execute_command` plus the command styles.
pub const COMMANDS: &[&str] = &[
    "angle_coeff",
    "angle_style",
    "atom_modify",
    "atom_style",
    "bond_coeff",
    "bond_style",
    "boundary",
    "box",
    "change_box",
    "clear",
    "communicate",
    "compute",
    "compute_modify",
    "create_atoms",
    "create_box",
    "delete_atoms",
    "delete_bonds",
    "dielectric",
    "dihedral_coeff",
    "dihedral_style",
    "dimension",
    "displace_atoms",
    "dump",
    "dump_modify",
    "echo",
    "fix",
    "fix_modify",
    "force_dt_reset",
    "group",
    "hard_particles",
    "if",
    "improper_coeff",
    "improper_style",
    "include",
    "info",
    "jump",
    "kspace_modify",
    "kspace_style",
    "label",
    "lattice",
    "log",
    "mass",
    "min_modify",
    "min_style",
    "minimize",
    "modify_timing",
    "neigh_modify",
    "neighbor",
    "newton",
    "next",
    "package",
    "pair_coeff",
    "pair_modify",
    "pair_style",
    "pair_write",
    "partition",
    "print",
    "processors",
    "quit",
    "read_data",
    "read_dump",
    "read_restart",
    "region",
    "replicate",
    "reset_timestep",
    "restart",
    "rotate",
    "run",
    "run_style",
    "run_time",
    "set",
    "shell",
    "soft_particles",
    "special_bonds",
    "suffix",
    "thermo",
    "thermo_log",
    "thermo_modify",
    "thermo_style",
    "timestep",
    "uncompute",
    "undump",
    "unfix",
    "units",
    "variable",
    "velocity",
    "write_data",
    "write_dump",
    "write_restart",
    "write_restart_on_signal",
];

/// `atom_style` names.
pub const ATOM_STYLES: &[&str] = &[
    "atomic",
    "charge",
    "ellipsoid",
    "full",
    "granular",
    "hybrid",
    "line",
    "molecular",
    "sph",
    "sph/var",
    "sphere",
    "tri",
];

/// `run_style` names (integrate styles).
pub const INTEGRATE_STYLES: &[&str] = &["respa", "verlet"];

/// `min_style` names (not printed by `-h`; from the sources, checked against the binary).
pub const MINIMIZE_STYLES: &[&str] = &["cg"];

/// `pair_style` names, plus `none`.
pub const PAIR_STYLES: &[&str] = &[
    "bubble",
    "gran",
    "gran_bubble",
    "hybrid",
    "hybrid/overlay",
    "line/lj",
    "none",
    "soft",
    "sph/artVisc/tensCorr",
];

/// `bond_style` names, plus `none` (not printed by `-h`; checked against the binary).
pub const BOND_STYLES: &[&str] = &["harmonic", "hybrid", "none"];

/// `angle_style` names, plus `none` (not printed by `-h`; checked against the binary).
pub const ANGLE_STYLES: &[&str] = &["hybrid", "none"];

/// `dihedral_style` names, plus `none` (not printed by `-h`; checked against the binary).
pub const DIHEDRAL_STYLES: &[&str] = &["hybrid", "none"];

/// `improper_style` names, plus `none` (not printed by `-h`; checked against the binary).
pub const IMPROPER_STYLES: &[&str] = &["hybrid", "none"];

/// `kspace_style` names: no long-range solver is compiled in, only `none` is accepted.
pub const KSPACE_STYLES: &[&str] = &["none"];

/// Normal contact models (`model ...` of `pair_style gran` / `fix wall/gran`), plus `off`.
pub const GRAN_NORMAL_MODELS: &[&str] = &[
    "edinburgh",
    "edinburgh/stiffness",
    "hertz",
    "hertz/stiffness",
    "hooke",
    "hooke/hysteresis",
    "hooke/stiffness",
    "luding",
    "off",
    "thornton_ning",
];

/// Tangential contact models (`tangential ...`), plus `off`.
pub const GRAN_TANGENTIAL_MODELS: &[&str] = &["history", "no_history", "off", "tan_luding"];

/// Cohesion models (`cohesion ...`), plus `off`.
pub const GRAN_COHESION_MODELS: &[&str] = &[
    "easo/capillary/viscous",
    "off",
    "sjkr",
    "sjkr2",
    "washino/capillary/viscous",
];

/// Rolling-friction models (`rolling_friction ...`), plus `off`.
pub const GRAN_ROLLING_MODELS: &[&str] = &["cdt", "epsd", "epsd2", "epsd3", "luding", "off"];

/// Surface models (`surface ...`); there is no `off`.
pub const GRAN_SURFACE_MODELS: &[&str] = &["default", "multicontact", "superquadric"];

/// `fix` style names (`fix ID group STYLE ...`).
pub const FIX_STYLES: &[&str] = &[
    "adapt",
    "addforce",
    "ave/atom",
    "ave/correlate",
    "ave/euler",
    "ave/euler/stress",
    "ave/histo",
    "ave/spatial",
    "ave/time",
    "aveforce",
    "box/relax",
    "buoyancy",
    "check/timestep/gran",
    "check/timestep/sph",
    "concave",
    "contacthistory",
    "contacthistory/mesh",
    "contactproperty/atom",
    "contactproperty/atom/wall",
    "continuum/weighted",
    "couple/cfd",
    "couple/cfd/convection",
    "couple/cfd/convectiveImpl",
    "couple/cfd/dragforce",
    "couple/cfd/force",
    "couple/cfd/force/implicit",
    "couple/cfd/radiation",
    "couple/cfd/speciesConvection",
    "couple/lb/onetoone",
    "custom_property/global",
    "deform",
    "deform/check",
    "diam/max",
    "drag",
    "dt/reset",
    "efield",
    "enforce2d",
    "external",
    "fiber/spring/simple",
    "freeze",
    "gravity",
    "heat/gran",
    "heat/gran/conduction",
    "insert/pack",
    "insert/rate/region",
    "insert/stream",
    "lineforce",
    "massflow/mesh",
    "massflow/mesh/sieve",
    "mesh/surface",
    "mesh/surface/planar",
    "momentum",
    "move",
    "move/mesh",
    "move/mesh/file",
    "move/mesh/gran",
    "multicontact/halfspace",
    "multisphere",
    "multisphere/break",
    "multisphere/nointegration",
    "neighlist/mesh",
    "nve",
    "nve/asphere",
    "nve/asphere/noforce",
    "nve/limit",
    "nve/line",
    "nve/noforce",
    "nve/sph",
    "nve/sph/stationary",
    "nve/sphere",
    "particledistribution/discrete",
    "particledistribution/discrete/massbased",
    "particledistribution/discrete/numberbased",
    "particletemplate/multiplespheres",
    "particletemplate/multisphere",
    "particletemplate/sphere",
    "planeforce",
    "print",
    "property/atom",
    "property/atom/regiontracer/time",
    "property/atom/timetracer",
    "property/atom/tracer",
    "property/atom/tracer/stream",
    "property/atomtype",
    "property/atomtypepair",
    "property/global",
    "region/variable",
    "rigid",
    "setforce",
    "sph/density/continuity",
    "sph/density/corr",
    "sph/density/summation",
    "sph/pressure",
    "spring",
    "spring/rg",
    "spring/self",
    "store/force",
    "store/state",
    "transportequation/scalar",
    "viscous",
    "wall/gran",
    "wall/region",
    "wall/region/sph",
    "wall/sph",
];

/// `compute` style names (`compute ID group STYLE ...`).
pub const COMPUTE_STYLES: &[&str] = &[
    "atom/molecule",
    "bond/local",
    "centro/atom",
    "cluster/atom",
    "cna/atom",
    "com",
    "com/molecule",
    "contact/atom",
    "contact/atom/gran",
    "coord/atom",
    "displace/atom",
    "erotate",
    "erotate/asphere",
    "erotate/multisphere",
    "erotate/sphere",
    "erotate/sphere/atom",
    "group/group",
    "gyration",
    "gyration/molecule",
    "inertia/molecule",
    "ke",
    "ke/atom",
    "ke/multisphere",
    "msd",
    "msd/molecule",
    "multisphere",
    "multisphere/single",
    "nparticles/tracer/region",
    "pair/gran/local",
    "pe",
    "pe/atom",
    "pressure",
    "property/atom",
    "property/local",
    "property/molecule",
    "rdf",
    "reduce",
    "reduce/region",
    "reduce/sph",
    "rigid",
    "slice",
    "stress/atom",
    "temp",
    "wall/gran/local",
];

/// `region` style names, plus `delete` (`region ID delete`).
pub const REGION_STYLES: &[&str] = &[
    "block",
    "cone",
    "cylinder",
    "delete",
    "intersect",
    "mesh/tet",
    "plane",
    "prism",
    "sphere",
    "union",
    "wedge",
];

/// `dump` style names (`dump ID group STYLE N file ...`).
pub const DUMP_STYLES: &[&str] = &[
    "atom/vtk",
    "custom",
    "custom/vtk",
    "custom/vtm",
    "decomposition/vtk",
    "euler/vtk",
    "image",
    "local",
    "local/gran/vtk",
    "mesh/gran/VTK",
    "mesh/stl",
    "mesh/vtk",
    "mesh/vtm",
    "movie",
    "stl",
    "xyz",
];

/// `read_dump ... format` reader styles (not printed by `-h`; checked against the binary).
pub const READER_STYLES: &[&str] = &["native", "xyz"];

// ---------------------------------------------------------------------------------------------
// Names LIGGGHTS 3.8.0 does not have either: in its manual or registered by an optional source
// package (POEMS, VORONOI, PASCAL, superquadric, extra SPH files), but rejected by the binary.

/// Command names documented or in the sources but rejected by the Debian binary.
pub const DOC_ONLY_COMMANDS: &[&str] = &["neigh_settings", "neighbor_skin", "orient", "origin"];

/// Atom style names documented or in the sources but rejected by the Debian binary.
pub const DOC_ONLY_ATOM_STYLES: &[&str] = &[
    "bond",
    "bond/gran",
    "convexhull",
    "granular_superquadric",
    "superquadric",
];

/// Pair style names documented or in the sources but rejected by the Debian binary.
pub const DOC_ONLY_PAIR_STYLES: &[&str] = &["sph/morris/tensCorr"];

/// Surface model names documented or in the sources but rejected by the Debian binary.
pub const DOC_ONLY_GRAN_SURFACE_MODELS: &[&str] = &["sphere"];

/// Fix style names documented or in the sources but rejected by the Debian binary.
pub const DOC_ONLY_FIX_STYLES: &[&str] = &[
    "bond/break",
    "bond/create",
    "couple/pascal",
    "nve/superquadric",
    "particletemplate/superquadric",
    "poems",
    "rigid/nph",
    "rigid/npt",
    "rigid/nve",
    "rigid/nvt",
    "rigid/small",
    "sph/density/drift/corr",
    "sph/integrity",
    "sph/mixidx",
    "sph/velgrad",
    "wall/reflect",
    "wall/sph/general",
    "wall/sph/general/gap",
];

/// Compute style names documented or in the sources but rejected by the Debian binary.
pub const DOC_ONLY_COMPUTE_STYLES: &[&str] = &[
    "coord/gran",
    "erotate/superquadric",
    "msd/nongauss",
    "voronoi/atom",
];

/// Dump style names documented or in the sources but rejected by the Debian binary.
pub const DOC_ONLY_DUMP_STYLES: &[&str] = &["atom"];

// ---------------------------------------------------------------------------------------------
// What LIGGGHTS 3.8.0 prints for a name it does not know (captured from the Debian binary; each is
// printed as `ERROR: <message> (<source location>)`).

/// Unknown command; LIGGGHTS appends the input line as read: variables not substituted, comment and
/// leading blanks kept, trailing blanks dropped, `&` lines joined (`ERROR: Unknown command: foo
/// ${a} # c (./src/input.cpp:259)`).
pub const LIGGGHTS_UNKNOWN_COMMAND: &str = "Unknown command: ";

/// Unknown atom style (./src/atom.cpp:459).
pub const LIGGGHTS_UNKNOWN_ATOM_STYLE: &str = "Invalid atom style";

/// Unknown run style (./src/update.cpp:400).
pub const LIGGGHTS_UNKNOWN_INTEGRATE_STYLE: &str = "Illegal integrate style";

/// Unknown `min_style` (./src/update.cpp:421).
pub const LIGGGHTS_UNKNOWN_MINIMIZE_STYLE: &str = "Illegal min_style command";

/// Unknown pair style (./src/force.cpp:247).
pub const LIGGGHTS_UNKNOWN_PAIR_STYLE: &str = "Invalid pair style";

/// Unknown bond style (./src/force.cpp:387).
pub const LIGGGHTS_UNKNOWN_BOND_STYLE: &str = "Invalid bond style";

/// Unknown angle style (./src/force.cpp:463).
pub const LIGGGHTS_UNKNOWN_ANGLE_STYLE: &str = "Invalid angle style";

/// Unknown dihedral style (./src/force.cpp:525).
pub const LIGGGHTS_UNKNOWN_DIHEDRAL_STYLE: &str = "Invalid dihedral style";

/// Unknown improper style (./src/force.cpp:586).
pub const LIGGGHTS_UNKNOWN_IMPROPER_STYLE: &str = "Invalid improper style";

/// Unknown kspace style (./src/force.cpp:647).
pub const LIGGGHTS_UNKNOWN_KSPACE_STYLE: &str = "Invalid kspace style";

/// Unknown `model`/`tangential`/`cohesion`/`rolling_friction`/`surface` name of `pair_style gran`
/// (./src/pair_gran_proxy.cpp:70); `fix wall/gran` prefixes it with `Fix wall/gran (id ID): `.
pub const LIGGGHTS_UNKNOWN_GRAN_MODEL: &str =
    "Invalid model specified (check for typos and enable at least one model)";

/// Unknown fix style; LIGGGHTS appends `: "STYLE"`: `ERROR: Invalid fix style: "foo"
/// (./src/modify.cpp:850)`.
pub const LIGGGHTS_UNKNOWN_FIX: &str = "Invalid fix style";

/// Unknown compute style (./src/modify.cpp:1024).
pub const LIGGGHTS_UNKNOWN_COMPUTE: &str = "Invalid compute style";

/// Unknown region style (./src/domain.cpp:1377).
pub const LIGGGHTS_UNKNOWN_REGION: &str = "Invalid region style";

/// Unknown dump style (./src/output.cpp:634).
pub const LIGGGHTS_UNKNOWN_DUMP: &str = "Invalid dump style";

/// Unknown dump reader style (./src/read_dump.cpp:354).
pub const LIGGGHTS_UNKNOWN_READER_STYLE: &str = "Invalid dump reader style";

/// Prefix LIGGGHTS 3.8.0 puts before [`LIGGGHTS_UNKNOWN_GRAN_MODEL`] when `fix wall/gran` raises it
/// (`Fix wall/gran (id ID): ...`, from `Error::fix_error`).
pub const LIGGGHTS_WALL_GRAN_PREFIX: &str = "Fix wall/gran (id ";

/// The kinds of names LIGGGHTS looks up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NameKind {
    /// Command.
    Command,
    /// Atom style.
    AtomStyle,
    /// Run style.
    IntegrateStyle,
    /// Min style.
    MinimizeStyle,
    /// Pair style.
    PairStyle,
    /// Bond style.
    BondStyle,
    /// Angle style.
    AngleStyle,
    /// Dihedral style.
    DihedralStyle,
    /// Improper style.
    ImproperStyle,
    /// Kspace style.
    KSpaceStyle,
    /// Normal contact model.
    GranNormalModel,
    /// Tangential contact model.
    GranTangentialModel,
    /// Cohesion model.
    GranCohesionModel,
    /// Rolling-friction model.
    GranRollingModel,
    /// Surface model.
    GranSurfaceModel,
    /// Fix style.
    FixStyle,
    /// Compute style.
    ComputeStyle,
    /// Region style.
    RegionStyle,
    /// Dump style.
    DumpStyle,
    /// Dump reader style.
    ReaderStyle,
}

impl NameKind {
    /// Every kind.
    pub const ALL: [NameKind; 20] = [
        NameKind::Command,
        NameKind::AtomStyle,
        NameKind::IntegrateStyle,
        NameKind::MinimizeStyle,
        NameKind::PairStyle,
        NameKind::BondStyle,
        NameKind::AngleStyle,
        NameKind::DihedralStyle,
        NameKind::ImproperStyle,
        NameKind::KSpaceStyle,
        NameKind::GranNormalModel,
        NameKind::GranTangentialModel,
        NameKind::GranCohesionModel,
        NameKind::GranRollingModel,
        NameKind::GranSurfaceModel,
        NameKind::FixStyle,
        NameKind::ComputeStyle,
        NameKind::RegionStyle,
        NameKind::DumpStyle,
        NameKind::ReaderStyle,
    ];
}

/// All names of one kind that LIGGGHTS 3.8.0 accepts, sorted.
pub fn names(kind: NameKind) -> &'static [&'static str] {
    match kind {
        NameKind::Command => COMMANDS,
        NameKind::AtomStyle => ATOM_STYLES,
        NameKind::IntegrateStyle => INTEGRATE_STYLES,
        NameKind::MinimizeStyle => MINIMIZE_STYLES,
        NameKind::PairStyle => PAIR_STYLES,
        NameKind::BondStyle => BOND_STYLES,
        NameKind::AngleStyle => ANGLE_STYLES,
        NameKind::DihedralStyle => DIHEDRAL_STYLES,
        NameKind::ImproperStyle => IMPROPER_STYLES,
        NameKind::KSpaceStyle => KSPACE_STYLES,
        NameKind::GranNormalModel => GRAN_NORMAL_MODELS,
        NameKind::GranTangentialModel => GRAN_TANGENTIAL_MODELS,
        NameKind::GranCohesionModel => GRAN_COHESION_MODELS,
        NameKind::GranRollingModel => GRAN_ROLLING_MODELS,
        NameKind::GranSurfaceModel => GRAN_SURFACE_MODELS,
        NameKind::FixStyle => FIX_STYLES,
        NameKind::ComputeStyle => COMPUTE_STYLES,
        NameKind::RegionStyle => REGION_STYLES,
        NameKind::DumpStyle => DUMP_STYLES,
        NameKind::ReaderStyle => READER_STYLES,
    }
}

/// Names of one kind that are in the manual or the sources but not in the binary, sorted.
pub fn doc_only(kind: NameKind) -> &'static [&'static str] {
    match kind {
        NameKind::Command => DOC_ONLY_COMMANDS,
        NameKind::AtomStyle => DOC_ONLY_ATOM_STYLES,
        NameKind::PairStyle => DOC_ONLY_PAIR_STYLES,
        NameKind::GranSurfaceModel => DOC_ONLY_GRAN_SURFACE_MODELS,
        NameKind::FixStyle => DOC_ONLY_FIX_STYLES,
        NameKind::ComputeStyle => DOC_ONLY_COMPUTE_STYLES,
        NameKind::DumpStyle => DOC_ONLY_DUMP_STYLES,
        _ => &[],
    }
}

/// Whether LIGGGHTS 3.8.0 accepts `name` as a name of this kind.
pub fn is_known(kind: NameKind, name: &str) -> bool {
    names(kind).binary_search(&name).is_ok()
}

/// Whether `name` is documented (or in the sources) for this kind but missing from LIGGGHTS 3.8.0.
pub fn is_doc_only(kind: NameKind, name: &str) -> bool {
    doc_only(kind).binary_search(&name).is_ok()
}

/// The words used for a kind in messages ("fix style", "rolling-friction model", ...).
pub fn label(kind: NameKind) -> &'static str {
    match kind {
        NameKind::Command => "command",
        NameKind::AtomStyle => "atom style",
        NameKind::IntegrateStyle => "run style",
        NameKind::MinimizeStyle => "min style",
        NameKind::PairStyle => "pair style",
        NameKind::BondStyle => "bond style",
        NameKind::AngleStyle => "angle style",
        NameKind::DihedralStyle => "dihedral style",
        NameKind::ImproperStyle => "improper style",
        NameKind::KSpaceStyle => "kspace style",
        NameKind::GranNormalModel => "normal contact model",
        NameKind::GranTangentialModel => "tangential contact model",
        NameKind::GranCohesionModel => "cohesion model",
        NameKind::GranRollingModel => "rolling-friction model",
        NameKind::GranSurfaceModel => "surface model",
        NameKind::FixStyle => "fix style",
        NameKind::ComputeStyle => "compute style",
        NameKind::RegionStyle => "region style",
        NameKind::DumpStyle => "dump style",
        NameKind::ReaderStyle => "dump reader style",
    }
}

/// The error text LIGGGHTS 3.8.0 prints (after `ERROR: `, before the source location) for an
/// unknown name of this kind. For [`NameKind::Command`] pass the whole input line as LIGGGHTS
/// read it: its message repeats the line, not just the command word.
pub fn liggghts_message(kind: NameKind, word: &str) -> String {
    match kind {
        NameKind::Command => format!("{LIGGGHTS_UNKNOWN_COMMAND}{word}"),
        NameKind::FixStyle => format!("{LIGGGHTS_UNKNOWN_FIX}: \"{word}\""),
        NameKind::AtomStyle => LIGGGHTS_UNKNOWN_ATOM_STYLE.into(),
        NameKind::IntegrateStyle => LIGGGHTS_UNKNOWN_INTEGRATE_STYLE.into(),
        NameKind::MinimizeStyle => LIGGGHTS_UNKNOWN_MINIMIZE_STYLE.into(),
        NameKind::PairStyle => LIGGGHTS_UNKNOWN_PAIR_STYLE.into(),
        NameKind::BondStyle => LIGGGHTS_UNKNOWN_BOND_STYLE.into(),
        NameKind::AngleStyle => LIGGGHTS_UNKNOWN_ANGLE_STYLE.into(),
        NameKind::DihedralStyle => LIGGGHTS_UNKNOWN_DIHEDRAL_STYLE.into(),
        NameKind::ImproperStyle => LIGGGHTS_UNKNOWN_IMPROPER_STYLE.into(),
        NameKind::KSpaceStyle => LIGGGHTS_UNKNOWN_KSPACE_STYLE.into(),
        NameKind::ComputeStyle => LIGGGHTS_UNKNOWN_COMPUTE.into(),
        NameKind::RegionStyle => LIGGGHTS_UNKNOWN_REGION.into(),
        NameKind::DumpStyle => LIGGGHTS_UNKNOWN_DUMP.into(),
        NameKind::ReaderStyle => LIGGGHTS_UNKNOWN_READER_STYLE.into(),
        NameKind::GranNormalModel
        | NameKind::GranTangentialModel
        | NameKind::GranCohesionModel
        | NameKind::GranRollingModel
        | NameKind::GranSurfaceModel => LIGGGHTS_UNKNOWN_GRAN_MODEL.into(),
    }
}

/// The same error as [`liggghts_message`] for a contact-model name given to `fix wall/gran`
/// with ID `fix_id`: `Fix wall/gran (id w): Invalid model specified (...)`.
pub fn liggghts_wall_gran_model_message(fix_id: &str) -> String {
    format!("{LIGGGHTS_WALL_GRAN_PREFIX}{fix_id}): {LIGGGHTS_UNKNOWN_GRAN_MODEL}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_are_sorted_and_unique() {
        for kind in NameKind::ALL {
            for list in [names(kind), doc_only(kind)] {
                assert!(
                    list.windows(2).all(|w| w[0] < w[1]),
                    "{kind:?} not sorted/unique"
                );
            }
            assert!(!names(kind).is_empty(), "{kind:?} empty");
            for n in doc_only(kind) {
                assert!(!is_known(kind, n), "{kind:?} {n} both known and doc-only");
            }
        }
    }

    #[test]
    fn known_members() {
        assert!(is_known(NameKind::FixStyle, "insert/stream"));
        assert!(is_known(NameKind::FixStyle, "wall/gran"));
        assert!(is_known(NameKind::FixStyle, "nve/sphere"));
        assert!(is_known(NameKind::ComputeStyle, "stress/atom"));
        assert!(is_known(NameKind::PairStyle, "gran"));
        assert!(is_known(NameKind::DumpStyle, "custom"));
        assert!(is_known(NameKind::DumpStyle, "custom/vtk"));
        assert!(is_known(NameKind::DumpStyle, "mesh/gran/VTK"));
        assert!(is_known(NameKind::RegionStyle, "block"));
        assert!(is_known(NameKind::AtomStyle, "granular"));
        assert!(is_known(NameKind::GranNormalModel, "hertz"));
        assert!(is_known(NameKind::GranCohesionModel, "off"));
        assert!(is_known(NameKind::GranRollingModel, "epsd"));
        assert!(!is_known(NameKind::GranSurfaceModel, "off"));
        for c in [
            "run",
            "read_restart",
            "write_restart",
            "create_atoms",
            "print",
            "jump",
            "variable",
            "modify_timing",
        ] {
            assert!(is_known(NameKind::Command, c), "{c}");
        }
        assert!(!is_known(NameKind::FixStyle, "wall/reflect"));
        assert!(is_doc_only(NameKind::FixStyle, "wall/reflect"));
        assert!(is_doc_only(NameKind::Command, "orient"));
        assert!(!is_known(NameKind::Command, "comm_modify"));
    }

    #[test]
    fn counts_match_the_binary() {
        // `liggghts -h` of the Debian build; commands are 69 built-ins + 21 command styles
        assert_eq!(names(NameKind::Command).len(), 90);
        assert_eq!(names(NameKind::AtomStyle).len(), 12);
        assert_eq!(names(NameKind::IntegrateStyle).len(), 2);
        assert_eq!(names(NameKind::MinimizeStyle).len(), 1);
        assert_eq!(names(NameKind::PairStyle).len(), 9);
        assert_eq!(names(NameKind::BondStyle).len(), 3);
        assert_eq!(names(NameKind::AngleStyle).len(), 2);
        assert_eq!(names(NameKind::DihedralStyle).len(), 2);
        assert_eq!(names(NameKind::ImproperStyle).len(), 2);
        assert_eq!(names(NameKind::KSpaceStyle).len(), 1);
        assert_eq!(names(NameKind::GranNormalModel).len(), 10);
        assert_eq!(names(NameKind::GranTangentialModel).len(), 4);
        assert_eq!(names(NameKind::GranCohesionModel).len(), 5);
        assert_eq!(names(NameKind::GranRollingModel).len(), 6);
        assert_eq!(names(NameKind::GranSurfaceModel).len(), 3);
        assert_eq!(names(NameKind::FixStyle).len(), 104);
        assert_eq!(names(NameKind::ComputeStyle).len(), 44);
        assert_eq!(names(NameKind::RegionStyle).len(), 11);
        assert_eq!(names(NameKind::DumpStyle).len(), 16);
        assert_eq!(names(NameKind::ReaderStyle).len(), 2);
    }

    #[test]
    fn messages() {
        assert_eq!(
            liggghts_message(NameKind::FixStyle, "foo"),
            "Invalid fix style: \"foo\""
        );
        assert_eq!(
            liggghts_message(NameKind::Command, "foo 1 2"),
            "Unknown command: foo 1 2"
        );
        assert_eq!(
            liggghts_message(NameKind::ComputeStyle, "foo"),
            "Invalid compute style"
        );
        assert_eq!(
            liggghts_wall_gran_model_message("w"),
            "Fix wall/gran (id w): Invalid model specified (check for typos and enable at least one model)"
        );
        for kind in NameKind::ALL {
            assert!(!label(kind).is_empty());
            assert!(!liggghts_message(kind, "x").is_empty());
        }
    }
}
