//! `fix buoyancy`: the weight of displaced liquid below a level plane, under the run's
//! gravity (`post_force`; f_ID[1..3] the total force).

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value, LENGTH};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::buoyancy::Buoyancy;
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixInit, FixStep, FixStyle, StepInputs};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "buoyancy",
    "fix ID GROUP buoyancy level L dim x|y|z density RHO",
    &[
        kw("level", &[arg("L", LENGTH)], "the liquid level along dim"),
        kw(
            "dim",
            &[arg("x|y|z", Value::OneOf(&["x", "y", "z"]))],
            "the axis gravity acts along",
        ),
        kw(
            "density",
            &[arg("RHO", Value::Real("mass/length^3"))],
            "liquid density",
        ),
        kw(
            "region",
            &[arg("R", Value::Id("region"))],
            "act only inside this region",
        ),
    ],
    "add the weight of the displaced liquid to immersed particles (f_ID[1..3]: total force)",
);

impl FixStyle for Buoyancy {
    fn name(&self) -> &str {
        "buoyancy"
    }

    fn init(&mut self, run: &FixInit) -> Result<(), EngineError> {
        Buoyancy::init(self, run.accelerations)
    }

    fn reads_computes(&self) -> bool {
        true
    }

    fn evaluates(&self) -> bool {
        self.region.is_some()
    }

    fn evaluate(
        &mut self,
        p: &Particles,
        _at: &FixStep,
        inputs: &mut dyn StepInputs,
    ) -> Result<(), EngineError> {
        if let Some(region) = self.region {
            self.inside.clear();
            self.inside
                .extend(p.x.iter().map(|&x| inputs.in_region(region, x)));
        }
        Ok(())
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        if let Some(g) = self.gravity {
            self.apply(p, at.group, g);
        }
    }

    /// LIGGGHTS flags its global vector extensive.
    fn extensive(&self, index: Option<usize>) -> bool {
        index.is_some()
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        match index {
            Some(i @ 1..=3) => Some(self.total[i - 1]),
            _ => None,
        }
    }
}

/// `fix ID GROUP buoyancy level L dim x|y|z density RHO [region R]` (length,
/// mass/length^3), keywords in any order, checked as LIGGGHTS checks them.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
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
    Ok(Box::new(Buoyancy {
        id: id.to_string(),
        density,
        dim,
        level,
        region,
        inside: Vec::new(),
        total: [0.0; 3],
        gravity: None,
    }))
}
