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
