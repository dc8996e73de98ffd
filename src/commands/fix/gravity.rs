//! `fix gravity`: a uniform acceleration added as m g to the group's forces (`post_force`);
//! clumps, `fix buoyancy` and the speed estimate read the acceleration.

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::integrate::Gravity;
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "gravity",
    "fix ID GROUP gravity G vector X Y Z | chute ANGLE | spherical PHI THETA",
    &[],
    "gravitational acceleration G (acceleration) along a direction, down a chute inclined by ANGLE (degrees) about y, or at polar angles PHI THETA (degrees)",
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

/// `fix ID GROUP gravity MAG vector X Y Z | chute ANGLE | spherical PHI THETA` (acceleration;
/// angles in degrees).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let FixDef { bit, .. } = *fix;
    let illegal = || a.error(a.len().saturating_sub(1), "Illegal fix gravity command");
    if a.len() < 5 {
        return Err(illegal());
    }
    if let Some(i) = (3..a.len()).find(|&i| i != 4 && a.word(i).is_ok_and(|w| w.starts_with("v_")))
    {
        return Err(a.unsupported(i, "fix gravity with an equal-style variable"));
    }
    let magnitude = a.real(3)?;
    let dimension = ctx.sim.dimension;
    let g = match a.word(4)? {
        "vector" => {
            if a.len() != 8 {
                return Err(illegal());
            }
            let dir = [a.real(5)?, a.real(6)?, a.real(7)?];
            Gravity::along(magnitude, dir, bit).map_err(|m| a.error(5, &m))?
        }
        // the chute's incline: the polar angle 180 - ANGLE in the xz plane
        "chute" => {
            if a.len() != 6 {
                return Err(illegal());
            }
            let vert = a.real(5)?;
            Gravity::spherical(magnitude, 0.0, 180.0 - vert, dimension, bit)
        }
        "spherical" => {
            if a.len() != 7 {
                return Err(illegal());
            }
            let (phi, theta) = (a.real(5)?, a.real(6)?);
            Gravity::spherical(magnitude, phi, theta, dimension, bit)
        }
        _ => return Err(a.error(4, "Illegal fix gravity command")),
    };
    Ok(Box::new(g))
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
