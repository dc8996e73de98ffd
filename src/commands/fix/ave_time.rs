//! `fix ave/time`: time averages of global values.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;
use crate::lang::system::Mode;

/// `fix ID GROUP ave/time Nevery Nrepeat Nfreq value ... [keyword value ...]` (scalar mode).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let id = fix.id;
    use crate::engine::fixes::{AveInput, AveMode, AveTime};
    a.count(
        7..=usize::MAX,
        "fix ID GROUP ave/time Nevery Nrepeat Nfreq value ...",
    )?;
    let (every, repeat, freq) = (a.int(3)?, a.int(4)?, a.int(5)?);
    if every <= 0 || repeat <= 0 || freq <= 0 || freq % every != 0 || (repeat - 1) * every >= freq {
        return Err(a.error(3, "Illegal fix ave/time command"));
    }
    let mut inputs = Vec::new();
    let mut names = Vec::new();
    let mut i = 6;
    while i < a.len() {
        let w = a.word(i)?;
        let Some(kind) = ["c_", "f_", "v_"].into_iter().find(|p| w.starts_with(p)) else {
            break;
        };
        let body = &w[2..];
        let (name, index) = match body.split_once('[') {
            Some((n, rest)) => {
                let k: usize = rest
                    .strip_suffix(']')
                    .and_then(|k| k.parse().ok())
                    .filter(|&k| k > 0)
                    .ok_or_else(|| a.error(i, "Illegal fix ave/time command"))?;
                (n, Some(k))
            }
            None => (body, None),
        };
        let input = match kind {
            "c_" => {
                if !ctx.sim.computes.iter().any(|c| c.id == name) {
                    return Err(a.error(i, "Compute ID for fix ave/time does not exist"));
                }
                AveInput::Compute(name.into(), index)
            }
            "f_" => {
                let Some(f) = ctx.sim.fixes.iter().find(|f| f.id == name) else {
                    return Err(a.error(i, "Fix ID for fix ave/time does not exist"));
                };
                let global_freq = match &f.kind {
                    FixKind::CheckTimestep(c) => c.every,
                    FixKind::AveTime(at) => at.freq,
                    FixKind::Mesh(m) if m.stress.is_some() => 1,
                    _ => return Err(a.error(i, "Fix ave/time fix does not calculate a vector")),
                };
                if every % global_freq != 0 {
                    return Err(a.error(i, "Fix for fix ave/time not computed at compatible time"));
                }
                AveInput::Fix(name.into(), index)
            }
            _ => {
                match ctx.vars.get(name).map(|v| v.style) {
                    None => return Err(a.error(i, "Variable name for fix ave/time does not exist")),
                    Some(crate::lang::variables::Style::Atom) => {
                        return Err(a.error(i, "Fix ave/time variable is not equal-style variable"))
                    }
                    _ => {}
                }
                if index.is_some() {
                    return Err(a.error(i, "Illegal fix ave/time command"));
                }
                AveInput::Variable(name.into())
            }
        };
        inputs.push(input);
        names.push(w.to_string());
        i += 1;
    }
    if inputs.is_empty() {
        return Err(a.error(6, "Illegal fix ave/time command"));
    }
    let mut off = vec![false; inputs.len()];
    let (mut mode, mut start, mut file) = (AveMode::One, 0, None);
    let mut titles: [Option<String>; 2] = [None, None];
    while i < a.len() {
        match a.word(i)? {
            "file" => {
                file = Some(a.word(i + 1)?.to_string());
                i += 2;
            }
            "ave" => {
                mode = match a.word_in(i + 1, &["one", "running", "window"])? {
                    "one" => AveMode::One,
                    "running" => AveMode::Running,
                    _ => {
                        let m = a.int32(i + 2)?;
                        if m <= 0 {
                            return Err(a.error(i + 2, "Illegal fix ave/time command"));
                        }
                        // LIGGGHTS keeps the last M values of every input
                        let row = 24 + 8 * inputs.len();
                        crate::engine::checks::allocation(m as f64, row, "ave/time:vector_list")
                            .map_err(|e| a.error(i + 2, &e))?;
                        i += 1;
                        AveMode::Window(m as usize)
                    }
                };
                i += 2;
            }
            "start" => {
                start = a.int(i + 1)?;
                i += 2;
            }
            "off" => {
                let k = a.int(i + 1)?;
                if k < 1 || k as usize > off.len() {
                    return Err(a.error(i + 1, "Invalid fix ave/time off column"));
                }
                off[k as usize - 1] = true;
                i += 2;
            }
            "mode" => {
                if a.word_in(i + 1, &["scalar", "vector"])? == "vector" {
                    return Err(a.unsupported(i + 1, "fix ave/time mode vector"));
                }
                i += 2;
            }
            "title1" | "title2" => {
                let k = (a.word(i)? == "title2") as usize;
                titles[k] = Some(a.word(i + 1)?.to_string());
                i += 2;
            }
            "title3" => {
                a.word(i + 1)?; // only used by mode vector
                i += 2;
            }
            "overwrite" => return Err(a.unsupported(i, "fix ave/time overwrite")),
            _ => {
                return Err(a.keyword_error(
                    i,
                    &[
                        "file", "ave", "start", "off", "mode", "title1", "title2", "title3",
                    ],
                ))
            }
        }
    }
    let schedule = crate::engine::fixes::AveSchedule {
        every,
        repeat,
        freq,
    };
    let mut fix = AveTime::new(schedule, inputs, off, mode, start, ctx.sim.step);
    if let (Some(name), Mode::Run) = (file, ctx.sys.mode) {
        use std::io::Write;
        let f = std::fs::File::create(&name)
            .map_err(|_| a.file_error(0, format!("Cannot open fix ave/time file {name}")))?;
        let mut f = std::io::BufWriter::new(f);
        let head = format!(
            "{}\n{}\n",
            titles[0]
                .clone()
                .unwrap_or_else(|| format!("# Time-averaged data for fix {id}")),
            titles[1]
                .clone()
                .unwrap_or_else(|| format!("# TimeStep {}", names.join(" ")))
        );
        f.write_all(head.as_bytes())
            .and_then(|_| f.flush())
            .map_err(|e| a.error(0, format!("fix ave/time: {e}")))?;
        fix.file = Some(f);
    }
    Ok(FixKind::AveTime(fix))
}
