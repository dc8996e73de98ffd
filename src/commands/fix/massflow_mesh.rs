//! `fix massflow/mesh`: particles and mass crossing a mesh face.

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value, LENGTH, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixStyle;
use crate::engine::massflow::{Massflow, Side};

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "massflow/mesh",
    "fix ID GROUP massflow/mesh mesh MESH vec_side VX VY VZ",
    &[
        kw(
            "count",
            &[arg("once|multiple", Value::OneOf(&["once", "multiple"]))],
            "count a particle once or at every crossing",
        ),
        kw(
            "point_at_outlet",
            &[arg("X", LENGTH), arg("Y", LENGTH), arg("Z", LENGTH)],
            "the outer side is away from this point (curved faces)",
        ),
        kw("inside_out", &[], "with point_at_outlet: count toward the point"),
        kw("file", &[arg("F", Value::File)], "write each counted particle to this file"),
        kw("append", &[arg("F", Value::File)], "append each counted particle to this file"),
        kw("writeTime", &[], "file lines start with the time"),
        kw("screen", &[arg("yes|no", YES_NO)], "print each counted particle"),
        kw(
            "delete_atoms",
            &[arg("yes|no", YES_NO)],
            "delete counted particles at the next re-neighbouring (needs count once)",
        ),
        kw(
            "sum_property",
            &[arg("NAME", Value::Word)],
            "sum a fix property/atom scalar over the counted particles (f_ID[7])",
        ),
    ],
    "count particles and mass crossing a mesh face (f_ID[1..6]: mass, count, their rates, deleted mass and count)",
);

/// `fix ID GROUP massflow/mesh mesh MESH vec_side VX VY VZ [count once|multiple]
/// [point_at_outlet X Y Z [inside_out]] [file|append F] [writeTime] [screen yes|no]
/// [delete_atoms yes|no] [sum_property NAME]`,
/// keywords read in LIGGGHTS's order and checks.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let id = fix.id;
    let fail = |i: usize, m: &str| a.error(i, format!("Fix massflow/mesh (id {id}): {m}"));
    let mut side = [0.0; 3];
    let mut mesh = None;
    let mut once = false;
    let mut write_time = false;
    let mut outlet: Option<[f64; 3]> = None;
    let mut inside_out = false;
    let mut file = None;
    let mut screen = false;
    let mut delete = false;
    let mut property = None;
    let mut i = 3;
    while i < a.len() {
        match a.word(i)? {
            "vec_side" => {
                if a.len() < i + 4 {
                    return Err(fail(i, "not enough arguments for 'vec_side'"));
                }
                side = [a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?];
                if side.iter().all(|&c| c == 0.0) {
                    return Err(fail(i, "vec_side > 0 required"));
                }
                i += 4;
            }
            "mesh" => {
                if a.len() < i + 2 {
                    return Err(fail(i, "not enough arguments for 'insert_stream'"));
                }
                let m = a.word(i + 1)?;
                let found =
                    crate::engine::fixes::mesh_named(&ctx.sim.fixes, m).map(|mf| mf.mesh.clone());
                mesh = Some((
                    m.to_string(),
                    found.ok_or_else(|| fail(i + 1, "fix mesh ID does not exist"))?,
                ));
                i += 2;
            }
            "count" => {
                if a.len() < i + 2 {
                    return Err(fail(i, "not enough arguments for 'insert_stream'"));
                }
                once = match a.word(i + 1)? {
                    "once" => true,
                    "multiple" => false,
                    _ => return Err(fail(i + 1, "expecting 'once' or 'multiple' after 'count'")),
                };
                i += 2;
            }
            "writeTime" => {
                write_time = true;
                i += 1;
            }
            "point_at_outlet" => {
                if a.len() < i + 4 {
                    return Err(fail(i, "not enough arguments for 'point_at_outlet'"));
                }
                outlet = Some([a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?]);
                i += 4;
            }
            "inside_out" => {
                inside_out = true;
                if outlet.is_none() {
                    return Err(fail(i, "the setting 'inside_out' has no meaning in case you do not use 'point_at_outlet'"));
                }
                i += 1;
            }
            kw @ ("file" | "append") => {
                if a.len() < i + 2 {
                    return Err(fail(i, "Illegal keyword entry"));
                }
                if let Some(f) = open_output(a, ctx, i, kw == "append", id)? {
                    file = Some(f);
                }
                i += 2;
            }
            "screen" => {
                if a.len() < i + 2 {
                    return Err(fail(i, "Illegal keyword entry"));
                }
                screen = match a.word(i + 1)? {
                    "yes" => true,
                    "no" => false,
                    _ => return Err(a.error(i + 1, "Illegal fix print command")),
                };
                i += 2;
            }
            "delete_atoms" => {
                if a.len() < i + 2 {
                    return Err(fail(i, "Illegal keyword entry"));
                }
                delete = match a.word(i + 1)? {
                    "yes" => true,
                    "no" => false,
                    _ => return Err(a.error(i + 1, "Illegal delete command")),
                };
                i += 2;
            }
            "sum_property" => {
                if a.len() < i + 2 {
                    return Err(fail(i, "not enough arguments for 'sum_property'"));
                }
                property = Some(summed_property(a, ctx, i + 1)?);
                i += 2;
            }
            _ => return Err(fail(i, "unknown keyword")),
        }
    }
    if delete && !once {
        return Err(fail(2, "using 'delete_atoms yes' requires 'count once'"));
    }
    if outlet.is_some() && !once {
        return Err(fail(2, "setting 'point_at_outlet' requires 'count once'"));
    }
    if side.iter().all(|&c| c == 0.0) && outlet.is_none() {
        return Err(fail(2, "expecting keyword 'vec_side'"));
    }
    let Some((mesh_id, trimesh)) = mesh else {
        return Err(fail(2, "expecting keyword 'mesh'"));
    };
    let side = match outlet {
        Some(point) => Side::Outlet { point, inside_out },
        None => Side::Vector(side),
    };
    let mut m = Massflow::new(id, &mesh_id, &trimesh, side).map_err(|e| fail(2, &e.to_string()))?;
    m.once = once;
    m.screen = screen;
    m.write_time = write_time;
    m.file = file;
    m.delete = delete;
    m.property = property;
    m.write_header()
        .map_err(|e| a.error(0, format!("fix massflow/mesh: {e}")))?;
    Ok(Box::new(m))
}

/// The output file of `file F` (`append` false) or `append F` at word `i` (the file name
/// is word `i + 1`); None in a dry run, which opens no file.
fn open_output(
    a: &Args,
    ctx: &Ctx,
    i: usize,
    append: bool,
    id: &str,
) -> Result<Option<std::io::BufWriter<std::fs::File>>, CommandError> {
    let name = a.word(i + 1)?;
    if ctx.sys.mode != crate::lang::system::Mode::Run {
        return Ok(None);
    }
    let f = std::fs::OpenOptions::new()
        .create(true)
        .write(true)
        .append(append)
        .truncate(!append)
        .open(name)
        .map_err(|_| {
            a.file_error(
                i + 1,
                format!("Fix massflow/mesh (id {id}): Cannot open file {name}"),
            )
        })?;
    Ok(Some(std::io::BufWriter::new(f)))
}

/// The fix ID of the per-atom scalar of `fix property/atom` named by word `i` (its variable
/// name), whose sum crossing the mesh is counted.
fn summed_property(a: &Args, ctx: &Ctx, i: usize) -> Result<String, CommandError> {
    let name = a.word(i)?;
    let found = crate::engine::fixes::properties_named(&ctx.sim.fixes, name)
        .find(|(_, pa)| !pa.vector)
        .map(|(f, _)| f.id.clone());
    found.ok_or_else(|| {
        a.error(
            i,
            format!("Could not locate a fix/property storing value(s) for {name} as requested by massflow/mesh."),
        )
    })
}
