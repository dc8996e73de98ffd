//! `compute slice`, `pressure` and `property/local`: their arguments, with LIGGGHTS
//! 3.8.0's errors.

use crate::commands::{Args, CommandError, Ctx};
use crate::engine::analysis_computes::{Pressure, Slice};
use crate::engine::computes::ComputeKind;
use crate::engine::global_values::fix_shape;

/// The first word after LIGGGHTS's general compute keyword `update_on_run_end yes|no`.
pub fn after_general_keyword(a: &Args, style: &str) -> Result<usize, CommandError> {
    if a.len() < 4 || a.word(3)? != "update_on_run_end" {
        return Ok(3);
    }
    if a.len() < 5 {
        return Err(a.error(3, "Not enough arguments for keyword 'update_on_run_end'"));
    }
    match a.word(4)? {
        "no" => Ok(5),
        "yes" => Err(a.unsupported(4, &format!("compute {style} update_on_run_end yes"))),
        _ => Err(a.error(
            4,
            "Value for keyword 'update_on_run_end' must be either 'yes' or 'no'",
        )),
    }
}

/// `compute ID all pressure temp-ID [ke pair bond angle dihedral improper kspace fix virial]`.
pub fn pressure(a: &Args, ctx: &Ctx) -> Result<ComputeKind, CommandError> {
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
    if !matches!(t.kind, ComputeKind::Temp) {
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
    Ok(ComputeKind::Pressure(Box::new(Pressure {
        temp: temp.to_string(),
        ke,
        pair,
    })))
}

/// `compute ID GROUP slice Nstart Nstop Nskip input` (one `c_ID`, `c_ID[I]`, `f_ID` or
/// `f_ID[I]`; several inputs: not supported, LIGGGHTS 3.8.0 fills only a first column).
pub fn slice(a: &Args, ctx: &Ctx) -> Result<ComputeKind, CommandError> {
    let i = after_general_keyword(a, "slice")?;
    let illegal = |k: usize| a.error(k, "Illegal compute slice command");
    if a.len() < i + 4 {
        return Err(illegal(2));
    }
    let (start, stop, skip) = (a.int32(i)?, a.int32(i + 1)?, a.int32(i + 2)?);
    if start < 1 || stop < start || skip < 1 {
        return Err(illegal(i));
    }
    for k in i + 3..a.len() {
        let w = a.word(k)?;
        if !(w.starts_with("c_") || w.starts_with("f_")) {
            return Err(illegal(k));
        }
    }
    if a.len() > i + 4 {
        return Err(a.unsupported(
            i + 4,
            "compute slice of several inputs (LIGGGHTS 3.8.0 fills only its first column)",
        ));
    }
    let k = i + 3;
    let w = a.word(k)?;
    let (id, index) =
        crate::util::numbers::split_reference_atoi(&w[2..]).ok_or_else(|| illegal(k))?;
    let is_compute = w.starts_with("c_");
    let (what, shape) = if is_compute {
        let Some(c) = ctx.sim.computes.iter().find(|c| c.id == id) else {
            return Err(a.error(k, "Compute ID for compute slice does not exist"));
        };
        ("compute", c.shape())
    } else {
        let Some(s) = fix_shape(ctx.sim, id) else {
            return Err(a.error(k, "Fix ID for compute slice does not exist"));
        };
        ("fix", s)
    };
    let err = |m: &str| Err(a.error(k, format!("Compute slice {what} {m}")));
    let stop = stop as usize;
    if shape.vector > 0 {
        if index.is_some() {
            return err("does not calculate a global array");
        }
        if stop > shape.vector {
            return err("vector is accessed out-of-range");
        }
    } else if let Some((rows, cols)) = shape.array {
        match index {
            None => return err("does not calculate a global vector"),
            Some(col) if col > cols => return err("array is accessed out-of-range"),
            _ if stop > rows => return err("array is accessed out-of-range"),
            _ => {}
        }
    } else {
        return err("does not calculate global vector or array");
    }
    let source = Some((id.to_string(), index));
    Ok(ComputeKind::Slice(Box::new(Slice {
        start: start as usize,
        stop,
        skip: skip as usize,
        compute: if is_compute { source.clone() } else { None },
        fix: if is_compute { None } else { source },
    })))
}

/// `compute ID GROUP property/local attribute ...`: LIGGGHTS's argument errors; pairs and
/// neighbours are refused at the run's init (granular pair styles have no `single()`),
/// bonds, angles, dihedrals and impropers here (atom style granular has none).
pub fn property_local(a: &Args) -> Result<ComputeKind, CommandError> {
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
    Ok(ComputeKind::PropertyLocal)
}
