//! `compute com`: the group's centre of mass, unwrapped, a global 3-vector.

use crate::commands::compute::{no_arguments, ComputeDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{center_of_mass, ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
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
#[derive(Debug)]
pub struct Com;

impl ComputeStyle for Com {
    fn name(&self) -> &str {
        "com"
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
        Ok(center_of_mass(&sim.particles, &sim.domain, at.group)[index - 1])
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
    Ok(Box::new(Com))
}
