//! `compute rdf Nbin [itype jtype ...]`: radial distribution functions g(r) and running
//! coordination numbers of particle pairs, as LIGGGHTS 3.8.0's compute_rdf.cpp counts
//! them over a fresh half neighbour list.

use crate::engine::error::EngineError;
use crate::engine::neighbour_counts::{distance_sq, excluded, fresh_pairs, CoordAtom};
use crate::engine::sim::Simulation;

/// The settings of one `compute rdf`.
#[derive(Debug, Clone, PartialEq)]
pub struct Rdf {
    /// Number of bins between 0 and the pair style's force cutoff.
    pub nbin: usize,
    /// One histogram per inclusive type range pair ((ilo, ihi), (jlo, jhi)).
    pub pairs: Vec<((u32, u32), (u32, u32))>,
}

impl Rdf {
    /// Columns of the global array: r, then g(r) and coord(r) per histogram.
    pub fn columns(&self) -> usize {
        1 + 2 * self.pairs.len()
    }

    /// Histograms (per type pair of the ordered pair (i, j)) that count it.
    fn histograms(&self, ti: u32, tj: u32) -> impl Iterator<Item = usize> + '_ {
        let within = |t: u32, (lo, hi): (u32, u32)| t >= lo && t <= hi;
        self.pairs
            .iter()
            .enumerate()
            .filter(move |(_, (ri, rj))| within(ti, *ri) && within(tj, *rj))
            .map(|(m, _)| m)
    }

    /// The global array (`nbin` rows of [`Rdf::columns`] values, row-major) for the
    /// particles of `group`.
    pub fn array(&self, sim: &Simulation, group: u32) -> Result<Vec<f64>, EngineError> {
        if sim.pair.is_none() && sim.pair_selection.is_none() {
            return Err("Compute rdf requires a pair style be defined".into());
        }
        let p = &sim.particles;
        let radii = CoordAtom::type_radii(sim);
        let (factor, skin) = (sim.contact_factor(), sim.neighbor.skin);
        // the pair style's cutoff at the run's init (LIGGGHTS's cutforce)
        let cutforce = if sim.neighbor.cutneighmax > skin {
            sim.neighbor.cutneighmax - skin
        } else {
            2.0 * sim.largest_radius() * factor
        };
        let nbin = self.nbin;
        let delr = cutforce / nbin as f64;
        let delrinv = 1.0 / delr;
        let npairs = self.pairs.len();
        let mut hist = vec![0.0f64; npairs * nbin];
        // every pair within a type pair's neighbour cutoff (the reach is the largest one)
        let cutmax = 2.0 * radii.iter().copied().fold(0.0, f64::max) * factor + skin;
        let reach = vec![0.5 * cutmax; p.len()];
        let list = fresh_pairs(sim, &reach, 1e-6 * cutmax.max(f64::MIN_POSITIVE));
        for pair in &list.pairs {
            let (i, j) = (pair.i as usize, pair.j as usize);
            if p.mask[i] & group == 0 || p.mask[j] & group == 0 || excluded(sim, i, j) {
                continue;
            }
            let (ti, tj) = (p.kind[i], p.kind[j]);
            let cutneigh = (radii[ti as usize] + radii[tj as usize]) * factor + skin;
            let rsq = distance_sq(sim, i, j, pair.shift);
            if rsq > cutneigh * cutneigh {
                continue;
            }
            let ibin = (rsq.sqrt() * delrinv) as usize;
            if ibin >= nbin {
                continue;
            }
            // the pair counts once from each side
            for m in self.histograms(ti, tj).chain(self.histograms(tj, ti)) {
                hist[m * nbin + ibin] += 1.0;
            }
        }
        Ok(self.normalise(sim, group, &hist, delr))
    }

    /// g(r) and coord(r) from the counts, with the box's volume (area in 2d).
    fn normalise(&self, sim: &Simulation, group: u32, hist: &[f64], delr: f64) -> Vec<f64> {
        let p = &sim.particles;
        let mut typecount = vec![0i64; sim.ntypes as usize + 1];
        for i in 0..p.len() {
            if p.mask[i] & group != 0 {
                if let Some(c) = typecount.get_mut(p.kind[i] as usize) {
                    *c += 1;
                }
            }
        }
        let count = |(lo, hi): (u32, u32)| -> i64 {
            (lo..=hi)
                .map(|t| typecount.get(t as usize).copied().unwrap_or(0))
                .sum()
        };
        let (nbin, cols) = (self.nbin, self.columns());
        let mut out = vec![0.0; nbin * cols];
        for (ibin, row) in out.chunks_mut(cols).enumerate() {
            row[0] = (ibin as f64 + 0.5) * delr;
        }
        let dom = &sim.domain;
        let three_d = sim.dimension == 3;
        let constant = if three_d {
            4.0 * std::f64::consts::PI / (3.0 * dom.length(0) * dom.length(1) * dom.length(2))
        } else {
            std::f64::consts::PI / (dom.length(0) * dom.length(1))
        };
        for (m, &(ri, rj)) in self.pairs.iter().enumerate() {
            let (icount, jcount) = (count(ri) as f64, count(rj) as f64);
            let mut ncoord = 0.0;
            for ibin in 0..nbin {
                let rlower = ibin as f64 * delr;
                let rupper = (ibin + 1) as f64 * delr;
                let shell = if three_d {
                    rupper * rupper * rupper - rlower * rlower * rlower
                } else {
                    rupper * rupper - rlower * rlower
                };
                let nideal = constant * shell * jcount;
                let gr = if icount * nideal != 0.0 {
                    hist[m * nbin + ibin] / (icount * nideal)
                } else {
                    0.0
                };
                ncoord += gr * nideal;
                out[ibin * cols + 1 + 2 * m] = gr;
                out[ibin * cols + 2 + 2 * m] = ncoord;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ordered_pairs_count_in_each_matching_histogram() {
        let rdf = Rdf {
            nbin: 4,
            pairs: vec![((1, 1), (2, 2)), ((1, 2), (1, 2))],
        };
        assert_eq!(rdf.columns(), 5);
        assert_eq!(rdf.histograms(1, 2).collect::<Vec<_>>(), [0, 1]);
        assert_eq!(rdf.histograms(2, 1).collect::<Vec<_>>(), [1]);
    }
}
