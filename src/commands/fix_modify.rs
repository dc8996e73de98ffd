//! `fix_modify ID energy yes|no ...`: the settings every fix shares. LIGGGHTS 3.8.0 knows
//! `energy` for all fixes; a fix style may add its own keywords.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};

/// Fix styles whose energy LIGGGHTS adds to `compute pe` after `fix_modify ID energy yes`.
const WITH_ENERGY: &[&str] = &[
    "gravity",
    "addforce",
    "spring",
    "spring/self",
    "wall/region",
];

/// Keywords of particular fix styles (their `modify_param`), not run by regolith yet.
const STYLE_KEYWORDS: &[(&str, &str)] = &[("property/global", "file"), ("multisphere", "fflag")];

/// `fix_modify ID keyword value ...`.
pub fn fix_modify(a: &Args, ctx: &mut Ctx) -> Result<(), CommandError> {
    const ILLEGAL: &str = "Illegal fix_modify command";
    if a.len() < 2 {
        return Err(a
            .error(a.len().saturating_sub(1), ILLEGAL)
            .with_help("fix_modify ID energy yes|no"));
    }
    let id = a.word(0)?;
    let Some(fix) = ctx.sim.fixes.iter().find(|f| f.id == id) else {
        return Err(a.error(0, "Could not find fix_modify ID"));
    };
    let style = fix.style.clone();
    // LIGGGHTS's errors first: a deck it refuses is invalid, whatever regolith lacks
    let mut unsupported = None;
    let mut i = 1;
    while i < a.len() {
        let key = a.word(i)?;
        if key == "energy" {
            if i + 1 >= a.len() {
                return Err(a.error(i, ILLEGAL));
            }
            match a.word(i + 1)? {
                "no" => {}
                "yes" if WITH_ENERGY.contains(&style.as_str()) => {
                    unsupported.get_or_insert((
                        i,
                        format!("fix_modify energy yes on fix {style} (its energy in compute pe)"),
                    ));
                }
                // a fix without an energy adds nothing to compute pe
                "yes" => {}
                _ => return Err(a.error(i + 1, ILLEGAL)),
            }
            i += 2;
        } else if style == "mesh/surface/stress/servo" {
            match super::fix_modify_servo::servo_param(a, i, id, ctx)? {
                0 => return Err(a.error(i, ILLEGAL)),
                n => i += n,
            }
        } else if STYLE_KEYWORDS.contains(&(style.as_str(), key))
            || (style.starts_with("mesh/surface") && key.contains('/'))
        {
            // the style's own keyword: its arguments are the style's to check
            return Err(a.unsupported(i, &format!("fix_modify {key} of fix {style}")));
        } else {
            return Err(a
                .error(i, ILLEGAL)
                .with_help("LIGGGHTS 3.8.0 knows energy yes|no for every fix"));
        }
    }
    match unsupported {
        Some((i, what)) => Err(a.unsupported(i, &what)),
        None => Ok(()),
    }
}
