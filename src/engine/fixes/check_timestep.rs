//! `fix check/timestep/gran`: the time step against the Rayleigh and Hertz times.

use crate::engine::error::EngineError;
use crate::engine::fixes::PairInit;
use crate::engine::particles::Particles;

/// Where LIGGGHTS 3.8.0 raises this fix's warnings; each warning ends with it and the line.
const SOURCE: &str = "./src/fix_check_timestep_gran.cpp";

/// `fix check/timestep/gran N rayleigh_limit hertz_limit [warn yes|no] [error yes|no] [vmax V]`.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckTimestep {
    /// The fix ID (thermo reads its values as `f_ID[N]`).
    pub id: String,
    /// Check every this many steps (at the end of the step).
    pub every: i64,
    /// Warn above this fraction of the Rayleigh time.
    pub rayleigh_limit: f64,
    /// Warn above this fraction of the Hertz time.
    pub hertz_limit: f64,
    /// Print warnings.
    pub warn: bool,
    /// Stop with an error instead.
    pub error: bool,
    /// A velocity (length/time) assumed at least for the Hertz estimate.
    pub vmax_user: f64,
    /// dt / Rayleigh time, dt / Hertz time, relative travel per step / skin (f_ID[1..3]).
    pub values: [f64; 3],
    /// Per type (1-based index - 1): Young's modulus, Poisson ratio, and Yeff of the type with itself.
    pub materials: Vec<(f64, f64, f64)>,
    /// The warnings of the last check, not yet printed.
    pub warnings: Vec<String>,
}

impl CheckTimestep {
    /// LIGGGHTS's init: a granular pair style, Young's moduli and Poisson ratios per type
    /// (each type's own effective modulus kept), and a thermo interval its values fit.
    pub fn init_pair(&mut self, pair: &PairInit) -> Result<(), EngineError> {
        use crate::engine::contact::material::mix_yeff;
        if !pair.pair_gran {
            return Err("Fix check/timestep/gran can only be used together with: gran".into());
        }
        let missing = |name: &str| {
            format!("Could not locate a fix/property storing value(s) for {name} as requested by fix check/timestep/gran.")
        };
        let input = pair.materials;
        let youngs = input
            .youngs_modulus
            .as_ref()
            .ok_or_else(|| missing("youngsModulus"))?;
        let poisson = input
            .poissons_ratio
            .as_ref()
            .ok_or_else(|| missing("poissonsRatio"))?;
        let n = input.ntypes;
        if youngs.len() < n || poisson.len() < n {
            return Err("fix check/timestep/gran: youngsModulus and poissonsRatio need one value per atom type".into());
        }
        let materials = (0..n)
            .map(|t| {
                let (y, nu) = (youngs[t], poisson[t]);
                (y, nu, mix_yeff(y, y, nu, nu))
            })
            .collect();
        let prefix = format!("f_{}", self.id);
        let in_thermo = pair.thermo_keywords.iter().any(|k| k.starts_with(&prefix));
        if in_thermo && pair.thermo_every % self.every != 0 {
            return Err("Thermo and fix not computed at compatible times".into());
        }
        self.materials = materials;
        Ok(())
    }

    /// LIGGGHTS's estimates, with `mesh_vmax_sqr` the largest squared speed of a moving
    /// mesh's nodes (length^2/time^2); returns the warnings to print.
    pub fn evaluate(
        &mut self,
        p: &Particles,
        group: u32,
        dt: f64,
        skin: f64,
        mesh_vmax_sqr: f64,
    ) -> Vec<String> {
        self.evaluate_over_ranks(p, group, dt, skin, mesh_vmax_sqr, &|_: &mut [f64]| {})
    }

    /// [`Self::evaluate`] over this rank's particles, the extremes taken over all ranks with
    /// `min` (each value of a slice replaced by its minimum over the ranks), as LIGGGHTS
    /// reduces them: the same values as one process over all particles.
    pub fn evaluate_over_ranks(
        &mut self,
        p: &Particles,
        group: u32,
        dt: f64,
        skin: f64,
        mesh_vmax_sqr: f64,
        min: &dyn Fn(&mut [f64]),
    ) -> Vec<String> {
        const BIG: f64 = 1.0e20;
        let mut rayleigh = BIG;
        let mut r_min = BIG;
        let mut vmax_sqr: f64 = 0.0;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let rad = p.radius[i];
            let (y, nu, _) = self.materials[p.kind[i] as usize - 1];
            let shear = y / (2. * (nu + 1.));
            let t =
                std::f64::consts::PI * rad * (p.density[i] / shear).sqrt() / (0.1631 * nu + 0.8766);
            if t < rayleigh {
                rayleigh = t;
            }
            let v = p.v[i];
            let vsq = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            if vsq > vmax_sqr {
                vmax_sqr = vsq;
            }
            if rad < r_min {
                r_min = rad;
            }
        }
        // the largest squared speed as the smallest of its negatives (exact)
        let mut extremes = [rayleigh, -vmax_sqr, r_min];
        min(&mut extremes);
        let (rayleigh, r_min) = (extremes[0], extremes[2]);
        vmax_sqr = -extremes[1];
        if self.vmax_user * self.vmax_user > vmax_sqr {
            vmax_sqr = self.vmax_user * self.vmax_user;
        }
        // particle-particle or particle-mesh contact, whichever is faster
        let v_rel = (2. * vmax_sqr.sqrt()).max(vmax_sqr.sqrt() + mesh_vmax_sqr.sqrt());
        let mut hertz: f64 = 1000000.;
        if (v_rel - 0.0).abs() >= 1e-13 {
            for ti in 1..=self.materials.len() {
                let eeff = self.materials[ti - 1].2;
                for i in 0..p.len() {
                    if p.mask[i] & group == 0 || p.kind[i] as usize != ti {
                        continue;
                    }
                    let r = p.radius[i];
                    let meff = 4. * r * r * r * std::f64::consts::PI / 3. * p.density[i];
                    let reff = r / 2.;
                    let t = 2.87 * (meff * meff / (reff * eeff * eeff * v_rel)).powf(0.2);
                    if t < hertz {
                        hertz = t;
                    }
                }
            }
        }
        let mut smallest = [hertz];
        min(&mut smallest);
        let hertz = smallest[0];
        self.values = [dt / rayleigh, dt / hertz, v_rel * dt / skin];
        let mut messages = Vec::new();
        if self.warn || self.error {
            if self.values[0] > self.rayleigh_limit {
                messages.push(format!(
                    "time-step is {} % of rayleigh time ({SOURCE}:200)",
                    crate::util::format::with_spec("%f", self.values[0] * 100.).unwrap_or_default()
                ));
            }
            if self.values[1] > self.hertz_limit {
                messages.push(format!(
                    "time-step is {} % of hertz time ({SOURCE}:208)",
                    crate::util::format::with_spec("%f", self.values[1] * 100.).unwrap_or_default()
                ));
            }
            if self.values[2] > 1.0 {
                messages.push(format!(
                    "time step too large or skin too small - particles may relatively travel a distance of {} per time-step, but skin is {} ({SOURCE}:217)",
                    crate::util::format::with_spec("%f", v_rel * dt).unwrap_or_default(),
                    crate::util::format::with_spec("%f", skin).unwrap_or_default()
                ));
            }
            if v_rel * dt > r_min {
                messages.push(format!("time step way too large - particles relativley move further than the minimum radius in one step ({SOURCE}:226)"));
            }
        }
        messages
    }
}
