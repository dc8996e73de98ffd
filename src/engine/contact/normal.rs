//! Normal contact models (`model hertz | hooke | hertz/stiffness | hooke/stiffness`).
//!
//! Each sets the normal force magnitude `Fn = Fn_damping + Fn_contact` (positive = repulsive;
//! `limitForce on` clips negative values to 0), the stiffnesses `kn`, `kt` and damping
//! coefficients `gamman`, `gammat` the other sub-models read, and adds `Fn en` to the force
//! on i (and `-Fn en` to j). LIGGGHTS divides kn and kt by `force->nktv2p`, which is exactly
//! 1 in the si, cgs and lj unit styles granular runs use, so regolith leaves it out.

use std::f64::consts::PI;

use super::material::{Coeffs, Property};
use super::real::{Mask, Real};
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
    fn surfaces_intersect<S: Real>(
        &self,
        c: &mut Contact<S>,
        m: &impl Coeffs<S>,
        history: &mut [S],
    );
    /// The surfaces separated (`surfacesClose`): reset the history.
    #[inline(always)]
    fn surfaces_close<S: Real>(&self, history: &mut [S]) {
        for h in history.iter_mut().take(self.history_len()) {
            *h = S::default();
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
pub(crate) fn reff<S: Real>(c: &Contact<S>) -> S {
    if c.is_wall {
        c.radi
    } else {
        c.radi * c.radj / (c.radi + c.radj)
    }
}

/// Store the results and add the normal force, as every LIGGGHTS normal model does.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn finish<S: Real>(
    c: &mut Contact<S>,
    fn_damping: S,
    fn_contact: S,
    limit: bool,
    kn: S,
    kt: S,
    gn: S,
    gt: S,
) {
    let mut fnorm = fn_damping + fn_contact;
    // limitForce: no attractive normal force from the damper
    if limit {
        fnorm = S::select(fnorm.lt(S::default()), S::default(), fnorm);
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
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>, _: &mut [S]) {
        let reff = reff(c);
        let meff = c.meff;
        let yeff = m.get(|k| k.yeff);
        let betaeff = m.get(|k| k.betaeff);
        let sqrtval = (reff * c.deltan).sqrt();
        let sn = S::splat(2.) * yeff * sqrtval;
        let st = S::splat(8.) * m.get(|k| k.geff) * sqrtval;
        let kn = S::splat(4. / 3.) * yeff * sqrtval;
        let kt = st;
        let gamman = S::splat(-2. * SQRT_FIVE_OVER_SIX) * betaeff * (sn * meff).sqrt();
        let gammat = if self.tangential_damping {
            S::splat(-2. * SQRT_FIVE_OVER_SIX) * betaeff * (st * meff).sqrt()
        } else {
            S::default()
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
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>, _: &mut [S]) {
        let reff = reff(c);
        let meff = c.meff;
        let yeff = m.get(|k| k.yeff);
        let sqrtval = reff.sqrt();
        let log_e = if self.viscous {
            let stokes =
                meff * c.vn / (S::splat(6.0 * PI) * m.get(|k| k.fluid_viscosity) * reff * reff);
            m.get(|k| k.log_coeff_rest_max) + m.get(|k| k.critical_stokes) / stokes
        } else {
            m.get(|k| k.coeff_rest_log)
        };
        let cv = m.get(|k| k.char_vel);
        let kn = S::splat(16. / 15.)
            * sqrtval
            * yeff
            * (S::splat(15.) * meff * cv * cv / (S::splat(16.) * sqrtval * yeff)).powf(0.2);
        let mut kt = kn;
        if self.kt_to_kn {
            kt *= S::splat(0.285714286);
        }
        let lsq = log_e * log_e;
        let four_m_kn = S::splat(4.) * meff * kn;
        let damped = (four_m_kn * lsq / (lsq + S::splat(PI * PI))).sqrt();
        let gamman = if self.viscous {
            damped
        } else {
            // e = 0 (regolith extension): the limit of the expression below
            S::select(lsq.is_infinite(), four_m_kn.sqrt(), damped)
        };
        let gammat = if self.tangential_damping {
            gamman
        } else {
            S::default()
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
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>, _: &mut [S]) {
        let meff = c.meff;
        let reff = reff(c);
        let polyhertz = (reff * c.deltan).sqrt();
        let kn = polyhertz * m.get(|k| k.kn);
        let kt = polyhertz * m.get(|k| k.kt);
        let gamman = polyhertz * meff * m.get(|k| k.gamman);
        let gammat = if self.tangential_damping {
            polyhertz * meff * m.get(|k| k.gammat)
        } else {
            S::default()
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
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>, _: &mut [S]) {
        let meff = c.meff;
        let kn = m.get(|k| k.kn);
        let kt = m.get(|k| k.kt);
        let (gamman, mut gammat) = if self.absolute_damping {
            (m.get(|k| k.gamman_abs), m.get(|k| k.gammat_abs))
        } else {
            (meff * m.get(|k| k.gamman), meff * m.get(|k| k.gammat))
        };
        if !self.tangential_damping {
            gammat = S::default();
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
    fn surfaces_intersect<S: Real>(
        &self,
        c: &mut Contact<S>,
        m: &impl Coeffs<S>,
        history: &mut [S],
    ) {
        let reff = reff(c);
        let meff = c.meff;
        let deltan = c.deltan;
        let log_e = if self.hooke.viscous {
            let stokes =
                meff * c.vn / (S::splat(6.0 * PI) * m.get(|k| k.fluid_viscosity) * reff * reff);
            m.get(|k| k.log_coeff_rest_max) + m.get(|k| k.critical_stokes) / stokes
        } else {
            m.get(|k| k.coeff_rest_log)
        };
        let yeff = m.get(|k| k.yeff);
        let sqrtval = reff.sqrt();
        let cv = m.get(|k| k.char_vel);
        let kn = S::splat(16. / 15.)
            * sqrtval
            * yeff
            * (S::splat(15.) * meff * cv * cv / (S::splat(16.) * sqrtval * yeff)).powf(0.2);
        let kt = kn;
        let pi = S::splat(PI);
        let gamman =
            (S::splat(4.) * meff * kn / (S::splat(1.) + (pi / log_e) * (pi / log_e))).sqrt();
        let gammat = if self.hooke.tangential_damping {
            gamman
        } else {
            S::default()
        };
        let k2_max = kn * m.get(|k| k.kn_to_k2_max);
        let kc = kn * m.get(|k| k.kn_to_kc);
        // the largest overlap so far (LIGGGHTS raises it even when history is frozen)
        history[0] = S::select(deltan.gt(history[0]), deltan, history[0]);
        let delta_max = history[0];
        let delta_max_lim = (k2_max / (k2_max - kn)) * m.get(|k| k.phi_f) * S::splat(2.) * reff;
        let adhesive_delta_max = S::splat(0.5)
            * (deltan
                + (deltan * deltan
                    + S::splat(4.) * ((kn + kc) * deltan * delta_max_lim / (k2_max - kn)))
                    .sqrt());
        let adhesive = -kc * deltan;
        // beyond the plastic limit: no kn branch any more
        let plastic = delta_max.ge(delta_max_lim);
        let f_plastic = k2_max * (deltan - delta_max_lim) + kn * delta_max_lim;
        let k2 = kn + (k2_max - kn) * delta_max / delta_max_lim;
        let f_elastic = k2 * (deltan - delta_max) + kn * delta_max;
        let loading = kn * deltan;
        let plastic_keeps = f_plastic.ge(adhesive);
        let on_loading = f_elastic.ge(loading);
        let elastic_keeps = f_elastic.gt(adhesive);
        let f_hys = S::select(
            plastic,
            S::select(plastic_keeps, f_plastic, adhesive),
            S::select(
                on_loading,
                loading,
                S::select(elastic_keeps, f_elastic, adhesive),
            ),
        );
        if c.update_history {
            // on the adhesive branch deltaMax follows the overlap
            let adhesion = plastic
                .and(plastic_keeps.not())
                .or(plastic.not().and(on_loading.not()).and(elastic_keeps.not()));
            history[0] = S::select(adhesion, adhesive_delta_max, history[0]);
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
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>, h: &mut [S]) {
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
    use crate::engine::contact::material::PairCoeffs;

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
