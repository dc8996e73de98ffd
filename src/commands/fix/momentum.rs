//! `fix momentum`: zero a group's linear and/or angular momentum every N steps.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;
use crate::engine::momentum::Momentum;

/// `fix ID GROUP momentum N [linear XFLAG YFLAG ZFLAG] [angular]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    const ILLEGAL: &str = "Illegal fix momentum command";
    a.count(
        4..=usize::MAX,
        "fix ID GROUP momentum N [linear XFLAG YFLAG ZFLAG] [angular]",
    )?;
    let every = a.int(3)?;
    if every <= 0 {
        return Err(a.error(3, ILLEGAL));
    }
    let (mut linear, mut angular) = (None, false);
    let mut i = 4;
    while i < a.len() {
        match a.word(i)? {
            "linear" => {
                if i + 4 > a.len() {
                    return Err(a.error(i, ILLEGAL));
                }
                let mut flags = [false; 3];
                for (d, flag) in flags.iter_mut().enumerate() {
                    *flag = match a.int(i + 1 + d)? {
                        0 => false,
                        1 => true,
                        _ => return Err(a.error(i + 1 + d, ILLEGAL)),
                    };
                }
                linear = Some(flags);
                i += 4;
            }
            "angular" => {
                angular = true;
                i += 1;
            }
            _ => return Err(a.error(i, ILLEGAL)),
        }
    }
    if linear.is_none() && !angular {
        return Err(a.error(2, ILLEGAL));
    }
    // checking a deck does not run it, so its particles may not exist yet
    let p = &ctx.sim.particles;
    let checking = ctx.sys.mode != crate::lang::system::Mode::Run;
    if !checking && !(0..p.len()).any(|i| p.mask[i] & fix.bit != 0) {
        return Err(a.error(1, "Fix momentum group has no atoms"));
    }
    Ok(FixKind::Momentum(Momentum {
        every,
        linear,
        angular,
        mass: 0.0,
    }))
}
