//! `fix gravity`: a uniform acceleration.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;
use crate::engine::integrate::Gravity;

/// `fix ID GROUP gravity MAG vector X Y Z` (acceleration).
pub fn build(a: &Args, _ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let FixDef { bit, .. } = *fix;
    a.count(4..=usize::MAX, "fix ID GROUP gravity MAG vector X Y Z")?;
    let magnitude = a.real(3)?;
    Ok(match a.word(4)? {
        "vector" => {
            a.count(8..=8, "fix ID GROUP gravity MAG vector X Y Z")?;
            let dir = [a.real(5)?, a.real(6)?, a.real(7)?];
            FixKind::Gravity(Gravity::along(magnitude, dir, bit).map_err(|m| a.error(5, &m))?)
        }
        other => return Err(a.unsupported(4, &format!("fix gravity {other}"))),
    })
}
