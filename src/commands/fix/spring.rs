//! `fix spring`: a spring on a group's centre of mass, tethered to a point or coupled to a
//! second group's centre of mass (`post_force`), as LIGGGHTS 3.8.0 (LAMMPS's fix spring)
//! does it. `f_ID` is the spring's energy, `f_ID[1..3]` the spring force on the group and
//! `f_ID[4]` its magnitude (negative while the spring is compressed).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::particles::Particles;
use crate::state::domain::Domain;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "spring",
    "fix ID GROUP spring tether K X Y Z R0 | couple GROUP2 K X Y Z R0",
    &[],
    "a spring of stiffness K (force/length) and rest length R0 from the group's centre of mass to the point X Y Z (tether) or from GROUP2's centre of mass offset by X Y Z (couple); NULL leaves an axis free; f_ID energy, f_ID[1..4] force",
);

/// LIGGGHTS's smallest spring length (length), so a spring at rest has a direction.
const SMALL: f64 = 1.0e-10;

/// What the spring connects the group's centre of mass to.
#[derive(Debug, Clone, PartialEq)]
pub enum Anchor {
    /// `tether`: a fixed point.
    Tether,
    /// `couple GROUP2`: the centre of mass of this group (bits), offset by the point.
    Couple(u32),
}

/// One `fix spring`.
#[derive(Debug, Clone, PartialEq)]
pub struct Spring {
    /// Tether or couple.
    pub anchor: Anchor,
    /// Stiffness (force/length).
    pub k: f64,
    /// The point (tether) or offset (couple) per axis (length); None: NULL, axis free.
    pub point: [Option<f64>; 3],
    /// Rest length (length).
    pub r0: f64,
    /// The group's mass at the run's start (mass), as LIGGGHTS keeps it.
    pub mass: f64,
    /// The second group's mass at the run's start (mass).
    pub mass2: f64,
    /// The spring's energy (energy).
    pub energy: f64,
    /// Force on the group (force) and its signed magnitude.
    pub ftotal: [f64; 4],
}

/// The centre of mass of `group` (unwrapped, length) divided by `mass`, as LIGGGHTS's
/// `Group::xcm` sums it.
fn xcm(p: &Particles, domain: &Domain, group: u32, mass: f64) -> [f64; 3] {
    let mut cm = [0.0; 3];
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            let m = p.mass[i];
            for (d, c) in cm.iter_mut().enumerate() {
                let xu = p.x[i][d] + p.image[i][d] as f64 * domain.length(d);
                *c += xu * m;
            }
        }
    }
    if mass > 0.0 {
        cm = cm.map(|c| c / mass);
    }
    cm
}

/// The summed mass of `group` (mass).
fn mass_of(p: &Particles, group: u32) -> f64 {
    (0..p.len())
        .filter(|&i| p.mask[i] & group != 0)
        .fold(0.0, |m, i| m + p.mass[i])
}

impl Spring {
    /// The spring's force per unit mass of the group (LIGGGHTS's fx/masstotal before it
    /// divides), from the separation `dx` of the centre of mass; sets the energy and totals.
    fn stretch(&mut self, mut dx: [f64; 3], sign: f64) -> [f64; 3] {
        for (d, p) in dx.iter_mut().zip(self.point) {
            if p.is_none() {
                *d = 0.0;
            }
        }
        let r = (dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]).sqrt();
        let r = r.max(SMALL);
        let dr = r - self.r0;
        let f = dx.map(|d| self.k * d * dr / r);
        self.ftotal = [sign * f[0], sign * f[1], sign * f[2], 0.0];
        self.ftotal[3] = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        if dr < 0.0 {
            self.ftotal[3] = -self.ftotal[3];
        }
        self.energy = 0.5 * self.k * dr * dr;
        f
    }

    /// Apply the spring's forces to the particles of `group` (and of the coupled group).
    pub fn apply(&mut self, p: &mut Particles, domain: &Domain, group: u32) {
        let c = xcm(p, domain, group, self.mass);
        let at = self.point.map(|x| x.unwrap_or(0.0));
        match self.anchor {
            Anchor::Tether => {
                let f = self.stretch([c[0] - at[0], c[1] - at[1], c[2] - at[2]], -1.0);
                let f = f.map(|x| x / self.mass);
                for i in 0..p.len() {
                    if p.mask[i] & group != 0 {
                        let m = p.mass[i];
                        for (fi, fd) in p.f[i].iter_mut().zip(f) {
                            *fi -= fd * m;
                        }
                    }
                }
            }
            Anchor::Couple(group2) => {
                let c2 = xcm(p, domain, group2, self.mass2);
                let dx = [0, 1, 2].map(|d| c2[d] - c[d] - at[d]);
                let f = self.stretch(dx, 1.0);
                let f2 = f.map(|x| x / self.mass2);
                let f = f.map(|x| x / self.mass);
                for i in 0..p.len() {
                    let m = p.mass[i];
                    if p.mask[i] & group != 0 {
                        for (fi, fd) in p.f[i].iter_mut().zip(f) {
                            *fi += fd * m;
                        }
                    }
                    if p.mask[i] & group2 != 0 {
                        for (fi, fd) in p.f[i].iter_mut().zip(f2) {
                            *fi -= fd * m;
                        }
                    }
                }
            }
        }
    }
}

impl FixStyle for Spring {
    fn name(&self) -> &str {
        "spring"
    }

    fn setup(&mut self, p: &Particles, at: &FixStep) {
        self.mass = mass_of(p, at.group);
        if let Anchor::Couple(group2) = self.anchor {
            self.mass2 = mass_of(p, group2);
        }
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        self.apply(p, at.domain, at.group);
    }

    /// LIGGGHTS flags its scalar and vector extensive.
    fn extensive(&self, _index: Option<usize>) -> bool {
        true
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        match index {
            None => Some(self.energy),
            Some(i @ 1..=4) => Some(self.ftotal[i - 1]),
            _ => None,
        }
    }
}

/// `fix ID GROUP spring tether K X Y Z R0` or `... couple GROUP2 K X Y Z R0`, with
/// LIGGGHTS's errors.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    const ILLEGAL: &str = "Illegal fix spring command";
    if a.len() < 9 {
        return Err(a.error(2, ILLEGAL));
    }
    let (anchor, first) = match a.word(3)? {
        "tether" => {
            if a.len() != 9 {
                return Err(a.error(3, ILLEGAL));
            }
            (Anchor::Tether, 4)
        }
        "couple" => {
            if a.len() != 10 {
                return Err(a.error(3, ILLEGAL));
            }
            let bit = ctx
                .sim
                .group_bit(a.word(4)?)
                .ok_or_else(|| a.error(4, "Fix spring couple group ID does not exist"))?;
            if bit == fix.bit {
                return Err(a.error(4, "Two groups cannot be the same in fix spring couple"));
            }
            (Anchor::Couple(bit), 5)
        }
        _ => return Err(a.error(3, ILLEGAL)),
    };
    let k = a.real(first)?;
    let mut point = [None; 3];
    for (d, slot) in point.iter_mut().enumerate() {
        if a.word(first + 1 + d)? != "NULL" {
            *slot = Some(a.real(first + 1 + d)?);
        }
    }
    let r0 = a.real(first + 4)?;
    if r0 < 0.0 {
        return Err(a.error(first + 4, "R0 < 0 for fix spring command"));
    }
    Ok(Box::new(Spring {
        anchor,
        k,
        point,
        r0,
        mass: 0.0,
        mass2: 0.0,
        energy: 0.0,
        ftotal: [0.0; 4],
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tether_pulls_the_centre_of_mass_back() {
        let mut p = Particles::default();
        p.push(1, 1, [1.0, 0.0, 0.0], 0.1, 1000.0);
        p.push(2, 1, [3.0, 0.0, 0.0], 0.1, 1000.0);
        p.f = vec![[0.0; 3]; 2];
        let mut s = Spring {
            anchor: Anchor::Tether,
            k: 10.0,
            point: [Some(0.0), None, Some(0.0)],
            r0: 0.5,
            mass: mass_of(&p, 1),
            mass2: 0.0,
            energy: 0.0,
            ftotal: [0.0; 4],
        };
        s.apply(&mut p, &Domain::default(), 1);
        // centre of mass at x = 2, stretched by 1.5: 15 N back toward the point, shared by mass
        assert!((s.ftotal[0] + 15.0).abs() < 1e-12);
        assert!((s.ftotal[3] - 15.0).abs() < 1e-12);
        assert!((s.energy - 11.25).abs() < 1e-12);
        assert!((p.f[0][0] + 7.5).abs() < 1e-12 && (p.f[1][0] + 7.5).abs() < 1e-12);
        assert_eq!(s.value(Some(2)), Some(0.0));
    }
}
