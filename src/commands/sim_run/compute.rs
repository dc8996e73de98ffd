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
    // Not module styles yet (`commands::compute`): temp and pressure (thermo_temp,
    // compute_modify and pressure's temperature read Temp by kind), rdf and slice (global
    // arrays, which the trait does not offer yet), and the local computes (dump local,
    // local/gran/vtk and the pair style read them by kind).
    let kind = match style {
        "temp" => no_keywords(ComputeKind::Temp)?,
        "rdf" => crate::commands::compute_rdf::build(a, ctx)?,
        "pressure" => crate::commands::compute_analysis::pressure(a, ctx)?,
        "slice" => crate::commands::compute_analysis::slice(a, ctx)?,
        "property/local" => crate::commands::compute_analysis::property_local(a)?,
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

pub(super) fn uncompute(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "uncompute ID")?;
    remove_by_id(
        &mut ctx.sim.computes,
        |c| &c.id,
        a,
        "Could not find uncompute ID",
    )
}
