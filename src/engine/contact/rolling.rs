//! Rolling-resistance models (`rolling_friction off | cdt | epsd | epsd2 | epsd3`). Each
//! computes a torque `Mr` and subtracts it from the torque on i (adds it to j).
//!
//! For particle pairs every model uses the relative angular velocity `omega_i - omega_j`
//! (not the surface model's `wr`); at walls it uses the surface model's
//! `wr = (R - d/2) omega_i / r` (r the centre-wall distance). Without `torsionTorque on`
//! the component along the contact normal is removed. Effective radius as in the normal
//! models (the particle radius at walls).

use super::material::{Coeffs, Property};
use super::normal::reff;
use super::real::{Mask, Real};
use super::Contact;

/// A rolling model adds a rolling-resistance torque after the tangential model ran.
pub trait RollingModel: Send + Sync + Copy + 'static {
    /// Doubles of per-contact history the model keeps (the maximum, for run-time enums).
    const HISTORY_LEN: usize;
    /// Doubles of history this instance uses.
    #[inline(always)]
    fn history_len(&self) -> usize {
        Self::HISTORY_LEN
    }
    /// Add the rolling torque of a touching contact; `history` holds this contact's values.
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
    /// The coefficients the model needs, with LIGGGHTS's caller name.
    fn properties(&self, out: &mut Vec<(Property, &'static str)>);
}

/// Torque on i -= Mr, on j += Mr.
#[inline(always)]
fn apply<S: Real>(c: &mut Contact<S>, r_torque: [S; 3]) {
    c.r_torque = r_torque;
    for d in 0..3 {
        c.ti[d] -= r_torque[d];
    }
    if !c.is_wall {
        for d in 0..3 {
            c.tj[d] += r_torque[d];
        }
    }
}

/// `v - en (v . en)`: remove the component along the normal.
#[inline(always)]
fn remove_normal<S: Real>(v: [S; 3], en: [S; 3]) -> [S; 3] {
    let dot = v[0] * en[0] + v[1] * en[1] + v[2] * en[2];
    let n = [en[0] * dot, en[1] * dot, en[2] * dot];
    [v[0] - n[0], v[1] - n[1], v[2] - n[2]]
}

/// The rolling angular velocity the models use: omega_i - omega_j, or `wr` at walls.
#[inline(always)]
fn rolling_omega<S: Real>(c: &Contact<S>) -> [S; 3] {
    if c.is_wall {
        c.wr
    } else {
        [
            c.omegai[0] - c.omegaj[0],
            c.omegai[1] - c.omegaj[1],
            c.omegai[2] - c.omegaj[2],
        ]
    }
}

/// `rolling_friction off`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoRolling;

impl RollingModel for NoRolling {
    const HISTORY_LEN: usize = 0;

    #[inline(always)]
    fn surfaces_intersect<S: Real>(&self, _: &mut Contact<S>, _: &impl Coeffs<S>, _: &mut [S]) {}

    fn properties(&self, _: &mut Vec<(Property, &'static str)>) {}
}

/// `rolling_friction cdt` (constant directional torque): |Mr| = mu_r kn d R* along the
/// rolling angular velocity (kn d the elastic normal force, not Fn), no history.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Cdt {
    /// `torsionTorque` (default off): keep the torsional (normal) component.
    pub torsion_torque: bool,
}

impl RollingModel for Cdt {
    const HISTORY_LEN: usize = 0;

    #[inline(always)]
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>, _: &mut [S]) {
        let rmu = m.get(|k| k.coeff_roll_frict);
        let reff = reff(c);
        let w = rolling_omega(c);
        let wmag = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        let mut rt = [S::default(); 3];
        if c.is_wall {
            let fnorm = c.deltan * c.kn;
            for d in 0..3 {
                rt[d] = rmu * fnorm * w[d] / wmag * reff;
            }
        } else {
            let s = rmu * c.kn * c.deltan * reff / wmag;
            rt = [s * w[0], s * w[1], s * w[2]];
        }
        if !self.torsion_torque {
            rt = remove_normal(rt, c.en);
        }
        // no rolling, no torque
        let rolling = wmag.gt(S::default());
        // written out, not `map`: an out-of-line closure would lose the caller's vector code
        let zero = S::default();
        apply(
            c,
            [
                S::select(rolling, rt[0], zero),
                S::select(rolling, rt[1], zero),
                S::select(rolling, rt[2], zero),
            ],
        );
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::CoeffRollFrict, "rolling_model cdt"));
    }
}

/// The elastic-plastic spring-dashpot torque shared by epsd and epsd3: a spring of
/// stiffness `kr` on the accumulated rolling angle (history: the spring torque, 3 doubles,
/// N m), capped at `mu_r R* |Fn|`, plus viscous damping `eta 2 sqrt(I kr) w` below the cap.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn epsd_torque<S: Real>(
    c: &Contact<S>,
    history: &mut [S],
    torsion: bool,
    rmu: S,
    kr: S,
    reff: S,
    w: [S; 3],
    damping: Option<(S, S)>,
) -> [S; 3] {
    let wr_tot = if torsion { w } else { remove_normal(w, c.en) };
    let s = c.dt * kr;
    let dr = [s * wr_tot[0], s * wr_tot[1], s * wr_tot[2]];
    let mut rt = [history[0] + dr[0], history[1] + dr[1], history[2] + dr[2]];
    let mag = (rt[0] * rt[0] + rt[1] * rt[1] + rt[2] * rt[2]).sqrt();
    let max = c.normal_force.abs() * reff * rmu;
    // fully mobilised: the spring is scaled back to the cap and there is no dashpot
    let capped = mag.gt(max);
    // the division only where a lane is capped (the results are the same either way)
    if capped.any() {
        let factor = max / mag;
        for x in rt.iter_mut() {
            *x = S::select(capped, *x * factor, *x);
        }
    }
    if c.update_history {
        history[..3].copy_from_slice(&rt);
    }
    if let Some((visc, r_inertia)) = damping {
        let r_coef = visc * S::splat(2.) * (r_inertia * kr).sqrt();
        for d in 0..3 {
            rt[d] = S::select(capped, rt[d], rt[d] + r_coef * wr_tot[d]);
        }
    }
    rt
}

/// Rolling moment of inertia LIGGGHTS's epsd and epsd3 use: 1.4 (1.5 in 2d) times the
/// reduced m R^2 of the pair, or of the particle at a wall (kg m^2).
#[inline(always)]
fn rolling_inertia<S: Real>(c: &Contact<S>, radius_wall: S, two_d: bool) -> S {
    let f = S::splat(if two_d { 1.5 } else { 1.4 });
    if c.is_wall {
        f * c.mi * radius_wall * radius_wall
    } else {
        let ri = c.mi * c.radi * c.radi;
        let rj = c.mj * c.radj * c.radj;
        f * ri * rj / (ri + rj)
    }
}

/// `rolling_friction epsd`: spring kr = 2.25 kn mu_r^2 R*^2 capped at mu_r R* |Fn|, with
/// viscous damping from coefficientRollingViscousDamping.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Epsd {
    /// `torsionTorque` (default off): keep the torsional (normal) component.
    pub torsion_torque: bool,
    /// 2d run (`dimension 2`): inertia factor 1.5 instead of 1.4.
    pub two_d: bool,
}

impl RollingModel for Epsd {
    const HISTORY_LEN: usize = 3;

    #[inline(always)]
    fn surfaces_intersect<S: Real>(
        &self,
        c: &mut Contact<S>,
        m: &impl Coeffs<S>,
        history: &mut [S],
    ) {
        let reff = reff(c);
        let r_inertia = rolling_inertia(c, reff, self.two_d);
        let rmu = m.get(|k| k.coeff_roll_frict);
        let kr = S::splat(2.25) * c.kn * rmu * rmu * reff * reff;
        let w = rolling_omega(c);
        let rt = epsd_torque(
            c,
            history,
            self.torsion_torque,
            rmu,
            kr,
            reff,
            w,
            Some((m.get(|k| k.coeff_roll_visc), r_inertia)),
        );
        apply(c, rt);
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::CoeffRollFrict, "rolling_model epsd"));
        out.push((Property::CoeffRollVisc, "rolling_model epsd"));
    }
}

/// `rolling_friction epsd2`: spring kr = kt R*^2 capped at mu_r R* |Fn|, no damping.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Epsd2 {
    /// `torsionTorque` (default off): keep the torsional (normal) component.
    pub torsion_torque: bool,
}

impl RollingModel for Epsd2 {
    const HISTORY_LEN: usize = 3;

    #[inline(always)]
    fn surfaces_intersect<S: Real>(
        &self,
        c: &mut Contact<S>,
        m: &impl Coeffs<S>,
        history: &mut [S],
    ) {
        let reff = reff(c);
        let rmu = m.get(|k| k.coeff_roll_frict);
        let kr = c.kt * reff * reff;
        let w = rolling_omega(c);
        let rt = epsd_torque(c, history, self.torsion_torque, rmu, kr, reff, w, None);
        apply(c, rt);
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::CoeffRollFrict, "rolling_model epsd2"));
    }
}

/// `rolling_friction epsd3`: as epsd with kr = rollingStiffness kn mu_r^2 R*^2.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Epsd3 {
    /// `torsionTorque` (default off): keep the torsional (normal) component.
    pub torsion_torque: bool,
    /// 2d run: inertia factor 1.5 instead of 1.4.
    pub two_d: bool,
}

impl RollingModel for Epsd3 {
    const HISTORY_LEN: usize = 3;

    #[inline(always)]
    fn surfaces_intersect<S: Real>(
        &self,
        c: &mut Contact<S>,
        m: &impl Coeffs<S>,
        history: &mut [S],
    ) {
        let reff = reff(c);
        let r_inertia = rolling_inertia(c, c.radi, self.two_d);
        let rmu = m.get(|k| k.coeff_roll_frict);
        let kr = m.get(|k| k.rolling_stiffness) * c.kn * rmu * rmu * reff * reff;
        let w = rolling_omega(c);
        let rt = epsd_torque(
            c,
            history,
            self.torsion_torque,
            rmu,
            kr,
            reff,
            w,
            Some((m.get(|k| k.coeff_roll_visc), r_inertia)),
        );
        apply(c, rt);
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::CoeffRollFrict, "rolling_model epsd3"));
        out.push((Property::CoeffRollVisc, "rolling_model epsd3"));
        out.push((Property::RollingStiffness, "rolling_model epsd3"));
    }
}

/// Any rolling model, chosen at run time; reserves 3 doubles of history for every variant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyRolling {
    /// `rolling_friction off`.
    Off(NoRolling),
    /// `rolling_friction cdt`.
    Cdt(Cdt),
    /// `rolling_friction epsd`.
    Epsd(Epsd),
    /// `rolling_friction epsd2`.
    Epsd2(Epsd2),
    /// `rolling_friction epsd3`.
    Epsd3(Epsd3),
}

impl RollingModel for AnyRolling {
    const HISTORY_LEN: usize = 3;

    #[inline]
    fn history_len(&self) -> usize {
        match self {
            AnyRolling::Off(_) | AnyRolling::Cdt(_) => 0,
            AnyRolling::Epsd(_) | AnyRolling::Epsd2(_) | AnyRolling::Epsd3(_) => 3,
        }
    }

    #[inline]
    fn surfaces_intersect<S: Real>(
        &self,
        c: &mut Contact<S>,
        m: &impl Coeffs<S>,
        history: &mut [S],
    ) {
        match self {
            AnyRolling::Off(_) => {}
            AnyRolling::Cdt(r) => r.surfaces_intersect(c, m, history),
            AnyRolling::Epsd(r) => r.surfaces_intersect(c, m, history),
            AnyRolling::Epsd2(r) => r.surfaces_intersect(c, m, history),
            AnyRolling::Epsd3(r) => r.surfaces_intersect(c, m, history),
        }
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        match self {
            AnyRolling::Off(_) => {}
            AnyRolling::Cdt(r) => r.properties(out),
            AnyRolling::Epsd(r) => r.properties(out),
            AnyRolling::Epsd2(r) => r.properties(out),
            AnyRolling::Epsd3(r) => r.properties(out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::contact::material::PairCoeffs;
    use crate::engine::contact::Vec3;

    fn contact(update: bool) -> Contact {
        Contact {
            radi: 0.01,
            radj: 0.01,
            mi: 0.01,
            mj: 0.01,
            en: [1.0, 0.0, 0.0],
            deltan: 1e-4,
            kn: 1e5,
            kt: 8e4,
            normal_force: 10.0,
            omegai: [0.0, 0.0, 5.0],
            omegaj: [0.0, 0.0, -5.0],
            dt: 1e-4,
            update_history: update,
            ..Contact::default()
        }
    }

    fn coeffs() -> PairCoeffs {
        PairCoeffs {
            coeff_roll_frict: 0.1,
            coeff_roll_visc: 0.3,
            rolling_stiffness: 2.0,
            ..PairCoeffs::default()
        }
    }

    fn dot(a: Vec3, b: Vec3) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    #[test]
    fn cdt_opposes_rolling_with_constant_magnitude() {
        let mut c = contact(true);
        Cdt::default().surfaces_intersect(&mut c, &coeffs(), &mut []);
        let w = [0.0, 0.0, 10.0];
        assert!(dot(c.ti, w) < 0.0 && dot(c.tj, w) > 0.0);
        let expect = 0.1 * 1e5 * 1e-4 * 0.005;
        assert!((c.ti[2] + expect).abs() < 1e-15 * expect.max(1.0));
        // torsion about the normal is removed unless torsionTorque is on
        let mut c = contact(true);
        c.omegai = [3.0, 0.0, 4.0];
        c.omegaj = [0.0; 3];
        Cdt::default().surfaces_intersect(&mut c, &coeffs(), &mut []);
        assert!(c.ti[0].abs() < 1e-18);
        let mut c = contact(true);
        c.omegai = [3.0, 0.0, 4.0];
        c.omegaj = [0.0; 3];
        Cdt {
            torsion_torque: true,
        }
        .surfaces_intersect(&mut c, &coeffs(), &mut []);
        assert!(c.ti[0] < 0.0);
    }

    #[test]
    fn epsd_builds_up_and_caps_at_mu_r_r_fn() {
        let m = coeffs();
        let mut h = [0.0; 3];
        let cap = 10.0 * 0.005 * 0.1;
        let mut last = 0.0;
        let mut capped = false;
        for _ in 0..2000 {
            let mut c = contact(true);
            Epsd::default().surfaces_intersect(&mut c, &m, &mut h);
            // opposes the relative rotation (omega_i - omega_j along +z)
            assert!(c.ti[2] < 0.0 && c.tj[2] > 0.0);
            let spring = h[2].abs();
            assert!(spring <= cap * (1.0 + 1e-12));
            assert!(spring >= last);
            last = spring;
            if (spring - cap).abs() < 1e-12 * cap {
                capped = true;
                // fully mobilised: torque exactly at the cap, no dashpot
                assert!((c.ti[2] + cap).abs() < 1e-12 * cap);
            }
        }
        assert!(capped);
        // epsd2 and epsd3 share the cap
        for model in [
            AnyRolling::Epsd2(Epsd2::default()),
            AnyRolling::Epsd3(Epsd3::default()),
        ] {
            let mut h = [0.0; 3];
            for _ in 0..5000 {
                let mut c = contact(true);
                model.surfaces_intersect(&mut c, &m, &mut h);
            }
            assert!((h[2] - cap).abs() < 1e-12 * cap, "{model:?} {h:?}");
        }
    }

    #[test]
    fn epsd_elastic_step_is_kr_dt_w_plus_damping() {
        let m = coeffs();
        let mut h = [0.0; 3];
        let mut c = contact(true);
        Epsd::default().surfaces_intersect(&mut c, &m, &mut h);
        let reff = 0.005;
        let kr = 2.25 * 1e5 * 0.01 * reff * reff;
        assert!((h[2] - kr * 1e-4 * 10.0).abs() < 1e-18);
        let inertia = 1.4 * (0.01 * 1e-4) / 2.0;
        let damp = 0.3 * 2.0 * (inertia * kr).sqrt() * 10.0;
        assert!((c.ti[2] + h[2] + damp).abs() < 1e-15);
    }
}
