//! `fix freeze`: particles that neither move nor turn.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP freeze`: force and torque zero.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let FixDef { id, .. } = *fix;
    if a.len() > 3 {
        return Err(a.error(3, "Illegal fix freeze command"));
    }
    if ctx
        .sim
        .fixes
        .iter()
        .any(|f| matches!(f.kind, FixKind::Freeze) && f.id != id)
    {
        return Err(a.error(2, "More than one fix freeze"));
    }
    Ok(FixKind::Freeze)
}
