//! Tangential (friction) models: `tangential off | no_history | history`, and the regolith
//! extension `history_total_cap`.
//!
//! What LIGGGHTS 3.8.0's `tangential history` does when the Coulomb limit is exceeded:
//! the spring force `Ft = -kt s` (s the stored shear displacement) is compared, without the
//! damper, against `mu |Fn|`. If `kt |s| > mu |Fn|` the spring force is scaled down to
//! `mu |Fn|`, the history is overwritten with `s = -Ft / kt` (only when the history is being
//! updated, i.e. not during setup), and NO damping force is added. Otherwise the damping
//! `-gammat vtr` is added to the spring force, so the total tangential force can exceed
//! `mu |Fn|` by up to `gammat |vtr|`. [`HistoryTotalCap`] instead caps the total.

use super::material::{Coeffs, Property};
use super::real::{Mask, Real};
use super::Contact;

/// A tangential model adds the friction force at the contact point and its torques.
pub trait TangentialModel: Send + Sync + Copy + 'static {
    /// Doubles of per-contact history the model keeps (the maximum, for run-time enums).
    const HISTORY_LEN: usize;
    /// Doubles of history this instance uses (equal to `HISTORY_LEN` for concrete models).
    #[inline(always)]
    fn history_len(&self) -> usize {
        Self::HISTORY_LEN
    }
    /// Add the friction force of a touching contact; `history` holds this contact's values.
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

/// Add the tangential force `ft` on i (and `-ft` on j) with the torques it exerts about the
/// centres, lever arms `cri`, `crj` along `-en` (LIGGGHTS's torque arithmetic).
#[inline(always)]
fn add_force_and_torques<S: Real>(c: &mut Contact<S>, ft: [S; 3]) {
    let [enx, eny, enz] = c.en;
    let tor1 = eny * ft[2] - enz * ft[1];
    let tor2 = enz * ft[0] - enx * ft[2];
    let tor3 = enx * ft[1] - eny * ft[0];
    let ti = [-c.cri * tor1, -c.cri * tor2, -c.cri * tor3];
    c.ft = ft;
    if c.is_wall {
        // (LIGGGHTS multiplies force and torque by area_ratio = 1)
        for d in 0..3 {
            c.fi[d] += ft[d];
        }
        for d in 0..3 {
            c.ti[d] += ti[d];
        }
    } else {
        let tj = [-c.crj * tor1, -c.crj * tor2, -c.crj * tor3];
        for d in 0..3 {
            c.fi[d] += ft[d];
        }
        for d in 0..3 {
            c.fj[d] += -ft[d];
        }
        for d in 0..3 {
            c.ti[d] += ti[d];
        }
        for d in 0..3 {
            c.tj[d] += tj[d];
        }
    }
}

/// Advance the shear displacement by `vtr dt` and project it into the tangent plane.
#[inline(always)]
fn advance_shear<S: Real>(c: &Contact<S>, shear: &mut [S]) {
    let [enx, eny, enz] = c.en;
    let dt = c.dt;
    shear[0] += c.vtr[0] * dt;
    shear[1] += c.vtr[1] * dt;
    shear[2] += c.vtr[2] * dt;
    let rsht = shear[0] * enx + shear[1] * eny + shear[2] * enz;
    shear[0] -= rsht * enx;
    shear[1] -= rsht * eny;
    shear[2] -= rsht * enz;
}

/// `tangential off` (the LIGGGHTS default when no `tangential` keyword is given).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoTangential;

impl TangentialModel for NoTangential {
    const HISTORY_LEN: usize = 0;

    #[inline(always)]
    fn surfaces_intersect<S: Real>(&self, _: &mut Contact<S>, _: &impl Coeffs<S>, _: &mut [S]) {}

    fn properties(&self, _: &mut Vec<(Property, &'static str)>) {}
}

/// `tangential no_history`: a viscous friction `-gamma vtr` with gamma = gammat, reduced to
/// `mu |Fn| / |vtr|` when that is smaller (so |Ft| <= mu |Fn|).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NoHistory;

impl TangentialModel for NoHistory {
    const HISTORY_LEN: usize = 0;

    #[inline(always)]
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>, _: &mut [S]) {
        let xmu = m.get(|k| k.coeff_frict);
        let v = c.vtr;
        let vrel = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let ft_friction = xmu * c.normal_force.abs();
        let gamma = S::select(
            ft_friction.lt(c.gammat * vrel),
            ft_friction / vrel,
            c.gammat,
        );
        add_force_and_torques(c, [-gamma * v[0], -gamma * v[1], -gamma * v[2]]);
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::CoeffFrict, "tangential_model history"));
    }
}

/// `tangential history`: a Mindlin-type spring on the accumulated shear displacement
/// (history: 3 doubles, m) plus damping, with LIGGGHTS's Coulomb treatment (module docs).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct History;

impl TangentialModel for History {
    const HISTORY_LEN: usize = 3;

    #[inline(always)]
    fn surfaces_intersect<S: Real>(
        &self,
        c: &mut Contact<S>,
        m: &impl Coeffs<S>,
        history: &mut [S],
    ) {
        let shear = &mut history[..3];
        let update = c.update_history;
        if update {
            advance_shear(c, shear);
        }
        let shrmag = (shear[0] * shear[0] + shear[1] * shear[1] + shear[2] * shear[2]).sqrt();
        let kt = c.kt;
        let xmu = m.get(|k| k.coeff_frict);
        let spring = [-(kt * shear[0]), -(kt * shear[1]), -(kt * shear[2])];
        let ft_shear = kt * shrmag;
        let ft_friction = xmu * c.normal_force.abs();
        // beyond the Coulomb limit the spring is scaled back (no damping); a zero spring
        // gives no force
        let capped = ft_shear.gt(ft_friction);
        let sliding = capped.and(shrmag.ne(S::default()));
        let gammat = c.gammat;
        let mut ft = [S::default(); 3];
        for d in 0..3 {
            ft[d] = spring[d] - gammat * c.vtr[d];
        }
        // the divisions only where a lane slides (rare in a bed at rest; the results are
        // the same either way)
        if capped.any() {
            let ratio = ft_friction / ft_shear;
            for d in 0..3 {
                let scaled = spring[d] * ratio;
                ft[d] = S::select(capped, S::select(sliding, scaled, S::default()), ft[d]);
            }
            if update && sliding.any() {
                for d in 0..3 {
                    shear[d] = S::select(sliding, -ft[d] / kt, shear[d]);
                }
            }
        }
        add_force_and_torques(c, ft);
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::CoeffFrict, "tangential_model history"));
    }
}

/// regolith extension `tangential history_total_cap`: the same spring and damper as
/// [`History`], but the TOTAL force `-kt s - gammat vtr` is capped at `mu |Fn|`. When the cap
/// applies, the total is scaled to `mu |Fn|` along its own direction and the spring is reset
/// to carry the capped total minus the damping part, `s = -(Ft + gammat vtr) / kt` (history
/// updates only; the spring is left alone unless kt > 0). Below the cap the force is bit for bit
/// that of `tangential history`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct HistoryTotalCap;

impl TangentialModel for HistoryTotalCap {
    const HISTORY_LEN: usize = 3;

    #[inline(always)]
    fn surfaces_intersect<S: Real>(
        &self,
        c: &mut Contact<S>,
        m: &impl Coeffs<S>,
        history: &mut [S],
    ) {
        let shear = &mut history[..3];
        let update = c.update_history;
        if update {
            advance_shear(c, shear);
        }
        let kt = c.kt;
        let gammat = c.gammat;
        let damp = [gammat * c.vtr[0], gammat * c.vtr[1], gammat * c.vtr[2]];
        let mut ft = [
            -(kt * shear[0]) - damp[0],
            -(kt * shear[1]) - damp[1],
            -(kt * shear[2]) - damp[2],
        ];
        let ftmag = (ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]).sqrt();
        let ft_friction = m.get(|k| k.coeff_frict) * c.normal_force.abs();
        let capped = ftmag.gt(ft_friction);
        // the divisions only where a lane is capped (the results are the same either way)
        if capped.any() {
            let ratio = ft_friction / ftmag;
            for f in ft.iter_mut() {
                *f = S::select(capped, *f * ratio, *f);
            }
            let reset = capped.and(kt.gt(S::default()));
            if update && reset.any() {
                for d in 0..3 {
                    shear[d] = S::select(reset, -(ft[d] + damp[d]) / kt, shear[d]);
                }
            }
        }
        add_force_and_torques(c, ft);
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        out.push((Property::CoeffFrict, "tangential_model history"));
    }
}

/// Any tangential model, chosen at run time; reserves 3 doubles of history for every
/// variant (`history_len` says how many the selected one uses).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyTangential {
    /// `tangential off`.
    Off(NoTangential),
    /// `tangential no_history`.
    NoHistory(NoHistory),
    /// `tangential history`.
    History(History),
    /// `tangential history_total_cap` (regolith extension).
    TotalCap(HistoryTotalCap),
}

impl TangentialModel for AnyTangential {
    const HISTORY_LEN: usize = 3;

    #[inline]
    fn history_len(&self) -> usize {
        match self {
            AnyTangential::Off(_) | AnyTangential::NoHistory(_) => 0,
            AnyTangential::History(_) | AnyTangential::TotalCap(_) => 3,
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
            AnyTangential::Off(_) => {}
            AnyTangential::NoHistory(t) => t.surfaces_intersect(c, m, history),
            AnyTangential::History(t) => t.surfaces_intersect(c, m, history),
            AnyTangential::TotalCap(t) => t.surfaces_intersect(c, m, history),
        }
    }

    fn properties(&self, out: &mut Vec<(Property, &'static str)>) {
        match self {
            AnyTangential::Off(_) => {}
            AnyTangential::NoHistory(t) => t.properties(out),
            AnyTangential::History(t) => t.properties(out),
            AnyTangential::TotalCap(t) => t.properties(out),
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
            cri: 0.0099,
            crj: 0.0099,
            en: [0.0, 0.0, 1.0],
            vtr: [0.2, -0.1, 0.0],
            kt: 1e5,
            gammat: 2.0,
            normal_force: 10.0,
            dt: 1e-5,
            update_history: update,
            ..Contact::default()
        }
    }

    fn mu(x: f64) -> PairCoeffs {
        PairCoeffs {
            coeff_frict: x,
            ..PairCoeffs::default()
        }
    }

    fn norm(v: Vec3) -> f64 {
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
    }

    #[test]
    fn history_rotates_into_the_tangent_plane() {
        // a stored shear with a normal component (the contact normal turned)
        let mut h = [1e-5, 2e-5, 3e-5];
        let mut c = contact(true);
        c.en = [0.6, 0.0, 0.8];
        c.vtr = [0.0; 3];
        History.surfaces_intersect(&mut c, &mu(10.0), &mut h);
        let dot = h[0] * 0.6 + h[2] * 0.8;
        assert!(dot.abs() < 1e-20, "{dot}");
        assert_eq!(h[1], 2e-5);
        // without update (setup) the history is untouched
        let mut h = [1e-5, 2e-5, 3e-5];
        let mut c = contact(false);
        History.surfaces_intersect(&mut c, &mu(10.0), &mut h);
        assert_eq!(h, [1e-5, 2e-5, 3e-5]);
    }

    #[test]
    fn elastic_regime_adds_damping() {
        let mut h = [0.0; 3];
        let mut c = contact(true);
        History.surfaces_intersect(&mut c, &mu(10.0), &mut h);
        assert_eq!(h, [0.2 * 1e-5, -0.1 * 1e-5, 0.0]);
        let expect = -(1e5 * 0.2e-5) - 2.0 * 0.2;
        assert!((c.fi[0] - expect).abs() < 1e-14);
        assert_eq!(c.fj[0], -c.fi[0]);
        // torque on i: -cri en x Ft, the same on j (both lever arms point to the contact)
        let ti_y = -0.0099 * c.fi[0];
        assert!((c.ti[1] - ti_y).abs() < 1e-15);
        assert_eq!(c.ti, c.tj);
    }

    #[test]
    fn coulomb_cap_rescales_spring_and_drops_damping() {
        let mut h = [3e-4, -4e-4, 0.0];
        let mut c = contact(false);
        History.surfaces_intersect(&mut c, &mu(0.3), &mut h);
        // |Ft| = mu Fn exactly along the spring direction, no damping
        assert!((norm(c.fi) - 3.0).abs() < 1e-12);
        assert!((c.fi[0] / c.fi[1] - (-0.75)).abs() < 1e-12);
        assert_eq!(h, [3e-4, -4e-4, 0.0]);
        // with update the history is rescaled so that kt |s| = mu Fn
        let mut h = [3e-4, -4e-4, 0.0];
        let mut c = contact(true);
        c.vtr = [0.0; 3];
        History.surfaces_intersect(&mut c, &mu(0.3), &mut h);
        assert!((1e5 * norm([h[0], h[1], h[2]]) - 3.0).abs() < 1e-12);
    }

    #[test]
    fn total_cap_bounds_spring_plus_damping() {
        // below the limit on the spring alone, but spring + damper exceeds it
        let mu_ = mu(0.1);
        let mut h = [-0.9e-5, 0.0, 0.0];
        let mut c = contact(false);
        c.vtr = [-0.3, 0.0, 0.0];
        History.surfaces_intersect(&mut c, &mu_, &mut h.clone());
        assert!(
            norm(c.fi) > 1.0 + 1e-9,
            "LIGGGHTS exceeds the cap: {}",
            norm(c.fi)
        );
        let mut c = contact(true);
        c.vtr = [-0.3, 0.0, 0.0];
        c.dt = 0.0;
        HistoryTotalCap.surfaces_intersect(&mut c, &mu_, &mut h);
        assert!((norm(c.fi) - 1.0).abs() < 1e-12);
        // the spring now carries the capped total minus the damping part
        let spring = -1e5 * h[0];
        assert!((spring - (c.fi[0] + 2.0 * -0.3)).abs() < 1e-12);
        // below the cap it equals tangential history bit for bit
        let mut h1 = [1e-6, 2e-6, 0.0];
        let mut h2 = h1;
        let mut c1 = contact(true);
        let mut c2 = contact(true);
        History.surfaces_intersect(&mut c1, &mu(10.0), &mut h1);
        HistoryTotalCap.surfaces_intersect(&mut c2, &mu(10.0), &mut h2);
        assert_eq!(c1.fi, c2.fi);
        assert_eq!(h1, h2);
    }

    #[test]
    fn no_history_is_capped_viscous_friction() {
        let mut c = contact(true);
        NoHistory.surfaces_intersect(&mut c, &mu(10.0), &mut []);
        assert_eq!(c.fi, [-2.0 * 0.2, 2.0 * 0.1, 0.0]);
        let mut c = contact(true);
        NoHistory.surfaces_intersect(&mut c, &mu(0.01), &mut []);
        assert!((norm(c.fi) - 0.1).abs() < 1e-14);
    }
}
