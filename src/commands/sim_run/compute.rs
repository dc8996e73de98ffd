//! `compute` and `uncompute`.

use super::*;

/// `compute ID GROUP STYLE ...`: the style's own file builds the compute (see
/// [`crate::commands::compute`]).
pub(super) fn compute(a: &Args, ctx: &mut Ctx) -> Result {
    use crate::engine::computes::Compute;
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
    let row = crate::commands::compute::TABLE.row_for(a, "compute")?;
    let def = crate::commands::compute::ComputeDef {
        id,
        group,
        bit,
        style,
    };
    let calc = (row.build)(a, ctx, &def)?;
    if let Some((fid, fstyle)) = crate::engine::fix_timing::created_with_compute(id, style) {
        ctx.sim.modify_list.ensure(&fid, &fstyle, Some(id));
    }
    ctx.sim.computes.push(Compute {
        id: id.into(),
        style: style.into(),
        group: bit,
        calc,
    });
    Ok(())
}

pub(super) fn uncompute(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "uncompute ID")?;
    remove_by_id(
        &mut ctx.sim.computes,
        |c| &c.id,
        a,
        "Could not find uncompute ID",
    )?;
    ctx.sim.modify_list.remove(a.word(0)?);
    Ok(())
}
