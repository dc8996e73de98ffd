//! `compute msd` and `compute displace/atom`: displacements of the group's particles from
//! where they were (unwrapped) when the compute was defined, as LIGGGHTS 3.8.0 computes them.

use std::collections::HashMap;

use crate::engine::domain::Domain;
use crate::engine::particles::Particles;

/// The unwrapped positions (length) of a group's particles when a compute was defined.
#[derive(Debug, Clone, PartialEq)]
pub struct Origins {
    /// Position by atom ID (relative to the centre of mass with `com yes`); atoms not in
    /// the group then (or inserted later) start at 0, as LIGGGHTS's stored array does.
    pub by_id: HashMap<i64, [f64; 3]>,
    /// `msd com yes`: displacements relative to the group's centre of mass.
    pub com: bool,
    /// Group members at the last run's start (the mean's divisor).
    pub count: usize,
    /// Group mass at the last run's start (mass).
    pub mass: f64,
}

/// Unwrapped position of particle `i` (length).
#[inline]
fn unwrapped(p: &Particles, domain: &Domain, i: usize) -> [f64; 3] {
    [0, 1, 2].map(|d| p.x[i][d] + p.image[i][d] as f64 * domain.length(d))
}

/// The group's count and mass.
fn count_mass(p: &Particles, group: u32) -> (usize, f64) {
    (0..p.len())
        .filter(|&i| p.mask[i] & group != 0)
        .fold((0, 0.0), |(n, m), i| (n + 1, m + p.mass[i]))
}

/// The group's centre of mass (unwrapped, length) divided by `mass` (LIGGGHTS's `xcm`).
fn xcm(p: &Particles, domain: &Domain, group: u32, mass: f64) -> [f64; 3] {
    let mut cm = [0.0; 3];
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            let xu = unwrapped(p, domain, i);
            for d in 0..3 {
                cm[d] += xu[d] * p.mass[i];
            }
        }
    }
    if mass > 0.0 {
        cm = cm.map(|c| c / mass);
    }
    cm
}

impl Origins {
    /// Record the group's unwrapped positions now.
    pub fn new(p: &Particles, domain: &Domain, group: u32, com: bool) -> Origins {
        let (count, mass) = count_mass(p, group);
        let cm = if com {
            xcm(p, domain, group, mass)
        } else {
            [0.0; 3]
        };
        let by_id = (0..p.len())
            .filter(|&i| p.mask[i] & group != 0)
            .map(|i| {
                let xu = unwrapped(p, domain, i);
                (p.id[i], [0, 1, 2].map(|d| xu[d] - cm[d]))
            })
            .collect();
        Origins {
            by_id,
            com,
            count,
            mass,
        }
    }

    /// LIGGGHTS's `init`: the group's count and mass at the start of a run.
    pub fn init(&mut self, p: &Particles, group: u32) {
        (self.count, self.mass) = count_mass(p, group);
    }

    /// Displacement of group member `i` from its origin, less `cm` (length).
    #[inline]
    fn delta(&self, p: &Particles, domain: &Domain, i: usize, cm: [f64; 3]) -> [f64; 3] {
        let o = self.by_id.get(&p.id[i]).copied().unwrap_or([0.0; 3]);
        [0, 1, 2].map(|d| p.x[i][d] + p.image[i][d] as f64 * domain.length(d) - cm[d] - o[d])
    }

    /// `compute msd`: mean squared displacement along x, y, z and in total (area).
    pub fn msd(&self, p: &Particles, domain: &Domain, group: u32) -> [f64; 4] {
        let cm = if self.com {
            xcm(p, domain, group, self.mass)
        } else {
            [0.0; 3]
        };
        let mut msd = [0.0; 4];
        for i in 0..p.len() {
            if p.mask[i] & group != 0 {
                let [dx, dy, dz] = self.delta(p, domain, i, cm);
                msd[0] += dx * dx;
                msd[1] += dy * dy;
                msd[2] += dz * dz;
                msd[3] += dx * dx + dy * dy + dz * dz;
            }
        }
        if self.count > 0 {
            msd = msd.map(|m| m / self.count as f64);
        }
        msd
    }

    /// `compute displace/atom`: dx, dy, dz and the distance per particle (length; 0
    /// outside the group), row-major.
    pub fn displace(&self, p: &Particles, domain: &Domain, group: u32, out: &mut [f64]) {
        for i in 0..p.len() {
            let row = &mut out[4 * i..4 * i + 4];
            if p.mask[i] & group != 0 {
                let [dx, dy, dz] = self.delta(p, domain, i, [0.0; 3]);
                row.copy_from_slice(&[dx, dy, dz, (dx * dx + dy * dy + dz * dz).sqrt()]);
            } else {
                row.fill(0.0);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn displacements_from_the_origins() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0, 0.0, 0.0], 0.1, 1000.0);
        p.push(2, 1, [1.0, 0.0, 0.0], 0.1, 1000.0);
        let domain = Domain::default();
        let o = Origins::new(&p, &domain, 1, false);
        p.x[0] = [3.0, 4.0, 0.0];
        let msd = o.msd(&p, &domain, 1);
        assert_eq!(msd, [4.5, 8.0, 0.0, 12.5]);
        let mut out = vec![0.0; 8];
        o.displace(&p, &domain, 1, &mut out);
        assert_eq!(out, vec![3.0, 4.0, 0.0, 5.0, 0.0, 0.0, 0.0, 0.0]);
        // with com yes a rigid shift of the whole group is no displacement
        let o = Origins::new(&p, &domain, 1, true);
        p.x[0][2] += 2.0;
        p.x[1][2] += 2.0;
        assert_eq!(o.msd(&p, &domain, 1), [0.0; 4]);
    }
}
