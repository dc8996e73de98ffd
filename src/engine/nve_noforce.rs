//! `fix ID GROUP nve/noforce`: positions follow the velocities (x += dt v), which no force
//! changes (LIGGGHTS's initial_integrate; there is no final step).

use crate::engine::particles::Particles;

/// Advance the group's positions by one step.
pub fn initial_integrate(p: &mut Particles, group: u32, dt: f64) {
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            for d in 0..3 {
                p.x[i][d] += dt * p.v[i][d];
            }
        }
    }
}
