//! `velocity GROUP set VX VY VZ` with variables (`v_name`, equal- or atom-style) as LIGGGHTS
//! 3.8.0 does it: every variable evaluated first (atom-style ones for every atom), then the
//! group's velocities set (or added with `sum yes`); NULL leaves a component alone and the
//! lattice scale applies to constants only.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::lang::system::Mode;
use crate::lang::variables::Style;

enum Component {
    Keep,
    Constant(f64),
    PerAtom(std::rc::Rc<Vec<f64>>),
    Unknown,
}

/// `velocity GROUP set ...` where a component is a variable.
pub fn set(a: &Args, ctx: &mut Ctx, bit: u32, sum: bool, scale: f64) -> Result<(), CommandError> {
    // names first (LIGGGHTS checks every component's variable before evaluating any)
    let mut kinds = Vec::new();
    for d in 0..3 {
        let w = a.word(2 + d)?;
        kinds.push(match w.strip_prefix("v_") {
            Some(name) => match ctx.vars.get(name).map(|v| v.style) {
                None => return Err(a.error(2 + d, "Variable name for velocity set does not exist")),
                Some(Style::Atom | Style::AtomFile) => Some((name.to_string(), true)),
                Some(Style::Equal) => Some((name.to_string(), false)),
                Some(_) => return Err(a.error(2 + d, "Variable for velocity set is invalid style")),
            },
            None => None,
        });
    }
    let check = ctx.sys.mode == Mode::Check;
    let mut components = Vec::new();
    for (d, kind) in kinds.iter().enumerate() {
        let w = a.word(2 + d)?;
        let mut scope = crate::lang::scope::Scope::new(ctx.vars, ctx.sys, ctx.sim);
        // a dry run may not know what a variable needs
        let unknown = |e: &crate::lang::error::VariableError| check || e.is_known_when_run();
        components.push(match kind {
            None if w == "NULL" => Component::Keep,
            None => Component::Constant(scale * a.real(2 + d)?),
            Some((name, true)) => match scope.atom_variable(name) {
                Ok(v) => Component::PerAtom(v),
                Err(e) if unknown(&e) => Component::Unknown,
                Err(e) => return Err(a.error(2 + d, e.to_string())),
            },
            Some((name, false)) => match scope.equal_variable(name) {
                Ok(v) => Component::Constant(v),
                Err(e) if unknown(&e) => Component::Unknown,
                Err(e) => return Err(a.error(2 + d, e.to_string())),
            },
        });
    }
    if check && components.iter().any(|c| matches!(c, Component::Unknown)) {
        return Ok(());
    }
    let p = &mut ctx.sim.particles;
    for k in 0..p.len() {
        if p.mask[k] & bit == 0 {
            continue;
        }
        for (d, c) in components.iter().enumerate() {
            let value = match c {
                Component::Keep | Component::Unknown => continue,
                Component::Constant(v) => *v,
                Component::PerAtom(values) => values[k],
            };
            if sum {
                p.v[k][d] += value;
            } else {
                p.v[k][d] = value;
            }
        }
    }
    Ok(())
}
