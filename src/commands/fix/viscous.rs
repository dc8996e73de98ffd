//! `fix viscous`: a drag force proportional to velocity.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP viscous GAMMA [scale TYPE RATIO ...]`: f -= gamma v (force/velocity), gamma
/// scaled by RATIO for atoms of TYPE.
pub fn build(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    const ILLEGAL: &str = "Illegal fix viscous command";
    if a.len() < 4 {
        return Err(a.error(0, ILLEGAL));
    }
    let gamma = a.real(3)?;
    let ntypes = ctx.sim.ntypes as usize;
    // one value per atom type, index 0 unused (LIGGGHTS's gamma[type])
    let mut by_type = vec![gamma; ntypes + 1];
    let mut k = 4;
    while k < a.len() {
        if a.word(k)? != "scale" {
            return Err(a.error(k, ILLEGAL));
        }
        if k + 2 >= a.len() {
            return Err(a.error(k, ILLEGAL));
        }
        let t = a.int(k + 1)?;
        if t < 1 || t > ntypes as i64 {
            return Err(a.error(k + 1, ILLEGAL));
        }
        by_type[t as usize] = gamma * a.real(k + 2)?;
        k += 3;
    }
    Ok(FixKind::Viscous(by_type))
}
