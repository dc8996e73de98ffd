//! Name validation: is this a LIGGGHTS command, is its style one LIGGGHTS has, and is it
//! spelled right. Misspellings get the nearest valid names.

use crate::commands::names::{self, NameKind};
use crate::commands::suggest::did_you_mean;
use crate::commands::{sim_run, sim_setup, specs, Args, At, CommandError, CommandLine, Ctx};
use crate::engine::contact::{AnyContactModel, ModelSelection};

/// Commands LIGGGHTS 3.8.0 lacks that regolith accepts (newer LAMMPS spellings users type).
pub const EXTENSION_COMMANDS: &[&str] = &["comm_modify", "balance"];

/// Fix styles Debian's LIGGGHTS 3.8.0 build lacks that regolith runs (LAMMPS's load balancing).
pub const EXTENSION_FIX_STYLES: &[&str] = &["balance"];

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

/// A style or sub-model name (`word`, argument `index`) LIGGGHTS does not have.
fn unknown(kind: NameKind, word: &str, index: usize) -> CommandError {
    let candidates = names::names(kind);
    let help = legacy_style_hint(kind, word)
        .or_else(|| did_you_mean(word, candidates))
        .unwrap_or_else(|| format!("'{word}' is not a {} of LIGGGHTS 3.8.0", names::label(kind)));
    CommandError::UnknownName {
        message: names::liggghts_message(kind, word),
        at: At::Arg(index),
        help,
    }
}

/// Check that the command and any style or contact sub-model it names exist in LIGGGHTS 3.8.0.
pub fn validate_names(cmd: &CommandLine) -> Result<(), CommandError> {
    let name = cmd.name();
    if !names::COMMANDS.contains(&name) && !EXTENSION_COMMANDS.contains(&name) {
        let help = did_you_mean(name, names::COMMANDS)
            .unwrap_or_else(|| format!("'{name}' is not a command of LIGGGHTS 3.8.0"));
        return Err(CommandError::UnknownName {
            message: format!("Unknown command: {}", cmd.text.trim()),
            at: At::Name,
            help,
        });
    }
    let Some(&(_, index, kind, usage)) = STYLED.iter().find(|s| s.0 == name) else {
        return Ok(());
    };
    let Some(style) = cmd.arg(index) else {
        return Err(CommandError::BadArgument {
            message: format!("Illegal {name} command"),
            at: At::Arg(index),
            expected: format!("expected: {usage}"),
        });
    };
    if crate::lang::UNKNOWN_VALUE == style {
        return Ok(());
    }
    if kind == NameKind::FixStyle && style.starts_with("mesh/surface") {
        validate_mesh_modules(style, index, cmd.arg(0).unwrap_or(""))?;
    } else if (kind == NameKind::DumpStyle && EXTENSION_DUMP_STYLES.contains(&style))
        || (kind == NameKind::FixStyle && EXTENSION_FIX_STYLES.contains(&style))
    {
        // accepted beyond LIGGGHTS
    } else if is_registered_module(kind, style) {
        // a module style added at run time
    } else if !names::names(kind).contains(&style) {
        return Err(unknown(kind, style, index));
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

/// Whether `style` is a module fix, compute or dump style added at run time (its name need not
/// be one LIGGGHTS knows).
fn is_registered_module(kind: NameKind, style: &str) -> bool {
    match kind {
        NameKind::FixStyle => crate::commands::fix::TABLE.is_registered(style),
        NameKind::ComputeStyle => crate::commands::compute::TABLE.is_registered(style),
        NameKind::DumpStyle => crate::commands::dump::TABLE.is_registered(style),
        _ => false,
    }
}

/// Mesh modules LIGGGHTS 3.8.0 composes into `fix mesh/surface/...` styles.
pub const MESH_MODULES: &[&str] = &["liquidtransfer", "planar", "servo", "stress"];

/// LIGGGHTS accepts any `mesh/surface[/module...]` fix style whose parts are mesh modules.
fn validate_mesh_modules(style: &str, index: usize, id: &str) -> Result<(), CommandError> {
    for part in style.split('/').skip(2) {
        if !MESH_MODULES.contains(&part) {
            let help = did_you_mean(part, MESH_MODULES)
                .unwrap_or_else(|| format!("mesh modules: {}", MESH_MODULES.join(", ")));
            return Err(CommandError::UnknownName {
                message: format!(
                    "Fix {style} (id {id}): unknown keyword in style definition: {style} ({part})"
                ),
                at: At::Arg(index),
                help,
            });
        }
    }
    Ok(())
}

/// Check `model X tangential Y cohesion Z rolling_friction W surface V` names.
fn validate_gran_models(cmd: &CommandLine, start: usize) -> Result<(), CommandError> {
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
            return Err(CommandError::BadArgument {
                message: format!("Illegal {} command", cmd.name()),
                at: At::Arg(i),
                expected: format!("expected a {} after '{key}'", names::label(kind)),
            });
        };
        if value != crate::lang::UNKNOWN_VALUE && !names::names(kind).contains(&value) {
            let mut e = unknown(kind, value, i + 1);
            // `fix wall/gran` raises it as a fix error, naming the fix
            if let (CommandError::UnknownName { message, .. }, "fix", Some(id)) =
                (&mut e, cmd.name(), cmd.arg(0))
            {
                *message = names::liggghts_wall_gran_model_message(id);
            }
            return Err(e);
        }
        i += 2;
    }
    Ok(())
}

/// A command's handler: reads the command's arguments and applies it to the simulation.
pub type Handler = fn(&Args, &mut Ctx) -> Result<(), CommandError>;

/// The handler regolith runs a command with (None: a LIGGGHTS command regolith does not run).
pub fn handler(name: &str) -> Option<Handler> {
    sim_setup::COMMANDS
        .iter()
        .chain(sim_run::COMMANDS)
        .find(|(command, _)| *command == name)
        .map(|&(_, run)| run)
}

/// Where a styled command regolith runs names its style.
pub struct StyleRow {
    /// The command (`fix`, `dump`, ...).
    pub command: &'static str,
    /// Which argument (0-based, after the command name) is the style.
    pub index: usize,
}

/// The styled commands regolith runs. Which styles each runs is declared once, in
/// [`specs::SPECS`]: the handlers refuse any other style as "not supported yet", and
/// [`is_supported`] reads the same declarations.
pub const STYLES: &[StyleRow] = &[
    StyleRow {
        command: "atom_style",
        index: 0,
    },
    StyleRow {
        command: "compute",
        index: 2,
    },
    StyleRow {
        command: "dump",
        index: 2,
    },
    StyleRow {
        command: "fix",
        index: 2,
    },
    StyleRow {
        command: "lattice",
        index: 0,
    },
    StyleRow {
        command: "pair_style",
        index: 0,
    },
    StyleRow {
        command: "region",
        index: 1,
    },
];

/// Whether the handler of `command` runs `style` (a style declared in [`specs::SPECS`]).
pub fn runs_style(command: &str, style: &str) -> bool {
    specs::find(command, Some(style)).is_some()
}

/// The "not supported yet" report, at the style word, of a handler asked for a style that
/// [`STYLES`] does not list for `command`.
pub fn require_style(a: &Args, command: &str) -> Result<(), CommandError> {
    let row = STYLES
        .iter()
        .find(|row| row.command == command)
        .expect("a styled command");
    let style = a.word(row.index)?;
    if runs_style(command, style) {
        return Ok(());
    }
    Err(a.unsupported(row.index, &format!("{command} {style}")))
}

/// Whether regolith runs this command with the style and contact sub-models it names (its
/// keywords are checked when it runs). Reads the tables the handlers dispatch on.
pub fn is_supported(cmd: &CommandLine) -> bool {
    let name = cmd.name();
    if handler(name).is_none() {
        return false;
    }
    let Some(row) = STYLES.iter().find(|row| row.command == name) else {
        return true;
    };
    let Some(style) = cmd.arg(row.index) else {
        return false;
    };
    if !runs_style(name, style) {
        return false;
    }
    match (name, style) {
        ("pair_style", "gran") => contact_models_run(cmd, 1, true),
        ("fix", "wall/gran") => contact_models_run(cmd, 3, false),
        _ => true,
    }
}

/// Whether the contact model named from argument `start` on is one regolith builds (the
/// engine's own constructor decides); a malformed selection is an error, not unsupported.
/// With `wet`, cohesion easo/capillary/viscous runs (the pair loop's liquid bridges) when
/// the rest of the selection does.
fn contact_models_run(cmd: &CommandLine, start: usize, wet: bool) -> bool {
    let words: Vec<&str> = (start..cmd.nargs()).filter_map(|i| cmd.arg(i)).collect();
    let Ok((mut selection, _)) = ModelSelection::select(&words) else {
        return true;
    };
    if wet {
        selection = crate::engine::wet::dry(&selection);
    }
    // `model off` is an error the handler reports, not a missing model
    selection.normal == "off" || AnyContactModel::new(&selection).is_ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::{Location, Severity};

    /// Lines that give a deck a box, so that styled commands reach their handlers.
    const WITH_BOX: &str = "atom_style granular\nregion box block 0 1 0 1 0 1\ncreate_box 1 box\n";

    /// What checking `line` (after `prefix`) reports: Some(true) if it reports `what` as not
    /// supported yet, Some(false) if it reports some other part of it so, None if neither.
    fn refused(prefix: &str, line: &str, what: &str) -> Option<bool> {
        let deck = format!("{prefix}{line}\n");
        let source = crate::script::interp::Source::from_text("in.test", &deck, false);
        let diagnostics = crate::session::check_deck(source, &Default::default());
        let unsupported: Vec<_> = diagnostics
            .iter()
            .filter(|d| d.severity == Severity::Unsupported)
            .collect();
        // "not supported yet", or the plain reason of an out-of-scope feature (SPH, CFD)
        let whole = format!("{what}: ");
        if unsupported.iter().any(|d| d.message.starts_with(&whole)) {
            Some(true)
        } else {
            (!unsupported.is_empty()).then_some(false)
        }
    }

    fn command(line: &str) -> CommandLine {
        CommandLine {
            words: crate::lang::line::split_words(line).expect("words"),
            text: line.to_string(),
            location: Location {
                file: "in.test".into(),
                line: 1,
            },
        }
    }

    /// The lookup agrees with the handler about `line`: the handler refuses `what` exactly
    /// when the lookup says regolith does not run it.
    fn agree(prefix: &str, line: &str, what: &str) {
        let handler_refuses = refused(prefix, line, what) == Some(true);
        let lookup_supports = is_supported(&command(line));
        assert_eq!(
            handler_refuses,
            !lookup_supports,
            "`{line}`: the handler {} it, the lookup says it is {}supported",
            if handler_refuses { "refuses" } else { "runs" },
            if lookup_supports { "" } else { "not " }
        );
    }

    #[test]
    fn lookup_agrees_with_the_handlers_on_every_style() {
        let kinds: &[(NameKind, &str, &str)] = &[
            (NameKind::FixStyle, "fix 1 all {}", "fix {}"),
            (NameKind::ComputeStyle, "compute 1 all {}", "compute {}"),
            (NameKind::DumpStyle, "dump 1 all {} 1 out.dump", "dump {}"),
            (NameKind::RegionStyle, "region r {}", "region {}"),
            (NameKind::PairStyle, "pair_style {}", "pair_style {}"),
        ];
        for &(kind, line, what) in kinds {
            let extension: &[&str] = if kind == NameKind::DumpStyle {
                EXTENSION_DUMP_STYLES
            } else {
                &[]
            };
            for style in names::names(kind).iter().chain(extension) {
                agree(
                    WITH_BOX,
                    &line.replace("{}", style),
                    &what.replace("{}", style),
                );
            }
        }
        for style in names::ATOM_STYLES {
            agree(
                "",
                &format!("atom_style {style}"),
                &format!("atom_style {style}"),
            );
        }
        for style in crate::commands::sim_setup::LATTICE_STYLES {
            agree(
                WITH_BOX,
                &format!("lattice {style} 1.0"),
                &format!("lattice {style}"),
            );
        }
    }

    #[test]
    fn lookup_agrees_with_the_handlers_on_every_command() {
        let styled = |name: &str| STYLES.iter().any(|row| row.command == name);
        for name in names::COMMANDS.iter().chain(EXTENSION_COMMANDS) {
            if crate::lang::SCRIPT_COMMANDS.contains(name) || styled(name) {
                continue;
            }
            // a command that names a style needs one to reach its handler
            let line = match STYLED.iter().find(|s| s.0 == *name) {
                Some(&(_, index, kind, _)) => {
                    assert_eq!(index, 0, "{name}");
                    format!("{name} {}", names::names(kind)[0])
                }
                None => name.to_string(),
            };
            agree(WITH_BOX, &line, &feature_name(&command(&line)));
        }
    }

    #[test]
    fn lookup_agrees_with_the_handlers_on_every_contact_model() {
        let lines: &[(&str, &[&str])] = &[
            ("pair_style gran model {}", names::GRAN_NORMAL_MODELS),
            (
                "pair_style gran model hertz tangential {}",
                names::GRAN_TANGENTIAL_MODELS,
            ),
            (
                "pair_style gran model hertz tangential history cohesion {}",
                names::GRAN_COHESION_MODELS,
            ),
            (
                "pair_style gran model hertz tangential history rolling_friction {}",
                names::GRAN_ROLLING_MODELS,
            ),
            (
                "pair_style gran model hertz tangential history surface {}",
                names::GRAN_SURFACE_MODELS,
            ),
        ];
        for &(line, models) in lines {
            for model in models {
                let line = line.replace("{}", model);
                let handler_refuses = refused(WITH_BOX, &line, "").is_some();
                assert_eq!(handler_refuses, !is_supported(&command(&line)), "`{line}`");
            }
        }
    }

    #[test]
    fn every_command_with_a_handler_is_declared_and_back() {
        for &(name, _) in sim_setup::COMMANDS.iter().chain(sim_run::COMMANDS) {
            let styled = STYLES.iter().any(|row| row.command == name);
            assert_eq!(styled, specs::is_styled(name), "{name}");
            assert!(
                styled || specs::find(name, None).is_some(),
                "{name} has no spec"
            );
        }
        for name in specs::commands() {
            assert!(
                handler(name).is_some(),
                "{name} is declared but has no handler"
            );
        }
    }

    #[test]
    fn valid_decks_are_not_refused() {
        for line in [
            "fix ins all insert/pack seed 123457 distributiontemplate pdd insert_every once",
            "fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes cad",
            "fix w all wall/gran model hertz tangential history primitive type 1 zplane 0",
            "dump d all xyz 100 out.xyz",
            "dump d all custom/vtk 100 out.vtk id x y z",
            "pair_style gran model hooke/hysteresis tangential history",
            "pair_style gran model hertz tangential history cohesion easo/capillary/viscous",
            "read_restart restart.file",
            "write_data out.data",
        ] {
            assert!(is_supported(&command(line)), "`{line}`");
        }
        assert!(!is_supported(&command(
            "fix m all multisphere/nointegration"
        )));
        assert!(!is_supported(&command("compute c all rigid")));
        // LIGGGHTS 3.8.0 runs liquid bridges in pair gran only (its primitive walls crash)
        assert!(!is_supported(&command(
            "fix w all wall/gran model hertz tangential history cohesion easo/capillary/viscous primitive type 1 zplane 0"
        )));
    }
}
