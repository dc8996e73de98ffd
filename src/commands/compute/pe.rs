//! `compute pe` (the potential energy) and `compute pe/atom` (each particle's): granular pair
//! styles and walls tally none, so both are 0, as in LIGGGHTS 3.8.0.

use crate::commands::compute::after_general_keyword;
use crate::commands::compute::ComputeDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;

/// The declared signature of `pe`.
pub const SPEC: Spec = style(
    "compute",
    "pe",
    "compute ID all pe [pair] [bond] ...",
    &[],
    "potential energy (0 for granular pair styles)",
);

/// The declared signature of `pe/atom`.
pub const ATOM: Spec = style(
    "compute",
    "pe/atom",
    "compute ID GROUP pe/atom [pair|bond|angle|dihedral|improper|kspace ...]",
    &[],
    "potential energy per particle (0: granular pair styles tally none)",
);

/// The energy terms both styles may name.
const TERMS: &[&str] = &["pair", "bond", "angle", "dihedral", "improper", "kspace"];

/// `compute pe`: the potential energy (energy), 0.
#[derive(Debug)]
pub struct Pe;

impl ComputeStyle for Pe {
    fn name(&self) -> &str {
        "pe"
    }

    fn has_scalar(&self) -> bool {
        true
    }

    fn extensive_scalar(&self) -> bool {
        true
    }

    fn scalar(&self, _at: &ComputeAt, _vars: &mut dyn VariableSource) -> Result<f64, EngineError> {
        Ok(0.0)
    }
}

/// `compute pe/atom`: the potential energy per particle (energy), 0.
#[derive(Debug)]
pub struct PeAtom;

impl ComputeStyle for PeAtom {
    fn name(&self) -> &str {
        "pe/atom"
    }

    fn per_atom_columns(&self) -> usize {
        1
    }
}

/// `compute ID all pe [pair|bond|angle|dihedral|improper|kspace ...]`.
pub fn build(
    a: &Args,
    ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    if ctx.sim.group_bit(a.word(1)?) != ctx.sim.group_bit("all") {
        return Err(a.error(1, "Compute pe must use group all"));
    }
    for i in 3..a.len() {
        a.word_in(i, TERMS).map_err(|d| {
            a.error(i, "Illegal compute pe command")
                .with_help(d.help().unwrap_or_default())
        })?;
    }
    Ok(Box::new(Pe))
}

/// `compute ID GROUP pe/atom [update_on_run_end no] [pair bond angle dihedral improper
/// kspace]`.
pub fn atom(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let i = after_general_keyword(a, "pe/atom")?;
    for k in i..a.len() {
        if !TERMS.contains(&a.word(k)?) {
            return Err(a.error(k, "Illegal compute pe/atom command"));
        }
    }
    Ok(Box::new(PeAtom))
}
