//! `fix multisphere`: integrates the rigid clumps inserted from multisphere templates.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP multisphere` (no keywords; `allow_group_and_set`, `allow_heatsource` and
/// `CAddRhoFluid` are not supported yet).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    if let Some(f) = ctx
        .sim
        .fixes
        .iter()
        .find(|f| matches!(f.kind, FixKind::Multisphere(_)) && f.id != fix.id)
    {
        return Err(a.unsupported(
            0,
            &format!("a second fix multisphere (fix {} holds the bodies)", f.id),
        ));
    }
    if a.len() > 3 {
        return match a.word(3)? {
            w @ ("allow_group_and_set" | "allow_heatsource" | "CAddRhoFluid") => {
                Err(a.unsupported(3, &format!("fix multisphere {w}")))
            }
            w => Err(a.error(
                3,
                format!(
                    "Fix multisphere (id {}): unknown keyword or wrong keyword order: {w}",
                    fix.id
                ),
            )),
        };
    }
    Ok(FixKind::Multisphere(Box::default()))
}
