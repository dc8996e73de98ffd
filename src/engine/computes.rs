//! Computes (`compute ID group style`): global quantities evaluated on demand for thermo
//! output, formulas and dumps, with LIGGGHTS's arithmetic.

use crate::engine::domain::Domain;
use crate::engine::error::EngineError;
use crate::engine::integrate::SPHERE_INERTIA;
use crate::engine::particles::Particles;
use crate::engine::sim::{Simulation, VariableSource};
pub use crate::state::local_field::LocalField;

mod style;
pub use style::{ComputeAt, ComputeStyle};

/// What a compute calculates: a module style, or one of the styles still dispatched by kind.
#[derive(Debug)]
pub enum ComputeKind {
    /// `temp`: temperature of the group (temperature; see `commands::compute_modify`).
    Temp,
    /// `pair/gran/local`: one row per touching pair with the selected fields.
    PairGranLocal(Vec<LocalField>),
    /// `wall/gran/local`: one row per particle-mesh contact of the mesh wall fix with this
    /// index, with the selected fields.
    WallGranLocal {
        /// The fields, in LIGGGHTS's column order.
        fields: Vec<LocalField>,
        /// ID of the mesh wall fix.
        wall: String,
    },
    /// `rdf Nbin [itype jtype ...]`: g(r) and coord(r) per type pair, a global array.
    Rdf(Box<crate::engine::rdf::Rdf>),
    /// `slice`: every Nskip-th element of a global vector or array column.
    Slice(Box<crate::engine::analysis_computes::Slice>),
    /// `pressure`: kinetic and pair-virial pressure (pressure), scalar and tensor.
    Pressure(Box<crate::engine::analysis_computes::Pressure>),
    /// `property/local` of neighbour or pair inputs (patom1, ntype2, ...): LIGGGHTS 3.8.0's
    /// granular pair styles have no `single()`, so a run refuses it at init.
    PropertyLocal,
    /// A style written as a module (see [`ComputeStyle`]): its hooks give its values.
    Style(Box<dyn ComputeStyle>),
}

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
    /// What it calculates.
    pub kind: ComputeKind,
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

/// The three values of one of a local compute's force or torque fields: the force (or
/// torque) on the particle, or its part along the unit `normal`, or the rest.
fn force_torque(field: LocalField, f: [f64; 3], t: [f64; 3], normal: [f64; 3]) -> [f64; 3] {
    use crate::engine::contact::split;
    match field {
        LocalField::Force => f,
        LocalField::ForceNormal => split(f, normal).0,
        LocalField::ForceTangential => split(f, normal).1,
        LocalField::Torque => t,
        LocalField::TorqueNormal => split(t, normal).0,
        LocalField::TorqueTangential => split(t, normal).1,
        other => unreachable!("{other:?} is not a force or torque field"),
    }
}

/// Compute styles regolith evaluates.
pub const STYLES: &[&str] = &[
    "com",
    "pair/gran/local",
    "wall/gran/local",
    "contact/atom",
    "coord/atom",
    "displace/atom",
    "erotate/sphere/atom",
    "msd",
    "reduce/region",
    "erotate",
    "erotate/sphere",
    "ke",
    "ke/atom",
    "gyration",
    "pe",
    "pe/atom",
    "pressure",
    "property/local",
    "slice",
    "property/atom",
    "rdf",
    "reduce",
    "stress/atom",
    "temp",
];

impl Compute {
    /// What the value hooks of a module style are told about this compute.
    fn at<'a>(&'a self, sim: &'a Simulation) -> ComputeAt<'a> {
        ComputeAt {
            sim,
            id: &self.id,
            group: self.group,
        }
    }

    /// The module style of the compute (None: a style still dispatched by kind).
    pub fn style(&self) -> Option<&dyn ComputeStyle> {
        match &self.kind {
            ComputeKind::Style(s) => Some(s.as_ref()),
            _ => None,
        }
    }

    /// Number of per-atom values per particle (0 if the compute is not per-atom).
    pub fn per_atom_columns(&self) -> usize {
        match &self.kind {
            ComputeKind::Style(s) => s.per_atom_columns(),
            _ => 0,
        }
    }

    /// True for computes with a global vector (`c_ID[N]` in thermo and formulas).
    pub fn vector_len(&self) -> usize {
        match &self.kind {
            ComputeKind::Style(s) => s.vector_len(),
            kind => crate::engine::analysis_computes::vector_len(kind),
        }
    }

    /// The compute's global scalar.
    pub fn scalar(
        &self,
        sim: &Simulation,
        vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        Ok(match &self.kind {
            ComputeKind::Temp => crate::engine::temperature::temperature(sim, self),
            ComputeKind::Pressure(_) => crate::engine::analysis_computes::scalar(self, sim, vars)?,
            ComputeKind::Style(s) if s.has_scalar() => s.scalar(&self.at(sim), vars)?,
            _ => {
                return Err(format!(
                    "Compute {} ({}) does not calculate a scalar",
                    self.id, self.style
                )
                .into())
            }
        })
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
        match &self.kind {
            ComputeKind::Style(s) => s.vector(&self.at(sim), index, vars),
            _ => crate::engine::analysis_computes::vector(self, index, sim, vars),
        }
    }

    /// Rows of a local compute: (columns per row, values row-major).
    pub fn local(&self, sim: &Simulation) -> Result<(usize, Vec<f64>), EngineError> {
        if let ComputeKind::WallGranLocal { fields, wall } = &self.kind {
            return self.wall_local(sim, fields, wall);
        }
        let ComputeKind::PairGranLocal(fields) = &self.kind else {
            return Err(format!(
                "Compute {} ({}) does not calculate local values",
                self.id, self.style
            )
            .into());
        };
        let Some(pair) = sim.pair.as_ref() else {
            return Err("compute pair/gran/local needs a granular pair style".into());
        };
        let width = pair.history_width();
        let flips = pair.history_flips();
        let ncols: usize = fields.iter().map(|f| f.width(width)).sum();
        let p = &sim.particles;
        let pairs = &sim.list.pairs;
        let mut out = Vec::new();
        // rows in LIGGGHTS's order: by the reporting atom, then its partners in bin order
        // (positions of the last list build, ghosts of periodic partners beyond the box)
        let order = crate::engine::neighbor::BinOrder::sized(
            sim.domain.lo,
            sim.domain.hi,
            sim.neighbor.cutneighmax,
            sim.extras.neigh_binsize,
        );
        let built = sim.list.built_positions();
        // (reporting atom, partner's bin, partner) and the row's index in `out`
        type RowKey = (usize, [i64; 3], usize);
        let mut keyed: Vec<(RowKey, usize)> = Vec::new();
        for (k, fi, ti, fj, tj) in pair.contacts(
            p,
            pairs,
            &sim.history,
            sim.dt,
            (&sim.force_time_state.0, &sim.force_time_state.1),
        ) {
            let pr = &pairs[k];
            let (mut i, mut j) = (pr.i as usize, pr.j as usize);
            if p.mask[i] & self.group == 0 || p.mask[j] & self.group == 0 {
                continue;
            }
            let periodic = pr.shift != [0.0; 3];
            // across a periodic face LIGGGHTS reports the pair from the atom with the
            // larger ID (its ghost partner carries the shift)
            let mut shift = pr.shift;
            let (mut f, mut t, mut sign) = (fi, ti, 1.0);
            if periodic && p.id[i] < p.id[j] {
                std::mem::swap(&mut i, &mut j);
                shift = shift.map(|v| -v);
                f = fj;
                t = tj;
                sign = -1.0;
            }
            let xb = built.get(j).copied().unwrap_or(p.x[j]);
            keyed.push((
                (i, order.bin([0, 1, 2].map(|d| xb[d] + shift[d])), j),
                out.len(),
            ));
            let xi = p.x[i];
            let xj_ghost = [
                p.x[j][0] + shift[0],
                p.x[j][1] + shift[1],
                p.x[j][2] + shift[2],
            ];
            // the unit vector from i to j, along which force and torque are split
            let mut normal = [
                xj_ghost[0] - xi[0],
                xj_ghost[1] - xi[1],
                xj_ghost[2] - xi[2],
            ];
            let len =
                (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
            if len > 0.0 {
                normal = normal.map(|c| c / len);
            }
            let (ri, rj) = (p.radius[i], p.radius[j]);
            let del = [
                xi[0] - xj_ghost[0],
                xi[1] - xj_ghost[1],
                xi[2] - xj_ghost[2],
            ];
            let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
            let r = rsq.sqrt();
            for field in fields {
                match field {
                    LocalField::Pos => {
                        out.extend_from_slice(&xi);
                        out.extend_from_slice(&p.x[j]);
                    }
                    LocalField::Vel => {
                        out.extend_from_slice(&p.v[i]);
                        out.extend_from_slice(&p.v[j]);
                    }
                    LocalField::Id => {
                        out.push(p.id[i] as f64);
                        out.push(p.id[j] as f64);
                        out.push(if periodic { 1.0 } else { 0.0 });
                    }
                    LocalField::Force
                    | LocalField::ForceNormal
                    | LocalField::ForceTangential
                    | LocalField::Torque
                    | LocalField::TorqueNormal
                    | LocalField::TorqueTangential => {
                        out.extend_from_slice(&force_torque(*field, f, t, normal))
                    }
                    LocalField::History => out.extend(
                        sim.history[k * width..(k + 1) * width]
                            .iter()
                            .zip(&flips)
                            .map(|(h, &f)| if f { h * sign } else { *h }),
                    ),
                    LocalField::ContactArea => out.push(
                        -std::f64::consts::PI / 4.0
                            * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj))
                            / rsq,
                    ),
                    LocalField::Delta => out.push(ri + rj - r),
                    LocalField::HeatFlux => out.push(0.0),
                    LocalField::ContactPoint => {
                        for d in 0..3 {
                            out.push((xi[d] * rj + xj_ghost[d] * ri) / (ri + rj));
                        }
                    }
                }
            }
        }
        keyed.sort_by_key(|(key, _)| *key);
        let mut sorted = Vec::with_capacity(out.len());
        for (_, at) in keyed {
            sorted.extend_from_slice(&out[at..at + ncols]);
        }
        Ok((ncols, sorted))
    }

    /// Rows of `compute wall/gran/local`: the mesh wall's contacts re-evaluated now, as
    /// LIGGGHTS re-runs the wall's loop at output (docs/notes/wall_gran_local.md).
    fn wall_local(
        &self,
        sim: &Simulation,
        fields: &[LocalField],
        wall: &str,
    ) -> Result<(usize, Vec<f64>), EngineError> {
        let k = sim
            .fixes
            .iter()
            .position(|f| f.id == wall)
            .ok_or_else(|| format!("Compute wall/gran/local: wall fix {wall} is gone"))?;
        let width = match &sim.fixes[k].kind {
            crate::engine::fixes::FixKind::MeshWall(w) => w.history_width(),
            _ => 0,
        };
        let ncols: usize = fields.iter().map(|f| f.width(width)).sum();
        let p = &sim.particles;
        let mut out = Vec::new();
        // LIGGGHTS's row order: mesh, triangle, then the triangle's neighbour list, which
        // walks bins x-outermost, z-innermost (positions of the last list build) and atoms
        // in index order within a bin
        let mut contacts = crate::engine::fixes::mesh_wall_contacts(&sim.fixes, k, p, sim.dt);
        let order = crate::engine::neighbor::BinOrder::sized(
            sim.domain.lo,
            sim.domain.hi,
            sim.neighbor.cutneighmax,
            sim.extras.neigh_binsize,
        );
        let built = sim.list.built_positions();
        contacts.sort_by_cached_key(|c| {
            let x = built.get(c.particle).copied().unwrap_or(p.x[c.particle]);
            let b = order.bin(x);
            (c.mesh, c.tri, b[2], b[1], b[0], c.particle)
        });
        for c in contacts {
            let i = c.particle;
            if p.mask[i] & self.group == 0 {
                continue;
            }
            let (f, t) = (c.out.f, c.out.t);
            let normal = c.out.en.map(|x| -x);
            let radius = p.radius[i];
            let r = radius - (-c.gap);
            let rsq = r * r;
            for field in fields {
                match field {
                    LocalField::Pos => {
                        let dvec = c.to_wall.map(|x| -x);
                        out.extend((0..3).map(|d| p.x[i][d] - dvec[d]));
                        out.extend_from_slice(&p.x[i]);
                    }
                    LocalField::Vel => {
                        out.extend_from_slice(&c.v_wall);
                        out.extend_from_slice(&p.v[i]);
                    }
                    LocalField::Id => {
                        out.push(c.mesh as f64);
                        out.push(c.tri as f64);
                        out.push(p.id[i] as f64);
                    }
                    LocalField::Force
                    | LocalField::ForceNormal
                    | LocalField::ForceTangential
                    | LocalField::Torque
                    | LocalField::TorqueNormal
                    | LocalField::TorqueTangential => {
                        out.extend_from_slice(&force_torque(*field, f, t, normal))
                    }
                    LocalField::History => out.extend_from_slice(&c.hist[..width]),
                    LocalField::ContactArea => {
                        out.push((radius * radius - rsq) * std::f64::consts::PI)
                    }
                    LocalField::Delta => out.push(radius - rsq.sqrt()),
                    // walls fill neither (LIGGGHTS leaves them as allocated: zero)
                    LocalField::HeatFlux => out.push(0.0),
                    LocalField::ContactPoint => out.extend_from_slice(&[0.0; 3]),
                }
            }
        }
        Ok((ncols, out))
    }

    /// The compute's per-atom values (for dumps and `compute reduce`).
    pub fn per_atom(
        &self,
        sim: &Simulation,
        vars: &mut dyn VariableSource,
    ) -> Result<PerAtom, EngineError> {
        let columns = self.per_atom_columns();
        let mut values = vec![0.0; sim.particles.len() * columns];
        match &self.kind {
            ComputeKind::Style(s) if columns > 0 => s.per_atom(&self.at(sim), &mut values, vars)?,
            _ => {
                return Err(format!(
                    "Compute {} ({}) does not calculate per-atom values",
                    self.id, self.style
                )
                .into())
            }
        }
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
    let mut cm = [0.0; 3];
    let mut mass = 0.0;
    for i in 0..p.len() {
        if p.mask[i] & group == 0 {
            continue;
        }
        let m = p.mass[i];
        for (d, c) in cm.iter_mut().enumerate() {
            let xu = p.x[i][d] + p.image[i][d] as f64 * domain.length(d);
            *c += xu * m;
        }
        mass += m;
    }
    if mass > 0.0 {
        for c in &mut cm {
            *c /= mass;
        }
    }
    cm
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
