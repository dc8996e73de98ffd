//! `fix property/atom`: user per-atom properties (a scalar or a vector of values per
//! particle), and the properties other fixes create through it (the heat fixes' `Temp`).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{properties_named, Fix, FixKind, FixStyle};
use crate::engine::heat::PropertyAtom;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "property/atom",
    "fix ID GROUP property/atom NAME scalar|vector RESTART COMM_GHOST COMM_REV VALUE ...",
    &[],
    "a user per-particle property (flags yes|no; one default value, or one per column); f_ID or f_ID[N] in dumps, set ... property/atom NAME VALUE ...",
);

/// `fix ID GROUP property/atom NAME scalar|vector|vector_one_entry RESTART COMM_GHOST
/// COMM_REV VALUE...` (flags `yes|no`; one default value for a scalar, the defaults of each
/// column for a vector).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() < 9 {
        return Err(a
            .error(
                a.len().saturating_sub(1),
                "Illegal fix property/atom command, not enough arguments",
            )
            .with_help(
                "fix ID GROUP property/atom NAME scalar|vector yes|no yes|no yes|no VALUE ...",
            ));
    }
    if a.len() > 29 {
        ctx.say("WARNING: Vector length in fix property/atom larger than 20. Are you sure you want that?\n");
    }
    let name = a.word(3)?;
    let (vector, one_entry) = match a.word(4)? {
        "scalar" => (false, false),
        "vector" => (true, false),
        "vector_one_entry" => (true, true),
        _ => return Err(a.error(4, "Unknown style for fix property/atom. Valid styles are 'scalar', 'vector' or 'vector_one_entry'")),
    };
    let flag = |i: usize, what: &str| -> Result<bool, CommandError> {
        match a.word(i)? {
            "yes" => Ok(true),
            "no" => Ok(false),
            _ => Err(a.error(
                i,
                format!(
                    "Unknown {what} style for fix property/atom. Valid styles are 'yes' or 'no'"
                ),
            )),
        }
    };
    let restart = flag(5, "restart")?;
    flag(6, "communicate_ghost")?;
    flag(7, "communicate_reverse_ghost")?;
    let n = a.len() - 8;
    if n == 1 && vector && !one_entry {
        return Err(a.error(8, "Error in fix property/atom: Number of default values provided not consistent with vector style. Provide more than 1 value or use style 'scalar'"));
    }
    if n > 1 && !vector {
        return Err(a.error(9, "Error in fix property/atom: Number of default values provided not consistent with scalar style. Provide 1 value or use style 'vector'"));
    }
    let mut defaults = Vec::with_capacity(n);
    for i in 8..a.len() {
        let w = a.word(i)?;
        if w == "none" || (!vector && !w.bytes().any(|b| b.is_ascii_digit())) {
            return Err(a.unsupported(
                i,
                &format!("fix property/atom default {w} (none, or values taken from a particle property)"),
            ));
        }
        defaults.push(a.real(i)?);
    }
    if properties_named(&ctx.sim.fixes, name).next().is_some() {
        return Err(a.error(
            3,
            format!(
                "Fix {} (id {}): there is already a fix that registers a variable of the same name",
                fix.style, fix.id
            ),
        ));
    }
    fill(ctx, fix.id, &defaults);
    Ok(Box::new(PropertyAtom {
        id: fix.id.to_string(),
        name: name.to_string(),
        defaults,
        vector,
        restart,
        fresh: true,
    }))
}

/// Give the particles the array of property/atom fix `id`: its defaults for every
/// particle, unless a restart file being read holds its values.
fn fill(ctx: &mut Ctx, id: &str, defaults: &[f64]) {
    let p = &mut ctx.sim.particles;
    let held = ctx.sim.restart_in_progress
        && ctx
            .sim
            .restart_peratom
            .iter()
            .any(|(i, s)| i == id && s == "property/atom");
    let kept = held
        && p.extra
            .iter()
            .any(|e| e.name == id && e.width == defaults.len());
    if kept {
        let k = p.extra_index(id, defaults.len());
        p.extra[k].fill = defaults.to_vec();
    } else {
        crate::engine::heat::add_property(p, id, defaults);
    }
}

/// The ID of the property/atom fix of variable `name`, created (ID `name`, group `all`, as
/// LIGGGHTS's fixes create theirs) with `defaults` if there is none; lines to print
/// (restart file state taken) go to `lines`.
pub fn ensure(
    ctx: &mut Ctx,
    name: &str,
    defaults: &[f64],
    restart: bool,
    lines: &mut Vec<String>,
) -> String {
    if let Some((f, _)) = properties_named(&ctx.sim.fixes, name).next() {
        return f.id.clone();
    }
    fill(ctx, name, defaults);
    for (what, held) in [
        (
            "global",
            restart && ctx.sim.held_fix_state(name, "property/atom").is_some(),
        ),
        (
            "per-atom",
            restart && ctx.sim.held_peratom(name, "property/atom"),
        ),
    ] {
        if held {
            lines.push(format!(
                "Resetting {what} state of Fix {name} Style property/atom from restart file info"
            ));
        }
    }
    let flag = |b: bool| if b { "yes" } else { "no" };
    let mut args = vec![
        name.to_string(),
        if defaults.len() == 1 {
            "scalar"
        } else {
            "vector"
        }
        .to_string(),
        flag(restart).to_string(),
        "yes".to_string(),
        "no".to_string(),
    ];
    args.extend(defaults.iter().map(|v| format!("{v:e}")));
    ctx.sim.fixes.push(Fix {
        id: name.to_string(),
        style: "property/atom".to_string(),
        group: 1,
        kind: FixKind::Style(Box::new(PropertyAtom {
            id: name.to_string(),
            name: name.to_string(),
            defaults: defaults.to_vec(),
            vector: defaults.len() > 1,
            restart,
            fresh: true,
        })),
        args,
        clock: Default::default(),
    });
    name.to_string()
}
