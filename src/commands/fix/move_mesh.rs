//! `fix move/mesh`: prescribed motion of a mesh.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID group move/mesh mesh MESH STYLE args...` (linear, wiggle, rotate, riggle, viblin,
/// vibrot), with LIGGGHTS's messages.
pub fn build(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<FixKind, CommandError> {
    use crate::engine::mesh_motion::{unit_axis, Motion, MoveMesh};
    if a.len() < 6 {
        return Err(a.error(
            2,
            "Illegal fix move/mesh command, you need to specify a mesh",
        ));
    }
    if a.word(3)? != "mesh" {
        return Err(a.error(3, "Illegal fix move/mesh command, expecting keyword 'mesh'"));
    }
    let mesh = a.word(4)?.to_string();
    let Some(m) = ctx.sim.fixes.iter().find_map(|f| match &f.kind {
        FixKind::Mesh(m) if f.id == mesh => Some(m),
        _ => None,
    }) else {
        return Err(a.error(4, "Illegal fix move/mesh command, illegal mesh ID provided"));
    };
    if m.surface_vel.is_some() {
        return Err(a.error(4, "Illegal fix move/mesh command, cannot apply move to a mesh using keywords 'velocity' or 'angular_velocity'"));
    }
    let style = a.word(5)?;
    // LIGGGHTS counts the style word as argument 0 of the motion's own list
    let narg = a.len() - 5;
    let at = |k: usize| 5 + k;
    let need = |n: usize| -> std::result::Result<(), CommandError> {
        if narg < n {
            Err(a.error(5, format!("Not enough arguments for movement type {style}")))
        } else {
            Ok(())
        }
    };
    let keyword = |k: usize, w: &str| -> std::result::Result<(), CommandError> {
        if a.word(at(k))? != w {
            Err(a.error(at(k), format!("Expected keyword '{w}'")))
        } else {
            Ok(())
        }
    };
    let vec3 = |k: usize| -> std::result::Result<[f64; 3], CommandError> {
        Ok([a.real(at(k))?, a.real(at(k + 1))?, a.real(at(k + 2))?])
    };
    let mut warn = |n: usize| {
        if narg > n {
            ctx.say(&format!("WARNING: Movement type {style} requires only {n} arguments, excess arguments will be ignored\n"));
        }
    };
    let two_pi = 2.0 * std::f64::consts::PI;
    // (words read, per mode: amplitude, phase, angular frequency)
    type Modes = (usize, Vec<(f64, f64, f64)>);
    let modes = |order_at: usize| -> std::result::Result<Modes, CommandError> {
        keyword(order_at, "order")?;
        let n = a.int(at(order_at + 1))?;
        if !(1..=30).contains(&n) {
            return Err(a.error(
                at(order_at + 1),
                "order can be at most 30 and must be greater 0",
            ));
        }
        let n = n as usize;
        // LIGGGHTS checks for two lists only and reads the periods after them
        if narg < order_at + 5 + 2 * n {
            return Err(a.error(5, format!("Not enough arguments for movement type {style}")));
        }
        if narg < order_at + 5 + 3 * n {
            return Err(a.error(
                5,
                format!("Not enough arguments for movement type {style} (LIGGGHTS reads the periods past the end of the command and crashes)"),
            ));
        }
        keyword(order_at + 2, "amplitude")?;
        keyword(order_at + 3 + n, "phase")?;
        keyword(order_at + 4 + 2 * n, "period")?;
        let mut out = Vec::with_capacity(n);
        for j in 0..n {
            let c = a.real(at(order_at + 3 + j))?;
            let phase = a.real(at(order_at + 4 + n + j))?;
            let period = a.real(at(order_at + 5 + 2 * n + j))?;
            out.push((c, phase, two_pi / period));
        }
        Ok((n, out))
    };
    let (motion, reference) = match style {
        "linear" => {
            need(4)?;
            (Motion::Linear(vec3(1)?), None)
        }
        "wiggle" => {
            need(7)?;
            keyword(1, "amplitude")?;
            keyword(5, "period")?;
            let m = Motion::Wiggle {
                amplitude: vec3(2)?,
                omega: two_pi / a.real(at(6))?,
            };
            (m, None)
        }
        "rotate" => {
            need(11)?;
            keyword(1, "origin")?;
            keyword(5, "axis")?;
            keyword(9, "period")?;
            let m = Motion::Rotate {
                axis: unit_axis(vec3(6)?),
                omega: two_pi / a.real(at(10))?,
            };
            (m, Some(vec3(2)?))
        }
        "riggle" => {
            need(13)?;
            keyword(1, "origin")?;
            keyword(5, "axis")?;
            keyword(9, "period")?;
            keyword(11, "amplitude")?;
            let m = Motion::Riggle {
                origin: vec3(2)?,
                axis: unit_axis(vec3(6)?),
                omega: two_pi / a.real(at(10))?,
                alpha: (std::f64::consts::PI * a.real(at(12))?) / 180.0,
            };
            (m, None)
        }
        "viblin" => {
            need(7)?;
            keyword(1, "axis")?;
            let axis = unit_axis(vec3(2)?);
            let (_, modes) = modes(5)?;
            (Motion::Viblin { axis, modes }, None)
        }
        "vibrot" => {
            need(11)?;
            keyword(1, "origin")?;
            keyword(5, "axis")?;
            let origin = vec3(2)?;
            let axis = unit_axis(vec3(6)?);
            let (_, modes) = modes(9)?;
            (
                Motion::Vibrot {
                    origin,
                    axis,
                    modes,
                },
                None,
            )
        }
        "linear/variable" | "rotate/variable" => {
            return Err(a.unsupported(5, &format!("fix move/mesh {style}")))
        }
        _ => {
            return Err(a
                .keyword_error(
                    5,
                    &["linear", "wiggle", "rotate", "riggle", "viblin", "vibrot"],
                )
                .with_help("LIGGGHTS: Mesh movement type not available"))
        }
    };
    // LIGGGHTS's excess-argument warnings (viblin's names the wiggle style)
    match &motion {
        Motion::Linear(_) => warn(4),
        Motion::Wiggle { .. } => warn(7),
        Motion::Rotate { .. } => warn(11),
        Motion::Riggle { .. } => warn(13),
        Motion::Viblin { modes, .. } => {
            let n = modes.len();
            if narg > 10 + 2 * n {
                ctx.say("WARNING: Movement type wiggle requires only (10 + 2*$order) arguments, excess arguments will be ignored (./src/mesh_mover_linear.cpp:303)\n");
            }
        }
        Motion::Vibrot { modes, .. } => {
            let n = modes.len();
            if narg > 14 + 2 * n {
                ctx.say("WARNING: Movement type vibrot requires only (14 + 2*$order) arguments, excess arguments will be ignored (./src/mesh_mover_rotation.cpp:347)\n");
            }
        }
    }
    Ok(FixKind::MoveMesh(MoveMesh {
        mesh,
        motion,
        time: 0.0,
        reference,
    }))
}
