//! A toy fix style for the registration test: `fix ID GROUP toy/push FX`, a constant force
//! FX (force) along x on every particle of the group.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixKind, ForceFix, ForceValue};

/// `fix ID GROUP toy/push FX`.
pub fn build(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    a.count(4..=4, "fix ID GROUP toy/push FX")?;
    let push = ForceValue::Constant(a.real(3)?);
    Ok(FixKind::AddForce(ForceFix {
        values: [push, ForceValue::Constant(0.0), ForceValue::Constant(0.0)],
        region: None,
        resolved: Vec::new(),
    }))
}
