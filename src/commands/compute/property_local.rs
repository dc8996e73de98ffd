//! `compute property/local`: LIGGGHTS 3.8.0's argument errors; its pair and neighbour
//! inputs are refused at the run's init as LIGGGHTS refuses them (granular pair styles
//! have no `single()`), so it never calculates.

use crate::commands::compute::{after_general_keyword, ComputeDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle, LocalRows};
use crate::engine::error::EngineError;
use crate::engine::sim::Simulation;

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "property/local",
    "compute ID GROUP property/local patom1|patom2|ptype1|ptype2|natom1|... ...",
    &[],
    "per-pair IDs and types; as LIGGGHTS 3.8.0, a run refuses it (granular pair styles have no single())",
);

/// `compute property/local` of neighbour or pair inputs (patom1, ntype2, ...).
#[derive(Debug)]
pub struct PropertyLocal;

impl ComputeStyle for PropertyLocal {
    fn name(&self) -> &str {
        "property/local"
    }

    fn init(&self, sim: &Simulation) -> Result<(), EngineError> {
        Err(if sim.pair_selection.is_none() {
            "No pair style is defined for compute property/local"
        } else {
            "Pair style does not support compute property/local"
        }
        .to_string()
        .into())
    }

    /// `dump local` takes it (the run refuses it at init, as LIGGGHTS).
    fn local_rows(&self) -> Option<LocalRows> {
        Some(LocalRows::VectorOrArray)
    }

    fn local(&self, at: &ComputeAt) -> Result<(usize, Vec<f64>), EngineError> {
        Err(format!(
            "Compute {} (property/local) does not calculate local values",
            at.id
        )
        .into())
    }
}

/// `compute ID GROUP property/local attribute ...`: bonds, angles, dihedrals and impropers
/// are refused here (atom style granular has none).
pub fn build(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let i = after_general_keyword(a, "property/local")?;
    if a.len() < i + 1 {
        return Err(a.error(2, "Illegal compute property/local command"));
    }
    let mut kind = None;
    for k in i..a.len() {
        let w = a.word(k)?;
        let this = match w {
            "natom1" | "natom2" | "ntype1" | "ntype2" => "neigh",
            "patom1" | "patom2" | "ptype1" | "ptype2" => "pair",
            "batom1" | "batom2" | "btype" => "bond",
            "aatom1" | "aatom2" | "aatom3" | "atype" => "angle",
            "datom1" | "datom2" | "datom3" | "datom4" | "dtype" => "dihedral",
            "iatom1" | "iatom2" | "iatom3" | "iatom4" | "itype" => "improper",
            _ => return Err(a.error(k, "Invalid keyword in compute property/local command")),
        };
        if kind.is_some_and(|c| c != this) {
            return Err(a.error(k, "Compute property/local cannot use these inputs together"));
        }
        kind = Some(this);
    }
    if !matches!(kind, Some("neigh" | "pair")) {
        return Err(a.error(
            2,
            "Compute property/local for property that isn't allocated",
        ));
    }
    Ok(Box::new(PropertyLocal))
}
