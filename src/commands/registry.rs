//! Name validation: is this a LIGGGHTS command, is its style one LIGGGHTS has, and is it
//! spelled right. Misspellings get the nearest valid names.

use crate::commands::names::{self, NameKind};
use crate::commands::suggest::did_you_mean;
use crate::commands::CommandLine;
use crate::error::Diagnostic;

/// Commands LIGGGHTS 3.8.0 lacks that regolith accepts (newer LAMMPS spellings users type).
pub const EXTENSION_COMMANDS: &[&str] = &["comm_modify"];

/// Dump styles Debian's LIGGGHTS 3.8.0 build lacks that regolith writes (LAMMPS's layout).
pub const EXTENSION_DUMP_STYLES: &[&str] = &["atom"];

/// Commands whose argument at `index` (0-based, after the command name) is a style name.
const STYLED: &[(&str, usize, NameKind, &str)] = &[
    ("atom_style", 0, NameKind::AtomStyle, "atom_style STYLE ..."),
    ("pair_style", 0, NameKind::PairStyle, "pair_style STYLE ..."),
    ("fix", 2, NameKind::FixStyle, "fix ID GROUP STYLE ..."),
    (
        "compute",
        2,
        NameKind::ComputeStyle,
        "compute ID GROUP STYLE ...",
    ),
    (
        "dump",
        2,
        NameKind::DumpStyle,
        "dump ID GROUP STYLE N FILE ...",
    ),
    ("region", 1, NameKind::RegionStyle, "region ID STYLE ..."),
    (
        "run_style",
        0,
        NameKind::IntegrateStyle,
        "run_style STYLE ...",
    ),
    ("min_style", 0, NameKind::MinimizeStyle, "min_style STYLE"),
];

/// The (command, style) a line names, e.g. `fix insert/stream` or `create_box`.
pub fn feature_name(cmd: &CommandLine) -> String {
    match STYLED.iter().find(|s| s.0 == cmd.name()) {
        Some(&(name, index, _, _)) => match cmd.arg(index) {
            Some(style) => format!("{name} {style}"),
            None => name.to_string(),
        },
        None => cmd.name().to_string(),
    }
}

/// Byte range of the command name through its style word, for "not supported yet" carets.
pub fn feature_span(cmd: &CommandLine) -> (usize, usize) {
    let start = cmd.words[0].start;
    let end = match STYLED.iter().find(|s| s.0 == cmd.name()) {
        Some(&(_, index, _, _)) if index < cmd.nargs() => cmd.span(index).1,
        _ => cmd.words[0].end,
    };
    (start, end)
}

/// What LIGGGHTS 3.x writes instead of a style that LIGGGHTS 2.x had (the syntax of
/// decks such as the contactModels tutorial's `in.oldModels`, which 3.8.0 rejects too).
pub fn legacy_style_hint(kind: NameKind, word: &str) -> Option<String> {
    let pair = |normal: &str, tangential: &str| {
        format!(
            "'{word}' is LIGGGHTS 2.x syntax; LIGGGHTS 3.x writes `pair_style gran model {normal} \
             tangential {tangential}` with the material in `fix property/global` \
             (youngsModulus, poissonsRatio, coefficientRestitution, coefficientFriction)"
        )
    };
    match (kind, word) {
        (NameKind::PairStyle, "gran/hooke") => Some(pair("hooke", "no_history")),
        (NameKind::PairStyle, "gran/hooke/history") => Some(pair("hooke", "history")),
        (NameKind::PairStyle, "gran/hertz/history") => Some(pair("hertz", "history")),
        (NameKind::FixStyle, "pour" | "pour/dev" | "pour/legacy" | "pour/multisphere") => {
            Some(format!(
                "'fix {word}' is LIGGGHTS 2.x syntax; LIGGGHTS 3.x inserts with \
                 `fix particletemplate/sphere`, `fix particledistribution/discrete` and \
                 `fix insert/pack`, `insert/rate/region` or `insert/stream`"
            ))
        }
        _ => None,
    }
}

fn unknown(kind: NameKind, word: &str, cmd: &CommandLine, index: usize) -> Diagnostic {
    let candidates = names::names(kind);
    let help = legacy_style_hint(kind, word)
        .or_else(|| did_you_mean(word, candidates))
        .unwrap_or_else(|| format!("'{word}' is not a {} of LIGGGHTS 3.8.0", names::label(kind)));
    Diagnostic::error(names::liggghts_message(kind, word))
        .with_source(&cmd.text, Some(cmd.span(index)))
        .with_help(help)
}

/// Check that the command and any style or contact sub-model it names exist in LIGGGHTS 3.8.0.
pub fn validate_names(cmd: &CommandLine) -> Result<(), Diagnostic> {
    let name = cmd.name();
    if !names::COMMANDS.contains(&name) && !EXTENSION_COMMANDS.contains(&name) {
        let help = did_you_mean(name, names::COMMANDS)
            .unwrap_or_else(|| format!("'{name}' is not a command of LIGGGHTS 3.8.0"));
        return Err(
            Diagnostic::error(format!("Unknown command: {}", cmd.text.trim()))
                .with_source(&cmd.text, Some((cmd.words[0].start, cmd.words[0].end)))
                .with_help(help),
        );
    }
    let Some(&(_, index, kind, usage)) = STYLED.iter().find(|s| s.0 == name) else {
        return Ok(());
    };
    let Some(style) = cmd.arg(index) else {
        return Err(Diagnostic::error(format!("Illegal {name} command"))
            .with_source(&cmd.text, Some(cmd.span(index)))
            .with_help(format!("expected: {usage}")));
    };
    if crate::script::interp::UNKNOWN_VALUE == style {
        return Ok(());
    }
    if kind == NameKind::FixStyle && style.starts_with("mesh/surface") {
        validate_mesh_modules(style, cmd, index)?;
    } else if kind == NameKind::DumpStyle && EXTENSION_DUMP_STYLES.contains(&style) {
        // accepted beyond LIGGGHTS
    } else if !names::names(kind).contains(&style) {
        return Err(unknown(kind, style, cmd, index));
    }
    let model_start = match (name, style) {
        ("pair_style", "gran") => Some(index + 1),
        ("fix", "wall/gran") => Some(index + 1),
        _ => None,
    };
    if let Some(start) = model_start {
        validate_gran_models(cmd, start)?;
    }
    Ok(())
}

/// Mesh modules LIGGGHTS 3.8.0 composes into `fix mesh/surface/...` styles.
pub const MESH_MODULES: &[&str] = &["liquidtransfer", "planar", "servo", "stress"];

/// LIGGGHTS accepts any `mesh/surface[/module...]` fix style whose parts are mesh modules.
fn validate_mesh_modules(style: &str, cmd: &CommandLine, index: usize) -> Result<(), Diagnostic> {
    for part in style.split('/').skip(2) {
        if !MESH_MODULES.contains(&part) {
            let help = did_you_mean(part, MESH_MODULES)
                .unwrap_or_else(|| format!("mesh modules: {}", MESH_MODULES.join(", ")));
            return Err(Diagnostic::error(format!(
                "unknown keyword in style definition: {style} ({part})"
            ))
            .with_source(&cmd.text, Some(cmd.span(index)))
            .with_help(help));
        }
    }
    Ok(())
}

/// Check `model X tangential Y cohesion Z rolling_friction W surface V` names.
fn validate_gran_models(cmd: &CommandLine, start: usize) -> Result<(), Diagnostic> {
    let mut i = start;
    while let Some(key) = cmd.arg(i) {
        let kind = match key {
            "model" => NameKind::GranNormalModel,
            "tangential" => NameKind::GranTangentialModel,
            "cohesion" => NameKind::GranCohesionModel,
            "rolling_friction" => NameKind::GranRollingModel,
            "surface" => NameKind::GranSurfaceModel,
            _ => return Ok(()),
        };
        let Some(value) = cmd.arg(i + 1) else {
            return Err(Diagnostic::error(format!("Illegal {} command", cmd.name()))
                .with_source(&cmd.text, Some(cmd.span(i)))
                .with_help(format!("expected a {} after '{key}'", names::label(kind))));
        };
        if value != crate::script::interp::UNKNOWN_VALUE && !names::names(kind).contains(&value) {
            return Err(unknown(kind, value, cmd, i + 1));
        }
        i += 2;
    }
    Ok(())
}

/// Commands regolith executes (beyond the script language), and their supported styles.
pub fn is_supported(cmd: &CommandLine) -> bool {
    match cmd.name() {
        "fix" if cmd.arg(2) == Some("wall/gran") => {
            gran_models_supported(cmd, 3)
                && (0..cmd.nargs()).any(|k| {
                    cmd.arg(k) == Some("primitive")
                        && matches!(
                            cmd.arg(k + 3),
                            Some(
                                "xplane"
                                    | "yplane"
                                    | "zplane"
                                    | "xcylinder"
                                    | "ycylinder"
                                    | "zcylinder"
                            )
                        )
                })
        }
        "fix" => cmd
            .arg(2)
            .is_some_and(|s| crate::commands::sim_run::FIX_STYLES.contains(&s)),
        "dump" => matches!(cmd.arg(2), Some("custom" | "local")),
        "compute" => cmd
            .arg(2)
            .is_some_and(|s| crate::engine::computes::STYLES.contains(&s)),
        "pair_style" => cmd.arg(0) == Some("gran") && gran_models_supported(cmd, 1),
        "atom_style" => matches!(cmd.arg(0), Some("granular" | "sphere")),
        "lattice" => matches!(cmd.arg(0), Some("none" | "sc" | "bcc" | "fcc")),
        "region" => matches!(
            cmd.arg(1),
            Some(
                "block"
                    | "cylinder"
                    | "sphere"
                    | "cone"
                    | "plane"
                    | "prism"
                    | "intersect"
                    | "union"
            )
        ),
        name => SUPPORTED_COMMANDS.contains(&name),
    }
}

/// Are the contact models named from argument `start` on ones regolith runs?
fn gran_models_supported(cmd: &CommandLine, start: usize) -> bool {
    let mut k = start;
    while let (Some(key), Some(value)) = (cmd.arg(k), cmd.arg(k + 1)) {
        let ok = match key {
            "model" => matches!(
                value,
                "hertz" | "hooke" | "hertz/stiffness" | "hooke/stiffness"
            ),
            "tangential" => matches!(
                value,
                "history" | "no_history" | "history_total_cap" | "off"
            ),
            "cohesion" => matches!(value, "sjkr" | "sjkr2" | "off"),
            "rolling_friction" => matches!(value, "cdt" | "epsd" | "epsd2" | "epsd3" | "off"),
            "surface" => value == "default",
            _ => break,
        };
        if !ok {
            return false;
        }
        k += 2;
    }
    true
}

/// Commands with a native implementation (their keywords are checked when they run).
pub const SUPPORTED_COMMANDS: &[&str] = &[
    "atom_modify",
    "boundary",
    "comm_modify",
    "communicate",
    "create_atoms",
    "create_box",
    "delete_atoms",
    "dimension",
    "displace_atoms",
    "dump_modify",
    "group",
    "hard_particles",
    "modify_timing",
    "neigh_modify",
    "neighbor",
    "newton",
    "pair_coeff",
    "processors",
    "reset_timestep",
    "run",
    "set",
    "soft_particles",
    "thermo",
    "thermo_log",
    "thermo_modify",
    "thermo_style",
    "timestep",
    "uncompute",
    "undump",
    "unfix",
    "units",
    "velocity",
    "write_dump",
];
