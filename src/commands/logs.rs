//! `thermo_log FILE [append]` (thermo headers and lines copied to a file of their own, or
//! `none`) and `modify_timing off|on|verbose`, as LIGGGHTS 3.8.0 parses them.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::lang::system::Mode;

type Result = std::result::Result<(), CommandError>;

/// `thermo_log FILE [append]`.
pub fn thermo_log(a: &Args, ctx: &mut Ctx) -> Result {
    if a.is_empty() || a.len() > 2 {
        return Err(a
            .error(a.len().saturating_sub(1), "Illegal thermo_log command")
            .with_help("thermo_log FILE [append] or thermo_log none"));
    }
    let append = a.len() == 2;
    if append && a.word(1)? != "append" {
        return Err(a.error(1, "Illegal thermo_log command"));
    }
    let name = a.word(0)?;
    ctx.sim.extras.thermo_file = None;
    let open_error =
        |e: std::io::Error| a.file_error(0, format!("Cannot open thermo log file {name}: {e}"));
    if name == "none" {
        return Ok(());
    }
    if ctx.sys.mode != Mode::Run {
        return ctx.sys.check_creatable(name).map_err(open_error);
    }
    let path = ctx.sys.resolve(name);
    let file = std::fs::OpenOptions::new()
        .create(true)
        .write(true)
        .append(append)
        .truncate(!append)
        .open(&path)
        .map_err(open_error)?;
    ctx.sim.extras.thermo_file = Some(file);
    Ok(())
}

/// `modify_timing off|on|verbose`: after each run, the fixes' time (`Modfy time`) and one
/// line per fix of LIGGGHTS's fix list (see [`crate::engine::fix_timing`]).
pub fn modify_timing(a: &Args, ctx: &mut Ctx) -> Result {
    if a.len() != 1 {
        return Err(a.error(0, "Illegal modify_timing command"));
    }
    ctx.sim.extras.modify_timing = match a.word(0)? {
        "off" => 0,
        "on" => 1,
        "verbose" => 2,
        _ => return Err(a.error(0, "Illegal modify_timing command")),
    };
    Ok(())
}
