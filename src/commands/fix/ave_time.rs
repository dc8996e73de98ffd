//! `fix ave/time`: time averages of global values, in scalar or vector mode.

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{AveInput, AveMode, AveSchedule, AveTime, FixStyle};
use crate::engine::global_values::{fix_global_freq, fix_shape, input_ext, zero_freq};
use crate::lang::system::Mode;

const ILLEGAL: &str = "Illegal fix ave/time command";

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "ave/time",
    "fix ID GROUP ave/time NEVERY NREPEAT NFREQ VALUE ...",
    &[
        kw(
            "mode",
            &[arg("scalar|vector", Value::OneOf(&["scalar", "vector"]))],
            "average global scalars, or global vectors and array columns (rows written per output)",
        ),
        kw(
            "ave",
            &[arg(
                "one|running|window",
                Value::OneOf(&["one", "running", "window"]),
            )],
            "averaging window (window M: the last M outputs)",
        ),
        kw(
            "overwrite",
            &[],
            "keep only the last output in the file (with ave running)",
        ),
        kw(
            "title3",
            &[arg("T", Value::Word)],
            "third comment line of a vector-mode file",
        ),
        kw("start", &[arg("STEP", Value::Int)], "first step averaged"),
        kw(
            "file",
            &[arg("F", Value::File)],
            "write averages to this file",
        ),
        kw("off", &[arg("M", Value::Int)], "leave value M out"),
    ],
    "time averages of global values",
);

/// The keywords after the values.
struct Options {
    mode: AveMode,
    vector: bool,
    start: i64,
    file: Option<String>,
    off: Vec<(usize, i64)>,
    overwrite: bool,
    titles: [Option<String>; 3],
}

/// `fix ID GROUP ave/time Nevery Nrepeat Nfreq value ... [keyword value ...]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    a.count(
        7..=usize::MAX,
        "fix ID GROUP ave/time Nevery Nrepeat Nfreq value ...",
    )?;
    let (every, repeat, freq) = (a.int(3)?, a.int(4)?, a.int(5)?);
    // as LIGGGHTS: count the values, read the keywords (the mode), then the values
    let mut nvalues = 0;
    while 6 + nvalues < a.len()
        && ["c_", "f_", "v_"]
            .iter()
            .any(|p| a.word(6 + nvalues).is_ok_and(|w| w.starts_with(p)))
    {
        nvalues += 1;
    }
    let opts = options(a, 6 + nvalues)?;
    let mut inputs = Vec::new();
    for i in 6..6 + nvalues {
        inputs.extend(input(a, ctx, i, opts.vector)?);
    }
    let mut off = vec![false; inputs.len()];
    for &(at, k) in &opts.off {
        if k < 1 || k as usize > off.len() {
            return Err(a.error(at, "Invalid fix ave/time off column"));
        }
        off[k as usize - 1] = true;
    }
    if every <= 0 || repeat <= 0 || freq <= 0 || freq % every != 0 || (repeat - 1) * every >= freq {
        return Err(a.error(3, ILLEGAL));
    }
    if opts.overwrite && opts.mode != AveMode::Running {
        return Err(a.error(6 + nvalues, ILLEGAL));
    }
    for (k, inp) in inputs.iter().enumerate() {
        if let AveInput::Fix(id, _) = inp {
            let freq = fix_global_freq(ctx.sim, id);
            if freq == 0 {
                return Err(a.engine_error(6 + k.min(nvalues - 1), zero_freq(id)));
            }
            if every % freq != 0 {
                let at = 6 + k.min(nvalues - 1);
                return Err(a.error(at, "Fix for fix ave/time not computed at compatible time"));
            }
        }
    }
    if opts.vector && inputs.len() > 1 {
        // LIGGGHTS's array needs one intensive/extensive flag from all inputs
        let exts: Vec<i8> = inputs
            .iter()
            .filter_map(|i| input_ext(ctx.sim, i))
            .collect();
        if exts.iter().any(|&e| e == -1 || e != exts[0]) {
            return Err(a.error(
                6,
                "Fix ave/time cannot set output array intensive/extensive from these inputs",
            ));
        }
    }
    let rows = if opts.vector {
        Some(common_rows(a, ctx, &inputs)?)
    } else {
        None
    };
    if let AveMode::Window(m) = opts.mode {
        // LIGGGHTS keeps the last M averages of every value
        let row = 24 + 8 * inputs.len() * rows.unwrap_or(1);
        crate::engine::checks::allocation(m as f64, row, "ave/time:vector_list")
            .map_err(|e| a.error(6 + nvalues, &e))?;
    }
    let schedule = AveSchedule {
        every,
        repeat,
        freq,
    };
    let header = header(fix.id, &opts, &inputs, (6..6 + nvalues).map(|i| a.word(i)));
    let mut at = AveTime::new(
        schedule,
        inputs,
        off,
        (opts.mode, rows),
        opts.start,
        ctx.sim.step,
    );
    if let (Some(name), Mode::Run) = (&opts.file, ctx.sys.mode) {
        use std::io::Write;
        let f = std::fs::File::create(name)
            .map_err(|_| a.file_error(0, format!("Cannot open fix ave/time file {name}")))?;
        let mut f = std::io::BufWriter::new(f);
        f.write_all(header?.as_bytes())
            .and_then(|_| f.flush())
            .map_err(|e| a.error(0, format!("fix ave/time: {e}")))?;
        at.overwrite = opts.overwrite.then_some(header_len(&f));
        at.file = Some(f);
    }
    Ok(Box::new(at))
}

/// Bytes written to a freshly created file.
fn header_len(f: &std::io::BufWriter<std::fs::File>) -> u64 {
    f.get_ref().metadata().map_or(0, |m| m.len())
}

/// The file's comment lines: title1, title2 (scalar mode: the values as written) and in
/// vector mode title3 (the expanded columns).
fn header<'a>(
    id: &str,
    opts: &Options,
    inputs: &[AveInput],
    words: impl Iterator<Item = Result<&'a str, CommandError>>,
) -> Result<String, CommandError> {
    let words: Vec<&str> = words.collect::<Result<_, _>>()?;
    let [t1, t2, t3] = &opts.titles;
    let mut h = t1
        .clone()
        .unwrap_or_else(|| format!("# Time-averaged data for fix {id}"));
    h.push('\n');
    h.push_str(&match (t2, opts.vector) {
        (Some(t), _) => t.clone(),
        (None, false) => format!("# TimeStep {}", words.join(" ")),
        (None, true) => "# TimeStep Number-of-rows".to_string(),
    });
    h.push('\n');
    if opts.vector {
        match t3 {
            Some(t) => h.push_str(t),
            None => {
                h.push_str("# Row");
                for inp in inputs {
                    let (p, id, k) = match inp {
                        AveInput::Compute(id, k) => ("c_", id, *k),
                        AveInput::Fix(id, k) => ("f_", id, *k),
                        AveInput::Variable(n) => ("v_", n, None),
                    };
                    h.push_str(&format!(" {p}{id}"));
                    if let Some(k) = k {
                        h.push_str(&format!("[{k}]"));
                    }
                }
            }
        }
        h.push('\n');
    }
    Ok(h)
}

/// The keywords from word `i` on.
fn options(a: &Args, mut i: usize) -> Result<Options, CommandError> {
    let mut o = Options {
        mode: AveMode::One,
        vector: false,
        start: 0,
        file: None,
        off: Vec::new(),
        overwrite: false,
        titles: [None, None, None],
    };
    let need = |i: usize, n: usize| {
        if i + n >= a.len() {
            Err(a.error(i, ILLEGAL))
        } else {
            Ok(())
        }
    };
    while i < a.len() {
        let w = a.word(i)?;
        match w {
            "file" | "start" | "mode" | "off" | "title1" | "title2" | "title3" | "ave" => {
                need(i, 1)?
            }
            _ => {}
        }
        match w {
            "file" => o.file = Some(a.word(i + 1)?.to_string()),
            "ave" => {
                o.mode = match a.word(i + 1)? {
                    "one" => AveMode::One,
                    "running" => AveMode::Running,
                    "window" => {
                        need(i, 2)?;
                        let m = a.int32(i + 2)?;
                        if m <= 0 {
                            return Err(a.error(i + 2, ILLEGAL));
                        }
                        i += 1;
                        AveMode::Window(m as usize)
                    }
                    _ => return Err(a.error(i + 1, ILLEGAL)),
                }
            }
            "start" => o.start = a.int(i + 1)?,
            "mode" => {
                o.vector = match a.word(i + 1)? {
                    "scalar" => false,
                    "vector" => true,
                    _ => return Err(a.error(i + 1, ILLEGAL)),
                }
            }
            "off" => o.off.push((i + 1, a.int(i + 1)?)),
            "overwrite" => {
                o.overwrite = true;
                i -= 1;
            }
            "title1" | "title2" | "title3" => {
                let k = (w.as_bytes()[5] - b'1') as usize;
                o.titles[k] = Some(a.word(i + 1)?.to_string());
            }
            _ => {
                return Err(a.keyword_error(
                    i,
                    &[
                        "file",
                        "ave",
                        "start",
                        "off",
                        "mode",
                        "overwrite",
                        "title1",
                        "title2",
                        "title3",
                    ],
                ))
            }
        }
        i += 2;
    }
    Ok(o)
}

/// The value at word `i`, checked as LIGGGHTS does in the mode; in vector mode a compute
/// or fix array named without a column stands for all its columns.
fn input(a: &Args, ctx: &Ctx, i: usize, vector: bool) -> Result<Vec<AveInput>, CommandError> {
    let w = a.word(i)?;
    let (kind, body) = w.split_at(2);
    let (name, index) = match body.split_once('[') {
        Some((n, rest)) => {
            let k = rest
                .strip_suffix(']')
                .ok_or_else(|| a.error(i, ILLEGAL))?
                .parse::<usize>()
                .ok()
                .filter(|&k| k > 0)
                .ok_or_else(|| a.error(i, ILLEGAL))?;
            (n, Some(k))
        }
        None => (body, None),
    };
    let what = if kind == "c_" { "compute" } else { "fix" };
    let shape = match kind {
        "c_" => ctx
            .sim
            .computes
            .iter()
            .find(|c| c.id == name)
            .map(|c| c.shape()),
        "f_" => fix_shape(ctx.sim, name),
        _ => return variable(a, ctx, i, name, index, vector),
    };
    let Some(shape) = shape else {
        let own = if kind == "c_" { "Compute ID" } else { "Fix ID" };
        return Err(a.error(i, format!("{own} for fix ave/time does not exist")));
    };
    let make = |k: Option<usize>| match kind {
        "c_" => AveInput::Compute(name.into(), k),
        _ => AveInput::Fix(name.into(), k),
    };
    let err = |m: &str| Err(a.error(i, format!("Fix ave/time {what} {m}")));
    match (vector, index) {
        (false, None) if !shape.scalar => err("does not calculate a scalar"),
        (false, Some(_)) if shape.vector == 0 => err("does not calculate a vector"),
        (false, Some(k)) if k > shape.vector => err("vector is accessed out-of-range"),
        (true, None) => match shape.array {
            Some((_, cols)) => Ok((1..=cols).map(|k| make(Some(k))).collect()),
            None if shape.vector == 0 => err("does not calculate a vector"),
            None => Ok(vec![make(None)]),
        },
        (true, Some(k)) => match shape.array {
            None => err("does not calculate an array"),
            Some((_, cols)) if k > cols => err("array is accessed out-of-range"),
            Some(_) => Ok(vec![make(Some(k))]),
        },
        _ => Ok(vec![make(index)]),
    }
}

/// A `v_name` value at word `i`.
fn variable(
    a: &Args,
    ctx: &Ctx,
    i: usize,
    name: &str,
    index: Option<usize>,
    vector: bool,
) -> Result<Vec<AveInput>, CommandError> {
    match ctx.vars.get(name).map(|v| v.style) {
        None => return Err(a.error(i, "Variable name for fix ave/time does not exist")),
        Some(crate::lang::variables::Style::Atom) => {
            return Err(a.error(i, "Fix ave/time variable is not equal-style variable"))
        }
        _ => {}
    }
    if vector {
        return Err(a.error(i, "Fix ave/time cannot use variable with vector mode"));
    }
    if index.is_some() {
        return Err(a.error(i, ILLEGAL));
    }
    Ok(vec![AveInput::Variable(name.into())])
}

/// The rows every vector-mode input has (LIGGGHTS's error if they differ).
fn common_rows(a: &Args, ctx: &Ctx, inputs: &[AveInput]) -> Result<usize, CommandError> {
    let mut rows = None;
    for inp in inputs {
        let (shape, index) = match inp {
            AveInput::Compute(id, k) => (
                ctx.sim
                    .computes
                    .iter()
                    .find(|c| &c.id == id)
                    .map(|c| c.shape()),
                k,
            ),
            AveInput::Fix(id, k) => (fix_shape(ctx.sim, id), k),
            AveInput::Variable(_) => continue,
        };
        let shape = shape.unwrap_or_default();
        let n = match index {
            None => shape.vector,
            Some(_) => shape.array.map_or(0, |(r, _)| r),
        };
        if rows.is_some_and(|r| r != n) {
            return Err(a.error(6, "Fix ave/time columns are inconsistent lengths"));
        }
        rows = Some(n);
    }
    Ok(rows.unwrap_or(0))
}
