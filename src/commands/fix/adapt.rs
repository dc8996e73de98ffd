//! `fix adapt`: particle diameters from a variable every N steps (`pre_force`, and
//! `setup_pre_force` at every run's setup), each particle keeping its density.

use super::variable_value;
use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStep, FixStyle, ForceValue, StepInputs};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "adapt",
    "fix ID GROUP adapt N atom diameter v_NAME",
    &[
        kw(
            "scale",
            &[arg("yes|no", YES_NO)],
            "scale mass with the diameter",
        ),
        kw(
            "reset",
            &[arg("yes|no", YES_NO)],
            "restore at the end of the run",
        ),
    ],
    "change particle diameters by a variable during a run",
);

/// `fix adapt N atom diameter v_name [scale yes|no] [reset yes|no]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Adapt {
    /// Apply every this many steps (0: only at the setup of each run).
    every: i64,
    /// The diameter (length), or the factor on the current diameter with `scale yes`.
    diameter: ForceValue,
    /// `scale yes`: the variable multiplies the current diameter.
    scale: bool,
    /// The diameters (or factors) read for this step, one per particle.
    values: Vec<f64>,
}

impl FixStyle for Adapt {
    fn name(&self) -> &str {
        "adapt"
    }

    fn reads_computes(&self) -> bool {
        true
    }

    fn changes_radii(&self) -> bool {
        true
    }

    fn unaccelerated(&self) -> Option<&'static str> {
        Some("growing particles (fix adapt)")
    }

    fn pre_force_due(&self, step: i64, setup: bool) -> bool {
        setup || (self.every != 0 && step % self.every == 0)
    }

    fn pre_force_evaluate(
        &mut self,
        p: &Particles,
        _at: &FixStep,
        inputs: &mut dyn StepInputs,
    ) -> Result<(), EngineError> {
        self.values = match &self.diameter {
            ForceValue::Equal(name) => vec![inputs.equal(name)?; p.len()],
            ForceValue::Atom(name) => inputs.atom(name)?,
            ForceValue::Constant(c) => vec![*c; p.len()],
            ForceValue::Null => Vec::new(),
        };
        Ok(())
    }

    fn pre_force(&mut self, p: &mut Particles, at: &FixStep) {
        use std::f64::consts::PI;
        for (i, &value) in self.values.iter().enumerate().take(p.len()) {
            if p.mask[i] & at.group == 0 {
                continue;
            }
            let r = p.radius[i];
            let density = p.mass[i] / (4.0 * PI / 3.0 * r * r * r);
            let mut value = value;
            if self.scale {
                value *= r * 2.0;
            }
            let r = 0.5 * value;
            p.radius[i] = r;
            p.mass[i] = 4.0 * PI / 3.0 * r * r * r * density;
        }
    }
}

/// `fix ID GROUP adapt N atom diameter v_name [scale yes|no] [reset yes|no]`.
pub fn build(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
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
    Ok(Box::new(Adapt {
        every,
        diameter,
        scale,
        values: Vec::new(),
    }))
}
