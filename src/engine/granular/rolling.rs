//! Rolling-friction models (`rolling_friction ...`).

use crate::engine::granular::material::Material;
use crate::engine::granular::Contact;

/// A rolling model adds a torque resisting relative rolling.
pub trait RollingModel: Send + Sync {
    /// Doubles of per-contact history the model keeps.
    const HISTORY: usize;
    /// Check that the material tables it needs exist.
    fn check(m: &Material) -> Result<(), String>;
    /// Add the rolling torque (to i with minus sign, to j with plus sign).
    fn torque(&self, c: &mut Contact, m: &Material, history: &mut [f64], dt: f64, update: bool);
}

/// No rolling friction.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NoRolling;

impl RollingModel for NoRolling {
    const HISTORY: usize = 0;

    fn check(_: &Material) -> Result<(), String> {
        Ok(())
    }

    #[inline(always)]
    fn torque(&self, _: &mut Contact, _: &Material, _: &mut [f64], _: f64, _: bool) {}
}

/// Remove the part of `v` along the unit normal `en`.
#[inline(always)]
fn tangential_part(v: [f64; 3], en: [f64; 3]) -> [f64; 3] {
    let dot = v[0] * en[0] + v[1] * en[1] + v[2] * en[2];
    [v[0] - en[0] * dot, v[1] - en[1] * dot, v[2] - en[2] * dot]
}

#[inline(always)]
fn apply(c: &mut Contact, r: [f64; 3]) {
    for d in 0..3 {
        c.ti[d] -= r[d];
    }
    for d in 0..3 {
        c.tj[d] += r[d];
    }
}

/// Constant directional torque (`rolling_friction cdt`): |M| = mu_r kn delta R*, opposing
/// the relative rolling direction.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Cdt {
    /// `torsionTorque on`: keep the component along the normal too.
    pub torsion: bool,
}

impl RollingModel for Cdt {
    const HISTORY: usize = 0;

    fn check(m: &Material) -> Result<(), String> {
        m.require_rolling("rolling_model cdt", false)
    }

    #[inline(always)]
    fn torque(&self, c: &mut Contact, m: &Material, _: &mut [f64], _: f64, _: bool) {
        let rmu = m.rolling_friction(c.itype, c.jtype);
        let reff = if c.wall {
            c.radi
        } else {
            c.radi * c.radj / (c.radi + c.radj)
        };
        let mut r = [0.0; 3];
        if c.wall {
            let w = c.wr;
            let wrmag = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
            if wrmag > 0. {
                let fnc = c.deltan * c.kn;
                r = [
                    rmu * fnc * w[0] / wrmag * reff,
                    rmu * fnc * w[1] / wrmag * reff,
                    rmu * fnc * w[2] / wrmag * reff,
                ];
            }
        } else {
            let w = c.wrel;
            let mag = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
            if mag > 0. {
                let s = rmu * c.kn * c.deltan * reff / mag;
                r = [w[0] * s, w[1] * s, w[2] * s];
            }
        }
        if !self.torsion && r != [0.0; 3] {
            r = tangential_part(r, c.en);
        }
        apply(c, r);
    }
}

/// Elastic-plastic spring-dashpot (`rolling_friction epsd`): an incremental rolling spring
/// capped at mu_r |Fn| R*, with viscous damping while below the cap.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Epsd {
    /// `torsionTorque on`.
    pub torsion: bool,
}

impl RollingModel for Epsd {
    const HISTORY: usize = 3;

    fn check(m: &Material) -> Result<(), String> {
        m.require_rolling("rolling_model epsd", true)
    }

    #[inline(always)]
    fn torque(&self, c: &mut Contact, m: &Material, hist: &mut [f64], dt: f64, update: bool) {
        let (radi, radj) = (c.radi, c.radj);
        let reff = if c.wall {
            radi
        } else {
            radi * radj / (radi + radj)
        };
        let (w, r_inertia) = if c.wall {
            (c.wr, 1.4 * c.mi * reff * reff)
        } else {
            let red_i = c.mi * radi * radi;
            let red_j = c.mj * radj * radj;
            (c.wrel, 1.4 * red_i * red_j / (red_i + red_j))
        };
        let rmu = m.rolling_friction(c.itype, c.jtype);
        let wr_tot = if self.torsion {
            w
        } else {
            tangential_part(w, c.en)
        };
        let kr = 2.25 * c.kn * rmu * rmu * reff * reff;
        let s = dt * kr;
        let mut r = [
            hist[0] + wr_tot[0] * s,
            hist[1] + wr_tot[1] * s,
            hist[2] + wr_tot[2] * s,
        ];
        let mag = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        let max = c.fn_total.abs() * reff * rmu;
        if mag > max {
            let factor = max / mag;
            for v in &mut r {
                *v *= factor;
            }
            if update {
                hist[..3].copy_from_slice(&r);
            }
        } else {
            if update {
                hist[..3].copy_from_slice(&r);
            }
            let coef = m.rolling_viscous(c.itype, c.jtype) * 2. * (r_inertia * kr).sqrt();
            for d in 0..3 {
                r[d] += coef * wr_tot[d];
            }
        }
        apply(c, r);
    }
}
