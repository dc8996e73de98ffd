//! Normal contact models (`model hertz | hooke | hertz/stiffness | hooke/stiffness`).
//!
//! Each sets the normal force magnitude `Fn = Fn_damping + Fn_contact` (positive = repulsive;
//! `limitForce on` clips negative values to 0), the stiffnesses `kn`, `kt` and damping
//! coefficients `gamman`, `gammat` the other sub-models read, and adds `Fn en` to the force
//! on i (and `-Fn en` to j). LIGGGHTS divides kn and kt by `force->nktv2p`, which is exactly
//! 1 in the si, cgs and lj unit styles granular runs use, so regolith leaves it out.

use std::f64::consts::PI;

use super::material::{PairCoeffs, Property};
use super::Contact;

/// A normal model: sets `c.normal_force`, `kn`, `kt`, `gamman`, `gammat` and adds the
/// normal force to `c.fi` (and `c.fj` for particle pairs).
pub trait NormalModel: Send + Sync + Copy + 'static {
    /// Doubles of per-contact history the model keeps (the maximum, for run-time enums).
    const HISTORY_LEN: usize = 0;
    /// Doubles of history this instance uses.
    #[inline(always)]
    fn history_len(&self) -> usize {
        Self::HISTORY_LEN
    }
    /// For each history value: does it change sign when the contact is seen from the other
    /// particle (LIGGGHTS's `newtonflag` of `add_history_value`)?
    fn history_flips(&self) -> &'static [bool] {
        &[]
    }
    /// Compute the normal force of a touching contact; `history` holds this model's values.
    fn surfaces_intersect(&self, c: &mut Contact, m: &PairCoeffs, history: &mut [f64]);
    /// The surfaces separated (`surfacesClose`): reset the history.
    #[inline(always)]
    fn surfaces_close(&self, history: &mut [f64]) {
        for h in history.iter_mut().take(self.history_len()) {
            *h = 0.0;
        }
    }
    /// The coefficients the model needs, with LIGGGHTS's caller name, in request order.
    fn properties(&self, out: &mut Vec<(Property, &'static str)>);
}

/// sqrt(5/6), written with the digits LIGGGHTS uses.
#[allow(clippy::excessive_precision)]
const SQRT_FIVE_OVER_SIX: f64 = 0.91287092917527685576161630466800355658790782499663875;

/// Effective radius: R_i R_j / (R_i + R_j) for pairs, the particle radius at walls (m).
#[inline(always)]
pub(crate) fn reff(c: &Contact) -> f64 {
    if c.is_wall {
        c.radi
    } else {
        c.radi * c.radj / (c.radi + c.radj)
    }
}

/// Store the results and add the normal force, as every LIGGGHTS normal model does.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn finish(
    c: &mut Contact,
    fn_damping: f64,
    fn_contact: f64,
    limit: bool,
    kn: f64,
    kt: f64,
    gn: f64,
    gt: f64,
) {
    let mut fnorm = fn_damping + fn_contact;
    // limitForce: no attractive normal force from the damper
    if limit && fnorm < 0.0 {
        fnorm = 0.0;
    }
    c.normal_force = fnorm;
    c.kn = kn;
    c.kt = kt;
    c.gamman = gn;
    c.gammat = gt;
    let en = c.en;
    if c.is_wall {
        // (LIGGGHTS multiplies by area_ratio, which is 1 for primitive walls and spheres)
        for d in 0..3 {
            c.fi[d] += fnorm * en[d];
        }
    } else {
        for d in 0..3 {
            c.fi[d] += fnorm * en[d];
        }
        // the force on j is minus the force on i so far, which is only the normal force
        for d in 0..3 {
            c.fj[d] += -c.fi[d];
        }
    }
}

/// `model hertz`: Fn = 4/3 Y* sqrt(R* d) d - gamman vn with the Tsuji damping
/// gamman = -2 sqrt(5/6) betaeff sqrt(2 Y* sqrt(R* d) meff), so the restitution equals e.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    /// `tangential_damping` (default on): damp the tangential spring with
    /// gammat = -2 sqrt(5/6) betaeff sqrt(8 G* sqrt(R* d) meff).
    pub tangential_damping: bool,
    /// `limitForce` (default off): clip an attractive (negative) Fn to 0.
    pub limit_force: bool,
}

impl Default for Hertz {
    fn default() -> Self {
        Hertz {
            tangential_damping: true,
            limit_force: false,
        }
    }
}

impl NormalModel for Hertz {
    #[inline(always)]
    fn surfaces_intersect(&self, c: &mut Contact, m: &PairCoeffs, _: &mut [f64]) {
        let reff = reff(c);
        let meff = c.meff;
        let sqrtval = (reff * c.deltan).sqrt();
        let sn = 2. * m.yeff * sqrtval;
        let st = 8. * m.geff * sqrtval;
        let kn = 4. / 3. * m.yeff * sqrtval;
        let kt = st;
        let gamman = -2. * SQRT_FIVE_OVER_SIX * m.betaeff * (sn * meff).sqrt();
        let gammat = if self.tangential_damping {
            -2. * SQRT_FIVE_OVER_SIX * m.betaeff * (st * meff).sqrt()
        } else {
            0.0
        };
        let fn_damping = -gamman * c.vn;
        let fn_contact = kn * c.deltan;
        finish(
            c,
            fn_damping,
            fn_contact,
            self.limit_force,
            kn,
            kt,
            gamman,
            gammat,
        );
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::Yeff, "model hertz"));
        out.push((Property::Geff, "model hertz"));
        out.push((Property::BetaEff, "model hertz"));
    }
}

/// `model hooke`: a linear spring whose stiffness gives a Hertzian contact time at the
/// characteristic velocity, kn = 16/15 sqrt(R*) Y* (15 meff v_c^2 / (16 sqrt(R*) Y*))^(1/5),
/// and the linear dashpot gamman = sqrt(4 meff kn ln^2 e / (ln^2 e + pi^2)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hooke {
    /// `tangential_damping` (default on): gammat = gamman.
    pub tangential_damping: bool,
    /// `limitForce` (default off): clip an attractive Fn to 0.
    pub limit_force: bool,
    /// `viscous` (default off): restitution from the Stokes number,
    /// ln e = ln(MaximumRestitution) + CriticalStokes / St, St = meff vn / (6 pi mu R*^2).
    pub viscous: bool,
    /// `ktToKnUser` (default off): kt = 0.285714286 kn instead of kt = kn.
    pub kt_to_kn: bool,
}

impl Default for Hooke {
    fn default() -> Self {
        Hooke {
            tangential_damping: true,
            limit_force: false,
            viscous: false,
            kt_to_kn: false,
        }
    }
}

impl NormalModel for Hooke {
    #[inline(always)]
    fn surfaces_intersect(&self, c: &mut Contact, m: &PairCoeffs, _: &mut [f64]) {
        let reff = reff(c);
        let meff = c.meff;
        let sqrtval = reff.sqrt();
        let log_e = if self.viscous {
            let stokes = meff * c.vn / (6.0 * PI * m.fluid_viscosity * reff * reff);
            m.log_coeff_rest_max + m.critical_stokes / stokes
        } else {
            m.coeff_rest_log
        };
        let cv = m.char_vel;
        let kn = 16. / 15.
            * sqrtval
            * m.yeff
            * (15. * meff * cv * cv / (16. * sqrtval * m.yeff)).powf(0.2);
        let mut kt = kn;
        if self.kt_to_kn {
            kt *= 0.285714286;
        }
        let lsq = log_e * log_e;
        let gamman = if !self.viscous && lsq.is_infinite() {
            // e = 0 (regolith extension): the limit of the expression below
            (4. * meff * kn).sqrt()
        } else {
            (4. * meff * kn * lsq / (lsq + PI * PI)).sqrt()
        };
        let gammat = if self.tangential_damping { gamman } else { 0.0 };
        let fn_damping = -gamman * c.vn;
        let fn_contact = kn * c.deltan;
        finish(
            c,
            fn_damping,
            fn_contact,
            self.limit_force,
            kn,
            kt,
            gamman,
            gammat,
        );
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::Yeff, "model hooke"));
        out.push((Property::Geff, "model hooke"));
        out.push((Property::CharVel, "model hooke"));
        if self.viscous {
            out.push((Property::CoeffMu, "model hooke viscous"));
            out.push((Property::CoeffStc, "model hooke viscous"));
            out.push((Property::CoeffRestMax, "model hooke viscous"));
        } else {
            out.push((Property::CoeffRestLog, "model hooke viscous"));
        }
    }
}

/// `model hertz/stiffness`: user stiffness and damping scaled by sqrt(R* d):
/// kn = sqrt(R* d) k_n, kt = sqrt(R* d) k_t, gamman = sqrt(R* d) meff gamma_n.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzStiffness {
    /// `tangential_damping` (default on): gammat = sqrt(R* d) meff gamma_t, else 0.
    pub tangential_damping: bool,
    /// `limitForce` (default off): clip an attractive Fn to 0.
    pub limit_force: bool,
}

impl Default for HertzStiffness {
    fn default() -> Self {
        HertzStiffness {
            tangential_damping: true,
            limit_force: false,
        }
    }
}

impl NormalModel for HertzStiffness {
    #[inline(always)]
    fn surfaces_intersect(&self, c: &mut Contact, m: &PairCoeffs, _: &mut [f64]) {
        let meff = c.meff;
        let reff = reff(c);
        let polyhertz = (reff * c.deltan).sqrt();
        let kn = polyhertz * m.kn;
        let kt = polyhertz * m.kt;
        let gamman = polyhertz * meff * m.gamman;
        let gammat = if self.tangential_damping {
            polyhertz * meff * m.gammat
        } else {
            0.0
        };
        let fn_damping = -gamman * c.vn;
        let fn_contact = kn * c.deltan;
        finish(
            c,
            fn_damping,
            fn_contact,
            self.limit_force,
            kn,
            kt,
            gamman,
            gammat,
        );
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::Kn, "model hertz/stiffness"));
        out.push((Property::Kt, "model hertz/stiffness"));
        out.push((Property::Gamman, "model hertz/stiffness"));
        out.push((Property::Gammat, "model hertz/stiffness"));
    }
}

/// `model hooke/stiffness`: constant user stiffness kn = k_n, kt = k_t and damping
/// gamman = meff gamma_n (or gamman_abs with `absolute_damping on`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HookeStiffness {
    /// `tangential_damping` (default on): gammat = meff gamma_t (or gammat_abs), else 0.
    pub tangential_damping: bool,
    /// `absolute_damping` (default off): use gamman_abs/gammat_abs (kg/s) without meff.
    pub absolute_damping: bool,
    /// `limitForce` (default off): clip an attractive Fn to 0.
    pub limit_force: bool,
}

impl Default for HookeStiffness {
    fn default() -> Self {
        HookeStiffness {
            tangential_damping: true,
            absolute_damping: false,
            limit_force: false,
        }
    }
}

impl NormalModel for HookeStiffness {
    #[inline(always)]
    fn surfaces_intersect(&self, c: &mut Contact, m: &PairCoeffs, _: &mut [f64]) {
        let meff = c.meff;
        let kn = m.kn;
        let kt = m.kt;
        let (gamman, mut gammat) = if self.absolute_damping {
            (m.gamman_abs, m.gammat_abs)
        } else {
            (meff * m.gamman, meff * m.gammat)
        };
        if !self.tangential_damping {
            gammat = 0.0;
        }
        let fn_damping = -gamman * c.vn;
        let fn_contact = kn * c.deltan;
        finish(
            c,
            fn_damping,
            fn_contact,
            self.limit_force,
            kn,
            kt,
            gamman,
            gammat,
        );
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::Kn, "model hooke/stiffness"));
        out.push((Property::Kt, "model hooke/stiffness"));
        if self.absolute_damping {
            out.push((Property::GammanAbs, "model hooke/stiffness"));
            out.push((Property::GammatAbs, "model hooke/stiffness"));
        } else {
            out.push((Property::Gamman, "model hooke/stiffness"));
            out.push((Property::Gammat, "model hooke/stiffness"));
        }
    }
}

/// `model hooke/hysteresis` (Walton-Braun): loading along kn (model hooke's stiffness), unloading
/// and reloading along k2, which grows from kn to k2Max = kn coefficientMaxElasticStiffness as
/// the largest overlap deltaMax grows to deltaMaxLim = k2Max/(k2Max - kn) phiF 2 R*, and an
/// adhesive branch -kc d with kc = kn coefficientAdhesionStiffness. Keeps deltaMax (m) as
/// history. Its damping is model hooke's, written as LIGGGHTS's hysteresis model writes it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HookeHysteresis {
    /// The model hooke options it inherits (`tangential_damping`, `viscous`).
    pub hooke: Hooke,
}

impl NormalModel for HookeHysteresis {
    const HISTORY_LEN: usize = 1;

    /// deltaMax is a length, the same from both particles.
    fn history_flips(&self) -> &'static [bool] {
        &[false]
    }

    #[inline(always)]
    fn surfaces_intersect(&self, c: &mut Contact, m: &PairCoeffs, history: &mut [f64]) {
        let reff = reff(c);
        let meff = c.meff;
        let deltan = c.deltan;
        let log_e = if self.hooke.viscous {
            let stokes = meff * c.vn / (6.0 * PI * m.fluid_viscosity * reff * reff);
            m.log_coeff_rest_max + m.critical_stokes / stokes
        } else {
            m.coeff_rest_log
        };
        let sqrtval = reff.sqrt();
        let cv = m.char_vel;
        let kn = 16. / 15.
            * sqrtval
            * m.yeff
            * (15. * meff * cv * cv / (16. * sqrtval * m.yeff)).powf(0.2);
        let kt = kn;
        let gamman = (4. * meff * kn / (1. + (PI / log_e) * (PI / log_e))).sqrt();
        let gammat = if self.hooke.tangential_damping {
            gamman
        } else {
            0.0
        };
        let k2_max = kn * m.kn_to_k2_max;
        let kc = kn * m.kn_to_kc;
        // the largest overlap so far (LIGGGHTS raises it even when history is frozen)
        if deltan > history[0] {
            history[0] = deltan;
        }
        let delta_max = history[0];
        let delta_max_lim = (k2_max / (k2_max - kn)) * m.phi_f * 2. * reff;
        let adhesive_delta_max = || {
            0.5 * (deltan
                + (deltan * deltan + 4. * ((kn + kc) * deltan * delta_max_lim / (k2_max - kn)))
                    .sqrt())
        };
        let f_hys;
        if delta_max >= delta_max_lim {
            // beyond the plastic limit: no kn branch any more
            let f_tmp = k2_max * (deltan - delta_max_lim) + kn * delta_max_lim;
            if f_tmp >= -kc * deltan {
                f_hys = f_tmp;
            } else {
                f_hys = -kc * deltan;
                if c.update_history {
                    history[0] = adhesive_delta_max();
                }
            }
        } else {
            let k2 = kn + (k2_max - kn) * delta_max / delta_max_lim;
            let f_tmp = k2 * (deltan - delta_max) + kn * delta_max;
            if f_tmp >= kn * deltan {
                f_hys = kn * deltan;
            } else if f_tmp > -kc * deltan {
                f_hys = f_tmp;
            } else {
                f_hys = -kc * deltan;
                if c.update_history {
                    history[0] = adhesive_delta_max();
                }
            }
        }
        let fn_damping = -gamman * c.vn;
        finish(c, fn_damping, f_hys, false, kn, kt, gamman, gammat);
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        self.hooke.properties(out);
        out.push((Property::CoeffMaxElasticStiffness, "model hooke/hysteresis"));
        out.push((Property::CoeffAdhesionStiffness, "model hooke/hysteresis"));
        out.push((Property::CoeffPlasticityDepth, "model hooke/hysteresis"));
    }
}

/// Any normal model, chosen at run time (the fallback for combinations that are not
/// monomorphised; one `match` per call).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyNormal {
    /// `model hertz`.
    Hertz(Hertz),
    /// `model hooke`.
    Hooke(Hooke),
    /// `model hertz/stiffness`.
    HertzStiffness(HertzStiffness),
    /// `model hooke/stiffness`.
    HookeStiffness(HookeStiffness),
    /// `model hooke/hysteresis`.
    HookeHysteresis(HookeHysteresis),
}

impl NormalModel for AnyNormal {
    const HISTORY_LEN: usize = HookeHysteresis::HISTORY_LEN;

    #[inline]
    fn history_len(&self) -> usize {
        match self {
            AnyNormal::HookeHysteresis(n) => n.history_len(),
            _ => 0,
        }
    }

    fn history_flips(&self) -> &'static [bool] {
        match self {
            AnyNormal::HookeHysteresis(n) => n.history_flips(),
            _ => &[],
        }
    }

    #[inline]
    fn surfaces_intersect(&self, c: &mut Contact, m: &PairCoeffs, h: &mut [f64]) {
        match self {
            AnyNormal::Hertz(n) => n.surfaces_intersect(c, m, h),
            AnyNormal::Hooke(n) => n.surfaces_intersect(c, m, h),
            AnyNormal::HertzStiffness(n) => n.surfaces_intersect(c, m, h),
            AnyNormal::HookeStiffness(n) => n.surfaces_intersect(c, m, h),
            AnyNormal::HookeHysteresis(n) => n.surfaces_intersect(c, m, h),
        }
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        match self {
            AnyNormal::Hertz(n) => n.properties(out),
            AnyNormal::Hooke(n) => n.properties(out),
            AnyNormal::HertzStiffness(n) => n.properties(out),
            AnyNormal::HookeStiffness(n) => n.properties(out),
            AnyNormal::HookeHysteresis(n) => n.properties(out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contact(deltan: f64, vn: f64) -> Contact {
        Contact {
            radi: 0.01,
            radj: 0.02,
            deltan,
            vn,
            meff: 0.003,
            en: [0.0, 0.0, 1.0],
            ..Contact::default()
        }
    }

    #[test]
    fn hertz_elastic_force_is_four_thirds_e_star_sqrt_r_d_to_three_halves() {
        let m = PairCoeffs {
            yeff: 7e7,
            geff: 3e7,
            betaeff: -0.3,
            ..PairCoeffs::default()
        };
        let d = 1e-4;
        let mut c = contact(d, 0.0);
        Hertz::default().surfaces_intersect(&mut c, &m, &mut []);
        let rstar: f64 = 0.01 * 0.02 / 0.03;
        let expect = 4.0 / 3.0 * 7e7 * rstar.sqrt() * d.powf(1.5);
        assert!((c.normal_force - expect).abs() < 1e-12 * expect);
        assert_eq!(c.fi, [0.0, 0.0, c.normal_force]);
        assert_eq!(c.fj, [0.0, 0.0, -c.normal_force]);
        // kt = 8 G* sqrt(R* d); damping opposes approach (vn < 0 pushes apart harder)
        assert!((c.kt - 8.0 * 3e7 * (rstar * d).sqrt()).abs() < 1e-9 * c.kt);
        let mut c2 = contact(d, -0.1);
        Hertz::default().surfaces_intersect(&mut c2, &m, &mut []);
        assert!(c2.normal_force > c.normal_force);
        assert!(c.gamman > 0.0 && c.gammat > 0.0);
    }

    #[test]
    fn limit_force_clips_attraction() {
        let m = PairCoeffs {
            yeff: 7e7,
            geff: 3e7,
            betaeff: -0.6,
            ..PairCoeffs::default()
        };
        let mut c = contact(1e-7, 5.0);
        Hertz::default().surfaces_intersect(&mut c, &m, &mut []);
        assert!(c.normal_force < 0.0);
        let mut c = contact(1e-7, 5.0);
        let h = Hertz {
            limit_force: true,
            ..Hertz::default()
        };
        h.surfaces_intersect(&mut c, &m, &mut []);
        assert_eq!(c.normal_force, 0.0);
    }

    #[test]
    fn zero_restitution_is_critical_damping() {
        // e = 0 (regolith extension): Hooke's gamman takes its limit sqrt(4 meff kn)
        let m = PairCoeffs {
            yeff: 7e7,
            char_vel: 1.0,
            coeff_rest_log: f64::NEG_INFINITY,
            ..PairCoeffs::default()
        };
        let mut c = contact(1e-4, -0.1);
        Hooke::default().surfaces_intersect(&mut c, &m, &mut []);
        assert_eq!(c.gamman, (4.0 * c.meff * c.kn).sqrt());
        let tiny = PairCoeffs {
            coeff_rest_log: (1e-300f64).ln(),
            ..m
        };
        let mut c2 = contact(1e-4, -0.1);
        Hooke::default().surfaces_intersect(&mut c2, &tiny, &mut []);
        assert!((c2.gamman - c.gamman).abs() < 1e-4 * c.gamman);
        // Hertz uses betaeff = -1 from the material tables, which is finite
        let h = PairCoeffs {
            yeff: 7e7,
            geff: 3e7,
            betaeff: crate::engine::contact::material::beta_of_restitution(0.0),
            ..PairCoeffs::default()
        };
        let mut c3 = contact(1e-4, -0.1);
        Hertz::default().surfaces_intersect(&mut c3, &h, &mut []);
        assert!(c3.gamman.is_finite() && c3.gamman > 0.0);
    }

    #[test]
    fn hooke_stiffness_is_linear() {
        let m = PairCoeffs {
            kn: 2e4,
            kt: 1e4,
            gamman: 50.0,
            gammat: 20.0,
            ..PairCoeffs::default()
        };
        let mut c = contact(1e-3, -0.2);
        HookeStiffness::default().surfaces_intersect(&mut c, &m, &mut []);
        assert!((c.normal_force - (2e4 * 1e-3 + 0.003 * 50.0 * 0.2)).abs() < 1e-12);
        assert_eq!(c.gammat, 0.003 * 20.0);
        let mut c = contact(1e-3, -0.2);
        HookeStiffness {
            tangential_damping: false,
            ..HookeStiffness::default()
        }
        .surfaces_intersect(&mut c, &m, &mut []);
        assert_eq!(c.gammat, 0.0);
    }
}
