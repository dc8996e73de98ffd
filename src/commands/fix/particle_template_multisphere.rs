//! `fix particletemplate/multisphere`: a rigid clump of spheres and its mass properties.

use super::seed_arg;
use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value, NUMBER};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixStyle;
use crate::engine::multisphere::{ClumpSpec, ClumpTemplate, GivenMass};
use crate::lang::system::Mode;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "particletemplate/multisphere",
    "fix ID GROUP particletemplate/multisphere SEED atom_type T density constant D nspheres N ntry N spheres file F scale S | spheres X Y Z R ... type MT",
    &[
        kw(
            "mass",
            &[arg("M", Value::Real("mass"))],
            "clump mass instead of the sampled one (with inertia_tensor)",
        ),
        kw(
            "inertia_tensor",
            &[arg("IXX IXY IXZ IYY IYZ IZZ", NUMBER)],
            "inertia tensor about the centre of mass (mass*length^2)",
        ),
        kw("use_volume", &[], "density from the given mass and the sampled volume"),
        kw("use_density", &[], "volume from the given mass and the density"),
        kw(
            "fflag",
            &[arg("on|off on|off on|off", Value::Word)],
            "translations integrated along x, y, z",
        ),
        kw(
            "tflag",
            &[arg("on|off on|off on|off", Value::Word)],
            "rotations integrated about x, y, z",
        ),
    ],
    "a rigid clump of spheres (length); volume, centre of mass and inertia by Monte Carlo with NTRY samples",
);

const USAGE: &str = "fix ID GROUP particletemplate/multisphere SEED atom_type T density constant D nspheres N ntry N spheres file F scale S type MT";

/// `fix ID GROUP particletemplate/multisphere SEED [atom_type T] density constant D
/// nspheres N ntry N spheres (file F scale S | x y z r ...) type MT [mass M inertia_tensor
/// Ixx Ixy Ixz Iyy Iyz Izz use_volume|use_density] [fflag f f f] [tflag f f f]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let id = fix.id;
    let fail = |i: usize, m: &str| failure(a, id, i, m);
    a.count(4..=usize::MAX, USAGE)?;
    let seed = seed_arg(a, ctx, 3)?;
    let mut i = 4;
    let (atom_type, density) = template_keywords(a, ctx, id, &mut i)?;
    let density = density.ok_or_else(|| fail(2, "have to define 'density'"))?;
    let (nspheres, ntry, ntry_at) = counts(a, id, &mut i)?;
    let spheres = spheres(a, ctx, id, &mut i, nspheres)?
        .ok_or_else(|| fail(2, "need to define spheres for the template"))?;
    if ntry < 1000 {
        return Err(fail(ntry_at, "ntry is too low"));
    }
    let mut props = MassArgs::default();
    while i < a.len() {
        i += props.keyword(a, id, i)?;
    }
    let (shape_type, given) = props.given(a, id)?;
    if ctx.sys.mode == Mode::Run {
        ctx.out.screen(
            "Calculating the properties of the given template.\n   Depending on ntry, this may take a while...\n",
        );
    }
    if ntry < 100_000 {
        ctx.say("WARNING: fix particletemplate/multisphere: ntry is very low (./src/fix_template_multiplespheres.cpp:230)\n");
    }
    let template = ClumpTemplate::build(ClumpSpec {
        id: id.to_string(),
        atom_type,
        shape_type,
        density,
        spheres,
        ntry,
        seed,
        given,
        fflag: props.fflag,
        tflag: props.tflag,
    })
    .map_err(|e| fail(2, &e.to_string()))?;
    if ctx.sys.mode == Mode::Run {
        ctx.out.log(&template.report());
    }
    Ok(Box::new(template))
}

/// LIGGGHTS's error of fix `id` at word `i`.
fn failure(a: &Args, id: &str, i: usize, m: &str) -> CommandError {
    a.error(
        i,
        format!("Fix particletemplate/multisphere (id {id}): {m}"),
    )
}

/// The keywords every particle template takes, from word `i` on (left at the first other
/// word): the atom type and the density (mass/length^3) when given.
fn template_keywords(
    a: &Args,
    ctx: &Ctx,
    id: &str,
    i: &mut usize,
) -> Result<(u32, Option<f64>), CommandError> {
    let fail = |i: usize, m: &str| failure(a, id, i, m);
    let (mut atom_type, mut density) = (1u32, None);
    while *i < a.len() {
        let at = *i;
        match a.word(at)? {
            "atom_type" => {
                let t = a.int(at + 1)?;
                if t < 1 {
                    return Err(fail(at + 1, "invalid atom type (must be >=1)"));
                }
                if t > ctx.sim.ntypes as i64 {
                    return Err(fail(at + 1, "atom type out of range"));
                }
                atom_type = t as u32;
                *i += 2;
            }
            "density" => {
                if a.word(at + 1)? != "constant" {
                    return Err(fail(at + 1, "invalid density random style"));
                }
                let v = a.real(at + 2)?;
                if v <= 0.0 {
                    return Err(fail(at + 2, "density must be >= 0"));
                }
                density = Some(v);
                *i += 3;
            }
            "volume_limit" => {
                if a.real(at + 1)? <= 0.0 {
                    return Err(fail(at + 1, "volume_limit > 0 required"));
                }
                *i += 2;
            }
            "relative" => {
                if a.word_in(at + 1, &["yes", "no"])? == "yes" {
                    return Err(a.unsupported(at, "fix particletemplate/multisphere relative yes"));
                }
                *i += 2;
            }
            "radius" => {
                return Err(fail(
                    at,
                    "keyword radius only valid for particletemplate/sphere",
                ))
            }
            w @ ("region" | "region_variable" | "additional_group") => {
                return Err(a.unsupported(at, &format!("fix particletemplate/multisphere {w}")))
            }
            _ => break,
        }
    }
    Ok((atom_type, density))
}

/// `nspheres N ntry N` at word `i` (left after them): the counts and ntry's word.
fn counts(a: &Args, id: &str, i: &mut usize) -> Result<(i64, i32, usize), CommandError> {
    let fail = |i: usize, m: &str| failure(a, id, i, m);
    if a.word(*i)? != "nspheres" {
        return Err(fail(*i, "expecting argument 'nspheres'"));
    }
    let nspheres = a.int32(*i + 1)?;
    if nspheres < 2 {
        return Err(fail(*i + 1, "illegal number of spheres"));
    }
    *i += 2;
    if a.len() < *i + 4 {
        return Err(fail(a.len() - 1, "not enough arguments"));
    }
    if a.word(*i)? != "ntry" {
        return Err(fail(*i, "need 'ntry' to be defined"));
    }
    let ntry_at = *i + 1;
    let ntry = a.int32(ntry_at)? as i32;
    *i += 2;
    Ok((nspheres, ntry, ntry_at))
}

/// The `spheres` (and `bonded`) keywords from word `i` on (left at the first other word):
/// the spheres (x, y, z, r; length) when given.
fn spheres(
    a: &Args,
    ctx: &Ctx,
    id: &str,
    i: &mut usize,
    nspheres: i64,
) -> Result<Option<Vec<[f64; 4]>>, CommandError> {
    let mut spheres = None;
    while *i < a.len() {
        match a.word(*i)? {
            "spheres" => {
                *i += 1;
                let (list, used) = if a.word(*i)? == "file" {
                    sphere_file(a, ctx, id, *i, nspheres as usize)?
                } else {
                    sphere_list(a, id, *i, nspheres as usize)?
                };
                spheres = Some(list);
                *i += used;
            }
            "spheres_different_types" => {
                return Err(a.unsupported(
                    *i,
                    "fix particletemplate/multisphere spheres_different_types",
                ))
            }
            "bonded" => {
                if a.word_in(*i + 1, &["yes", "no"])? == "yes" {
                    return Err(a.unsupported(*i, "fix particletemplate/multisphere bonded yes"));
                }
                *i += 2;
            }
            _ => break,
        }
    }
    Ok(spheres)
}

/// `file F scale S` at word `i`: the `n` spheres of the clump file, scaled, and the words
/// taken.
fn sphere_file(
    a: &Args,
    ctx: &Ctx,
    id: &str,
    i: usize,
    n: usize,
) -> Result<(Vec<[f64; 4]>, usize), CommandError> {
    let fail = |i: usize, m: &str| failure(a, id, i, m);
    if a.len() < i + 4 {
        return Err(fail(a.len() - 1, "not enough arguments for 'file'"));
    }
    let name = a.word(i + 1)?;
    if a.word(i + 2)? != "scale" {
        return Err(fail(i + 2, "you have to specify a scale factor"));
    }
    let scale = a.real(i + 3)?;
    if scale <= 0.0 {
        return Err(fail(i + 3, "scale factor must be >0"));
    }
    let text = ctx
        .sys
        .read(name)
        .map_err(|m| a.file_error(i + 1, format!("Cannot open clump file {name}: {m}")))?;
    let mut list = crate::engine::multisphere::read_clump_file(&text, n)
        .map_err(|m| a.error(i + 1, format!("{name}: {m}")))?;
    for s in list.iter_mut() {
        if s[3] <= 0.0 {
            return Err(fail(i + 1, "radius must be > 0"));
        }
        for x in s.iter_mut() {
            *x *= scale;
        }
    }
    Ok((list, 4))
}

/// `x y z r` for each of the `n` spheres at word `i`: the spheres and the words taken.
fn sphere_list(
    a: &Args,
    id: &str,
    i: usize,
    n: usize,
) -> Result<(Vec<[f64; 4]>, usize), CommandError> {
    if a.len() < i + 4 * n {
        return Err(failure(a, id, a.len() - 1, "not enough arguments"));
    }
    let mut list = Vec::with_capacity(n);
    for k in 0..n {
        let at = i + 4 * k;
        let s = [
            a.real(at)?,
            a.real(at + 1)?,
            a.real(at + 2)?,
            a.real(at + 3)?,
        ];
        if s[3] <= 0.0 {
            return Err(failure(a, id, at + 3, "radius must be >0"));
        }
        list.push(s);
    }
    Ok((list, 4 * n))
}

/// The clump's type and mass-property keywords as given.
#[derive(Debug, Clone)]
struct MassArgs {
    /// `type MT`.
    shape_type: i64,
    /// `mass M`.
    mass: Option<f64>,
    /// `inertia_tensor ...` (mass length^2).
    tensor: Option<[[f64; 3]; 3]>,
    /// `use_density` (true) or `use_volume`.
    use_density: Option<bool>,
    /// `fflag`: the force directions that act.
    fflag: [bool; 3],
    /// `tflag`: the torque directions that act.
    tflag: [bool; 3],
}

impl Default for MassArgs {
    fn default() -> MassArgs {
        MassArgs {
            shape_type: 0,
            mass: None,
            tensor: None,
            use_density: None,
            fflag: [true; 3],
            tflag: [true; 3],
        }
    }
}

impl MassArgs {
    /// The keyword at word `i`: the words it took.
    fn keyword(&mut self, a: &Args, id: &str, i: usize) -> Result<usize, CommandError> {
        let fail = |i: usize, m: &str| failure(a, id, i, m);
        Ok(match a.word(i)? {
            "type" => {
                self.shape_type = a.int(i + 1)?;
                2
            }
            "mass" => {
                self.mass = Some(a.real(i + 1)?);
                2
            }
            "use_volume" => {
                self.use_density = Some(false);
                1
            }
            "use_density" => {
                self.use_density = Some(true);
                1
            }
            w @ ("fflag" | "tflag") => {
                if a.len() < i + 4 {
                    return Err(fail(
                        a.len() - 1,
                        &format!("not enough arguments for '{w}'"),
                    ));
                }
                let mut f = [true; 3];
                for (k, x) in f.iter_mut().enumerate() {
                    *x = match a.word(i + 1 + k)? {
                        "on" => true,
                        "off" => false,
                        _ => {
                            return Err(fail(
                                i + 1 + k,
                                &format!("expecting 'on or 'off' after '{w}'"),
                            ))
                        }
                    };
                }
                if w == "fflag" {
                    self.fflag = f;
                } else {
                    self.tflag = f;
                }
                4
            }
            "inertia_tensor" => {
                if a.len() < i + 7 {
                    return Err(fail(
                        a.len() - 1,
                        "not enough arguments for 'inertia_tensor'",
                    ));
                }
                let v: Vec<f64> = (1..=6).map(|k| a.real(i + k)).collect::<Result<_, _>>()?;
                self.tensor = Some([[v[0], v[1], v[2]], [v[1], v[3], v[4]], [v[2], v[4], v[5]]]);
                7
            }
            _ => {
                return Err(a.keyword_error(
                    i,
                    &[
                        "type",
                        "mass",
                        "inertia_tensor",
                        "use_volume",
                        "use_density",
                        "fflag",
                        "tflag",
                    ],
                ))
            }
        })
    }

    /// The clump's type and the mass properties given (None: computed), after LIGGGHTS's
    /// checks.
    fn given(&self, a: &Args, id: &str) -> Result<(u32, Option<GivenMass>), CommandError> {
        let fail = |i: usize, m: &str| failure(a, id, i, m);
        if self.shape_type < 1 || self.shape_type > u32::MAX as i64 {
            return Err(fail(2, "have to provide a type >=1"));
        }
        let given = match (self.mass, self.tensor) {
            (None, None) => None,
            (Some(mass), Some(inertia)) => Some(GivenMass {
                mass,
                inertia,
                use_density: self.use_density.ok_or_else(|| {
                    fail(2, "have to use either 'use_volume' or 'use_density' in case 'mass' and 'moi' are specified")
                })?,
            }),
            _ => {
                return Err(fail(
                    2,
                    "have to define either both 'mass' and 'inertia_tensor' or none of the two",
                ))
            }
        };
        Ok((self.shape_type as u32, given))
    }
}
