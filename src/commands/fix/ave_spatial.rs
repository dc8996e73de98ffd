//! `fix ave/spatial`: per-bin averages of per-atom quantities, written to a file.

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::ave_spatial::{AveSpatial, Origin, SpatialSettings, SpatialValue};
use crate::engine::fixes::{AveMode, FixStyle};
use crate::lang::system::Mode;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "ave/spatial",
    "fix ID GROUP ave/spatial NEVERY NREPEAT NFREQ x|y|z lower|center|upper|COORD DELTA ... vx|vy|vz|fx|fy|fz|density/number|density/mass|c_ID|c_ID[N]|f_ID|f_ID[N]|v_NAME ...",
    &[
        kw(
            "norm",
            &[arg("all|sample", Value::OneOf(&["all", "sample"]))],
            "normalise by all samples' atoms or each sample's",
        ),
        kw(
            "units",
            &[arg("box|lattice|reduced", Value::OneOf(&["box", "lattice", "reduced"]))],
            "units of origins and widths",
        ),
        kw("region", &[arg("ID", Value::Word)], "only atoms in this region"),
        kw("file", &[arg("FILE", Value::Word)], "write the averages to this file"),
        kw("write_ts", &[arg("yes|no", YES_NO)], "a step line before each output"),
        kw("ave", &[arg("one|running|window M", Value::Word)], "combine outputs"),
        kw("overwrite", &[], "keep only the last output (ave running)"),
        kw("title1", &[arg("TEXT", Value::Word)], "first comment line"),
        kw("title2", &[arg("TEXT", Value::Word)], "second comment line"),
        kw("title3", &[arg("TEXT", Value::Word)], "third comment line"),
    ],
    "per-bin averages of per-atom values in 1d, 2d or 3d bins, every NFREQ steps, written to a file",
);

const ILLEGAL: &str = "Illegal fix ave/spatial command";

/// `fix ID GROUP ave/spatial Nevery Nrepeat Nfreq dim origin delta ... value ... keyword
/// value ...` with up to three `x|y|z lower|center|upper|COORD DELTA` triples, values vx vy
/// vz fx fy fz density/number density/mass c_ID c_ID[N] f_ID f_ID[N] v_name, and keywords
/// norm, units, region, file, write_ts, ave, overwrite, title1/2/3.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() < 6 {
        return Err(a.error(2, ILLEGAL));
    }
    let schedule = (a.int(3)?, a.int(4)?, a.int(5)?);
    let mut i = 6;
    let mut dims: Vec<(usize, Origin, f64)> = Vec::new();
    while i + 3 <= a.len() && dims.len() < 3 {
        let axis = match a.word(i)? {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => break,
        };
        if axis == 2 && ctx.sim.dimension == 2 {
            return Err(a.error(i, "Cannot use fix ave/spatial z for 2 dimensional model"));
        }
        let origin = match a.word(i + 1)? {
            "lower" => Origin::Lower,
            "center" => Origin::Center,
            "upper" => Origin::Upper,
            _ => Origin::Coord(a.real(i + 1)?),
        };
        dims.push((axis, origin, a.real(i + 2)?));
        i += 3;
    }
    if dims.is_empty() {
        return Err(a.error(6, ILLEGAL));
    }
    for (k, d) in dims.iter().enumerate() {
        if dims[..k].iter().any(|e| e.0 == d.0) {
            return Err(a.error(6 + 3 * k, "Same dimension twice in fix ave/spatial"));
        }
    }
    let first_value = i;
    let mut values = Vec::new();
    while i < a.len() {
        let w = a.word(i)?;
        let v = match w {
            "vx" | "vy" | "vz" => SpatialValue::V((w.as_bytes()[1] - b'x') as usize),
            "fx" | "fy" | "fz" => SpatialValue::F((w.as_bytes()[1] - b'x') as usize),
            "density/number" => SpatialValue::DensityNumber,
            "density/mass" => SpatialValue::DensityMass,
            _ if w.starts_with("c_") || w.starts_with("f_") || w.starts_with("v_") => {
                reference(a, ctx, i)?
            }
            _ => break,
        };
        values.push(v);
        i += 1;
    }
    let names: Vec<&str> = (first_value..i)
        .map(|k| a.word(k))
        .collect::<Result<_, _>>()?;
    let (set, file, titles) = keywords(a, ctx, i, schedule, dims, values)?;
    let mut fix_state = AveSpatial::new(set, ctx.sim.step);
    if let (Some(name), Mode::Run) = (file, ctx.sys.mode) {
        fix_state.file = Some(open_file(a, &name, fix, &names, &titles, &fix_state.set)?);
    }
    Ok(Box::new(fix_state))
}

/// The file with LIGGGHTS's three comment lines (or the titles given; a title of one
/// character prints nothing), and where they end.
fn open_file(
    a: &Args,
    name: &str,
    fix: &FixDef,
    names: &[&str],
    titles: &[Option<String>; 3],
    set: &SpatialSettings,
) -> Result<(std::fs::File, u64), CommandError> {
    use std::io::Write;
    let mut f = std::fs::File::create(name)
        .map_err(|_| a.file_error(0, format!("Cannot open fix ave/spatial file {name}")))?;
    let coords = ["Coord", "Coord1 Coord2", "Coord1 Coord2 Coord3"][set.dims.len() - 1];
    let defaults = [
        format!(
            "# Spatial-averaged data for fix {} and group {}",
            fix.id, fix.group
        ),
        "# Timestep Number-of-bins".to_string(),
        format!("# Bin {coords} Ncount {}", names.join(" "))
            .trim_end()
            .to_string(),
    ];
    let mut head = String::new();
    for (title, default) in titles.iter().zip(&defaults) {
        match title {
            Some(t) if t.len() > 1 => head.push_str(&format!("{t}\n")),
            Some(_) => {}
            None => head.push_str(&format!("{default}\n")),
        }
    }
    f.write_all(head.as_bytes())
        .map_err(|e| a.error(0, format!("fix ave/spatial: {e}")))?;
    Ok((f, head.len() as u64))
}

type Parsed = (SpatialSettings, Option<String>, [Option<String>; 3]);

/// The optional keywords from word `i`, then LIGGGHTS's checks of the schedule and widths;
/// the widths scaled by the lattice for `units lattice`.
fn keywords(
    a: &Args,
    ctx: &Ctx,
    mut i: usize,
    schedule: (i64, i64, i64),
    mut dims: Vec<(usize, Origin, f64)>,
    values: Vec<SpatialValue>,
) -> Result<Parsed, CommandError> {
    let mut k = Keywords {
        set: SpatialSettings {
            schedule,
            dims: Vec::new(),
            values,
            norm_sample: false,
            reduced: false,
            region: None,
            mode: AveMode::One,
            overwrite: false,
            write_ts: true,
        },
        lattice: false,
        file: None,
        titles: [None, None, None],
    };
    while i < a.len() {
        i = keyword(a, ctx, i, &mut k)?;
    }
    check_schedule(a, &k.set, &dims)?;
    if k.lattice {
        in_lattice_units(ctx, &mut dims);
    }
    k.set.dims = dims;
    Ok((k.set, k.file, k.titles))
}

/// What the optional keywords set.
struct Keywords {
    /// The averaging settings (all but the bins).
    set: SpatialSettings,
    /// `units lattice`.
    lattice: bool,
    /// `file F`.
    file: Option<String>,
    /// `title1`, `title2`, `title3`.
    titles: [Option<String>; 3],
}

/// Read the keyword at word `i` into `k`: the word after it and its values.
fn keyword(a: &Args, ctx: &Ctx, i: usize, k: &mut Keywords) -> Result<usize, CommandError> {
    let need = |n: usize| {
        if n > a.len() {
            Err(a.error(a.len() - 1, ILLEGAL))
        } else {
            Ok(())
        }
    };
    let w = a.word(i)?;
    match w {
        "norm" | "units" | "region" | "file" | "write_ts" | "ave" | "title1" | "title2"
        | "title3" => need(i + 2)?,
        _ => {}
    }
    let set = &mut k.set;
    match w {
        "norm" => match a.word(i + 1)? {
            "all" => set.norm_sample = false,
            "sample" => set.norm_sample = true,
            _ => return Err(a.error(i + 1, ILLEGAL)),
        },
        "units" => match a.word(i + 1)? {
            "box" => (k.lattice, set.reduced) = (false, false),
            "lattice" => (k.lattice, set.reduced) = (true, false),
            "reduced" => (k.lattice, set.reduced) = (false, true),
            _ => return Err(a.error(i + 1, ILLEGAL)),
        },
        "region" => {
            let id = a.word(i + 1)?;
            let r =
                ctx.sim.regions.find(id).ok_or_else(|| {
                    a.error(i + 1, "Region ID for fix ave/spatial does not exist")
                })?;
            set.region = Some(r);
        }
        "file" => k.file = Some(a.word(i + 1)?.to_string()),
        "write_ts" => match a.word(i + 1)? {
            "yes" => set.write_ts = true,
            "no" => set.write_ts = false,
            _ => return Err(a.error(i + 1, ILLEGAL)),
        },
        "ave" => match a.word(i + 1)? {
            "one" => set.mode = AveMode::One,
            "running" => set.mode = AveMode::Running,
            "window" => {
                need(i + 3)?;
                let n = a.int(i + 2)?;
                if n <= 0 {
                    return Err(a.error(i + 2, ILLEGAL));
                }
                set.mode = AveMode::Window(n as usize);
                return Ok(i + 3);
            }
            _ => return Err(a.error(i + 1, ILLEGAL)),
        },
        "overwrite" => {
            set.overwrite = true;
            return Ok(i + 1);
        }
        "title1" | "title2" | "title3" => {
            k.titles[(w.as_bytes()[5] - b'1') as usize] = Some(a.word(i + 1)?.to_string());
        }
        "std" => return Err(a.unsupported(i, "fix ave/spatial std")),
        _ => return Err(a.error(i, ILLEGAL)),
    }
    Ok(i + 2)
}

/// LIGGGHTS's checks of the schedule (`Nevery Nrepeat Nfreq`), the bin widths and
/// `overwrite`.
fn check_schedule(
    a: &Args,
    set: &SpatialSettings,
    dims: &[(usize, Origin, f64)],
) -> Result<(), CommandError> {
    let (every, repeat, freq) = set.schedule;
    if every <= 0 || repeat <= 0 || freq <= 0 || freq % every != 0 || (repeat - 1) * every >= freq {
        return Err(a.error(3, ILLEGAL));
    }
    if dims.iter().any(|d| d.2 <= 0.0) {
        return Err(a.error(6, ILLEGAL));
    }
    if set.overwrite && set.mode != AveMode::Running {
        return Err(a.error(0, ILLEGAL));
    }
    Ok(())
}

/// `units lattice`: the bins' origins and widths scaled by the lattice spacings.
fn in_lattice_units(ctx: &Ctx, dims: &mut [(usize, Origin, f64)]) {
    let spacing = crate::engine::thermo::lattice_spacings(ctx.sim);
    for d in dims.iter_mut() {
        d.2 *= spacing[d.0];
        if let Origin::Coord(c) = &mut d.1 {
            *c *= spacing[d.0];
        }
    }
}

/// A `c_`, `f_` or `v_` value at word `i`, checked as LIGGGHTS checks it.
fn reference(a: &Args, ctx: &Ctx, i: usize) -> Result<SpatialValue, CommandError> {
    let w = a.word(i)?;
    let (id, index) =
        crate::util::numbers::split_reference_atoi(&w[2..]).ok_or_else(|| a.error(i, ILLEGAL))?;
    match &w[..2] {
        "c_" => {
            let c = super::input_compute(a, ctx, i, id, "ave/spatial")?;
            let cols = c.per_atom_columns();
            let problem = match index {
                _ if cols == 0 => Some("does not calculate per-atom values"),
                None if cols > 1 => Some("does not calculate a per-atom vector"),
                Some(_) if cols == 1 => Some("does not calculate a per-atom array"),
                Some(k) if k > cols => Some("vector is accessed out-of-range"),
                _ => None,
            };
            if let Some(p) = problem {
                return Err(a.error(i, format!("Fix ave/spatial compute {p}")));
            }
            Ok(SpatialValue::Compute(id.to_string(), index))
        }
        "f_" => {
            if !ctx.sim.fixes.iter().any(|f| f.id == id) {
                return Err(a.error(i, "Fix ID for fix ave/spatial does not exist"));
            }
            crate::engine::fix_columns::column(ctx.sim, id, index)
                .map_err(|e| a.error(i, format!("Fix ave/spatial: {e}")))?;
            Ok(SpatialValue::Fix(id.to_string(), index))
        }
        _ => {
            super::input_atom_variable(a, ctx, i, id, "ave/spatial")?;
            Ok(SpatialValue::Variable(id.into()))
        }
    }
}
