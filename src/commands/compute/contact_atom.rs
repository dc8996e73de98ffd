//! `compute contact/atom [skin S]`: each particle's partners within the sum of the radii
//! plus S.

use crate::commands::compute::ComputeDef;
use crate::commands::specs::{arg, kw, style, Spec, LENGTH};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::{Simulation, VariableSource};

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "contact/atom",
    "compute ID GROUP contact/atom",
    &[kw(
        "skin",
        &[arg("S", LENGTH)],
        "count contacts within this gap",
    )],
    "number of contacts per particle",
);

/// `compute contact/atom`: the count of neighbours touching each particle of the group.
#[derive(Debug)]
pub struct ContactAtom {
    /// Extra distance beyond the sum of the radii (length).
    skin: f64,
}

impl ComputeStyle for ContactAtom {
    fn name(&self) -> &str {
        "contact/atom"
    }

    fn init(&self, sim: &Simulation) -> Result<(), EngineError> {
        if sim.pair_selection.is_none() {
            return Err("Compute contact/atom requires a pair style be defined".into());
        }
        Ok(())
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
        crate::engine::neighbour_counts::contact_counts(at.sim, at.group, self.skin, values);
        Ok(())
    }
}

/// `compute ID GROUP contact/atom [skin S]`.
pub fn build(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let mut skin = 0.0;
    if a.len() > 3 {
        if a.len() != 5 {
            return Err(a.error(3, "Illegal compute contact/atom command"));
        }
        if a.word(3)? != "skin" {
            return Err(a.error(
                3,
                "Illegal compute contact/atom command, expecting keyword 'skin'",
            ));
        }
        skin = a.real(4)?;
    }
    Ok(Box::new(ContactAtom { skin }))
}
