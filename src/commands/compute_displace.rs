//! `compute msd` and `compute displace/atom`: displacements from where the group's particles
//! were when the compute was defined.

use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::ComputeKind;
use crate::engine::displacement::Origins;

/// `compute ID GROUP msd [com yes|no]` or `compute ID GROUP displace/atom` (group `bit`).
pub fn build(a: &Args, ctx: &mut Ctx, bit: u32) -> Result<ComputeKind, CommandError> {
    let style = a.word(2)?;
    let illegal = format!("Illegal compute {style} command");
    let mut com = false;
    let mut i = 3;
    while i < a.len() {
        if style == "msd" && a.word(i)? == "com" {
            if a.len() < i + 2 {
                return Err(a.error(i, &illegal));
            }
            com = match a.word(i + 1)? {
                "yes" => true,
                "no" => false,
                _ => return Err(a.error(i + 1, &illegal)),
            };
            i += 2;
        } else {
            return Err(a.error(i, &illegal));
        }
    }
    let origins = Box::new(Origins::new(&ctx.sim.particles, &ctx.sim.domain, bit, com));
    Ok(match style {
        "msd" => ComputeKind::Msd(origins),
        _ => ComputeKind::DisplaceAtom(origins),
    })
}
