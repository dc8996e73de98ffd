//! Group functions of formulas: `count(g)`, `mass(g)`, `xcm(g,dim)`, `vcm(g,dim)`,
//! `fcm(g,dim)`, `bound(g,xmin|xmax|...)`, `ke(g)`, and about the centre of mass
//! `gyration(g)`, `angmom(g,dim)`, `torque(g,dim)`, `inertia(g,xx|yy|zz|xy|yz|xz)` and
//! `omega(g,dim)`, each with an optional region, summed over the members in particle order
//! as LIGGGHTS 3.8.0's Group does.

use crate::engine::error::EngineError;
use crate::engine::sim::Simulation;
use crate::lang::system::Mode;

impl Simulation {
    /// Group functions of formulas: `count(g)`, `mass(g)`, `xcm(g,dim)`, `vcm(g,dim)`,
    /// `fcm(g,dim)`, `bound(g,xmin|xmax|...)`, `ke(g)`, each with an optional region.
    pub fn group_function(
        &self,
        name: &str,
        args: &[String],
        mode: Mode,
    ) -> Result<f64, EngineError> {
        if mode == Mode::Check {
            return Err(EngineError::KnownWhenRun);
        }
        let members = group_members(self, name, args)?;
        let p = &self.particles;
        let mass = members.iter().fold(0.0, |s, &i| s + p.mass[i]);
        Ok(match name {
            "count" => members.len() as f64,
            "mass" => mass,
            "xcm" | "vcm" => mass_weighted_mean(self, name, dim(&args[1])?, &members, mass),
            "fcm" => {
                let d = dim(&args[1])?;
                members.iter().fold(0.0, |s, &i| s + p.f[i][d])
            }
            "bound" => bound(self, &args[1], &members)?,
            "ke" => kinetic_energy(self, &members),
            "gyration" | "angmom" | "torque" | "inertia" | "omega" => {
                about_centre(self, name, args, &members, mass)?
            }
            other => {
                return Err(EngineError::Unsupported(format!(
                    "group function {other}()"
                )))
            }
        })
    }
}

/// LIGGGHTS's error for a group function's arguments it does not take.
fn invalid() -> EngineError {
    EngineError::from("Invalid group function in variable formula")
}

/// The component `x`, `y` or `z` of a group function's argument.
fn dim(w: &str) -> Result<usize, EngineError> {
    match w {
        "x" => Ok(0),
        "y" => Ok(1),
        "z" => Ok(2),
        _ => Err(invalid()),
    }
}

/// The particles group function `name` sums over: those of the group `args[0]`, inside the
/// region of the last argument when one is given, in particle order.
fn group_members(sim: &Simulation, name: &str, args: &[String]) -> Result<Vec<usize>, EngineError> {
    let bit = sim
        .group_bit(args.first().map(String::as_str).unwrap_or(""))
        .ok_or("Group ID in variable formula does not exist")?;
    let takes_dim = matches!(
        name,
        "xcm" | "vcm" | "fcm" | "bound" | "angmom" | "torque" | "inertia" | "omega"
    );
    let region_arg = args.get(if takes_dim { 2 } else { 1 });
    if args.len() > if takes_dim { 3 } else { 2 } || (takes_dim && args.len() < 2) {
        return Err(invalid());
    }
    let region = match region_arg {
        Some(r) => Some(
            sim.regions
                .find(r)
                .ok_or("Region ID in variable formula does not exist")?,
        ),
        None => None,
    };
    let p = &sim.particles;
    Ok((0..p.len())
        .filter(|&i| p.mask[i] & bit != 0 && region.is_none_or(|r| sim.regions.matches(r, p.x[i])))
        .collect())
}

/// `xcm` (unwrapped positions, length) or `vcm` (velocities, length/time) along `d`: the
/// mass-weighted mean over `members` of total `mass` (0 for a massless group).
fn mass_weighted_mean(sim: &Simulation, name: &str, d: usize, members: &[usize], mass: f64) -> f64 {
    let p = &sim.particles;
    let mut sum = 0.0;
    for &i in members {
        let value = if name == "xcm" {
            p.x[i][d] + p.image[i][d] as f64 * sim.domain.length(d)
        } else {
            p.v[i][d]
        };
        sum += value * p.mass[i];
    }
    if mass > 0.0 {
        sum / mass
    } else {
        0.0
    }
}

/// `bound(g,xmin|xmax|ymin|ymax|zmin|zmax)`: the smallest or largest coordinate of the
/// members (length; LIGGGHTS's +-1e20 for an empty group).
fn bound(sim: &Simulation, which: &str, members: &[usize]) -> Result<f64, EngineError> {
    let (d, lower) = match which {
        "xmin" => (0, true),
        "xmax" => (0, false),
        "ymin" => (1, true),
        "ymax" => (1, false),
        "zmin" => (2, true),
        "zmax" => (2, false),
        _ => return Err(invalid()),
    };
    let values = members.iter().map(|&i| sim.particles.x[i][d]);
    Ok(if lower {
        values.fold(1.0e20, f64::min)
    } else {
        values.fold(-1.0e20, f64::max)
    })
}

/// `ke(g)`: the translational kinetic energy of the members (energy).
fn kinetic_energy(sim: &Simulation, members: &[usize]) -> f64 {
    let p = &sim.particles;
    let mut ke = 0.0;
    for &i in members {
        let v = p.v[i];
        ke += p.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    0.5 * ke
}

/// The value of group function `name` about the centre of mass over `members` (particle
/// indices) of total `mass`; `args[1]` is the component for all but `gyration`.
pub fn about_centre(
    sim: &Simulation,
    name: &str,
    args: &[String],
    members: &[usize],
    mass: f64,
) -> Result<f64, EngineError> {
    let p = &sim.particles;
    let unwrap = |i: usize| -> [f64; 3] {
        [0, 1, 2].map(|d| p.x[i][d] + p.image[i][d] as f64 * sim.domain.length(d))
    };
    let mut cm = [0.0; 3];
    for &i in members {
        let u = unwrap(i);
        for d in 0..3 {
            cm[d] += u[d] * p.mass[i];
        }
    }
    if mass > 0.0 {
        cm = cm.map(|c| c / mass);
    }
    let arm = |i: usize| {
        let u = unwrap(i);
        [u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]]
    };
    let angmom = || {
        let mut l = [0.0; 3];
        for &i in members {
            let ([dx, dy, dz], m, v) = (arm(i), p.mass[i], p.v[i]);
            l[0] += m * (dy * v[2] - dz * v[1]);
            l[1] += m * (dz * v[0] - dx * v[2]);
            l[2] += m * (dx * v[1] - dy * v[0]);
        }
        l
    };
    let inertia = || {
        let mut t = [[0.0; 3]; 3];
        for &i in members {
            crate::engine::momentum::add_inertia(&mut t, arm(i), p.mass[i]);
        }
        crate::engine::momentum::mirror_inertia(&mut t);
        t
    };
    let dim = || match args.get(1).map(String::as_str) {
        Some("x") => Ok(0),
        Some("y") => Ok(1),
        Some("z") => Ok(2),
        _ => Err(invalid()),
    };
    Ok(match name {
        "gyration" => {
            let mut rg = 0.0;
            for &i in members {
                let [dx, dy, dz] = arm(i);
                rg += (dx * dx + dy * dy + dz * dz) * p.mass[i];
            }
            if mass > 0.0 {
                (rg / mass).sqrt()
            } else {
                0.0
            }
        }
        "angmom" => angmom()[dim()?],
        "torque" => {
            let mut tq = [0.0; 3];
            for &i in members {
                let ([dx, dy, dz], f) = (arm(i), p.f[i]);
                tq[0] += dy * f[2] - dz * f[1];
                tq[1] += dz * f[0] - dx * f[2];
                tq[2] += dx * f[1] - dy * f[0];
            }
            tq[dim()?]
        }
        "inertia" => {
            let (r, c) = match args.get(1).map(String::as_str) {
                Some("xx") => (0, 0),
                Some("yy") => (1, 1),
                Some("zz") => (2, 2),
                Some("xy") => (0, 1),
                Some("yz") => (1, 2),
                Some("xz") => (0, 2),
                _ => return Err(invalid()),
            };
            inertia()[r][c]
        }
        "omega" => {
            let d = dim()?;
            crate::engine::momentum::omega(angmom(), inertia())[d]
        }
        other => {
            return Err(EngineError::Unsupported(format!(
                "group function {other}()"
            )))
        }
    })
}
