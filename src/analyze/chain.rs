//! The struck chain (SCENES.md, scene A): the peak force of every particle along the struck
//! column, the time of that peak (the wave's arrival), and the wave speed c_w fitted to
//! distance from the struck end against arrival time; over a sweep of impact speeds, c_w
//! against v_im with its power-law exponent (1/5 for Hertz shocks) and the weak-impact sound
//! speed.

use std::collections::BTreeMap;

use super::fit::{fit_line, fit_power, mean_std, LineFit, PowerFit};
use super::series::{norm, Series};
use super::AnalyzeError;

/// Settings of the single-run analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainOptions {
    /// The column's axis: 0 x, 1 y, 2 z.
    pub axis: usize,
    /// Atom type of the striker (left out of the column; its start marks the struck end).
    pub striker_type: i64,
    /// Layer spacing along the axis (m); None: estimated from the initial positions.
    pub spacing: Option<f64>,
    /// Layers next to the struck end left out of the fit (the shock forms there).
    pub skip_first: usize,
    /// Layers at the far (free) end left out of the fit.
    pub skip_last: usize,
    /// Layers whose peak force is below this fraction of the largest are left out.
    pub min_peak_fraction: f64,
}

impl Default for ChainOptions {
    fn default() -> Self {
        ChainOptions {
            axis: 2,
            striker_type: 2,
            spacing: None,
            skip_first: 2,
            skip_last: 1,
            min_peak_fraction: 0.01,
        }
    }
}

/// One particle's record.
#[derive(Debug, Clone, PartialEq)]
pub struct ParticlePeak {
    /// Atom ID.
    pub id: i64,
    /// Distance from the struck end along the axis at the first frame (m).
    pub distance: f64,
    /// Largest |f| over the run (N).
    pub peak_force: f64,
    /// Time of that peak (s).
    pub peak_time: f64,
}

/// One layer of the column: its strongest particle's peak.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    /// Layer number from the struck end (0 = struck layer).
    pub index: usize,
    /// Distance from the struck end (m).
    pub distance: f64,
    /// Peak force (N).
    pub peak_force: f64,
    /// Arrival time: the time of the peak (s).
    pub arrival: f64,
    /// Used in the wave-speed fit.
    pub fitted: bool,
}

/// The result of one run.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainResult {
    /// Per particle.
    pub particles: Vec<ParticlePeak>,
    /// Per layer.
    pub layers: Vec<Layer>,
    /// Distance (m) against arrival (s): the slope is c_w (m/s).
    pub fit: LineFit,
    /// Time of the first and last frame (s).
    pub span: (f64, f64),
}

/// Analyse one run's dumps (columns id type x y z fx fy fz).
pub fn analyze(series: &Series, o: &ChainOptions) -> Result<ChainResult, AnalyzeError> {
    // id -> (type, initial axis coordinate, peak force, time of peak)
    let mut atoms: BTreeMap<i64, (i64, f64, f64, f64)> = BTreeMap::new();
    let mut span = (f64::INFINITY, f64::NEG_INFINITY);
    series.for_each(|fr| {
        let (id, ty) = (fr.col(&["id"])?, fr.col(&["type"])?);
        let (pos, f) = (fr.xyz()?[o.axis], fr.force()?);
        span = (span.0.min(fr.time), span.1.max(fr.time));
        for r in &fr.rows {
            let e = atoms
                .entry(r[id] as i64)
                .or_insert((r[ty] as i64, r[pos], -1.0, fr.time));
            let fm = norm(r, f);
            if fm > e.2 {
                e.2 = fm;
                e.3 = fr.time;
            }
        }
        Ok(())
    })?;
    let striker: Vec<f64> = atoms
        .values()
        .filter(|a| a.0 == o.striker_type)
        .map(|a| a.1)
        .collect();
    let coords: Vec<f64> = atoms
        .values()
        .filter(|a| a.0 != o.striker_type)
        .map(|a| a.1)
        .collect();
    if coords.is_empty() {
        return Err(AnalyzeError::Fit("no column particles in the dumps".into()));
    }
    let lo = coords.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = coords.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    // the struck end is the column end nearest the striker (the top if there is none)
    let end = match striker.first() {
        Some(&s) if (s - lo).abs() < (s - hi).abs() => lo,
        _ => hi,
    };
    let spacing = match o.spacing {
        Some(s) => s,
        None => estimate_spacing(&coords)?,
    };
    let particles: Vec<ParticlePeak> = atoms
        .iter()
        .filter(|(_, a)| a.0 != o.striker_type)
        .map(|(&id, a)| ParticlePeak {
            id,
            distance: (a.1 - end).abs(),
            peak_force: a.2.max(0.0),
            peak_time: a.3,
        })
        .collect();
    let layers = layers_of(&particles, spacing, o, span.1);
    let pts: Vec<(f64, f64)> = layers
        .iter()
        .filter(|l| l.fitted)
        .map(|l| (l.arrival, l.distance))
        .collect();
    let fit = fit_line(&pts).map_err(|e| {
        AnalyzeError::Fit(format!(
            "wave speed: {e} (layers reached by the wave before the last frame: the run may be too short)"
        ))
    })?;
    Ok(ChainResult {
        particles,
        layers,
        fit,
        span,
    })
}

/// The typical gap between distinct layer coordinates (m).
fn estimate_spacing(coords: &[f64]) -> Result<f64, AnalyzeError> {
    let mut c = coords.to_vec();
    c.sort_by(f64::total_cmp);
    let range = c[c.len() - 1] - c[0];
    let mut gaps: Vec<f64> = c
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|g| *g > 1e-6 * range)
        .collect();
    if gaps.is_empty() {
        return Err(AnalyzeError::Fit("the column has a single layer".into()));
    }
    gaps.sort_by(f64::total_cmp);
    Ok(gaps[gaps.len() / 2])
}

fn layers_of(ps: &[ParticlePeak], spacing: f64, o: &ChainOptions, t_last: f64) -> Vec<Layer> {
    let mut by_layer: BTreeMap<usize, &ParticlePeak> = BTreeMap::new();
    for p in ps {
        let k = (p.distance / spacing).round() as usize;
        let e = by_layer.entry(k).or_insert(p);
        if p.peak_force > e.peak_force {
            *e = p;
        }
    }
    let fmax = by_layer.values().map(|p| p.peak_force).fold(0.0, f64::max);
    let nlayers = by_layer.keys().max().map_or(0, |k| k + 1);
    by_layer
        .into_iter()
        .map(|(k, p)| Layer {
            index: k,
            distance: k as f64 * spacing,
            peak_force: p.peak_force,
            arrival: p.peak_time,
            fitted: k >= o.skip_first
                && k + o.skip_last < nlayers
                && p.peak_force > o.min_peak_fraction * fmax
                && p.peak_time < t_last,
        })
        .collect()
}

/// Material constants for the sound speed and the Hertz elastic limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus (Pa).
    pub youngs: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Density (kg/m3).
    pub density: f64,
}

impl Material {
    /// The study's soft beads (E 5e6 Pa, nu 0.2, 2500 kg/m3).
    pub const SOFT: Material = Material {
        youngs: 5e6,
        poisson: 0.2,
        density: 2500.0,
    };
    /// The study's steel beads (E 2.1e11 Pa, nu 0.28, 7870 kg/m3).
    pub const STEEL: Material = Material {
        youngs: 2.1e11,
        poisson: 0.28,
        density: 7870.0,
    };

    /// Bulk (P-wave) sound speed of the solid, sqrt((1-nu) E / ((1+nu)(1-2nu) rho)) (m/s).
    pub fn sound_speed(&self) -> f64 {
        let nu = self.poisson;
        ((1.0 - nu) * self.youngs / ((1.0 + nu) * (1.0 - 2.0 * nu) * self.density)).sqrt()
    }

    /// Impact speed above which Hertz theory no longer holds: 0.02 % of c_m (m/s).
    pub fn elastic_limit(&self) -> f64 {
        2e-4 * self.sound_speed()
    }
}

/// One impact speed of a sweep: c_w over its runs.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepPoint {
    /// Impact speed (m/s).
    pub v_im: f64,
    /// Mean wave speed over the runs (m/s).
    pub c_w: f64,
    /// Uncertainty: the spread over runs, or the fit's standard error for one run (m/s).
    pub c_w_err: f64,
    /// Runs at this speed.
    pub runs: usize,
    /// Above the Hertz elastic limit (outside Hertz theory).
    pub above_limit: bool,
}

/// The sweep: c_w against v_im.
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    /// Per impact speed, ascending.
    pub points: Vec<SweepPoint>,
    /// Power law c_w = A v_im^p over the strong impacts (v_im above `weak_max`).
    pub power: Option<PowerFit>,
    /// Weak-impact speed: mean and spread of c_w for v_im <= `weak_max` (m/s).
    pub sound_speed: Option<(f64, f64)>,
    /// Power law over the weak impacts: an exponent near 0 is a sound speed; near 0.2, the
    /// weak impacts are Hertz shocks too (a chain without precompression).
    pub weak_power: Option<PowerFit>,
    /// The weak-impact bound used (m/s).
    pub weak_max: f64,
    /// The elastic limit (m/s).
    pub elastic_limit: f64,
}

/// Combine runs (v_im, fit) into the sweep.
pub fn sweep(runs: &[(f64, LineFit)], weak_max: f64, material: &Material) -> Sweep {
    let mut by_v: BTreeMap<u64, Vec<&LineFit>> = BTreeMap::new();
    for (v, f) in runs {
        by_v.entry(v.to_bits()).or_default().push(f);
    }
    let limit = material.elastic_limit();
    let mut points: Vec<SweepPoint> = by_v
        .iter()
        .map(|(bits, fits)| {
            let v = f64::from_bits(*bits);
            let speeds: Vec<f64> = fits.iter().map(|f| f.slope).collect();
            let (m, s) = mean_std(&speeds).unwrap_or((0.0, 0.0));
            SweepPoint {
                v_im: v,
                c_w: m,
                c_w_err: if fits.len() > 1 { s } else { fits[0].slope_err },
                runs: fits.len(),
                above_limit: v > limit,
            }
        })
        .collect();
    points.sort_by(|a, b| a.v_im.total_cmp(&b.v_im));
    let strong: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.v_im > weak_max)
        .map(|p| (p.v_im, p.c_w))
        .collect();
    let weak_points: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.v_im <= weak_max)
        .map(|p| (p.v_im, p.c_w))
        .collect();
    let weak: Vec<f64> = weak_points.iter().map(|p| p.1).collect();
    Sweep {
        power: fit_power(&strong).ok(),
        weak_power: fit_power(&weak_points).ok(),
        sound_speed: mean_std(&weak),
        points,
        weak_max,
        elastic_limit: limit,
    }
}

#[cfg(test)]
mod tests;
