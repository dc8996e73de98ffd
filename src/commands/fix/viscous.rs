//! `fix viscous`: a drag force proportional to velocity (`post_force`).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "viscous",
    "fix ID GROUP viscous GAMMA [scale TYPE RATIO ...]",
    &[],
    "drag force -GAMMA v (force per velocity), GAMMA scaled by RATIO for atoms of TYPE",
);

/// `fix viscous`: f -= gamma v for the group's particles.
#[derive(Debug, Clone, PartialEq)]
pub struct Viscous {
    /// gamma per atom type (force/velocity; index 0 unused, LIGGGHTS's `gamma[type]`).
    pub by_type: Vec<f64>,
}

impl FixStyle for Viscous {
    fn name(&self) -> &str {
        "viscous"
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        for i in (0..p.len()).filter(|&i| p.mask[i] & at.group != 0) {
            let gamma = self.by_type.get(p.kind[i] as usize).copied().unwrap_or(0.0);
            for d in 0..3 {
                p.f[i][d] -= gamma * p.v[i][d];
            }
        }
    }
}

/// `fix ID GROUP viscous GAMMA [scale TYPE RATIO ...]`: gamma (force/velocity) scaled by
/// RATIO for atoms of TYPE.
pub fn build(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    const ILLEGAL: &str = "Illegal fix viscous command";
    if a.len() < 4 {
        return Err(a.error(0, ILLEGAL));
    }
    let gamma = a.real(3)?;
    let ntypes = ctx.sim.ntypes as usize;
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
    Ok(Box::new(Viscous { by_type }))
}
