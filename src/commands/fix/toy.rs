//! A toy fix style for the registration test: `fix ID GROUP toy/push FX`, a constant force
//! FX (force) along x on every particle of the group.

use crate::commands::fix::force::{Action, Force};
use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixStyle;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "toy/push",
    "fix ID GROUP toy/push FX",
    &[],
    "a constant force FX (force) along x",
);

/// `fix ID GROUP toy/push FX`.
pub fn build(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    a.count(4..=4, "fix ID GROUP toy/push FX")?;
    let push = a.real(3)?;
    Ok(Box::new(Force::constant(
        Action::Add,
        [Some(push), Some(0.0), Some(0.0)],
    )))
}
