//! `cohesion easo/capillary/viscous`: a liquid bridge between wet particles (LIGGGHTS
//! 3.8.0). A bridge forms when two surfaces touch and lasts, across a gap, until the gap
//! exceeds its rupture distance; while it exists it pulls with a capillary force (Soulié et
//! al. 2006, eqs. 13-14) and damps with a viscous force (lubrication, Nase et al. as cited by
//! Shi and McCarthy 2008, eqs. 40-41). When it breaks, its liquid is split between the two
//! particles in proportion to their volumes, which changes their `surfaceLiquidContent`
//! through a per-atom flux (integrated like `fix transportequation/scalar`).
//!
//! Walls are dry: a wall bridge holds half the particle's film (j's radius is taken as
//! i's) and its rupture moves no liquid.
//!
//! Volumes carry LIGGGHTS's factor 1000 (`volBond1000`): the film volume of a particle is
//! `4/3 * 1000 * pi R^3 * content`. Every expression keeps LIGGGHTS's association and
//! constants (`1333.333333`, `0.5333333`), so results are bit-identical.
//!
//! Per contact the model keeps one history value, the bridge flag (1 while a bridge
//! exists, 0 otherwise).
//!
//! The engine runs it in `pair_style gran` ([`crate::engine::granular::wet`]): the
//! neighbour list's contact distance scaled by [`Easo::contact_distance_factor`] (pairs
//! listed up to `factor (Ri + Rj) + skin`); [`Easo::close`] (and the dry models' history
//! reset) for listed pairs with `(Ri + Rj)^2 <= rsq < factor^2 (Ri + Rj)^2`; the bridge flag
//! stored after the normal model's history and before the tangential one; per-atom
//! `surfaceLiquidContent` (default `surfaceLiquidContentInitial`, written to restart files)
//! and `liquidFlux` ([`crate::engine::wet`]), the flux cleared in `initial_integrate` and
//! `content += flux dt` in `final_integrate`, as `fix transportequation/scalar` does (no
//! capacity). Walls are refused: LIGGGHTS 3.8.0's manual allows the model in `pair gran`
//! only, and its primitive walls crash once a wall bridge is apart.

use std::f64::consts::PI;

use super::Vec3;

/// `4/3 * 1000`, as LIGGGHTS writes it.
const FOUR_THIRDS_1000: f64 = 1333.333333;
/// `8/15`, as LIGGGHTS writes it.
const EIGHT_FIFTEENTHS: f64 = 0.5333333;
/// Bridges with less liquid than this (x1000, m^3) exert no force.
const MIN_BOND_VOLUME: f64 = 1e-14;

/// The global coefficients of `easo/capillary/viscous`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Easo {
    /// `surfaceTension` (N/m).
    pub surface_tension: f64,
    /// `fluidViscosity` (Pa s).
    pub fluid_viscosity: f64,
    /// `minSeparationDistanceRatio` (gap / effective radius below which lubrication stops
    /// growing; dimensionless).
    pub min_separation: f64,
    /// `maxSeparationDistanceRatio` (>= 1; a bridge always breaks once the gap exceeds
    /// (ratio - 1) (Ri + Rj)).
    pub max_separation: f64,
    /// `tangential_reduce` (default off): add the normal wet force to Fn in touching
    /// contacts.
    pub tangential_reduce: bool,
}

/// One wet pair (or particle and dry wall) as the bridge sees it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WetPair {
    /// The other side is a wall (dry; j's radius taken as i's).
    pub is_wall: bool,
    /// Radius of i (m).
    pub radi: f64,
    /// Radius of j (m; i's radius again at a wall).
    pub radj: f64,
    /// LIGGGHTS's `radsum`: radi + radj for pairs, radi at a wall (m).
    pub radsum: f64,
    /// `surfaceLiquidContent` of i (dimensionless, LIGGGHTS's per-atom value).
    pub liquid_i: f64,
    /// `surfaceLiquidContent` of j (ignored at a wall).
    pub liquid_j: f64,
    /// The effective contact angle of the two types, see [`effective_contact_angle`].
    pub contact_angle: f64,
    /// Share of a mesh element's contact (1 for pairs and primitive walls).
    pub area_ratio: f64,
}

/// The liquid held in a bridge (x1000, m^3).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Bond {
    /// Part from i's film.
    pub from_i: f64,
    /// Part from j's film (0 at a wall).
    pub from_j: f64,
    /// The whole bridge.
    pub volume: f64,
}

/// LIGGGHTS 3.8.0's effective contact angle of two types from their `contactAngle`s in
/// degrees: `0.5 theta_i theta_j` with theta in rad (a product; later LIGGGHTS versions take
/// the mean).
pub fn effective_contact_angle(deg_i: f64, deg_j: f64) -> f64 {
    let ti = deg_i * PI / 180.;
    let tj = deg_j * PI / 180.;
    0.5 * ti * tj
}

/// The film volume of a particle: `4/3 1000 pi R^3` (x1000, m^3 per unit content).
#[inline(always)]
fn film(rad: f64) -> f64 {
    FOUR_THIRDS_1000 * PI * rad * rad * rad
}

impl WetPair {
    /// The bridge's liquid: each film gives half its spherical-cap share
    /// `(1 - sqrt(1 - R_other^2 / radsum^2)) / 2`.
    #[inline]
    pub fn bond(&self) -> Bond {
        let (ri, rj, rs) = (self.radi, self.radj, self.radsum);
        let vol_i = film(ri) * self.liquid_i;
        let vol_j = if self.is_wall {
            0.0
        } else {
            film(rj) * self.liquid_j
        };
        let from_i = 0.5 * vol_i * (1. - (1. - rj * rj / (rs * rs)).sqrt());
        let from_j = 0.5 * vol_j * (1. - (1. - ri * ri / (rs * rs)).sqrt());
        Bond {
            from_i,
            from_j,
            volume: from_i + from_j,
        }
    }

    /// Soulié's capillary force at gap `dist` (N, negative: attractive); `dist = None` is
    /// the touching form, without the gap term.
    #[inline]
    fn capillary(&self, easo: &Easo, bond: &Bond, dist: Option<f64>) -> f64 {
        let (ri, rj) = (self.radi, self.radj);
        let r2 = if ri >= rj { ri } else { rj };
        let r2inv = 1. / r2;
        let scaled = bond.volume * r2inv * 0.001 * r2inv * r2inv;
        let ca = self.contact_angle;
        let b = (-0.148 * scaled.ln() - 0.96) * ca * ca - 0.0082 * scaled.ln() + 0.48;
        let c = 0.0018 * scaled.ln() + 0.078;
        let e = match dist {
            None => b.exp(),
            Some(d) => {
                let a = -1.1 * scaled.powf(-0.53);
                (a * d / r2 + b).exp()
            }
        };
        -PI * easo.surface_tension * (ri * rj).sqrt() * (e + c)
    }

    /// `-6 pi mu R*` (kg/s).
    #[inline]
    fn stokes(&self, easo: &Easo) -> f64 {
        let r_eff = self.radi * self.radj / (self.radi + self.radj);
        -6. * PI * easo.fluid_viscosity * r_eff
    }

    /// The rupture distance `(1 + theta/2) cbrt(V) / 10` (m).
    #[inline]
    pub fn rupture_distance(&self, bond: &Bond) -> f64 {
        (1. + 0.5 * self.contact_angle) * bond.volume.cbrt() * 0.1
    }
}

/// The wet force of one contact: on i `f` and `ti`; on j `-f` and `tj`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WetForce {
    /// Force on i (N).
    pub f: Vec3,
    /// Torque on i (N m).
    pub ti: Vec3,
    /// Torque on j (N m; zero at a wall).
    pub tj: Vec3,
    /// The normal part, capillary plus viscous (N), for `tangential_reduce`.
    pub normal: f64,
}

/// The relative motion of a contact (LIGGGHTS's normal and tangential velocities).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Motion {
    /// Unit normal from j (or the wall) to i.
    pub en: Vec3,
    /// Normal relative velocity (m/s).
    pub vn: f64,
    /// Tangential relative surface velocity (m/s).
    pub vtr: Vec3,
    /// Lever arm of i (m).
    pub cri: f64,
    /// Lever arm of j (m).
    pub crj: f64,
}

/// Force on i and the two torques from the normal magnitude and the tangential viscous
/// factor, added as LIGGGHTS adds them (area-weighted at a wall).
#[inline]
fn assemble(w: &WetPair, m: &Motion, normal: f64, ft_over_vt: f64) -> WetForce {
    let ft = [
        ft_over_vt * m.vtr[0],
        ft_over_vt * m.vtr[1],
        ft_over_vt * m.vtr[2],
    ];
    let en = m.en;
    let tor = [
        en[1] * ft[2] - en[2] * ft[1],
        en[2] * ft[0] - en[0] * ft[2],
        en[0] * ft[1] - en[1] * ft[0],
    ];
    let mut out = WetForce {
        normal,
        ..WetForce::default()
    };
    for d in 0..3 {
        let f = normal * en[d] + ft[d];
        if w.is_wall {
            out.f[d] = f * w.area_ratio;
            out.ti[d] = -m.cri * tor[d] * w.area_ratio;
        } else {
            out.f[d] = f;
            out.ti[d] = -m.cri * tor[d];
            out.tj[d] = -m.crj * tor[d];
        }
    }
    out
}

/// What a bridge does between surfaces that do not touch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Close {
    /// No bridge (none formed, or it broke earlier).
    Dry,
    /// The bridge holds; its force (None when it holds too little liquid to act).
    Holds(Option<WetForce>),
    /// The bridge breaks now; its liquid moves by these fluxes (content per second; 0 at
    /// a wall), to be added to i's and j's `liquidFlux`.
    Breaks {
        /// Flux into i (1/s).
        flux_i: f64,
        /// Flux into j (1/s).
        flux_j: f64,
    },
}

/// The state of a non-touching contact LIGGGHTS's `surfacesClose` reads.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Gap {
    /// x_i - x_j, or from the wall point to i's centre (m).
    pub delta: Vec3,
    /// |delta|^2 (m^2).
    pub rsq: f64,
    /// Velocity of i (m/s).
    pub vi: Vec3,
    /// Velocity of j, or the wall's as LIGGGHTS 3.8.0 reads it: `atom->v[j]` with j the
    /// triangle index at a mesh wall (the velocity of its local atom of that index) and an
    /// out-of-range read, zero in practice, at a primitive wall (m/s).
    pub vj: Vec3,
    /// Angular velocity of i (rad/s).
    pub omegai: Vec3,
    /// Angular velocity of j (rad/s; unused at a wall).
    pub omegaj: Vec3,
    /// Time step (s).
    pub dt: f64,
}

impl Easo {
    /// `ln(1 / minSeparationDistanceRatio)`.
    #[inline]
    fn ln_inv_min(&self) -> f64 {
        (1. / self.min_separation).ln()
    }

    /// The neighbour list's contact distance factor this model asks for
    /// (`1.1 maxSeparationDistanceRatio`).
    pub fn contact_distance_factor(&self) -> f64 {
        self.max_separation * 1.1
    }

    /// Touching surfaces: the bridge exists from now on (`flag` set to 1) and acts with the
    /// gap-free capillary force and lubrication at the minimum separation.
    #[inline]
    pub fn intersect(&self, w: &WetPair, m: &Motion, flag: &mut f64) -> Option<WetForce> {
        *flag = 1.0;
        let bond = w.bond();
        if bond.volume < MIN_BOND_VOLUME {
            return None;
        }
        let fcap = w.capillary(self, &bond, None);
        let stokes = w.stokes(self);
        let fvisc_n = stokes * m.vn / self.min_separation;
        let ft_over_vt = (EIGHT_FIFTEENTHS * self.ln_inv_min() + 0.9588) * stokes;
        Some(assemble(w, m, fcap + fvisc_n, ft_over_vt))
    }

    /// Surfaces within the contact distance but apart: keep, act through, or break the
    /// bridge `flag` records (LIGGGHTS's `surfacesClose`).
    #[inline]
    pub fn close(&self, w: &WetPair, g: &Gap, flag: &mut f64) -> Close {
        if *flag != 1.0 {
            return Close::Dry;
        }
        let (ri, rj) = (w.radi, w.radj);
        let r = g.rsq.sqrt();
        let dist = if w.is_wall { r - ri } else { r - (ri + rj) };
        let bond = w.bond();
        let dist_max = w.rupture_distance(&bond);
        let limit = (self.max_separation - 1.0) * (ri + rj);
        // beyond the limit it always breaks; within, it holds up to its rupture distance
        if !(dist < dist_max && dist < limit) {
            *flag = 0.0;
            if w.is_wall {
                return Close::Breaks {
                    flux_i: 0.0,
                    flux_j: 0.0,
                };
            }
            let invdt = 1. / g.dt;
            let ratio = rj / ri;
            let split = 1.0 / (1.0 + ratio * ratio * ratio);
            return Close::Breaks {
                flux_i: invdt * (split * bond.volume - bond.from_i) / film(ri),
                flux_j: invdt * ((1. - split) * bond.volume - bond.from_j) / film(rj),
            };
        }
        *flag = 1.0;
        if bond.volume < MIN_BOND_VOLUME {
            return Close::Holds(None);
        }
        let fcap = w.capillary(self, &bond, Some(dist));
        let rinv = 1.0 / r;
        let [dx, dy, dz] = g.delta;
        let en = [dx * rinv, dy * rinv, dz * rinv];
        let vr = [g.vi[0] - g.vj[0], g.vi[1] - g.vj[1], g.vi[2] - g.vj[2]];
        let vn = vr[0] * en[0] + vr[1] * en[1] + vr[2] * en[2];
        let vt = [vr[0] - vn * en[0], vr[1] - vn * en[1], vr[2] - vn * en[2]];
        let mut wr = [0.0; 3];
        for d in 0..3 {
            wr[d] = if w.is_wall {
                ri * g.omegai[d] * rinv
            } else {
                (ri * g.omegai[d] + rj * g.omegaj[d]) * rinv
            };
        }
        let vtr = [
            vt[0] - (dz * wr[1] - dy * wr[2]),
            vt[1] - (dx * wr[2] - dz * wr[0]),
            vt[2] - (dy * wr[0] - dx * wr[1]),
        ];
        let r_eff = ri * rj / (ri + rj);
        let sep = self.min_separation.max(dist / r_eff);
        let stokes = w.stokes(self);
        let fvisc_n = stokes * vn / sep;
        let ft_over_vt = (EIGHT_FIFTEENTHS * (1. / sep).ln() + 0.9588) * stokes;
        let m = Motion {
            en,
            vn,
            vtr,
            cri: ri,
            crj: rj,
        };
        Close::Holds(Some(assemble(w, &m, fcap + fvisc_n, ft_over_vt)))
    }
}

#[cfg(test)]
mod tests;
