//! `compute msd` and `compute displace/atom`: displacements from where the group's particles
//! were (unwrapped) when the compute was defined.

use crate::commands::compute::ComputeDef;
use crate::commands::specs::{arg, kw, style, Spec, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle};
use crate::engine::displacement::Origins;
use crate::engine::error::EngineError;
use crate::engine::particles::Particles;
use crate::engine::sim::{Simulation, VariableSource};

/// The declared signature of `msd`.
pub const MSD: Spec = style(
    "compute",
    "msd",
    "compute ID GROUP msd",
    &[kw(
        "com",
        &[arg("yes|no", YES_NO)],
        "displacements relative to the group's centre of mass",
    )],
    "mean squared displacement (area) along x, y, z and in total since the compute was defined (c_ID[1..4])",
);

/// The declared signature of `displace/atom`.
pub const ATOM: Spec = style(
    "compute",
    "displace/atom",
    "compute ID GROUP displace/atom",
    &[],
    "per-particle displacement dx dy dz and distance (length) since the compute was defined",
);

/// `compute msd`: the group's mean squared displacement along x, y, z and in total (area,
/// `c_ID[1..4]`).
#[derive(Debug)]
pub struct Msd(Origins);

impl ComputeStyle for Msd {
    fn name(&self) -> &str {
        "msd"
    }

    fn setup(&mut self, p: &Particles, group: u32) {
        self.0.init(p, group);
    }

    fn vector_len(&self) -> usize {
        4
    }

    fn vector(
        &self,
        at: &ComputeAt,
        index: usize,
        _vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        let sim = at.sim;
        Ok(self.0.msd(&sim.particles, &sim.domain, at.group)[index - 1])
    }

    fn extensive(&self, _sim: &Simulation, column: Option<usize>) -> Option<i8> {
        column.is_none().then_some(0)
    }

    fn keeps_per_atom_state(&self) -> bool {
        true
    }
}

/// `compute displace/atom`: dx, dy, dz and the distance per particle (length).
#[derive(Debug)]
pub struct DisplaceAtom(Origins);

impl ComputeStyle for DisplaceAtom {
    fn name(&self) -> &str {
        "displace/atom"
    }

    fn per_atom_columns(&self) -> usize {
        4
    }

    fn per_atom(
        &self,
        at: &ComputeAt,
        values: &mut [f64],
        _vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let sim = at.sim;
        self.0
            .displace(&sim.particles, &sim.domain, at.group, values);
        Ok(())
    }

    fn keeps_per_atom_state(&self) -> bool {
        true
    }
}

/// `compute ID GROUP msd [com yes|no]`.
pub fn msd(
    a: &Args,
    ctx: &mut Ctx,
    def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let illegal = "Illegal compute msd command";
    let mut com = false;
    let mut i = 3;
    while i < a.len() {
        if a.word(i)? != "com" || a.len() < i + 2 {
            return Err(a.error(i, illegal));
        }
        com = match a.word(i + 1)? {
            "yes" => true,
            "no" => false,
            _ => return Err(a.error(i + 1, illegal)),
        };
        i += 2;
    }
    let origins = Origins::new(&ctx.sim.particles, &ctx.sim.domain, def.bit, com);
    Ok(Box::new(Msd(origins)))
}

/// `compute ID GROUP displace/atom`.
pub fn atom(
    a: &Args,
    ctx: &mut Ctx,
    def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    if a.len() > 3 {
        return Err(a.error(3, "Illegal compute displace/atom command"));
    }
    let origins = Origins::new(&ctx.sim.particles, &ctx.sim.domain, def.bit, false);
    Ok(Box::new(DisplaceAtom(origins)))
}
