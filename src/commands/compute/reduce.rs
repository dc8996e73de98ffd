//! `compute reduce` and `compute reduce/region`: the sum, minimum, maximum or mean of
//! per-atom inputs over the group (and, for `reduce/region`, inside a region).

use crate::commands::compute::ComputeDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{column_of, ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::fix_columns;
use crate::engine::sim::{Simulation, VariableSource};
use crate::io::dump::Column;

/// The declared signature of `reduce/region`.
pub const REGION: Spec = style(
    "compute",
    "reduce/region",
    "compute ID GROUP reduce/region REGION sum|min|max|ave INPUT ...",
    &[],
    "compute reduce over the group's particles inside a region",
);

/// The declared signature of `reduce`.
pub const SPEC: Spec = style(
    "compute",
    "reduce",
    "compute ID GROUP reduce sum|min|max|ave INPUT ...",
    &[],
    "sum, minimum, maximum or mean of per-particle values",
);

/// The reductions of `compute reduce`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReduceMode {
    /// Sum over the atoms.
    Sum,
    /// Minimum.
    Min,
    /// Maximum.
    Max,
    /// Average (sum over count).
    Ave,
}

/// A per-atom input of `compute reduce`.
#[derive(Debug, Clone, PartialEq)]
pub enum Input {
    /// An atom attribute (x, vx, fx, ...).
    Atom(Column),
    /// A per-atom compute `c_ID` or column `c_ID[N]` (1-based).
    Compute(String, Option<usize>),
    /// An atom-style variable `v_name`.
    Variable(String),
    /// A per-atom fix `f_ID` or column `f_ID[N]` (1-based).
    Fix(String, Option<usize>),
}

/// `compute reduce`: one input gives the scalar `c_ID`, several the vector `c_ID[1..N]`
/// (each in its input's units).
#[derive(Debug)]
pub struct Reduce {
    /// The reduction.
    mode: ReduceMode,
    /// One value per input.
    inputs: Vec<Input>,
    /// `reduce/region`: only atoms inside this region (index) count.
    region: Option<usize>,
}

impl Reduce {
    /// LIGGGHTS's `compute reduce` of one input over the group (atom order), and of
    /// `reduce/region` over the group's atoms inside the region.
    fn reduce(
        &self,
        at: &ComputeAt,
        input: &Input,
        vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        let (sim, mode, region) = (at.sim, self.mode, self.region);
        let p = &sim.particles;
        let n = p.len();
        // the inputs' values for every particle, then one pass over them
        let values: Vec<f64> = match input {
            Input::Atom(col) => (0..n).map(|i| col.value(p, &sim.domain, i)).collect(),
            Input::Compute(id, index) => {
                let c =
                    sim.computes.iter().find(|c| &c.id == id).ok_or_else(|| {
                        format!("Compute ID {id} for compute reduce does not exist")
                    })?;
                let data = c.per_atom(sim, vars)?;
                let col = column_of(c, *index)?;
                (0..n).map(|i| data.get(i, col)).collect()
            }
            Input::Variable(name) => vars.atom(sim, name)?,
            Input::Fix(id, index) => {
                let (data, col) = fix_columns::per_atom(sim, id, *index)?;
                (0..n).map(|i| data.get(i, col)).collect()
            }
        };
        let inside = region.map(|r| sim.regions.matches_each(r, &p.x[..n]));
        let (mut acc, mut count) = match mode {
            ReduceMode::Sum | ReduceMode::Ave => (0.0, 0usize),
            ReduceMode::Min => (1.0e20, 0), // LIGGGHTS's BIG: what an empty group reduces to,
            ReduceMode::Max => (-1.0e20, 0),
        };
        for (i, &v) in values[..n].iter().enumerate() {
            if !at.in_group(i) || inside.as_ref().is_some_and(|inside| !inside[i]) {
                continue;
            }
            count += 1;
            match mode {
                ReduceMode::Sum | ReduceMode::Ave => acc += v,
                ReduceMode::Min => acc = acc.min(v),
                ReduceMode::Max => acc = acc.max(v),
            }
        }
        if mode == ReduceMode::Ave {
            acc = if count > 0 { acc / count as f64 } else { 0.0 };
        }
        Ok(acc)
    }
}

impl ComputeStyle for Reduce {
    fn name(&self) -> &str {
        if self.region.is_some() {
            "reduce/region"
        } else {
            "reduce"
        }
    }

    fn has_scalar(&self) -> bool {
        self.inputs.len() == 1
    }

    fn extensive_scalar(&self) -> bool {
        self.mode == ReduceMode::Sum
    }

    fn scalar(&self, at: &ComputeAt, vars: &mut dyn VariableSource) -> Result<f64, EngineError> {
        self.reduce(at, &self.inputs[0], vars)
    }

    fn vector_len(&self) -> usize {
        if self.inputs.len() > 1 {
            self.inputs.len()
        } else {
            0
        }
    }

    fn vector(
        &self,
        at: &ComputeAt,
        index: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        self.reduce(at, &self.inputs[index - 1], vars)
    }

    fn extensive(&self, _sim: &Simulation, column: Option<usize>) -> Option<i8> {
        column
            .is_none()
            .then_some((self.mode == ReduceMode::Sum) as i8)
    }
}

/// `compute ID GROUP reduce MODE INPUT ...`.
pub fn build(
    a: &Args,
    ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    Ok(Box::new(read(a, ctx, 3, None)?))
}

/// `compute ID GROUP reduce/region REGION MODE INPUT ...`: the region, then the reduction
/// as `compute reduce` reads it.
pub fn region(
    a: &Args,
    ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    if a.len() < 6 {
        return Err(a.error(2, "Illegal compute reduce/region command"));
    }
    let region = ctx
        .sim
        .regions
        .find(a.word(3)?)
        .ok_or_else(|| a.error(3, "Region ID for compute reduce/region does not exist"))?;
    Ok(Box::new(read(a, ctx, 4, Some(region))?))
}

/// `compute ID GROUP reduce MODE input1 input2 ...` (inputs: atom attributes or per-atom
/// computes `c_ID`, `c_ID[N]`), the mode at word `at`; `region`: the region index of
/// `reduce/region`.
fn read(a: &Args, ctx: &Ctx, at: usize, region: Option<usize>) -> Result<Reduce, CommandError> {
    if a.len() < at + 2 {
        return Err(a.error(2, "Illegal compute reduce command"));
    }
    let mode = match a.word(at)? {
        "sum" => ReduceMode::Sum,
        "min" => ReduceMode::Min,
        "max" => ReduceMode::Max,
        "ave" => ReduceMode::Ave,
        "region" => return Err(a.unsupported(at, "compute reduce/region")),
        _ => return Err(a.error(at, "Illegal compute reduce command")),
    };
    let mut inputs = Vec::new();
    for i in at + 1..a.len() {
        let w = a.word(i)?;
        if w == "replace" {
            return Err(a.unsupported(i, "compute reduce replace"));
        }
        if let Some(body) = w.strip_prefix("c_") {
            let (id, index) = crate::util::numbers::split_reference(body)
                .ok_or_else(|| a.error(i, "Illegal compute reduce command"))?;
            let c = ctx
                .sim
                .computes
                .iter()
                .find(|c| c.id == id)
                .ok_or_else(|| a.error(i, "Compute ID for compute reduce does not exist"))?;
            column_of(c, index).map_err(|m| a.error(i, &m))?;
            inputs.push(Input::Compute(id.to_string(), index));
            continue;
        }
        if let Some(name) = w.strip_prefix("v_") {
            match ctx.vars.get(name).map(|v| v.style) {
                Some(crate::lang::variables::Style::Atom) => {}
                Some(_) => {
                    return Err(a.error(i, "Compute reduce variable is not atom-style variable"))
                }
                None => return Err(a.error(i, "Variable name for compute reduce does not exist")),
            }
            inputs.push(Input::Variable(name.to_string()));
            continue;
        }
        if let Some(body) = w.strip_prefix("f_") {
            let (id, index) = crate::util::numbers::split_reference(body)
                .ok_or_else(|| a.error(i, "Illegal compute reduce command"))?;
            if !ctx.sim.fixes.iter().any(|f| f.id == id) {
                return Err(a.error(i, "Fix ID for compute reduce does not exist"));
            }
            crate::engine::fix_columns::column(ctx.sim, id, index)
                .map_err(|e| a.error(i, format!("Compute reduce: {e}")))?;
            inputs.push(Input::Fix(id.to_string(), index));
            continue;
        }
        match crate::io::dump::Column::parse(w) {
            Ok(crate::io::dump::Column::Reference(_)) | Err(_) => {
                return Err(a.error(i, "Illegal compute reduce command"))
            }
            Ok(c) => inputs.push(Input::Atom(c)),
        }
    }
    Ok(Reduce {
        mode,
        inputs,
        region,
    })
}
