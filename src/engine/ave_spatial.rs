//! `fix ave/spatial`: per-atom quantities summed in 1d, 2d or 3d bins of the box, averaged
//! over `repeat` samples every `every` steps ending on multiples of `freq`, combined as
//! `ave one|running|window` and written to a file as LIGGGHTS 3.8.0's fix_ave_spatial.cpp
//! writes it.

use crate::engine::error::EngineError;
use crate::engine::fixes::{AveMode, FixStyle, SetupPass};
use crate::engine::sim::{Simulation, VariableSource};

/// One binned value.
#[derive(Debug, Clone, PartialEq)]
pub enum SpatialValue {
    /// `vx vy vz`: a velocity component (length/time).
    V(usize),
    /// `fx fy fz`: a force component (force).
    F(usize),
    /// `density/number`: atoms per volume.
    DensityNumber,
    /// `density/mass`: mass per volume.
    DensityMass,
    /// A per-atom compute `c_ID` or column `c_ID[N]`.
    Compute(String, Option<usize>),
    /// A per-atom fix `f_ID` or column `f_ID[N]`.
    Fix(String, Option<usize>),
    /// An atom-style variable `v_name`.
    Variable(String),
}

/// Where a dimension's bins start.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Origin {
    /// The box's lower face.
    Lower,
    /// The box's centre.
    Center,
    /// The box's upper face.
    Upper,
    /// A coordinate (length, already scaled).
    Coord(f64),
}

/// The settings of the fix, as parsed.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialSettings {
    /// Steps between samples, samples per average, steps between averages.
    pub schedule: (i64, i64, i64),
    /// Per binned dimension: the axis, the origin and the bin width (length or reduced).
    pub dims: Vec<(usize, Origin, f64)>,
    /// The values, one column each.
    pub values: Vec<SpatialValue>,
    /// `norm sample`: each sample normalised by its own count.
    pub norm_sample: bool,
    /// `units reduced`: bins in fractions of the box.
    pub reduced: bool,
    /// `region ID`: only atoms inside this region (index).
    pub region: Option<usize>,
    /// How averages combine.
    pub mode: AveMode,
    /// `overwrite`: each output replaces the previous one in the file.
    pub overwrite: bool,
    /// `write_ts no`: no `step nbins` line before each output.
    pub write_ts: bool,
}

/// `fix ave/spatial` with its bins and sums.
#[derive(Debug)]
pub struct AveSpatial {
    /// The settings.
    pub set: SpatialSettings,
    /// The output file and where its header ends.
    pub file: Option<(std::fs::File, u64)>,
    /// The next step that samples.
    pub nvalid: i64,
    irepeat: i64,
    offset: Vec<f64>,
    nlayers: Vec<usize>,
    coord: Vec<Vec<f64>>,
    bin_volume: f64,
    count_many: Vec<f64>,
    count_sum: Vec<f64>,
    count_total: Vec<f64>,
    values_many: Vec<Vec<f64>>,
    values_sum: Vec<Vec<f64>>,
    values_total: Vec<Vec<f64>>,
    window: Vec<(Vec<f64>, Vec<Vec<f64>>)>,
    iwindow: usize,
    window_full: bool,
    norm: usize,
    maxbin: usize,
}

/// LIGGGHTS's layer bounds along one axis (lower end of the first layer, upper end of the
/// last): whole layers of `delta` from the origin out past the box's faces `blo`, `bhi`
/// (all in the axis's length unit, or reduced).
fn layer_bounds(origin: Origin, delta: f64, blo: f64, bhi: f64) -> (f64, f64) {
    let inv = 1.0 / delta;
    let o = match origin {
        Origin::Lower => blo,
        Origin::Upper => bhi,
        Origin::Center => 0.5 * (blo + bhi),
        Origin::Coord(c) => c,
    };
    let lo = if o < blo {
        o + ((blo - o) * inv) as i32 as f64 * delta
    } else {
        let lo = o - ((o - blo) * inv) as i32 as f64 * delta;
        if lo > blo {
            lo - delta
        } else {
            lo
        }
    };
    let hi = if o < bhi {
        let hi = o + ((bhi - o) * inv) as i32 as f64 * delta;
        if hi < bhi {
            hi + delta
        } else {
            hi
        }
    } else {
        o - ((o - bhi) * inv) as i32 as f64 * delta
    };
    (lo, hi)
}

impl AveSpatial {
    /// A fix defined at `step`.
    pub fn new(set: SpatialSettings, step: i64) -> AveSpatial {
        let mut a = AveSpatial {
            set,
            file: None,
            nvalid: 0,
            irepeat: 0,
            offset: Vec::new(),
            nlayers: Vec::new(),
            coord: Vec::new(),
            bin_volume: 0.0,
            count_many: Vec::new(),
            count_sum: Vec::new(),
            count_total: Vec::new(),
            values_many: Vec::new(),
            values_sum: Vec::new(),
            values_total: Vec::new(),
            window: Vec::new(),
            iwindow: 0,
            window_full: false,
            norm: 0,
            maxbin: 0,
        };
        a.nvalid = a.next_valid(step);
        a
    }

    /// The first sampling step at or after `step` (LIGGGHTS's `nextvalid`).
    pub fn next_valid(&self, step: i64) -> i64 {
        let (every, repeat, freq) = self.set.schedule;
        let mut nvalid = (step / freq) * freq + freq;
        if nvalid - freq == step && repeat == 1 {
            nvalid = step;
        } else {
            nvalid -= (repeat - 1) * every;
        }
        if nvalid < step {
            nvalid += freq;
        }
        nvalid
    }

    fn nbins(&self) -> usize {
        self.nlayers.iter().product()
    }

    /// LIGGGHTS's `setup_bins`: layers from the origin out past both faces, bin centres,
    /// the bin volume; sums grow (and restart) when the bin count grows.
    pub fn setup_bins(&mut self, sim: &Simulation) -> Result<(), EngineError> {
        let d = &sim.domain;
        let (lo_box, hi_box, prd) = if self.set.reduced {
            ([0.0; 3], [1.0; 3], [1.0; 3])
        } else {
            (d.lo, d.hi, [0, 1, 2].map(|k| d.length(k)))
        };
        self.bin_volume = if sim.dimension == 3 {
            d.length(0) * d.length(1) * d.length(2)
        } else {
            d.length(0) * d.length(1)
        };
        self.offset.clear();
        self.nlayers.clear();
        for &(axis, origin, delta) in &self.set.dims {
            let (lo, hi) = layer_bounds(origin, delta, lo_box[axis], hi_box[axis]);
            let inv = 1.0 / delta;
            self.offset.push(lo);
            self.nlayers.push(((hi - lo) * inv + 0.5) as i32 as usize);
            self.bin_volume *= delta / prd[axis];
        }
        // a bin size far below the box gives more bins than memory holds (Debian's LIGGGHTS
        // crashes there): stop with the count instead
        let total = self
            .nlayers
            .iter()
            .try_fold(1usize, |acc, &n| acc.checked_mul(n))
            .filter(|&n| {
                n > 0 && n <= MAX_BINS && self.nlayers.iter().all(|&l| l < i32::MAX as usize)
            });
        if total.is_none() {
            let sizes: Vec<String> = self
                .set
                .dims
                .iter()
                .map(|d| crate::util::format::g(d.2))
                .collect();
            return Err(format!(
                "Fix ave/spatial: bin sizes {} give no bins or more than {MAX_BINS} of them",
                sizes.join(" ")
            )
            .into());
        }
        if self.set.reduced {
            // Debian's LIGGGHTS 3.8.0 prints densities of 0 in reduced units (observed):
            // its lamda period is 0 there, which makes the bin volume infinite
            self.bin_volume = f64::INFINITY;
        }
        let (n, nv) = (self.nbins(), self.set.values.len());
        if n > self.maxbin {
            self.maxbin = n;
            self.count_total = vec![0.0; n];
            self.values_total = vec![vec![0.0; nv]; n];
            if let AveMode::Window(w) = self.set.mode {
                self.window = vec![(vec![0.0; n], vec![vec![0.0; nv]; n]); w];
            }
        }
        self.count_many.resize(n, 0.0);
        self.count_sum.resize(n, 0.0);
        self.values_many.resize(n, vec![0.0; nv]);
        self.values_sum.resize(n, vec![0.0; nv]);
        self.count_total.resize(n, 0.0);
        self.values_total.resize(n, vec![0.0; nv]);
        self.coord = (0..n)
            .map(|mut m| {
                let mut c = vec![0.0; self.nlayers.len()];
                for k in (0..self.nlayers.len()).rev() {
                    let i = m % self.nlayers[k];
                    m /= self.nlayers[k];
                    c[k] = self.offset[k] + (i as f64 + 0.5) * self.set.dims[k].2;
                }
                c
            })
            .collect();
        Ok(())
    }

    /// The bin of position `x` (LIGGGHTS's `atom2bin1d/2d/3d`); `x` is in reduced units for
    /// `units reduced`.
    fn bin_of(&self, sim: &Simulation, x: [f64; 3]) -> usize {
        let d = &sim.domain;
        let mut bin = 0;
        for (k, &(axis, _, delta)) in self.set.dims.iter().enumerate() {
            let mut r = x[axis];
            if d.periodic(axis) {
                // in reduced units Debian's LIGGGHTS 3.8.0 remaps by a period of 0
                // (observed): atoms past a periodic face stay in the outermost bin
                let (lo, hi, prd) = if self.set.reduced {
                    (0.0, 1.0, 0.0)
                } else {
                    (d.lo[axis], d.hi[axis], d.length(axis))
                };
                if r < lo {
                    r += prd;
                }
                if r >= hi {
                    r -= prd;
                }
            }
            let mut top = self.nlayers[k] as i64 - 1;
            if self.set.dims.len() == 2 && self.set.region.is_some() {
                // LIGGGHTS 3.8.0's 2d binning inside a region never uses the last layer
                top -= 1;
            }
            let i = (((r - self.offset[k]) * (1.0 / delta)) as i32 as i64)
                .max(0)
                .min(top)
                .max(0);
            bin = bin * self.nlayers[k] + i as usize;
        }
        bin
    }
}

/// The most bins `fix ave/spatial` makes (each holds a count and every value's sums).
const MAX_BINS: usize = 1 << 26;

impl Simulation {
    /// The bins of the group's atoms (None outside the group or region) and the per-bin
    /// atom count of one sample; `units reduced` round-trips positions through fractions
    /// of the box as LIGGGHTS does.
    fn spatial_bins(&mut self, a: &AveSpatial, group: u32) -> (Vec<Option<usize>>, Vec<f64>) {
        let n = self.particles.len();
        let mut bins = vec![None; n];
        let mut count = vec![0.0; a.nbins()];
        let (lo, prd) = (self.domain.lo, [0, 1, 2].map(|k| self.domain.length(k)));
        let to_reduced = |x: [f64; 3]| [0, 1, 2].map(|k| (x[k] - lo[k]) * (1.0 / prd[k]));
        for (i, slot) in bins.iter_mut().enumerate() {
            let x = self.particles.x[i];
            if self.particles.mask[i] & group == 0 {
                continue;
            }
            if a.set.region.is_some_and(|r| !self.regions.matches(r, x)) {
                continue;
            }
            let at = if a.set.reduced { to_reduced(x) } else { x };
            let b = a.bin_of(self, at);
            *slot = Some(b);
            count[b] += 1.0;
        }
        if a.set.reduced && a.set.region.is_none() {
            // x2lamda then lamda2x over all local atoms
            for x in self.particles.x.iter_mut() {
                let l = to_reduced(*x);
                *x = [0, 1, 2].map(|k| prd[k] * l[k] + 0.0 + 0.0 + lo[k]);
            }
        }
        (bins, count)
    }

    /// One value's per-atom numbers.
    fn spatial_value(
        &self,
        v: &SpatialValue,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<f64>, EngineError> {
        let p = &self.particles;
        Ok(match v {
            SpatialValue::V(d) => p.v.iter().map(|v| v[*d]).collect(),
            SpatialValue::F(d) => p.f.iter().map(|f| f[*d]).collect(),
            SpatialValue::DensityNumber => vec![1.0; p.len()],
            SpatialValue::DensityMass => p.mass.clone(),
            SpatialValue::Compute(id, index) => {
                let c = self.computes.iter().find(|c| &c.id == id).ok_or_else(|| {
                    format!("Compute ID for fix ave/spatial does not exist: {id}")
                })?;
                let data = c.per_atom(self, vars)?;
                let col = crate::engine::computes::column_of(c, *index)?;
                (0..p.len()).map(|i| data.get(i, col)).collect()
            }
            SpatialValue::Fix(id, index) => {
                let (data, col) = crate::engine::fix_columns::per_atom(self, id, *index)?;
                (0..p.len()).map(|i| data.get(i, col)).collect()
            }
            SpatialValue::Variable(name) => vars.atom(self, name)?,
        })
    }

    fn ave_spatial_sample(
        &mut self,
        a: &mut AveSpatial,
        group: u32,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let nv = a.set.values.len();
        if a.irepeat == 0 {
            if self.domain.shrinks() {
                a.setup_bins(self)?;
            }
            a.count_many.fill(0.0);
            a.count_sum.fill(0.0);
            a.values_many.iter_mut().for_each(|v| v.fill(0.0));
        }
        let (bins, count_one) = self.spatial_bins(a, group);
        let mut values_one = vec![vec![0.0; nv]; a.nbins()];
        for (m, v) in a.set.values.iter().enumerate() {
            let per_atom = self.spatial_value(v, vars)?;
            for (i, b) in bins.iter().enumerate() {
                if let Some(b) = b {
                    values_one[*b][m] += per_atom[i];
                }
            }
        }
        let density =
            |v: &SpatialValue| matches!(v, SpatialValue::DensityNumber | SpatialValue::DensityMass);
        for (m, count) in count_one.iter().enumerate() {
            if a.set.norm_sample {
                a.count_many[m] = *count;
                if *count > 0.0 {
                    for (j, v) in a.set.values.iter().enumerate() {
                        let x = values_one[m][j];
                        a.values_many[m][j] += if density(v) { x } else { x / count };
                    }
                }
                a.count_sum[m] += count;
            } else {
                a.count_many[m] += count;
                for (sum, one) in a.values_many[m].iter_mut().zip(&values_one[m]) {
                    *sum += one;
                }
            }
        }
        let (every, repeat, freq) = a.set.schedule;
        a.irepeat += 1;
        if a.irepeat < repeat {
            a.nvalid += every;
            return Ok(());
        }
        a.irepeat = 0;
        a.nvalid = self.step + freq - (repeat - 1) * every;
        a.finish_average(repeat as f64);
        a.write(self.step)
    }
}

impl AveSpatial {
    /// Time average across the samples, normalised per bin volume for densities, then
    /// combined with earlier averages.
    fn finish_average(&mut self, repeat: f64) {
        let density =
            |v: &SpatialValue| matches!(v, SpatialValue::DensityNumber | SpatialValue::DensityMass);
        for m in 0..self.nbins() {
            if !self.set.norm_sample {
                self.count_sum[m] = self.count_many[m];
            }
            self.values_sum[m] = self.values_many[m].clone();
            for (j, v) in self.set.values.iter().enumerate() {
                let s = &mut self.values_sum[m][j];
                if self.set.norm_sample {
                    *s /= repeat;
                } else if self.count_sum[m] > 0.0 {
                    match v {
                        SpatialValue::DensityNumber => *s /= repeat,
                        SpatialValue::DensityMass => *s *= 1.0 / repeat,
                        _ => *s /= self.count_sum[m],
                    }
                }
            }
            self.count_sum[m] /= repeat;
            for (j, v) in self.set.values.iter().enumerate() {
                if density(v) {
                    self.values_sum[m][j] /= self.bin_volume;
                }
            }
        }
        match self.set.mode {
            AveMode::One => {
                self.values_total = self.values_sum.clone();
                self.count_total = self.count_sum.clone();
                self.norm = 1;
            }
            AveMode::Running => {
                for m in 0..self.nbins() {
                    for j in 0..self.set.values.len() {
                        self.values_total[m][j] += self.values_sum[m][j];
                    }
                    self.count_total[m] += self.count_sum[m];
                }
                self.norm += 1;
            }
            AveMode::Window(w) => {
                let slot = &mut self.window[self.iwindow];
                for m in 0..self.count_sum.len() {
                    for j in 0..self.set.values.len() {
                        self.values_total[m][j] += self.values_sum[m][j];
                        if self.window_full {
                            self.values_total[m][j] -= slot.1[m][j];
                        }
                        slot.1[m][j] = self.values_sum[m][j];
                    }
                    self.count_total[m] += self.count_sum[m];
                    if self.window_full {
                        self.count_total[m] -= slot.0[m];
                    }
                    slot.0[m] = self.count_sum[m];
                }
                self.iwindow += 1;
                if self.iwindow == w {
                    self.iwindow = 0;
                    self.window_full = true;
                }
                self.norm = if self.window_full { w } else { self.iwindow };
            }
        }
    }

    /// One output block: `step nbins`, then per bin its number, centre, count and values
    /// (`%g`), each divided by the number of averages combined.
    fn write(&mut self, step: i64) -> Result<(), EngineError> {
        let Some((file, header_end)) = &mut self.file else {
            return Ok(());
        };
        let g = |v: f64| crate::util::format::g(v);
        let norm = self.norm as f64;
        let mut text = String::new();
        if self.set.write_ts {
            text.push_str(&format!("{step} {}\n", self.coord.len()));
        }
        for (m, c) in self.coord.iter().enumerate() {
            text.push_str(&format!("  {}", m + 1));
            for x in c {
                text.push_str(&format!(" {}", g(*x)));
            }
            text.push_str(&format!(" {}", g(self.count_total[m] / norm)));
            for v in &self.values_total[m] {
                text.push_str(&format!(" {}", g(v / norm)));
            }
            text.push('\n');
        }
        crate::engine::ave_histo::write_block(file, *header_end, self.set.overwrite, &text)
            .map_err(|e| EngineError::Invalid(format!("fix ave/spatial file: {e}")))
    }
}

impl FixStyle for AveSpatial {
    fn name(&self) -> &str {
        "ave/spatial"
    }

    fn reads_computes(&self) -> bool {
        true
    }

    fn array_unsupported(&self) -> bool {
        true
    }

    fn end_of_step_sim_due(&self, step: i64) -> bool {
        self.nvalid == step
    }

    fn end_of_step_sim(
        &mut self,
        sim: &mut Simulation,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let group = sim.fixes[k].group;
        sim.ave_spatial_sample(self, group, vars)
    }

    fn setup_pass(&self) -> Option<SetupPass> {
        Some(SetupPass::SpatialAverages)
    }

    /// The box check of running and window averages, a schedule left behind restarted
    /// (LIGGGHTS's `init`), the bins set up, then a sample if one is due now (its `setup`).
    fn setup_sim(
        &mut self,
        sim: &mut Simulation,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let (step, box_changes) = (sim.step, sim.domain.shrinks());
        if !self.set.reduced && box_changes && self.set.mode != AveMode::One {
            return Err("Fix ave/spatial settings invalid with changing box size".into());
        }
        if self.nvalid < step {
            self.irepeat = 0;
            self.nvalid = self.next_valid(step);
        }
        self.setup_bins(sim)?;
        if self.nvalid != step {
            return Ok(());
        }
        let group = sim.fixes[k].group;
        sim.ave_spatial_sample(self, group, vars)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bins_reach_past_both_faces_from_the_origin() {
        let mut sim = Simulation::default();
        sim.domain.create([0.0; 3], [0.03, 0.03, 0.04]);
        let set = SpatialSettings {
            schedule: (20, 2, 100),
            dims: vec![(0, Origin::Center, 0.25), (1, Origin::Coord(0.0031), 0.2)],
            values: vec![SpatialValue::V(0)],
            norm_sample: true,
            reduced: true,
            region: None,
            mode: AveMode::Running,
            overwrite: true,
            write_ts: true,
        };
        let mut a = AveSpatial::new(set, 0);
        // samples at 80 and 100, then every 100 steps
        assert_eq!(a.nvalid, 80);
        assert_eq!(a.next_valid(100), 180);
        a.setup_bins(&sim).unwrap();
        // x: 4 layers from 0 (centre 0.5 minus two widths); y: 6 from -0.1969 to 1.0031
        assert_eq!(a.nlayers, [4, 6]);
        assert_eq!(a.coord[0], [0.125, 0.0031 - 0.2 + 0.5 * 0.2]);
        assert_eq!(a.coord[23][0], 0.875);
        // reduced units: LIGGGHTS's densities come out 0
        assert_eq!(a.bin_volume, f64::INFINITY);
        // reduced position (0.6, 0.95): x layer 2, y layer 5 (from -0.1969)
        assert_eq!(a.bin_of(&sim, [0.6, 0.95, 0.5]), 2 * 6 + 5);
    }
}
