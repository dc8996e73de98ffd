//! `fix massflow/mesh`: particles and mass crossing a mesh face.

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value, LENGTH, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixStyle;
use crate::engine::massflow::{Massflow, Side};
use crate::engine::mesh::TriMesh;

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
    let mut o = Options::default();
    let mut i = 3;
    while i < a.len() {
        i = keyword(a, ctx, i, &mut o, id, &fail)?;
    }
    let (mesh_id, trimesh, side) = check_options(&mut o, &fail)?;
    let mut m = Massflow::new(id, &mesh_id, &trimesh, side).map_err(|e| fail(2, &e.to_string()))?;
    m.once = o.once;
    m.screen = o.screen;
    m.write_time = o.write_time;
    m.file = o.file;
    m.delete = o.delete;
    m.property = o.property;
    m.write_header()
        .map_err(|e| a.error(0, format!("fix massflow/mesh: {e}")))?;
    Ok(Box::new(m))
}

/// What the keywords set, as LIGGGHTS reads them.
#[derive(Default)]
struct Options {
    /// `vec_side`: the direction counted as crossing (zero: not given).
    side: [f64; 3],
    /// `mesh`: the mesh fix's ID and its mesh.
    mesh: Option<(String, TriMesh)>,
    /// `count once`.
    once: bool,
    /// `writeTime`.
    write_time: bool,
    /// `point_at_outlet` (length).
    outlet: Option<[f64; 3]>,
    /// `inside_out`.
    inside_out: bool,
    /// `file` or `append` (None also in a dry run).
    file: Option<std::io::BufWriter<std::fs::File>>,
    /// `screen yes`.
    screen: bool,
    /// `delete_atoms yes`.
    delete: bool,
    /// `sum_property`: the fix ID of the summed property.
    property: Option<String>,
}

/// Read the keyword at word `i` into `o`: the word after it and its values.
fn keyword(
    a: &Args,
    ctx: &Ctx,
    i: usize,
    o: &mut Options,
    id: &str,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<usize, CommandError> {
    let need = |n: usize, m: &str| {
        if a.len() < i + n {
            Err(fail(i, m))
        } else {
            Ok(())
        }
    };
    match a.word(i)? {
        "vec_side" => {
            need(4, "not enough arguments for 'vec_side'")?;
            o.side = [a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?];
            if o.side.iter().all(|&c| c == 0.0) {
                return Err(fail(i, "vec_side > 0 required"));
            }
            Ok(i + 4)
        }
        "mesh" => {
            need(2, "not enough arguments for 'insert_stream'")?;
            let m = a.word(i + 1)?;
            let found =
                crate::engine::fixes::mesh_named(&ctx.sim.fixes, m).map(|mf| mf.mesh.clone());
            o.mesh = Some((
                m.to_string(),
                found.ok_or_else(|| fail(i + 1, "fix mesh ID does not exist"))?,
            ));
            Ok(i + 2)
        }
        "count" => {
            need(2, "not enough arguments for 'insert_stream'")?;
            o.once = match a.word(i + 1)? {
                "once" => true,
                "multiple" => false,
                _ => return Err(fail(i + 1, "expecting 'once' or 'multiple' after 'count'")),
            };
            Ok(i + 2)
        }
        "writeTime" => {
            o.write_time = true;
            Ok(i + 1)
        }
        "point_at_outlet" => {
            need(4, "not enough arguments for 'point_at_outlet'")?;
            o.outlet = Some([a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?]);
            Ok(i + 4)
        }
        "inside_out" => {
            o.inside_out = true;
            if o.outlet.is_none() {
                return Err(fail(i, "the setting 'inside_out' has no meaning in case you do not use 'point_at_outlet'"));
            }
            Ok(i + 1)
        }
        kw @ ("file" | "append") => {
            need(2, "Illegal keyword entry")?;
            if let Some(f) = open_output(a, ctx, i, kw == "append", id)? {
                o.file = Some(f);
            }
            Ok(i + 2)
        }
        "screen" => {
            need(2, "Illegal keyword entry")?;
            o.screen = yes_no(a, i + 1, "Illegal fix print command")?;
            Ok(i + 2)
        }
        "delete_atoms" => {
            need(2, "Illegal keyword entry")?;
            o.delete = yes_no(a, i + 1, "Illegal delete command")?;
            Ok(i + 2)
        }
        "sum_property" => {
            need(2, "not enough arguments for 'sum_property'")?;
            o.property = Some(summed_property(a, ctx, i + 1)?);
            Ok(i + 2)
        }
        _ => Err(fail(i, "unknown keyword")),
    }
}

/// Word `i` as `yes` (true) or `no` (false); any other word is refused with `refusal`.
fn yes_no(a: &Args, i: usize, refusal: &str) -> Result<bool, CommandError> {
    match a.word(i)? {
        "yes" => Ok(true),
        "no" => Ok(false),
        _ => Err(a.error(i, refusal)),
    }
}

/// LIGGGHTS's checks of the keywords together: the mesh (its fix ID and mesh) and the
/// side counted as crossing.
fn check_options(
    o: &mut Options,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<(String, TriMesh, Side), CommandError> {
    if o.delete && !o.once {
        return Err(fail(2, "using 'delete_atoms yes' requires 'count once'"));
    }
    if o.outlet.is_some() && !o.once {
        return Err(fail(2, "setting 'point_at_outlet' requires 'count once'"));
    }
    if o.side.iter().all(|&c| c == 0.0) && o.outlet.is_none() {
        return Err(fail(2, "expecting keyword 'vec_side'"));
    }
    let Some((mesh_id, trimesh)) = o.mesh.take() else {
        return Err(fail(2, "expecting keyword 'mesh'"));
    };
    let side = match o.outlet {
        Some(point) => Side::Outlet {
            point,
            inside_out: o.inside_out,
        },
        None => Side::Vector(o.side),
    };
    Ok((mesh_id, trimesh, side))
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
