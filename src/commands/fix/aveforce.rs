//! `fix aveforce`: the group's forces replaced by their mean plus an extra force.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;
use crate::engine::force_project::AveForce;

/// `fix ID GROUP aveforce FX FY FZ` (force, or NULL to leave a component alone).
pub fn build(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    if a.len() < 6 {
        return Err(a.error(3, "Illegal fix aveforce command"));
    }
    let mut add = [None; 3];
    for (k, slot) in add.iter_mut().enumerate() {
        let w = a.word(3 + k)?;
        if w.starts_with("v_") {
            return Err(a.unsupported(3 + k, "fix aveforce with variables"));
        }
        if w != "NULL" {
            *slot = Some(a.real(3 + k)?);
        }
    }
    if a.len() > 6 {
        return Err(match a.word(6)? {
            "region" => a.unsupported(6, "fix aveforce region"),
            _ => a.error(6, "Illegal fix aveforce command"),
        });
    }
    Ok(FixKind::AveForce(AveForce {
        add,
        original: [0.0; 3],
    }))
}
