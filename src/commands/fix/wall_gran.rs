//! `fix wall/gran`: granular walls, primitive planes and cylinders or triangle meshes.
//!
//! The arguments are read as LIGGGHTS 3.8.0 reads them (fix_wall_gran.cpp): the contact
//! model keywords, then its own keywords in any order until a word that is none of them,
//! then the model's on/off settings; its errors name the fix (`Fix wall/gran (id ID): ...`).

use crate::commands::fix::FixDef;
use crate::commands::sim_run::gran_models;
use crate::commands::specs::{arg, kw, style, Spec, Value, VELOCITY, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::contact::ModelError;
use crate::engine::fixes::{Fix, FixStep, FixStyle, ForcePass, MeshWallFix, WallFix};
use crate::engine::granular::Primitive;
use crate::util::numbers::c_atoi;

/// The declared signature.
pub const SPEC: Spec = style("fix", "wall/gran", "fix ID GROUP wall/gran model M tangential T ... primitive type T xplane|yplane|zplane|xcylinder|ycylinder|zcylinder ARGS | mesh n_meshes N meshes MESH ...", &[kw("model", &[arg("M", Value::Word)], "normal contact model"), kw("tangential", &[arg("T", Value::Word)], "tangential contact model"), kw("cohesion", &[arg("C", Value::Word)], "cohesion model"), kw("rolling_friction", &[arg("R", Value::Word)], "rolling-friction model"), kw("primitive", &[arg("type T SHAPE ARGS", Value::Word)], "a plane or cylinder wall (positions in length)"), kw("mesh", &[arg("n_meshes N meshes MESH ...", Value::Id("fix"))], "walls made of meshes"), kw("shear", &[arg("x|y|z V", VELOCITY)], "the wall slides at velocity V"), kw("store_force", &[arg("yes|no", YES_NO)], "keep per-particle wall forces")], "granular walls: planes, cylinders or meshes");

/// `fix ID GROUP wall/gran model ... primitive type T SHAPE ARGS | mesh n_meshes N meshes ...`
/// with keywords and model settings after them.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let FixDef { id, group, .. } = *fix;
    let fail = |k: usize, m: &str| a.error(k, format!("Fix wall/gran (id {id}): {m}"));
    let (mut selection, k, pending) = gran_models(a, ctx, 3, "fix wall/gran")?;
    if let Some(d) = pending {
        return Err(d);
    }
    let (wall, k) = wall_keywords(a, ctx, k, &fail)?;
    // the rest are the contact model's on/off settings
    let rest: Vec<&str> = (k..a.len())
        .map(|i| a.word(i))
        .collect::<std::result::Result<_, _>>()?;
    if let Err(e) = selection.apply_settings(&rest) {
        // a mesh ID beyond the count `n_meshes` gave
        let extra_mesh = rest.first().is_some_and(|w| {
            wall.meshes.is_some()
                && ctx
                    .sim
                    .fixes
                    .iter()
                    .any(|f| f.id == *w && f.kind.mesh().is_some())
        });
        return Err(match e {
            ModelError::Invalid(m) if extra_mesh => fail(k, &m).with_help(format!(
                "'{}' is a mesh: the meshes listed outnumber n_meshes",
                rest[0]
            )),
            ModelError::Invalid(m) => fail(k, &m),
            ModelError::Unsupported(setting) => a.unsupported(
                k,
                &format!("fix wall/gran setting {}", setting.trim_matches('\'')),
            ),
        });
    }
    let group_index = ctx.sim.groups.iter().position(|g| g == group).unwrap_or(0) as u32;
    wall_kind(selection, wall, id, group_index, &fail)
}

/// The fix's own keywords from word `k` on, in any order until a word that is none of
/// them: the wall they define and the first word after them.
fn wall_keywords(
    a: &Args,
    ctx: &Ctx,
    mut k: usize,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<(Wall, usize), CommandError> {
    // LIGGGHTS's meshwall_ (`mesh_style`): unset, primitive (false) or mesh (true),
    // whichever came last
    let mut wall = Wall {
        mesh_style: None,
        primitive: None,
        meshes: None,
        shear: None,
    };
    let mut n_meshes = 0usize;
    while k < a.len() {
        match a.word(k)? {
            "primitive" => {
                wall.mesh_style = Some(false);
                let (primitive, next) = primitive_wall(a, ctx, k, fail)?;
                wall.primitive = Some(primitive);
                k = next;
            }
            "mesh" => {
                wall.mesh_style = Some(true);
                k += 1;
            }
            // LIGGGHTS 3.8.0 sets a flag nothing reads
            "track_energy" => k += 1,
            // only relaxes a check of triclinic and wedge domains, which regolith has not
            "allow_special_domain_periodic" => {
                yes_no(a, k, "allow_special_domain_periodic", fail)?;
                k += 2;
            }
            w @ ("store_force" | "store_force_contact" | "store_force_contact_stress") => {
                store_force(a, k, w, fail)?;
                k += 2;
            }
            "store_force_contact_every" => return Err(store_force_every(a, k, fail)),
            "n_meshes" => {
                n_meshes = n_meshes_keyword(a, k, wall.mesh_style, fail)?;
                k += 2;
            }
            "meshes" => {
                wall.meshes = Some(mesh_list(a, ctx, k, (wall.mesh_style, n_meshes), fail)?);
                k += 1 + n_meshes;
            }
            "shear" => {
                wall.shear = Some(shear(a, k, wall.primitive.is_some(), fail)?);
                k += 3;
            }
            "temperature" => {
                if k + 1 >= a.len() {
                    return Err(fail(k, "not enough arguments for 'temperature'"));
                }
                a.real(k + 1)?;
                return Err(
                    a.unsupported(k, "fix wall/gran temperature (heat transfer with walls)")
                );
            }
            "contact_area" => {
                contact_area(a, k, fail)?;
                k += 2;
            }
            _ => break,
        }
    }
    Ok((wall, k))
}

/// The `yes`/`no` after keyword `what` at word `k`, with LIGGGHTS's errors.
fn yes_no(
    a: &Args,
    k: usize,
    what: &str,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<bool, CommandError> {
    if k + 2 > a.len() {
        return Err(fail(k, " not enough arguments"));
    }
    match a.word(k + 1)? {
        "yes" => Ok(true),
        "no" => Ok(false),
        _ => Err(fail(
            k + 1,
            &format!("expecting 'yes' or 'no' after keyword '{what}'"),
        )),
    }
}

/// `store_force`, `store_force_contact` or `store_force_contact_stress` (keyword `w` at
/// word `k`): `no` passes, `yes` is not supported yet.
fn store_force(
    a: &Args,
    k: usize,
    w: &str,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<(), CommandError> {
    // the names LIGGGHTS's messages give them
    let named = match w {
        "store_force" => "store_force",
        "store_force_contact" => "store_force_contact_",
        _ => "store_force_contact_stress_",
    };
    if yes_no(a, k, named, fail)? {
        return Err(a.unsupported(k, &format!("fix wall/gran {w} yes")));
    }
    Ok(())
}

/// `store_force_contact_every N` at word `k`: LIGGGHTS's errors for N, else not supported yet.
fn store_force_every(
    a: &Args,
    k: usize,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> CommandError {
    if k + 2 > a.len() {
        return fail(k, " not enough arguments");
    }
    match a.word(k + 1) {
        Err(e) => e,
        Ok(w) if c_atoi(w) <= 0 => fail(k + 1, "store_force_contact_every must be > 0"),
        Ok(_) => a.unsupported(k, "fix wall/gran store_force_contact_every"),
    }
}

/// `n_meshes N` at word `k` (after `mesh`): the number of meshes.
fn n_meshes_keyword(
    a: &Args,
    k: usize,
    mesh_style: Option<bool>,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<usize, CommandError> {
    if mesh_style != Some(true) {
        return Err(fail(
            k,
            "have to use keyword 'mesh' before using 'n_meshes'",
        ));
    }
    if k + 2 > a.len() {
        return Err(fail(k, "not enough arguments"));
    }
    let n = c_atoi(a.word(k + 1)?);
    if n < 1 {
        return Err(fail(k + 1, "'n_meshes' > 0 required"));
    }
    Ok(n as usize)
}

/// `shear x|y|z V` at word `k` (after a primitive wall): the dimension and the velocity.
fn shear(
    a: &Args,
    k: usize,
    has_primitive: bool,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<(usize, f64), CommandError> {
    if k + 3 > a.len() {
        return Err(fail(k, "not enough arguments for 'shear'"));
    }
    if !has_primitive {
        return Err(fail(k, "have to define primitive wall before 'shear'. For mehs walls, please use fix move/mesh"));
    }
    let dim = match a.word(k + 1)? {
        "x" => 0,
        "y" => 1,
        "z" => 2,
        _ => return Err(fail(k + 1, "illegal 'shear' dim")),
    };
    Ok((dim, a.real(k + 2)?))
}

/// The wall of `primitive type T SHAPE ARGS` at word `k` and the word after it.
fn primitive_wall(
    a: &Args,
    ctx: &Ctx,
    k: usize,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<((usize, Primitive), usize), CommandError> {
    if a.word(k + 1)? != "type" {
        return Err(fail(k + 1, "expecting keyword 'type'"));
    }
    let wall_type = a.int(k + 2)?;
    if wall_type < 1 || wall_type > ctx.sim.ntypes as i64 {
        return Err(fail(
            k + 2,
            "1 <= type <= max type as defined in create_box'",
        ));
    }
    let shape_word = a.word(k + 3)?;
    let nargs = match shape_word {
        "xplane" | "yplane" | "zplane" => 1,
        "xcylinder" | "ycylinder" | "zcylinder" => 3,
        _ => 0,
    };
    let first = k + 4;
    if a.len() - first < nargs {
        return Err(fail(k + 3, "not enough arguments for primitive wall"));
    }
    let values = (first..first + nargs)
        .map(|i| a.real(i))
        .collect::<Result<Vec<f64>, _>>()?;
    // only the named shapes (x/y/z first) have an axis
    let axis = || usize::from(shape_word.as_bytes()[0] - b'x');
    let shape = match nargs {
        1 => Primitive::Plane {
            axis: axis(),
            position: values[0],
        },
        3 => Primitive::Cylinder {
            axis: axis(),
            radius: values[0],
            c1: values[1],
            c2: values[2],
        },
        _ => return Err(fail(k + 3, "unknown primitive wall style")),
    };
    Ok(((wall_type as usize, shape), first + nargs))
}

/// `contact_area overlap|projection|constant A` at word `k`: the default (overlap) passes,
/// the others are refused.
fn contact_area(
    a: &Args,
    k: usize,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<(), CommandError> {
    match a.word(k + 1)? {
        // the default
        "overlap" => {}
        "projection" => return Err(a.unsupported(k, "fix wall/gran contact_area projection")),
        "constant" => {
            if k + 3 > a.len() {
                return Err(fail(
                    k,
                    "not enough arguments for keyword 'contact_area constant'",
                ));
            }
            if a.real(k + 2)? <= 0.0 {
                return Err(fail(k + 2, "'contact_area constant' value must be > 0"));
            }
            return Err(a.unsupported(k, "fix wall/gran contact_area constant"));
        }
        _ => {
            return Err(fail(
                k + 1,
                "expecting 'overlap', 'projection' or 'constant' after 'contact_area'",
            ))
        }
    }
    Ok(())
}

/// The mesh IDs of `meshes ID ...` at word `k` (`style`: LIGGGHTS's meshwall_ and the
/// `n_meshes` count read before it).
fn mesh_list(
    a: &Args,
    ctx: &Ctx,
    k: usize,
    (mesh_style, n_meshes): (Option<bool>, usize),
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<Vec<String>, CommandError> {
    if mesh_style != Some(true) {
        return Err(fail(k, "have to use keyword 'mesh' before using 'meshes'"));
    }
    if n_meshes == 0 {
        return Err(fail(k, "have to define 'n_meshes' before 'meshes'"));
    }
    if a.len() < k + 1 + n_meshes {
        return Err(fail(k, "not enough arguments"));
    }
    let mut list = Vec::with_capacity(n_meshes);
    for i in k + 1..k + 1 + n_meshes {
        let mesh_id = a.word(i)?;
        let Some(f) = ctx.sim.fixes.iter().find(|f| f.id == mesh_id) else {
            return Err(fail(i, "could not find fix mesh id you provided"));
        };
        if f.kind.mesh().is_none() {
            return Err(fail(
                i,
                "the fix belonging to the id you provided is not of type mesh",
            ));
        }
        list.push(mesh_id.to_string());
    }
    Ok(list)
}

/// What the arguments of a wall say besides its contact model.
struct Wall {
    mesh_style: Option<bool>,
    primitive: Option<(usize, Primitive)>,
    meshes: Option<Vec<String>>,
    shear: Option<(usize, f64)>,
}

/// The fix of a primitive or mesh wall with contact model `selection` (fix `id`; its
/// group's index `group_index`).
fn wall_kind(
    selection: crate::engine::granular::Selection,
    wall: Wall,
    id: &str,
    group_index: u32,
    fail: &dyn Fn(usize, &str) -> CommandError,
) -> Result<Box<dyn FixStyle>, CommandError> {
    let Wall {
        mesh_style,
        primitive,
        meshes,
        shear,
    } = wall;
    match (mesh_style, primitive) {
        (Some(true), _) => {
            let Some(meshes) = meshes else {
                return Err(fail(
                    2,
                    "Need to provide the number and a list of meshes by using 'n_meshes' and 'meshes'",
                ));
            };
            Ok(Box::new(MeshWallFix {
                selection,
                meshes,
                group_index,
                model: None,
                trackers: Vec::new(),
                built: None,
                multicontact: Vec::new(),
            }))
        }
        (_, Some((wall_type, plane))) => Ok(Box::new(WallFix {
            selection,
            plane,
            wall_type,
            shear,
            model: None,
            history_name: format!("history_{id}"),
            multicontact: None,
        })),
        _ => Err(fail(2, "Need to use define style 'mesh' or 'primitive'")),
    }
}

/// A primitive wall: its forces in `post_force` from the wall's own list of the pair list's
/// particles, its history per particle.
impl FixStyle for WallFix {
    fn name(&self) -> &str {
        "wall/gran"
    }

    fn among_fixes(&self) -> bool {
        true
    }

    fn post_force_among(
        &mut self,
        _fixes: &mut [Fix],
        p: &mut crate::engine::particles::Particles,
        at: &FixStep,
        pass: &ForcePass,
    ) {
        let Some(model) = self.model.as_mut() else {
            return;
        };
        let k = p.extra_index(&self.history_name, model.history_width());
        let mut history = std::mem::take(&mut p.extra[k].data);
        let store = self.multicontact.as_ref();
        model.compute(
            p,
            at.group,
            &mut history,
            at.dt,
            pass.update,
            pass.list,
            store,
        );
        p.extra[k].data = history;
    }

    fn refuses_thermo(&self) -> bool {
        true
    }

    fn array_unsupported(&self) -> bool {
        true
    }
}

/// Mesh walls: their forces in `post_force` from their meshes among the other fixes, each
/// contact's force summed into its mesh's stress module.
impl FixStyle for MeshWallFix {
    fn name(&self) -> &str {
        "wall/gran"
    }

    fn among_fixes(&self) -> bool {
        true
    }

    fn post_force_among(
        &mut self,
        fixes: &mut [Fix],
        p: &mut crate::engine::particles::Particles,
        at: &FixStep,
        pass: &ForcePass,
    ) {
        crate::engine::fixes::mesh_wall_force(self, fixes, p, at.dt, pass);
    }

    fn refuses_thermo(&self) -> bool {
        true
    }

    fn array_unsupported(&self) -> bool {
        true
    }
}
