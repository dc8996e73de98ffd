//! Time integration of spheres (`fix nve/sphere`): velocity Verlet for translation and
//! rotation in LIGGGHTS's order of operations, plus uniform body forces (`fix gravity`).
//! Every update is element-wise, so results do not depend on the thread count.

use rayon::prelude::*;

use crate::engine::particles::Particles;

/// Moment-of-inertia prefactor of a solid sphere (I = 0.4 m r^2).
pub const SPHERE_INERTIA: f64 = 0.4;

/// Below this many particles the loops stay on one thread.
const PARALLEL_MIN: usize = 4096;

/// First half of a velocity-Verlet step for particles whose `mask` has `group` bits:
/// half-kick v and omega with the current force and torque, then drift x by a full `dt`.
pub fn initial_integrate(p: &mut Particles, group: u32, dt: f64) {
    let dtf = 0.5 * dt;
    let dtfrotate = dtf / SPHERE_INERTIA;
    let body = |(((((x, v), omega), f), torque), ((mask, mass), radius)): (
        (
            (((&mut [f64; 3], &mut [f64; 3]), &mut [f64; 3]), &[f64; 3]),
            &[f64; 3],
        ),
        ((&u32, &f64), &f64),
    )| {
        if mask & group == 0 {
            return;
        }
        let dtfm = dtf / (mass * 1.0);
        for d in 0..3 {
            v[d] += dtfm * f[d];
        }
        for d in 0..3 {
            x[d] += dt * v[d];
        }
        let dtirotate = dtfrotate / (radius * radius * mass);
        for d in 0..3 {
            omega[d] += dtirotate * torque[d];
        }
    };
    let n = p.len();
    if n >= PARALLEL_MIN {
        p.x.par_iter_mut()
            .zip(p.v.par_iter_mut())
            .zip(p.omega.par_iter_mut())
            .zip(p.f.par_iter())
            .zip(p.torque.par_iter())
            .zip(
                p.mask
                    .par_iter()
                    .zip(p.mass.par_iter())
                    .zip(p.radius.par_iter()),
            )
            .for_each(body);
    } else {
        p.x.iter_mut()
            .zip(p.v.iter_mut())
            .zip(p.omega.iter_mut())
            .zip(p.f.iter())
            .zip(p.torque.iter())
            .zip(p.mask.iter().zip(p.mass.iter()).zip(p.radius.iter()))
            .for_each(body);
    }
}

/// Second half of a velocity-Verlet step: half-kick v and omega with the new force/torque.
pub fn final_integrate(p: &mut Particles, group: u32, dt: f64) {
    let dtf = 0.5 * dt;
    let dtfrotate = dtf / SPHERE_INERTIA;
    for i in 0..p.len() {
        if p.mask[i] & group == 0 {
            continue;
        }
        let dtfm = dtf / (p.mass[i] * 1.0);
        for d in 0..3 {
            p.v[i][d] += dtfm * p.f[i][d];
        }
        let dtirotate = dtfrotate / (p.radius[i] * p.radius[i] * p.mass[i]);
        for d in 0..3 {
            p.omega[i][d] += dtirotate * p.torque[i][d];
        }
    }
}

/// A uniform acceleration field (`fix gravity MAG vector X Y Z`), acceleration in length/time^2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gravity {
    /// Acceleration components (length/time^2).
    pub acc: [f64; 3],
    /// Group bits it acts on.
    pub group: u32,
}

impl Gravity {
    /// Gravity of `magnitude` along the direction (dx, dy, dz), normalised as LIGGGHTS does.
    pub fn along(magnitude: f64, dir: [f64; 3], group: u32) -> Result<Gravity, String> {
        let length = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
        if length == 0.0 {
            return Err("Gravity direction vector = 0".into());
        }
        Ok(Gravity {
            acc: [
                magnitude * (dir[0] / length),
                magnitude * (dir[1] / length),
                magnitude * (dir[2] / length),
            ],
            group,
        })
    }

    /// Add m g to every particle's force (LIGGGHTS's post_force).
    pub fn apply(&self, p: &mut Particles) {
        for i in 0..p.len() {
            if p.mask[i] & self.group != 0 {
                let m = p.mass[i] * 1.0;
                for d in 0..3 {
                    p.f[i][d] += m * self.acc[d];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_fall_is_exact_for_verlet() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0, 0.0, 1.0], 0.01, 2500.0);
        let g = Gravity::along(9.81, [0.0, 0.0, -2.0], 1).unwrap();
        let dt = 1e-3;
        g.apply(&mut p);
        for _ in 0..1000 {
            initial_integrate(&mut p, 1, dt);
            p.f[0] = [0.0; 3];
            g.apply(&mut p);
            final_integrate(&mut p, 1, dt);
        }
        // velocity Verlet integrates constant acceleration exactly: z = 1 - g t^2 / 2
        assert!((p.x[0][2] - (1.0 - 0.5 * 9.81)).abs() < 1e-9);
        assert!((p.v[0][2] + 9.81).abs() < 1e-9);
    }

    #[test]
    fn torque_spins_up_a_sphere() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0; 3], 0.5, 1.0);
        p.torque[0] = [0.0, 0.0, 2.0];
        initial_integrate(&mut p, 1, 0.1);
        final_integrate(&mut p, 1, 0.1);
        let inertia = 0.4 * p.mass[0] * 0.25;
        assert!((p.omega[0][2] - 2.0 * 0.1 / inertia).abs() < 1e-12);
        assert!(Gravity::along(1.0, [0.0; 3], 1).is_err());
    }
}
