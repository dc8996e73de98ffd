//! `fix deform`: the box changes every N steps (orthogonal boxes: x, y, z), with LIGGGHTS
//! 3.8.0's arguments and errors.

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::deform::{BoxNow, Deform, Remap, Style};
use crate::engine::domain::Boundary;
use crate::engine::error::EngineError;
use crate::engine::fixes::FixStyle;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "deform",
    "fix ID GROUP deform N x|y|z final|delta|scale|vel|erate|trate|volume|wiggle|variable ARGS ...",
    &[
        kw(
            "remap",
            &[arg("x|v|none", Value::OneOf(&["x", "v", "none"]))],
            "move the group's atoms with the box (x), or add the box edges' velocity to atoms crossing a periodic face (v; only on non-periodic changed dimensions yet)",
        ),
        kw(
            "flip",
            &[arg("yes|no", Value::OneOf(&["yes", "no"]))],
            "box flips of tilted boxes (accepted; tilts need a triclinic box)",
        ),
        kw(
            "units",
            &[arg("box|lattice", Value::OneOf(&["box", "lattice"]))],
            "lengths in box or lattice units",
        ),
    ],
    "change the box bounds every N steps (orthogonal boxes: x, y, z; lengths, rates per time)",
);

const ILLEGAL: &str = "Illegal fix deform command";

/// `fix ID GROUP deform N x|y|z STYLE ARGS ... [remap x|v|none] [flip yes|no] [units
/// box|lattice]`.
pub fn build(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() < 4 {
        return Err(a.error(a.len() - 1, ILLEGAL));
    }
    let every = a.int(3)?;
    if every <= 0 {
        return Err(a.error(3, ILLEGAL));
    }
    let mut styles = [Style::None, Style::None, Style::None];
    let mut i = 4;
    while i < a.len() {
        let word = a.word(i)?;
        let d = match word {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            "xy" | "xz" | "yz" => {
                // every regolith box is orthogonal; LIGGGHTS refuses tilts on such boxes
                return Err(a.error(
                    i,
                    "Fix deform tilt factors require triclinic box (regolith has no triclinic boxes yet)",
                ));
            }
            _ => break,
        };
        let (style, used) = style_of(a, i)?;
        styles[d] = style;
        i += used;
    }
    let (remap, lattice) = options(a, i)?;
    for (d, style) in styles.iter().enumerate() {
        let shrinks = ctx.sim.domain.boundary[d]
            .iter()
            .any(|b| matches!(b, Boundary::Shrink | Boundary::ShrinkMin));
        if *style != Style::None && shrinks {
            return Err(a.error(4, "Cannot use fix deform on a shrink-wrapped boundary"));
        }
    }
    let scale = lattice_scale(ctx, lattice, &styles);
    let styles = styles
        .into_iter()
        .enumerate()
        .map(|(d, s)| scaled(s, scale[d]))
        .collect::<Vec<_>>();
    let styles: [Style; 3] = styles.try_into().expect("three dimensions");
    let d = &ctx.sim.domain;
    let now = BoxNow { lo: d.lo, hi: d.hi };
    let fix = Deform::new(every, styles, remap, now).map_err(|e| a.engine_error(4, e))?;
    if remap == Remap::V && (0..3).any(|d| fix.changes(d) && ctx.sim.domain.periodic(d)) {
        // LIGGGHTS adds the box edges' velocity to the ghost images' velocities across such
        // faces, which the pair forces then see; regolith's pair kernels do not yet
        let k = (4..a.len())
            .find(|&k| a.word(k).ok() == Some("remap"))
            .unwrap_or(4);
        return Err(a.unsupported(
            k + 1,
            "fix deform remap v on a periodic dimension it changes",
        ));
    }
    Ok(Box::new(fix))
}

/// The style after parameter word `i`, and how many words the parameter took.
fn style_of(a: &Args, i: usize) -> Result<(Style, usize), CommandError> {
    if i + 2 > a.len() {
        return Err(a.error(i, ILLEGAL));
    }
    let need = |n: usize| {
        if i + n > a.len() {
            Err(a.error(a.len() - 1, ILLEGAL))
        } else {
            Ok(())
        }
    };
    let style = match a.word(i + 1)? {
        "final" => {
            need(4)?;
            (Style::Final(a.real(i + 2)?, a.real(i + 3)?), 4)
        }
        "delta" => {
            need(4)?;
            (Style::Delta(a.real(i + 2)?, a.real(i + 3)?), 4)
        }
        "scale" => {
            need(3)?;
            (Style::Scale(a.real(i + 2)?), 3)
        }
        "vel" => {
            need(3)?;
            (Style::Vel(a.real(i + 2)?), 3)
        }
        "erate" => {
            need(3)?;
            (Style::Erate(a.real(i + 2)?), 3)
        }
        "trate" => {
            need(3)?;
            (Style::Trate(a.real(i + 2)?), 3)
        }
        "volume" => (Style::Volume, 2),
        "wiggle" => {
            need(4)?;
            let (amplitude, period) = (a.real(i + 2)?, a.real(i + 3)?);
            if period <= 0.0 {
                return Err(a.error(i + 3, ILLEGAL));
            }
            (Style::Wiggle(amplitude, period), 4)
        }
        "variable" => {
            need(4)?;
            let name = |k: usize| -> Result<String, CommandError> {
                a.word(k)?
                    .strip_prefix("v_")
                    .map(str::to_string)
                    .ok_or_else(|| a.error(k, ILLEGAL))
            };
            (Style::Variable(name(i + 2)?, name(i + 3)?), 4)
        }
        other => {
            return Err(a.error(
                i + 1,
                format!("{ILLEGAL}: unknown style '{other}' (expected final, delta, scale, vel, erate, trate, volume, wiggle or variable)"),
            ))
        }
    };
    Ok(style)
}

/// The trailing keywords from word `i`: the remap mode and whether lengths are in lattice
/// units.
fn options(a: &Args, mut i: usize) -> Result<(Remap, bool), CommandError> {
    let (mut remap, mut lattice) = (Remap::X, false);
    while i < a.len() {
        if i + 2 > a.len() {
            return Err(a.error(i, ILLEGAL));
        }
        match a.word(i)? {
            "remap" => {
                remap = match a.word(i + 1)? {
                    "x" => Remap::X,
                    "v" => Remap::V,
                    "none" => Remap::None,
                    _ => return Err(a.error(i + 1, ILLEGAL)),
                }
            }
            "units" => {
                lattice = match a.word(i + 1)? {
                    "box" => false,
                    "lattice" => true,
                    _ => return Err(a.error(i + 1, ILLEGAL)),
                }
            }
            // tilts need a triclinic box, so box flips never happen here
            "flip" => {
                if !matches!(a.word(i + 1)?, "yes" | "no") {
                    return Err(a.error(i + 1, ILLEGAL));
                }
            }
            other => {
                return Err(a.error(
                    i,
                    format!("{ILLEGAL}: unknown keyword '{other}' (expected remap, flip or units)"),
                ))
            }
        }
        i += 2;
    }
    Ok((remap, lattice))
}

/// The lattice spacings lengths are scaled by (1 in box units, or when no style takes a
/// length), as LIGGGHTS decides it.
fn lattice_scale(ctx: &Ctx, lattice: bool, styles: &[Style; 3]) -> [f64; 3] {
    let lengths = styles.iter().any(|s| {
        matches!(
            s,
            Style::Final(..) | Style::Delta(..) | Style::Vel(_) | Style::Wiggle(..)
        )
    });
    if !(lattice && lengths) {
        return [1.0; 3];
    }
    crate::engine::thermo::lattice_spacings(ctx.sim)
}

/// A style with its lengths multiplied by `s`.
fn scaled(style: Style, s: f64) -> Style {
    match style {
        Style::Final(lo, hi) => Style::Final(lo * s, hi * s),
        Style::Delta(lo, hi) => Style::Delta(lo * s, hi * s),
        Style::Vel(v) => Style::Vel(v * s),
        Style::Wiggle(amp, tp) => Style::Wiggle(amp * s, tp),
        other => other,
    }
}

/// LIGGGHTS's init check of the `variable` styles' variables (at every `run`).
pub fn check_variables(ctx: &Ctx) -> Result<(), EngineError> {
    for f in &ctx.sim.fixes {
        let Some(d) = f.kind.style_as::<Deform>() else {
            continue;
        };
        for (disp, rate) in d.variables() {
            for name in [disp, rate] {
                match ctx.vars.get(name).map(|v| v.style) {
                    None => return Err("Variable name for fix deform does not exist".into()),
                    Some(s) if s != crate::lang::variables::Style::Equal => {
                        return Err("Variable for fix deform is invalid style".into())
                    }
                    _ => {}
                }
            }
        }
    }
    Ok(())
}
