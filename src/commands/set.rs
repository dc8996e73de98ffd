//! `set atom|type|group|region ID keyword value ...` as LIGGGHTS 3.8.0 parses it: each
//! keyword in turn, a value or an atom-style variable `v_name` (evaluated for every atom when
//! the keyword is reached), LIGGGHTS's checks, and `N settings made for KEYWORD` after each.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::lang::system::Mode;

type Result = std::result::Result<(), CommandError>;

/// Keywords regolith sets, each with one value (a number or `v_name`).
const VALUED: &[&str] = &[
    "type", "x", "y", "z", "vx", "vy", "vz", "omegax", "omegay", "omegaz", "mass", "diameter",
    "density",
];

/// Keywords LIGGGHTS 3.8.0 knows that regolith does not set (other atom styles, molecules,
/// SPH and superquadric particles).
const ELSEWHERE: &[&str] = &[
    "mol",
    "inertiax",
    "inertiay",
    "inertiaz",
    "charge",
    "shape",
    "blockiness",
    "roundness",
    "aspect_ratio",
    "length",
    "dipole",
    "dipole/random",
    "quat",
    "quat_direct",
    "quat/random",
    "theta",
    "angmom",
    "volume",
    "image",
    "bond",
    "angle",
    "dihedral",
    "improper",
    "meso_e",
    "meso_cv",
    "meso_rho",
    "smd/mass/density",
    "smd/contact/radius",
    "sphkernel",
];

/// A keyword's value: a constant or an atom-style variable's per-atom values.
enum Value {
    Constant(f64),
    PerAtom(std::rc::Rc<Vec<f64>>),
    /// A variable a dry run cannot evaluate.
    Unknown,
}

/// The value word `i`: a number (an integer for `type`) or `v_name` of an atom-style variable.
fn value(
    a: &Args,
    ctx: &mut Ctx,
    i: usize,
    integer: bool,
) -> std::result::Result<Value, CommandError> {
    let word = a.word(i)?;
    let Some(name) = word.strip_prefix("v_") else {
        return Ok(Value::Constant(if integer {
            a.int(i)? as f64
        } else {
            a.real(i)?
        }));
    };
    match ctx.vars.get(name).map(|v| v.style) {
        None => return Err(a.error(i, "Variable name for set command does not exist")),
        Some(crate::lang::variables::Style::Atom) => {}
        Some(_) => {
            return Err(a
                .error(i, "Variable for set command is invalid style")
                .with_help("set takes atom-style variables"))
        }
    }
    let mut scope = crate::lang::scope::Scope::new(ctx.vars, ctx.sys, ctx.sim);
    match scope.atom_variable(name) {
        Ok(v) => Ok(Value::PerAtom(v)),
        Err(e) if e.is_known_when_run() || ctx.sys.mode == Mode::Check => Ok(Value::Unknown),
        Err(e) => Err(a.error(i, e.to_string())),
    }
}

/// `set`.
pub fn set(a: &Args, ctx: &mut Ctx) -> Result {
    ctx.reshape_regions(false)
        .map_err(|e| a.engine_error(0, e))?;
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Set command before simulation box is defined"));
    }
    a.count(
        4..=usize::MAX,
        "set atom|type|group|region ID keyword value ...",
    )?;
    let atoms = super::sim_setup::selection(a, ctx)?;
    ctx.say("Setting atom values ...\n");
    let mut i = 2;
    // LIGGGHTS's `add yes` with `until STEP` stops property/atom settings from that step on
    let (mut add, mut until) = (false, 1.0);
    while i < a.len() {
        let key = a.word(i)?;
        let count = match key {
            "type/fraction" => {
                let n = type_fraction(a, ctx, i, &atoms)?;
                i += 4;
                n
            }
            // LIGGGHTS's add/until only gate `property/atom` settings
            "add" => {
                add = a
                    .word_in(i + 1, &["yes", "no"])
                    .map_err(|_| a.error(i + 1, "Illegal 'add' option called"))?
                    == "yes";
                i += 2;
                0
            }
            "until" => {
                until = crate::util::numbers::c_atof(a.word(i + 1)?);
                if until <= 0.0 {
                    return Err(a.error(
                        i + 1,
                        "Illegal 'until' option called. Please set keyword value >0",
                    ));
                }
                i += 2;
                0
            }
            k if VALUED.contains(&k) => {
                let v = value(a, ctx, i + 1, k == "type")?;
                if let Value::Constant(c) = v {
                    if k == "diameter" && c < 0.0 {
                        return Err(a.error(i + 1, "Invalid diameter in set command"));
                    }
                    if k == "density" && c <= 0.0 {
                        return Err(a.error(i + 1, "Invalid density in set command"));
                    }
                }
                apply(a, ctx, i, k, &v, &atoms)?;
                i += 2;
                atoms.len()
            }
            k if k.starts_with("property/atom") => {
                let skip = add && ctx.sim.step as f64 >= until;
                let n = property_atom(a, ctx, i, &atoms, skip)?;
                i = a.len();
                n
            }
            k if ELSEWHERE.contains(&k) || k.starts_with("i_") || k.starts_with("d_") => {
                return Err(a.unsupported(i, &format!("set {k}")));
            }
            _ => {
                let mut known: Vec<&str> = VALUED.to_vec();
                known.extend(["type/fraction", "add", "until", "property/atom"]);
                known.extend(ELSEWHERE);
                return Err(a.keyword_error(i, &known));
            }
        };
        ctx.say(&format!("  {count} settings made for {key}\n"));
    }
    Ok(())
}

/// `property/atom NAME VALUE...` (the rest of the command): the values of a property/atom
/// fix's property for the selected atoms (constants, or `v_name` atom-style variables for a
/// scalar or three-column property); `skip` (`add yes` past `until`) sets nothing.
fn property_atom(
    a: &Args,
    ctx: &mut Ctx,
    i: usize,
    atoms: &[usize],
    skip: bool,
) -> std::result::Result<usize, CommandError> {
    use crate::engine::fixes::properties_named;
    if i + 1 >= a.len() {
        return Err(a.error(i, "Illegal set command for property/atom"));
    }
    let name = a.word(i + 1)?;
    let last = properties_named(&ctx.sim.fixes, name).next_back();
    let Some((id, width, fresh)) = last.map(|(f, pa)| (f.id.clone(), pa.defaults.len(), pa.fresh))
    else {
        return Err(a.error(
            i + 1,
            "Could not identify the per-atom property you want to set",
        ));
    };
    if width != a.len() - i - 2 {
        return Err(a.error(
            i + 1,
            "The number of values for the set property/atom does not match the number needed",
        ));
    }
    let values: Vec<Value> = if a.word(i + 2)?.starts_with("v_") {
        if width != 1 && width != 3 {
            return Err(a.error(i + 2, "Set command for property/atom and variables does only work with scalar and 3-vector quantities"));
        }
        let mut v = Vec::with_capacity(width);
        for c in 0..width {
            v.push(value(a, ctx, i + 2 + c, false)?);
        }
        v
    } else {
        (0..width)
            .map(|c| {
                a.word(i + 2 + c)
                    .map(|w| Value::Constant(crate::util::numbers::c_atof(w)))
            })
            .collect::<std::result::Result<_, _>>()?
    };
    if values.iter().any(|v| matches!(v, Value::Unknown)) {
        return Ok(atoms.len());
    }
    if fresh && !atoms.is_empty() {
        return Err(a.error(i, "May not use the set command right after fix property/atom without a prior run. Add a 'run 0' between fix property/atom and set"));
    }
    if skip {
        return Ok(0);
    }
    let p = &mut ctx.sim.particles;
    let k = p.extra_index(&id, width);
    let data = &mut p.extra[k].data;
    for &atom in atoms {
        for (c, v) in values.iter().enumerate() {
            data[atom * width + c] = match v {
                Value::Constant(x) => *x,
                Value::PerAtom(per) => per[atom],
                Value::Unknown => continue,
            };
        }
    }
    Ok(atoms.len())
}

/// `type/fraction T FRACTION SEED`: each selected atom draws from a generator reseeded by
/// its position.
fn type_fraction(
    a: &Args,
    ctx: &mut Ctx,
    i: usize,
    atoms: &[usize],
) -> std::result::Result<usize, CommandError> {
    let t = a.int(i + 1)?;
    let fraction = a.real(i + 2)?;
    let seed = a.int(i + 3)?;
    if t <= 0 || t > ctx.sim.ntypes as i64 || !(0.0..=1.0).contains(&fraction) {
        return Err(a.error(i + 1, "Invalid value in set command"));
    }
    if seed <= 0 || seed > i32::MAX as i64 {
        return Err(a.error(i + 3, "Invalid random number seed in set command"));
    }
    let mut rng = crate::util::random::RanPark::new(12345787).map_err(|m| a.error(i + 3, &m))?;
    let p = &mut ctx.sim.particles;
    let mut count = 0;
    for &k in atoms {
        rng.reset_at(seed as i32, p.x[k]);
        if rng.uniform() > fraction {
            continue;
        }
        p.kind[k] = t as u32;
        count += 1;
    }
    Ok(count)
}

/// Set `key` of every selected atom (LIGGGHTS's per-atom checks, made for variables' values).
fn apply(a: &Args, ctx: &mut Ctx, i: usize, key: &str, v: &Value, atoms: &[usize]) -> Result {
    let ntypes = ctx.sim.ntypes as i64;
    let planar = ctx.sim.dimension == 2;
    let p = &mut ctx.sim.particles;
    for &k in atoms {
        let value = match v {
            Value::Constant(c) => *c,
            Value::PerAtom(values) => values[k],
            Value::Unknown => return Ok(()),
        };
        match key {
            "diameter" => {
                if value < 0.0 {
                    return Err(a.error(i + 1, "Invalid diameter in set command"));
                }
                crate::engine::checks::check_sphere(value, p.density[k], "diameter")
                    .map_err(|m| a.error(i + 1, format!("Invalid diameter in set command: {m}")))?;
                p.radius[k] = 0.5 * value * 1.0;
                if p.density[k] > 0.0 {
                    let r = p.radius[k];
                    p.mass[k] = crate::engine::planar::sphere_or_disc_mass(planar, r, p.density[k]);
                }
            }
            "density" => {
                if value <= 0.0 {
                    return Err(a.error(i + 1, "Invalid density in set command"));
                }
                crate::engine::checks::check_sphere(2.0 * p.radius[k], value, "density")
                    .map_err(|m| a.error(i + 1, format!("Invalid density in set command: {m}")))?;
                p.density[k] = value;
                if p.radius[k] > 0.0 {
                    let r = p.radius[k];
                    p.mass[k] = crate::engine::planar::sphere_or_disc_mass(planar, r, p.density[k]);
                }
            }
            "mass" => {
                if value <= 0.0 {
                    return Err(a.error(i + 1, "Invalid mass in set command"));
                }
                p.mass[k] = value;
            }
            "type" => {
                // a variable's value is truncated as LIGGGHTS's static_cast<int>
                let t = value as i64;
                if t < 1 || t > ntypes {
                    return Err(a.error(i + 1, "Invalid value in set command"));
                }
                p.kind[k] = t as u32;
            }
            "x" => p.x[k][0] = value,
            "y" => p.x[k][1] = value,
            "z" => p.x[k][2] = value,
            "vx" => p.v[k][0] = value,
            "vy" => p.v[k][1] = value,
            "vz" => p.v[k][2] = value,
            "omegax" => p.omega[k][0] = value,
            "omegay" => p.omega[k][1] = value,
            "omegaz" => p.omega[k][2] = value,
            _ => unreachable!("VALUED keywords only"),
        }
    }
    Ok(())
}
