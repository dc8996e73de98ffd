//! The channel's sensor grid: square cells over the y-z plane, each spanning the channel's
//! whole (periodic) width in x. Cell averages of particle force and overlap take the
//! particles whose centres lie in the cell; the packing fraction splits each particle's
//! volume across the cells it straddles.

use std::sync::OnceLock;

/// A y-z grid of square cells.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Lower y edge of the grid (m).
    pub y0: f64,
    /// Lower z edge of the grid (m).
    pub z0: f64,
    /// Cell edge (m).
    pub cell: f64,
    /// Cells along y.
    pub ny: usize,
    /// Cells along z.
    pub nz: usize,
    /// Width of the channel in x (m): the depth of every cell.
    pub width: f64,
}

/// What one particle contributes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe {
    /// Centre y (m).
    pub y: f64,
    /// Centre z (m).
    pub z: f64,
    /// Radius (m).
    pub r: f64,
    /// |f| (N).
    pub force: f64,
    /// Mean contact overlap (m), if known.
    pub overlap: Option<f64>,
}

/// Per-cell values of one snapshot, indexed `iy * nz + iz`.
#[derive(Debug, Clone, PartialEq)]
pub struct CellStats {
    /// Particles whose centre is in the cell.
    pub count: Vec<usize>,
    /// Mean |f| of those particles (N); 0 for an empty cell.
    pub force: Vec<f64>,
    /// Mean overlap of those particles with a known overlap (m); NaN when none.
    pub overlap: Vec<f64>,
    /// Solid volume fraction (particle volume in the cell / cell volume).
    pub packing: Vec<f64>,
}

/// Sub-grid resolution of the volume split (per direction, over the sphere's square).
const SUB: usize = 10;

/// Weights of the SUB x SUB sample points of a unit sphere's projection (column thickness x
/// area), normalised to the sphere's volume 4 pi / 3.
fn unit_weights() -> &'static Vec<(f64, f64, f64)> {
    static W: OnceLock<Vec<(f64, f64, f64)>> = OnceLock::new();
    W.get_or_init(|| {
        let h = 2.0 / SUB as f64;
        let mut w = Vec::new();
        for i in 0..SUB {
            for j in 0..SUB {
                let (u, v) = (-1.0 + h * (i as f64 + 0.5), -1.0 + h * (j as f64 + 0.5));
                let rho2 = u * u + v * v;
                if rho2 < 1.0 {
                    w.push((u, v, 2.0 * (1.0 - rho2).sqrt() * h * h));
                }
            }
        }
        let total: f64 = w.iter().map(|p| p.2).sum();
        let scale = 4.0 * std::f64::consts::PI / 3.0 / total;
        w.into_iter().map(|(u, v, x)| (u, v, x * scale)).collect()
    })
}

impl Grid {
    /// Cells of edge `cell` covering y in [y0, y1] and z in [z0, z1].
    pub fn covering(y: (f64, f64), z: (f64, f64), cell: f64, width: f64) -> Grid {
        Grid {
            y0: y.0,
            z0: z.0,
            cell,
            ny: (((y.1 - y.0) / cell).ceil() as usize).max(1),
            nz: (((z.1 - z.0) / cell).ceil() as usize).max(1),
            width,
        }
    }

    /// The number of cells.
    pub fn len(&self) -> usize {
        self.ny * self.nz
    }

    /// True when the grid has no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The cell holding point (y, z), if any.
    pub fn index(&self, y: f64, z: f64) -> Option<usize> {
        let iy = ((y - self.y0) / self.cell).floor();
        let iz = ((z - self.z0) / self.cell).floor();
        (iy >= 0.0 && iz >= 0.0 && (iy as usize) < self.ny && (iz as usize) < self.nz)
            .then(|| iy as usize * self.nz + iz as usize)
    }

    /// The centre (y, z) of cell `k` (m).
    pub fn center(&self, k: usize) -> (f64, f64) {
        let (iy, iz) = (k / self.nz, k % self.nz);
        (
            self.y0 + (iy as f64 + 0.5) * self.cell,
            self.z0 + (iz as f64 + 0.5) * self.cell,
        )
    }

    /// Cell averages of one snapshot.
    pub fn measure(&self, probes: &[Probe]) -> CellStats {
        let n = self.len();
        let mut count = vec![0usize; n];
        let mut force = vec![0.0; n];
        let mut osum = vec![0.0; n];
        let mut on = vec![0usize; n];
        let mut volume = vec![0.0; n];
        for p in probes {
            if let Some(k) = self.index(p.y, p.z) {
                count[k] += 1;
                force[k] += p.force;
                if let Some(o) = p.overlap {
                    osum[k] += o;
                    on[k] += 1;
                }
            }
            let r3 = p.r.powi(3);
            for &(u, v, w) in unit_weights() {
                if let Some(k) = self.index(p.y + p.r * u, p.z + p.r * v) {
                    volume[k] += w * r3;
                }
            }
        }
        let cell_volume = self.cell * self.cell * self.width;
        CellStats {
            force: (0..n)
                .map(|k| {
                    if count[k] > 0 {
                        force[k] / count[k] as f64
                    } else {
                        0.0
                    }
                })
                .collect(),
            overlap: (0..n)
                .map(|k| {
                    if on[k] > 0 {
                        osum[k] / on[k] as f64
                    } else {
                        f64::NAN
                    }
                })
                .collect(),
            packing: volume.iter().map(|v| v / cell_volume).collect(),
            count,
        }
    }
}

/// The arrival time in one cell: the first maximum of its mean force that exceeds `factor`
/// times the initial (first snapshot) mean force. `series` is (time s, mean force N).
pub fn arrival(series: &[(f64, f64)], factor: f64) -> Option<f64> {
    let f0 = series.first()?.1;
    if f0 <= 0.0 {
        return None;
    }
    let first = series.iter().position(|p| p.1 > factor * f0)?;
    let mut k = first;
    while k + 1 < series.len() && series[k + 1].1 >= series[k].1 {
        k += 1;
    }
    Some(series[k].0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn volume_is_split_across_cells() {
        let g = Grid::covering((0.0, 0.02), (0.0, 0.02), 0.005, 0.01);
        let r = 0.00125;
        // a sphere centred on a corner shared by four cells: a quarter in each
        let p = Probe {
            y: 0.005,
            z: 0.005,
            r,
            force: 2.0,
            overlap: Some(1e-6),
        };
        let s = g.measure(&[p]);
        let v = 4.0 / 3.0 * std::f64::consts::PI * r.powi(3) / (0.005 * 0.005 * 0.01);
        for k in [0, 1, 4, 5] {
            assert!(
                (s.packing[k] - v / 4.0).abs() < 1e-9 * v,
                "{k}: {}",
                s.packing[k]
            );
        }
        let total: f64 = s.packing.iter().sum();
        assert!((total - v).abs() < 1e-12);
        assert_eq!(s.count[5], 1);
        assert_eq!(s.force[5], 2.0);
        assert_eq!(s.overlap[5], 1e-6);
        assert!(s.overlap[0].is_nan());
        assert_eq!(g.center(5), (0.0075, 0.0075));
        assert_eq!(g.index(0.021, 0.0), None);
    }

    #[test]
    fn arrival_is_the_first_maximum_above_ten_times_the_start() {
        let s = [
            (0.0, 1.0),
            (1.0, 5.0),
            (2.0, 20.0),
            (3.0, 30.0),
            (4.0, 10.0),
            (5.0, 40.0),
        ];
        assert_eq!(arrival(&s, 10.0), Some(3.0));
        assert_eq!(arrival(&s[..2], 10.0), None);
        assert_eq!(arrival(&[(0.0, 0.0), (1.0, 5.0)], 10.0), None);
    }
}
