//! `fix multisphere`: integrates the rigid clumps inserted from multisphere templates.

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::clumps::Clumps;
use crate::engine::fixes::{Fix, FixStep, FixStyle};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "multisphere",
    "fix ID GROUP multisphere",
    &[],
    "rigid-body integration of the multisphere clumps (centre of mass and orientation)",
);

/// `fix ID GROUP multisphere` (no keywords; `allow_group_and_set`, `allow_heatsource` and
/// `CAddRhoFluid` are not supported yet).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if let Some(f) = ctx
        .sim
        .fixes
        .iter()
        .find(|f| f.kind.style_as::<Clumps>().is_some() && f.id != fix.id)
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
    Ok(Box::<Clumps>::default())
}

/// The rigid clumps: kicked, drifted and rotated in `initial_integrate` (at the insertion
/// face's velocity until released, when a `fix insert/stream` is defined), the members'
/// forces and the body's weight (the first gravity fix's) summed and kicked in
/// `final_integrate`.
impl FixStyle for Clumps {
    fn name(&self) -> &str {
        "multisphere"
    }

    fn among_fixes(&self) -> bool {
        true
    }

    fn initial_integrate_among(&mut self, fixes: &mut [Fix], p: &mut Particles, at: &FixStep) {
        let has_stream = fixes.iter().any(|f| f.kind.stream().is_some());
        Clumps::initial_integrate(self, p, at.dt, at.domain, at.step, has_stream);
    }

    fn final_integrate_among(&mut self, fixes: &mut [Fix], p: &mut Particles, at: &FixStep) {
        self.calc_force(p, at.domain, crate::engine::fixes::gravity(fixes));
        Clumps::final_integrate(self, p, at.dt);
    }

    fn unaccelerated(&self) -> Option<&'static str> {
        Some("multisphere clumps (fix multisphere)")
    }

    fn keeps_per_atom_state(&self) -> bool {
        true
    }

    fn reads_computes(&self) -> bool {
        true
    }

    fn array_unsupported(&self) -> bool {
        true
    }
}
