//! `compute coord/atom`: its arguments, with LIGGGHTS 3.8.0's errors.

use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::ComputeKind;
use crate::engine::neighbour_counts::CoordAtom;

/// `compute ID GROUP coord/atom cutoff [typeN ...]` or `... cutoff mix yes|no`.
pub fn build(a: &Args, ctx: &Ctx) -> Result<ComputeKind, CommandError> {
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
    Ok(ComputeKind::CoordAtom(Box::new(coord)))
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
