//! `fix setforce` and `fix addforce`: prescribed force components.

use super::variable_value;
use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP setforce|addforce FX FY FZ [region ID]` (force).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let FixDef { style, .. } = *fix;
    use crate::engine::fixes::{ForceFix, ForceValue};
    a.count(
        6..=usize::MAX,
        &format!("fix ID GROUP {style} FX FY FZ [region ID]"),
    )?;
    let mut values = [ForceValue::Null, ForceValue::Null, ForceValue::Null];
    for (d, slot) in values.iter_mut().enumerate() {
        let w = a.word(3 + d)?;
        if let Some(name) = w.strip_prefix("v_") {
            *slot = variable_value(a, ctx, 3 + d, name, style)?;
        } else if w != "NULL" {
            *slot = ForceValue::Constant(a.real(3 + d)?);
        } else if style == "addforce" {
            return Err(a.error(3 + d, "Illegal fix addforce command"));
        }
    }
    let mut region = None;
    let mut i = 6;
    while i < a.len() {
        match a.word(i)? {
            "region" => {
                let id = a.word(i + 1)?;
                region = Some(ctx.sim.regions.find(id).ok_or_else(|| {
                    a.error(i + 1, format!("Region ID for fix {style} does not exist"))
                })?);
                i += 2;
            }
            w => {
                return Err(a.unsupported(i, &format!("fix {style} keyword {w}")));
            }
        }
    }
    let f = ForceFix {
        values,
        region,
        resolved: Vec::new(),
    };
    Ok(if style == "setforce" {
        FixKind::SetForce(f)
    } else {
        FixKind::AddForce(f)
    })
}
