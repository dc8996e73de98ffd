//! `compute_modify ID extra N | dynamic yes|no | thermo yes|no`: the settings of the
//! temperature computes (see [`crate::engine::temperature`]).

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};

/// `compute_modify ID keyword value ...`.
pub fn compute_modify(a: &Args, ctx: &mut Ctx) -> Result<(), CommandError> {
    if a.len() < 2 {
        return Err(a
            .error(a.len().saturating_sub(1), "Illegal compute_modify command")
            .with_help("compute_modify ID extra N | dynamic yes|no | thermo yes|no"));
    }
    let id = a.word(0)?;
    if !ctx.sim.computes.iter().any(|c| c.id == id) {
        return Err(a.error(0, "Could not find compute_modify ID"));
    }
    if id == "thermo_temp" {
        ctx.say("WARNING: Changing thermo_temp compute object. This object is deprecated and will be removed in the future. (./src/compute.cpp:161)\n");
    }
    let mut s = ctx
        .sim
        .extras
        .compute_settings
        .get(id)
        .copied()
        .unwrap_or_default();
    let mut i = 1;
    while i < a.len() {
        let key = a.word(i)?;
        if !matches!(key, "extra" | "dynamic" | "thermo") {
            return Err(a
                .error(i, "Illegal compute_modify command")
                .with_help("LIGGGHTS 3.8.0 knows extra, dynamic and thermo"));
        }
        if i + 1 >= a.len() {
            return Err(a.error(i, "Illegal compute_modify command"));
        }
        match key {
            "extra" => s.extra = Some(a.int32(i + 1)?),
            _ => {
                let yes = match a.word(i + 1)? {
                    "yes" => true,
                    "no" => false,
                    _ => return Err(a.error(i + 1, "Illegal compute_modify command")),
                };
                if key == "dynamic" {
                    s.dynamic = yes;
                } else {
                    s.thermo = Some(yes);
                }
            }
        }
        i += 2;
    }
    ctx.sim.extras.compute_settings.insert(id.to_string(), s);
    Ok(())
}
