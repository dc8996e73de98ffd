//! Cohesion models (`cohesion ...`).

use crate::engine::granular::material::Material;
use crate::engine::granular::Contact;

/// A cohesion model adds an attractive normal force to touching particles.
pub trait CohesionModel: Send + Sync {
    /// Check that the material tables it needs exist.
    fn check(m: &Material) -> Result<(), String>;
    /// Add the cohesive force.
    fn force(&self, c: &mut Contact, m: &Material);
}

/// No cohesion: no code runs and no coefficients are needed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NoCohesion;

impl CohesionModel for NoCohesion {
    fn check(_: &Material) -> Result<(), String> {
        Ok(())
    }

    #[inline(always)]
    fn force(&self, _: &mut Contact, _: &Material) {}
}

/// Simplified JKR (`cohesion sjkr`): F = -k A, with A the contact area of the overlapping
/// spheres (or sphere and wall) and k the cohesion energy density (energy/volume).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sjkr {
    /// `tangential_reduce on`: the cohesive force also lowers the friction limit.
    pub tangential_reduce: bool,
}

impl CohesionModel for Sjkr {
    fn check(m: &Material) -> Result<(), String> {
        m.require_cohesion("cohesion_model sjkr")
    }

    #[inline(always)]
    fn force(&self, c: &mut Contact, m: &Material) {
        let (r, ri, rj) = (c.r, c.radi, c.radj);
        let area = if c.wall {
            (ri * ri - r * r) * std::f64::consts::PI * 1.0
        } else {
            -std::f64::consts::PI / 4.0
                * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj))
                / (r * r)
        };
        let fn_coh = -m.cohesion(c.itype, c.jtype) * area;
        if self.tangential_reduce {
            c.fn_total += fn_coh;
        }
        let f = [fn_coh * c.en[0], fn_coh * c.en[1], fn_coh * c.en[2]];
        for d in 0..3 {
            c.fi[d] += f[d];
        }
        for d in 0..3 {
            c.fj[d] -= f[d];
        }
    }
}
