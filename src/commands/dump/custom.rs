//! `dump custom`: the chosen per-particle columns (attributes and `c_`/`f_`/`v_` values) as
//! LIGGGHTS's `ITEM:` text, or LAMMPS's binary format for a `*.bin` file.

use crate::commands::dump::{style_words, Built, DumpDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::dump_style::{DumpAt, DumpStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;
use crate::io::dump::Layout;

/// The declared signature of `custom`.
pub const SPEC: Spec = style(
    "dump",
    "custom",
    "dump ID GROUP custom N FILE COLUMN ...",
    &[],
    "chosen per-particle columns every N steps (LAMMPS's binary format for a FILE named *.bin)",
);

/// `dump custom`: the layout's text (or binary) snapshot.
#[derive(Debug)]
pub struct Custom;

impl DumpStyle for Custom {
    fn name(&self) -> &str {
        "custom"
    }

    fn snapshot(
        &self,
        at: &mut DumpAt,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        text_snapshot(at, vars)
    }

    // LIGGGHTS's text dumps take no `binary` keyword (a `.bin` file name makes `dump custom`
    // binary)
    fn takes_binary(&self) -> Option<bool> {
        Some(false)
    }
}

/// `dump ID GROUP custom N FILE COLUMN ...`.
pub fn build(a: &Args, ctx: &mut Ctx, _def: &DumpDef) -> Result<Built, CommandError> {
    Ok((columns(a, ctx)?, Box::new(Custom)))
}

/// The per-atom columns of `dump custom` and `custom/vtk` (words 5 on), checked as LIGGGHTS
/// checks them.
pub(super) fn columns(a: &Args, ctx: &Ctx) -> Result<Layout, CommandError> {
    let names = style_words(a)?;
    if names.is_empty() {
        return Err(a
            .error(4, "Illegal dump custom command")
            .with_help("list the columns to dump"));
    }
    check_custom_columns(a, ctx, &names)?;
    let layout = Layout::new(&names).map_err(|e| {
        let k = match &e {
            crate::io::dump::ColumnError::Attribute(w) => {
                names.iter().position(|n| n == w).unwrap_or(0)
            }
            _ => 0,
        };
        a.error(5 + k, &e)
    })?;
    // the molecule ID exists only with fix multisphere (its body tags)
    if let Some(k) = names.iter().position(|n| *n == "mol") {
        if ctx.sim.clumps().is_none() {
            return Err(a.error(5 + k, "Dumping an atom property that isn't allocated"));
        }
    }
    Ok(layout)
}

/// The `f_`, `v_` and `c_` columns of `dump custom`: fixes with per-atom values, atom-style
/// variables and computes with per-atom values, checked as LIGGGHTS checks them.
fn check_custom_columns(a: &Args, ctx: &Ctx, names: &[&str]) -> Result<(), CommandError> {
    for (k, n) in names.iter().enumerate() {
        if let Some(body) = n.strip_prefix("f_") {
            let (fid, index) = crate::util::numbers::split_reference(body)
                .ok_or_else(|| a.error(5 + k, "Invalid attribute in dump custom command"))?;
            crate::engine::fix_columns::column(ctx.sim, fid, index)
                .map_err(|m| a.error(5 + k, &m))?;
        }
    }
    for (k, n) in names.iter().enumerate() {
        if let Some(var) = n.strip_prefix("v_") {
            match ctx.vars.get(var).map(|v| v.style) {
                Some(crate::lang::variables::Style::Atom) => {}
                Some(_) => {
                    return Err(a.error(5 + k, "Dump custom variable is not atom-style variable"))
                }
                None => return Err(a.error(5 + k, "Could not find dump custom variable name")),
            }
        }
    }
    for (k, n) in names.iter().enumerate() {
        if let Some(body) = n.strip_prefix("c_") {
            let (cid, index) = crate::util::numbers::split_reference(body)
                .ok_or_else(|| a.error(5 + k, "Invalid attribute in dump custom command"))?;
            let c = ctx
                .sim
                .computes
                .iter()
                .find(|c| c.id == cid)
                .ok_or_else(|| a.error(5 + k, "Could not find dump custom compute ID"))?;
            crate::engine::computes::column_of(c, index)
                .map_err(|m| a.error(5 + k, format!("Dump custom: {m}")))?;
        }
    }
    Ok(())
}

/// The group's particles with the layout's columns as `ITEM:` text, or in LAMMPS's binary
/// format for names ending in `.bin` (as LIGGGHTS's dump custom).
pub(super) fn text_snapshot(
    at: &mut DumpAt,
    vars: &mut dyn VariableSource,
) -> Result<Vec<u8>, EngineError> {
    let columns = at.references(vars)?;
    let (sim, dump) = (at.sim, at.dump);
    let mut text = Vec::new();
    let value = |c: usize, i: usize| columns[c].0.get(i, columns[c].1);
    let (step, p, group, domain) = (sim.step, &sim.particles, dump.group, &sim.domain);
    if dump.file.ends_with(".bin") {
        dump.layout
            .write_binary_snapshot(&mut text, step, p, group, domain, value)
    } else {
        dump.layout
            .write_snapshot(&mut text, step, p, group, domain, value)
    }
    .map_err(|e| e.to_string())?;
    Ok(text)
}
