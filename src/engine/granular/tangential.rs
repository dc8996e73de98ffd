//! Tangential (friction) models.

use crate::engine::granular::material::Material;
use crate::engine::granular::Contact;

/// A tangential model adds the friction force and its torques.
pub trait TangentialModel: Send + Sync {
    /// Doubles of per-contact history the model keeps.
    const HISTORY: usize;
    /// Compute the tangential force; `history` holds this contact's stored values.
    fn force(&self, c: &mut Contact, m: &Material, history: &mut [f64], dt: f64, update: bool);
}

/// Torques of a tangential force (ft on i, -ft on j) about the particle centres.
#[inline(always)]
fn add_force_and_torque(c: &mut Contact, ft: [f64; 3]) {
    let [enx, eny, enz] = c.en;
    let tor1 = eny * ft[2] - enz * ft[1];
    let tor2 = enz * ft[0] - enx * ft[2];
    let tor3 = enx * ft[1] - eny * ft[0];
    for d in 0..3 {
        c.fi[d] += ft[d];
    }
    for d in 0..3 {
        c.fj[d] += -ft[d];
    }
    let ti = [-c.cri * tor1, -c.cri * tor2, -c.cri * tor3];
    let tj = [-c.crj * tor1, -c.crj * tor2, -c.crj * tor3];
    for d in 0..3 {
        c.ti[d] += ti[d];
    }
    for d in 0..3 {
        c.tj[d] += tj[d];
    }
}

/// `tangential no_history`: viscous friction capped at mu |Fn|.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoHistory;

impl TangentialModel for NoHistory {
    const HISTORY: usize = 0;

    #[inline(always)]
    fn force(&self, c: &mut Contact, m: &Material, _: &mut [f64], _: f64, _: bool) {
        let xmu = m.friction(c.itype, c.jtype);
        let v = c.vtr;
        let vrel = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let ft_friction = xmu * c.fn_total.abs();
        let gamma = if ft_friction < c.gammat * vrel {
            ft_friction / vrel
        } else {
            c.gammat
        };
        add_force_and_torque(c, [-gamma * v[0], -gamma * v[1], -gamma * v[2]]);
    }
}

/// `tangential history`: an elastic tangential spring (Mindlin) with damping and a Coulomb
/// cap on the spring force. When the cap is hit, the spring is shortened to the cap and no
/// damping is added (LIGGGHTS 3.8.0 behaviour).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct History;

impl TangentialModel for History {
    const HISTORY: usize = 3;

    #[inline(always)]
    fn force(&self, c: &mut Contact, m: &Material, shear: &mut [f64], dt: f64, update: bool) {
        let [enx, eny, enz] = c.en;
        if update {
            shear[0] += c.vtr[0] * dt;
            shear[1] += c.vtr[1] * dt;
            shear[2] += c.vtr[2] * dt;
            let rsht = shear[0] * enx + shear[1] * eny + shear[2] * enz;
            shear[0] -= rsht * enx;
            shear[1] -= rsht * eny;
            shear[2] -= rsht * enz;
        }
        let shrmag = (shear[0] * shear[0] + shear[1] * shear[1] + shear[2] * shear[2]).sqrt();
        let kt = c.kt;
        let xmu = m.friction(c.itype, c.jtype);
        let mut ft = [-(kt * shear[0]), -(kt * shear[1]), -(kt * shear[2])];
        let ft_shear = kt * shrmag;
        let ft_friction = xmu * c.fn_total.abs();
        if ft_shear > ft_friction {
            if shrmag != 0.0 {
                let ratio = ft_friction / ft_shear;
                for d in 0..3 {
                    ft[d] *= ratio;
                }
                if update {
                    for d in 0..3 {
                        shear[d] = -ft[d] / kt;
                    }
                }
            } else {
                ft = [0.0; 3];
            }
        } else {
            for d in 0..3 {
                ft[d] -= c.gammat * c.vtr[d];
            }
        }
        add_force_and_torque(c, ft);
    }
}

/// regolith extension `tangential history_total_cap`: as [`History`], but the Coulomb limit
/// caps the total tangential force (spring plus damping), and the stored spring is rescaled
/// so that it stays consistent with the capped force (the correction the lunar-regolith study
/// used; LIGGGHTS 3.8.0 caps the spring part only and drops damping while sliding).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HistoryTotalCap;

impl TangentialModel for HistoryTotalCap {
    const HISTORY: usize = 3;

    #[inline(always)]
    fn force(&self, c: &mut Contact, m: &Material, shear: &mut [f64], dt: f64, update: bool) {
        let [enx, eny, enz] = c.en;
        if update {
            for d in 0..3 {
                shear[d] += c.vtr[d] * dt;
            }
            let rsht = shear[0] * enx + shear[1] * eny + shear[2] * enz;
            shear[0] -= rsht * enx;
            shear[1] -= rsht * eny;
            shear[2] -= rsht * enz;
        }
        let (kt, gammat) = (c.kt, c.gammat);
        let mut ft = [0.0; 3];
        for d in 0..3 {
            ft[d] = -(kt * shear[d]) - gammat * c.vtr[d];
        }
        let mag = (ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]).sqrt();
        let limit = m.friction(c.itype, c.jtype) * c.fn_total.abs();
        if mag > limit {
            let ratio = if mag > 0.0 { limit / mag } else { 0.0 };
            for d in 0..3 {
                ft[d] *= ratio;
            }
            if update && kt > 0.0 {
                // the spring that, with the damping, gives exactly the capped force
                for d in 0..3 {
                    shear[d] = -(ft[d] + gammat * c.vtr[d]) / kt;
                }
            }
        }
        add_force_and_torque(c, ft);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::granular::material::{Material, MaterialInput};

    fn material() -> Material {
        Material::new(&MaterialInput {
            youngs: vec![5e6],
            poisson: vec![0.2],
            restitution: vec![0.5],
            friction: vec![0.5],
            soft: false,
            hard: false,
            cohesion: None,
            rolling_friction: None,
            rolling_viscous: None,
            char_vel: None,
            zero_restitution: false,
        })
        .unwrap()
    }

    fn contact(vt: f64) -> Contact {
        Contact {
            itype: 1,
            jtype: 1,
            en: [0.0, 0.0, 1.0],
            vtr: [vt, 0.0, 0.0],
            fn_total: 1.0,
            kt: 1000.0,
            gammat: 0.5,
            cri: 0.01,
            crj: 0.01,
            ..Contact::default()
        }
    }

    #[test]
    fn total_cap_never_exceeds_coulomb_and_liggghts_spring_cap_can() {
        let m = material();
        let mut shear_ext = [0.0; 3];
        let mut shear_lig = [0.0; 3];
        for _ in 0..200 {
            let mut a = contact(0.3);
            HistoryTotalCap.force(&mut a, &m, &mut shear_ext, 1e-3, true);
            let fa = a.fi[0].hypot(a.fi[1]);
            assert!(fa <= 0.5 * 1.0 * (1.0 + 1e-12), "{fa}");
            let mut b = contact(0.3);
            History.force(&mut b, &m, &mut shear_lig, 1e-3, true);
            assert!(b.fi[0].abs() <= 0.5 + 1e-12);
        }
        // sliding: the extension sits exactly at the Coulomb limit, opposing the slip
        let mut a = contact(0.3);
        HistoryTotalCap.force(&mut a, &m, &mut shear_ext, 1e-3, true);
        assert!((a.fi[0] + 0.5).abs() < 1e-12, "{:?}", a.fi);
        // sticking with damping: below the limit both models add the damping force
        let (mut s1, mut s2) = ([0.0; 3], [0.0; 3]);
        let mut a = contact(0.01);
        let mut b = contact(0.01);
        HistoryTotalCap.force(&mut a, &m, &mut s1, 1e-6, true);
        History.force(&mut b, &m, &mut s2, 1e-6, true);
        assert_eq!(a.fi, b.fi);
    }
}
