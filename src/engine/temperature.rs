//! The temperature of the temperature computes (`compute temp`, LIGGGHTS's default
//! `thermo_temp`) with the settings `compute_modify` gives them.

use crate::engine::contact::UnitStyle;
use crate::engine::sim::Simulation;

/// What `compute_modify` sets on one compute.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ComputeSettings {
    /// Degrees of freedom subtracted from dimension * N (`extra`; None: the dimension).
    pub extra: Option<i64>,
    /// Count the group's atoms at every evaluation instead of at each run's setup.
    pub dynamic: bool,
    /// `thermo yes|no` (fix energies in compute pe; granular fixes add none).
    pub thermo: Option<bool>,
    /// Atoms of the group at the last run's setup (the count of a static compute).
    pub setup_count: f64,
}

impl Default for ComputeSettings {
    fn default() -> Self {
        ComputeSettings {
            extra: None,
            dynamic: false,
            thermo: None,
            setup_count: 0.0,
        }
    }
}

/// At a run's setup: temperature computes that are not dynamic count their group's atoms.
pub fn setup_counts(sim: &mut Simulation) {
    for c in &sim.computes {
        if c.style().is_temperature() {
            let n = sim
                .particles
                .mask
                .iter()
                .filter(|&&m| m & c.group != 0)
                .count() as f64;
            let entry = sim.extras.compute_settings.entry(c.id.clone()).or_default();
            entry.setup_count = n;
        }
    }
}

/// LIGGGHTS's temperature of the compute temp `id` of `group` (temperature): sum of m v^2
/// over the group, times mvv2e / (dof kB) with dof = dimension * N - extra (0 when dof is
/// not positive).
pub fn temperature(sim: &Simulation, id: &str, group: u32) -> f64 {
    let (t, dof, boltz) = temperature_parts(sim, id, group);
    let tfactor = if dof > 0.0 { 1.0 / (dof * boltz) } else { 0.0 };
    t * tfactor
}

/// The parts of the temperature of the compute temp `id` of `group`: sum of m v^2 over the
/// group (energy), the degrees of freedom and LIGGGHTS's Boltzmann constant (energy per
/// temperature).
pub fn temperature_parts(sim: &Simulation, id: &str, group: u32) -> (f64, f64, f64) {
    let p = &sim.particles;
    let mut t = 0.0;
    let mut n = 0usize;
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            let v = p.v[i];
            t += (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * p.mass[i];
            n += 1;
        }
    }
    let s = sim
        .extras
        .compute_settings
        .get(id)
        .copied()
        .unwrap_or_default();
    let natoms = if s.dynamic { n as f64 } else { s.setup_count };
    let dimension = sim.dimension as f64;
    let mut dof = dimension * natoms;
    dof -= s.extra.map_or(dimension, |e| e as f64);
    // LIGGGHTS's Boltzmann constants (energy per temperature) of its si and cgs units
    let boltz = match sim.units {
        UnitStyle::Si => 1.3806504e-23,
        UnitStyle::Cgs => 1.3806504e-16,
        // lj (the only other style a box can be made in): kB = 1
        UnitStyle::Other => 1.0,
    };
    (t, dof, boltz)
}
