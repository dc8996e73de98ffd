//! `fix enforce2d`: particles kept in the xy plane of a 2d run.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP enforce2d`: zero vz, fz and the x, y angular velocity and torque after the
/// forces (refused at the run's init in 3d, as LIGGGHTS does).
pub fn build(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    if a.len() != 3 {
        return Err(a.error(a.len() - 1, "Illegal fix enforce2d command"));
    }
    Ok(FixKind::Enforce2d)
}
