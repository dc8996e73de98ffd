//! `compute pressure`: the pressure and its tensor from the kinetic energy of a
//! temperature compute and the pair virial (LIGGGHTS 3.8.0's compute_pressure.cpp).

use crate::commands::compute::{after_general_keyword, temp::ke_tensor, ComputeDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{Compute, ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::{Simulation, VariableSource};
use crate::engine::temperature::temperature_parts;

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "pressure",
    "compute ID all pressure TEMP-ID [ke|pair|virial ...]",
    &[],
    "pressure (scalar) and pressure tensor (c_ID[1..6]) from the kinetic energy of the temperature compute and the pair virial",
);

/// `compute pressure temp-ID [ke] [pair] [virial] ...`: the pressure (scalar) and the
/// pressure tensor xx yy zz xy xz yz (`c_ID[1..6]`), pressure units.
#[derive(Debug, Clone, PartialEq)]
pub struct Pressure {
    /// ID of the temperature compute.
    pub temp: String,
    /// Include the kinetic part.
    pub ke: bool,
    /// Include the pair virial.
    pub pair: bool,
}

impl Pressure {
    /// The temperature compute the pressure reads.
    fn temperature<'a>(&self, sim: &'a Simulation) -> Result<&'a Compute, EngineError> {
        sim.computes
            .iter()
            .find(|c| c.id == self.temp && c.style().is_temperature())
            .ok_or_else(|| "Could not find compute pressure temperature ID".into())
    }

    /// The pair virial of the last force evaluation, summed over the particles (force
    /// length), or zeros without `pair`.
    fn virial(&self, sim: &Simulation) -> Result<[f64; 6], EngineError> {
        let mut v = [0.0; 6];
        if !self.pair || sim.pair.is_none() {
            return Ok(v);
        }
        if sim.virial_step != Some(sim.step) {
            return Err("Virial was not tallied on needed timestep".into());
        }
        for w in &sim.virial {
            for k in 0..6 {
                v[k] += w[k];
            }
        }
        Ok(v)
    }
}

/// 1 / volume of the box (1 / area in 2d; per volume).
fn inverse_volume(sim: &Simulation) -> f64 {
    let d = &sim.domain;
    if sim.dimension == 3 {
        1.0 / (d.length(0) * d.length(1) * d.length(2))
    } else {
        1.0 / (d.length(0) * d.length(1))
    }
}

impl ComputeStyle for Pressure {
    fn name(&self) -> &str {
        "pressure"
    }

    fn has_scalar(&self) -> bool {
        true
    }

    fn scalar(&self, at: &ComputeAt, vars: &mut dyn VariableSource) -> Result<f64, EngineError> {
        let sim = at.sim;
        let n = sim.dimension as usize;
        let virial = self.virial(sim)?;
        let mut sum = 0.0;
        if self.ke {
            let t = self.temperature(sim)?;
            let (_, dof, boltz) = temperature_parts(sim, &t.id, t.group);
            sum = dof * boltz * t.scalar(sim, vars)?;
        }
        for v in &virial[..n] {
            sum += v;
        }
        Ok(sum / n as f64 * inverse_volume(sim))
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
        let (sim, k) = (at.sim, index - 1);
        let mut v = self.virial(sim)?;
        if self.ke {
            let ke = ke_tensor(sim, self.temperature(sim)?.group);
            for (a, b) in v.iter_mut().zip(ke) {
                *a += b;
            }
        }
        if sim.dimension == 2 && matches!(k, 2 | 4 | 5) {
            return Ok(0.0);
        }
        Ok(v[k] * inverse_volume(sim))
    }

    fn extensive(&self, _sim: &Simulation, column: Option<usize>) -> Option<i8> {
        column.is_none().then_some(0)
    }

    fn reads_virial(&self) -> bool {
        self.pair
    }
}

/// `compute ID all pressure temp-ID [ke pair bond angle dihedral improper kspace fix virial]`.
pub fn build(
    a: &Args,
    ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let i = after_general_keyword(a, "pressure")?;
    if a.len() < i + 1 {
        return Err(a.error(2, "Illegal compute pressure command"));
    }
    if a.word(1)? != "all" {
        return Err(a.error(1, "Compute pressure must use group all"));
    }
    let temp = a.word(i)?;
    let Some(t) = ctx.sim.computes.iter().find(|c| c.id == temp) else {
        return Err(a.error(i, "Could not find compute pressure temperature ID"));
    };
    if !t.style().is_temperature() {
        return Err(a.error(
            i,
            "Compute pressure temperature ID does not compute temperature",
        ));
    }
    let (mut ke, mut pair) = (a.len() == i + 1, a.len() == i + 1);
    for k in i + 1..a.len() {
        match a.word(k)? {
            "ke" => ke = true,
            "pair" | "virial" => pair = true,
            // granular runs have no bonds, angles, kspace or fixes with a virial
            "bond" | "angle" | "dihedral" | "improper" | "kspace" | "fix" => {}
            _ => return Err(a.error(k, "Illegal compute pressure command")),
        }
    }
    Ok(Box::new(Pressure {
        temp: temp.to_string(),
        ke,
        pair,
    }))
}
