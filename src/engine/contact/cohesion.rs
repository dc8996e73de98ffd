//! Cohesion models (`cohesion off | sjkr | sjkr2`): an attractive normal force
//! `Fn_coh = -k A`, k the cohesionEnergyDensity (J/m^3) and A a contact area (m^2).
//! Both act only while the surfaces overlap (LIGGGHTS 3.8.0's `surfacesClose` of sjkr and
//! sjkr2 only clears a flag, so neither attracts across a gap).

use std::f64::consts::PI;

use super::material::{Coeffs, Property};
use super::real::Real;
use super::Contact;

/// A cohesion model adds an attractive normal force after the normal model ran.
pub trait CohesionModel: Send + Sync + Copy + 'static {
    /// Doubles of per-contact history the model keeps.
    const HISTORY_LEN: usize = 0;
    /// Add the cohesive force of a touching contact.
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>);
    /// The coefficients the model needs, with LIGGGHTS's caller name.
    fn properties(&self, out: &mut Vec<(Property, &'static str)>);
}

/// `cohesion off`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoCohesion;

impl CohesionModel for NoCohesion {
    #[inline(always)]
    fn surfaces_intersect<S: Real>(&self, _: &mut Contact<S>, _: &impl Coeffs<S>) {}
    fn properties(&self, _: &mut Vec<(Property, &'static str)>) {}
}

/// Add `fn_coh en` to i (and subtract it from j); with `reduce` also add it to Fn.
#[inline(always)]
fn apply<S: Real>(c: &mut Contact<S>, fn_coh: S, reduce: bool) {
    if reduce {
        c.normal_force += fn_coh;
    }
    let en = c.en;
    if c.is_wall {
        for d in 0..3 {
            c.fi[d] += fn_coh * en[d];
        }
    } else {
        let f = [fn_coh * en[0], fn_coh * en[1], fn_coh * en[2]];
        for d in 0..3 {
            c.fi[d] += f[d];
        }
        for d in 0..3 {
            c.fj[d] -= f[d];
        }
    }
}

/// `cohesion sjkr`: A is the area of the lens where the two spheres intersect,
/// A = -pi/4 (r - Ri - Rj)(r + Ri - Rj)(r - Ri + Rj)(r + Ri + Rj) / r^2, and
/// A = pi (R^2 - r^2) at a wall (r = centre-wall distance).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Sjkr {
    /// `tangential_reduce` (default off): add Fn_coh to Fn, lowering the Coulomb limit
    /// mu |Fn| and the rolling torque limit.
    pub tangential_reduce: bool,
}

impl CohesionModel for Sjkr {
    #[inline(always)]
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>) {
        let r = c.r;
        let ri = c.radi;
        let rj = c.radj;
        let acont = if c.is_wall {
            (ri * ri - r * r) * S::splat(PI)
        } else {
            S::splat(-PI / 4.0) * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj))
                / (r * r)
        };
        let fn_coh = -m.get(|k| k.cohesion_energy_density) * acont;
        apply(c, fn_coh, self.tangential_reduce);
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::CohEnergyDens, "cohesion_model sjkr"));
    }
}

/// `cohesion sjkr2`: A = 2 pi (2 R*) d for pairs (R* = Ri Rj / (Ri + Rj), d the overlap;
/// twice the lens area of sjkr for small d) but A = 2 pi R (R - r) at a wall, exactly as
/// LIGGGHTS 3.8.0 writes them.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Sjkr2 {
    /// `tangential_reduce` (default off): add Fn_coh to Fn.
    pub tangential_reduce: bool,
}

impl CohesionModel for Sjkr2 {
    #[inline(always)]
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>) {
        let r = c.r;
        let ri = c.radi;
        let rj = c.radj;
        let acont = if c.is_wall {
            S::splat(PI * 2.) * ri * (ri - r)
        } else {
            S::splat(PI * 2.) * (S::splat(2.) * ri * rj / (ri + rj)) * (ri + rj - r)
        };
        let fn_coh = -m.get(|k| k.cohesion_energy_density) * acont;
        apply(c, fn_coh, self.tangential_reduce);
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::CohEnergyDens, "cohesion_model sjkr2"));
    }
}

/// Any cohesion model, chosen at run time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyCohesion {
    /// `cohesion off`.
    Off(NoCohesion),
    /// `cohesion sjkr`.
    Sjkr(Sjkr),
    /// `cohesion sjkr2`.
    Sjkr2(Sjkr2),
}

impl CohesionModel for AnyCohesion {
    #[inline]
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>) {
        match self {
            AnyCohesion::Off(_) => {}
            AnyCohesion::Sjkr(x) => x.surfaces_intersect(c, m),
            AnyCohesion::Sjkr2(x) => x.surfaces_intersect(c, m),
        }
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        match self {
            AnyCohesion::Off(_) => {}
            AnyCohesion::Sjkr(x) => x.properties(out),
            AnyCohesion::Sjkr2(x) => x.properties(out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::contact::material::PairCoeffs;

    fn pair(ri: f64, rj: f64, r: f64) -> Contact {
        Contact {
            radi: ri,
            radj: rj,
            r,
            en: [1.0, 0.0, 0.0],
            normal_force: 10.0,
            ..Contact::default()
        }
    }

    #[test]
    fn sjkr_force_is_energy_density_times_lens_area() {
        let (ri, rj, r) = (0.01_f64, 0.015_f64, 0.0245_f64);
        // radius a of the intersection circle of two spheres at distance r
        let x = (r * r - rj * rj + ri * ri) / (2.0 * r);
        let a2 = ri * ri - x * x;
        let area = PI * a2;
        let m = PairCoeffs {
            cohesion_energy_density: 3e5,
            ..PairCoeffs::default()
        };
        let mut c = pair(ri, rj, r);
        Sjkr::default().surfaces_intersect(&mut c, &m);
        let expect = -3e5 * area;
        assert!(
            (c.fi[0] - expect).abs() < 1e-9 * expect.abs(),
            "{} {}",
            c.fi[0],
            expect
        );
        assert_eq!(c.fj[0], -c.fi[0]);
        assert_eq!(c.normal_force, 10.0);
        // tangential_reduce lowers Fn by the same amount
        let mut c = pair(ri, rj, r);
        Sjkr {
            tangential_reduce: true,
        }
        .surfaces_intersect(&mut c, &m);
        assert!((c.normal_force - (10.0 + expect)).abs() < 1e-12);
        // sjkr2: 2 pi (2 R*) d
        let mut c = pair(ri, rj, r);
        Sjkr2::default().surfaces_intersect(&mut c, &m);
        let rstar = ri * rj / (ri + rj);
        let expect2 = -3e5 * 2.0 * PI * 2.0 * rstar * (ri + rj - r);
        assert!((c.fi[0] - expect2).abs() < 1e-9 * expect2.abs());
    }

    #[test]
    fn sjkr_wall_area_is_the_cap_circle() {
        let m = PairCoeffs {
            cohesion_energy_density: 1e5,
            ..PairCoeffs::default()
        };
        let mut c = Contact {
            is_wall: true,
            radi: 0.01,
            r: 0.0096,
            en: [0.0, 0.0, 1.0],
            ..Contact::default()
        };
        Sjkr::default().surfaces_intersect(&mut c, &m);
        let a = PI * (0.01f64 * 0.01 - 0.0096 * 0.0096);
        assert!((c.fi[2] + 1e5 * a).abs() < 1e-9 * 1e5 * a);
        assert_eq!(c.fj, [0.0; 3]);
    }
}
