//! `compute com`: the group's centre of mass, unwrapped, a global 3-vector.

use crate::commands::compute::{no_arguments, ComputeDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{center_from_moment, mass_moment, ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::particles::Particles;
use crate::engine::sim::{Simulation, VariableSource};

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "com",
    "compute ID GROUP com",
    &[],
    "centre of mass of the group",
);

/// `compute com`: x, y, z of the group's centre of mass (length, `c_ID[1..3]`).
#[derive(Debug, Default)]
pub struct Com {
    /// The group's mass at the start of the run (mass): LIGGGHTS divides by the mass its
    /// `init` took, so particles inserted or deleted during the run do not change it.
    mass: f64,
}

impl ComputeStyle for Com {
    fn name(&self) -> &str {
        "com"
    }

    fn setup(&mut self, p: &Particles, group: u32) {
        self.mass = crate::engine::momentum::group_mass(p, group);
    }

    fn vector_len(&self) -> usize {
        3
    }

    fn vector(
        &self,
        at: &ComputeAt,
        index: usize,
        _vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        let sim = at.sim;
        let (moment, _) = mass_moment(&sim.particles, &sim.domain, at.group);
        Ok(center_from_moment(moment, self.mass)[index - 1])
    }

    fn extensive(&self, _sim: &Simulation, column: Option<usize>) -> Option<i8> {
        column.is_none().then_some(0)
    }
}

/// `compute ID GROUP com`.
pub fn build(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    no_arguments(a, "com")?;
    Ok(Box::new(Com::default()))
}
