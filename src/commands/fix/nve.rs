//! Velocity-Verlet integration fixes: `nve/sphere` (translation and rotation), `nve`
//! (translation alone) and `nve/noforce` (positions follow velocities).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::integrate;
use crate::engine::particles::Particles;

/// The declared signature of `nve/sphere`.
pub const SPHERE: Spec = style(
    "fix",
    "nve/sphere",
    "fix ID GROUP nve/sphere",
    &[],
    "velocity-Verlet integration of positions and rotations",
);

/// The declared signature of `nve/noforce`.
pub const NOFORCE: Spec = style(
    "fix",
    "nve/noforce",
    "fix ID GROUP nve/noforce",
    &[],
    "positions advance with the velocities; forces leave velocities unchanged",
);

/// The declared signature of `nve`.
pub const PLAIN: Spec = style(
    "fix",
    "nve",
    "fix ID GROUP nve",
    &[],
    "velocity-Verlet integration of positions and velocities (no rotation)",
);

/// `fix nve/sphere`: velocity Verlet for positions and angular velocities of spheres (or of
/// discs in 2d).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NveSphere {
    /// The moment-of-inertia prefactor (I = inertia m r^2): 0.4 for spheres, 0.5 for discs.
    pub inertia: f64,
}

impl FixStyle for NveSphere {
    fn name(&self) -> &str {
        "nve/sphere"
    }

    /// LIGGGHTS's `init`: every integrated particle has a radius.
    fn check(&self, p: &Particles, group: u32, _dimension: u32) -> Result<(), EngineError> {
        let point = (0..p.len()).find(|&i| p.mask[i] & group != 0 && p.radius[i] == 0.0);
        match point {
            Some(i) => Err(format!(
                "Fix nve/sphere requires extended particles (atom {} has radius 0)",
                p.id[i]
            )
            .into()),
            None => Ok(()),
        }
    }

    fn initial_integrate(&mut self, p: &mut Particles, at: &FixStep) {
        integrate::initial_integrate_with(p, at.group, at.dt, self.inertia);
    }

    fn final_integrate(&mut self, p: &mut Particles, at: &FixStep) {
        integrate::final_integrate_with(p, at.group, at.dt, self.inertia);
    }
}

/// `fix nve/noforce`: x += dt v in `initial_integrate` (LIGGGHTS's; there is no final step).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NveNoforce;

impl FixStyle for NveNoforce {
    fn name(&self) -> &str {
        "nve/noforce"
    }

    fn initial_integrate(&mut self, p: &mut Particles, at: &FixStep) {
        for i in 0..p.len() {
            if p.mask[i] & at.group != 0 {
                for d in 0..3 {
                    p.x[i][d] += at.dt * p.v[i][d];
                }
            }
        }
    }
}

/// `fix nve`: half-kick and drift, then the second half-kick (angular velocities untouched).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Nve;

impl FixStyle for Nve {
    fn name(&self) -> &str {
        "nve"
    }

    /// Half-kick v with the force, then drift x by a full step.
    fn initial_integrate(&mut self, p: &mut Particles, at: &FixStep) {
        half_kick(p, at);
        for i in 0..p.len() {
            if p.mask[i] & at.group != 0 {
                for d in 0..3 {
                    p.x[i][d] += at.dt * p.v[i][d];
                }
            }
        }
    }

    /// The second half-kick.
    fn final_integrate(&mut self, p: &mut Particles, at: &FixStep) {
        half_kick(p, at);
    }
}

/// `fix ID GROUP nve/noforce`: positions follow velocities, forces are ignored.
pub fn noforce(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() != 3 {
        return Err(a.error(3, "Illegal fix nve/noforce command"));
    }
    Ok(Box::new(NveNoforce))
}

/// `fix ID GROUP nve/sphere`: positions, velocities and angular velocities of spheres.
pub fn sphere(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() > 3 {
        return Err(a.unsupported(3, "fix nve/sphere keywords"));
    }
    // LIGGGHTS integrates discs in 2d (moment of inertia 0.5 m r^2)
    let inertia = if ctx.sim.dimension == 2 {
        crate::engine::planar::DISC_INERTIA
    } else {
        integrate::SPHERE_INERTIA
    };
    Ok(Box::new(NveSphere { inertia }))
}

/// `fix ID GROUP nve`: positions and velocities (angular velocities left alone).
pub fn plain(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() != 3 {
        return Err(a.error(3, "Illegal fix nve command"));
    }
    Ok(Box::new(Nve))
}

/// Half-kick the velocities of the fix's group: v += (dt / 2) f / m (velocity).
fn half_kick(p: &mut Particles, at: &FixStep) {
    let dtf = 0.5 * at.dt;
    for i in 0..p.len() {
        if p.mask[i] & at.group != 0 {
            let dtfm = dtf / p.mass[i];
            for d in 0..3 {
                p.v[i][d] += dtfm * p.f[i][d];
            }
        }
    }
}
