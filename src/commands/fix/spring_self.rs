//! `fix spring/self K [xyz|xy|xz|yz|x|y|z]`: each particle of the group tethered to where it
//! was when the fix was defined (LIGGGHTS 3.8.0's fix_spring_self.cpp), pulled back in
//! `post_force`; `f_ID` is the springs' energy, the tether points are per-atom restart state.

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "spring/self",
    "fix ID GROUP spring/self K [xyz|xy|xz|yz|x|y|z]",
    &[],
    "each particle pulled back to where it was when the fix was defined, force -K d (K: force per length; f_ID the springs' energy)",
);

/// One `fix spring/self`.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringSelf {
    /// Spring constant (force per length).
    pub k: f64,
    /// The dimensions the spring acts along (x, y, z).
    pub dims: [bool; 3],
    /// Name of the per-particle slot holding the tether points (unwrapped, length).
    pub slot: String,
    /// Box lengths when the fix was defined, to unwrap periodic images (length).
    pub prd: [f64; 3],
    /// The springs' energy at the last force evaluation (energy): `f_ID`.
    pub energy: f64,
}

impl SpringSelf {
    /// Record the group's unwrapped positions as the tether points (others 0).
    pub fn tether(&self, p: &mut Particles, group: u32) {
        let k = p.extra_index(&self.slot, 3);
        for i in 0..p.len() {
            let at = if p.mask[i] & group != 0 {
                self.unwrap(p, i)
            } else {
                [0.0; 3]
            };
            p.extra[k].data[3 * i..3 * i + 3].copy_from_slice(&at);
        }
    }

    /// Unwrapped position of particle `i` (length).
    fn unwrap(&self, p: &Particles, i: usize) -> [f64; 3] {
        [0, 1, 2].map(|d| p.x[i][d] + p.image[i][d] as f64 * self.prd[d])
    }

    /// Pull each particle of the group back towards its tether point, f -= K d, and sum
    /// the energy 0.5 K |d|^2.
    pub fn apply(&mut self, p: &mut Particles, group: u32) {
        let k = p.extra_index(&self.slot, 3);
        let mut energy = 0.0;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let u = self.unwrap(p, i);
            let origin = &p.extra[k].data[3 * i..3 * i + 3];
            let d: [f64; 3] =
                std::array::from_fn(|c| if self.dims[c] { u[c] - origin[c] } else { 0.0 });
            for (f, dc) in p.f[i].iter_mut().zip(d) {
                *f -= self.k * dc;
            }
            energy += self.k * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        }
        self.energy = energy * 0.5;
    }
}

impl FixStyle for SpringSelf {
    fn name(&self) -> &str {
        "spring/self"
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        self.apply(p, at.group);
    }

    /// LIGGGHTS flags its global scalar extensive.
    fn extensive(&self, index: Option<usize>) -> bool {
        index.is_none()
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        index.is_none().then_some(self.energy)
    }

    fn restart_per_atom(&self, p: &Particles) -> Option<(i32, Vec<Vec<f64>>)> {
        // the tether points, as LIGGGHTS's per-atom `xoriginal`
        let rows = match p.extra.iter().position(|e| e.name == self.slot) {
            Some(k) => p.extra[k].data.chunks(3).map(<[f64]>::to_vec).collect(),
            None => vec![vec![0.0; 3]; p.len()],
        };
        Some((4, rows))
    }

    fn keeps_per_atom_state(&self) -> bool {
        true
    }

    // regolith has tallied the per-atom virial on every step while this fix is defined
    fn reads_computes(&self) -> bool {
        true
    }
}

/// `fix ID GROUP spring/self K [xyz|xy|xz|yz|x|y|z]` (K: force per length).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    const ILLEGAL: &str = "Illegal fix spring/self command";
    if a.len() < 4 || a.len() > 5 {
        return Err(a.error(2, ILLEGAL));
    }
    let k = a.real(3)?;
    if k <= 0.0 {
        return Err(a.error(3, ILLEGAL));
    }
    let dims = match a.len() {
        4 => [true; 3],
        _ => match a.word(4)? {
            "xyz" => [true, true, true],
            "xy" => [true, true, false],
            "xz" => [true, false, true],
            "yz" => [false, true, true],
            "x" => [true, false, false],
            "y" => [false, true, false],
            "z" => [false, false, true],
            _ => return Err(a.error(4, ILLEGAL)),
        },
    };
    let spring = SpringSelf {
        k,
        dims,
        slot: format!("spring/self {}", fix.id),
        prd: [0, 1, 2].map(|d| ctx.sim.domain.length(d)),
        energy: 0.0,
    };
    spring.tether(&mut ctx.sim.particles, fix.bit);
    // a restart file's tether points of this fix replace the current positions
    if let Some(stored) = ctx.sim.restart_move_origins.get(&spring.slot) {
        let p = &mut ctx.sim.particles;
        let k = p.extra_index(&spring.slot, 3);
        for i in 0..p.len() {
            if let (true, Some(x)) = (p.mask[i] & fix.bit != 0, stored.get(&p.id[i])) {
                p.extra[k].data[3 * i..3 * i + 3].copy_from_slice(x);
            }
        }
    }
    Ok(Box::new(spring))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pulls_back_along_its_dimensions_only() {
        let mut p = Particles::default();
        p.push(1, 1, [1.0, 2.0, 3.0], 0.5, 1.0);
        let mut s = SpringSelf {
            k: 10.0,
            dims: [true, false, true],
            slot: "spring_self_s".into(),
            prd: [5.0; 3],
            energy: 0.0,
        };
        s.tether(&mut p, 1);
        p.x[0] = [1.5, 1.0, 2.0];
        p.image[0] = [0, 0, 1];
        s.apply(&mut p, 1);
        // dx = 0.5, dy ignored, dz = 2 + 5 - 3 = 4
        assert_eq!(p.f[0], [-5.0, 0.0, -40.0]);
        assert_eq!(s.energy, 0.5 * 10.0 * (0.25 + 16.0));
        assert_eq!(s.value(None), Some(s.energy));
        assert_eq!(s.value(Some(1)), None);
        let (size, rows) = s.restart_per_atom(&p).expect("tether points");
        assert_eq!((size, rows), (4, vec![vec![1.0, 2.0, 3.0]]));
    }
}
