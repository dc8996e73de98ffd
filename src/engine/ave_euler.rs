//! The cell grid of `fix ave/euler`: LIGGGHTS 3.8.0's Eulerian averages over a regular grid
//! of cells a few particle diameters wide (mass-averaged velocity, number-averaged radius,
//! volume fraction, and the stress of the contacts plus the velocity fluctuations), in
//! LIGGGHTS's order of operations so the values come out to the last bit.

use crate::engine::particles::Particles;
use crate::state::domain::Domain;

/// The image shifts of LIGGGHTS's ghost atoms in the order its border exchange creates
/// them (one process): per periodic axis, the images of the lower face's atoms (+1) and
/// then of the upper face's (-1), each of every atom and earlier image. The first entry is
/// the particle itself.
fn ghost_shifts(periodic: [bool; 3]) -> Vec<[i32; 3]> {
    let mut shifts = vec![[0; 3]];
    for (d, &is_periodic) in periodic.iter().enumerate() {
        if !is_periodic {
            continue;
        }
        let mut added = Vec::new();
        for sign in [1, -1] {
            for s in &shifts {
                let mut t = *s;
                t[d] = sign;
                added.push(t);
            }
        }
        shifts.extend(added);
    }
    shifts
}

/// LIGGGHTS's Monte Carlo tries per cell; only its inverse, the smallest cell weight that
/// still counts, is used without a `basevolume_region`.
const TRIES_PER_CELL: f64 = 50.0;

/// The grid and the averages of its last evaluation (one proc: LIGGGHTS's local and global
/// grids are the same).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EulerGrid {
    /// Cells along x, y, z.
    pub dims: [usize; 3],
    /// Lower corner of the grid (length).
    pub lo: [f64; 3],
    /// Upper corner of the grid (length).
    pub hi: [f64; 3],
    /// Cell edges (length).
    pub size: [f64; 3],
    /// Inverse cell edges (1/length).
    pub size_inv: [f64; 3],
    /// Cell volume (length^3).
    pub volume: f64,
    /// Cell centres (length), x fastest, then y, then z.
    pub center: Vec<[f64; 3]>,
    /// Mass-averaged velocity of each cell (velocity).
    pub v_av: Vec<[f64; 3]>,
    /// Volume fraction of each cell.
    pub vol_fr: Vec<f64>,
    /// Number-averaged radius of each cell (length).
    pub radius: Vec<f64>,
    /// Summed mass of each cell (mass).
    pub mass: Vec<f64>,
    /// Particles in each cell.
    pub count: Vec<i32>,
    /// Pressure and stress of each cell: [p, xx, yy, zz, xy, xz, yz] (pressure).
    pub stress: Vec<[f64; 7]>,
}

/// The most cells a grid gets: 2^20, a grid for a bed of some 10^8 particles (its
/// `dump euler/vtk` text alone is about 200 MB). Larger grids come from boxes blown up by
/// runaway particles (LIGGGHTS fails to allocate them, or overflows its `int` count), and
/// keep one cell.
const MAX_CELLS: usize = 1 << 20;

/// A double truncated to `int` as LIGGGHTS's `static_cast<int>` does on x86-64: values
/// outside the `int` range, and NaN, give `INT_MIN`.
fn c_int(x: f64) -> i32 {
    if x.is_nan() || x >= 2_147_483_648.0 || x <= -2_147_483_649.0 {
        i32::MIN
    } else {
        x as i32
    }
}

impl EulerGrid {
    /// LIGGGHTS's `setup_bins`: cells of at least `relative` times the largest contact
    /// distance `cutoff` (length) fitted into the box `lo`..`hi`, at least one per axis.
    /// Returns whether an axis had room for less than one cell (LIGGGHTS warns).
    pub fn setup_bins(&mut self, lo: [f64; 3], hi: [f64; 3], relative: f64, cutoff: f64) -> bool {
        let ideal = relative * cutoff;
        let mut less_than_one = false;
        for d in 0..3 {
            let mut n = c_int((hi[d] - lo[d]) / ideal);
            if n < 1 {
                n = 1;
                less_than_one = true;
            }
            self.dims[d] = n as usize;
        }
        // more cells than memory holds (where LIGGGHTS fails to allocate them): regolith
        // keeps one cell rather than stop the run
        let total = self.dims.iter().try_fold(1usize, |t, &n| t.checked_mul(n));
        if total.is_none_or(|t| t > MAX_CELLS) {
            self.dims = [1; 3];
            less_than_one = true;
        }
        for d in 0..3 {
            self.size[d] = (hi[d] - lo[d]) / self.dims[d] as f64;
            self.size_inv[d] = 1.0 / self.size[d];
        }
        self.lo = lo;
        self.hi = hi;
        self.volume = self.size[0] * self.size[1] * self.size[2];
        let n = self.cells();
        self.center = vec![[0.0; 3]; n];
        for iz in 0..self.dims[2] {
            for iy in 0..self.dims[1] {
                for ix in 0..self.dims[0] {
                    let c = (iz * self.dims[1] + iy) * self.dims[0] + ix;
                    let at = |d: usize, i: usize| lo[d] + (i as f64 + 0.5) * self.size[d];
                    self.center[c] = [at(0, ix), at(1, iy), at(2, iz)];
                }
            }
        }
        less_than_one
    }

    /// Number of cells.
    pub fn cells(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    /// LIGGGHTS's `coord2bin`: the cell of position `x` (length), None outside the box
    /// (on a face counts as outside) or past the last cell. An index rounding up to an
    /// axis's cell count spills into the next row, as in LIGGGHTS.
    fn cell_of(&self, x: [f64; 3], box_lo: [f64; 3], box_hi: [f64; 3]) -> Option<usize> {
        let mut idx = [0i64; 3];
        for d in 0..3 {
            if x[d] <= box_lo[d] || x[d] >= box_hi[d] {
                return None;
            }
            idx[d] = ((x[d] - self.lo[d]) * self.size_inv[d]) as i32 as i64;
        }
        let (nx, ny) = (self.dims[0] as i64, self.dims[1] as i64);
        let c = idx[2] * ny * nx + idx[1] * nx + idx[0];
        (c >= 0 && c < self.cells() as i64).then_some(c as usize)
    }

    /// LIGGGHTS's `bin_atoms`: the group's particles inside the box in particle order, then
    /// the periodic images (LIGGGHTS's ghost atoms) that lie inside the box, those of
    /// particles that left it through a periodic face since the last re-neighbouring, in
    /// the order LIGGGHTS creates ghosts (x faces, then y, then z; lower face first).
    fn bin(&self, p: &Particles, group: u32, domain: &Domain) -> Vec<Vec<(usize, bool)>> {
        let (lo, hi) = (domain.lo, domain.hi);
        let mut members: Vec<Vec<(usize, bool)>> = vec![Vec::new(); self.cells()];
        let shifts = ghost_shifts([0, 1, 2].map(|d| domain.periodic(d)));
        let mut images = Vec::new();
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let x = p.x[i];
            if let Some(c) = self.cell_of(x, lo, hi) {
                members[c].push((i, false));
                continue;
            }
            let shift = [0, 1, 2].map(|d| {
                if x[d] < lo[d] {
                    1
                } else if x[d] > hi[d] {
                    -1
                } else {
                    0
                }
            });
            let Some(rank) = shifts.iter().position(|s| *s == shift) else {
                continue;
            };
            let image = [0, 1, 2].map(|d| x[d] + shift[d] as f64 * domain.length(d));
            if let Some(c) = self.cell_of(image, lo, hi) {
                images.push((rank, i, c));
            }
        }
        images.sort_by_key(|&(rank, i, _)| (rank, i));
        for (_, i, c) in images {
            members[c].push((i, true));
        }
        members
    }

    /// LIGGGHTS's `bin_atoms` and `calculate_eu`: the group's particles binned (see
    /// [`EulerGrid::bin`]), then each cell's averages. `stress_atom` is the per-atom pair
    /// stress times volume of `compute stress/atom pair` (xx yy zz xy xz yz; force length);
    /// `ghost_v` the velocities as the step's forward communication gave them to LIGGGHTS's
    /// ghost atoms (empty: the current ones). `parallel no` recomputes the pressure from the
    /// scaled stresses.
    pub fn average(
        &mut self,
        p: &Particles,
        group: u32,
        stress_atom: &[[f64; 6]],
        ghost_v: &[[f64; 3]],
        domain: &Domain,
        parallel: bool,
    ) {
        let vel = |i: usize, ghost: bool| match ghost_v.get(i) {
            Some(v) if ghost => *v,
            _ => p.v[i],
        };
        let n = self.cells();
        let members = self.bin(p, group, domain);
        self.v_av = vec![[0.0; 3]; n];
        self.vol_fr = vec![0.0; n];
        self.radius = vec![0.0; n];
        self.mass = vec![0.0; n];
        self.count = vec![0; n];
        self.stress = vec![[0.0; 7]; n];
        for (c, atoms) in members.iter().enumerate() {
            for &(i, ghost) in atoms {
                let m = p.mass[i];
                let v = vel(i, ghost);
                for (sum, vk) in self.v_av[c].iter_mut().zip(v) {
                    *sum += m * vk;
                }
                let r = p.radius[i];
                self.vol_fr[c] += r * r * r;
                self.radius[c] += r;
                self.mass[c] += m;
                self.count[c] += 1;
            }
        }
        let min_weight = 1.0 / TRIES_PER_CELL;
        let prefactor_vol_fr = 4.0 / 3.0 * std::f64::consts::PI / self.volume;
        let prefactor_stress = 1.0 / self.volume;
        // every cell weighs 1 without a basevolume_region
        let weight = 1.0;
        for (c, atoms) in members.iter().enumerate() {
            if self.count[c] != 0 {
                let inv = 1.0 / self.mass[c];
                for k in 0..3 {
                    self.v_av[c][k] *= inv;
                }
                self.radius[c] /= self.count[c] as f64;
            }
            if weight < min_weight {
                self.vol_fr[c] = 0.0;
            } else {
                self.vol_fr[c] *= prefactor_vol_fr / weight;
            }
            let va = self.v_av[c];
            let s = &mut self.stress[c];
            for &(i, ghost) in atoms {
                let m = p.mass[i];
                let v = vel(i, ghost);
                let dv = [0, 1, 2].map(|k| v[k] - va[k]);
                let sa = stress_atom.get(i).copied().unwrap_or([0.0; 6]);
                s[1] += -m * dv[0] * dv[0] + sa[0];
                s[2] += -m * dv[1] * dv[1] + sa[1];
                s[3] += -m * dv[2] * dv[2] + sa[2];
                s[4] += -m * dv[0] * dv[1] + sa[3];
                s[5] += -m * dv[0] * dv[2] + sa[4];
                s[6] += -m * dv[1] * dv[2] + sa[5];
            }
            s[0] = -0.333333333333333 * (s[1] + s[2] + s[3]);
            let scale = prefactor_stress / weight;
            for v in s.iter_mut() {
                *v *= scale;
            }
            if !parallel {
                s[0] = -0.333333333333333 * (s[1] + s[2] + s[3]);
            }
        }
    }

    /// LIGGGHTS's `compute_array(i, j)` (0-based): centre x y z, volume fraction, velocity
    /// x y z; 0 past the last cell.
    pub fn array(&self, i: usize, j: usize) -> f64 {
        if i >= self.center.len() || i >= self.vol_fr.len() {
            return 0.0;
        }
        match j {
            0..=2 => self.center[i][j],
            3 => self.vol_fr[i],
            4..=6 => self.v_av[i][j - 4],
            _ => 0.0,
        }
    }

    /// The cells as `dump euler/vtk` writes them: legacy VTK points with the average
    /// velocity, volume fraction, radius and pressure (LIGGGHTS's `%f` text).
    pub fn vtk(&self) -> String {
        use std::fmt::Write;
        let f = |v: f64| crate::util::format::with_spec("%f", v).unwrap_or_default();
        let n = self.vol_fr.len().min(self.center.len());
        let mut t = String::new();
        t.push_str("# vtk DataFile Version 2.0\nLIGGGHTS mesh/VTK export\nASCII\n");
        let _ = writeln!(t, "DATASET POLYDATA\nPOINTS {n} float");
        for c in &self.center[..n] {
            let _ = writeln!(t, "{} {} {}", f(c[0]), f(c[1]), f(c[2]));
        }
        let _ = writeln!(t, "VERTICES {n} {}", 2 * n);
        for i in 0..n {
            let _ = writeln!(t, "1 {i}");
        }
        let _ = writeln!(t, "POINT_DATA {n}\nVECTORS v_avg float");
        for v in &self.v_av[..n] {
            let _ = writeln!(t, "{} {} {}", f(v[0]), f(v[1]), f(v[2]));
        }
        let scalars: [(&str, Vec<f64>); 3] = [
            ("volumefraction", self.vol_fr.clone()),
            ("radius", self.radius.clone()),
            ("pressure", self.stress.iter().map(|s| s[0]).collect()),
        ];
        for (name, values) in scalars {
            let _ = writeln!(t, "SCALARS {name} float 1\nLOOKUP_TABLE default");
            for v in &values[..n] {
                let _ = writeln!(t, "{}", f(*v));
            }
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_far_smaller_than_the_box_give_one_cell_as_liggghts_int_cast_does() {
        let mut g = EulerGrid::default();
        // 0.1 / 3e-300 is past the int range: LIGGGHTS's cast gives INT_MIN, so one cell
        assert!(g.setup_bins([0.0; 3], [0.1; 3], 3.0, 1e-300));
        assert_eq!(g.dims, [1, 1, 1]);
        assert_eq!(g.cells(), 1);
        // 2000 cells a side fit an int each, but their product does not fit in memory
        assert!(g.setup_bins([0.0; 3], [2.0; 3], 1.0, 1e-3));
        assert_eq!(g.dims, [1, 1, 1]);
        assert!(!g.setup_bins([0.0; 3], [0.02; 3], 1.0, 1e-3));
        assert_eq!(g.dims, [20, 20, 20]);
    }

    #[test]
    fn cells_fit_the_box_and_average_by_mass() {
        let mut g = EulerGrid::default();
        // 0.03 / 0.012 = 2.5 cells: 2 of 0.015 in x and y; 0.04 / 0.012: 3 in z
        g.setup_bins([0.0; 3], [0.03, 0.03, 0.04], 3.0, 0.004);
        assert_eq!(g.dims, [2, 2, 3]);
        assert_eq!(g.center[1], [0.0225, 0.0075, 0.04 / 3.0 * 0.5]);
        let mut p = Particles::default();
        p.push(1, 1, [0.001, 0.001, 0.001], 0.002, 2500.0);
        p.push(2, 1, [0.002, 0.001, 0.001], 0.001, 2500.0);
        p.v = vec![[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]];
        let mut domain = Domain::default();
        domain.lo = [0.0; 3];
        domain.hi = [0.03, 0.03, 0.04];
        g.average(&p, 1, &[], &[], &domain, false);
        let (m1, m2) = (p.mass[0], p.mass[1]);
        assert_eq!(g.v_av[0][0], m1 * (1.0 / (m1 + m2)));
        assert_eq!(g.radius[0], 0.0015);
        assert_eq!(g.count[0], 2);
        assert_eq!(g.array(0, 4), g.v_av[0][0]);
        assert_eq!(g.array(99, 1), 0.0);
        // the kinetic part of the stress is negative along x, so the pressure is positive
        assert!(g.stress[0][1] < 0.0 && g.stress[0][0] > 0.0);
        // a particle past the upper x face counts through its image, after the others
        p.x[0][0] = 0.0301;
        let members = g.bin(&p, 1, &domain);
        assert_eq!(members[0], vec![(1, false), (0, true)]);
    }

    #[test]
    fn ghost_images_come_in_liggghts_border_order() {
        let s = ghost_shifts([true, true, false]);
        assert_eq!(
            s,
            vec![
                [0, 0, 0],
                [1, 0, 0],
                [-1, 0, 0],
                [0, 1, 0],
                [1, 1, 0],
                [-1, 1, 0],
                [0, -1, 0],
                [1, -1, 0],
                [-1, -1, 0]
            ]
        );
    }
}
