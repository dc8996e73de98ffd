//! `compute property/atom`: atom attributes as per-atom columns.

use crate::commands::compute::ComputeDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;
use crate::io::dump::Column;

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "property/atom",
    "compute ID GROUP property/atom ATTRIBUTE ...",
    &[],
    "per-particle attributes as columns",
);

/// `compute property/atom`: one column per attribute, in the attribute's units.
#[derive(Debug)]
pub struct PropertyAtom(Vec<Column>);

impl ComputeStyle for PropertyAtom {
    fn name(&self) -> &str {
        "property/atom"
    }

    fn per_atom_columns(&self) -> usize {
        self.0.len()
    }

    fn per_atom(
        &self,
        at: &ComputeAt,
        values: &mut [f64],
        _vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let (p, domain) = (&at.sim.particles, &at.sim.domain);
        let columns = self.0.len();
        for i in (0..p.len()).filter(|&i| at.in_group(i)) {
            for (k, c) in self.0.iter().enumerate() {
                values[i * columns + k] = c.value(p, domain, i);
            }
        }
        Ok(())
    }
}

/// `compute ID GROUP property/atom ATTRIBUTE ...` (the attributes of dump custom).
pub fn build(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    if a.len() < 4 {
        return Err(a.error(2, "Illegal compute property/atom command"));
    }
    let mut cols = Vec::new();
    for i in 3..a.len() {
        let w = a.word(i)?;
        match Column::parse(w) {
            Ok(Column::Reference(_)) | Err(_) => {
                return Err(a.unsupported(i, &format!("compute property/atom {w}")))
            }
            Ok(c) => cols.push(c),
        }
    }
    Ok(Box::new(PropertyAtom(cols)))
}
