//! `fix balance`: LAMMPS's dynamic load balancing (Debian's LIGGGHTS 3.8.0 has none) on
//! several MPI ranks: every NFREQ steps (a neighbour-list build is forced then, on any rank
//! count) or at every build (NFREQ 0), the brick grid's cuts move by the `shift` style when
//! the imbalance factor exceeds THRESH. `f_ID` is the imbalance factor after the last
//! rebalance; `f_ID[1]` the most particles (weight) on a rank, `f_ID[2]` the iterations,
//! `f_ID[3]` the factor before it. On one process the factor is 1.

use crate::commands::balance::{illegal, parse_shift, parse_weight, rcb_refusal, FIX_USAGE};
use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value, NUMBER};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::decomp::balance::{BalanceFix, Outcome};
use crate::engine::fixes::FixStyle;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "balance",
    FIX_USAGE,
    &[kw(
        "weight",
        &[arg("time", Value::OneOf(&["time"])), arg("FACTOR", NUMBER)],
        "weigh each rank's particles by its measured time per particle, stretched by FACTOR",
    )],
    "move the processor grid's cuts so that each rank holds an even share of the particles (on several MPI ranks)",
);

/// `fix ID GROUP balance NFREQ THRESH shift DIMS NITER STOPTHRESH [weight time FACTOR]`.
pub fn build(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    const WHAT: &str = "fix balance";
    if a.len() < 6 {
        return Err(illegal(a, a.len(), WHAT, FIX_USAGE));
    }
    let every = a.int(3)?;
    if every < 0 {
        return Err(illegal(a, 3, WHAT, "NFREQ >= 0"));
    }
    let thresh = a.real(4)?;
    let (shift, next) = match a.word(5)? {
        "shift" => parse_shift(a, 5, ctx.sim.dimension, WHAT, FIX_USAGE)?,
        "rcb" => return Err(rcb_refusal(WHAT, 5)),
        _ => return Err(illegal(a, 5, WHAT, FIX_USAGE)),
    };
    let weight = parse_weight(a, next, WHAT, FIX_USAGE)?;
    Ok(Box::new(BalanceFix {
        every,
        thresh,
        shift,
        weight,
        last: Outcome::default(),
        clock: 0.0,
    }))
}
