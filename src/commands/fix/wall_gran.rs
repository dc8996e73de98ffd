//! `fix wall/gran`: granular walls, primitive planes and cylinders or triangle meshes.

use crate::commands::fix::FixDef;
use crate::commands::sim_run::gran_models;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP wall/gran model ... primitive type T SHAPE ARGS | mesh n_meshes N meshes ...`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let FixDef { id, group, .. } = *fix;
    let (selection, next, pending) = gran_models(a, 3, "fix wall/gran")?;
    if let Some(d) = pending {
        return Err(d);
    }
    if a.word(next)? == "mesh" {
        return mesh_wall(a, ctx, group, selection, next);
    }
    if a.word(next)? != "primitive" {
        return Err(a.keyword_error(next, &["primitive", "mesh"]));
    }
    if a.word(next + 1)? != "type" {
        return Err(a
            .error(next + 1, "Illegal fix wall/gran command")
            .with_help("expected: primitive type T xplane|yplane|zplane POS"));
    }
    let wall_type = a.int(next + 2)?;
    if wall_type < 1 || wall_type > ctx.sim.ntypes as i64 {
        return Err(a.error(
            next + 2,
            "Illegal fix wall/gran command: wall type out of range",
        ));
    }
    use crate::engine::granular::Primitive;
    let shape_word = a.word(next + 3)?;
    let axis = |c: char| (c as usize) - ('x' as usize);
    let (shape, used) = match shape_word {
        "xplane" | "yplane" | "zplane" => (
            Primitive::Plane {
                axis: axis(shape_word.chars().next().unwrap()),
                position: a.real(next + 4)?,
            },
            5,
        ),
        "xcylinder" | "ycylinder" | "zcylinder" => (
            Primitive::Cylinder {
                axis: axis(shape_word.chars().next().unwrap()),
                radius: a.real(next + 4)?,
                c1: a.real(next + 5)?,
                c2: a.real(next + 6)?,
            },
            7,
        ),
        other => return Err(a.unsupported(next + 3, &format!("fix wall/gran primitive {other}"))),
    };
    // general keywords, then on/off model settings in any order
    let mut selection = selection;
    let mut shear = None;
    let mut k = next + used;
    while k < a.len() {
        match a.word(k)? {
            "shear" => {
                let dim = match a.word(k + 1)? {
                    "x" => 0,
                    "y" => 1,
                    "z" => 2,
                    _ => return Err(a.error(k + 1, "Fix wall/gran: illegal 'shear' dim")),
                };
                shear = Some((dim, a.real(k + 2)?));
                k += 3;
            }
            "store_force" | "store_force_contact" | "store_force_contact_stress" => {
                if a.word_in(k + 1, &["yes", "no"])? == "yes" {
                    return Err(a.unsupported(k, &format!("fix wall/gran {} yes", a.word(k)?)));
                }
                k += 2;
            }
            "temperature" => {
                return Err(a.unsupported(k, "fix wall/gran temperature (heat transfer with walls)"))
            }
            _ => break,
        }
    }
    let rest: Vec<&str> = (k..a.len())
        .map(|i| a.word(i))
        .collect::<std::result::Result<_, _>>()?;
    selection
        .apply_settings(&rest)
        .map_err(|m| a.error(k, format!("Fix wall/gran: {m}")))?;
    Ok(FixKind::WallGran(crate::engine::fixes::WallFix {
        selection,
        plane: shape,
        wall_type: wall_type as usize,
        shear,
        model: None,
        history_name: format!("history_{id}"),
        multicontact: None,
    }))
}

/// `fix ID GROUP wall/gran model ... mesh n_meshes N meshes M1 .. MN [model settings]`.
fn mesh_wall(
    a: &Args,
    ctx: &Ctx,
    group: &str,
    mut selection: crate::engine::granular::Selection,
    at: usize,
) -> Result<FixKind, CommandError> {
    if a.word(at + 1)? != "n_meshes" {
        return Err(a
            .error(at + 1, "Fix wall/gran: expecting keyword 'n_meshes'")
            .with_help("expected: mesh n_meshes N meshes ID1 ... IDN"));
    }
    let n = a.int(at + 2)?;
    if n < 1 {
        return Err(a.error(at + 2, "Fix wall/gran: 'n_meshes' must be > 0"));
    }
    if a.word(at + 3)? != "meshes" {
        return Err(a.error(at + 3, "Fix wall/gran: expecting keyword 'meshes'"));
    }
    let mut meshes = Vec::new();
    for k in 0..n as usize {
        let id = a.word(at + 4 + k)?;
        if crate::engine::fixes::mesh_named(&ctx.sim.fixes, id).is_none() {
            return Err(a.error(
                at + 4 + k,
                format!("Fix wall/gran: failed to find fix mesh/surface with ID {id}"),
            ));
        }
        meshes.push(id.to_string());
    }
    if ctx.sim.fixes.iter().any(|f| f.kind.mesh_wall().is_some()) {
        return Err(a.error(
            0,
            "More than one wall of type 'mesh' is not supported; list all meshes with n_meshes",
        ));
    }
    let mut k = at + 4 + n as usize;
    while k < a.len() {
        match a.word(k)? {
            w @ ("store_force" | "store_force_contact" | "store_force_contact_stress") => {
                if a.word_in(k + 1, &["yes", "no"])? == "yes" {
                    return Err(a.unsupported(k, &format!("fix wall/gran {w} yes")));
                }
                k += 2;
            }
            _ => break,
        }
    }
    let rest: Vec<&str> = (k..a.len())
        .map(|i| a.word(i))
        .collect::<std::result::Result<_, _>>()?;
    selection
        .apply_settings(&rest)
        .map_err(|m| a.error(k, format!("Fix wall/gran: {m}")))?;
    let group_index = ctx.sim.groups.iter().position(|g| g == group).unwrap_or(0) as u32;
    Ok(FixKind::MeshWall(crate::engine::fixes::MeshWallFix {
        selection,
        meshes,
        group_index,
        model: None,
        trackers: Vec::new(),
        built: None,
        multicontact: Vec::new(),
    }))
}
