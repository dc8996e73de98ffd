//! `fix property/atom/tracer`: mark particles that are inside a region.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;
use crate::engine::tracer::{MarkerStyle, Tracer};

/// `fix ID GROUP property/atom/tracer region_mark R mark_step S [marker_style
/// dirac|heaviside|none] [check_mark_every N]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let id = fix.id;
    let fail = |i: usize, m: &str| a.error(i, format!("Fix property/atom/tracer (id {id}): {m}"));
    let (mut region, mut step, mut style, mut every) = (None, None, MarkerStyle::Dirac, 10);
    let mut first_mark = true;
    let mut i = 3;
    while i < a.len() {
        let key = a.word(i)?;
        if !matches!(
            key,
            "region_mark" | "mark_step" | "marker_style" | "check_mark_every"
        ) {
            return Err(fail(i, "unknown keyword"));
        }
        if a.len() < i + 2 {
            return Err(fail(i, &format!("not enough arguments for '{key}'")));
        }
        match key {
            "region_mark" => {
                region = Some(
                    ctx.sim
                        .regions
                        .find(a.word(i + 1)?)
                        .ok_or_else(|| fail(i + 1, "Region ID does not exist"))?,
                );
            }
            "mark_step" => {
                let s = a.int(i + 1)?;
                if s < 0 {
                    return Err(fail(i + 1, "mark_step > 0 required"));
                }
                if s < ctx.sim.step {
                    first_mark = false;
                }
                step = Some(s);
            }
            "marker_style" => {
                style = match a.word(i + 1)? {
                    "dirac" => MarkerStyle::Dirac,
                    "heaviside" => MarkerStyle::Heaviside,
                    "none" => MarkerStyle::None,
                    _ => {
                        return Err(fail(
                            i + 1,
                            "expecting 'heaviside' or 'dirac' after keyword 'marker_style'",
                        ))
                    }
                };
            }
            _ => {
                every = a.int(i + 1)?;
                if every <= 0 {
                    return Err(fail(i + 1, "check_mark_every > 0 required"));
                }
            }
        }
        i += 2;
    }
    let region = region.ok_or_else(|| fail(2, "expecting keyword 'region_mark'"))?;
    let step = step.ok_or_else(|| fail(2, "expecting keyword 'mark_step'"))?;
    Ok(FixKind::Tracer(Box::new(Tracer {
        region,
        step,
        style,
        every,
        first_mark,
        marker: id.to_string(),
        marked: 0,
        marked_read: std::sync::atomic::AtomicI64::new(0),
    })))
}
