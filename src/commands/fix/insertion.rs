//! The keywords `fix insert/pack`, `insert/rate/region` and `insert/stream` share, and the
//! table of keyword families their parsers run.

use super::seed_arg;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::insert::Velocity;

/// One family of a style's keywords: reads the keyword `w` at word `i` into the parser's
/// state and gives the words it took, or None when `w` is not of the family.
pub(super) type Family<S> =
    fn(&mut S, &Args, &Ctx, usize, &str) -> Result<Option<usize>, CommandError>;

/// The words the keyword `w` at word `i` takes, read by the first of `families` that knows
/// it (None: no family knows it).
pub(super) fn keyword<S>(
    state: &mut S,
    families: &[Family<S>],
    a: &Args,
    ctx: &Ctx,
    i: usize,
    w: &str,
) -> Result<Option<usize>, CommandError> {
    for family in families {
        if let Some(used) = family(state, a, ctx, i, w)? {
            return Ok(Some(used));
        }
    }
    Ok(None)
}

/// The keywords every insertion fix takes, as given (LIGGGHTS's defaults otherwise).
#[derive(Debug, Clone)]
pub(super) struct Insertion {
    /// `seed S`.
    pub seed: Option<i32>,
    /// `distributiontemplate D`: the ID of a `fix particledistribution/discrete`.
    pub distribution: Option<String>,
    /// `vel constant|uniform|gaussian ...` (m/s).
    pub velocity: Velocity,
    /// `omega constant wx wy wz` (rad/s).
    pub omega: [f64; 3],
    /// `orientation random` (true) or `template`.
    pub random_orientation: bool,
    /// `overlapcheck yes|no`.
    pub overlapcheck: bool,
    /// `maxattempt N`.
    pub maxattempt: i64,
    /// `verbose yes|no`.
    pub verbose: bool,
}

impl Default for Insertion {
    fn default() -> Insertion {
        Insertion {
            seed: None,
            distribution: None,
            velocity: Velocity::Constant([0.0; 3]),
            omega: [0.0; 3],
            random_orientation: false,
            overlapcheck: true,
            maxattempt: 50,
            verbose: true,
        }
    }
}

/// The schedule keywords of the insertion fixes, `insert_every` (or `every`,
/// `insert_every_time`) and `start`, as given.
#[derive(Debug, Clone)]
pub(super) struct Schedule {
    /// `insert_every N` (steps; 0 for `once`).
    pub every: Option<i64>,
    /// `start N` (step; the next step unless given).
    pub start: i64,
    /// insert/pack's forms: `insert_every once`, and a `start` before the next step refused.
    pub region_style: bool,
}

impl Schedule {
    /// LIGGGHTS's defaults at step `step`; `region_style` for insert/pack and insert/rate/region.
    pub fn new(step: i64, region_style: bool) -> Schedule {
        Schedule {
            every: None,
            start: step + 1,
            region_style,
        }
    }

    /// The schedule keyword `w` at word `i` (see [`Family`]).
    pub fn keyword(
        &mut self,
        a: &Args,
        ctx: &Ctx,
        i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        match w {
            "insert_every" | "every" | "insert_every_time" => {
                self.every = Some(if self.region_style && a.word(i + 1)? == "once" {
                    0
                } else if w == "insert_every_time" {
                    (a.real(i + 1)? / ctx.sim.dt) as i32 as i64
                } else {
                    a.int(i + 1)?
                });
            }
            "start" => {
                let st = a.int(i + 1)?;
                if self.region_style && st < ctx.sim.step + 1 {
                    return Err(a.error(
                        i + 1,
                        "Fix insert: 'start' step can not be before current step",
                    ));
                }
                self.start = st;
            }
            _ => return Ok(None),
        }
        Ok(Some(2))
    }
}

/// `yes` or `no` at word `k`: true for yes.
pub(super) fn yes(a: &Args, k: usize) -> Result<bool, CommandError> {
    a.word_in(k, &["yes", "no"]).map(|w| w == "yes")
}

impl Insertion {
    /// The shared keyword `w` at word `i` (see [`Family`]).
    pub fn keyword(
        &mut self,
        a: &Args,
        ctx: &Ctx,
        i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        Ok(Some(match w {
            "seed" => {
                self.seed = Some(seed_arg(a, ctx, i + 1)?);
                2
            }
            "distributiontemplate" => {
                self.distribution = Some(distribution_arg(a, ctx, i + 1)?);
                2
            }
            "overlapcheck" => {
                self.overlapcheck = yes(a, i + 1)?;
                2
            }
            "verbose" => {
                self.verbose = yes(a, i + 1)?;
                2
            }
            "maxattempt" => {
                self.maxattempt = a.int32(i + 1)?;
                2
            }
            "vel" => {
                let used;
                (self.velocity, used) = insertion_velocity(a, i)?;
                used
            }
            "omega" => {
                a.word_in(i + 1, &["constant"])?;
                self.omega = [a.real(i + 2)?, a.real(i + 3)?, a.real(i + 4)?];
                5
            }
            "orientation" => {
                self.random_orientation = orientation_arg(a, i)?;
                2
            }
            _ => return Ok(None),
        }))
    }
}

/// The `distributiontemplate` ID at word `i`: a `fix particledistribution/discrete`, else
/// LIGGGHTS's error with what the ID names instead and the nearest distribution's ID.
fn distribution_arg(a: &Args, ctx: &Ctx, i: usize) -> Result<String, CommandError> {
    let d = a.word(i)?;
    let fixes = &ctx.sim.fixes;
    if fixes
        .iter()
        .any(|f| f.id == d && f.kind.distribution().is_some())
    {
        return Ok(d.to_string());
    }
    let distributions: Vec<&str> = fixes
        .iter()
        .filter(|f| f.kind.distribution().is_some())
        .map(|f| f.id.as_str())
        .collect();
    let found = match fixes.iter().find(|f| f.id == d) {
        Some(f) => format!("fix {d} is a fix {}", f.style),
        None => format!("there is no fix {d}"),
    };
    let hint = crate::commands::suggest::did_you_mean(d, &distributions)
        .map_or(String::new(), |h| format!("; {h}"));
    Err(a.error(
        i,
        format!(
            "Fix {} (id {}): Fix insert requires you to define a valid ID for a fix of type \
             particledistribution/discrete ({found}{hint})",
            a.word(2)?,
            a.word(0)?
        ),
    ))
}

/// The `vel constant vx vy vz` or `vel uniform|gaussian vx vy vz dvx dvy dvz` keyword of
/// the insertion fixes at word `i`: the velocity (m/s) and the words it took.
fn insertion_velocity(a: &Args, i: usize) -> Result<(Velocity, usize), CommandError> {
    let v = [a.real(i + 2)?, a.real(i + 3)?, a.real(i + 4)?];
    Ok(
        match a.word_in(i + 1, &["constant", "uniform", "gaussian"])? {
            "constant" => (Velocity::Constant(v), 5),
            style => {
                let d = [a.real(i + 5)?, a.real(i + 6)?, a.real(i + 7)?];
                if style == "uniform" {
                    (Velocity::Uniform(v, d), 8)
                } else {
                    (Velocity::Gaussian(v, d), 8)
                }
            }
        },
    )
}

/// `orientation random|template` of an insertion fix at `i`: true for random (`constant`
/// is not supported yet).
fn orientation_arg(a: &Args, i: usize) -> Result<bool, CommandError> {
    match a.word(i + 1)? {
        "random" => Ok(true),
        "template" => Ok(false),
        "constant" => Err(a.unsupported(i + 1, "insertion orientation constant")),
        _ => Err(a.error(
            i + 1,
            "expecting 'random', template' or 'constant' after keyword 'quat'",
        )),
    }
}

impl Insertion {
    /// LIGGGHTS's check when an insertion fix is made: its seed, its distribution's
    /// generator and the insertion generators of the distribution's templates must all
    /// differ (compared as their states now, as LIGGGHTS compares them).
    pub fn check_seeds(&self, a: &Args, ctx: &Ctx) -> Result<(), CommandError> {
        let (Some(seed), Some(dist_id)) = (self.seed, self.distribution.as_deref()) else {
            return Ok(());
        };
        let Some(dist) = ctx
            .sim
            .fixes
            .iter()
            .find(|f| f.id == dist_id)
            .and_then(|f| f.kind.distribution())
        else {
            return Ok(());
        };
        let mut seeds = vec![seed, dist.rng.state()];
        seeds.extend(dist.templates.iter().map(|t| t.rng_state.0));
        seeds.sort_unstable();
        let n = seeds.len();
        seeds.dedup();
        if seeds.len() == n {
            return Ok(());
        }
        let at = (0..a.len())
            .find(|&i| a.word(i).is_ok_and(|w| w == "seed"))
            .map_or(2, |i| i + 1);
        Err(a.error(
            at,
            format!(
                "Fix {}, ID {}: Random number generation: It is required that all the random \
                 seeds of this fix insert/*, the random seed of particle distribution fix (id \
                 {dist_id}) template and all random seeds of the fix particletemplate/* commands \
                 used by particle distribution fix (id {dist_id}) are different. Hint: possible \
                 valid (different) seeds would be the following numbers: 15485863, 15485867, \
                 32452843, 32452867, 49979687, 49979693, 67867967, 67867979, 86028121, 86028157",
                a.word(2)?,
                a.word(0)?
            ),
        ))
    }
}
