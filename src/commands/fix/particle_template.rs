//! `fix particletemplate/sphere`: the spheres an insertion makes.

use super::seed_arg;
use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStyle, RestoreError};
use crate::engine::insert::Template;
use crate::engine::restart_fixes::{doubles, to_bytes};

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "particletemplate/sphere",
    "fix ID GROUP particletemplate/sphere SEED atom_type T density constant D radius constant|gaussian|lognormal|uniform ...",
    &[kw(
        "volume_limit",
        &[arg("V", Value::Real("volume"))],
        "smallest particle volume",
    )],
    "one kind of sphere: type, density (density), radius (length)",
);

/// `fix ID GROUP particletemplate/sphere SEED atom_type T density constant D radius constant R`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let id = fix.id;
    a.count(4..=usize::MAX, "fix ID GROUP particletemplate/sphere SEED atom_type T density constant D radius constant R")?;
    let seed = seed_arg(a, ctx, 3)?;
    let mut s = Sphere {
        atom_type: 1,
        density: None,
        radius: None,
        volume_limit: 1e-12,
    };
    let mut i = 4;
    while i < a.len() {
        i = keyword(a, ctx, i, id, &mut s)?;
    }
    let density = s
        .density
        .ok_or_else(|| a.error(2, "Fix particletemplate/sphere: have to define 'density'"))?;
    let radius = s
        .radius
        .ok_or_else(|| a.error(2, "Fix particletemplate/sphere: have to define 'radius'"))?;
    check_sphere(a, radius, density)?;
    let mut template = Template::new(id, s.atom_type, radius, density);
    template.rng_state = (seed, seed);
    if template.volume < s.volume_limit {
        return Err(a.error(2, "Fix particletemplate/sphere: Volume expectancy too small. Change 'volume_limit' or particle size in the simulation"));
    }
    Ok(Box::new(template))
}

/// The sphere the keywords describe.
struct Sphere {
    /// `atom_type`.
    atom_type: u32,
    /// `density constant D` (mass/length^3).
    density: Option<f64>,
    /// `radius constant R` (length).
    radius: Option<f64>,
    /// `volume_limit` (length^3).
    volume_limit: f64,
}

/// Read the keyword at word `i` into `s`: the word after it and its values.
fn keyword(a: &Args, ctx: &Ctx, i: usize, id: &str, s: &mut Sphere) -> Result<usize, CommandError> {
    match a.word(i)? {
        "atom_type" => {
            let t = a.int(i + 1)?;
            if t < 1 || t > ctx.sim.ntypes as i64 {
                return Err(a.error(i + 1, "Fix particletemplate/sphere: atom type out of range"));
            }
            s.atom_type = t as u32;
            Ok(i + 2)
        }
        w @ ("density" | "radius") => {
            let v = constant(a, i, w, id)?;
            if w == "density" {
                s.density = Some(v);
            } else {
                s.radius = Some(v);
            }
            Ok(i + 3)
        }
        "volume_limit" => {
            s.volume_limit = a.real(i + 1)?;
            if s.volume_limit <= 0.0 {
                return Err(a.error(
                    i + 1,
                    "Fix particletemplate/sphere: volume_limit > 0 required",
                ));
            }
            Ok(i + 2)
        }
        "relative" => {
            if a.word_in(i + 1, &["yes", "no"])? == "yes" {
                return Err(a.unsupported(i, "fix particletemplate/sphere relative yes"));
            }
            Ok(i + 2)
        }
        _ => Err(a.keyword_error(
            i,
            &["atom_type", "density", "radius", "volume_limit", "relative"],
        )),
    }
}

/// `density|radius constant V` at word `i` (`what` the keyword): the value, which must be
/// positive. LIGGGHTS 3.8.0 documents random styles but rejects every one.
fn constant(a: &Args, i: usize, what: &str, id: &str) -> Result<f64, CommandError> {
    match a.word(i + 1)? {
        "constant" => {}
        "gaussian" | "lognormal" | "uniform" => {
            return Err(a
                .error(
                    i + 1,
                    format!("Fix particletemplate/sphere (id {id}): invalid {what} random style"),
                )
                .with_help(
                    "LIGGGHTS 3.8.0 accepts only 'constant'; for a size distribution, \
                     give several templates to fix particledistribution/discrete",
                ));
        }
        _ => {
            return Err(a.error(
                i + 1,
                "Illegal fix particletemplate/sphere command: expected 'constant'",
            ))
        }
    }
    let v = a.real(i + 2)?;
    if v <= 0.0 {
        return Err(a.error(
            i + 2,
            format!("Fix particletemplate/sphere: {what} must be > 0"),
        ));
    }
    Ok(v)
}

/// The sphere's size and density checked as particles' are, the error pointing at the last
/// `radius` value.
fn check_sphere(a: &Args, radius: f64, density: f64) -> Result<(), CommandError> {
    if let Err(m) = crate::engine::checks::check_sphere(2.0 * radius, density, "diameter") {
        let at = (4..a.len())
            .rev()
            .find(|&k| a.word(k).ok() == Some("radius"));
        return Err(a.error(
            at.map_or(2, |k| k + 2),
            format!(
                "Fix particletemplate/sphere: radius {}: {m}",
                crate::util::format::g(radius)
            ),
        ));
    }
    Ok(())
}

/// A template acts in no phase: insertion fixes read it through their distributions, the
/// neighbour cutoffs and the time-step checks by type ([`FixKind::template`]).
///
/// [`FixKind::template`]: crate::engine::fixes::FixKind::template
impl FixStyle for Template {
    fn name(&self) -> &str {
        "particletemplate/sphere"
    }

    /// LIGGGHTS's layout: the number of ranks (1), the insertion generator's state, the
    /// Monte Carlo generator's state.
    fn restart_state(&self) -> Option<Vec<u8>> {
        Some(to_bytes(&[
            1.0,
            self.rng_state.0 as f64,
            self.rng_state.1 as f64,
        ]))
    }

    /// The insertion generator's state; the Monte Carlo seed stays the deck's.
    fn restore_state(&mut self, state: &[u8]) -> Result<(), RestoreError> {
        let d = doubles(state);
        if d.len() < 3 {
            return Err(RestoreError::Malformed("too short".into()));
        }
        self.rng_state.0 = d[1] as i32;
        Ok(())
    }

    fn array_unsupported(&self) -> bool {
        true
    }

    fn refuses_thermo(&self) -> bool {
        true
    }
}
