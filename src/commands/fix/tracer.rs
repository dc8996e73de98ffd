//! `fix property/atom/tracer`: mark particles that are inside a region (`end_of_step`;
//! the marker per atom as f_ID, the particles marked since the last read as global f_ID).

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStep, FixStyle, PerAtomShape};
use crate::engine::particles::Particles;
use crate::engine::tracer::{MarkerStyle, Tracer};

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "property/atom/tracer",
    "fix ID GROUP property/atom/tracer region_mark R mark_step S",
    &[
        kw(
            "marker_style",
            &[arg(
                "dirac|heaviside|none",
                Value::OneOf(&["dirac", "heaviside", "none"]),
            )],
            "mark once at the mark step, or at every check from it on",
        ),
        kw(
            "check_mark_every",
            &[arg("N", Value::Int)],
            "steps between checks (default 10)",
        ),
    ],
    "mark particles inside a region (per-atom f_ID; f_ID: marked since last read)",
);

impl FixStyle for Tracer {
    fn name(&self) -> &str {
        "property/atom/tracer"
    }

    fn end_of_step(&mut self, p: &mut Particles, at: &FixStep) {
        if at.step % self.every == 0 {
            if let Some(regions) = at.regions {
                self.mark(p, at.group, regions, at.step);
            }
        }
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        match index {
            None => Some(self.scalar()),
            Some(_) => None,
        }
    }

    fn scalar_before_per_atom(&self) -> bool {
        true
    }

    fn per_atom_shape(&self) -> PerAtomShape {
        PerAtomShape::Vector
    }

    fn per_atom(&self, p: &Particles) -> Vec<f64> {
        self.markers(p)
    }
}

/// `fix ID GROUP property/atom/tracer region_mark R mark_step S [marker_style
/// dirac|heaviside|none] [check_mark_every N]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let id = fix.id;
    let fail = |i: usize, m: &str| a.error(i, format!("Fix property/atom/tracer (id {id}): {m}"));
    let (mut region, mut step, mut style, mut every) = (None, None, MarkerStyle::Dirac, 10);
    let mut first_mark = true;
    let mut i = 3;
    while i < a.len() {
        let key = a.word(i)?;
        if !matches!(
            key,
            "region_mark" | "mark_step" | "marker_style" | "check_mark_every"
        ) {
            return Err(fail(i, "unknown keyword"));
        }
        if a.len() < i + 2 {
            return Err(fail(i, &format!("not enough arguments for '{key}'")));
        }
        match key {
            "region_mark" => {
                region = Some(
                    ctx.sim
                        .regions
                        .find(a.word(i + 1)?)
                        .ok_or_else(|| fail(i + 1, "Region ID does not exist"))?,
                );
            }
            "mark_step" => {
                let s = a.int(i + 1)?;
                if s < 0 {
                    return Err(fail(i + 1, "mark_step > 0 required"));
                }
                if s < ctx.sim.step {
                    first_mark = false;
                }
                step = Some(s);
            }
            "marker_style" => {
                style = match a.word(i + 1)? {
                    "dirac" => MarkerStyle::Dirac,
                    "heaviside" => MarkerStyle::Heaviside,
                    "none" => MarkerStyle::None,
                    _ => {
                        return Err(fail(
                            i + 1,
                            "expecting 'heaviside' or 'dirac' after keyword 'marker_style'",
                        ))
                    }
                };
            }
            _ => {
                every = a.int(i + 1)?;
                if every <= 0 {
                    return Err(fail(i + 1, "check_mark_every > 0 required"));
                }
            }
        }
        i += 2;
    }
    let region = region.ok_or_else(|| fail(2, "expecting keyword 'region_mark'"))?;
    let step = step.ok_or_else(|| fail(2, "expecting keyword 'mark_step'"))?;
    Ok(Box::new(Tracer {
        region,
        step,
        style,
        every,
        first_mark,
        marker: id.to_string(),
        marked: 0,
        marked_read: std::sync::atomic::AtomicI64::new(0),
    }))
}
