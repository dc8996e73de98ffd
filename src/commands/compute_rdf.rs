//! `compute rdf`: its arguments, with LIGGGHTS 3.8.0's errors.

use crate::commands::compute::type_range;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::ComputeKind;
use crate::engine::rdf::Rdf;

/// `compute ID GROUP rdf [update_on_run_end yes|no] Nbin [itype jtype ...]`.
pub fn build(a: &Args, ctx: &Ctx) -> Result<ComputeKind, CommandError> {
    let i = crate::commands::compute_analysis::after_general_keyword(a, "rdf")?;
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
    Ok(ComputeKind::Rdf(Box::new(Rdf {
        nbin: nbin as usize,
        pairs,
    })))
}
