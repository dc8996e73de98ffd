//! `compute coord/atom`: each particle's partners within a cutoff, one column per type
//! range, with LIGGGHTS 3.8.0's errors.

use crate::commands::compute::ComputeDef;
use crate::commands::specs::{arg, kw, style, Spec, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::neighbour_counts::CoordAtom;
use crate::engine::sim::{Simulation, VariableSource};

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "coord/atom",
    "compute ID GROUP coord/atom CUTOFF [TYPES ...]",
    &[kw(
        "mix",
        &[arg("yes|no", YES_NO)],
        "leave out partners of the particle's own type",
    )],
    "partners within CUTOFF (length) per particle, one column per type range (N, *, N*, *N, M*N)",
);

/// `compute coord/atom`: the counts of partners within the cutoff.
#[derive(Debug)]
pub struct Coord(CoordAtom);

impl ComputeStyle for Coord {
    fn name(&self) -> &str {
        "coord/atom"
    }

    fn init(&self, sim: &Simulation) -> Result<(), EngineError> {
        if sim.pair_selection.is_none() {
            return Err("Compute coord/atom requires a pair style be defined".into());
        }
        if self.0.cutoff > sim.liggghts_cutneighmax() {
            return Err("Compute coord/atom cutoff is longer than neigh cutoff".into());
        }
        Ok(())
    }

    fn per_atom_columns(&self) -> usize {
        self.0.columns()
    }

    fn per_atom(
        &self,
        at: &ComputeAt,
        values: &mut [f64],
        _vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.0.counts(at.sim, at.group, values);
        Ok(())
    }
}

/// `compute ID GROUP coord/atom cutoff [typeN ...]` or `... cutoff mix yes|no`.
pub fn build(
    a: &Args,
    ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let id = a.word(0)?;
    let own = |m: &str| format!("Compute coord/atom (id {id}): {m}");
    if a.len() < 4 {
        return Err(a.error(2, own("Illegal # of arguments")));
    }
    let cutoff = a.real(3)?;
    let ntypes = ctx.sim.ntypes;
    let mut coord = CoordAtom {
        cutoff,
        ranges: vec![(1, ntypes)],
        mix: false,
    };
    if a.len() == 6 && a.word(4)? == "mix" {
        coord.mix = match a.word(5)? {
            "yes" => true,
            "no" => false,
            _ => return Err(a.error(5, own("valid arguments for 'mix' are 'yes' or 'no'"))),
        };
    } else if a.len() > 4 {
        coord.ranges.clear();
        for i in 4..a.len() {
            coord.ranges.push(type_range(a, i, ntypes, "coord/atom")?);
        }
    }
    Ok(Box::new(Coord(coord)))
}

/// A type range (`N`, `*`, `*N`, `N*`, `M*N`) at word `i`: out of 1..=ntypes is LIGGGHTS's
/// bounds error, a reversed range the compute's own (`compute STYLE`).
pub(crate) fn type_range(
    a: &Args,
    i: usize,
    ntypes: u32,
    style: &str,
) -> Result<(u32, u32), CommandError> {
    let w = a.word(i)?;
    match crate::util::numbers::bounds(w, ntypes as i64) {
        Ok((lo, hi)) => Ok((lo as u32, hi as u32)),
        Err(e) => {
            // a reversed range of valid types
            let reversed = w.split_once('*').is_some_and(|(l, h)| {
                let ok = |s: &str| s.parse::<u32>().is_ok_and(|t| (1..=ntypes).contains(&t));
                ok(l) && ok(h)
            });
            Err(if reversed {
                a.error(i, format!("Illegal compute {style} command"))
            } else {
                a.error(i, e)
            })
        }
    }
}
