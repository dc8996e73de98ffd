//! The material checks LIGGGHTS makes when a run starts (`youngsModulus >= 5e6 required for
//! SI units`, Poisson ratios, restitution, ...): `run` and `check` make them alike, and an
//! error points at the `fix property/global` line that set the offending value.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::engine::extras::Origin;
use crate::error::Diagnostic;

/// `fix ID GROUP property/global NAME ...`: remember where NAME was set.
pub fn remember(a: &Args, ctx: &mut Ctx) {
    let Ok(name) = a.word(3) else { return };
    let origin = Origin {
        location: a.cmd.location.clone(),
        text: a.cmd.text.clone(),
        span: a.cmd.span(3),
    };
    ctx.sim
        .extras
        .property_origins
        .insert(name.to_string(), origin);
}

/// Whether `name` occurs in `message` as a word of its own.
fn mentions(message: &str, name: &str) -> bool {
    message.match_indices(name).any(|(at, _)| {
        let before = message[..at].chars().next_back();
        let after = message[at + name.len()..].chars().next();
        let free = |c: Option<char>| c.is_none_or(|c| !c.is_ascii_alphanumeric() && c != '_');
        free(before) && free(after)
    })
}

/// The checks of the contact models a run would build (pair style and granular walls), at
/// the `run` command `a`.
pub fn validate(a: &Args, ctx: &Ctx) -> Result<(), CommandError> {
    let sim = &*ctx.sim;
    let input = sim.material_input();
    // the walls' models (the multiple-contact model runs around their dry rest)
    let mut selections: Vec<_> = sim
        .fixes
        .iter()
        .filter_map(|f| f.kind.wall_selection())
        .map(|sel| {
            let mut dry = sel.clone();
            if dry.surface == "multicontact" {
                dry.surface = "default".into();
            }
            dry
        })
        .collect();
    // the pair loop's liquid bridges around its dry model
    selections.extend(sim.pair_selection.as_ref().map(crate::engine::wet::dry));
    if sim.pair_is_wet() {
        if (0..3).any(|d| sim.domain.periodic(d)) {
            return Err(a.unsupported(0, crate::engine::wet::PERIODIC));
        }
        // LIGGGHTS reports bridges apart as contacts too; regolith's compute does not yet
        if sim.computes.iter().any(|c| c.style().reads_pair_contacts()) {
            return Err(a.unsupported(0, crate::engine::wet::LOCAL));
        }
        sim.wet_input().map_err(|e| a.error(0, e.to_string()))?;
    }
    if sim
        .pair_selection
        .as_ref()
        .is_some_and(|s| s.surface == "multicontact")
    {
        // LIGGGHTS reports pairs apart within the contact distance too
        if sim.computes.iter().any(|c| c.style().reads_pair_contacts()) {
            return Err(a.unsupported(0, "compute pair/gran/local with surface multicontact"));
        }
        if (0..3).any(|d| sim.domain.periodic(d)) {
            return Err(a.unsupported(
                0,
                "pair_style gran surface multicontact across periodic boundaries",
            ));
        }
    }
    for sel in &selections {
        let Err(error) = crate::engine::granular::model_and_material(sel, &input) else {
            continue;
        };
        let message = error.to_string();
        let mut names: Vec<&String> = sim.extras.property_origins.keys().collect();
        names.sort_by_key(|n| std::cmp::Reverse(n.len()));
        let origin = names
            .into_iter()
            .find(|n| mentions(&message, n))
            .and_then(|n| sim.extras.property_origins.get(n));
        return Err(match origin {
            // reported at the line that set the value, not at `run`
            Some(o) => CommandError::Reported(
                Diagnostic::error(&message)
                    .with_source(&o.text, Some(o.span))
                    .at(&o.location)
                    .with_help(format!(
                        "LIGGGHTS checks this value when a run starts (here the `{}` at {}:{})",
                        a.cmd.text.trim(),
                        a.cmd.location.file,
                        a.cmd.location.line
                    )),
            ),
            None => a.error(0, &message),
        });
    }
    Ok(())
}
