//! Normal contact models.

use crate::engine::granular::material::Material;
use crate::engine::granular::Contact;

/// A normal model sets the normal force and the stiffness/damping the others use.
pub trait NormalModel: Send + Sync {
    /// Check that the material tables it needs exist.
    fn check(_m: &Material) -> Result<(), String> {
        Ok(())
    }
    /// Compute the normal force of a contact and add it to both particles.
    fn force(&self, c: &mut Contact, m: &Material);
}

/// Hertz (`model hertz`): Fn = 4/3 E* sqrt(R* d) d + damping from the restitution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    /// Damp the tangential spring too (`tangential_damping on`, the default).
    pub tangential_damping: bool,
    /// Never let the normal force attract (`limitForce on`).
    pub limit_force: bool,
}

/// sqrt(5/6), as LIGGGHTS writes it.
const SQRT_FIVE_OVER_SIX: f64 = 0.912_870_929_175_276_855_761_616_304_668;

impl NormalModel for Hertz {
    #[inline(always)]
    fn force(&self, c: &mut Contact, m: &Material) {
        let (it, jt) = (c.itype, c.jtype);
        let sqrtval = (c.reff * c.deltan).sqrt();
        let yeff = m.yeff(it, jt);
        let sn = 2. * yeff * sqrtval;
        let st = 8. * m.geff(it, jt) * sqrtval;
        let kn = 4. / 3. * yeff * sqrtval;
        let kt = st;
        let beta = m.betaeff(it, jt);
        let gamman = -2. * SQRT_FIVE_OVER_SIX * beta * (sn * c.meff).sqrt();
        let gammat = if self.tangential_damping {
            -2. * SQRT_FIVE_OVER_SIX * beta * (st * c.meff).sqrt()
        } else {
            0.0
        };
        let fn_damping = -gamman * c.vn;
        let fn_contact = kn * c.deltan;
        let mut fn_total = fn_damping + fn_contact;
        if self.limit_force && fn_total < 0.0 {
            fn_total = 0.0;
        }
        c.fn_total = fn_total;
        c.kn = kn;
        c.kt = kt;
        c.gamman = gamman;
        c.gammat = gammat;
        for d in 0..3 {
            c.fi[d] += fn_total * c.en[d];
        }
        for d in 0..3 {
            c.fj[d] += -c.fi[d];
        }
    }
}

/// Hooke (`model hooke`): a linear spring whose stiffness gives the Hertz collision time at
/// the characteristic velocity, and a damping set by the restitution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hooke {
    /// Damp the tangential spring with the normal damping (`tangential_damping on`).
    pub tangential_damping: bool,
    /// Never let the normal force attract (`limitForce on`).
    pub limit_force: bool,
}

impl NormalModel for Hooke {
    fn check(m: &Material) -> Result<(), String> {
        m.characteristic_velocity("model hooke").map(|_| ())
    }

    #[inline(always)]
    fn force(&self, c: &mut Contact, m: &Material) {
        let (it, jt) = (c.itype, c.jtype);
        let sqrtval = c.reff.sqrt();
        let yeff = m.yeff(it, jt);
        let cv = m.char_vel;
        let meff = c.meff;
        let kn =
            16. / 15. * sqrtval * yeff * (15. * meff * cv * cv / (16. * sqrtval * yeff)).powf(0.2);
        let kt = kn;
        let ln_e = m.restitution_log(it, jt);
        let ln_sq = ln_e * ln_e;
        let gamman = if ln_e.is_infinite() {
            // e = 0 (extension): the limit of the expression below, critical damping
            (4. * meff * kn).sqrt()
        } else {
            (4. * meff * kn * ln_sq / (ln_sq + std::f64::consts::PI * std::f64::consts::PI)).sqrt()
        };
        let gammat = if self.tangential_damping { gamman } else { 0.0 };
        let fn_damping = -gamman * c.vn;
        let fn_contact = kn * c.deltan;
        let mut fn_total = fn_damping + fn_contact;
        if self.limit_force && fn_total < 0.0 {
            fn_total = 0.0;
        }
        c.fn_total = fn_total;
        c.kn = kn;
        c.kt = kt;
        c.gamman = gamman;
        c.gammat = gammat;
        for d in 0..3 {
            c.fi[d] += fn_total * c.en[d];
        }
        for d in 0..3 {
            c.fj[d] += -c.fi[d];
        }
    }
}
