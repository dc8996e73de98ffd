//! `fix ave/atom`: per-particle time averages (f_ID, or f_ID[N] with several inputs).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::ave_atom::{AtomInput, AveAtom};
use crate::engine::fixes::FixStyle;
use crate::io::dump::Column;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "ave/atom",
    "fix ID GROUP ave/atom NEVERY NREPEAT NFREQ x|y|z|vx|vy|vz|fx|fy|fz|c_ID|c_ID[N]|f_ID|f_ID[N]|v_NAME ...",
    &[],
    "per-particle time averages of NREPEAT samples every NEVERY steps, ending on multiples of NFREQ (f_ID or f_ID[N] in dumps)",
);

/// `fix ID GROUP ave/atom NEVERY NREPEAT NFREQ input ...` with inputs x y z vx vy vz fx fy
/// fz, c_ID, c_ID[N], f_ID, f_ID[N], v_name.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() < 7 {
        return Err(a.error(3, "Illegal fix ave/atom command"));
    }
    let (every, repeat, freq) = (a.int(3)?, a.int(4)?, a.int(5)?);
    let mut inputs = Vec::new();
    for i in 6..a.len() {
        let w = a.word(i)?;
        let input = match w {
            "x" | "y" | "z" | "vx" | "vy" | "vz" | "fx" | "fy" | "fz" => AtomInput::Atom(
                Column::parse(w).map_err(|_| a.error(i, "Illegal fix ave/atom command"))?,
            ),
            _ => {
                let Some(body) = w
                    .strip_prefix("c_")
                    .or_else(|| w.strip_prefix("f_"))
                    .or_else(|| w.strip_prefix("v_"))
                else {
                    return Err(a.error(i, "Illegal fix ave/atom command"));
                };
                let (id, index) = crate::util::numbers::split_reference(body)
                    .ok_or_else(|| a.error(i, "Illegal fix ave/atom command"))?;
                input(a, ctx, i, &w[..2], id, index)?
            }
        };
        inputs.push(input);
    }
    if every <= 0 || repeat <= 0 || freq <= 0 {
        return Err(a.error(3, "Illegal fix ave/atom command"));
    }
    if freq % every != 0 || (repeat - 1) * every >= freq {
        return Err(a.error(3, "Illegal fix ave/atom command"));
    }
    let mut ave = AveAtom {
        every,
        repeat,
        freq,
        inputs,
        nvalid: 0,
        irepeat: 0,
        array: format!("ave_atom_{}", fix.id),
    };
    ave.nvalid = ave.next_valid(ctx.sim.step);
    // the averages start at zero (a dump may read them before the first average)
    let n = ave.inputs.len();
    let k = ctx.sim.particles.extra_index(&ave.array, n);
    ctx.sim.particles.extra[k].data.fill(0.0);
    Ok(Box::new(ave))
}

/// A `c_`, `f_` or `v_` input, checked as LIGGGHTS checks it when the fix is defined.
fn input(
    a: &Args,
    ctx: &Ctx,
    i: usize,
    prefix: &str,
    id: &str,
    index: Option<usize>,
) -> Result<AtomInput, CommandError> {
    match prefix {
        "c_" => {
            let c = super::input_compute(a, ctx, i, id, "ave/atom")?;
            crate::engine::computes::column_of(c, index)
                .map_err(|e| a.error(i, format!("fix ave/atom: {e}")))?;
            Ok(AtomInput::Compute(id.to_string(), index))
        }
        "f_" => {
            crate::engine::fix_columns::column(ctx.sim, id, index)
                .map_err(|e| a.error(i, format!("fix ave/atom: {e}")))?;
            Ok(AtomInput::Fix(id.to_string(), index))
        }
        _ => {
            super::input_atom_variable(a, ctx, i, id, "ave/atom")?;
            Ok(AtomInput::Variable(id.to_string()))
        }
    }
}
