//! `fix gravity`: a uniform acceleration added as m g to the group's forces (`post_force`);
//! clumps, `fix buoyancy` and the speed estimate read the acceleration.

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStep, FixStyle, StepInputs};
use crate::engine::integrate::Gravity;
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "gravity",
    "fix ID GROUP gravity G vector X Y Z | chute ANGLE | spherical PHI THETA",
    &[],
    "gravitational acceleration G (acceleration) along a direction, down a chute inclined by ANGLE (degrees) about y, or at polar angles PHI THETA (degrees); each number may be a v_name equal-style variable, evaluated every step",
);

impl FixStyle for Gravity {
    fn name(&self) -> &str {
        "gravity"
    }

    fn post_force(&mut self, p: &mut Particles, _at: &FixStep) {
        self.apply(p);
    }

    fn acceleration(&self) -> Option<[f64; 3]> {
        Some(self.acc)
    }
}

/// One of the numbers that define the acceleration: a constant or an equal-style variable
/// evaluated at every force evaluation (LIGGGHTS's `v_name`).
#[derive(Debug, Clone, PartialEq)]
enum Term {
    /// A number as written.
    Constant(f64),
    /// The name of an equal-style variable.
    Variable(String),
}

/// How the terms give a direction (LIGGGHTS's `set_acceleration`).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Shape {
    /// `vector X Y Z`: the terms are the components, normalised.
    Vector,
    /// `chute ANGLE`: the term is the incline (degrees).
    Chute,
    /// `spherical PHI THETA` (degrees).
    Spherical,
}

/// `fix gravity` with `v_name` terms: the acceleration is set again from the variables at
/// every force evaluation, before its `post_force`, as LIGGGHTS's post_force does.
struct VariableGravity {
    /// The magnitude (acceleration) and the direction's terms in the order written.
    terms: Vec<Term>,
    shape: Shape,
    dimension: u32,
    /// The acceleration of this force evaluation (zero before the first).
    gravity: Gravity,
}

impl VariableGravity {
    /// The acceleration from the terms' values (magnitude first), or LIGGGHTS's error.
    fn set(&mut self, v: &[f64]) -> Result<(), EngineError> {
        let (magnitude, group) = (v[0], self.gravity.group);
        self.gravity = match self.shape {
            Shape::Vector if self.dimension == 2 => {
                Gravity::along(magnitude, [v[1], v[2], 0.0], group)?
            }
            Shape::Vector => Gravity::along(magnitude, [v[1], v[2], v[3]], group)?,
            Shape::Chute => Gravity::spherical(magnitude, 0.0, 180.0 - v[1], self.dimension, group),
            Shape::Spherical => Gravity::spherical(magnitude, v[1], v[2], self.dimension, group),
        };
        Ok(())
    }
}

impl FixStyle for VariableGravity {
    fn name(&self) -> &str {
        "gravity"
    }

    fn evaluates(&self) -> bool {
        true
    }

    fn evaluate(
        &mut self,
        _p: &Particles,
        _at: &FixStep,
        inputs: &mut dyn StepInputs,
    ) -> Result<(), EngineError> {
        let mut values = Vec::with_capacity(self.terms.len());
        for t in &self.terms {
            values.push(match t {
                Term::Constant(c) => *c,
                // LIGGGHTS's init names the fix when the variable is missing
                Term::Variable(name) => inputs.equal(name).map_err(|e| {
                    if e.to_string() == format!("Variable name {name} does not exist") {
                        EngineError::from(
                            "Variable name for fix gravity does not exist".to_string(),
                        )
                    } else {
                        e
                    }
                })?,
            });
        }
        self.set(&values)
    }

    fn post_force(&mut self, p: &mut Particles, _at: &FixStep) {
        self.gravity.apply(p);
    }

    fn acceleration(&self) -> Option<[f64; 3]> {
        Some(self.gravity.acc)
    }

    fn reads_computes(&self) -> bool {
        true
    }
}

/// Argument `i` as a term: `v_name` (an equal-style variable, if it is defined yet: LIGGGHTS
/// looks it up at the run's init) or a number.
fn term(a: &Args, ctx: &Ctx, i: usize) -> Result<Term, CommandError> {
    use crate::lang::variables::Style;
    let w = a.word(i)?;
    let Some(name) = w.strip_prefix("v_") else {
        return Ok(Term::Constant(a.real(i)?));
    };
    match ctx.vars.get(name).map(|v| v.style) {
        Some(Style::Equal) | None => Ok(Term::Variable(name.to_string())),
        Some(_) => Err(a.error(i, "Variable for fix gravity is invalid style")),
    }
}

/// `fix ID GROUP gravity MAG vector X Y Z | chute ANGLE | spherical PHI THETA` (acceleration;
/// angles in degrees; any of them a `v_name` equal-style variable).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let FixDef { bit, .. } = *fix;
    let illegal = || a.error(a.len().saturating_sub(1), "Illegal fix gravity command");
    if a.len() < 5 {
        return Err(illegal());
    }
    let (shape, n) = match a.word(4)? {
        "vector" => (Shape::Vector, 8),
        "chute" => (Shape::Chute, 6),
        "spherical" => (Shape::Spherical, 7),
        _ => return Err(a.error(4, "Illegal fix gravity command")),
    };
    if a.len() != n {
        return Err(illegal());
    }
    let terms = (3..n)
        .filter(|&i| i != 4)
        .map(|i| term(a, ctx, i))
        .collect::<Result<Vec<_>, _>>()?;
    let mut g = VariableGravity {
        terms,
        shape,
        dimension: ctx.sim.dimension,
        gravity: Gravity {
            acc: [0.0; 3],
            group: bit,
        },
    };
    let constants: Option<Vec<f64>> = g
        .terms
        .iter()
        .map(|t| match t {
            Term::Constant(c) => Some(*c),
            Term::Variable(_) => None,
        })
        .collect();
    let Some(values) = constants else {
        return Ok(Box::new(g));
    };
    // constant terms: the acceleration once and for all
    if shape == Shape::Vector {
        // the vector's own form, normalised in three dimensions as before
        let dir = [values[1], values[2], values[3]];
        return Ok(Box::new(
            Gravity::along(values[0], dir, bit).map_err(|m| a.error(5, &m))?,
        ));
    }
    g.set(&values).map_err(|m| a.error(5, &m))?;
    Ok(Box::new(g.gravity))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adds_the_weight_of_its_group_and_offers_its_acceleration() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0; 3], 0.5, 2.0);
        p.push(2, 1, [1.0; 3], 0.5, 3.0);
        p.mask[1] = 2;
        let mut g = Gravity::along(9.81, [0.0, 0.0, -2.0], 1).expect("direction");
        let domain = crate::engine::domain::Domain::default();
        g.post_force(&mut p, &FixStep::plain(1, 0, 1e-5, &domain));
        assert_eq!(p.f[0], [0.0, 0.0, -9.81 * p.mass[0]]);
        assert_eq!(p.f[1], [0.0; 3]);
        assert_eq!(FixStyle::acceleration(&g), Some([0.0, 0.0, -9.81]));
    }
}
