//! `fix momentum`: zero a group's linear and/or angular momentum every N steps at the end
//! of the step, as LIGGGHTS 3.8.0 (LAMMPS's fix momentum) does.

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::domain::Domain;
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::momentum::{add_inertia, mirror_inertia, omega};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "momentum",
    "fix ID GROUP momentum N",
    &[
        kw(
            "linear",
            &[
                arg("XFLAG", Value::Int),
                arg("YFLAG", Value::Int),
                arg("ZFLAG", Value::Int),
            ],
            "remove the centre-of-mass velocity along the flagged (1) axes",
        ),
        kw(
            "angular",
            &[],
            "remove the rigid rotation about the centre of mass",
        ),
    ],
    "zero the group's linear and/or angular momentum every N steps",
);

/// One `fix momentum N [linear XF YF ZF] [angular]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Momentum {
    /// Act every this many steps.
    pub every: i64,
    /// `linear xflag yflag zflag`: which centre-of-mass velocity components are removed.
    pub linear: Option<[bool; 3]>,
    /// `angular`: remove the rigid rotation about the centre of mass.
    pub angular: bool,
    /// The group's mass at the run's setup (mass), as LIGGGHTS keeps it for the run.
    pub mass: f64,
}

/// The unwrapped position of particle `i` (length).
fn unwrap(p: &Particles, i: usize, domain: &Domain) -> [f64; 3] {
    let mut x = p.x[i];
    for (d, xd) in x.iter_mut().enumerate() {
        *xd += p.image[i][d] as f64 * domain.length(d);
    }
    x
}

impl Momentum {
    /// The group's total mass (mass), summed in particle order.
    pub fn group_mass(p: &Particles, group: u32) -> f64 {
        crate::engine::momentum::group_mass(p, group)
    }

    /// Adjust the velocities of `group` (LIGGGHTS's `end_of_step`).
    pub fn apply(&self, p: &mut Particles, group: u32, domain: &Domain) {
        let members = |p: &Particles, i: usize| p.mask[i] & group != 0;
        let total = self.mass;
        if let Some(flags) = self.linear {
            let mut mom = [0.0; 3];
            for i in 0..p.len() {
                if members(p, i) {
                    for (d, m) in mom.iter_mut().enumerate() {
                        *m += p.v[i][d] * p.mass[i];
                    }
                }
            }
            if total > 0.0 {
                mom = mom.map(|c| c / total);
            }
            for i in 0..p.len() {
                if members(p, i) {
                    for d in (0..3).filter(|&d| flags[d]) {
                        p.v[i][d] -= mom[d];
                    }
                }
            }
        }
        if self.angular {
            let mut cm = [0.0; 3];
            for i in 0..p.len() {
                if members(p, i) {
                    let u = unwrap(p, i, domain);
                    for (c, ud) in cm.iter_mut().zip(u) {
                        *c += ud * p.mass[i];
                    }
                }
            }
            if total > 0.0 {
                cm = cm.map(|c| c / total);
            }
            let mut l = [0.0; 3];
            let mut t = [[0.0; 3]; 3];
            for i in 0..p.len() {
                if !members(p, i) {
                    continue;
                }
                let u = unwrap(p, i, domain);
                let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
                let (m, v) = (p.mass[i], p.v[i]);
                l[0] += m * (dy * v[2] - dz * v[1]);
                l[1] += m * (dz * v[0] - dx * v[2]);
                l[2] += m * (dx * v[1] - dy * v[0]);
            }
            for i in 0..p.len() {
                if !members(p, i) {
                    continue;
                }
                let u = unwrap(p, i, domain);
                let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
                let m = p.mass[i];
                add_inertia(&mut t, [dx, dy, dz], m);
            }
            mirror_inertia(&mut t);
            let w = omega(l, t);
            for i in 0..p.len() {
                if !members(p, i) {
                    continue;
                }
                let u = unwrap(p, i, domain);
                let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
                p.v[i][0] -= w[1] * dz - w[2] * dy;
                p.v[i][1] -= w[2] * dx - w[0] * dz;
                p.v[i][2] -= w[0] * dy - w[1] * dx;
            }
        }
    }
}

impl FixStyle for Momentum {
    fn name(&self) -> &str {
        "momentum"
    }

    /// The group's mass at the run's setup (LIGGGHTS's `init`).
    fn setup(&mut self, p: &Particles, at: &FixStep) {
        self.mass = Momentum::group_mass(p, at.group);
    }

    fn end_of_step(&mut self, p: &mut Particles, at: &FixStep) {
        if at.step % self.every == 0 {
            self.apply(p, at.group, at.domain);
        }
    }
}

/// `fix ID GROUP momentum N [linear XFLAG YFLAG ZFLAG] [angular]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    const ILLEGAL: &str = "Illegal fix momentum command";
    a.count(
        4..=usize::MAX,
        "fix ID GROUP momentum N [linear XFLAG YFLAG ZFLAG] [angular]",
    )?;
    let every = a.int(3)?;
    if every <= 0 {
        return Err(a.error(3, ILLEGAL));
    }
    let (mut linear, mut angular) = (None, false);
    let mut i = 4;
    while i < a.len() {
        match a.word(i)? {
            "linear" => {
                if i + 4 > a.len() {
                    return Err(a.error(i, ILLEGAL));
                }
                let mut flags = [false; 3];
                for (d, flag) in flags.iter_mut().enumerate() {
                    *flag = match a.int(i + 1 + d)? {
                        0 => false,
                        1 => true,
                        _ => return Err(a.error(i + 1 + d, ILLEGAL)),
                    };
                }
                linear = Some(flags);
                i += 4;
            }
            "angular" => {
                angular = true;
                i += 1;
            }
            _ => return Err(a.error(i, ILLEGAL)),
        }
    }
    if linear.is_none() && !angular {
        return Err(a.error(2, ILLEGAL));
    }
    // checking a deck does not run it, so its particles may not exist yet
    let p = &ctx.sim.particles;
    let checking = ctx.sys.mode != crate::lang::system::Mode::Run;
    if !checking && !(0..p.len()).any(|i| p.mask[i] & fix.bit != 0) {
        return Err(a.error(1, "Fix momentum group has no atoms"));
    }
    Ok(Box::new(Momentum {
        every,
        linear,
        angular,
        mass: 0.0,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_and_angular_momentum_vanish() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0, 0.0, 0.0], 0.1, 1000.0);
        p.push(2, 1, [1.0, 0.0, 0.0], 0.1, 1000.0);
        p.push(3, 1, [0.0, 1.0, 0.5], 0.2, 1000.0);
        p.v = vec![[1.0, 0.5, 0.0], [0.0, 2.0, 1.0], [0.3, 0.0, -1.0]];
        let mut m = Momentum {
            every: 1,
            linear: Some([true; 3]),
            angular: true,
            mass: 0.0,
        };
        m.mass = Momentum::group_mass(&p, 1);
        m.apply(&mut p, 1, &Domain::default());
        let mom: f64 = (0..3)
            .map(|d| (0..3).map(|i| p.mass[i] * p.v[i][d]).sum::<f64>().abs())
            .sum();
        assert!(mom < 1e-12, "{mom}");
    }
}
