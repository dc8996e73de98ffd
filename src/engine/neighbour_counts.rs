//! Per-atom neighbour counts: `compute contact/atom` (touching partners) and `compute
//! coord/atom` (partners within a cutoff, by type), counted over the pairs LIGGGHTS's lists
//! hold (LIGGGHTS 3.8.0's compute_contact_atom.cpp and compute_coord_atom.cpp).

use crate::engine::neighbor::NeighborList;
use crate::engine::sim::Simulation;

/// `compute ID GROUP coord/atom cutoff [typeN ...] [mix yes|no]`.
#[derive(Debug, Clone, PartialEq)]
pub struct CoordAtom {
    /// Partners closer than this count (length).
    pub cutoff: f64,
    /// One column per inclusive type range (lo, hi) of the partner.
    pub ranges: Vec<(u32, u32)>,
    /// `mix yes`: partners of the atom's own type are left out.
    pub mix: bool,
}

/// Whether `neigh_modify exclude` keeps particles `i` and `j` out of every list.
pub(crate) fn excluded(sim: &Simulation, i: usize, j: usize) -> bool {
    let (p, n) = (&sim.particles, &sim.neighbor);
    let (ti, tj) = (p.kind[i], p.kind[j]);
    let (mi, mj) = (p.mask[i], p.mask[j]);
    n.exclude_types
        .iter()
        .any(|&(a, b)| (ti == a && tj == b) || (ti == b && tj == a))
        || n.exclude_groups
            .iter()
            .any(|&(a, b)| (mi & a != 0 && mj & b != 0) || (mi & b != 0 && mj & a != 0))
}

/// Pairs of a fresh list reaching `reach[i] + reach[j] + skin` (length), without the
/// excluded ones.
pub(crate) fn fresh_pairs(sim: &Simulation, reach: &[f64], skin: f64) -> NeighborList {
    let mut list = NeighborList::default();
    list.build(&sim.particles.x, reach, skin, &sim.domain, None);
    list.retain(|pair| !excluded(sim, pair.i as usize, pair.j as usize));
    list
}

/// Squared distance of a listed pair (its periodic image).
pub(crate) fn distance_sq(sim: &Simulation, i: usize, j: usize, shift: [f64; 3]) -> f64 {
    let x = &sim.particles.x;
    let mut rsq = 0.0;
    for d in 0..3 {
        let del = x[i][d] - (x[j][d] + shift[d]);
        rsq += del * del;
    }
    rsq
}

/// `contact/atom`: per particle, the partners within the sum of radii plus `skin` (length).
/// LIGGGHTS's half list (newton off) holds a pair once, from the lower index, and a pair
/// across a periodic face from both sides; a pair counts for both only from a side whose
/// atom is in `group`.
pub fn contact_counts(sim: &Simulation, group: u32, skin: f64, out: &mut [f64]) {
    let p = &sim.particles;
    let list = fresh_pairs(sim, &p.radius, sim.neighbor.skin);
    for pair in &list.pairs {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let radsum = p.radius[i] + p.radius[j] + skin;
        if distance_sq(sim, i, j, pair.shift) > radsum * radsum {
            continue;
        }
        if pair.shift != [0.0; 3] {
            // each side's own copy adds to its atom only (the ghost's count is dropped)
            for k in [i, j] {
                if p.mask[k] & group != 0 {
                    out[k] += 1.0;
                }
            }
        } else if p.mask[i.min(j)] & group != 0 {
            out[i] += 1.0;
            out[j] += 1.0;
        }
    }
}

impl CoordAtom {
    /// Number of per-atom columns (one per type range).
    pub fn columns(&self) -> usize {
        self.ranges.len()
    }

    /// The largest radius of each atom type among the particles and the particle
    /// templates (length; index 0 unused), as LIGGGHTS's pair gran sizes its cutoffs.
    pub(crate) fn type_radii(sim: &Simulation) -> Vec<f64> {
        let mut radii = vec![0.0f64; sim.ntypes as usize + 1];
        let p = &sim.particles;
        for i in 0..p.len() {
            if let Some(r) = radii.get_mut(p.kind[i] as usize) {
                *r = r.max(p.radius[i]);
            }
        }
        for f in &sim.fixes {
            if let Some(t) = f.kind.template() {
                if let Some(r) = radii.get_mut(t.atom_type as usize) {
                    *r = r.max(t.radius);
                }
            }
        }
        radii
    }

    /// Counts per particle and range, row-major into `out` (`columns()` per particle);
    /// zero for particles outside `group`. LIGGGHTS counts over a full list, so each pair
    /// within the cutoff (strictly) and within its type pair's neighbour cutoff counts for
    /// both particles.
    pub fn counts(&self, sim: &Simulation, group: u32, out: &mut [f64]) {
        let p = &sim.particles;
        let ncol = self.columns();
        let radii = Self::type_radii(sim);
        let (factor, skin) = (sim.contact_factor(), sim.neighbor.skin);
        let cutsq = self.cutoff * self.cutoff;
        // every pair closer than the cutoff (a little beyond it, then tested exactly)
        let reach = vec![0.5 * self.cutoff; p.len()];
        let list = fresh_pairs(sim, &reach, 1e-6 * self.cutoff);
        for pair in &list.pairs {
            let (i, j) = (pair.i as usize, pair.j as usize);
            let rsq = distance_sq(sim, i, j, pair.shift);
            let (ti, tj) = (p.kind[i], p.kind[j]);
            let cutneigh = (radii[ti as usize] + radii[tj as usize]) * factor + skin;
            if rsq >= cutsq || rsq > cutneigh * cutneigh {
                continue;
            }
            for (a, b) in [(i, j), (j, i)] {
                if p.mask[a] & group == 0 || (self.mix && p.kind[a] == p.kind[b]) {
                    continue;
                }
                let tb = p.kind[b];
                for (m, &(lo, hi)) in self.ranges.iter().enumerate() {
                    if tb >= lo && tb <= hi {
                        out[a * ncol + m] += 1.0;
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::state::domain::Boundary;

    /// Four particles of radius 0.5 on the x axis of a box periodic in x (length 4): at
    /// 0.5, 1.5, 2.4 and 3.45 (types 1, 2, 1, 2); the last touches the first across the face.
    fn row() -> Simulation {
        let mut sim = Simulation::default();
        sim.domain.create([0.0; 3], [4.0, 4.0, 4.0]);
        sim.domain.boundary = [
            [Boundary::Periodic; 2],
            [Boundary::Fixed; 2],
            [Boundary::Fixed; 2],
        ];
        sim.ntypes = 2;
        sim.neighbor.skin = 0.2;
        for (k, x) in [0.5, 1.5, 2.4, 3.45].into_iter().enumerate() {
            sim.particles
                .push(k as i64 + 1, 1 + k as u32 % 2, [x, 2.0, 2.0], 0.5, 1.0);
        }
        sim
    }

    #[test]
    fn contacts_and_coordination_as_liggghts_counts_them() {
        let mut sim = row();
        let mut out = vec![0.0; 4];
        contact_counts(&sim, 1, 0.0, &mut out);
        // gaps 0, -0.1 (overlap), 0.05, 0.05 across the face
        assert_eq!(out, [1.0, 2.0, 1.0, 0.0]);
        let mut out = vec![0.0; 4];
        contact_counts(&sim, 1, 0.06, &mut out);
        assert_eq!(out, [2.0, 2.0, 2.0, 2.0]);
        // only particle 1 (index 0) in the group: its pairs count from its side only
        sim.particles.mask = vec![3, 1, 1, 1];
        let mut out = vec![0.0; 4];
        contact_counts(&sim, 2, 0.06, &mut out);
        assert_eq!(out, [2.0, 1.0, 0.0, 0.0]);
        sim.particles.mask = vec![1; 4];
        // partners closer than 1.1, by partner type: all, type 1, type 2
        let coord = CoordAtom {
            cutoff: 1.1,
            ranges: vec![(1, 2), (1, 1), (2, 2)],
            mix: false,
        };
        let mut out = vec![0.0; 12];
        coord.counts(&sim, 1, &mut out);
        assert_eq!(
            out,
            [2.0, 0.0, 2.0, 2.0, 2.0, 0.0, 2.0, 0.0, 2.0, 2.0, 2.0, 0.0]
        );
        let mix = CoordAtom {
            cutoff: 1.1,
            ranges: vec![(1, 2)],
            mix: true,
        };
        let mut out = vec![0.0; 4];
        mix.counts(&sim, 1, &mut out);
        assert_eq!(out, [2.0, 2.0, 2.0, 2.0]);
    }
}
