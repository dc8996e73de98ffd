//! The radial blast in a granular ring (SCENES.md, scene C): over time, the inner surface
//! R(theta) (the smallest r - radius per angular sector), its inner and outer radius and
//! relative amplitude, and the compaction front (where the outward radial velocity falls
//! below a fraction of its peak); at the last snapshot, the azimuthal Fourier spectrum of the
//! force field in annular bands, whose dominant mode gives the force-chain spacing.

use std::f64::consts::PI;

use super::fit::mean_std;
use super::series::{norm, Frame, Series};
use super::AnalyzeError;

/// Settings.
#[derive(Debug, Clone, PartialEq)]
pub struct RingOptions {
    /// Centre of the ring in the x-y plane (m).
    pub centre: (f64, f64),
    /// Angular sectors for R(theta).
    pub sectors: usize,
    /// The front is where the mean radial velocity drops below this fraction of its peak.
    pub front_fraction: f64,
    /// Annular bands of the spectrum, between the surface's outer radius and the ring's edge.
    pub bands: usize,
    /// Angular bins of the force field in each band.
    pub angular_bins: usize,
}

impl Default for RingOptions {
    fn default() -> Self {
        RingOptions {
            centre: (0.0, 0.0),
            sectors: 72,
            front_fraction: 0.1,
            bands: 3,
            angular_bins: 256,
        }
    }
}

/// The ring at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RingState {
    /// Time (s).
    pub t: f64,
    /// Inner radius of the disturbed surface: min over theta of R (m).
    pub r_in: f64,
    /// Outer radius of the disturbed surface: max over theta of R (m).
    pub r_out: f64,
    /// Mean of R(theta) (m).
    pub r_mean: f64,
    /// Relative amplitude (r_out - r_in) / (2 r_mean).
    pub amplitude: f64,
    /// Standard deviation of R(theta) over its mean.
    pub rms: f64,
    /// Compaction-front radius (m); NaN before anything moves.
    pub front: f64,
    /// Outer edge of the ring: max of r + radius (m).
    pub edge: f64,
}

/// The force spectrum of one band.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    /// Inner and outer radius (m).
    pub radii: (f64, f64),
    /// Power per azimuthal mode m = 1, 2, ... (N^2).
    pub power: Vec<f64>,
    /// The dominant mode.
    pub mode: usize,
    /// Arc length between force chains at the band's mid radius, 2 pi r / m (m).
    pub spacing: f64,
    /// The same in mean particle diameters.
    pub spacing_diameters: f64,
}

/// Everything measured on one run.
#[derive(Debug, Clone, PartialEq)]
pub struct RingResult {
    /// Per snapshot.
    pub states: Vec<RingState>,
    /// R(theta) at the last snapshot: (sector centre rad, R m).
    pub surface: Vec<(f64, f64)>,
    /// Force spectra at the last snapshot.
    pub bands: Vec<Band>,
    /// Mean particle diameter (m).
    pub diameter: f64,
}

/// The particles in polar form and the surface R(theta) of one snapshot.
type Snapshot = (Vec<Polar>, Vec<(f64, f64)>);

struct Polar {
    r: f64,
    theta: f64,
    radius: f64,
    vr: f64,
    force: f64,
}

fn polar(fr: &Frame, c: (f64, f64)) -> Result<Vec<Polar>, AnalyzeError> {
    let [x, y, _] = fr.xyz()?;
    let (vx, vy) = (fr.col(&["vx"])?, fr.col(&["vy"])?);
    let (f, rad) = (fr.force()?, fr.col(&["radius"])?);
    Ok(fr
        .rows
        .iter()
        .map(|w| {
            let (dx, dy) = (w[x] - c.0, w[y] - c.1);
            let r = (dx * dx + dy * dy).sqrt().max(1e-300);
            Polar {
                r,
                theta: dy.atan2(dx).rem_euclid(2.0 * PI),
                radius: w[rad],
                vr: (dx * w[vx] + dy * w[vy]) / r,
                force: norm(w, f),
            }
        })
        .collect())
}

fn surface(ps: &[Polar], sectors: usize) -> Vec<(f64, f64)> {
    let mut min = vec![f64::INFINITY; sectors];
    for p in ps {
        let k = ((p.theta / (2.0 * PI) * sectors as f64) as usize).min(sectors - 1);
        min[k] = min[k].min(p.r - p.radius);
    }
    min.iter()
        .enumerate()
        .filter(|(_, r)| r.is_finite())
        .map(|(k, &r)| ((k as f64 + 0.5) * 2.0 * PI / sectors as f64, r))
        .collect()
}

/// The radius where the mean radial velocity, binned by `dr` outward from `from`, first falls
/// below `fraction` of its peak beyond the peak's bin; NaN if nothing moves outward.
fn front(ps: &[Polar], from: f64, dr: f64, fraction: f64) -> f64 {
    let edge = ps.iter().map(|p| p.r).fold(from, f64::max);
    let n = (((edge - from) / dr).ceil() as usize).max(1);
    let mut sum = vec![(0.0, 0usize); n];
    for p in ps.iter().filter(|p| p.r >= from) {
        let k = (((p.r - from) / dr) as usize).min(n - 1);
        sum[k].0 += p.vr;
        sum[k].1 += 1;
    }
    let mean: Vec<f64> = sum
        .iter()
        .map(|s| if s.1 > 0 { s.0 / s.1 as f64 } else { 0.0 })
        .collect();
    let (peak_bin, peak) = mean
        .iter()
        .enumerate()
        .fold((0, 0.0), |b, (k, &v)| if v > b.1 { (k, v) } else { b });
    if peak <= 0.0 {
        return f64::NAN;
    }
    let below = (peak_bin..n)
        .find(|&k| mean[k] < fraction * peak)
        .unwrap_or(n);
    from + below as f64 * dr
}

/// The power of azimuthal modes 1..=bins/2 of `signal` sampled on `bins` equal angles.
pub fn azimuthal_power(signal: &[f64]) -> Vec<f64> {
    let n = signal.len();
    let mean = signal.iter().sum::<f64>() / n.max(1) as f64;
    (1..=n / 2)
        .map(|m| {
            let (mut re, mut im) = (0.0, 0.0);
            for (k, s) in signal.iter().enumerate() {
                let a = 2.0 * PI * (m * k) as f64 / n as f64;
                re += (s - mean) * a.cos();
                im -= (s - mean) * a.sin();
            }
            re * re + im * im
        })
        .collect()
}

fn bands(ps: &[Polar], from: f64, to: f64, o: &RingOptions, diameter: f64) -> Vec<Band> {
    let width = (to - from) / o.bands.max(1) as f64;
    (0..o.bands)
        .filter(|_| width > 0.0)
        .map(|b| {
            let (r0, r1) = (from + b as f64 * width, from + (b + 1) as f64 * width);
            let mut signal = vec![0.0; o.angular_bins];
            for p in ps.iter().filter(|p| p.r >= r0 && p.r < r1) {
                let k = (p.theta / (2.0 * PI) * o.angular_bins as f64) as usize;
                signal[k.min(o.angular_bins - 1)] += p.force;
            }
            let power = azimuthal_power(&signal);
            let mode = power
                .iter()
                .enumerate()
                .fold(
                    (0, -1.0),
                    |best, (k, &v)| if v > best.1 { (k, v) } else { best },
                )
                .0
                + 1;
            let spacing = 2.0 * PI * 0.5 * (r0 + r1) / mode as f64;
            Band {
                radii: (r0, r1),
                power,
                mode,
                spacing,
                spacing_diameters: spacing / diameter,
            }
        })
        .collect()
}

/// Analyse a blast run's dumps (id x y z vx vy fx fy fz radius).
pub fn analyze(series: &Series, o: &RingOptions) -> Result<RingResult, AnalyzeError> {
    let mut states = Vec::new();
    let mut last: Option<Snapshot> = None;
    let mut diameter = 0.0;
    series.for_each(|fr| {
        let ps = polar(&fr, o.centre)?;
        if ps.is_empty() {
            return Ok(());
        }
        diameter = 2.0 * ps.iter().map(|p| p.radius).sum::<f64>() / ps.len() as f64;
        let surf = surface(&ps, o.sectors.max(1));
        let rs: Vec<f64> = surf.iter().map(|s| s.1).collect();
        let (r_mean, r_std) = mean_std(&rs).unwrap_or((f64::NAN, 0.0));
        let r_in = rs.iter().copied().fold(f64::INFINITY, f64::min);
        let r_out = rs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        states.push(RingState {
            t: fr.time,
            r_in,
            r_out,
            r_mean,
            amplitude: (r_out - r_in) / (2.0 * r_mean),
            rms: r_std / r_mean,
            front: front(&ps, r_in, diameter, o.front_fraction),
            edge: ps.iter().map(|p| p.r + p.radius).fold(0.0, f64::max),
        });
        last = Some((ps, surf));
        Ok(())
    })?;
    let (ps, surface) = last.ok_or_else(|| AnalyzeError::Read("no particles".into()))?;
    let st = states[states.len() - 1];
    let bands = bands(&ps, st.r_out, st.edge, o, diameter);
    Ok(RingResult {
        states,
        surface,
        bands,
        diameter,
    })
}

#[cfg(test)]
mod tests;
