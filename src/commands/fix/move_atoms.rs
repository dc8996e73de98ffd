//! `fix move`: prescribed motion of particles.

use super::variable_value;
use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStyle, Motion, Move};

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "move",
    "fix ID GROUP move linear|wiggle|rotate|variable ...",
    &[kw(
        "units",
        &[arg("box|lattice", Value::OneOf(&["box", "lattice"]))],
        "lengths in box or lattice units",
    )],
    "prescribed particle motion",
);

/// `fix ID GROUP move linear|wiggle|rotate|variable ... [units box|lattice]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let FixDef { bit, .. } = *fix;
    let components = |from: usize| -> std::result::Result<[Option<f64>; 3], CommandError> {
        let mut v = [None; 3];
        for (d, slot) in v.iter_mut().enumerate() {
            let w = a.word(from + d)?;
            if w != "NULL" {
                *slot = Some(a.real(from + d)?);
            }
        }
        Ok(v)
    };
    let (motion, used) = match a.word(3)? {
        "linear" => (Motion::Linear(components(4)?), 7),
        "wiggle" => {
            let amplitude = components(4)?;
            let period = a.real(7)?;
            if period <= 0.0 {
                return Err(a.error(7, "Illegal fix move command"));
            }
            (
                Motion::Wiggle {
                    amplitude,
                    omega: 2.0 * std::f64::consts::PI / period,
                },
                8,
            )
        }
        "rotate" => {
            a.count(
                11..=usize::MAX,
                "fix ID GROUP move rotate Px Py Pz Rx Ry Rz PERIOD",
            )?;
            let point = [a.real(4)?, a.real(5)?, a.real(6)?];
            let axis = [a.real(7)?, a.real(8)?, a.real(9)?];
            let period = a.real(10)?;
            if period <= 0.0 {
                return Err(a.error(10, "Illegal fix move command"));
            }
            let len = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
            if len == 0.0 {
                return Err(a.error(7, "Zero length rotation vector with fix move"));
            }
            (
                Motion::Rotate {
                    point,
                    axis: axis.map(|c| c / len),
                    omega: 2.0 * std::f64::consts::PI / period,
                },
                11,
            )
        }
        "variable" => {
            use crate::engine::fixes::ForceValue;
            a.count(
                10..=usize::MAX,
                "fix ID GROUP move variable DX DY DZ VX VY VZ",
            )?;
            let mut slots: [ForceValue; 6] = Default::default();
            for (k, slot) in slots.iter_mut().enumerate() {
                let w = a.word(4 + k)?;
                if let Some(name) = w.strip_prefix("v_") {
                    *slot = variable_value(a, ctx, 4 + k, name, "move")?;
                } else if w != "NULL" {
                    return Err(a.error(4 + k, "Illegal fix move command"));
                }
            }
            let [dx, dy, dz, vx, vy, vz] = slots;
            (
                Motion::Variable {
                    displace: [dx, dy, dz],
                    velocity: [vx, vy, vz],
                },
                10,
            )
        }
        _ => return Err(a.error(3, "Illegal fix move command")),
    };
    // `units lattice` scales lengths and velocities by the lattice spacing
    let mut motion = motion;
    let mut i = used;
    while i < a.len() {
        match a.word(i)? {
            "units" => {
                if a.word_in(i + 1, &["box", "lattice"])? == "lattice" {
                    let scale =
                        ctx.sim.lattice.as_ref().map(|l| l.0).ok_or_else(|| {
                            a.error(i + 1, "Use of fix move with undefined lattice")
                        })?;
                    let sc = |v: &mut [Option<f64>; 3]| {
                        v.iter_mut().for_each(|c| *c = c.map(|x| x * scale))
                    };
                    match &mut motion {
                        Motion::Linear(v) => sc(v),
                        Motion::Wiggle { amplitude, .. } => sc(amplitude),
                        Motion::Rotate { point, .. } => point.iter_mut().for_each(|c| *c *= scale),
                        // LIGGGHTS scales variable motion by neither
                        Motion::Variable { .. } => {}
                    }
                }
                i += 2;
            }
            _ => return Err(a.error(i, "Illegal fix move command")),
        }
    }
    let sim = &ctx.sim;
    Ok(Box::new(Move::new(
        motion,
        &sim.particles,
        bit,
        &sim.domain,
        sim.step,
    )))
}
