//! `fix momentum`: zero the linear and/or angular momentum of a group every N steps at the
//! end of the step, as LIGGGHTS 3.8.0 (LAMMPS's fix momentum) does.

use crate::engine::domain::Domain;
use crate::engine::fixes::FixKind;
use crate::engine::particles::Particles;

/// One `fix momentum N [linear XF YF ZF] [angular]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Momentum {
    /// Act every this many steps.
    pub every: i64,
    /// `linear xflag yflag zflag`: which centre-of-mass velocity components are removed.
    pub linear: Option<[bool; 3]>,
    /// `angular`: remove the rigid rotation about the centre of mass.
    pub angular: bool,
    /// The group's mass at the run's setup (mass), as LIGGGHTS keeps it for the run.
    pub mass: f64,
}

/// The unwrapped position of particle `i` (length).
fn unwrap(p: &Particles, i: usize, domain: &Domain) -> [f64; 3] {
    let mut x = p.x[i];
    for (d, xd) in x.iter_mut().enumerate() {
        *xd += p.image[i][d] as f64 * domain.length(d);
    }
    x
}

impl Momentum {
    /// The group's total mass (mass), summed in particle order.
    pub fn group_mass(p: &Particles, group: u32) -> f64 {
        let mut m = 0.0;
        for i in 0..p.len() {
            if p.mask[i] & group != 0 {
                m += p.mass[i];
            }
        }
        m
    }

    /// Adjust the velocities of `group` (LIGGGHTS's `end_of_step`).
    pub fn apply(&self, p: &mut Particles, group: u32, domain: &Domain) {
        let members = |p: &Particles, i: usize| p.mask[i] & group != 0;
        let total = self.mass;
        if let Some(flags) = self.linear {
            let mut mom = [0.0; 3];
            for i in 0..p.len() {
                if members(p, i) {
                    for (d, m) in mom.iter_mut().enumerate() {
                        *m += p.v[i][d] * p.mass[i];
                    }
                }
            }
            if total > 0.0 {
                mom = mom.map(|c| c / total);
            }
            for i in 0..p.len() {
                if members(p, i) {
                    for d in (0..3).filter(|&d| flags[d]) {
                        p.v[i][d] -= mom[d];
                    }
                }
            }
        }
        if self.angular {
            let mut cm = [0.0; 3];
            for i in 0..p.len() {
                if members(p, i) {
                    let u = unwrap(p, i, domain);
                    for (c, ud) in cm.iter_mut().zip(u) {
                        *c += ud * p.mass[i];
                    }
                }
            }
            if total > 0.0 {
                cm = cm.map(|c| c / total);
            }
            let mut l = [0.0; 3];
            let mut t = [[0.0; 3]; 3];
            for i in 0..p.len() {
                if !members(p, i) {
                    continue;
                }
                let u = unwrap(p, i, domain);
                let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
                let (m, v) = (p.mass[i], p.v[i]);
                l[0] += m * (dy * v[2] - dz * v[1]);
                l[1] += m * (dz * v[0] - dx * v[2]);
                l[2] += m * (dx * v[1] - dy * v[0]);
            }
            for i in 0..p.len() {
                if !members(p, i) {
                    continue;
                }
                let u = unwrap(p, i, domain);
                let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
                let m = p.mass[i];
                add_inertia(&mut t, [dx, dy, dz], m);
            }
            mirror_inertia(&mut t);
            let w = omega(l, t);
            for i in 0..p.len() {
                if !members(p, i) {
                    continue;
                }
                let u = unwrap(p, i, domain);
                let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
                p.v[i][0] -= w[1] * dz - w[2] * dy;
                p.v[i][1] -= w[2] * dx - w[0] * dz;
                p.v[i][2] -= w[0] * dy - w[1] * dx;
            }
        }
    }
}

/// Add a particle of mass `m` (mass) at arm `d` (length) from the centre of mass to the
/// inertia tensor `t` (mass*length^2): its diagonal and upper triangle, in LIGGGHTS's order.
#[inline]
pub fn add_inertia(t: &mut [[f64; 3]; 3], [dx, dy, dz]: [f64; 3], m: f64) {
    t[0][0] += m * (dy * dy + dz * dz);
    t[1][1] += m * (dx * dx + dz * dz);
    t[2][2] += m * (dx * dx + dy * dy);
    t[0][1] -= m * dx * dy;
    t[1][2] -= m * dy * dz;
    t[0][2] -= m * dx * dz;
}

/// Copy the upper triangle of the inertia tensor `t` to its lower one (it is symmetric).
#[inline]
pub fn mirror_inertia(t: &mut [[f64; 3]; 3]) {
    t[1][0] = t[0][1];
    t[2][1] = t[1][2];
    t[2][0] = t[0][2];
}

/// The angular velocity (1/time) of angular momentum `l` with inertia tensor `t`, through
/// the adjugate and determinant as LAMMPS's Group::omega computes it.
/// The angular velocity (rad/s) of angular momentum `l` (kg m^2/s) about inertia tensor `t`
/// (kg m^2), through the adjugate divided by the determinant when it is positive (as LIGGGHTS
/// does for `fix momentum angular` and `velocity ... rot yes`).
pub fn omega(l: [f64; 3], t: [[f64; 3]; 3]) -> [f64; 3] {
    let mut inv = [[0.0; 3]; 3];
    inv[0][0] = t[1][1] * t[2][2] - t[1][2] * t[2][1];
    inv[0][1] = -(t[0][1] * t[2][2] - t[0][2] * t[2][1]);
    inv[0][2] = t[0][1] * t[1][2] - t[0][2] * t[1][1];
    inv[1][0] = -(t[1][0] * t[2][2] - t[1][2] * t[2][0]);
    inv[1][1] = t[0][0] * t[2][2] - t[0][2] * t[2][0];
    inv[1][2] = -(t[0][0] * t[1][2] - t[0][2] * t[1][0]);
    inv[2][0] = t[1][0] * t[2][1] - t[1][1] * t[2][0];
    inv[2][1] = -(t[0][0] * t[2][1] - t[0][1] * t[2][0]);
    inv[2][2] = t[0][0] * t[1][1] - t[0][1] * t[1][0];
    let det =
        t[0][0] * t[1][1] * t[2][2] + t[0][1] * t[1][2] * t[2][0] + t[0][2] * t[1][0] * t[2][1]
            - t[0][0] * t[1][2] * t[2][1]
            - t[0][1] * t[1][0] * t[2][2]
            - t[2][0] * t[1][1] * t[0][2];
    if det > 0.0 {
        for row in &mut inv {
            for c in row.iter_mut() {
                *c /= det;
            }
        }
    }
    [0, 1, 2].map(|r| inv[r][0] * l[0] + inv[r][1] * l[1] + inv[r][2] * l[2])
}

impl crate::engine::sim::Simulation {
    /// Each `fix momentum` takes its group's mass at the run's setup (LIGGGHTS's `init`).
    pub(crate) fn setup_momentum(&mut self) {
        for f in &mut self.fixes {
            if let FixKind::Momentum(m) = &mut f.kind {
                m.mass = Momentum::group_mass(&self.particles, f.group);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_and_angular_momentum_vanish() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0, 0.0, 0.0], 0.1, 1000.0);
        p.push(2, 1, [1.0, 0.0, 0.0], 0.1, 1000.0);
        p.push(3, 1, [0.0, 1.0, 0.5], 0.2, 1000.0);
        p.v = vec![[1.0, 0.5, 0.0], [0.0, 2.0, 1.0], [0.3, 0.0, -1.0]];
        let mut m = Momentum {
            every: 1,
            linear: Some([true; 3]),
            angular: true,
            mass: 0.0,
        };
        m.mass = Momentum::group_mass(&p, 1);
        m.apply(&mut p, 1, &Domain::default());
        let mom: f64 = (0..3)
            .map(|d| (0..3).map(|i| p.mass[i] * p.v[i][d]).sum::<f64>().abs())
            .sum();
        assert!(mom < 1e-12, "{mom}");
    }
}
