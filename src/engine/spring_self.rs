//! `fix spring/self K [xyz|xy|xz|yz|x|y|z]`: each particle of the group tethered to where it
//! was when the fix was defined (LIGGGHTS 3.8.0's fix_spring_self.cpp).

use crate::engine::particles::Particles;

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

    /// The `post_force` phase: pull each particle of the group back towards its tether
    /// point, f -= K d, and sum the energy 0.5 K |d|^2.
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
    }
}
