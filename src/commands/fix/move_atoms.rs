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
    let (mut motion, used) = match a.word(3)? {
        "linear" => (Motion::Linear(components(a, 4)?), 7),
        "wiggle" => (wiggle(a)?, 8),
        "rotate" => (rotate(a)?, 11),
        "variable" => (variable(a, ctx)?, 10),
        _ => return Err(a.error(3, "Illegal fix move command")),
    };
    let mut i = used;
    while i < a.len() {
        match a.word(i)? {
            "units" => {
                if a.word_in(i + 1, &["box", "lattice"])? == "lattice" {
                    in_lattice_units(a, ctx, i, &mut motion)?;
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

/// Words `from..from + 3` as the x, y, z of a displacement or velocity, `NULL` for a
/// component left free.
fn components(a: &Args, from: usize) -> Result<[Option<f64>; 3], CommandError> {
    let mut v = [None; 3];
    for (d, slot) in v.iter_mut().enumerate() {
        let w = a.word(from + d)?;
        if w != "NULL" {
            *slot = Some(a.real(from + d)?);
        }
    }
    Ok(v)
}

/// `wiggle Ax Ay Az PERIOD`: a sine oscillation of amplitude A (length) and period PERIOD
/// (time).
fn wiggle(a: &Args) -> Result<Motion, CommandError> {
    let amplitude = components(a, 4)?;
    let period = a.real(7)?;
    if period <= 0.0 {
        return Err(a.error(7, "Illegal fix move command"));
    }
    Ok(Motion::Wiggle {
        amplitude,
        omega: 2.0 * std::f64::consts::PI / period,
    })
}

/// `rotate Px Py Pz Rx Ry Rz PERIOD`: a rotation about the axis R (made a unit vector)
/// through the point P (length), one turn per PERIOD (time).
fn rotate(a: &Args) -> Result<Motion, CommandError> {
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
    Ok(Motion::Rotate {
        point,
        axis: axis.map(|c| c / len),
        omega: 2.0 * std::f64::consts::PI / period,
    })
}

/// `variable DX DY DZ VX VY VZ`: displacement and velocity from equal-style variables
/// (`v_NAME`), `NULL` for a component not set.
fn variable(a: &Args, ctx: &mut Ctx) -> Result<Motion, CommandError> {
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
    Ok(Motion::Variable {
        displace: [dx, dy, dz],
        velocity: [vx, vy, vz],
    })
}

/// `units lattice` (keyword at word `i`): lengths and velocities scaled by the lattice
/// spacing.
fn in_lattice_units(
    a: &Args,
    ctx: &Ctx,
    i: usize,
    motion: &mut Motion,
) -> Result<(), CommandError> {
    let scale = ctx
        .sim
        .lattice
        .as_ref()
        .map(|l| l.0)
        .ok_or_else(|| a.error(i + 1, "Use of fix move with undefined lattice"))?;
    let sc = |v: &mut [Option<f64>; 3]| v.iter_mut().for_each(|c| *c = c.map(|x| x * scale));
    match motion {
        Motion::Linear(v) => sc(v),
        Motion::Wiggle { amplitude, .. } => sc(amplitude),
        Motion::Rotate { point, .. } => point.iter_mut().for_each(|c| *c *= scale),
        // LIGGGHTS scales variable motion by neither
        Motion::Variable { .. } => {}
    }
    Ok(())
}
