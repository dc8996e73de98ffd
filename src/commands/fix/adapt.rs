//! `fix adapt`: particle diameters from a variable.

use super::variable_value;
use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP adapt N atom diameter v_name [scale yes|no] [reset yes|no]`.
pub fn build(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    use crate::engine::fixes::{Adapt, ForceValue};
    a.count(
        5..=usize::MAX,
        "fix ID GROUP adapt N atom diameter v_name ...",
    )?;
    let every = a.int(3)?;
    if every < 0 {
        return Err(a.error(3, "Illegal fix adapt command"));
    }
    let mut diameter = None;
    let (mut scale, mut i) = (false, 4);
    while i < a.len() {
        match a.word(i)? {
            "atom" => {
                a.count(
                    i + 3..=usize::MAX,
                    "fix ID GROUP adapt N atom diameter v_name",
                )?;
                match a.word(i + 1)? {
                    "diameter" => {}
                    "charge" => {
                        return Err(a.error(i + 1, "Fix adapt requires atom attribute charge"))
                    }
                    _ => return Err(a.error(i + 1, "Illegal fix adapt command")),
                }
                let Some(name) = a.word(i + 2)?.strip_prefix("v_") else {
                    return Err(a.error(i + 2, "Illegal fix adapt command"));
                };
                diameter = Some(variable_value(a, ctx, i + 2, name, "adapt")?);
                i += 3;
            }
            w @ ("pair" | "kspace") => return Err(a.unsupported(i, &format!("fix adapt {w}"))),
            "scale" => {
                scale = a.word_in(i + 1, &["yes", "no"])? == "yes";
                i += 2;
            }
            // LIGGGHTS restores nothing for atom attributes: `reset` has no effect
            "reset" => {
                a.word_in(i + 1, &["yes", "no"])?;
                i += 2;
            }
            _ => return Err(a.error(i, "Illegal fix adapt command")),
        }
    }
    let Some(diameter) = diameter else {
        return Err(a.error(3, "Illegal fix adapt command"));
    };
    debug_assert!(!matches!(diameter, ForceValue::Null));
    Ok(FixKind::Adapt(Adapt {
        every,
        diameter,
        scale,
    }))
}
