//! `fix check/timestep/gran`: the time step against Rayleigh and Hertz times.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP check/timestep/gran N RAYLEIGH_LIMIT HERTZ_LIMIT [warn yes|no] [error yes|no] [vmax V]`.
pub fn build(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    a.count(6..=usize::MAX, "fix ID GROUP check/timestep/gran N RAYLEIGH_LIMIT HERTZ_LIMIT [warn yes|no] [error yes|no] [vmax V]")?;
    let every = a.int(3)?;
    if every <= 0 {
        return Err(a.error(3, "Illegal fix check/timestep/gran command"));
    }
    let mut c = crate::engine::fixes::CheckTimestep {
        every,
        rayleigh_limit: a.real(4)?,
        hertz_limit: a.real(5)?,
        warn: true,
        error: false,
        vmax_user: 0.0,
        values: [0.0; 3],
        materials: Vec::new(),
    };
    let mut i = 6;
    while i < a.len() {
        match a.word(i)? {
            "warn" => c.warn = a.word_in(i + 1, &["yes", "no"])? == "yes",
            "error" => c.error = a.word_in(i + 1, &["yes", "no"])? == "yes",
            "vmax" => c.vmax_user = a.real(i + 1)?,
            _ => return Err(a.keyword_error(i, &["warn", "error", "vmax"])),
        }
        i += 2;
    }
    if c.error {
        return Err(a.unsupported(6, "fix check/timestep/gran error yes"));
    }
    Ok(FixKind::CheckTimestep(c))
}
