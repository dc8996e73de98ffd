//! `fix spring/self`: particles tethered to their positions when the fix is defined.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;
use crate::engine::spring_self::SpringSelf;

/// `fix ID GROUP spring/self K [xyz|xy|xz|yz|x|y|z]` (K: force per length).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    const ILLEGAL: &str = "Illegal fix spring/self command";
    if a.len() < 4 || a.len() > 5 {
        return Err(a.error(2, ILLEGAL));
    }
    let k = a.real(3)?;
    if k <= 0.0 {
        return Err(a.error(3, ILLEGAL));
    }
    let dims = match a.len() {
        4 => [true; 3],
        _ => match a.word(4)? {
            "xyz" => [true, true, true],
            "xy" => [true, true, false],
            "xz" => [true, false, true],
            "yz" => [false, true, true],
            "x" => [true, false, false],
            "y" => [false, true, false],
            "z" => [false, false, true],
            _ => return Err(a.error(4, ILLEGAL)),
        },
    };
    let spring = SpringSelf {
        k,
        dims,
        slot: format!("spring/self {}", fix.id),
        prd: [0, 1, 2].map(|d| ctx.sim.domain.length(d)),
        energy: 0.0,
    };
    spring.tether(&mut ctx.sim.particles, fix.bit);
    // a restart file's tether points of this fix replace the current positions
    if let Some(stored) = ctx.sim.restart_move_origins.get(&spring.slot) {
        let p = &mut ctx.sim.particles;
        let k = p.extra_index(&spring.slot, 3);
        for i in 0..p.len() {
            if let (true, Some(x)) = (p.mask[i] & fix.bit != 0, stored.get(&p.id[i])) {
                p.extra[k].data[3 * i..3 * i + 3].copy_from_slice(x);
            }
        }
    }
    Ok(FixKind::SpringSelf(spring))
}
