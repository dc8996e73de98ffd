//! `compute slice`: every Nskip-th element of a global vector or array column of a compute
//! or fix, as a global vector (LIGGGHTS 3.8.0's compute_slice.cpp).

use crate::commands::compute::{after_general_keyword, ComputeDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::global_values::{compute_ext, fix_ext, fix_global_freq, fix_shape};
use crate::engine::sim::{Simulation, VariableSource};

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "slice",
    "compute ID GROUP slice NSTART NSTOP NSKIP c_ID|c_ID[I]|f_ID|f_ID[I]",
    &[],
    "elements NSTART, NSTART+NSKIP, ... below NSTOP of a global vector or array column (a global vector)",
);

/// `compute slice Nstart Nstop Nskip input`: every Nskip-th element of a global vector or
/// array column, from Nstart up to (not including) Nstop.
#[derive(Debug, Clone, PartialEq)]
pub struct Slice {
    /// First element (1-based).
    pub start: usize,
    /// Elements up to this one (exclusive).
    pub stop: usize,
    /// Step between elements.
    pub skip: usize,
    /// `c_ID` or `c_ID[I]`: the compute and its array column (None: its vector).
    pub compute: Option<(String, Option<usize>)>,
    /// `f_ID` or `f_ID[I]`: the fix and its array column.
    pub fix: Option<(String, Option<usize>)>,
}

impl ComputeStyle for Slice {
    fn name(&self) -> &str {
        "slice"
    }

    /// (Nstop - Nstart) / Nskip elements, as LIGGGHTS sizes it.
    fn vector_len(&self) -> usize {
        (self.stop - self.start) / self.skip
    }

    fn vector(
        &self,
        at: &ComputeAt,
        index: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        let sim = at.sim;
        let at = self.start + (index - 1) * self.skip; // 1-based element of the source
        if let Some((id, col)) = &self.compute {
            let c = sim
                .computes
                .iter()
                .find(|c| &c.id == id)
                .ok_or_else(|| format!("Compute ID {id} for compute slice does not exist"))?;
            return match col {
                None => c.vector(at, sim, vars),
                Some(col) => {
                    let (values, cols) = c.global_array(sim)?;
                    Ok(values[(at - 1) * cols + col - 1])
                }
            };
        }
        let (id, col) = self.fix.as_ref().expect("a slice has a compute or a fix");
        let freq = fix_global_freq(sim, id);
        if freq == 0 {
            return Err(crate::engine::global_values::zero_freq(id));
        }
        if sim.step % freq != 0 {
            return Err("Fix used in compute slice not computed at compatible time".into());
        }
        match col {
            None => sim.fix_value(id, Some(at)),
            Some(col) => {
                let at_fix = sim
                    .fixes
                    .iter()
                    .find(|f| &f.id == id)
                    .and_then(|f| f.kind.style_as::<crate::engine::fixes::AveTime>());
                Ok(at_fix.and_then(|a| a.array(at, *col)).unwrap_or(0.0))
            }
        }
    }

    fn extensive(&self, sim: &Simulation, column: Option<usize>) -> Option<i8> {
        if column.is_some() {
            return None;
        }
        match (&self.compute, &self.fix) {
            (Some((id, col)), _) => {
                let src = sim.computes.iter().find(|x| &x.id == id)?;
                compute_ext(sim, src, *col)
            }
            (_, Some((id, col))) => fix_ext(sim, id, *col),
            _ => None,
        }
    }
}

/// `compute ID GROUP slice Nstart Nstop Nskip input` (one `c_ID`, `c_ID[I]`, `f_ID` or
/// `f_ID[I]`; several inputs: not supported, LIGGGHTS 3.8.0 fills only a first column).
pub fn build(
    a: &Args,
    ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
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
    Ok(Box::new(Slice {
        start: start as usize,
        stop,
        skip: skip as usize,
        compute: if is_compute { source.clone() } else { None },
        fix: if is_compute { None } else { source },
    }))
}
