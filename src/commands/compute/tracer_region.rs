//! `compute nparticles/tracer/region`: the particles in a region and those a tracer fix
//! marked, with their masses.

use crate::commands::compute::ComputeDef;
use crate::commands::specs::{arg, kw, style, Spec, Value, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::particles::Particles;
use crate::engine::sim::VariableSource;
use crate::engine::tracer::TracerCount;

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "nparticles/tracer/region",
    "compute ID GROUP nparticles/tracer/region region_count R tracer T",
    &[
        kw(
            "periodic",
            &[
                arg("x|y|z", Value::OneOf(&["x", "y", "z"])),
                arg("IMAGE|all", Value::Word),
            ],
            "count only particles in this periodic image",
        ),
        kw(
            "reset_marker",
            &[arg("yes|no", YES_NO)],
            "un-mark counted particles (default yes)",
        ),
    ],
    "particles and marked particles in a region and their masses (c_ID[1..4])",
);

/// `compute nparticles/tracer/region`: count, marked count, mass, marked mass (`c_ID[1..4]`).
#[derive(Debug)]
pub struct TracerRegion(TracerCount);

impl ComputeStyle for TracerRegion {
    fn name(&self) -> &str {
        "nparticles/tracer/region"
    }

    fn vector_len(&self) -> usize {
        4
    }

    fn vector(
        &self,
        at: &ComputeAt,
        index: usize,
        _vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        let sim = at.sim;
        Ok(self.0.values(&sim.particles, at.group, &sim.regions)[index - 1])
    }

    fn before_step(&mut self, p: &mut Particles) {
        self.0.apply_resets(p);
    }
}

/// `compute ID GROUP nparticles/tracer/region region_count R tracer T [periodic DIM
/// IMAGE|all] [reset_marker yes|no]`: a 4-vector (count, marked count, mass, marked mass).
pub fn build(
    a: &Args,
    ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let id = a.word(0)?;
    let fail = |i: usize, m: &str| {
        a.error(
            i,
            format!("Compute nparticles/tracer/region (id {id}): {m}"),
        )
    };
    let (mut region, mut tracer, mut image, mut reset) = (None, None, None, true);
    let mut i = 3;
    while i < a.len() {
        match a.word(i)? {
            "periodic" => {
                if a.len() < i + 3 {
                    return Err(fail(i, "not enough arguments for 'periodic'"));
                }
                let dim = match a.word(i + 1)? {
                    "x" => 0,
                    "y" => 1,
                    "z" => 2,
                    _ => return Err(fail(i + 1, "'x', 'y' or 'z' expected after 'periodic'")),
                };
                let which = match a.word(i + 2)? {
                    "all" => None,
                    _ => Some(a.int(i + 2)? as i32),
                };
                if !ctx.sim.domain.periodic(dim) {
                    return Err(fail(
                        i + 1,
                        "using 'periodic' in a dimension which is not periodic",
                    ));
                }
                image = Some((dim, which));
                i += 3;
            }
            "reset_marker" => {
                if a.len() < i + 2 {
                    return Err(fail(i, "not enough arguments for 'reset_marker'"));
                }
                reset = match a.word(i + 1)? {
                    "yes" => true,
                    "no" => false,
                    _ => return Err(fail(i + 1, "expecing 'yes' or 'no' for 'reset_marker'")),
                };
                i += 2;
            }
            "tracer" => {
                if a.len() < i + 2 {
                    return Err(fail(i, "not enough arguments for 'tracer'"));
                }
                tracer = Some((i + 1, a.word(i + 1)?.to_string()));
                i += 2;
            }
            "region_count" => {
                if a.len() < i + 2 {
                    return Err(fail(i, "not enough arguments for 'region_count'"));
                }
                region = Some(
                    ctx.sim
                        .regions
                        .find(a.word(i + 1)?)
                        .ok_or_else(|| fail(i + 1, "Region ID does not exist"))?,
                );
                i += 2;
            }
            _ => return Err(fail(i, "unknown keyword")),
        }
    }
    let (at, tracer) = tracer.ok_or_else(|| fail(2, "have to define 'tracer'"))?;
    let region = region.ok_or_else(|| fail(2, "have to define 'region_count'"))?;
    if !ctx
        .sim
        .fixes
        .iter()
        .any(|f| f.id == tracer && f.style == "property/atom/tracer")
    {
        return Err(fail(
            at,
            "need a tracer fix of type fix property/atom/tracer",
        ));
    }
    Ok(Box::new(TracerRegion(TracerCount {
        region,
        tracer,
        image,
        reset,
        pending: std::sync::Mutex::new(Vec::new()),
    })))
}
