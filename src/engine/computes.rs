//! Computes (`compute ID group style`): global quantities evaluated on demand for thermo
//! output, formulas and dumps, with LIGGGHTS's arithmetic.

use crate::engine::domain::Domain;
use crate::engine::error::EngineError;
use crate::engine::integrate::SPHERE_INERTIA;
use crate::engine::particles::Particles;
use crate::engine::sim::{Simulation, VariableSource};
pub use crate::state::local_field::LocalField;

mod style;
pub use style::{ComputeAt, ComputeStyle, LocalRows};

/// Per-atom values of a compute: `columns` values per particle, row-major in particle
/// order.
#[derive(Debug, Clone, PartialEq)]
pub struct PerAtom {
    /// Values per particle.
    pub columns: usize,
    /// The values (particle-major).
    pub values: Vec<f64>,
}

impl PerAtom {
    /// The value of column `col` (0-based) for particle `i`.
    pub fn get(&self, i: usize, col: usize) -> f64 {
        self.values[i * self.columns + col]
    }
}

/// One defined compute.
#[derive(Debug)]
pub struct Compute {
    /// Its ID.
    pub id: String,
    /// Its style name.
    pub style: String,
    /// Group bits.
    pub group: u32,
    /// What it calculates: its style's state and hooks.
    pub calc: Box<dyn ComputeStyle>,
}

/// Translational kinetic energy of the particles in `group`, summed as LIGGGHTS's
/// `compute ke` does: 0.5 * sum m v^2 (energy); members of multisphere clumps are left out
/// (their bodies' energy is [`crate::engine::clumps::Clumps::kinetic_energy`]).
pub fn kinetic_energy(p: &Particles, group: u32) -> f64 {
    let tags = crate::engine::clumps::body_tags(p);
    let mut sum = 0.0;
    for i in 0..p.len() {
        if p.mask[i] & group != 0 && !crate::engine::clumps::is_member(tags, i) {
            let v = p.v[i];
            sum += p.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        }
    }
    sum * 0.5
}

/// Rotational kinetic energy of the spheres in `group`, summed as LIGGGHTS's `compute
/// erotate/sphere` does: 0.5 * 0.4 * sum m r^2 w^2 (energy); members of multisphere clumps
/// are left out.
pub fn rotational_energy(p: &Particles, group: u32) -> f64 {
    let tags = crate::engine::clumps::body_tags(p);
    let mut sum = 0.0;
    for i in 0..p.len() {
        if p.mask[i] & group != 0 && !crate::engine::clumps::is_member(tags, i) {
            let w = p.omega[i];
            sum +=
                (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) * p.radius[i] * p.radius[i] * p.mass[i];
        }
    }
    sum * (0.5 * 1.0 * SPHERE_INERTIA)
}

impl Compute {
    /// What the value hooks of a module style are told about this compute.
    fn at<'a>(&'a self, sim: &'a Simulation) -> ComputeAt<'a> {
        ComputeAt {
            sim,
            id: &self.id,
            group: self.group,
        }
    }

    /// The compute's style: its hooks and flags.
    pub fn style(&self) -> &dyn ComputeStyle {
        self.calc.as_ref()
    }

    /// Number of per-atom values per particle (0 if the compute is not per-atom).
    pub fn per_atom_columns(&self) -> usize {
        self.calc.per_atom_columns()
    }

    /// True for computes with a global vector (`c_ID[N]` in thermo and formulas).
    pub fn vector_len(&self) -> usize {
        self.calc.vector_len()
    }

    /// The compute's global scalar.
    pub fn scalar(
        &self,
        sim: &Simulation,
        vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        if !self.calc.has_scalar() {
            return Err(format!(
                "Compute {} ({}) does not calculate a scalar",
                self.id, self.style
            )
            .into());
        }
        self.calc.scalar(&self.at(sim), vars)
    }

    /// Element `index` (1-based) of the compute's global vector.
    pub fn vector(
        &self,
        index: usize,
        sim: &Simulation,
        vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        if index == 0 || index > self.vector_len() {
            return Err(format!(
                "Compute {} ({}) has no global vector element {index}",
                self.id, self.style
            )
            .into());
        }
        self.calc.vector(&self.at(sim), index, vars)
    }

    /// (rows, columns) of the compute's global array, if it has one.
    pub fn array_size(&self) -> Option<(usize, usize)> {
        self.calc.array_size()
    }

    /// The compute's global array, row-major, and its number of columns.
    pub fn global_array(&self, sim: &Simulation) -> Result<(Vec<f64>, usize), EngineError> {
        let Some((_, columns)) = self.calc.array_size() else {
            return Err(format!(
                "Compute {} ({}) does not calculate a global array",
                self.id, self.style
            )
            .into());
        };
        Ok((self.calc.array(&self.at(sim))?, columns))
    }

    /// Rows of a local compute: (columns per row, values row-major).
    pub fn local(&self, sim: &Simulation) -> Result<(usize, Vec<f64>), EngineError> {
        if self.calc.local_rows().is_none() {
            return Err(format!(
                "Compute {} ({}) does not calculate local values",
                self.id, self.style
            )
            .into());
        }
        self.calc.local(&self.at(sim))
    }

    /// The compute's per-atom values (for dumps and `compute reduce`).
    pub fn per_atom(
        &self,
        sim: &Simulation,
        vars: &mut dyn VariableSource,
    ) -> Result<PerAtom, EngineError> {
        let columns = self.per_atom_columns();
        if columns == 0 {
            return Err(format!(
                "Compute {} ({}) does not calculate per-atom values",
                self.id, self.style
            )
            .into());
        }
        let mut values = vec![0.0; sim.particles.len() * columns];
        self.calc.per_atom(&self.at(sim), &mut values, vars)?;
        Ok(PerAtom { columns, values })
    }
}

/// The 0-based column of `c_ID` / `c_ID[N]` of a per-atom compute, with LIGGGHTS's checks.
pub fn column_of(c: &Compute, index: Option<usize>) -> Result<usize, EngineError> {
    let cols = c.per_atom_columns();
    match index {
        _ if cols == 0 => Err(format!(
            "Compute {} ({}) does not calculate per-atom values",
            c.id, c.style
        )
        .into()),
        None if cols == 1 => Ok(0),
        None => Err(format!(
            "Compute {} ({}) calculates a per-atom array: give a column, c_{}[N]",
            c.id, c.style, c.id
        )
        .into()),
        Some(k) if cols == 1 || k == 0 || k > cols => {
            Err(format!("Compute {} ({}) has no per-atom column {k}", c.id, c.style).into())
        }
        Some(k) => Ok(k - 1),
    }
}

/// Centre of mass of `group` with unwrapped positions (length), as LIGGGHTS's `xcm`.
pub fn center_of_mass(p: &Particles, domain: &Domain, group: u32) -> [f64; 3] {
    let (moment, mass) = mass_moment(p, domain, group);
    center_from_moment(moment, mass)
}

/// The first mass moment of `group`, sum of m x with unwrapped positions (mass x length), and
/// the group's mass (mass).
pub fn mass_moment(p: &Particles, domain: &Domain, group: u32) -> ([f64; 3], f64) {
    let mut moment = [0.0; 3];
    let mut mass = 0.0;
    for i in 0..p.len() {
        if p.mask[i] & group == 0 {
            continue;
        }
        let m = p.mass[i];
        for (d, c) in moment.iter_mut().enumerate() {
            let xu = p.x[i][d] + p.image[i][d] as f64 * domain.length(d);
            *c += xu * m;
        }
        mass += m;
    }
    (moment, mass)
}

/// A mass moment divided by `mass` (length), left as it is when `mass` is not positive: LIGGGHTS's
/// `xcm` divides by the mass it is given, which `compute com`/`gyration` take at a run's
/// start (so a group that was empty then gives the raw moment).
pub fn center_from_moment(mut moment: [f64; 3], mass: f64) -> [f64; 3] {
    if mass > 0.0 {
        for c in &mut moment {
            *c /= mass;
        }
    }
    moment
}

/// A per-atom keyword of particle `i` (`x`, `vx`, `fx`, `mass`, `r`, ...).
pub fn atom_keyword(
    p: &crate::engine::particles::Particles,
    name: &str,
    i: usize,
) -> Result<f64, crate::engine::error::EngineError> {
    let axis = |c: u8| (c - b'x') as usize;
    let b = name.as_bytes();
    Ok(match name {
        "id" => p.id[i] as f64,
        "type" => p.kind[i] as f64,
        "mass" => p.mass[i],
        "r" => p.radius[i],
        "density" => p.density[i],
        "x" | "y" | "z" => p.x[i][axis(b[0])],
        "vx" | "vy" | "vz" => p.v[i][axis(b[1])],
        "fx" | "fy" | "fz" => p.f[i][axis(b[1])],
        "omegax" | "omegay" | "omegaz" => p.omega[i][axis(b[5])],
        "tqx" | "tqy" | "tqz" => p.torque[i][axis(b[2])],
        other => {
            return Err(crate::engine::error::EngineError::Unsupported(format!(
                "per-atom keyword {other}"
            )))
        }
    })
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
        assert!((kinetic_energy(&p, 1) - 0.5 * 25.0).abs() < 1e-12);
        // 0.5 * 0.4 m r^2 w^2 with m = 1
        assert!((rotational_energy(&p, 1) - 0.5 * 0.4 * 0.25 * 4.0).abs() < 1e-12);
        assert_eq!(kinetic_energy(&p, 2), 0.0);
    }
}
