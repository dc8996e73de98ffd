//! `fix particledistribution/discrete`: templates drawn by weight.

use super::seed_arg;
use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStyle, RestoreError};
use crate::engine::insert::{Distribution, Template};
use crate::engine::restart_fixes::{doubles, to_bytes};

/// The declared signature (mass fractions).
pub const SPEC: Spec = style(
    "fix",
    "particledistribution/discrete",
    "fix ID GROUP particledistribution/discrete SEED N TEMPLATE FRACTION ...",
    &[],
    "a mix of particle templates by mass fraction",
);

/// The declared signature of the explicitly mass-based style.
pub const MASSBASED: Spec = style(
    "fix",
    "particledistribution/discrete/massbased",
    "fix ID GROUP particledistribution/discrete/massbased SEED N TEMPLATE FRACTION ...",
    &[],
    "a mix of particle templates by mass fraction",
);

/// The declared signature of the number-based style.
pub const NUMBERBASED: Spec = style(
    "fix",
    "particledistribution/discrete/numberbased",
    "fix ID GROUP particledistribution/discrete/numberbased SEED N TEMPLATE FRACTION ...",
    &[],
    "a mix of particle templates by number fraction",
);

/// `fix ID GROUP particledistribution/discrete SEED N T1 W1 ... TN WN`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let style = fix.style;
    a.count(
        7..=usize::MAX,
        &format!("fix ID GROUP {style} SEED N TEMPLATE1 WEIGHT1 ..."),
    )?;
    let seed = seed_arg(a, ctx, 3)?;
    let n = a.int(4)?;
    if n < 1 || a.len() != 5 + 2 * n as usize {
        return Err(a.error(
            4,
            format!("Illegal fix {style} command: expected N template/weight pairs"),
        ));
    }
    let mut templates = Vec::new();
    let mut weights = Vec::new();
    for k in 0..n as usize {
        let tid = a.word(5 + 2 * k)?;
        let t = ctx
            .sim
            .fixes
            .iter()
            .filter(|f| f.id == tid)
            .find_map(|f| match f.kind.template() {
                Some(t) => Some(t.clone()),
                None => Some(Template::clump(
                    f.kind
                        .style_as::<crate::engine::multisphere::ClumpTemplate>()?,
                )),
            })
            .ok_or_else(|| missing_template(a, ctx, 5 + 2 * k, style, tid))?;
        let w = a.real(6 + 2 * k)?;
        // LIGGGHTS refuses only negative weights (a zero weight never inserts its template)
        if w < 0.0 {
            return Err(a.error(
                6 + 2 * k,
                format!("Fix {style}: invalid weight (must be >= 0)"),
            ));
        }
        templates.push(t);
        weights.push(w);
    }
    if weights.iter().all(|&w| w == 0.0) {
        return Err(a.error(
            6,
            format!("Fix {style}: all weights are 0, nothing to insert"),
        ));
    }
    let number_based = style.ends_with("numberbased");
    let names: Vec<&str> = (0..n as usize)
        .map(|k| a.word(5 + 2 * k))
        .collect::<Result<_, _>>()?;
    let d =
        Distribution::new(seed, templates, &weights, number_based).map_err(|m| a.error(3, &m))?;
    report(ctx, fix.id, &names, &weights, &d, number_based);
    Ok(Box::new(d))
}

/// A distribution acts in no phase: the insertion fixes draw from it, found by type
/// ([`FixKind::distribution`]).
///
/// [`FixKind::distribution`]: crate::engine::fixes::FixKind::distribution
impl FixStyle for Distribution {
    /// The family's name (the three styles differ only in how weights are read).
    fn name(&self) -> &str {
        "particledistribution/discrete"
    }

    /// The generator's state (leftover particles).
    fn restart_state(&self) -> Option<Vec<u8>> {
        Some(to_bytes(&[self.rng.state() as f64]))
    }

    fn restore_state(&mut self, state: &[u8]) -> Result<(), RestoreError> {
        let state = *doubles(state)
            .first()
            .ok_or_else(|| RestoreError::Malformed("empty".into()))?;
        self.rng.reset(state as i32)?;
        Ok(())
    }

    fn array_unsupported(&self) -> bool {
        true
    }

    fn refuses_thermo(&self) -> bool {
        true
    }
}

/// LIGGGHTS's printout of a distribution when it is defined (screen only): the weight-sum
/// warning, the mass fractions as given (mass-based styles), then the number fractions.
fn report(
    ctx: &mut Ctx,
    id: &str,
    names: &[&str],
    weights: &[f64],
    d: &crate::engine::insert::Distribution,
    number_based: bool,
) {
    let mut sum = 0.0;
    for w in weights {
        sum += w;
    }
    if (sum - 1.0).abs() > 0.00001 {
        ctx.say("WARNING: particledistribution/discrete: sum of distribution weights != 1, normalizing distribution (./src/fix_particledistribution_discrete.cpp:135)\n");
    }
    if ctx.sys.mode != crate::lang::system::Mode::Run {
        return;
    }
    let e = |x: f64| crate::util::format::with_spec("%e", x).unwrap_or_default();
    let f = |x: f64| crate::util::format::with_spec("%f", x).unwrap_or_default();
    let mut text = String::new();
    let mut block = |what: &str, fractions: &mut dyn Iterator<Item = f64>| {
        text.push_str(&format!(
            "Fix particledistribution/discrete (id {id}): distribution based on {what}%:\n"
        ));
        for ((name, t), w) in names.iter().zip(&d.templates).zip(fractions) {
            text.push_str(&format!(
                "    {name}: d={} (max. bounding sphere) {what}%={}%\n",
                e(2. * t.radius),
                f(100. * w)
            ));
        }
    };
    if !number_based {
        block("mass", &mut weights.iter().map(|w| w / sum));
    }
    block("number", &mut d.weights.iter().copied());
    ctx.out.screen(&text);
}

/// LIGGGHTS's error for a template ID (word `i`) that names no `particletemplate` fix, with
/// what the ID names instead and the nearest template's ID.
fn missing_template(a: &Args, ctx: &Ctx, i: usize, style: &str, tid: &str) -> CommandError {
    let fixes = &ctx.sim.fixes;
    let templates: Vec<&str> = fixes
        .iter()
        .filter(|f| f.style.starts_with("particletemplate/"))
        .map(|f| f.id.as_str())
        .collect();
    let found = match fixes.iter().find(|f| f.id == tid) {
        Some(f) => format!("fix {tid} is a fix {}", f.style),
        None => format!("there is no fix {tid}"),
    };
    let hint = crate::commands::suggest::did_you_mean(tid, &templates)
        .map_or(String::new(), |h| format!("; {h}"));
    let id = a.word(0).unwrap_or("?");
    a.error(
        i,
        format!(
            "Fix {style} (id {id}): invalid ID for fix particletemplate provided ({found}{hint})"
        ),
    )
}
