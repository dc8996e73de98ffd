//! `fix ave/histo` of per-atom inputs (`mode vector`), with LIGGGHTS 3.8.0's errors;
//! global and local inputs are not run yet.

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::ave_atom::AtomInput;
use crate::engine::ave_histo::{AveHisto, Beyond};
use crate::engine::fixes::{AveMode, FixStyle};
use crate::io::dump::Column;
use crate::lang::system::Mode;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "ave/histo",
    "fix ID GROUP ave/histo NEVERY NREPEAT NFREQ LO HI NBIN x|y|z|vx|vy|vz|fx|fy|fz|c_ID|c_ID[N]|f_ID|v_NAME ... mode vector",
    &[
        kw(
            "mode",
            &[arg("scalar|vector", Value::OneOf(&["scalar", "vector"]))],
            "vector for per-atom inputs (the only ones run yet)",
        ),
        kw("file", &[arg("FILE", Value::Word)], "write the histograms to this file"),
        kw("ave", &[arg("one|running|window M", Value::Word)], "combine histograms"),
        kw("start", &[arg("N", Value::Word)], "no histogram before step N"),
        kw(
            "beyond",
            &[arg("ignore|end|extra", Value::OneOf(&["ignore", "end", "extra"]))],
            "values outside LO..HI",
        ),
        kw("overwrite", &[], "keep only the last histogram (ave running)"),
        kw("title1", &[arg("TEXT", Value::Word)], "first comment line"),
        kw("title2", &[arg("TEXT", Value::Word)], "second comment line"),
        kw("title3", &[arg("TEXT", Value::Word)], "third comment line"),
    ],
    "histograms of the group's per-atom values in NBIN bins from LO to HI, every NFREQ steps, written to a file",
);

const ILLEGAL: &str = "Illegal fix ave/histo command";

/// `fix ID GROUP ave/histo Nevery Nrepeat Nfreq lo hi Nbin input ... keyword value ...`
/// with inputs x y z vx vy vz fx fy fz, per-atom c_ID, c_ID[N], f_ID, atom-style v_name and
/// keywords mode, file, ave, start, beyond, overwrite, title1/2/3.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() < 10 {
        return Err(a.error(2, ILLEGAL));
    }
    let schedule = (a.int(3)?, a.int(4)?, a.int(5)?);
    let (lo, hi, nbins) = (a.real(6)?, a.real(7)?, a.int(8)?);
    let mut i = 9;
    let mut inputs = Vec::new();
    while i < a.len() {
        let w = a.word(i)?;
        let input = match w {
            "x" | "y" | "z" | "vx" | "vy" | "vz" | "fx" | "fy" | "fz" => {
                AtomInput::Atom(Column::parse(w).map_err(|_| a.error(i, ILLEGAL))?)
            }
            _ if w.starts_with("c_") || w.starts_with("f_") || w.starts_with("v_") => {
                reference(a, ctx, i)?
            }
            _ => break,
        };
        inputs.push(input);
        i += 1;
    }
    let (mut mode, mut start, mut beyond, mut overwrite) = (AveMode::One, 0, Beyond::Ignore, false);
    let (mut vector, mut file) = (false, None);
    let mut titles: [Option<String>; 3] = [None, None, None];
    while i < a.len() {
        let w = a.word(i)?;
        if w != "overwrite" && i + 2 > a.len() {
            return Err(a.error(i, ILLEGAL));
        }
        match w {
            "file" => file = Some(a.word(i + 1)?.to_string()),
            "ave" => match a.word(i + 1)? {
                "one" => mode = AveMode::One,
                "running" => mode = AveMode::Running,
                "window" => {
                    let n = if i + 3 > a.len() { 0 } else { a.int(i + 2)? };
                    if n <= 0 {
                        return Err(a.error(i + 1, ILLEGAL));
                    }
                    mode = AveMode::Window(n as usize);
                    i += 1;
                }
                _ => return Err(a.error(i + 1, ILLEGAL)),
            },
            "start" => start = a.int(i + 1)?,
            "mode" => match a.word(i + 1)? {
                "scalar" => vector = false,
                "vector" => vector = true,
                _ => return Err(a.error(i + 1, ILLEGAL)),
            },
            "beyond" => match a.word(i + 1)? {
                "ignore" => beyond = Beyond::Ignore,
                "end" => beyond = Beyond::End,
                "extra" => beyond = Beyond::Extra,
                _ => return Err(a.error(i + 1, ILLEGAL)),
            },
            "overwrite" => {
                overwrite = true;
                i -= 1;
            }
            "title1" | "title2" | "title3" => {
                titles[(w.as_bytes()[5] - b'1') as usize] = Some(a.word(i + 1)?.to_string());
            }
            _ => return Err(a.error(i, ILLEGAL)),
        }
        i += 2;
    }
    let (every, repeat, freq) = schedule;
    if every <= 0 || repeat <= 0 || freq <= 0 || freq % every != 0 || (repeat - 1) * every >= freq {
        return Err(a.error(3, ILLEGAL));
    }
    if lo >= hi || nbins <= 0 || (overwrite && mode != AveMode::Running) {
        return Err(a.error(6, ILLEGAL));
    }
    if !vector {
        return Err(a.error(
            2,
            "Fix ave/histo cannot input per-atom values in scalar mode",
        ));
    }
    let range = (lo, hi);
    let mut h = AveHisto::new(
        schedule,
        start,
        range,
        nbins as usize,
        beyond,
        inputs,
        (mode, overwrite),
        ctx.sim.step,
    );
    if let (Some(name), Mode::Run) = (file, ctx.sys.mode) {
        h.file = Some(open_file(a, &name, fix.id, &titles)?);
    }
    Ok(Box::new(h))
}

/// The file with LIGGGHTS's three comment lines (or the titles given), and where they end.
fn open_file(
    a: &Args,
    name: &str,
    id: &str,
    titles: &[Option<String>; 3],
) -> Result<(std::fs::File, u64), CommandError> {
    use std::io::Write;
    let mut f = std::fs::File::create(name)
        .map_err(|_| a.file_error(0, format!("Cannot open fix ave/histo file {name}")))?;
    let defaults = [
        format!("# Histogrammed data for fix {id}"),
        "# TimeStep Number-of-bins Total-counts Missing-counts Min-value Max-value".into(),
        "# Bin Coord Count Count/Total".into(),
    ];
    let head: String = titles
        .iter()
        .zip(&defaults)
        .map(|(t, d)| format!("{}\n", t.as_deref().unwrap_or(d)))
        .collect();
    f.write_all(head.as_bytes())
        .map_err(|e| a.error(0, format!("fix ave/histo: {e}")))?;
    Ok((f, head.len() as u64))
}

/// A `c_`, `f_` or `v_` input at word `i`: per-atom ones run; global ones are not run yet.
fn reference(a: &Args, ctx: &Ctx, i: usize) -> Result<AtomInput, CommandError> {
    let w = a.word(i)?;
    let (id, index) =
        crate::util::numbers::split_reference(&w[2..]).ok_or_else(|| a.error(i, ILLEGAL))?;
    let global = || a.unsupported(i, &format!("fix ave/histo of global or local {w}"));
    match &w[..2] {
        "c_" => {
            let c = super::input_compute(a, ctx, i, id, "ave/histo")?;
            let cols = c.per_atom_columns();
            if cols == 0 {
                return Err(global());
            }
            let problem = match index {
                None if cols > 1 => Some("does not calculate a per-atom vector"),
                Some(_) if cols == 1 => Some("does not calculate a per-atom array"),
                Some(k) if k > cols => Some("array is accessed out-of-range"),
                _ => None,
            };
            if let Some(p) = problem {
                return Err(a.error(i, format!("Fix ave/histo compute {p}")));
            }
            Ok(AtomInput::Compute(id.to_string(), index))
        }
        "f_" => {
            if !ctx.sim.fixes.iter().any(|f| f.id == id) {
                return Err(a.error(i, "Fix ID for fix ave/histo does not exist"));
            }
            // LIGGGHTS 3.8.0 reads a per-atom fix column f_ID[N] from the wrong place
            if index.is_some() || crate::engine::fix_columns::column(ctx.sim, id, None).is_err() {
                return Err(global());
            }
            Ok(AtomInput::Fix(id.to_string(), None))
        }
        _ => match ctx.vars.get(id).map(|v| v.style) {
            Some(crate::lang::variables::Style::Atom) => Ok(AtomInput::Variable(id.into())),
            Some(_) => Err(global()),
            None => Err(a.error(i, "Variable name for fix ave/histo does not exist")),
        },
    }
}
