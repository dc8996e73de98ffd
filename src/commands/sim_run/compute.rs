//! `compute` and `uncompute`.

use super::*;

pub(super) fn compute(a: &Args, ctx: &mut Ctx) -> Result {
    use crate::engine::computes::{Compute, ComputeKind};
    a.count(3..=usize::MAX, "compute ID GROUP STYLE ...")?;
    let (id, group, style) = (a.word(0)?, a.word(1)?, a.word(2)?);
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Compute command before simulation box is defined"));
    }
    let bit = ctx
        .sim
        .group_bit(group)
        .ok_or_else(|| a.error(1, "Could not find compute group ID"))?;
    if ctx.sim.computes.iter().any(|c| c.id == id) {
        return Err(a.error(0, "Reuse of compute ID"));
    }
    if let Some(row) = crate::commands::compute::module_row(style) {
        let def = crate::commands::compute::ComputeDef {
            id,
            group,
            bit,
            style,
        };
        let kind = ComputeKind::Style((row.build)(a, ctx, &def)?);
        ctx.sim.computes.push(Compute {
            id: id.into(),
            style: style.into(),
            group: bit,
            kind,
        });
        return Ok(());
    }
    let no_keywords = |kind: ComputeKind| {
        if a.len() > 3 {
            Err(a.error(3, format!("Illegal compute {style} command")))
        } else {
            Ok(kind)
        }
    };
    registry::require_style(a, "compute")?;
    let kind = match style {
        "temp" => no_keywords(ComputeKind::Temp)?,
        "rdf" => crate::commands::compute_rdf::build(a, ctx)?,
        "pressure" => crate::commands::compute_analysis::pressure(a, ctx)?,
        "slice" => crate::commands::compute_analysis::slice(a, ctx)?,
        "property/local" => crate::commands::compute_analysis::property_local(a)?,
        "reduce" => compute_reduce(a, ctx, 3, None)?,
        "reduce/region" => crate::commands::compute_reduce_region::build(a, ctx)?,
        "pair/gran/local" => pair_gran_local(a, ctx)?,
        "wall/gran/local" => crate::commands::fix_state::wall_gran_local(a, ctx, id)?,
        other => return Err(a.unsupported(2, &format!("compute {other}"))),
    };
    ctx.sim.computes.push(Compute {
        id: id.into(),
        style: style.into(),
        group: bit,
        kind,
    });
    Ok(())
}

/// `compute ID GROUP pair/gran/local [FIELD ...]`: one row per touching pair with the
/// fields (LIGGGHTS's defaults without any), defined before the first run.
fn pair_gran_local(
    a: &Args,
    ctx: &Ctx,
) -> std::result::Result<crate::engine::computes::ComputeKind, CommandError> {
    use crate::engine::computes::ComputeKind;
    use crate::engine::computes::LocalField;
    if ctx.sim.step > 0 && !ctx.sim.restart_in_progress {
        return Err(a.error(
            2,
            "Compute pair/gran/local: Need to define this compute before first run",
        ));
    }
    let mut fields = Vec::new();
    for i in 3..a.len() {
        let w = a.word(i)?;
        match LocalField::parse(w) {
            Some(LocalField::HeatFlux) => {
                return Err(a.unsupported(i, "compute pair/gran/local heatFlux"))
            }
            Some(f) => fields.push(f),
            None if w == "verbose" => {}
            None if matches!(w, "heatFlux" | "ms_id") => {
                return Err(a.unsupported(i, &format!("compute pair/gran/local {w}")))
            }
            None => return Err(a.error(i, "Compute pair/gran/local: illegal/unrecognized keyword")),
        }
    }
    if a.len() == 3 {
        fields = LocalField::defaults();
    }
    if ctx
        .sim
        .computes
        .iter()
        .any(|c| matches!(c.kind, ComputeKind::PairGranLocal(_)))
    {
        return Err(a.error(2, "Pair gran allows only one compute of type pair/local"));
    }
    fields.sort();
    fields.dedup();
    Ok(ComputeKind::PairGranLocal(fields))
}

/// `compute ID GROUP reduce MODE input1 input2 ...` (inputs: atom attributes or per-atom
/// computes `c_ID`, `c_ID[N]`), the mode at word `at`; `region`: the region index of
/// `reduce/region`.
pub(crate) fn compute_reduce(
    a: &Args,
    ctx: &Ctx,
    at: usize,
    region: Option<usize>,
) -> std::result::Result<crate::engine::computes::ComputeKind, CommandError> {
    use crate::engine::computes::{column_of, ComputeKind, Input, ReduceMode};
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
    Ok(ComputeKind::Reduce {
        mode,
        inputs,
        region,
    })
}

pub(super) fn uncompute(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "uncompute ID")?;
    remove_by_id(
        &mut ctx.sim.computes,
        |c| &c.id,
        a,
        "Could not find uncompute ID",
    )
}
