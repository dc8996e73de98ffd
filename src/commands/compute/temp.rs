//! `compute temp`: the group's temperature with the settings `compute_modify` gives it
//! (LIGGGHTS 3.8.0's compute_temp.cpp), and LIGGGHTS's default `thermo_temp`.

use crate::commands::compute::{no_arguments, ComputeDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{Compute, ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::{Simulation, VariableSource};
use crate::engine::temperature::temperature;

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "temp",
    "compute ID GROUP temp",
    &[],
    "temperature of the group (3N - 3 degrees of freedom; see compute_modify)",
);

/// `compute temp`: the temperature as the scalar (temperature), the kinetic energy tensor
/// sum m v_a v_b, xx yy zz xy xz yz, as `c_ID[1..6]` (energy).
#[derive(Debug)]
pub struct Temp;

impl ComputeStyle for Temp {
    fn name(&self) -> &str {
        "temp"
    }

    fn has_scalar(&self) -> bool {
        true
    }

    fn scalar(&self, at: &ComputeAt, _vars: &mut dyn VariableSource) -> Result<f64, EngineError> {
        Ok(temperature(at.sim, at.id, at.group))
    }

    fn vector_len(&self) -> usize {
        6
    }

    fn vector(
        &self,
        at: &ComputeAt,
        index: usize,
        _vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        Ok(ke_tensor(at.sim, at.group)[index - 1])
    }

    fn extensive(&self, _sim: &Simulation, column: Option<usize>) -> Option<i8> {
        column.is_none().then_some(1)
    }

    fn is_temperature(&self) -> bool {
        true
    }
}

/// The kinetic energy tensor of the particles in `group`: sum of m v_a v_b, xx yy zz xy
/// xz yz (energy).
pub(super) fn ke_tensor(sim: &Simulation, group: u32) -> [f64; 6] {
    let p = &sim.particles;
    let mut t = [0.0; 6];
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            let (m, v) = (p.mass[i], p.v[i]);
            t[0] += m * v[0] * v[0];
            t[1] += m * v[1] * v[1];
            t[2] += m * v[2] * v[2];
            t[3] += m * v[0] * v[1];
            t[4] += m * v[0] * v[2];
            t[5] += m * v[1] * v[2];
        }
    }
    t
}

/// `compute ID GROUP temp`.
pub fn build(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    no_arguments(a, "temp")?;
    Ok(Box::new(Temp))
}

/// LIGGGHTS's `thermo_temp`, the `temp` compute of group all every deck has (its Output
/// constructor makes it).
pub fn thermo_temp() -> Compute {
    Compute {
        id: "thermo_temp".into(),
        style: "temp".into(),
        group: 1,
        calc: Box::new(Temp),
    }
}
