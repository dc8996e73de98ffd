//! Velocity-Verlet integration fixes: `nve/sphere` (translation and rotation) and `nve/noforce`.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP nve/noforce`: positions follow velocities, forces are ignored.
pub fn noforce(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    if a.len() != 3 {
        return Err(a.error(3, "Illegal fix nve/noforce command"));
    }
    Ok(FixKind::NveNoforce)
}

/// `fix ID GROUP nve/sphere`: positions, velocities and angular velocities of spheres.
pub fn sphere(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    if a.len() > 3 {
        return Err(a.unsupported(3, "fix nve/sphere keywords"));
    }
    // LIGGGHTS integrates discs in 2d (moment of inertia 0.5 m r^2)
    Ok(if ctx.sim.dimension == 2 {
        FixKind::NveDisc
    } else {
        FixKind::NveSphere
    })
}

/// `fix ID GROUP nve`: positions and velocities (angular velocities left alone).
pub fn plain(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    if a.len() != 3 {
        return Err(a.error(3, "Illegal fix nve command"));
    }
    Ok(FixKind::Nve)
}
