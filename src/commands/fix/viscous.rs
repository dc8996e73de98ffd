//! `fix viscous`: a drag force proportional to velocity.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP viscous GAMMA`: f -= gamma v (force/velocity).
pub fn build(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    a.count(4..=4, "fix ID GROUP viscous GAMMA")?;
    Ok(FixKind::Viscous(a.real(3)?))
}
