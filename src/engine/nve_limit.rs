//! `fix nve` and `fix nve/limit`: velocity Verlet of positions and velocities alone
//! (angular velocities are left as they are), in LIGGGHTS's order of operations;
//! `nve/limit` caps each particle's speed after every half-kick.

use crate::engine::particles::Particles;

/// `fix nve`: half-kick v with the force, then drift x by a full step (`initial_integrate`).
pub fn initial_integrate(p: &mut Particles, group: u32, dt: f64) {
    let dtf = 0.5 * dt;
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            let dtfm = dtf / p.mass[i];
            for d in 0..3 {
                p.v[i][d] += dtfm * p.f[i][d];
            }
            for d in 0..3 {
                p.x[i][d] += dt * p.v[i][d];
            }
        }
    }
}

/// `fix nve`: the second half-kick (`final_integrate`).
pub fn final_integrate(p: &mut Particles, group: u32, dt: f64) {
    let dtf = 0.5 * dt;
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            let dtfm = dtf / p.mass[i];
            for d in 0..3 {
                p.v[i][d] += dtfm * p.f[i][d];
            }
        }
    }
}

/// `fix nve/limit absolute|radius_ratio XLIMIT`.
#[derive(Debug, Clone, PartialEq)]
pub struct NveLimit {
    /// The largest distance a particle may move in one step (length), or with
    /// `radius_ratio` that distance over the particle's radius (a pure number).
    pub xlimit: f64,
    /// `radius_ratio`: the limit scales with each particle's radius.
    pub relative: bool,
    /// Speeds capped since the run began (f_ID).
    pub count: i64,
}

impl NveLimit {
    /// Cap particle `i`'s speed at xlimit / dt (times its radius with `radius_ratio`).
    #[inline]
    fn limit(&mut self, p: &mut Particles, i: usize, vlimitsq: f64) {
        let v = p.v[i];
        let vsq = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        let cap = if self.relative {
            vlimitsq * (p.radius[i] * p.radius[i])
        } else {
            vlimitsq
        };
        if vsq > cap {
            self.count += 1;
            let scale = (cap / vsq).sqrt();
            for d in 0..3 {
                p.v[i][d] *= scale;
            }
        }
    }

    /// Half-kick, cap, drift (`initial_integrate`).
    pub fn initial_integrate(&mut self, p: &mut Particles, group: u32, dt: f64) {
        self.kick_and_cap(p, group, dt, true);
    }

    /// Half-kick and cap (`final_integrate`).
    pub fn final_integrate(&mut self, p: &mut Particles, group: u32, dt: f64) {
        self.kick_and_cap(p, group, dt, false);
    }

    /// Half-kick v, cap the speed and, with `drift`, move x a full step `dt` (time).
    fn kick_and_cap(&mut self, p: &mut Particles, group: u32, dt: f64, drift: bool) {
        let dtf = 0.5 * dt;
        let vlimitsq = (self.xlimit / dt) * (self.xlimit / dt);
        for i in 0..p.len() {
            if p.mask[i] & group != 0 {
                let dtfm = dtf / p.mass[i];
                for d in 0..3 {
                    p.v[i][d] += dtfm * p.f[i][d];
                }
                self.limit(p, i, vlimitsq);
                if drift {
                    for d in 0..3 {
                        p.x[i][d] += dt * p.v[i][d];
                    }
                }
            }
        }
    }
}

impl crate::engine::sim::Simulation {
    /// Each `fix nve/limit` counts capped speeds from the start of a run (LIGGGHTS's `init`).
    pub(crate) fn setup_nve_limit(&mut self) {
        for f in &mut self.fixes {
            if let crate::engine::fixes::FixKind::NveLimit(n) = &mut f.kind {
                n.count = 0;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speeds_are_capped_and_counted() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0, 0.0, 0.0], 0.1, 1000.0);
        p.push(2, 1, [1.0, 0.0, 0.0], 0.1, 1000.0);
        p.v = vec![[3.0, 4.0, 0.0], [0.1, 0.0, 0.0]];
        let mut n = NveLimit {
            xlimit: 1e-3,
            relative: false,
            count: 0,
        };
        n.initial_integrate(&mut p, 1, 1e-3);
        // speed 5 capped at 1: direction kept
        assert!((p.v[0][0] - 0.6).abs() < 1e-12 && (p.v[0][1] - 0.8).abs() < 1e-12);
        assert_eq!(p.v[1], [0.1, 0.0, 0.0]);
        assert!((p.x[0][0] - 0.6e-3).abs() < 1e-15);
        assert_eq!(n.count, 1);
        n.relative = true; // cap 1e-3 / 1e-3 * 0.1 = 0.1
        n.final_integrate(&mut p, 1, 1e-3);
        assert!((p.v[0][0] - 0.06).abs() < 1e-12);
        assert_eq!(n.count, 2);
    }
}
