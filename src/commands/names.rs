//! Every command and style name that Debian's LIGGGHTS 3.8.0 accepts, taken from the
//! binary's own list (`liggghts -h`) and the built-in commands of its input reader, each
//! cross-checked against the style registrations in the LIGGGHTS sources.

/// Commands: the built-ins of the input reader plus the command styles.
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

/// `run_style` names.
pub const INTEGRATE_STYLES: &[&str] = &["respa", "verlet"];

/// `min_style` names.
pub const MINIMIZE_STYLES: &[&str] = &["cg"];

/// `pair_style` names.
pub const PAIR_STYLES: &[&str] = &[
    "bubble",
    "gran",
    "gran_bubble",
    "hybrid",
    "hybrid/overlay",
    "line/lj",
    "soft",
    "sph/artVisc/tensCorr",
];

/// Normal contact models of `pair_style gran model ...`.
pub const GRAN_NORMAL_MODELS: &[&str] = &[
    "edinburgh",
    "edinburgh/stiffness",
    "hertz",
    "hertz/stiffness",
    "hooke",
    "hooke/hysteresis",
    "hooke/stiffness",
    "luding",
    "thornton_ning",
];

/// Tangential models (`tangential ...`).
pub const GRAN_TANGENTIAL_MODELS: &[&str] = &["history", "no_history", "tan_luding"];

/// Cohesion models (`cohesion ...`).
pub const GRAN_COHESION_MODELS: &[&str] = &[
    "easo/capillary/viscous",
    "sjkr",
    "sjkr2",
    "washino/capillary/viscous",
];

/// Rolling-friction models (`rolling_friction ...`).
pub const GRAN_ROLLING_MODELS: &[&str] = &["cdt", "epsd", "epsd2", "epsd3", "luding"];

/// Surface models (`surface ...`).
pub const GRAN_SURFACE_MODELS: &[&str] = &["default", "multicontact", "superquadric"];

/// `fix` style names.
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

/// `compute` style names.
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

/// `region` style names.
pub const REGION_STYLES: &[&str] = &[
    "block",
    "cone",
    "cylinder",
    "intersect",
    "mesh/tet",
    "plane",
    "prism",
    "sphere",
    "union",
    "wedge",
];

/// `dump` style names.
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

/// The kinds of names the registry validates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NameKind {
    /// A command (first word of a line).
    Command,
    /// An `atom_style`.
    AtomStyle,
    /// A `pair_style`.
    PairStyle,
    /// A `fix` style.
    FixStyle,
    /// A `compute` style.
    ComputeStyle,
    /// A `dump` style.
    DumpStyle,
    /// A `region` style.
    RegionStyle,
    /// A `run_style`.
    IntegrateStyle,
    /// A `min_style`.
    MinimizeStyle,
    /// A granular normal model (`model ...`).
    GranNormalModel,
    /// A granular tangential model (`tangential ...`).
    GranTangentialModel,
    /// A granular cohesion model (`cohesion ...`).
    GranCohesionModel,
    /// A granular rolling-friction model (`rolling_friction ...`).
    GranRollingModel,
    /// A granular surface model (`surface ...`).
    GranSurfaceModel,
}

/// All names of one kind, sorted.
pub fn names(kind: NameKind) -> &'static [&'static str] {
    match kind {
        NameKind::Command => COMMANDS,
        NameKind::AtomStyle => ATOM_STYLES,
        NameKind::PairStyle => PAIR_STYLES,
        NameKind::FixStyle => FIX_STYLES,
        NameKind::ComputeStyle => COMPUTE_STYLES,
        NameKind::DumpStyle => DUMP_STYLES,
        NameKind::RegionStyle => REGION_STYLES,
        NameKind::IntegrateStyle => INTEGRATE_STYLES,
        NameKind::MinimizeStyle => MINIMIZE_STYLES,
        NameKind::GranNormalModel => GRAN_NORMAL_MODELS,
        NameKind::GranTangentialModel => GRAN_TANGENTIAL_MODELS,
        NameKind::GranCohesionModel => GRAN_COHESION_MODELS,
        NameKind::GranRollingModel => GRAN_ROLLING_MODELS,
        NameKind::GranSurfaceModel => GRAN_SURFACE_MODELS,
    }
}

/// The words used for a kind in messages ("fix style", "rolling-friction model", ...).
pub fn label(kind: NameKind) -> &'static str {
    match kind {
        NameKind::Command => "command",
        NameKind::AtomStyle => "atom style",
        NameKind::PairStyle => "pair style",
        NameKind::FixStyle => "fix style",
        NameKind::ComputeStyle => "compute style",
        NameKind::DumpStyle => "dump style",
        NameKind::RegionStyle => "region style",
        NameKind::IntegrateStyle => "run style",
        NameKind::MinimizeStyle => "min style",
        NameKind::GranNormalModel => "normal contact model",
        NameKind::GranTangentialModel => "tangential contact model",
        NameKind::GranCohesionModel => "cohesion model",
        NameKind::GranRollingModel => "rolling-friction model",
        NameKind::GranSurfaceModel => "surface model",
    }
}

/// The error LIGGGHTS 3.8.0 prints for an unknown name of this kind (observed with `liggghts`).
pub fn liggghts_message(kind: NameKind, word: &str) -> String {
    match kind {
        NameKind::Command => format!("Unknown command: {word}"),
        NameKind::FixStyle => format!("Invalid fix style: \"{word}\""),
        NameKind::ComputeStyle => "Invalid compute style".into(),
        NameKind::RegionStyle => "Invalid region style".into(),
        NameKind::DumpStyle => "Invalid dump style".into(),
        NameKind::PairStyle => "Invalid pair style".into(),
        NameKind::AtomStyle => "Invalid atom style".into(),
        NameKind::IntegrateStyle => "Illegal integrate style".into(),
        NameKind::MinimizeStyle => "Illegal min_style command".into(),
        NameKind::GranNormalModel
        | NameKind::GranTangentialModel
        | NameKind::GranCohesionModel
        | NameKind::GranRollingModel
        | NameKind::GranSurfaceModel => {
            "Invalid model specified (check for typos and enable at least one model)".into()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [NameKind; 14] = [
        NameKind::Command,
        NameKind::AtomStyle,
        NameKind::PairStyle,
        NameKind::FixStyle,
        NameKind::ComputeStyle,
        NameKind::DumpStyle,
        NameKind::RegionStyle,
        NameKind::IntegrateStyle,
        NameKind::MinimizeStyle,
        NameKind::GranNormalModel,
        NameKind::GranTangentialModel,
        NameKind::GranCohesionModel,
        NameKind::GranRollingModel,
        NameKind::GranSurfaceModel,
    ];

    #[test]
    fn lists_are_sorted_and_unique() {
        for kind in ALL {
            let list = names(kind);
            assert!(
                list.windows(2).all(|w| w[0] < w[1]),
                "{kind:?} not sorted/unique"
            );
        }
    }

    #[test]
    fn known_members_and_counts() {
        assert!(FIX_STYLES.contains(&"insert/stream"));
        assert!(FIX_STYLES.contains(&"wall/gran"));
        assert!(COMPUTE_STYLES.contains(&"stress/atom"));
        assert!(DUMP_STYLES.contains(&"custom/vtk"));
        assert!(REGION_STYLES.contains(&"block"));
        assert!(PAIR_STYLES.contains(&"gran"));
        for c in [
            "run",
            "read_restart",
            "write_restart",
            "create_atoms",
            "print",
            "jump",
        ] {
            assert!(COMMANDS.contains(&c), "{c}");
        }
        assert!(GRAN_ROLLING_MODELS.contains(&"epsd"));
        // as the Debian binary lists them: 104 fix, 44 compute, 10 region, 16 dump styles
        assert_eq!(FIX_STYLES.len(), 104);
        assert_eq!(COMPUTE_STYLES.len(), 44);
        assert_eq!(REGION_STYLES.len(), 10);
        assert_eq!(DUMP_STYLES.len(), 16);
    }
}
