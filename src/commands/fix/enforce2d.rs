//! `fix enforce2d`: particles kept in the xy plane of a 2d run (`post_force`).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "enforce2d",
    "fix ID GROUP enforce2d",
    &[],
    "keep particles in the xy plane (2d only): zero vz, fz, omega and torque about x and y",
);

/// `fix enforce2d`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Enforce2d;

impl FixStyle for Enforce2d {
    fn name(&self) -> &str {
        "enforce2d"
    }

    fn check(&self, _p: &Particles, _group: u32, dimension: u32) -> Result<(), EngineError> {
        if dimension == 3 {
            return Err("Cannot use fix enforce2d with 3d simulation".into());
        }
        Ok(())
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        crate::engine::planar::enforce(p, at.group);
    }
}

/// `fix ID GROUP enforce2d`: zero vz, fz and the x, y angular velocity and torque after the
/// forces (refused at the run's init in 3d, as LIGGGHTS does).
pub fn build(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() != 3 {
        return Err(a.error(a.len() - 1, "Illegal fix enforce2d command"));
    }
    Ok(Box::new(Enforce2d))
}
