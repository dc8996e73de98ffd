//! `fix gravity`: a uniform acceleration.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;
use crate::engine::integrate::Gravity;

/// `fix ID GROUP gravity MAG vector X Y Z | chute ANGLE | spherical PHI THETA` (acceleration;
/// angles in degrees).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let FixDef { bit, .. } = *fix;
    let illegal = || a.error(a.len().saturating_sub(1), "Illegal fix gravity command");
    if a.len() < 5 {
        return Err(illegal());
    }
    if let Some(i) = (3..a.len()).find(|&i| i != 4 && a.word(i).is_ok_and(|w| w.starts_with("v_")))
    {
        return Err(a.unsupported(i, "fix gravity with an equal-style variable"));
    }
    let magnitude = a.real(3)?;
    let dimension = ctx.sim.dimension;
    Ok(match a.word(4)? {
        "vector" => {
            if a.len() != 8 {
                return Err(illegal());
            }
            let dir = [a.real(5)?, a.real(6)?, a.real(7)?];
            FixKind::Gravity(Gravity::along(magnitude, dir, bit).map_err(|m| a.error(5, &m))?)
        }
        // the chute's incline: the polar angle 180 - ANGLE in the xz plane
        "chute" => {
            if a.len() != 6 {
                return Err(illegal());
            }
            let vert = a.real(5)?;
            FixKind::Gravity(Gravity::spherical(
                magnitude,
                0.0,
                180.0 - vert,
                dimension,
                bit,
            ))
        }
        "spherical" => {
            if a.len() != 7 {
                return Err(illegal());
            }
            let (phi, theta) = (a.real(5)?, a.real(6)?);
            FixKind::Gravity(Gravity::spherical(magnitude, phi, theta, dimension, bit))
        }
        _ => return Err(a.error(4, "Illegal fix gravity command")),
    })
}
