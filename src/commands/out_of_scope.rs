//! What regolith will not run, said plainly: CFD coupling (`fix couple/cfd...` needs an
//! external CFD solver driving LIGGGHTS) and SPH (smoothed-particle hydrodynamics, which is
//! not DEM).

use crate::commands::{CommandError, CommandLine};
use crate::error::Severity;

/// The plain reason a command's feature is out of scope, if it is.
fn reason(cmd: &CommandLine) -> Option<(String, &'static str)> {
    let name = cmd.name();
    let style = |i: usize| cmd.arg(i).unwrap_or("");
    let cfd = "needs an external CFD solver; regolith has no CFD coupling";
    let sph = "out of scope: SPH is a fluid method, regolith is a DEM solver";
    match name {
        "fix" if style(2).starts_with("couple/cfd") => Some((format!("fix {}", style(2)), cfd)),
        "fix" if style(2).split('/').any(|p| p == "sph") => {
            Some((format!("fix {}", style(2)), sph))
        }
        "atom_style" if style(0) == "sph" => Some(("atom_style sph".into(), sph)),
        "pair_style" if style(0).starts_with("sph") => {
            Some((format!("pair_style {}", style(0)), sph))
        }
        "set" => {
            let k = (2..cmd.nargs())
                .map(style)
                .find(|w| w.starts_with("meso_") || *w == "sphkernel")?;
            Some((format!("set {k}"), sph))
        }
        _ => None,
    }
}

/// An unsupported report for an out-of-scope feature, reworded to say why.
pub fn explain(cmd: &CommandLine, e: CommandError) -> CommandError {
    if e.severity() != Severity::Unsupported {
        return e;
    }
    let Some((feature, reason)) = reason(cmd) else {
        return e;
    };
    let help = if reason.contains("CFD") {
        "CFDEMcoupling runs LIGGGHTS as a library inside an OpenFOAM solver and exchanges \
         particle-fluid forces with it every coupling interval; run such cases with \
         LIGGGHTS and CFDEMcoupling"
    } else {
        "SPH (smoothed-particle hydrodynamics) decks need LIGGGHTS itself"
    };
    match e {
        CommandError::Reported(mut d) => {
            d.message = format!("{feature}: {reason}");
            d.help = Some(help.to_string());
            CommandError::Reported(d)
        }
        CommandError::Unsupported { at, .. } | CommandError::OutOfScope { at, .. } => {
            CommandError::OutOfScope {
                feature,
                at,
                reason: reason.to_string(),
                help: help.to_string(),
            }
        }
        other => other,
    }
}
