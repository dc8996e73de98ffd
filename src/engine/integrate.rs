//! Time integration of spheres (`fix nve/sphere`): velocity Verlet for translation and
//! rotation in LIGGGHTS's order of operations, plus uniform body forces (`fix gravity`).
//! Every update is element-wise, so results do not depend on the thread count.

use crate::engine::particles::Particles;

/// Moment-of-inertia prefactor of a solid sphere (I = 0.4 m r^2).
pub const SPHERE_INERTIA: f64 = 0.4;

/// First half of a velocity-Verlet step for particles whose `mask` has `group` bits:
/// half-kick v and omega with the current force and torque, then drift x by a full `dt`.
/// (A plain loop: the work per particle is too small for threads to pay off.)
pub fn initial_integrate(p: &mut Particles, group: u32, dt: f64) {
    let dtf = 0.5 * dt;
    let dtfrotate = dtf / SPHERE_INERTIA;
    for i in 0..p.len() {
        if p.mask[i] & group == 0 {
            continue;
        }
        let mass = p.mass[i];
        let dtfm = dtf / (mass * 1.0);
        for d in 0..3 {
            p.v[i][d] += dtfm * p.f[i][d];
        }
        for d in 0..3 {
            p.x[i][d] += dt * p.v[i][d];
        }
        let dtirotate = dtfrotate / (p.radius[i] * p.radius[i] * mass);
        for d in 0..3 {
            p.omega[i][d] += dtirotate * p.torque[i][d];
        }
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
