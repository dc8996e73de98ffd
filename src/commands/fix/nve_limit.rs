//! `fix nve/limit`: `fix nve` with each particle's step capped at a distance.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;
use crate::engine::nve_limit::NveLimit;

/// `fix ID GROUP nve/limit absolute|radius_ratio XLIMIT`: XLIMIT a length (absolute) or a
/// multiple of each particle's radius (radius_ratio).
pub fn build(a: &Args, _ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    if a.len() != 5 {
        return Err(a.error(3, "Illegal fix nve/limit command"));
    }
    let relative = match a.word(3)? {
        "radius_ratio" => true,
        "absolute" => false,
        _ => {
            return Err(a.error(
                3,
                format!(
                    "Fix nve/limit (id {}): expecting keyword 'absolute' or 'radius_ratio'",
                    fix.id
                ),
            ))
        }
    };
    Ok(FixKind::NveLimit(NveLimit {
        xlimit: a.real(4)?,
        relative,
        count: 0,
    }))
}
