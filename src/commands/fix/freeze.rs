//! `fix freeze`: particles that neither move nor turn (`post_force`; contacts treat them as
//! infinitely heavy).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "freeze",
    "fix ID GROUP freeze",
    &[],
    "hold particles still (zero force and torque)",
);

/// `fix freeze`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Freeze;

impl FixStyle for Freeze {
    fn name(&self) -> &str {
        "freeze"
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        for i in (0..p.len()).filter(|&i| p.mask[i] & at.group != 0) {
            p.f[i] = [0.0; 3];
            p.torque[i] = [0.0; 3];
        }
    }

    fn holds_still(&self) -> bool {
        true
    }
}

/// `fix ID GROUP freeze`: force and torque zero.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let FixDef { id, .. } = *fix;
    if a.len() > 3 {
        return Err(a.error(3, "Illegal fix freeze command"));
    }
    if ctx
        .sim
        .fixes
        .iter()
        .any(|f| f.style == "freeze" && f.id != id)
    {
        return Err(a.error(2, "More than one fix freeze"));
    }
    Ok(Box::new(Freeze))
}
