//! `compute rdf`: radial distribution functions and coordination numbers per type pair as
//! a global array (the counting is [`crate::engine::rdf`]), with LIGGGHTS 3.8.0's errors.

use crate::commands::compute::{after_general_keyword, type_range, ComputeDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::rdf::Rdf;
use crate::engine::sim::Simulation;

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "rdf",
    "compute ID GROUP rdf NBIN [ITYPE JTYPE ...]",
    &[],
    "radial distribution g(r) and coordination number per type pair over NBIN bins up to the pair cutoff (global array: r, then g and coord per pair; fix ave/time mode vector writes it)",
);

impl ComputeStyle for Rdf {
    fn name(&self) -> &str {
        "rdf"
    }

    fn init(&self, sim: &Simulation) -> Result<(), EngineError> {
        if sim.pair_selection.is_none() {
            return Err("Compute rdf requires a pair style be defined".into());
        }
        Ok(())
    }

    fn array_size(&self) -> Option<(usize, usize)> {
        Some((self.nbin, self.columns()))
    }

    fn array(&self, at: &ComputeAt) -> Result<Vec<f64>, EngineError> {
        self.array(at.sim, at.group)
    }

    fn extensive(&self, _sim: &Simulation, column: Option<usize>) -> Option<i8> {
        column.is_some().then_some(0)
    }
}

/// `compute ID GROUP rdf [update_on_run_end yes|no] Nbin [itype jtype ...]`.
pub fn build(
    a: &Args,
    ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let i = after_general_keyword(a, "rdf")?;
    if a.len() < i + 1 || !(a.len() - (i + 1)).is_multiple_of(2) {
        return Err(a.error(2, "Illegal compute rdf command"));
    }
    let nbin = a.int32(i)?;
    if nbin < 1 {
        return Err(a.error(i, "Illegal compute rdf command"));
    }
    let ntypes = ctx.sim.ntypes;
    let mut pairs = Vec::new();
    let mut k = i + 1;
    while k < a.len() {
        let ri = type_range(a, k, ntypes, "rdf")?;
        let rj = type_range(a, k + 1, ntypes, "rdf")?;
        pairs.push((ri, rj));
        k += 2;
    }
    if pairs.is_empty() {
        pairs.push(((1, ntypes), (1, ntypes)));
    }
    // LIGGGHTS allocates nbin rows of 1 + 2 npairs doubles and as many histogram bins
    let row = 8 * (1 + 4 * pairs.len());
    crate::engine::checks::allocation(nbin as f64, row, "rdf:array").map_err(|e| a.error(i, &e))?;
    Ok(Box::new(Rdf {
        nbin: nbin as usize,
        pairs,
    }))
}
