//! Compute styles of researchers' decks that need only their arguments checked.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::engine::computes::ComputeKind;

/// `compute ID all pe [pair|bond|angle|dihedral|improper|kspace ...]`: granular pair styles
/// and walls tally no potential energy, so its value is 0 (as in LIGGGHTS).
pub fn pe(a: &Args, ctx: &mut Ctx) -> Result<ComputeKind, CommandError> {
    if ctx.sim.group_bit(a.word(1)?) != ctx.sim.group_bit("all") {
        return Err(a.error(1, "Compute pe must use group all"));
    }
    for i in 3..a.len() {
        a.word_in(
            i,
            &["pair", "bond", "angle", "dihedral", "improper", "kspace"],
        )
        .map_err(|d| {
            a.error(i, "Illegal compute pe command")
                .with_help(d.help().unwrap_or_default())
        })?;
    }
    Ok(ComputeKind::PotentialEnergy)
}
