//! Computes (`compute ID group style`): global quantities evaluated on demand for thermo
//! output, formulas and dumps, with LIGGGHTS's arithmetic.

use crate::engine::integrate::SPHERE_INERTIA;
use crate::engine::particles::Particles;

/// What a compute calculates.
#[derive(Debug, Clone, PartialEq)]
pub enum ComputeKind {
    /// `erotate/sphere`: rotational kinetic energy, 0.5 I w^2 summed (energy).
    ErotateSphere,
    /// `ke`: translational kinetic energy, 0.5 m v^2 summed (energy).
    Ke,
}

/// One defined compute.
#[derive(Debug, Clone, PartialEq)]
pub struct Compute {
    /// Its ID.
    pub id: String,
    /// Its style name.
    pub style: String,
    /// Group bits.
    pub group: u32,
    /// What it calculates.
    pub kind: ComputeKind,
}

/// Translational kinetic energy of the particles in `group`, summed as LIGGGHTS's
/// `compute ke` does: 0.5 * sum m v^2 (energy).
pub fn kinetic_energy(p: &Particles, group: u32) -> f64 {
    let mut sum = 0.0;
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            let v = p.v[i];
            sum += p.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        }
    }
    sum * 0.5
}

/// Compute styles regolith evaluates.
pub const STYLES: &[&str] = &["erotate/sphere", "ke"];

impl Compute {
    /// The compute's global scalar.
    pub fn scalar(&self, p: &Particles) -> Result<f64, String> {
        Ok(match self.kind {
            ComputeKind::ErotateSphere => {
                let mut sum = 0.0;
                for i in 0..p.len() {
                    if p.mask[i] & self.group != 0 {
                        let w = p.omega[i];
                        sum += (w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
                            * p.radius[i]
                            * p.radius[i]
                            * p.mass[i];
                    }
                }
                sum * (0.5 * 1.0 * SPHERE_INERTIA)
            }
            ComputeKind::Ke => kinetic_energy(p, self.group),
        })
    }

    /// Element `index` (1-based) of the compute's global vector.
    pub fn vector(&self, index: usize, _p: &Particles) -> Result<f64, String> {
        Err(format!(
            "Compute {} ({}) has no global vector; c_{}[{index}] is invalid",
            self.id, self.style, self.id
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energies() {
        let mut p = Particles::default();
        p.push(
            1,
            1,
            [0.0; 3],
            0.5,
            3.0 / (4.0 * std::f64::consts::PI * 0.125),
        );
        p.v[0] = [3.0, 4.0, 0.0];
        p.omega[0] = [0.0, 0.0, 2.0];
        let c = |kind| Compute {
            id: "c".into(),
            style: "x".into(),
            group: 1,
            kind,
        };
        assert!((c(ComputeKind::Ke).scalar(&p).unwrap() - 0.5 * 25.0).abs() < 1e-12);
        // 0.5 * 0.4 m r^2 w^2 with m = 1
        assert!(
            (c(ComputeKind::ErotateSphere).scalar(&p).unwrap() - 0.5 * 0.4 * 0.25 * 4.0).abs()
                < 1e-12
        );
    }
}
