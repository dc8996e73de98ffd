//! `balance THRESH STYLE ARGS ... [weight time FACTOR]`, LAMMPS's static load balancing
//! (Debian's LIGGGHTS 3.8.0 has no `balance`): the `shift` style (`shift DIMS NITER
//! STOPTHRESH`) or the `x`/`y`/`z` styles (`uniform` or the Px-1 interior cuts as fractions
//! of the box), weighted by particle count or by each rank's measured time per particle.
//! The brick grid stays a grid; `rcb` (a tiled decomposition) is not supported yet.

use crate::commands::{Args, At, CommandError, Ctx};
use crate::engine::decomp::balance::{Shift, Weight};
use crate::engine::sim::{BalanceRequest, Cuts};

type Result<T> = std::result::Result<T, CommandError>;

/// The `balance` command's usage.
pub const USAGE: &str = "balance THRESH shift DIMS NITER STOPTHRESH [weight time FACTOR] | \
    balance THRESH x uniform|C1 ... [y ...] [z ...] [weight time FACTOR]";

/// The `fix balance` usage.
pub const FIX_USAGE: &str =
    "fix ID GROUP balance NFREQ THRESH shift DIMS NITER STOPTHRESH [weight time FACTOR]";

/// What the balancing styles regolith runs are, for the refusals.
const SUPPORTED: &str = "supported: shift DIMS NITER STOPTHRESH and x/y/z cuts (a brick grid), \
    weighted by count or `weight time FACTOR`";

/// An illegal argument at `i`: LAMMPS's message with the usage expected.
pub(crate) fn illegal(a: &Args, i: usize, what: &str, usage: &str) -> CommandError {
    CommandError::BadArgument {
        message: format!("Illegal {what} command"),
        at: At::Arg(i.min(a.len().saturating_sub(1))),
        expected: format!("expected: {usage}"),
    }
}

/// `shift DIMS NITER STOPTHRESH` at argument `i` (the word `shift`), in a `dimension`-d
/// deck: the settings and the next argument.
pub(crate) fn parse_shift(
    a: &Args,
    i: usize,
    dimension: u32,
    what: &str,
    usage: &str,
) -> Result<(Shift, usize)> {
    if i + 4 > a.len() {
        return Err(illegal(a, a.len(), what, usage));
    }
    let word = a.word(i + 1)?;
    let mut dims = Vec::new();
    for ch in word.chars() {
        let d = match ch {
            'x' => 0,
            'y' => 1,
            'z' if dimension == 3 => 2,
            _ => {
                return Err(CommandError::BadArgument {
                    message: "Balance shift string is invalid".into(),
                    at: At::Arg(i + 1),
                    expected: "expected: DIMS of x, y and z (no z in 2d), each at most once".into(),
                })
            }
        };
        if dims.contains(&d) || dims.len() == 3 {
            return Err(CommandError::BadArgument {
                message: "Balance shift string is invalid".into(),
                at: At::Arg(i + 1),
                expected: "expected: DIMS of x, y and z (no z in 2d), each at most once".into(),
            });
        }
        dims.push(d);
    }
    if dims.is_empty() {
        return Err(illegal(a, i + 1, what, usage));
    }
    let niter = a.int(i + 2)?;
    if niter <= 0 {
        return Err(illegal(a, i + 2, what, "NITER > 0"));
    }
    let stopthresh = a.real(i + 3)?;
    if stopthresh < 1.0 {
        return Err(illegal(a, i + 3, what, "STOPTHRESH >= 1.0"));
    }
    let shift = Shift {
        dims,
        niter: niter as usize,
        stopthresh,
    };
    Ok((shift, i + 4))
}

/// The keywords after the style from argument `i` (`weight time FACTOR`; the other weights
/// and `out` are not supported yet): the weighting.
pub(crate) fn parse_weight(a: &Args, mut i: usize, what: &str, usage: &str) -> Result<Weight> {
    let mut weight = Weight::Count;
    while i < a.len() {
        match a.word(i)? {
            "weight" => {
                let style = a.word(i + 1).map_err(|_| illegal(a, i, what, usage))?;
                match style {
                    "time" => {
                        let factor = a
                            .real(i + 2)
                            .map_err(|_| illegal(a, i + 1, what, "weight time FACTOR"))?;
                        if factor <= 0.0 {
                            return Err(illegal(a, i + 2, what, "weight time FACTOR > 0"));
                        }
                        weight = Weight::Time(factor);
                        i += 3;
                    }
                    "group" | "neigh" | "var" | "store" => {
                        return Err(CommandError::unsupported(
                            format!("{what} weight {style} ({SUPPORTED})"),
                            At::Arg(i + 1),
                        ))
                    }
                    _ => return Err(illegal(a, i + 1, what, usage)),
                }
            }
            "out" => {
                return Err(CommandError::unsupported(
                    format!("{what} out ({SUPPORTED})"),
                    At::Arg(i),
                ))
            }
            _ => return Err(a.keyword_error(i, &["weight"])),
        }
    }
    Ok(weight)
}

/// `rcb`, refused by name.
pub(crate) fn rcb_refusal(what: &str, i: usize) -> CommandError {
    CommandError::unsupported(
        format!("{what} rcb (recursive bisection needs a tiled decomposition; {SUPPORTED})"),
        At::Arg(i),
    )
}

/// The `balance` command (see the module's description): the cuts moved, LAMMPS's report
/// printed (rank 0, run mode).
pub fn balance(a: &Args, ctx: &mut Ctx) -> Result<()> {
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Balance command before simulation box is defined"));
    }
    if a.len() < 2 {
        return Err(illegal(a, a.len(), "balance", USAGE));
    }
    let thresh = a.real(0)?;
    let procs = ctx.sim.balance_procs().map_err(|e| a.engine_error(0, e))?;
    let mut req = BalanceRequest {
        thresh,
        shift: None,
        cuts: [Cuts::Keep, Cuts::Keep, Cuts::Keep],
        weight: Weight::Count,
    };
    let mut i = 1;
    while i < a.len() {
        let w = a.word(i)?;
        match w {
            "x" | "y" | "z" => {
                if req.shift.is_some() {
                    return Err(illegal(a, i, "balance", USAGE));
                }
                let d = usize::from(w.as_bytes()[0] - b'x');
                if d == 2 && ctx.sim.dimension == 2 {
                    return Err(a.error(i, "Cannot balance in z dimension for 2d simulation"));
                }
                if a.word(i + 1).ok() == Some("uniform") {
                    req.cuts[d] = Cuts::Uniform;
                    i += 2;
                    continue;
                }
                let n = procs[d] - 1;
                if i + 1 + n > a.len() {
                    let usage = format!(
                        "{w} uniform or {n} cuts between 0 and 1 ({} processors along {w})",
                        procs[d]
                    );
                    return Err(illegal(a, a.len(), "balance", &usage));
                }
                let mut cuts = Vec::with_capacity(n);
                for k in 0..n {
                    cuts.push(a.real(i + 1 + k)?);
                }
                let mut last = 0.0;
                for (k, &c) in cuts.iter().enumerate() {
                    if c <= last || c >= 1.0 {
                        return Err(illegal(
                            a,
                            i + 1 + k,
                            "balance",
                            "cuts ascending strictly between 0 and 1",
                        ));
                    }
                    last = c;
                }
                req.cuts[d] = Cuts::At(cuts);
                i += 1 + n;
            }
            "shift" => {
                if req.shift.is_some() || req.cuts.iter().any(|c| *c != Cuts::Keep) {
                    return Err(illegal(a, i, "balance", USAGE));
                }
                let (shift, next) = parse_shift(a, i, ctx.sim.dimension, "balance", USAGE)?;
                req.shift = Some(shift);
                i = next;
            }
            "rcb" => return Err(rcb_refusal("balance", i)),
            _ => break,
        }
    }
    if req.shift.is_none() && req.cuts.iter().all(|c| *c == Cuts::Keep) {
        return Err(illegal(a, i, "balance", USAGE));
    }
    req.weight = parse_weight(a, i, "balance", USAGE)?;
    let text = ctx
        .sim
        .balance_command(&req)
        .map_err(|e| a.engine_error(0, e))?;
    ctx.say(&text);
    Ok(())
}
