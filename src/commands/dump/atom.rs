//! `dump atom`: LAMMPS's fixed columns `id type xs ys zs` (scaled positions), every N steps.

use crate::commands::dump::{Built, DumpDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::dump_style::{DumpAt, DumpStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;
use crate::io::dump::Layout;

/// The declared signature of `atom`.
pub const SPEC: Spec = style(
    "dump",
    "atom",
    "dump ID GROUP atom N FILE",
    &[],
    "positions, scaled, every N steps (LAMMPS layout)",
);

/// `dump atom`: the layout's text snapshot (LAMMPS's binary format for a `*.bin` file).
#[derive(Debug)]
pub struct Atom;

impl DumpStyle for Atom {
    fn name(&self) -> &str {
        "atom"
    }

    fn snapshot(
        &self,
        at: &mut DumpAt,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        super::custom::text_snapshot(at, vars)
    }

    fn takes_binary(&self) -> Option<bool> {
        Some(false)
    }
}

/// `dump ID GROUP atom N FILE`.
pub fn build(a: &Args, _ctx: &mut Ctx, _def: &DumpDef) -> Result<Built, CommandError> {
    a.count(5..=5, "dump ID GROUP atom N FILE")?;
    let mut layout = Layout::new(&["id", "type", "xs", "ys", "zs"]).expect("known columns");
    layout.no_trailing_blank = true;
    Ok((layout, Box::new(Atom)))
}
