//! `fix_modify ID [servo/]KEYWORD ...` on a `fix mesh/surface/stress/servo`: the servo
//! module's own settings (`integrate start|stop`, `vel_max`, `target_val`, `ctrlParam`,
//! `ratio`), as LIGGGHTS 3.8.0's mesh module reads them. A keyword without the module
//! prefix works with LIGGGHTS's deprecation warning.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::engine::mesh_servo::MeshServo;

/// The mesh modules of a servo mesh, in LIGGGHTS's order.
const MODULES: &[&str] = &["stress", "servo"];

/// One keyword at argument `i` of `fix_modify` on servo mesh `id`: the number of arguments
/// it takes (0: not a servo keyword, LIGGGHTS's "Illegal fix_modify command").
pub fn servo_param(a: &Args, i: usize, id: &str, ctx: &mut Ctx) -> Result<usize, CommandError> {
    let word = a.word(i)?;
    let (module, key) = match word.split_once('/') {
        Some((m, k)) => (Some(m), k),
        None => (None, word),
    };
    if let Some(m) = module {
        if !MODULES.contains(&m) {
            return Err(a.error(
                i,
                format!("Fix mesh/surface/stress/servo (id {id}): Could not find appropriate mesh module \"{m}\" in modify_param"),
            ));
        }
        if m != "servo" {
            return Ok(0);
        }
    }
    let left = a.len() - i;
    let need = |n: usize| -> Result<(), CommandError> {
        if left < n {
            Err(a.error(i, format!("not enough arguments for fix_modify '{key}'")))
        } else {
            Ok(())
        }
    };
    // a variable set point: an equal-style variable, checked as LIGGGHTS checks it here
    let variable = match (key, a.word(i + 1)) {
        ("target_val", Ok(w)) if left >= 2 && w.starts_with("v_") => {
            let name = &w[2..];
            match ctx.vars.get(name).map(|v| v.style) {
                None => return Err(a.error(i + 1, "Variable name does not exist")),
                Some(crate::lang::variables::Style::Equal) => Some(name.to_string()),
                Some(_) => return Err(a.error(i + 1, "Variable is invalid style")),
            }
        }
        _ => None,
    };
    let Some(servo) = servo_of(ctx, id) else {
        return Ok(0);
    };
    let mut warning = None;
    let taken = match key {
        "integrate" => {
            need(2)?;
            servo.integrate = match a.word(i + 1)? {
                "start" => true,
                "stop" => false,
                _ => return Err(a.error(i + 1, "wrong argument for fix_modify 'integrate'")),
            };
            2
        }
        "vel_max" => {
            need(2)?;
            let v = a.real(i + 1)?;
            if v <= 0. {
                return Err(a.error(i + 1, "vel_max > 0 required"));
            }
            servo.vel_max = v;
            2
        }
        "target_val" => {
            need(2)?;
            servo.sum_err = 0.;
            if variable.is_some() {
                // evaluated at each step's controller
                servo.set_point_var = variable;
                return finish(ctx, module, key, None, 2);
            }
            let v = a.real(i + 1)?;
            if v == 0. {
                return Err(a.error(
                    i + 1,
                    "'target_val' (desired force/torque) has to be != 0.0",
                ));
            }
            servo.set_point = -v;
            servo.set_point_var = None;
            2
        }
        "ctrlParam" => {
            need(4)?;
            servo.gains = [a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?];
            servo.sum_err = 0.;
            4
        }
        "ratio" => {
            need(2)?;
            servo.ratio = a.real(i + 1)?;
            if !servo.auto {
                warning = Some("WARNING: Modifying 'ratio' makes sense only when mode='auto' (./src/mesh_module_stress_servo.cpp:729)\n".to_string());
            }
            2
        }
        _ => return Ok(0),
    };
    finish(ctx, module, key, warning, taken)
}

/// The warnings after a servo keyword (its own, then LIGGGHTS's deprecation warning for a
/// keyword without the module prefix); the number of arguments it took.
fn finish(
    ctx: &mut Ctx,
    module: Option<&str>,
    key: &str,
    warning: Option<String>,
    taken: usize,
) -> Result<usize, CommandError> {
    if let Some(w) = warning {
        ctx.say(&w);
    }
    if module.is_none() {
        ctx.say(&format!("WARNING: Using deprecated modify_param for attribute \"{key}\". Consider using servo/{key} in your input file to explicitly specify the mesh module the argument is used for.\n (./src/fix_mesh_surface.cpp:1102)\n"));
    }
    Ok(taken)
}

/// The controller of servo mesh `id`, if it has one.
fn servo_of<'c>(ctx: &'c mut Ctx, id: &str) -> Option<&'c mut MeshServo> {
    crate::engine::fixes::mesh_named_mut(&mut ctx.sim.fixes, id)?
        .servo
        .as_deref_mut()
}
