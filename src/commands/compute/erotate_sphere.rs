//! `compute erotate/sphere` and `erotate` (the group's rotational kinetic energy) and
//! `compute erotate/sphere/atom` (each particle's).

use crate::commands::compute::{no_arguments, ComputeDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{rotational_energy, ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::integrate::SPHERE_INERTIA;
use crate::engine::sim::VariableSource;

/// The declared signature of `erotate`.
pub const EROTATE: Spec = style(
    "compute",
    "erotate",
    "compute ID GROUP erotate",
    &[],
    "rotational kinetic energy of the group (through an erotate/sphere compute)",
);

/// The declared signature of `erotate/sphere`.
pub const SPHERE: Spec = style(
    "compute",
    "erotate/sphere",
    "compute ID GROUP erotate/sphere",
    &[],
    "rotational kinetic energy of the group",
);

/// The declared signature of `erotate/sphere/atom`.
pub const ATOM: Spec = style(
    "compute",
    "erotate/sphere/atom",
    "compute ID GROUP erotate/sphere/atom",
    &[],
    "rotational kinetic energy per particle (energy)",
);

/// `compute erotate/sphere` (and `erotate`, which LIGGGHTS sums from one): 0.5 I w^2
/// summed over the group's spheres (energy), members of multisphere clumps left out.
#[derive(Debug)]
pub struct ErotateSphere {
    /// The style name as written (`erotate` or `erotate/sphere`).
    name: &'static str,
}

impl ComputeStyle for ErotateSphere {
    fn name(&self) -> &str {
        self.name
    }

    fn has_scalar(&self) -> bool {
        true
    }

    fn extensive_scalar(&self) -> bool {
        true
    }

    fn scalar(&self, at: &ComputeAt, _vars: &mut dyn VariableSource) -> Result<f64, EngineError> {
        Ok(rotational_energy(&at.sim.particles, at.group))
    }
}

/// `compute erotate/sphere/atom`: 0.5 I w^2 per sphere (energy), 0 for members of
/// multisphere clumps.
#[derive(Debug)]
pub struct ErotateSphereAtom;

impl ComputeStyle for ErotateSphereAtom {
    fn name(&self) -> &str {
        "erotate/sphere/atom"
    }

    fn per_atom_columns(&self) -> usize {
        1
    }

    fn per_atom(
        &self,
        at: &ComputeAt,
        values: &mut [f64],
        _vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let p = &at.sim.particles;
        let tags = crate::engine::clumps::body_tags(p);
        for (i, value) in values.iter_mut().enumerate() {
            if at.in_group(i) && !crate::engine::clumps::is_member(tags, i) {
                let w = p.omega[i];
                *value = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
                    * p.radius[i]
                    * p.radius[i]
                    * p.mass[i];
                *value *= 0.5 * 1.0 * SPHERE_INERTIA;
            }
        }
        Ok(())
    }
}

/// `compute ID GROUP erotate/sphere`.
pub fn sphere(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    no_arguments(a, "erotate/sphere")?;
    Ok(Box::new(ErotateSphere {
        name: "erotate/sphere",
    }))
}

/// `compute ID GROUP erotate`: LIGGGHTS 3.8.0 defines an internal compute
/// `erotate_sphere_` for it, so a deck can have only one. Its constructor prints
/// `igrpu: GROUP` with `printf` (standard output, not the log), before that check.
pub fn erotate(
    a: &Args,
    ctx: &mut Ctx,
    def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    no_arguments(a, "erotate")?;
    ctx.out.stdout(&format!("igrpu: {}\n", def.group));
    if ctx.sim.computes.iter().any(|c| c.style == "erotate") {
        return Err(a.error(0, "Reuse of compute ID").with_help(
            "LIGGGHTS 3.8.0's compute erotate defines an internal compute \
             erotate_sphere_, so a deck can have only one; use compute erotate/sphere",
        ));
    }
    Ok(Box::new(ErotateSphere { name: "erotate" }))
}

/// `compute ID GROUP erotate/sphere/atom`.
pub fn atom(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    no_arguments(a, "erotate/sphere/atom")?;
    Ok(Box::new(ErotateSphereAtom))
}
