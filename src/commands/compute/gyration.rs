//! `compute gyration`: the group's radius of gyration and its tensor, from unwrapped
//! positions (LIGGGHTS 3.8.0's compute_gyration.cpp).

use crate::commands::compute::after_general_keyword;
use crate::commands::compute::ComputeDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{center_from_moment, mass_moment, ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::particles::Particles;
use crate::engine::sim::{Simulation, VariableSource};

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "gyration",
    "compute ID GROUP gyration",
    &[],
    "radius of gyration of the group (length) and its tensor xx yy zz xy xz yz (area, c_ID[1..6]), unwrapped",
);

/// `compute gyration`: Rg (length) as the scalar, the tensor (area) as `c_ID[1..6]`.
#[derive(Debug, Default)]
pub struct Gyration {
    /// The group's mass at the start of the run (mass): LIGGGHTS divides by the mass its
    /// `init` took, so particles inserted or deleted during the run do not change it.
    mass: f64,
}

/// Each member's unwrapped arm (length) with its mass, from the centre LIGGGHTS's group->xcm
/// gives for the run-start `mass`.
fn arms(at: &ComputeAt, mass: f64) -> Vec<([f64; 3], f64)> {
    let (p, domain) = (&at.sim.particles, &at.sim.domain);
    let cm = center_from_moment(mass_moment(p, domain, at.group).0, mass);
    (0..p.len())
        .filter(|&i| at.in_group(i))
        .map(|i| {
            let d = [0, 1, 2].map(|k| p.x[i][k] + p.image[i][k] as f64 * domain.length(k) - cm[k]);
            (d, p.mass[i])
        })
        .collect()
}

impl ComputeStyle for Gyration {
    fn name(&self) -> &str {
        "gyration"
    }

    fn setup(&mut self, p: &Particles, group: u32) {
        self.mass = crate::engine::momentum::group_mass(p, group);
    }

    fn has_scalar(&self) -> bool {
        true
    }

    fn scalar(&self, at: &ComputeAt, _vars: &mut dyn VariableSource) -> Result<f64, EngineError> {
        let (mass, arms) = (self.mass, arms(at, self.mass));
        let rg: f64 = arms
            .iter()
            .map(|([dx, dy, dz], m)| (dx * dx + dy * dy + dz * dz) * m)
            .fold(0.0, |a, b| a + b);
        Ok(if mass > 0.0 { (rg / mass).sqrt() } else { 0.0 })
    }

    fn vector_len(&self) -> usize {
        6
    }

    fn vector(
        &self,
        at: &ComputeAt,
        index: usize,
        _vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        let (mass, arms) = (self.mass, arms(at, self.mass));
        let mut rg = [0.0; 6];
        for ([dx, dy, dz], m) in arms {
            let t = [dx * dx, dy * dy, dz * dz, dx * dy, dx * dz, dy * dz];
            for (r, v) in rg.iter_mut().zip(t) {
                *r += v * m;
            }
        }
        let k = index - 1;
        Ok(if mass == 0.0 { rg[k] } else { rg[k] / mass })
    }

    fn extensive(&self, _sim: &Simulation, column: Option<usize>) -> Option<i8> {
        column.is_none().then_some(0)
    }
}

/// `compute ID GROUP gyration [update_on_run_end no]`.
pub fn build(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let i = after_general_keyword(a, "gyration")?;
    if a.len() != i {
        return Err(a.error(i, "Illegal compute gyration command"));
    }
    Ok(Box::new(Gyration::default()))
}
