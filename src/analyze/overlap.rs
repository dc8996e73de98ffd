//! Initial contact overlap against depth in the settled bed, beside the 1D-chain estimate
//! delta_0 = 2 (3 (1 - nu^2) F_0 / (4 E))^(2/3) / R^(1/3) with F_0 = rho phi z pi R^2 g, and the
//! sound-speed estimate c_0^2 = E (2R)^(1/2) delta_0^(1/2) 6 R^2 / (3 (1 - nu^2) m), scaled
//! by sqrt(3)/2 (SCENES.md, scene B).

use std::collections::HashMap;

use super::chain::Material;
use super::fit::mean_std;
use super::series::Frame;
use super::AnalyzeError;
use crate::io::diff::read_text;
use crate::io::dump_compare::parse;

/// Bed constants for the estimates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bed {
    /// Particle material.
    pub material: Material,
    /// Particle radius (m).
    pub radius: f64,
    /// Solid volume fraction.
    pub packing: f64,
    /// Gravity (m/s2).
    pub gravity: f64,
}

impl Bed {
    /// The 1D-chain overlap at `depth` below the surface (m).
    pub fn delta0(&self, depth: f64) -> f64 {
        let m = &self.material;
        let r = self.radius;
        let f0 = m.density * self.packing * depth * std::f64::consts::PI * r * r * self.gravity;
        2.0 * (3.0 * (1.0 - m.poisson.powi(2)) * f0 / (4.0 * m.youngs)).powf(2.0 / 3.0)
            / r.powf(1.0 / 3.0)
    }

    /// The sound-speed estimate for a contact overlap `delta` (m/s), with the sqrt(3)/2 factor.
    pub fn sound_speed(&self, delta: f64) -> f64 {
        let m = &self.material;
        let r = self.radius;
        let mass = m.density * 4.0 / 3.0 * std::f64::consts::PI * r.powi(3);
        let c2 = m.youngs * (2.0 * r).sqrt() * delta.sqrt() * 6.0 * r * r
            / (3.0 * (1.0 - m.poisson.powi(2)) * mass);
        c2.sqrt() * 3f64.sqrt() / 2.0
    }
}

/// One depth bin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthBin {
    /// Bin centre below the surface (m).
    pub depth: f64,
    /// Mean measured overlap of the contacts in the bin (m); NaN if none.
    pub measured: f64,
    /// Contacts in the bin.
    pub contacts: usize,
    /// The 1D-chain estimate at the bin centre (m).
    pub estimate: f64,
}

/// The profile and the sound-speed estimates.
#[derive(Debug, Clone, PartialEq)]
pub struct OverlapProfile {
    /// Bins from the surface down.
    pub bins: Vec<DepthBin>,
    /// Sound-speed estimate from the chain overlap averaged over the bed's depth (m/s).
    pub c0_chain: f64,
    /// Sound-speed estimate from the mean measured overlap (m/s), if contacts were given.
    pub c0_measured: Option<f64>,
}

/// Contact overlaps (m) by the mid-height z of each pair (m), from a `dump local` of
/// `compute pair/gran/local` (ids in `id_cols`, overlap in `delta_col`, None: the last
/// column) and the positions
/// of the same step.
pub fn contact_depths(
    file: &str,
    positions: &Frame,
    id_cols: (usize, usize),
    delta_col: Option<usize>,
) -> Result<Vec<(f64, f64)>, AnalyzeError> {
    let text = read_text(file).map_err(|e| AnalyzeError::Read(e.to_string()))?;
    let snaps = parse(&text).map_err(|m| AnalyzeError::Read(format!("{file}: {m}")))?;
    let snap = snaps
        .iter()
        .find(|s| s.step == positions.step)
        .or(snaps.first())
        .ok_or_else(|| AnalyzeError::Read(format!("{file}: no entries")))?;
    let (id, z) = (positions.col(&["id"])?, positions.xyz()?[2]);
    let zs: HashMap<i64, f64> = positions
        .rows
        .iter()
        .map(|r| (r[id] as i64, r[z]))
        .collect();
    let mut out = Vec::new();
    for row in snap.rows.values() {
        let get = |c: usize| {
            row.get(c).copied().ok_or_else(|| {
                AnalyzeError::Read(format!(
                    "{file}: {} columns, column {} wanted",
                    row.len(),
                    c + 1
                ))
            })
        };
        let dc = delta_col.unwrap_or(row.len().saturating_sub(1));
        let (a, b, d) = (get(id_cols.0)? as i64, get(id_cols.1)? as i64, get(dc)?);
        if let (Some(za), Some(zb)) = (zs.get(&a), zs.get(&b)) {
            out.push((0.5 * (za + zb), d));
        }
    }
    Ok(out)
}

/// Bin overlaps by depth below `surface` in bins of `bin` (m), down to `surface`.
pub fn profile(contacts: &[(f64, f64)], surface: f64, bin: f64, bed: &Bed) -> OverlapProfile {
    let nbins = ((surface / bin).ceil() as usize).max(1);
    let mut sums = vec![(0.0, 0usize); nbins];
    for &(z, d) in contacts {
        let k = ((surface - z) / bin).floor();
        if k >= 0.0 && (k as usize) < nbins {
            sums[k as usize].0 += d;
            sums[k as usize].1 += 1;
        }
    }
    let bins: Vec<DepthBin> = sums
        .iter()
        .enumerate()
        .map(|(k, &(s, n))| {
            let depth = (k as f64 + 0.5) * bin;
            DepthBin {
                depth,
                measured: if n > 0 { s / n as f64 } else { f64::NAN },
                contacts: n,
                estimate: bed.delta0(depth),
            }
        })
        .collect();
    let chain: Vec<f64> = bins.iter().map(|b| bed.sound_speed(b.estimate)).collect();
    let measured: Vec<f64> = contacts.iter().map(|c| c.1).filter(|d| *d > 0.0).collect();
    OverlapProfile {
        c0_chain: mean_std(&chain).map_or(0.0, |m| m.0),
        c0_measured: mean_std(&measured).map(|m| bed.sound_speed(m.0)),
        bins,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bed() -> Bed {
        Bed {
            material: Material::SOFT,
            radius: 0.00125,
            packing: 0.6,
            gravity: 1.625,
        }
    }

    #[test]
    fn chain_estimate_follows_hertz() {
        let b = bed();
        // delta_0 grows as depth^(2/3)
        let ratio = b.delta0(0.16) / b.delta0(0.02);
        assert!((ratio - 8f64.powf(2.0 / 3.0)).abs() < 1e-12);
        // at 20 cm: F_0 = 2.393e-3 N, delta_0 = 9.13 um, c_0 = 9.49 m/s
        let d = b.delta0(0.2);
        assert!((d - 9.126e-6).abs() < 1e-8, "{d}");
        let c = b.sound_speed(d);
        assert!((c - 9.49).abs() < 0.01, "{c}");
        // c_0 grows as delta^(1/4)
        assert!((b.sound_speed(16.0 * d) / c - 2.0).abs() < 1e-12);
    }

    #[test]
    fn contacts_are_binned_by_depth() {
        let p = profile(
            &[(0.029, 1e-6), (0.028, 3e-6), (0.011, 5e-6)],
            0.03,
            0.005,
            &bed(),
        );
        assert_eq!(p.bins.len(), 6);
        assert_eq!(p.bins[0].contacts, 2);
        assert!((p.bins[0].measured - 2e-6).abs() < 1e-18);
        assert_eq!(p.bins[3].contacts, 1);
        assert!(p.bins[1].measured.is_nan());
        assert!(p.c0_measured.unwrap() > 0.0 && p.c0_chain > 0.0);
    }
}
