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
    crate::engine::insert::Distribution::new(seed, templates, &weights, number_based)
        .map(FixKind::Distribution)
        .map_err(|m| a.error(3, &m))
}
