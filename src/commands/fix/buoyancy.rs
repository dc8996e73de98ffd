//! `fix buoyancy`: the weight of displaced liquid below a level plane.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::buoyancy::Buoyancy;
use crate::engine::fixes::FixKind;

/// `fix ID GROUP buoyancy level L dim x|y|z density RHO [region R]` (length,
/// mass/length^3), keywords in any order, checked as LIGGGHTS checks them.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let id = fix.id;
    let fail = |i: usize, m: &str| a.error(i, format!("Fix buoyancy (id {id}): {m}"));
    let (mut density, mut dim, mut level, mut region) = (0.0, None, 0.0, None);
    let mut i = 3;
    while i < a.len() {
        let key = a.word(i)?;
        if !matches!(key, "density" | "level" | "dim" | "region") {
            return Err(fail(i, " expecting 'density' or 'region'"));
        }
        if i + 2 > a.len() {
            return Err(fail(i, &format!("not enough arguments for '{key}'")));
        }
        match key {
            "density" => {
                density = a.real(i + 1)?;
                if density <= 0. {
                    return Err(fail(i + 1, "'density' > 0 required"));
                }
            }
            "level" => {
                level = a.real(i + 1)?;
                if level <= 0. {
                    return Err(fail(i + 1, "'level' > 0 required"));
                }
            }
            "dim" => {
                dim = Some(match a.word(i + 1)? {
                    "x" => 0,
                    "y" => 1,
                    "z" => 2,
                    _ => return Err(fail(i + 1, "expecting 'x' or 'y' or 'z' after 'dim'")),
                });
            }
            _ => {
                let r = a.word(i + 1)?;
                region = Some(
                    ctx.sim
                        .regions
                        .find(r)
                        .ok_or_else(|| fail(i + 1, "Region ID does not exist"))?,
                );
            }
        }
        i += 2;
    }
    let Some(dim) = dim else {
        return Err(fail(2, " you have to specify 'dim'"));
    };
    if density.abs() < 1e-6 {
        return Err(fail(2, " you have to specify 'density'"));
    }
    Ok(FixKind::Buoyancy(Buoyancy {
        density,
        dim,
        level,
        region,
        inside: Vec::new(),
        total: [0.0; 3],
    }))
}
