//! `compute ID GROUP reduce/region REGION MODE input1 input2 ...`: `compute reduce` over the
//! group's particles inside a region.

use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::ComputeKind;

/// Reads the region, then the reduction as `compute reduce` reads it.
pub fn build(a: &Args, ctx: &mut Ctx) -> Result<ComputeKind, CommandError> {
    if a.len() < 6 {
        return Err(a.error(2, "Illegal compute reduce/region command"));
    }
    let region = ctx
        .sim
        .regions
        .find(a.word(3)?)
        .ok_or_else(|| a.error(3, "Region ID for compute reduce/region does not exist"))?;
    crate::commands::sim_run::compute_reduce(a, ctx, 4, Some(region))
}
