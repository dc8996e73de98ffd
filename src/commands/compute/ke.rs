//! `compute ke` (the group's translational kinetic energy) and `compute ke/atom` (each
//! particle's).

use crate::commands::compute::{no_arguments, ComputeDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{kinetic_energy, Compute, ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;

/// The declared signature of `ke`.
pub const SPEC: Spec = style(
    "compute",
    "ke",
    "compute ID GROUP ke",
    &[],
    "translational kinetic energy of the group",
);

/// The declared signature of `ke/atom`.
pub const ATOM: Spec = style(
    "compute",
    "ke/atom",
    "compute ID GROUP ke/atom",
    &[],
    "kinetic energy per particle",
);

/// `compute ke`: 0.5 m v^2 summed over the group (energy), multisphere bodies counted as
/// bodies.
#[derive(Debug)]
pub struct Ke;

impl ComputeStyle for Ke {
    fn name(&self) -> &str {
        "ke"
    }

    fn has_scalar(&self) -> bool {
        true
    }

    fn extensive_scalar(&self) -> bool {
        true
    }

    fn scalar(&self, at: &ComputeAt, _vars: &mut dyn VariableSource) -> Result<f64, EngineError> {
        let sim = at.sim;
        Ok(kinetic_energy(&sim.particles, at.group)
            + sim.clumps().map_or(0.0, |c| c.kinetic_energy()))
    }
}

/// `compute ke/atom`: 0.5 m v^2 per particle (energy).
#[derive(Debug)]
pub struct KeAtom;

impl ComputeStyle for KeAtom {
    fn name(&self) -> &str {
        "ke/atom"
    }

    fn per_atom_columns(&self) -> usize {
        1
    }

    fn per_atom(
        &self,
        at: &ComputeAt,
        values: &mut [f64],
        _vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let p = &at.sim.particles;
        for (i, value) in values.iter_mut().enumerate() {
            if at.in_group(i) {
                let v = p.v[i];
                *value = 0.5 * 1.0 * p.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            }
        }
        Ok(())
    }
}

/// `compute ID GROUP ke`.
pub fn build(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    no_arguments(a, "ke")?;
    Ok(Box::new(Ke))
}

/// `compute ID GROUP ke/atom`.
pub fn atom(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    no_arguments(a, "ke/atom")?;
    Ok(Box::new(KeAtom))
}

/// LIGGGHTS's `thermo_kin_eng`, the `ke` compute of group all every deck has.
pub fn thermo_kin_eng() -> Compute {
    Compute {
        id: "thermo_kin_eng".into(),
        style: "ke".into(),
        group: 1,
        calc: Box::new(Ke),
    }
}
