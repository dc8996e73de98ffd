//! `fix particledistribution/discrete`: templates drawn by weight.

use super::seed_arg;
use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP particledistribution/discrete SEED N T1 W1 ... TN WN`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
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
            .find_map(|f| match &f.kind {
                FixKind::Template(t) if f.id == tid => Some(t.clone()),
                kind if f.id == tid => Some(crate::engine::insert::Template::clump(
                    kind.style_as::<crate::engine::multisphere::ClumpTemplate>()?,
                )),
                _ => None,
            })
            .ok_or_else(|| {
                a.error(
                    5 + 2 * k,
                    format!("Fix {style}: could not find fix particletemplate {tid}"),
                )
            })?;
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
    let d = crate::engine::insert::Distribution::new(seed, templates, &weights, number_based)
        .map_err(|m| a.error(3, &m))?;
    report(ctx, fix.id, &names, &weights, &d, number_based);
    Ok(FixKind::Distribution(d))
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
