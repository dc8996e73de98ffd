//! LIGGGHTS's `init` of the whole system, which `run`, `write_restart`, `write_data` and
//! `delete_atoms overlap` make before they act: the pair style's checks and warnings, the
//! material and atom-type checks of the contact models, and the thermo output's references.
//! `run` and `check` make them alike, at the command that triggers them.

use crate::commands::compute::pair_history_width;
use crate::commands::{Args, CommandError, Ctx};
use crate::lang::system::Mode;

/// LIGGGHTS's warning (src/pair_gran.cpp) when a granular pair style runs with a neighbour
/// list build delay.
const DELAY_WARNING: &str = "WARNING: It is heavily recommended to use 'neigh_modify delay 0' with granular pair styles (./src/pair_gran.cpp:237)\n";

/// Computes LIGGGHTS's output creates for every deck that regolith does not keep as
/// computes (their thermo keywords are checked where they are evaluated).
pub const LIGGGHTS_OWN: &[&str] = &["thermo_press", "thermo_pe"];

/// The system init of command `a`; `announce` names the command for LIGGGHTS's
/// "System init for NAME ..." screen line (None for `run`, which prints none).
pub fn system_init(a: &Args, ctx: &mut Ctx, announce: Option<&str>) -> Result<(), CommandError> {
    if let Some(name) = announce {
        if ctx.sys.mode == Mode::Run {
            ctx.out.screen(&format!("System init for {name} ...\n"));
        }
    }
    if ctx.sim.pair_selection.is_some() {
        // LIGGGHTS's Pair::init checks every I,I type pair before the style's own init
        if !ctx.sim.pair_coeff_set {
            return Err(a.error(0, "All pair coeffs are not set"));
        }
        if ctx.sim.neighbor.delay != 0 {
            ctx.say(DELAY_WARNING);
        }
        if !ctx.sim.comm_vel {
            return Err(a.error(0, "Pair granular requires ghost atoms store velocity"));
        }
        let history = ctx
            .sim
            .pair_selection
            .as_ref()
            .map_or(0, pair_history_width);
        if history > 0 && ctx.sim.newton_pair {
            return Err(a.error(
                0,
                "Pair granular with shear history requires newton pair off",
            ));
        }
    }
    ctx.sim.check_types().map_err(|e| a.engine_error(0, e))?;
    super::material_check::validate(a, ctx)?;
    thermo_references(a, ctx)?;
    // LIGGGHTS's Modify::init forgets the restart file's fix entries: a later change_box
    // no longer needs `force`
    ctx.sim.extras.restart_peratom_fixes = 0;
    Ok(())
}

/// The computes, fixes and variables the thermo output names must exist (LIGGGHTS's
/// Thermo::init).
fn thermo_references(a: &Args, ctx: &Ctx) -> Result<(), CommandError> {
    for field in &ctx.sim.thermo.fields {
        let word = field.keyword.as_str();
        let id = |body: &'static str| -> Option<&str> {
            let rest = word.strip_prefix(body)?;
            Some(rest.split_once('[').map_or(rest, |(id, _)| id))
        };
        if let Some(id) = id("c_") {
            if !ctx.sim.computes.iter().any(|c| c.id == id) && !LIGGGHTS_OWN.contains(&id) {
                return Err(a.error(0, "Could not find thermo compute ID"));
            }
        } else if let Some(id) = id("f_") {
            if !ctx.sim.fixes.iter().any(|f| f.id == id) {
                return Err(a.error(0, "Could not find thermo fix ID"));
            }
        } else if let Some(id) = id("v_") {
            if ctx.vars.get(id).is_none() {
                return Err(a.error(0, "Could not find thermo variable name"));
            }
        }
    }
    Ok(())
}
