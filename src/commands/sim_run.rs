//! Commands that drive and observe the run: fixes regolith integrates, thermo, dumps, `run`.

use crate::commands::registry::{self, Handler};
use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::engine::error::EngineError;
use crate::engine::fixes::{Fix, FixKind, Motion, Move};
use crate::engine::integrate::Gravity;
use crate::engine::sim::Dump;
use crate::io::dump::Layout;
use crate::script::system::Mode;

type Result = std::result::Result<(), CommandError>;

/// The commands that drive and observe the run, and their handlers.
pub const COMMANDS: &[(&str, Handler)] = &[
    ("fix", fix),
    ("unfix", unfix),
    ("thermo", thermo),
    ("thermo_style", thermo_style),
    ("thermo_modify", thermo_modify),
    ("dump", dump),
    ("dump_modify", dump_modify),
    ("undump", undump),
    ("run", run),
    ("compute", compute),
    ("uncompute", uncompute),
    ("pair_style", pair_style),
    ("pair_coeff", pair_coeff),
    ("soft_particles", |a, ctx| {
        soft_hard("soft_particles", a, ctx)
    }),
    ("hard_particles", |a, ctx| {
        soft_hard("hard_particles", a, ctx)
    }),
    ("write_dump", super::write_dump::write_dump),
    ("thermo_log", super::logs::thermo_log),
    ("modify_timing", super::logs::modify_timing),
];

fn fix(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(3..=usize::MAX, "fix ID GROUP STYLE ...")?;
    let (id, group, style) = (a.word(0)?, a.word(1)?, a.word(2)?);
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Fix command before simulation box is defined"));
    }
    if !id.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') {
        return Err(a.error(0, "Fix ID must be alphanumeric or underscore characters"));
    }
    let bit = ctx
        .sim
        .group_bit(group)
        .ok_or_else(|| a.error(1, "Could not find fix group ID"))?;
    registry::require_style(a, "fix")?;
    let kind = 'style: {
        match style {
            "nve/noforce" => {
                if a.len() != 3 {
                    return Err(a.error(3, "Illegal fix nve/noforce command"));
                }
                FixKind::NveNoforce
            }
            "nve/sphere" => {
                if a.len() > 3 {
                    return Err(a.unsupported(3, "fix nve/sphere keywords"));
                }
                FixKind::NveSphere
            }
            "gravity" => {
                a.count(4..=usize::MAX, "fix ID GROUP gravity MAG vector X Y Z")?;
                let magnitude = a.real(3)?;
                match a.word(4)? {
                    "vector" => {
                        a.count(8..=8, "fix ID GROUP gravity MAG vector X Y Z")?;
                        let dir = [a.real(5)?, a.real(6)?, a.real(7)?];
                        FixKind::Gravity(
                            Gravity::along(magnitude, dir, bit).map_err(|m| a.error(5, &m))?,
                        )
                    }
                    other => return Err(a.unsupported(4, &format!("fix gravity {other}"))),
                }
            }
            "check/timestep/gran" => {
                a.count(6..=usize::MAX, "fix ID GROUP check/timestep/gran N RAYLEIGH_LIMIT HERTZ_LIMIT [warn yes|no] [error yes|no] [vmax V]")?;
                let every = a.int(3)?;
                if every <= 0 {
                    return Err(a.error(3, "Illegal fix check/timestep/gran command"));
                }
                let mut c = crate::engine::fixes::CheckTimestep {
                    every,
                    rayleigh_limit: a.real(4)?,
                    hertz_limit: a.real(5)?,
                    warn: true,
                    error: false,
                    vmax_user: 0.0,
                    values: [0.0; 3],
                    materials: Vec::new(),
                };
                let mut i = 6;
                while i < a.len() {
                    match a.word(i)? {
                        "warn" => c.warn = a.word_in(i + 1, &["yes", "no"])? == "yes",
                        "error" => c.error = a.word_in(i + 1, &["yes", "no"])? == "yes",
                        "vmax" => c.vmax_user = a.real(i + 1)?,
                        _ => return Err(a.keyword_error(i, &["warn", "error", "vmax"])),
                    }
                    i += 2;
                }
                if c.error {
                    return Err(a.unsupported(6, "fix check/timestep/gran error yes"));
                }
                FixKind::CheckTimestep(c)
            }
            "property/global" => {
                a.count(
                    6..=usize::MAX,
                    "fix ID GROUP property/global NAME STYLE VALUES...",
                )?;
                let style = a.word_in(
                    4,
                    &[
                        "scalar",
                        "vector",
                        "peratomtype",
                        "atomtype",
                        "peratomtypepair",
                        "atomtypepair",
                        "matrix",
                    ],
                )?;
                let first_value = if matches!(style, "peratomtypepair" | "atomtypepair" | "matrix")
                {
                    6
                } else {
                    5
                };
                if matches!(style, "peratomtypepair" | "atomtypepair" | "matrix") {
                    let n = a.int(5)?;
                    if n < 1 {
                        return Err(a.error(5, "Illegal fix property/global command"));
                    }
                    if (a.len() - first_value) as i64 % n != 0 {
                        return Err(a.error(5, "Fix property/global: the number of default values must be a multiple of nCols."));
                    }
                }
                for i in first_value..a.len() {
                    a.real(i)?;
                }
                super::material_check::remember(a, ctx);
                FixKind::Settings
            }
            "mesh/surface" | "mesh/surface/planar" | "mesh/surface/stress" => {
                mesh_surface(a, ctx, style)?
            }
            "move/mesh" => move_mesh(a, ctx)?,
            "particletemplate/sphere" => particle_template(a, ctx, id)?,
            "particledistribution/discrete"
            | "particledistribution/discrete/numberbased"
            | "particledistribution/discrete/massbased" => distribution(a, ctx, style)?,
            "insert/pack" | "insert/rate/region" => {
                ctx.sim.inserts_atoms = true;
                insert_pack(a, ctx, id, style)?
            }
            "insert/stream" => {
                ctx.sim.inserts_atoms = true;
                insert_stream(a, ctx, id)?
            }
            "wall/gran" => {
                let (selection, next, pending) = gran_models(a, 3, "history", "fix wall/gran")?;
                if let Some(d) = pending {
                    return Err(d);
                }
                if a.word(next)? == "mesh" {
                    break 'style mesh_wall(a, ctx, group, selection, next)?;
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
                    other => {
                        return Err(
                            a.unsupported(next + 3, &format!("fix wall/gran primitive {other}"))
                        )
                    }
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
                                _ => {
                                    return Err(a.error(k + 1, "Fix wall/gran: illegal 'shear' dim"))
                                }
                            };
                            shear = Some((dim, a.real(k + 2)?));
                            k += 3;
                        }
                        "store_force" | "store_force_contact" | "store_force_contact_stress" => {
                            if a.word_in(k + 1, &["yes", "no"])? == "yes" {
                                return Err(
                                    a.unsupported(k, &format!("fix wall/gran {} yes", a.word(k)?))
                                );
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
                FixKind::WallGran(crate::engine::fixes::WallFix {
                    selection,
                    plane: shape,
                    wall_type: wall_type as usize,
                    shear,
                    model: None,
                    history_name: format!("history_{id}"),
                })
            }
            "freeze" => {
                if a.len() > 3 {
                    return Err(a.error(3, "Illegal fix freeze command"));
                }
                if ctx
                    .sim
                    .fixes
                    .iter()
                    .any(|f| matches!(f.kind, FixKind::Freeze) && f.id != id)
                {
                    return Err(a.error(2, "More than one fix freeze"));
                }
                FixKind::Freeze
            }
            "setforce" | "addforce" => {
                use crate::engine::fixes::{ForceFix, ForceValue};
                a.count(
                    6..=usize::MAX,
                    &format!("fix ID GROUP {style} FX FY FZ [region ID]"),
                )?;
                let mut values = [ForceValue::Null, ForceValue::Null, ForceValue::Null];
                for (d, slot) in values.iter_mut().enumerate() {
                    let w = a.word(3 + d)?;
                    if let Some(name) = w.strip_prefix("v_") {
                        *slot = variable_value(a, ctx, 3 + d, name, style)?;
                    } else if w != "NULL" {
                        *slot = ForceValue::Constant(a.real(3 + d)?);
                    } else if style == "addforce" {
                        return Err(a.error(3 + d, "Illegal fix addforce command"));
                    }
                }
                let mut region = None;
                let mut i = 6;
                while i < a.len() {
                    match a.word(i)? {
                        "region" => {
                            let id = a.word(i + 1)?;
                            region = Some(ctx.sim.regions.find(id).ok_or_else(|| {
                                a.error(i + 1, format!("Region ID for fix {style} does not exist"))
                            })?);
                            i += 2;
                        }
                        w => {
                            return Err(a.unsupported(i, &format!("fix {style} keyword {w}")));
                        }
                    }
                }
                let f = ForceFix {
                    values,
                    region,
                    resolved: Vec::new(),
                };
                if style == "setforce" {
                    FixKind::SetForce(f)
                } else {
                    FixKind::AddForce(f)
                }
            }
            "adapt" => {
                use crate::engine::fixes::{Adapt, ForceValue};
                a.count(
                    5..=usize::MAX,
                    "fix ID GROUP adapt N atom diameter v_name ...",
                )?;
                let every = a.int(3)?;
                if every < 0 {
                    return Err(a.error(3, "Illegal fix adapt command"));
                }
                let mut diameter = None;
                let (mut scale, mut i) = (false, 4);
                while i < a.len() {
                    match a.word(i)? {
                        "atom" => {
                            a.count(
                                i + 3..=usize::MAX,
                                "fix ID GROUP adapt N atom diameter v_name",
                            )?;
                            match a.word(i + 1)? {
                                "diameter" => {}
                                "charge" => {
                                    return Err(
                                        a.error(i + 1, "Fix adapt requires atom attribute charge")
                                    )
                                }
                                _ => return Err(a.error(i + 1, "Illegal fix adapt command")),
                            }
                            let Some(name) = a.word(i + 2)?.strip_prefix("v_") else {
                                return Err(a.error(i + 2, "Illegal fix adapt command"));
                            };
                            diameter = Some(variable_value(a, ctx, i + 2, name, "adapt")?);
                            i += 3;
                        }
                        w @ ("pair" | "kspace") => {
                            return Err(a.unsupported(i, &format!("fix adapt {w}")))
                        }
                        "scale" => {
                            scale = a.word_in(i + 1, &["yes", "no"])? == "yes";
                            i += 2;
                        }
                        // LIGGGHTS restores nothing for atom attributes: `reset` has no effect
                        "reset" => {
                            a.word_in(i + 1, &["yes", "no"])?;
                            i += 2;
                        }
                        _ => return Err(a.error(i, "Illegal fix adapt command")),
                    }
                }
                let Some(diameter) = diameter else {
                    return Err(a.error(3, "Illegal fix adapt command"));
                };
                debug_assert!(!matches!(diameter, ForceValue::Null));
                FixKind::Adapt(Adapt {
                    every,
                    diameter,
                    scale,
                })
            }
            "print" => {
                a.count(
                    5..=usize::MAX,
                    "fix ID GROUP print N \"text\" [file F] [screen yes|no] [title T]",
                )?;
                let every = a.int(3)?;
                if every <= 0 {
                    return Err(a.error(3, "Illegal fix print command"));
                }
                let text = a.word(4)?.to_string();
                let (mut screen, mut file, mut title) = (true, None, None);
                let mut i = 5;
                while i < a.len() {
                    match a.word(i)? {
                        kw @ ("file" | "append") => {
                            let name = a.word(i + 1)?;
                            if ctx.sys.mode == crate::script::system::Mode::Run {
                                let f = std::fs::OpenOptions::new()
                                    .create(true)
                                    .write(true)
                                    .append(kw == "append")
                                    .truncate(kw == "file")
                                    .open(name)
                                    .map_err(|_| {
                                        a.file_error(
                                            i + 1,
                                            format!("Cannot open fix print file {name}"),
                                        )
                                    })?;
                                file = Some(std::io::BufWriter::new(f));
                            }
                        }
                        "screen" => screen = a.word_in(i + 1, &["yes", "no"])? == "yes",
                        "title" => title = Some(a.word(i + 1)?.to_string()),
                        _ => return Err(a.error(i, "Illegal fix print command")),
                    }
                    i += 2;
                }
                if let Some(f) = file.as_mut() {
                    use std::io::Write;
                    let head = match title.as_deref() {
                        Some("none") => None,
                        Some(t) => Some(t.to_string()),
                        None => Some(format!("# Fix print output for fix {id}")),
                    };
                    if let Some(h) = head {
                        writeln!(f, "{h}")
                            .and_then(|_| f.flush())
                            .map_err(|e| a.error(0, format!("fix print: {e}")))?;
                    }
                }
                FixKind::Print(crate::engine::fixes::PrintFix {
                    every,
                    text,
                    screen,
                    file,
                })
            }
            "ave/time" => ave_time(a, ctx, id)?,
            "viscous" => {
                a.count(4..=4, "fix ID GROUP viscous GAMMA")?;
                FixKind::Viscous(a.real(3)?)
            }
            "move" => {
                let components =
                    |from: usize| -> std::result::Result<[Option<f64>; 3], CommandError> {
                        let mut v = [None; 3];
                        for (d, slot) in v.iter_mut().enumerate() {
                            let w = a.word(from + d)?;
                            if w != "NULL" {
                                *slot = Some(a.real(from + d)?);
                            }
                        }
                        Ok(v)
                    };
                let (motion, used) = match a.word(3)? {
                    "linear" => (Motion::Linear(components(4)?), 7),
                    "wiggle" => {
                        let amplitude = components(4)?;
                        let period = a.real(7)?;
                        if period <= 0.0 {
                            return Err(a.error(7, "Illegal fix move command"));
                        }
                        (
                            Motion::Wiggle {
                                amplitude,
                                omega: 2.0 * std::f64::consts::PI / period,
                            },
                            8,
                        )
                    }
                    "rotate" => {
                        a.count(
                            11..=usize::MAX,
                            "fix ID GROUP move rotate Px Py Pz Rx Ry Rz PERIOD",
                        )?;
                        let point = [a.real(4)?, a.real(5)?, a.real(6)?];
                        let axis = [a.real(7)?, a.real(8)?, a.real(9)?];
                        let period = a.real(10)?;
                        if period <= 0.0 {
                            return Err(a.error(10, "Illegal fix move command"));
                        }
                        let len =
                            (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
                        if len == 0.0 {
                            return Err(a.error(7, "Zero length rotation vector with fix move"));
                        }
                        (
                            Motion::Rotate {
                                point,
                                axis: axis.map(|c| c / len),
                                omega: 2.0 * std::f64::consts::PI / period,
                            },
                            11,
                        )
                    }
                    "variable" => {
                        use crate::engine::fixes::ForceValue;
                        a.count(
                            10..=usize::MAX,
                            "fix ID GROUP move variable DX DY DZ VX VY VZ",
                        )?;
                        let mut slots: [ForceValue; 6] = Default::default();
                        for (k, slot) in slots.iter_mut().enumerate() {
                            let w = a.word(4 + k)?;
                            if let Some(name) = w.strip_prefix("v_") {
                                *slot = variable_value(a, ctx, 4 + k, name, "move")?;
                            } else if w != "NULL" {
                                return Err(a.error(4 + k, "Illegal fix move command"));
                            }
                        }
                        let [dx, dy, dz, vx, vy, vz] = slots;
                        (
                            Motion::Variable {
                                displace: [dx, dy, dz],
                                velocity: [vx, vy, vz],
                            },
                            10,
                        )
                    }
                    _ => return Err(a.error(3, "Illegal fix move command")),
                };
                // `units lattice` scales lengths and velocities by the lattice spacing
                let mut motion = motion;
                let mut i = used;
                while i < a.len() {
                    match a.word(i)? {
                        "units" => {
                            if a.word_in(i + 1, &["box", "lattice"])? == "lattice" {
                                let scale =
                                    ctx.sim.lattice.as_ref().map(|l| l.0).ok_or_else(|| {
                                        a.error(i + 1, "Use of fix move with undefined lattice")
                                    })?;
                                let sc = |v: &mut [Option<f64>; 3]| {
                                    v.iter_mut().for_each(|c| *c = c.map(|x| x * scale))
                                };
                                match &mut motion {
                                    Motion::Linear(v) => sc(v),
                                    Motion::Wiggle { amplitude, .. } => sc(amplitude),
                                    Motion::Rotate { point, .. } => {
                                        point.iter_mut().for_each(|c| *c *= scale)
                                    }
                                    // LIGGGHTS scales variable motion by neither
                                    Motion::Variable { .. } => {}
                                }
                            }
                            i += 2;
                        }
                        _ => return Err(a.error(i, "Illegal fix move command")),
                    }
                }
                let sim = &ctx.sim;
                FixKind::Move(Move::new(
                    motion,
                    &sim.particles,
                    bit,
                    &sim.domain,
                    sim.step,
                ))
            }
            other => return Err(a.unsupported(2, &format!("fix {other}"))),
        }
    };
    let args: Vec<String> = (3..a.len())
        .map(|i| a.word(i).map(str::to_string))
        .collect::<std::result::Result<_, _>>()?;
    let mut fix = Fix {
        id: id.to_string(),
        style: style.to_string(),
        group: bit,
        kind,
        args,
    };
    for line in crate::commands::fix_state::restore_fix_state(a, ctx, &mut fix)? {
        ctx.say(&format!("{line}\n"));
    }
    match ctx.sim.fixes.iter().position(|f| f.id == id) {
        Some(i) => {
            if ctx.sim.fixes[i].style != style {
                return Err(a.error(2, "Replacing a fix, but new style != old style"));
            }
            ctx.sim.fixes[i] = fix;
        }
        None => ctx.sim.fixes.push(fix),
    }
    Ok(())
}

fn unfix(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "unfix ID")?;
    let id = a.word(0)?;
    if ctx.sim.computes.iter().any(|c| {
        matches!(&c.kind, crate::engine::computes::ComputeKind::WallGranLocal { wall, .. } if wall == id)
    }) {
        return Err(a.error(0, format!("Fix wall/gran (id {id}): need to uncompute the active compute wall/gran/local before unfixing the wall")));
    }
    let movers = |mesh: &str| -> Vec<usize> {
        (0..ctx.sim.fixes.len())
            .filter(|&k| matches!(&ctx.sim.fixes[k].kind, FixKind::MoveMesh(m) if m.mesh == mesh))
            .collect()
    };
    if let Some(k) = ctx.sim.fixes.iter().position(|f| f.id == id) {
        match &ctx.sim.fixes[k].kind {
            FixKind::MoveMesh(mv) => {
                let on_mesh = movers(&mv.mesh);
                if on_mesh.len() > 1 && on_mesh[0] == k {
                    return Err(a.error(0, "Illegal deletion of a fix move/mesh. There is another fix move/mesh command active on the same mesh. Superposed fix move/mesh commands must be unfixed in reverse order of creation"));
                }
                // the mesh stays where it is, at rest
                let mesh = mv.mesh.clone();
                for f in ctx.sim.fixes.iter_mut() {
                    if let FixKind::Mesh(m) = &mut f.kind {
                        if f.id == mesh {
                            if let Some(v) = &mut m.node_v {
                                v.iter_mut().for_each(|t| *t = [[0.0; 3]; 3]);
                            }
                        }
                    }
                }
            }
            FixKind::Mesh(_) => {
                if let Some(&m) = movers(id).first() {
                    return Err(a.error(0, format!("Fix mesh/surface (id {id}): illegal unfix command, may not unfix a moving mesh while a fix move is applied to it. Unfix the fix move/mesh first (id: {})", ctx.sim.fixes[m].id)));
                }
            }
            _ => {}
        }
    }
    remove_by_id(
        &mut ctx.sim.fixes,
        |f| &f.id,
        a,
        "Could not find fix ID to delete",
    )
}

fn thermo(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "thermo N")?;
    let n = a.int(0)?;
    if n < 0 {
        return Err(a.error(0, "Illegal thermo command"));
    }
    ctx.sim.thermo.every = n;
    Ok(())
}

fn thermo_style(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=usize::MAX, "thermo_style one|custom KEYWORDS...")?;
    let words: Vec<&str> = match a.word(0)? {
        "one" => vec!["step", "atoms", "ke", "cpu"],
        "custom" => (1..a.len())
            .map(|i| a.word(i))
            .collect::<std::result::Result<_, _>>()?,
        "multi" => vec!["step", "atoms", "ke", "cpu"],
        _ => return Err(a.keyword_error(0, &["one", "custom", "multi"])),
    };
    if a.word(0)? != "custom" && a.len() > 1 {
        return Err(a.error(1, "Illegal thermo_style command"));
    }
    ctx.sim.thermo.custom = a.word(0)? == "custom";
    ctx.sim.thermo.set_style(&words).map_err(|e| {
        let m = e.to_string();
        let at = words
            .iter()
            .position(|w| m.contains(w))
            .map_or(0, |k| k + 1);
        match e {
            EngineError::Unsupported(what) => a.unsupported(at, &what),
            EngineError::Invalid(m) => a.error(at, m),
        }
    })?;
    // LIGGGHTS: a new thermo_style resets thermo_modify settings
    let t = &mut ctx.sim.thermo;
    t.multi = a.word(0)? == "multi";
    t.int_format = None;
    t.float_format = None;
    t.column_formats = vec![None; t.fields.len()];
    ctx.sim.thermo.norm = false;
    ctx.sim.lost_ignore = true;
    Ok(())
}

fn thermo_modify(a: &Args, ctx: &mut Ctx) -> Result {
    let mut i = 0;
    while i < a.len() {
        match a.word(i)? {
            "norm" => ctx.sim.thermo.norm = a.word_in(i + 1, &["yes", "no"])? == "yes",
            "lost" => {
                ctx.sim.lost_ignore = a.word_in(i + 1, &["ignore", "warn", "error"])? != "error"
            }
            "flush" => {
                a.word_in(i + 1, &["yes", "no"])?;
            }
            "line" => ctx.sim.thermo.multi = a.word_in(i + 1, &["one", "multi"])? == "multi",
            "format" => {
                let which = a.word(i + 1)?;
                let spec = a.word(i + 2)?.to_string();
                let probe = if which == "int" { 1.0 } else { 0.5 };
                crate::util::format::with_spec(&spec, probe)
                    .map_err(|m| a.error(i + 2, format!("thermo_modify format: {m}")))?;
                let t = &mut ctx.sim.thermo;
                match which {
                    "int" => {
                        if !spec.contains('d') {
                            return Err(a.error(
                                i + 2,
                                "Thermo_modify int format does not contain d character",
                            ));
                        }
                        t.int_format = Some(spec)
                    }
                    "float" => t.float_format = Some(spec),
                    n => {
                        let k = n.parse::<i64>().unwrap_or(0) - 1;
                        if k < 0 || k as usize >= t.fields.len() {
                            return Err(a.error(i + 1, "Illegal thermo_modify command"));
                        }
                        t.column_formats.resize(t.fields.len(), None);
                        t.column_formats[k as usize] = Some(spec);
                    }
                }
                i += 1;
            }
            other => return Err(a.unsupported(i, &format!("thermo_modify {other}"))),
        }
        i += 2;
    }
    Ok(())
}

pub(super) fn dump(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(5..=usize::MAX, "dump ID GROUP custom N FILE columns...")?;
    let (id, group, style) = (a.word(0)?, a.word(1)?, a.word(2)?);
    let bit = ctx
        .sim
        .group_bit(group)
        .ok_or_else(|| a.error(1, "Could not find dump group ID"))?;
    if ctx.sim.dumps.iter().any(|d| d.id == id) {
        return Err(a.error(0, "Reuse of dump ID"));
    }
    let every = a.int(3)?;
    if every <= 0 {
        return Err(a.error(3, "Illegal dump command"));
    }
    let file = a.word(4)?;
    let mut dump_style = crate::engine::sim::DumpStyle::Text;
    if style == "custom/vtk" {
        if file.ends_with(".gz") {
            return Err(a.error(4, "dump custom/vtk files cannot be gzipped"));
        }
        if [".pvtu", ".pvtp", ".vtm"].iter().any(|e| file.ends_with(e)) {
            return Err(a.unsupported(
                4,
                "dump custom/vtk parallel or multiblock files (.pvtu/.pvtp/.vtm)",
            ));
        }
        if crate::io::vtk::Flavor::of(file).is_none() {
            return Err(a.error(
                4,
                "dump custom/vtk: the file name must end in .vtk, .vtp or .vtu",
            ));
        }
    }
    registry::require_style(a, "dump")?;
    let layout = match style {
        "atom" | "xyz" => {
            a.count(5..=5, &format!("dump ID GROUP {style} N FILE"))?;
            if style == "xyz" {
                dump_style = crate::engine::sim::DumpStyle::Xyz(Vec::new());
                Layout::new(&[]).expect("no columns")
            } else {
                let mut l = Layout::new(&["id", "type", "xs", "ys", "zs"]).expect("known columns");
                l.no_trailing_blank = true;
                l
            }
        }
        "mesh/vtk" | "mesh/gran/VTK" => {
            if !file.ends_with(".vtk") {
                return Err(a.unsupported(
                    4,
                    &format!(
                        "dump {style} to XML or parallel VTK files (regolith writes legacy .vtk)"
                    ),
                ));
            }
            let words: Vec<&str> = (5..a.len())
                .map(|i| a.word(i))
                .collect::<std::result::Result<_, _>>()?;
            let fixes = &ctx.sim.fixes;
            let spec = crate::io::mesh_vtk::parse_keywords(
                &words,
                |w| {
                    fixes
                        .iter()
                        .any(|f| f.id == w && matches!(f.kind, FixKind::Mesh(_)))
                },
                |_| false,
            )
            .map_err(|m| a.error(5, format!("dump {style}: {m}")))?;
            dump_style = crate::engine::sim::DumpStyle::MeshVtk(spec);
            Layout::new(&[]).expect("no columns")
        }
        "mesh/stl" => {
            let ids: Vec<String> = (5..a.len())
                .map(|i| a.word(i).map(str::to_string))
                .collect::<std::result::Result<_, _>>()?;
            for (k, id) in ids.iter().enumerate() {
                let is_mesh = ctx
                    .sim
                    .fixes
                    .iter()
                    .any(|f| &f.id == id && matches!(f.kind, FixKind::Mesh(_)));
                if !is_mesh {
                    return Err(a.error(
                        5 + k,
                        "Could not find fix mesh/surface ID for dump mesh/stl",
                    ));
                }
            }
            dump_style = crate::engine::sim::DumpStyle::MeshStl(ids);
            Layout::new(&[]).expect("no columns")
        }
        "custom" | "custom/vtk" => {
            let names: Vec<&str> = (5..a.len())
                .map(|i| a.word(i))
                .collect::<std::result::Result<_, _>>()?;
            if names.is_empty() {
                return Err(a
                    .error(4, "Illegal dump custom command")
                    .with_help("list the columns to dump"));
            }
            for (k, n) in names.iter().enumerate() {
                if let Some(body) = n.strip_prefix("f_") {
                    let (fid, index) =
                        crate::util::numbers::split_reference(body).ok_or_else(|| {
                            a.error(5 + k, "Invalid attribute in dump custom command")
                        })?;
                    crate::engine::fix_columns::column(ctx.sim, fid, index)
                        .map_err(|m| a.error(5 + k, &m))?;
                }
            }
            for (k, n) in names.iter().enumerate() {
                if let Some(var) = n.strip_prefix("v_") {
                    match ctx.vars.get(var).map(|v| v.style) {
                        Some(crate::script::variables::Style::Atom) => {}
                        Some(_) => {
                            return Err(
                                a.error(5 + k, "Dump custom variable is not atom-style variable")
                            )
                        }
                        None => {
                            return Err(a.error(5 + k, "Could not find dump custom variable name"))
                        }
                    }
                }
            }
            for (k, n) in names.iter().enumerate() {
                if let Some(body) = n.strip_prefix("c_") {
                    let (cid, index) =
                        crate::util::numbers::split_reference(body).ok_or_else(|| {
                            a.error(5 + k, "Invalid attribute in dump custom command")
                        })?;
                    let c = ctx
                        .sim
                        .computes
                        .iter()
                        .find(|c| c.id == cid)
                        .ok_or_else(|| a.error(5 + k, "Could not find dump custom compute ID"))?;
                    crate::engine::computes::column_of(c, index)
                        .map_err(|m| a.error(5 + k, format!("Dump custom: {m}")))?;
                }
            }
            let layout = Layout::new(&names).map_err(|m| {
                let k = names
                    .iter()
                    .position(|n| m.contains(&format!(" {n} ")))
                    .unwrap_or(0);
                a.error(5 + k, &m)
            })?;
            if style == "custom/vtk" {
                dump_style =
                    crate::engine::sim::DumpStyle::Vtk(crate::io::vtk::fields(&layout.names));
            }
            layout
        }
        "local" => {
            let names: Vec<&str> = (5..a.len())
                .map(|i| a.word(i))
                .collect::<std::result::Result<_, _>>()?;
            if names.is_empty() {
                return Err(a.error(4, "Illegal dump local command"));
            }
            let mut cols = Vec::new();
            for (k, n) in names.iter().enumerate() {
                let body = n
                    .strip_prefix("c_")
                    .ok_or_else(|| a.unsupported(5 + k, &format!("dump local column {n}")))?;
                let (cid, index) = crate::util::numbers::split_reference(body)
                    .ok_or_else(|| a.error(5 + k, "Invalid attribute in dump local command"))?;
                let c = ctx
                    .sim
                    .computes
                    .iter()
                    .find(|c| c.id == cid)
                    .ok_or_else(|| a.error(5 + k, "Could not find dump local compute ID"))?;
                match c.kind {
                    crate::engine::computes::ComputeKind::PairGranLocal(_) => {}
                    // always a local array, even with one column
                    crate::engine::computes::ComputeKind::WallGranLocal { .. } => {
                        if index.is_none() {
                            return Err(a.error(
                                5 + k,
                                "Dump local compute does not calculate local vector",
                            ));
                        }
                    }
                    _ => {
                        return Err(a.error(5 + k, "Dump local compute does not compute local info"))
                    }
                }
                cols.push((cid.to_string(), index.unwrap_or(1).max(1) - 1));
            }
            let mut layout = Layout::new(&[]).expect("no columns");
            layout.names = names.iter().map(|s| s.to_string()).collect();
            ctx.sim.dumps.push(Dump {
                id: id.to_string(),
                group: bit,
                every,
                file: ctx.sys.resolve(file).to_string_lossy().into_owned(),
                layout,
                local: Some(cols),
                last_written: None,
                handle: None,
                first: false,
                pad: 0,
                style: crate::engine::sim::DumpStyle::Text,
            });
            return Ok(());
        }
        other => return Err(a.unsupported(2, &format!("dump {other}"))),
    };
    ctx.sim.dumps.push(Dump {
        id: id.to_string(),
        group: bit,
        every,
        file: ctx.sys.resolve(file).to_string_lossy().into_owned(),
        layout,
        local: None,
        last_written: None,
        handle: None,
        first: false,
        pad: 0,
        style: dump_style,
    });
    Ok(())
}

/// `ID` or `ID[N]` of a `c_`/`f_` reference: the ID and the 1-based index.
pub fn split_reference(body: &str) -> Option<(&str, Option<usize>)> {
    match body.split_once('[') {
        Some((id, rest)) => Some((id, Some(rest.strip_suffix(']')?.parse().ok()?))),
        None => Some((body, None)),
    }
}

pub(super) fn dump_modify(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(3..=usize::MAX, "dump_modify ID keyword value ...")?;
    let id = a.word(0)?;
    let k = ctx
        .sim
        .dumps
        .iter()
        .position(|d| d.id == id)
        .ok_or_else(|| a.error(0, "Could not find dump_modify ID"))?;
    let mut i = 1;
    while i < a.len() {
        let dump = &mut ctx.sim.dumps[k];
        match a.word(i)? {
            "sort" => match a.word(i + 1)? {
                "id" => dump.layout.sort_by_id = true,
                "off" => dump.layout.sort_by_id = false,
                _ => return Err(a.unsupported(i + 1, "dump_modify sort by column")),
            },
            "format" => dump
                .layout
                .set_format(a.word(i + 1)?)
                .map_err(|m| a.error(i + 1, &m))?,
            "first" => dump.first = a.word_in(i + 1, &["yes", "no"])? == "yes",
            "pad" => {
                let n = a.int(i + 1)?;
                if n < 0 {
                    return Err(a.error(i + 1, "Illegal dump_modify command"));
                }
                dump.pad = n as usize;
            }
            "every" => {
                let n = a.int(i + 1)?;
                if n <= 0 {
                    return Err(a.error(i + 1, "Illegal dump_modify command"));
                }
                dump.every = n;
            }
            "flush" => {
                a.word_in(i + 1, &["yes", "no"])?;
            }
            "element" => {
                let n = ctx.sim.ntypes as usize;
                if i + n >= a.len() {
                    return Err(a.error(i, "Dump modify element names do not match atom types"));
                }
                let names: Vec<String> = (i + 1..=i + n)
                    .map(|k| a.word(k).map(str::to_string))
                    .collect::<std::result::Result<_, _>>()?;
                if let crate::engine::sim::DumpStyle::Xyz(e) = &mut ctx.sim.dumps[k].style {
                    *e = names;
                }
                i += n + 1;
                continue;
            }
            "binary" if matches!(dump.style, crate::engine::sim::DumpStyle::Vtk(_)) => {
                if a.word_in(i + 1, &["yes", "no"])? == "yes" {
                    return Err(a.unsupported(i, "dump_modify binary yes (binary VTK)"));
                }
            }
            other => return Err(a.unsupported(i, &format!("dump_modify {other}"))),
        }
        i += 2;
    }
    Ok(())
}

fn undump(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "undump ID")?;
    remove_by_id(&mut ctx.sim.dumps, |d| &d.id, a, "Could not find undump ID")
}

fn run(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(
        1..=usize::MAX,
        "run N [upto] [start N] [stop N] [pre yes|no] [post yes|no] [every M c1 c2 ...]",
    )?;
    let n = a.int(0)?;
    let (mut upto, mut start, mut stop, mut pre) = (false, None, None, true);
    let mut i = 1;
    while i < a.len() {
        match a.word(i)? {
            "upto" => {
                upto = true;
                i += 1;
            }
            "start" => {
                start = Some(a.int(i + 1)?);
                i += 2;
            }
            "stop" => {
                stop = Some(a.int(i + 1)?);
                i += 2;
            }
            "post" => {
                // post no only shortens LIGGGHTS's timing summary, which regolith keeps short
                a.word_in(i + 1, &["yes", "no"])?;
                i += 2;
            }
            "pre" => {
                pre = a.word_in(i + 1, &["yes", "no"])? == "yes";
                i += 2;
            }
            // the interpreter splits `every` runs into chunks before they get here
            "every" => return Err(a.error(i, "Illegal run command")),
            _ => return Err(a.keyword_error(i, &["upto", "start", "stop", "pre", "post", "every"])),
        }
    }
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Run command before simulation box is defined"));
    }
    let nsteps = if upto {
        let delta = n - ctx.sim.step;
        if delta < 0 {
            return Err(a.error(0, "Invalid run command upto value"));
        }
        delta
    } else {
        if n < 0 {
            return Err(a.error(0, "Invalid run command N value"));
        }
        n
    };
    if ctx
        .sim
        .step
        .checked_add(nsteps)
        .is_none_or(|last| last >= 9.2e18 as i64)
    {
        return Err(a.error(0, "Too many timesteps"));
    }
    if start.is_some_and(|s| s < 0 || s > ctx.sim.step) {
        return Err(a.error(0, "Run command start value is after start of run"));
    }
    if stop.is_some_and(|s| s < ctx.sim.step + nsteps) {
        return Err(a.error(0, "Run command stop value is before end of run"));
    }
    super::material_check::validate(a, ctx)?;
    super::compute_modify::setup_counts(ctx.sim);
    if ctx.sys.mode == Mode::Check {
        // a dry run validates the deck but never steps: it makes LIGGGHTS's init checks, keeps
        // the restart files the run would write, and moves the step count to the run's end
        ctx.sim.check_run().map_err(|m| a.error(0, &m))?;
        if let Some(m) = ctx.sim.new_margin() {
            ctx.sim.margin_notes.push(m);
        }
        if ctx.sim.restart_output.iter().any(Option::is_some) {
            ctx.sim.check_restart_size().map_err(|m| a.error(0, &m))?;
        }
        keep_periodic_restarts(ctx, nsteps);
        ctx.sim.step += nsteps;
        return Ok(());
    }
    if ctx.sim.pair_selection.is_some() && !ctx.sim.pair_coeff_set {
        return Err(a.error(0, "All pair coeffs are not set"));
    }
    ctx.sim.ramp_bounds = (start, stop);
    let out = &mut *ctx.out;
    let mut sink = |s: &str| out.both(s);
    let mut vars = crate::script::scope::RunVariables {
        vars: &mut *ctx.vars,
        sys: &mut *ctx.sys,
    };
    ctx.sim
        .run_with_setup(nsteps, pre, &mut sink, &mut vars)
        .map_err(|m| a.error(0, &m))
}

/// Check mode: the files `restart N ...` would write during a run of `nsteps` from the current
/// step, kept in memory (holding the dry run's state) for a later `read_restart`.
fn keep_periodic_restarts(ctx: &mut Ctx, nsteps: i64) {
    use crate::script::system::{KeptFile, KeptSeries};
    let (first, last) = (ctx.sim.step, ctx.sim.step + nsteps);
    let mut bytes: Option<std::rc::Rc<Vec<u8>>> = None;
    for k in 0..ctx.sim.restart_output.len() {
        let Some(out) = ctx.sim.restart_output[k].clone() else {
            continue;
        };
        // multiples of the interval after the first step, up to the last
        let from = first.div_euclid(out.every) + 1;
        let to = last.div_euclid(out.every);
        if to < from {
            continue;
        }
        let contents = bytes
            .get_or_insert_with(|| {
                let partners = ctx.sim.contact_partners();
                std::rc::Rc::new(ctx.sim.to_restart(&partners).to_bytes())
            })
            .clone();
        let writes = to - from + 1;
        if out.files.len() == 1 {
            ctx.sys.keep_series(KeptSeries {
                template: out.files[0].clone(),
                every: out.every,
                after: first,
                upto: last,
                bytes: contents,
            });
        } else {
            // two names in turn: each holds its last write
            for i in (writes - 2).max(0)..writes {
                let name = &out.files[(out.toggle + i as usize) % 2];
                let file = KeptFile {
                    bytes: contents.clone(),
                    step: Some((from + i) * out.every),
                };
                ctx.sys.keep_file(std::path::Path::new(name), file);
            }
        }
        if let Some(o) = ctx.sim.restart_output[k].as_mut() {
            o.toggle = (o.toggle + writes as usize) % 2;
            o.last = Some(to * out.every);
        }
    }
}

/// Parse `model M tangential T ... [option on|off ...]` starting at argument `start` in
/// LIGGGHTS's fixed keyword order; returns the selection and the index after the on/off
/// settings. Without a `tangential` keyword the model is `default_tangential`.
#[allow(clippy::type_complexity)]
fn gran_models(
    a: &Args,
    start: usize,
    default_tangential: &str,
    what: &str,
) -> std::result::Result<
    (
        crate::engine::granular::Selection,
        usize,
        Option<CommandError>,
    ),
    CommandError,
> {
    use crate::engine::granular::Selection;
    let words: Vec<&str> = (start..a.len())
        .map(|i| a.word(i))
        .collect::<std::result::Result<_, _>>()?;
    let (mut sel, used) = Selection::select(&words).map_err(|m| {
        let err = a.error(start, &m);
        match words.first() {
            // LIGGGHTS 2.x: `wall/gran kn kt gamman gammat xmu dampflag wallstyle ...`
            Some(w) if what.contains("wall") && w.parse::<f64>().is_ok() => err.with_help(
                "numeric coefficients here are LIGGGHTS 2.x syntax; LIGGGHTS 3.x writes \
                 `fix ID group wall/gran model hertz tangential history primitive type 1 \
                 zplane 0.0` with the material in `fix property/global`",
            ),
            _ => err,
        }
    })?;
    if !words[..used].contains(&"tangential") {
        sel.tangential = default_tangential.into();
    }
    if sel.normal == "off" {
        return Err(a.error(
            start,
            "Invalid model specified (check for typos and enable at least one model)",
        ));
    }
    // on/off settings follow until the first word that is not a setting name
    let mut end = used;
    while end + 1 < words.len() && matches!(words[end + 1], "on" | "off" | "yes" | "no") {
        end += 2;
    }
    let settings: Vec<&str> = words[used..end]
        .iter()
        .map(|w| match *w {
            "yes" => "on",
            "no" => "off",
            w => w,
        })
        .collect();
    let mut pending = None;
    if let Err(m) = sel.apply_settings(&settings) {
        match m.strip_suffix(" is not supported by regolith") {
            // a valid LIGGGHTS setting regolith cannot run: the rest of the style stands
            Some(setting) => {
                let at = (start + used..start + end)
                    .find(|&i| setting.starts_with(&format!("'{} ", a.word(i).unwrap_or(""))))
                    .unwrap_or(start + used);
                pending = Some(a.unsupported(
                    at,
                    &format!("{what} setting {}", setting.trim_matches('\'')),
                ));
            }
            None => {
                return Err(a.error(start + used, &m).with_help(format!(
                    "{what}: model keywords go in the order model, tangential, cohesion, rolling_friction, surface, then on/off settings"
                )))
            }
        }
    }
    crate::engine::contact::AnyContactModel::new(&sel).map_err(|m| {
        let m = m.trim_end_matches(" is not supported by regolith");
        a.unsupported(start, &format!("{what} {m}"))
    })?;
    Ok((sel, start + end, pending))
}

fn pair_style(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=usize::MAX, "pair_style gran model M tangential T ...")?;
    if a.word(0)? != "gran" {
        return Err(a.unsupported(0, &format!("pair_style {}", a.word(0)?)));
    }
    let (sel, next, pending) = gran_models(a, 1, "no_history", "pair_style gran")?;
    if next < a.len() {
        return Err(a.unsupported(next, &format!("pair_style gran option {}", a.word(next)?)));
    }
    ctx.sim.pair_selection = Some(sel);
    ctx.sim.pair_coeff_set = false;
    if let Some(d) = pending {
        // the style is defined (so `pair_coeff` is not refused), only this setting is reported
        return Err(d);
    }
    // the per-type-pair tables this pair style needs must fit the machine (the style stays
    // defined, so that a dry run does not also report every later pair command)
    let n = ctx.sim.ntypes.max(1) as f64;
    crate::engine::checks::allocation(
        n * n,
        std::mem::size_of::<crate::engine::contact::PairCoeffs>(),
        &format!("pair coefficients ({} atom types)", ctx.sim.ntypes),
    )
    .map_err(|m| a.error(0, &m))
}

fn pair_coeff(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(2..=2, "pair_coeff * *")?;
    if ctx.sim.pair_selection.is_none() {
        return Err(a.error(0, "Pair_coeff command before pair_style is defined"));
    }
    for i in 0..2 {
        let w = a.word(i)?;
        crate::util::numbers::bounds(w, ctx.sim.ntypes.max(1) as i64)
            .map_err(|m| a.error(i, &m))?;
    }
    if a.word(0)? != "*" || a.word(1)? != "*" {
        return Err(a.unsupported(0, "pair_coeff for single type pairs"));
    }
    ctx.sim.pair_coeff_set = true;
    Ok(())
}

fn soft_hard(name: &str, a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, &format!("{name} yes|no"))?;
    let on = a.word_in(0, &["yes", "no"])? == "yes";
    if name == "soft_particles" {
        ctx.sim.soft_hard.0 = on;
    } else {
        ctx.sim.soft_hard.1 = on;
    }
    Ok(())
}

fn compute(a: &Args, ctx: &mut Ctx) -> Result {
    use crate::engine::computes::{Compute, ComputeKind};
    a.count(3..=usize::MAX, "compute ID GROUP STYLE ...")?;
    let (id, group, style) = (a.word(0)?, a.word(1)?, a.word(2)?);
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Compute command before simulation box is defined"));
    }
    let bit = ctx
        .sim
        .group_bit(group)
        .ok_or_else(|| a.error(1, "Could not find compute group ID"))?;
    if ctx.sim.computes.iter().any(|c| c.id == id) {
        return Err(a.error(0, "Reuse of compute ID"));
    }
    let no_keywords = |kind: ComputeKind| {
        if a.len() > 3 {
            Err(a.error(3, format!("Illegal compute {style} command")))
        } else {
            Ok(kind)
        }
    };
    registry::require_style(a, "compute")?;
    let kind = match style {
        "erotate/sphere" => no_keywords(ComputeKind::ErotateSphere)?,
        // LIGGGHTS's `erotate` sums erotate/sphere (and multisphere) of its group
        "erotate" => {
            if ctx.sim.computes.iter().any(|c| c.style == "erotate") {
                // each adds an internal compute `erotate_sphere_`
                return Err(a.error(0, "Reuse of compute ID").with_help(
                    "LIGGGHTS 3.8.0's compute erotate defines an internal compute \
                     erotate_sphere_, so a deck can have only one; use compute erotate/sphere",
                ));
            }
            no_keywords(ComputeKind::ErotateSphere)?
        }
        "pe" => super::computes_extra::pe(a, ctx)?,
        "ke" => no_keywords(ComputeKind::Ke)?,
        "temp" => no_keywords(ComputeKind::Temp)?,
        "ke/atom" => no_keywords(ComputeKind::KeAtom)?,
        "contact/atom" => {
            let mut skin = 0.0;
            if a.len() > 3 {
                if a.len() != 5 {
                    return Err(a.error(3, "Illegal compute contact/atom command"));
                }
                if a.word(3)? != "skin" {
                    return Err(a.error(
                        3,
                        "Illegal compute contact/atom command, expecting keyword 'skin'",
                    ));
                }
                skin = a.real(4)?;
            }
            ComputeKind::ContactAtom { skin }
        }
        "com" => no_keywords(ComputeKind::Com)?,
        "stress/atom" => {
            let (mut ke, mut pair) = (a.len() == 3, a.len() == 3);
            for i in 3..a.len() {
                match a.word(i)? {
                    "ke" => ke = true,
                    "pair" | "virial" => pair = true,
                    // no bonds, angles, kspace or virial-contributing fixes exist in a
                    // granular run: these parts are zero
                    "bond" | "angle" | "dihedral" | "improper" | "kspace" | "fix" => {}
                    _ => return Err(a.error(i, "Illegal compute stress/atom command")),
                }
            }
            ComputeKind::StressAtom { ke, pair }
        }
        "property/atom" => {
            if a.len() < 4 {
                return Err(a.error(2, "Illegal compute property/atom command"));
            }
            let mut cols = Vec::new();
            for i in 3..a.len() {
                let w = a.word(i)?;
                let col = match crate::io::dump::Column::parse(w) {
                    Ok(crate::io::dump::Column::Reference(_)) | Err(_) => {
                        return Err(a.unsupported(i, &format!("compute property/atom {w}")))
                    }
                    Ok(c) => c,
                };
                cols.push(col);
            }
            ComputeKind::PropertyAtom(cols)
        }
        "reduce" => compute_reduce(a, ctx)?,
        "pair/gran/local" => {
            use crate::engine::computes::LocalField;
            if ctx.sim.step > 0 && !ctx.sim.restart_in_progress {
                return Err(a.error(
                    2,
                    "Compute pair/gran/local: Need to define this compute before first run",
                ));
            }
            let mut fields = Vec::new();
            for i in 3..a.len() {
                let w = a.word(i)?;
                match LocalField::parse(w) {
                    Some(LocalField::HeatFlux) => {
                        return Err(a.unsupported(i, "compute pair/gran/local heatFlux"))
                    }
                    Some(f) => fields.push(f),
                    None if w == "verbose" => {}
                    None if matches!(w, "heatFlux" | "ms_id") => {
                        return Err(a.unsupported(i, &format!("compute pair/gran/local {w}")))
                    }
                    None => {
                        return Err(
                            a.error(i, "Compute pair/gran/local: illegal/unrecognized keyword")
                        )
                    }
                }
            }
            if a.len() == 3 {
                fields = LocalField::defaults();
            }
            if ctx
                .sim
                .computes
                .iter()
                .any(|c| matches!(c.kind, ComputeKind::PairGranLocal(_)))
            {
                return Err(a.error(2, "Pair gran allows only one compute of type pair/local"));
            }
            fields.sort();
            fields.dedup();
            ComputeKind::PairGranLocal(fields)
        }
        "wall/gran/local" => crate::commands::fix_state::wall_gran_local(a, ctx, id)?,
        other => return Err(a.unsupported(2, &format!("compute {other}"))),
    };
    ctx.sim.computes.push(Compute {
        id: id.into(),
        style: style.into(),
        group: bit,
        kind,
    });
    Ok(())
}

/// `compute ID GROUP reduce MODE input1 input2 ...` (inputs: atom attributes or per-atom
/// computes `c_ID`, `c_ID[N]`).
fn compute_reduce(
    a: &Args,
    ctx: &Ctx,
) -> std::result::Result<crate::engine::computes::ComputeKind, CommandError> {
    use crate::engine::computes::{column_of, ComputeKind, Input, ReduceMode};
    if a.len() < 5 {
        return Err(a.error(2, "Illegal compute reduce command"));
    }
    let mode = match a.word(3)? {
        "sum" => ReduceMode::Sum,
        "min" => ReduceMode::Min,
        "max" => ReduceMode::Max,
        "ave" => ReduceMode::Ave,
        "region" => return Err(a.unsupported(3, "compute reduce/region")),
        _ => return Err(a.error(3, "Illegal compute reduce command")),
    };
    let mut inputs = Vec::new();
    for i in 4..a.len() {
        let w = a.word(i)?;
        if w == "replace" {
            return Err(a.unsupported(i, "compute reduce replace"));
        }
        if let Some(body) = w.strip_prefix("c_") {
            let (id, index) = match body.split_once('[') {
                Some((id, rest)) => {
                    let k = rest
                        .strip_suffix(']')
                        .and_then(|k| k.parse::<usize>().ok())
                        .ok_or_else(|| a.error(i, "Illegal compute reduce command"))?;
                    (id, Some(k))
                }
                None => (body, None),
            };
            let c = ctx
                .sim
                .computes
                .iter()
                .find(|c| c.id == id)
                .ok_or_else(|| a.error(i, "Compute ID for compute reduce does not exist"))?;
            column_of(c, index).map_err(|m| a.error(i, &m))?;
            inputs.push(Input::Compute(id.to_string(), index));
            continue;
        }
        if let Some(name) = w.strip_prefix("v_") {
            match ctx.vars.get(name).map(|v| v.style) {
                Some(crate::script::variables::Style::Atom) => {}
                Some(_) => {
                    return Err(a.error(i, "Compute reduce variable is not atom-style variable"))
                }
                None => return Err(a.error(i, "Variable name for compute reduce does not exist")),
            }
            inputs.push(Input::Variable(name.to_string()));
            continue;
        }
        if w.starts_with("f_") {
            return Err(a.unsupported(i, "compute reduce of fixes"));
        }
        match crate::io::dump::Column::parse(w) {
            Ok(crate::io::dump::Column::Reference(_)) | Err(_) => {
                return Err(a.error(i, "Illegal compute reduce command"))
            }
            Ok(c) => inputs.push(Input::Atom(c)),
        }
    }
    Ok(ComputeKind::Reduce { mode, inputs })
}

fn uncompute(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "uncompute ID")?;
    remove_by_id(
        &mut ctx.sim.computes,
        |c| &c.id,
        a,
        "Could not find uncompute ID",
    )
}

/// Remove the item whose ID is the command's first argument, or fail with `missing`.
fn remove_by_id<T>(
    items: &mut Vec<T>,
    id_of: impl Fn(&T) -> &String,
    a: &Args,
    missing: &str,
) -> Result {
    let id = a.word(0)?;
    let k = items
        .iter()
        .position(|t| id_of(t) == id)
        .ok_or_else(|| a.error(0, missing))?;
    items.remove(k);
    Ok(())
}

/// A `v_name` argument of a fix: equal- or atom-style, its style read as LIGGGHTS reads it.
fn variable_value(
    a: &Args,
    ctx: &Ctx,
    at: usize,
    name: &str,
    style: &str,
) -> std::result::Result<crate::engine::fixes::ForceValue, CommandError> {
    use crate::engine::fixes::ForceValue;
    use crate::script::variables::Style;
    match ctx.vars.get(name).map(|v| v.style) {
        Some(Style::Equal) => Ok(ForceValue::Equal(name.into())),
        Some(Style::Atom) => Ok(ForceValue::Atom(name.into())),
        Some(_) => Err(a.error(
            at,
            format!("Variable {name} for fix {style} is invalid style"),
        )),
        None => Err(a.error(at, format!("Variable name for fix {style} does not exist"))),
    }
}

/// `fix ID GROUP ave/time Nevery Nrepeat Nfreq value ... [keyword value ...]` (scalar mode).
fn ave_time(a: &Args, ctx: &mut Ctx, id: &str) -> std::result::Result<FixKind, CommandError> {
    use crate::engine::fixes::{AveInput, AveMode, AveTime};
    a.count(
        7..=usize::MAX,
        "fix ID GROUP ave/time Nevery Nrepeat Nfreq value ...",
    )?;
    let (every, repeat, freq) = (a.int(3)?, a.int(4)?, a.int(5)?);
    if every <= 0 || repeat <= 0 || freq <= 0 || freq % every != 0 || (repeat - 1) * every >= freq {
        return Err(a.error(3, "Illegal fix ave/time command"));
    }
    let mut inputs = Vec::new();
    let mut names = Vec::new();
    let mut i = 6;
    while i < a.len() {
        let w = a.word(i)?;
        let Some(kind) = ["c_", "f_", "v_"].into_iter().find(|p| w.starts_with(p)) else {
            break;
        };
        let body = &w[2..];
        let (name, index) = match body.split_once('[') {
            Some((n, rest)) => {
                let k: usize = rest
                    .strip_suffix(']')
                    .and_then(|k| k.parse().ok())
                    .filter(|&k| k > 0)
                    .ok_or_else(|| a.error(i, "Illegal fix ave/time command"))?;
                (n, Some(k))
            }
            None => (body, None),
        };
        let input = match kind {
            "c_" => {
                if !ctx.sim.computes.iter().any(|c| c.id == name) {
                    return Err(a.error(i, "Compute ID for fix ave/time does not exist"));
                }
                AveInput::Compute(name.into(), index)
            }
            "f_" => {
                let Some(f) = ctx.sim.fixes.iter().find(|f| f.id == name) else {
                    return Err(a.error(i, "Fix ID for fix ave/time does not exist"));
                };
                let global_freq = match &f.kind {
                    FixKind::CheckTimestep(c) => c.every,
                    FixKind::AveTime(at) => at.freq,
                    FixKind::Mesh(m) if m.stress.is_some() => 1,
                    _ => return Err(a.error(i, "Fix ave/time fix does not calculate a vector")),
                };
                if every % global_freq != 0 {
                    return Err(a.error(i, "Fix for fix ave/time not computed at compatible time"));
                }
                AveInput::Fix(name.into(), index)
            }
            _ => {
                match ctx.vars.get(name).map(|v| v.style) {
                    None => return Err(a.error(i, "Variable name for fix ave/time does not exist")),
                    Some(crate::script::variables::Style::Atom) => {
                        return Err(a.error(i, "Fix ave/time variable is not equal-style variable"))
                    }
                    _ => {}
                }
                if index.is_some() {
                    return Err(a.error(i, "Illegal fix ave/time command"));
                }
                AveInput::Variable(name.into())
            }
        };
        inputs.push(input);
        names.push(w.to_string());
        i += 1;
    }
    if inputs.is_empty() {
        return Err(a.error(6, "Illegal fix ave/time command"));
    }
    let mut off = vec![false; inputs.len()];
    let (mut mode, mut start, mut file) = (AveMode::One, 0, None);
    let mut titles: [Option<String>; 2] = [None, None];
    while i < a.len() {
        match a.word(i)? {
            "file" => {
                file = Some(a.word(i + 1)?.to_string());
                i += 2;
            }
            "ave" => {
                mode = match a.word_in(i + 1, &["one", "running", "window"])? {
                    "one" => AveMode::One,
                    "running" => AveMode::Running,
                    _ => {
                        let m = a.int32(i + 2)?;
                        if m <= 0 {
                            return Err(a.error(i + 2, "Illegal fix ave/time command"));
                        }
                        // LIGGGHTS keeps the last M values of every input
                        let row = 24 + 8 * inputs.len();
                        crate::engine::checks::allocation(m as f64, row, "ave/time:vector_list")
                            .map_err(|e| a.error(i + 2, &e))?;
                        i += 1;
                        AveMode::Window(m as usize)
                    }
                };
                i += 2;
            }
            "start" => {
                start = a.int(i + 1)?;
                i += 2;
            }
            "off" => {
                let k = a.int(i + 1)?;
                if k < 1 || k as usize > off.len() {
                    return Err(a.error(i + 1, "Invalid fix ave/time off column"));
                }
                off[k as usize - 1] = true;
                i += 2;
            }
            "mode" => {
                if a.word_in(i + 1, &["scalar", "vector"])? == "vector" {
                    return Err(a.unsupported(i + 1, "fix ave/time mode vector"));
                }
                i += 2;
            }
            "title1" | "title2" => {
                let k = (a.word(i)? == "title2") as usize;
                titles[k] = Some(a.word(i + 1)?.to_string());
                i += 2;
            }
            "title3" => {
                a.word(i + 1)?; // only used by mode vector
                i += 2;
            }
            "overwrite" => return Err(a.unsupported(i, "fix ave/time overwrite")),
            _ => {
                return Err(a.keyword_error(
                    i,
                    &[
                        "file", "ave", "start", "off", "mode", "title1", "title2", "title3",
                    ],
                ))
            }
        }
    }
    let schedule = crate::engine::fixes::AveSchedule {
        every,
        repeat,
        freq,
    };
    let mut fix = AveTime::new(schedule, inputs, off, mode, start, ctx.sim.step);
    if let (Some(name), Mode::Run) = (file, ctx.sys.mode) {
        use std::io::Write;
        let f = std::fs::File::create(&name)
            .map_err(|_| a.file_error(0, format!("Cannot open fix ave/time file {name}")))?;
        let mut f = std::io::BufWriter::new(f);
        let head = format!(
            "{}\n{}\n",
            titles[0]
                .clone()
                .unwrap_or_else(|| format!("# Time-averaged data for fix {id}")),
            titles[1]
                .clone()
                .unwrap_or_else(|| format!("# TimeStep {}", names.join(" ")))
        );
        f.write_all(head.as_bytes())
            .and_then(|_| f.flush())
            .map_err(|e| a.error(0, format!("fix ave/time: {e}")))?;
        fix.file = Some(f);
    }
    Ok(FixKind::AveTime(fix))
}

/// `fix ID GROUP wall/gran model ... mesh n_meshes N meshes M1 .. MN [model settings]`.
fn mesh_wall(
    a: &Args,
    ctx: &Ctx,
    group: &str,
    mut selection: crate::engine::granular::Selection,
    at: usize,
) -> std::result::Result<FixKind, CommandError> {
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
        if !ctx
            .sim
            .fixes
            .iter()
            .any(|f| f.id == id && matches!(f.kind, FixKind::Mesh(_)))
        {
            return Err(a.error(
                at + 4 + k,
                format!("Fix wall/gran: failed to find fix mesh/surface with ID {id}"),
            ));
        }
        meshes.push(id.to_string());
    }
    if ctx
        .sim
        .fixes
        .iter()
        .any(|f| matches!(f.kind, FixKind::MeshWall(_)))
    {
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
    }))
}

/// `fix ID GROUP mesh/surface[/planar] file F type T [scale f] [move x y z]
/// [rotate axis x y z angle deg] [curvature deg] [curvature_tolerant yes|no]
/// [precision p] [heal auto_remove_duplicates|no] [verbose yes|no]`.
fn mesh_surface(
    a: &Args,
    ctx: &mut Ctx,
    style: &str,
) -> std::result::Result<FixKind, CommandError> {
    use crate::io::stl::MeshOp;
    a.count(
        5..=usize::MAX,
        &format!("fix ID GROUP {style} file FILE type T ..."),
    )?;
    match a.word(3)? {
        "file" => {}
        "fix" => return Err(a.unsupported(3, "fix mesh/surface fix (meshes from another fix)")),
        _ => return Err(a.keyword_error(3, &["file", "fix"])),
    }
    let file = a.word(4)?.to_string();
    let (mut wall_type, mut ops) = (None, Vec::new());
    let mut settings = crate::engine::mesh::MeshSettings::default();
    let (mut heal, mut surface_vel) = (false, None);
    // the stress module's keywords (after all mesh/surface keywords, as LIGGGHTS requires)
    let (mut stress_on, mut wear_on, mut reference) = (true, false, [0.0; 3]);
    let mut module_from = None;
    let module_keyword = |w: &str| matches!(w, "stress" | "wear" | "reference_point");
    let mut i = 5;
    while i < a.len() {
        let w = a.word(i)?;
        if style == "mesh/surface/stress" && module_keyword(w) {
            module_from.get_or_insert(i);
            match w {
                "stress" => stress_on = a.word_in(i + 1, &["on", "off"])? == "on",
                "wear" => wear_on = a.word_in(i + 1, &["finnie", "off"])? == "finnie",
                _ => {
                    reference = [a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?];
                    i += 2;
                }
            }
            i += 2;
            continue;
        }
        if let Some(at) = module_from {
            return Err(a.error(
                i,
                format!("Fix mesh/surface/stress: unknown keyword or wrong keyword order ('{w}' after the stress keyword at word {at})"),
            ));
        }
        match w {
            "type" => {
                let t = a.int(i + 1)?;
                if t < 1 || t > ctx.sim.ntypes as i64 {
                    return Err(a.error(i + 1, "Fix mesh: type is out of range"));
                }
                wall_type = Some(t as usize);
                i += 2;
            }
            "scale" => {
                ops.push(MeshOp::Scale(a.real(i + 1)?));
                i += 2;
            }
            "move" => {
                ops.push(MeshOp::Move([
                    a.real(i + 1)?,
                    a.real(i + 2)?,
                    a.real(i + 3)?,
                ]));
                i += 4;
            }
            "rotate" => {
                if a.word(i + 1)? != "axis" || a.word(i + 5)? != "angle" {
                    return Err(a
                        .error(i, "Illegal fix mesh/surface command")
                        .with_help("expected: rotate axis AX AY AZ angle DEGREES"));
                }
                ops.push(MeshOp::Rotate {
                    axis: [a.real(i + 2)?, a.real(i + 3)?, a.real(i + 4)?],
                    degrees: a.real(i + 6)?,
                });
                i += 7;
            }
            "curvature" => {
                let v = a.real(i + 1)?;
                if v <= 0.0 || v > 60.0 {
                    return Err(a.error(i + 1, "Fix mesh: 0° < curvature < 60° required"));
                }
                settings.curvature = (v * std::f64::consts::PI / 180.).cos();
                i += 2;
            }
            "precision" => {
                let v = a.real(i + 1)?;
                if v <= 0.0 || v > 0.001 {
                    return Err(a.error(i + 1, "Fix mesh: 0 < precision < 0.001 required"));
                }
                settings.precision = v;
                i += 2;
            }
            "curvature_tolerant" => {
                settings.curvature_tolerant = a.word_in(i + 1, &["yes", "no"])? == "yes";
                i += 2;
            }
            // only LIGGGHTS's extra screen output
            "verbose" => {
                a.word_in(i + 1, &["yes", "no"])?;
                i += 2;
            }
            "heal" => {
                heal = a.word_in(i + 1, &["auto_remove_duplicates", "no"])? != "no";
                i += 2;
            }
            "surface_vel" => {
                surface_vel = Some([a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?]);
                i += 4;
            }
            w @ ("temperature"
            | "mass_temperature"
            | "surface_ang_vel"
            | "region"
            | "extrude_planar"
            | "element_exclusion_list"
            | "min_feature_length") => {
                return Err(a.unsupported(i, &format!("fix mesh/surface {w}")))
            }
            _ => {
                return Err(a.keyword_error(
                    i,
                    &[
                        "type",
                        "scale",
                        "move",
                        "rotate",
                        "curvature",
                        "curvature_tolerant",
                        "precision",
                        "heal",
                        "verbose",
                        "temperature",
                        "surface_vel",
                    ],
                ))
            }
        }
    }
    let wall_type = wall_type.ok_or_else(|| a.error(2, "Fix mesh: must define type"))?;
    let path = ctx.sys.resolve(&file).to_string_lossy().into_owned();
    let stored = ctx
        .sim
        .held_fix_state(a.word(0)?, style)
        .map(<[u8]>::to_vec);
    let mut restored = None;
    let mut triangles = if let Some(bytes) = stored {
        // LIGGGHTS takes the nodes from the restart file (scale/move/rotate act on an empty
        // mesh); the file must still open
        if std::fs::File::open(&path).is_err() {
            return Err(a.file_error(
                4,
                format!("Cannot open mesh file {file}. FYI: This file is required, but data will be taken from restart file"),
            ));
        }
        ctx.say(&format!("INFO: mesh file ({file}) is required, but data will be taken from restart file (./src/fix_mesh.cpp:417)\n"));
        // the stress module adds each triangle's wear (when on) and the reference point
        let stress = style == "mesh/surface/stress";
        let (element, global) = match (stress, wear_on) {
            (true, true) => (1, 3),
            (true, false) => (0, 3),
            _ => (0, 0),
        };
        let (t, extras) = crate::engine::restart_fixes::mesh_from_state(&bytes, element, global)
            .map_err(|m| a.error(2, &m))?;
        restored = Some(extras);
        t
    } else {
        ctx.say(&format!(
            "\nReading STL file '{file}' (mesh processing step 1/3) \n"
        ));
        let mut t = crate::io::stl::read(&path).map_err(|m| a.error(4, &m))?;
        crate::io::stl::transform(&mut t, &ops);
        t
    };
    if heal && restored.is_none() {
        // `heal auto_remove_duplicates`: a triangle with the nodes of an earlier one goes
        let p = settings.precision;
        let same = |x: [f64; 3], y: [f64; 3]| (0..3).all(|k| (x[k] - y[k]).abs() < p);
        let mut kept: Vec<crate::io::stl::Triangle> = Vec::with_capacity(triangles.len());
        for t in triangles {
            let dup = kept
                .iter()
                .any(|u| t.iter().all(|n| u.iter().any(|m| same(*n, *m))));
            if !dup {
                kept.push(t);
            }
        }
        triangles = kept;
    }
    let d = &ctx.sim.domain;
    let size = (0..3).map(|k| d.length(k)).fold(0.0, f64::max);
    for w in crate::io::stl::check(&triangles, &file, Some(size)).map_err(|m| a.error(4, &m))? {
        ctx.say(&format!("WARNING: {w}\n"));
    }
    if style == "mesh/surface/planar" {
        let n0 = crate::io::stl::normal(&triangles[0]);
        let p0 = triangles[0][0];
        let off = |v: [f64; 3]| (0..3).map(|k| (v[k] - p0[k]) * n0[k]).sum::<f64>().abs();
        let scale = size.max(f64::MIN_POSITIVE);
        if triangles.iter().flatten().any(|v| off(*v) > 1e-8 * scale) {
            return Err(a.error(4, "Fix mesh/surface/planar: the mesh is not planar"));
        }
    }
    let mut fix = crate::engine::fixes::MeshFix {
        file,
        wall_type,
        mesh: crate::engine::mesh::TriMesh::new(&triangles, settings),
        node_v: None,
        surface_vel,
        planar: style == "mesh/surface/planar",
        nodes_at_refresh: Vec::new(),
        stress: None,
    };
    if style == "mesh/surface/stress" {
        let mut st = crate::engine::mesh_stress::MeshStress::new(
            fix.mesh.len(),
            stress_on,
            wear_on,
            reference,
        );
        if let Some(extras) = restored {
            if wear_on {
                st.wear = extras.element.iter().map(|e| e[0]).collect();
            }
            st.reference = [extras.global[0], extras.global[1], extras.global[2]];
        }
        fix.stress = Some(st);
    }
    fix.set_surface_velocity();
    Ok(FixKind::Mesh(Box::new(fix)))
}

/// `fix ID group move/mesh mesh MESH STYLE args...` (linear, wiggle, rotate, riggle, viblin,
/// vibrot), with LIGGGHTS's messages.
fn move_mesh(a: &Args, ctx: &mut Ctx) -> std::result::Result<FixKind, CommandError> {
    use crate::engine::mesh_motion::{unit_axis, Motion, MoveMesh};
    if a.len() < 6 {
        return Err(a.error(
            2,
            "Illegal fix move/mesh command, you need to specify a mesh",
        ));
    }
    if a.word(3)? != "mesh" {
        return Err(a.error(3, "Illegal fix move/mesh command, expecting keyword 'mesh'"));
    }
    let mesh = a.word(4)?.to_string();
    let Some(m) = ctx.sim.fixes.iter().find_map(|f| match &f.kind {
        FixKind::Mesh(m) if f.id == mesh => Some(m),
        _ => None,
    }) else {
        return Err(a.error(4, "Illegal fix move/mesh command, illegal mesh ID provided"));
    };
    if m.surface_vel.is_some() {
        return Err(a.error(4, "Illegal fix move/mesh command, cannot apply move to a mesh using keywords 'velocity' or 'angular_velocity'"));
    }
    let style = a.word(5)?;
    // LIGGGHTS counts the style word as argument 0 of the motion's own list
    let narg = a.len() - 5;
    let at = |k: usize| 5 + k;
    let need = |n: usize| -> std::result::Result<(), CommandError> {
        if narg < n {
            Err(a.error(5, format!("Not enough arguments for movement type {style}")))
        } else {
            Ok(())
        }
    };
    let keyword = |k: usize, w: &str| -> std::result::Result<(), CommandError> {
        if a.word(at(k))? != w {
            Err(a.error(at(k), format!("Expected keyword '{w}'")))
        } else {
            Ok(())
        }
    };
    let vec3 = |k: usize| -> std::result::Result<[f64; 3], CommandError> {
        Ok([a.real(at(k))?, a.real(at(k + 1))?, a.real(at(k + 2))?])
    };
    let mut warn = |n: usize| {
        if narg > n {
            ctx.say(&format!("WARNING: Movement type {style} requires only {n} arguments, excess arguments will be ignored\n"));
        }
    };
    let two_pi = 2.0 * std::f64::consts::PI;
    // (words read, per mode: amplitude, phase, angular frequency)
    type Modes = (usize, Vec<(f64, f64, f64)>);
    let modes = |order_at: usize| -> std::result::Result<Modes, CommandError> {
        keyword(order_at, "order")?;
        let n = a.int(at(order_at + 1))?;
        if !(1..=30).contains(&n) {
            return Err(a.error(
                at(order_at + 1),
                "order can be at most 30 and must be greater 0",
            ));
        }
        let n = n as usize;
        // LIGGGHTS checks for two lists only and reads the periods after them
        if narg < order_at + 5 + 2 * n {
            return Err(a.error(5, format!("Not enough arguments for movement type {style}")));
        }
        if narg < order_at + 5 + 3 * n {
            return Err(a.error(
                5,
                format!("Not enough arguments for movement type {style} (LIGGGHTS reads the periods past the end of the command and crashes)"),
            ));
        }
        keyword(order_at + 2, "amplitude")?;
        keyword(order_at + 3 + n, "phase")?;
        keyword(order_at + 4 + 2 * n, "period")?;
        let mut out = Vec::with_capacity(n);
        for j in 0..n {
            let c = a.real(at(order_at + 3 + j))?;
            let phase = a.real(at(order_at + 4 + n + j))?;
            let period = a.real(at(order_at + 5 + 2 * n + j))?;
            out.push((c, phase, two_pi / period));
        }
        Ok((n, out))
    };
    let (motion, reference) = match style {
        "linear" => {
            need(4)?;
            (Motion::Linear(vec3(1)?), None)
        }
        "wiggle" => {
            need(7)?;
            keyword(1, "amplitude")?;
            keyword(5, "period")?;
            let m = Motion::Wiggle {
                amplitude: vec3(2)?,
                omega: two_pi / a.real(at(6))?,
            };
            (m, None)
        }
        "rotate" => {
            need(11)?;
            keyword(1, "origin")?;
            keyword(5, "axis")?;
            keyword(9, "period")?;
            let m = Motion::Rotate {
                axis: unit_axis(vec3(6)?),
                omega: two_pi / a.real(at(10))?,
            };
            (m, Some(vec3(2)?))
        }
        "riggle" => {
            need(13)?;
            keyword(1, "origin")?;
            keyword(5, "axis")?;
            keyword(9, "period")?;
            keyword(11, "amplitude")?;
            let m = Motion::Riggle {
                origin: vec3(2)?,
                axis: unit_axis(vec3(6)?),
                omega: two_pi / a.real(at(10))?,
                alpha: (std::f64::consts::PI * a.real(at(12))?) / 180.0,
            };
            (m, None)
        }
        "viblin" => {
            need(7)?;
            keyword(1, "axis")?;
            let axis = unit_axis(vec3(2)?);
            let (_, modes) = modes(5)?;
            (Motion::Viblin { axis, modes }, None)
        }
        "vibrot" => {
            need(11)?;
            keyword(1, "origin")?;
            keyword(5, "axis")?;
            let origin = vec3(2)?;
            let axis = unit_axis(vec3(6)?);
            let (_, modes) = modes(9)?;
            (
                Motion::Vibrot {
                    origin,
                    axis,
                    modes,
                },
                None,
            )
        }
        "linear/variable" | "rotate/variable" => {
            return Err(a.unsupported(5, &format!("fix move/mesh {style}")))
        }
        _ => {
            return Err(a
                .keyword_error(
                    5,
                    &["linear", "wiggle", "rotate", "riggle", "viblin", "vibrot"],
                )
                .with_help("LIGGGHTS: Mesh movement type not available"))
        }
    };
    // LIGGGHTS's excess-argument warnings (viblin's names the wiggle style)
    match &motion {
        Motion::Linear(_) => warn(4),
        Motion::Wiggle { .. } => warn(7),
        Motion::Rotate { .. } => warn(11),
        Motion::Riggle { .. } => warn(13),
        Motion::Viblin { modes, .. } => {
            let n = modes.len();
            if narg > 10 + 2 * n {
                ctx.say("WARNING: Movement type wiggle requires only (10 + 2*$order) arguments, excess arguments will be ignored (./src/mesh_mover_linear.cpp:303)\n");
            }
        }
        Motion::Vibrot { modes, .. } => {
            let n = modes.len();
            if narg > 14 + 2 * n {
                ctx.say("WARNING: Movement type vibrot requires only (14 + 2*$order) arguments, excess arguments will be ignored (./src/mesh_mover_rotation.cpp:347)\n");
            }
        }
    }
    Ok(FixKind::MoveMesh(MoveMesh {
        mesh,
        motion,
        time: 0.0,
        reference,
    }))
}

fn seed_arg(a: &Args, ctx: &Ctx, i: usize) -> std::result::Result<i32, CommandError> {
    let seed = a.int(i)?;
    if !ctx.sim.seed_tolerant {
        crate::util::random::check_seed(seed).map_err(|m| a.error(i, &m))?;
    }
    if seed <= 0 || seed > i32::MAX as i64 {
        return Err(a.error(i, "Invalid seed for Park random # generator"));
    }
    Ok(seed as i32)
}

/// `fix ID GROUP particletemplate/sphere SEED atom_type T density constant D radius constant R`.
fn particle_template(
    a: &Args,
    ctx: &mut Ctx,
    id: &str,
) -> std::result::Result<FixKind, CommandError> {
    a.count(4..=usize::MAX, "fix ID GROUP particletemplate/sphere SEED atom_type T density constant D radius constant R")?;
    let seed = seed_arg(a, ctx, 3)?;
    let (mut atom_type, mut density, mut radius) = (1u32, None, None);
    let mut volume_limit = 1e-12;
    let mut i = 4;
    while i < a.len() {
        match a.word(i)? {
            "atom_type" => {
                let t = a.int(i + 1)?;
                if t < 1 || t > ctx.sim.ntypes as i64 {
                    return Err(
                        a.error(i + 1, "Fix particletemplate/sphere: atom type out of range")
                    );
                }
                atom_type = t as u32;
                i += 2;
            }
            w @ ("density" | "radius") => {
                match a.word(i + 1)? {
                    "constant" => {}
                    "gaussian" | "lognormal" | "uniform" => {
                        // documented, but LIGGGHTS 3.8.0 rejects every random style
                        return Err(a
                            .error(
                                i + 1,
                                format!(
                                    "Fix particletemplate/sphere (id {id}): invalid {w} random style"
                                ),
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
                        format!("Fix particletemplate/sphere: {w} must be > 0"),
                    ));
                }
                if w == "density" {
                    density = Some(v);
                } else {
                    radius = Some(v);
                }
                i += 3;
            }
            "volume_limit" => {
                volume_limit = a.real(i + 1)?;
                if volume_limit <= 0.0 {
                    return Err(a.error(
                        i + 1,
                        "Fix particletemplate/sphere: volume_limit > 0 required",
                    ));
                }
                i += 2;
            }
            "relative" => {
                if a.word_in(i + 1, &["yes", "no"])? == "yes" {
                    return Err(a.unsupported(i, "fix particletemplate/sphere relative yes"));
                }
                i += 2;
            }
            _ => {
                return Err(a.keyword_error(
                    i,
                    &["atom_type", "density", "radius", "volume_limit", "relative"],
                ))
            }
        }
    }
    let density = density
        .ok_or_else(|| a.error(2, "Fix particletemplate/sphere: have to define 'density'"))?;
    let radius =
        radius.ok_or_else(|| a.error(2, "Fix particletemplate/sphere: have to define 'radius'"))?;
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
    let mut template = crate::engine::insert::Template::new(id, atom_type, radius, density);
    template.rng_state = (seed, seed);
    if template.volume < volume_limit {
        return Err(a.error(2, "Fix particletemplate/sphere: Volume expectancy too small. Change 'volume_limit' or particle size in the simulation"));
    }
    Ok(FixKind::Template(template))
}

/// `fix ID GROUP particledistribution/discrete SEED N T1 W1 ... TN WN`.
fn distribution(
    a: &Args,
    ctx: &mut Ctx,
    style: &str,
) -> std::result::Result<FixKind, CommandError> {
    a.count(
        7..=usize::MAX,
        &format!("fix ID GROUP {style} SEED N TEMPLATE1 WEIGHT1 ..."),
    )?;
    let seed = seed_arg(a, ctx, 3)?;
    let n = a.int(4)?;
    if n < 1 || a.len() != 5 + 2 * n as usize {
        return Err(a.error(
            4,
            format!("Illegal fix {style} command: expected N template/weight pairs"),
        ));
    }
    let mut templates = Vec::new();
    let mut weights = Vec::new();
    for k in 0..n as usize {
        let tid = a.word(5 + 2 * k)?;
        let t = ctx
            .sim
            .fixes
            .iter()
            .find_map(|f| match &f.kind {
                FixKind::Template(t) if f.id == tid => Some(t.clone()),
                _ => None,
            })
            .ok_or_else(|| {
                a.error(
                    5 + 2 * k,
                    format!("Fix {style}: could not find fix particletemplate {tid}"),
                )
            })?;
        let w = a.real(6 + 2 * k)?;
        // LIGGGHTS refuses only negative weights (a zero weight never inserts its template)
        if w < 0.0 {
            return Err(a.error(
                6 + 2 * k,
                format!("Fix {style}: invalid weight (must be >= 0)"),
            ));
        }
        templates.push(t);
        weights.push(w);
    }
    if weights.iter().all(|&w| w == 0.0) {
        return Err(a.error(
            6,
            format!("Fix {style}: all weights are 0, nothing to insert"),
        ));
    }
    let number_based = style.ends_with("numberbased");
    crate::engine::insert::Distribution::new(seed, templates, &weights, number_based)
        .map(FixKind::Distribution)
        .map_err(|m| a.error(3, &m))
}

/// `fix ID GROUP insert/pack seed S distributiontemplate D [keywords]`.
fn insert_pack(
    a: &Args,
    ctx: &mut Ctx,
    id: &str,
    style: &str,
) -> std::result::Result<FixKind, CommandError> {
    let rate_style = style == "insert/rate/region";
    let (mut nparticles, mut particlerate): (Option<i64>, Option<f64>) = (None, None);
    use crate::engine::insert::{InsertPack, Target, Velocity};
    a.count(
        5..=usize::MAX,
        "fix ID GROUP insert/pack seed S distributiontemplate D region R ...",
    )?;
    let mut seed = None;
    let mut dist = None;
    let (mut region, mut target, mut every) = (None, None, None);
    let mut start = None;
    let (mut overlap, mut all_in, mut maxattempt, mut ntry_mc, mut check_dist, mut verbose) =
        (true, false, 50i64, 100000i64, true, true);
    let mut velocity = Velocity::Constant([0.0; 3]);
    let mut omega = [0.0; 3];
    let mut i = 3;
    let yes = |a: &Args, k: usize| a.word_in(k, &["yes", "no"]).map(|w| w == "yes");
    while i < a.len() {
        match a.word(i)? {
            "seed" => {
                seed = Some(seed_arg(a, ctx, i + 1)?);
                i += 2;
            }
            "distributiontemplate" => {
                let d = a.word(i + 1)?;
                if !ctx
                    .sim
                    .fixes
                    .iter()
                    .any(|f| f.id == d && matches!(f.kind, FixKind::Distribution(_)))
                {
                    return Err(a.error(i + 1, "Fix insert: distributiontemplate must be a fix particledistribution/discrete"));
                }
                dist = Some(d.to_string());
                i += 2;
            }
            "region" => {
                let r = a.word(i + 1)?;
                let k =
                    ctx.sim.regions.find(r).ok_or_else(|| {
                        a.error(i + 1, "Fix insert/pack: region ID does not exist")
                    })?;
                let reg = &ctx.sim.regions.list[k];
                let simple = |k: usize| {
                    let r = &ctx.sim.regions.list[k];
                    r.radius_variable.is_none()
                        && matches!(
                            r.shape,
                            crate::engine::region::Shape::Block { .. }
                                | crate::engine::region::Shape::Cylinder { .. }
                        )
                };
                let ok = reg.interior
                    && match &reg.shape {
                        crate::engine::region::Shape::Intersect(m) => m.iter().all(|&k| simple(k)),
                        _ => simple(k),
                    };
                if !ok {
                    return Err(a.unsupported(
                        i + 1,
                        "fix insert/pack into regions other than blocks, cylinders and their intersections (side in)",
                    ));
                }
                region = Some((k, r.to_string()));
                i += 2;
            }
            "particles_in_region" => {
                let n = a.int32(i + 1)?;
                if n <= 0 {
                    return Err(a.error(i + 1, "Fix insert/pack: particles_in_region must be > 0"));
                }
                target = Some(Target::Count(n));
                i += 2;
            }
            "volumefraction_region" => {
                let f = a.real(i + 1)?;
                if !(0.0..=1.0).contains(&f) {
                    return Err(a.error(
                        i + 1,
                        "Fix insert/pack: volumefraction_region must be between 0 and 1",
                    ));
                }
                target = Some(Target::VolumeFraction(f));
                i += 2;
            }
            "mass_in_region" => {
                let m = a.real(i + 1)?;
                if m <= 0.0 {
                    return Err(a.error(i + 1, "Fix insert/pack: mass_in_region must be > 0"));
                }
                target = Some(Target::Mass(m));
                i += 2;
            }
            w @ ("insert_every" | "every" | "insert_every_time") => {
                every = Some(if a.word(i + 1)? == "once" {
                    0
                } else if w == "insert_every_time" {
                    (a.real(i + 1)? / ctx.sim.dt) as i32 as i64
                } else {
                    a.int(i + 1)?
                });
                i += 2;
            }
            "start" => {
                let st = a.int(i + 1)?;
                if st < ctx.sim.step + 1 {
                    return Err(a.error(
                        i + 1,
                        "Fix insert: 'start' step can not be before current step",
                    ));
                }
                start = Some(st);
                i += 2;
            }
            "overlapcheck" => {
                overlap = yes(a, i + 1)?;
                i += 2;
            }
            "all_in" => {
                all_in = yes(a, i + 1)?;
                i += 2;
            }
            "check_dist_from_subdomain_border" => {
                check_dist = yes(a, i + 1)?;
                i += 2;
            }
            "verbose" => {
                verbose = yes(a, i + 1)?;
                i += 2;
            }
            "warn_region" => {
                yes(a, i + 1)?;
                i += 2;
            }
            "maxattempt" => {
                maxattempt = a.int32(i + 1)?;
                i += 2;
            }
            "ntry_mc" => {
                ntry_mc = a.int32(i + 1)?;
                if ntry_mc < 1000 {
                    return Err(a.error(i + 1, "Fix insert/pack: ntry_mc must be > 1000"));
                }
                i += 2;
            }
            "random_distribute" => {
                if a.word_in(i + 1, &["exact", "uncorrelated"])? == "uncorrelated" {
                    return Err(
                        a.unsupported(i + 1, "fix insert/pack random_distribute uncorrelated")
                    );
                }
                i += 2;
            }
            "vel" => {
                let v = [a.real(i + 2)?, a.real(i + 3)?, a.real(i + 4)?];
                match a.word_in(i + 1, &["constant", "uniform", "gaussian"])? {
                    "constant" => {
                        velocity = Velocity::Constant(v);
                        i += 5;
                    }
                    style => {
                        let d = [a.real(i + 5)?, a.real(i + 6)?, a.real(i + 7)?];
                        velocity = if style == "uniform" {
                            Velocity::Uniform(v, d)
                        } else {
                            Velocity::Gaussian(v, d)
                        };
                        i += 8;
                    }
                }
            }
            "omega" => {
                a.word_in(i + 1, &["constant"])?;
                omega = [a.real(i + 2)?, a.real(i + 3)?, a.real(i + 4)?];
                i += 5;
            }
            "nparticles" if rate_style => {
                nparticles = Some(a.int32(i + 1)?);
                i += 2;
            }
            "particlerate" if rate_style => {
                particlerate = Some(a.real(i + 1)?);
                i += 2;
            }
            w @ ("orientation" | "set_property" | "compress_tags" | "nparticles" | "mass"
            | "massrate" | "particlerate") => {
                return Err(a.unsupported(i, &format!("fix {style} {w}")))
            }
            _ => {
                return Err(a.keyword_error(
                    i,
                    &[
                        "seed",
                        "distributiontemplate",
                        "region",
                        "particles_in_region",
                        "volumefraction_region",
                        "mass_in_region",
                        "insert_every",
                        "start",
                        "overlapcheck",
                        "all_in",
                        "maxattempt",
                        "ntry_mc",
                        "vel",
                        "omega",
                        "check_dist_from_subdomain_border",
                        "verbose",
                        "warn_region",
                    ],
                ))
            }
        }
    }
    let seed = seed.ok_or_else(|| a.error(2, "Fix insert: have to define 'seed'"))?;
    let distribution =
        dist.ok_or_else(|| a.error(2, "Fix insert: have to define a 'distributiontemplate'"))?;
    let (region, region_id) =
        region.ok_or_else(|| a.error(2, "Fix insert/pack: must define an insertion region"))?;
    let rate = if rate_style {
        if target.is_some() {
            return Err(a.error(2, "Fix insert/rate/region: particles_in_region, volumefraction_region and mass_in_region are insert/pack keywords"));
        }
        let n = nparticles
            .ok_or_else(|| a.error(2, "Fix insert/rate/region: have to define 'nparticles'"))?;
        let r = particlerate
            .ok_or_else(|| a.error(2, "Fix insert/rate/region: have to define 'particlerate'"))?;
        Some((n, r))
    } else {
        None
    };
    let target = match (rate, target) {
        (Some(_), _) => Target::Count(1),
        (None, Some(t)) => t,
        (None, None) => return Err(a.error(2, "Fix insert/pack: must define exactly one keyword out of 'volumefraction_region', 'particles_in_region', and 'mass_in_region'")),
    };
    let every = every.ok_or_else(|| a.error(2, "Fix insert/pack: must define 'insert_every'"))?;
    Ok(FixKind::InsertPack(Box::new(InsertPack {
        id: id.to_string(),
        distribution,
        region,
        region_id,
        target,
        every,
        next: Some(start.unwrap_or(ctx.sim.step + 1)),
        overlapcheck: overlap,
        all_in,
        maxattempt,
        ntry_mc,
        check_dist,
        verbose,
        velocity,
        omega,
        rng: crate::util::random::RanPark::new(seed).map_err(|m| a.error(3, &m))?,
        seed,
        region_rng: crate::util::random::RanPark::new(3012211).expect("positive seed"),
        region_volume: 0.0,
        set_up: false,
        inserted: 0,
        inserted_mass: 0.0,
        rate,
        per_insertion: 0.0,
    })))
}

/// `fix ID GROUP insert/stream seed S distributiontemplate D nparticles N particlerate R
/// insertion_face MESH extrude_length L|insert_every N vel ... [overlapcheck ...]`.
fn insert_stream(a: &Args, ctx: &mut Ctx, id: &str) -> std::result::Result<FixKind, CommandError> {
    use crate::engine::insert::Velocity;
    a.count(5..=usize::MAX, "fix ID GROUP insert/stream seed S distributiontemplate D nparticles N particlerate R insertion_face MESH extrude_length L ...")?;
    let (mut seed, mut dist, mut face, mut extrude, mut every) = (None, None, None, None, None);
    let mut duration = None;
    let (mut total, mut rate) = (None, None);
    let (mut overlap, mut maxattempt, mut ntry_mc, mut verbose) = (true, 50i64, 100000i64, true);
    let mut velocity = Velocity::Constant([0.0; 3]);
    let mut omega = [0.0; 3];
    let mut start = ctx.sim.step + 1;
    let (mut all_in, mut all_in_at, mut face_id) = (false, 0, String::new());
    let mut i = 3;
    let yes = |a: &Args, k: usize| a.word_in(k, &["yes", "no"]).map(|w| w == "yes");
    // LIGGGHTS reads the general insertion keywords first, then insert/stream's own; a
    // general one after those is an error there
    let mut own_part = false;
    while i < a.len() {
        let w = a.word(i)?;
        let own = matches!(
            w,
            "insertion_face"
                | "extrude_length"
                | "duration"
                | "duration_time"
                | "parallel"
                | "ntry_mc"
                | "save_template"
        );
        if own {
            own_part = true;
        } else if own_part {
            return Err(a.error(
                i,
                format!("Fix insert/stream (id {id}): unknown keyword or wrong keyword order"),
            ));
        }
        match w {
            "seed" => {
                seed = Some(seed_arg(a, ctx, i + 1)?);
                i += 2;
            }
            "distributiontemplate" => {
                let d = a.word(i + 1)?;
                if !ctx
                    .sim
                    .fixes
                    .iter()
                    .any(|f| f.id == d && matches!(f.kind, FixKind::Distribution(_)))
                {
                    return Err(a.error(i + 1, "Fix insert: distributiontemplate must be a fix particledistribution/discrete"));
                }
                dist = Some(d.to_string());
                i += 2;
            }
            "insertion_face" => {
                let m = a.word(i + 1)?;
                let tri = ctx.sim.fixes.iter().find_map(|f| match &f.kind {
                    FixKind::Mesh(mesh) if f.id == m => {
                        Some((mesh.triangles().to_vec(), mesh.planar))
                    }
                    _ => None,
                });
                face_id = m.to_string();
                face = Some(tri.ok_or_else(|| {
                    a.error(
                        i + 1,
                        "Fix insert/stream: could not find the insertion_face mesh",
                    )
                })?);
                i += 2;
            }
            "extrude_length" => {
                extrude = Some(a.real(i + 1)?);
                i += 2;
            }
            w @ ("insert_every" | "every" | "insert_every_time") => {
                every = Some(if w == "insert_every_time" {
                    (a.real(i + 1)? / ctx.sim.dt) as i32 as i64
                } else {
                    a.int(i + 1)?
                });
                i += 2;
            }
            w @ ("duration" | "duration_time") => {
                let d = if w == "duration_time" {
                    (a.real(i + 1)? / ctx.sim.dt) as i32 as i64
                } else {
                    a.int(i + 1)?
                };
                if d < 1 {
                    return Err(a.error(
                        i + 1,
                        format!("Fix insert/stream (id {id}): 'duration' can not be < 1"),
                    ));
                }
                duration = Some(d);
                i += 2;
            }
            w @ ("nparticles" | "mass") => {
                if a.word(i + 1)? == "INF" {
                    return Err(a.unsupported(i + 1, &format!("fix insert/stream {w} INF")));
                }
                if total.is_some() {
                    return Err(a.error(
                        i,
                        "Fix insert/stream: must not define both 'nparticles' and 'mass'",
                    ));
                }
                total = Some(if w == "mass" {
                    Err(a.real(i + 1)?)
                } else {
                    Ok(a.int32(i + 1)?)
                });
                i += 2;
            }
            w @ ("particlerate" | "massrate") => {
                if rate.is_some() {
                    return Err(a.error(
                        i,
                        "Fix insert/stream: must not define both 'particlerate' and 'massrate'",
                    ));
                }
                let r = a.real(i + 1)?;
                rate = Some(if w == "massrate" { Err(r) } else { Ok(r) });
                i += 2;
            }
            "start" => {
                start = a.int(i + 1)?;
                i += 2;
            }
            "overlapcheck" => {
                overlap = yes(a, i + 1)?;
                i += 2;
            }
            "verbose" => {
                verbose = yes(a, i + 1)?;
                i += 2;
            }
            "maxattempt" => {
                maxattempt = a.int32(i + 1)?;
                i += 2;
            }
            "ntry_mc" => {
                ntry_mc = a.int32(i + 1)?;
                if ntry_mc < 1000 {
                    return Err(a.error(
                        i + 1,
                        format!("Fix insert/stream (id {id}): ntry_mc must be > 1000"),
                    ));
                }
                i += 2;
            }
            "vel" => {
                let v = [a.real(i + 2)?, a.real(i + 3)?, a.real(i + 4)?];
                match a.word_in(i + 1, &["constant", "uniform", "gaussian"])? {
                    "constant" => {
                        velocity = Velocity::Constant(v);
                        i += 5;
                    }
                    style => {
                        let d = [a.real(i + 5)?, a.real(i + 6)?, a.real(i + 7)?];
                        velocity = if style == "uniform" {
                            Velocity::Uniform(v, d)
                        } else {
                            Velocity::Gaussian(v, d)
                        };
                        i += 8;
                    }
                }
            }
            "omega" => {
                a.word_in(i + 1, &["constant"])?;
                omega = [a.real(i + 2)?, a.real(i + 3)?, a.real(i + 4)?];
                i += 5;
            }
            "all_in" => {
                all_in = yes(a, i + 1)?;
                all_in_at = i;
                i += 2;
            }
            w @ ("parallel" | "orientation" | "set_property" | "compress_tags"
            | "random_distribute") => {
                return Err(a.unsupported(i, &format!("fix insert/stream {w}")))
            }
            _ => {
                return Err(a.keyword_error(
                    i,
                    &[
                        "seed",
                        "distributiontemplate",
                        "nparticles",
                        "mass",
                        "particlerate",
                        "massrate",
                        "insertion_face",
                        "extrude_length",
                        "insert_every",
                        "insert_every_time",
                        "duration",
                        "duration_time",
                        "vel",
                        "omega",
                        "overlapcheck",
                        "maxattempt",
                        "ntry_mc",
                        "verbose",
                        "start",
                        "all_in",
                    ],
                ))
            }
        }
    }
    let need = |what: &str| a.error(2, format!("Fix insert/stream: have to define '{what}'"));
    let seed = seed.ok_or_else(|| need("seed"))?;
    let distribution = dist.ok_or_else(|| need("distributiontemplate"))?;
    let (triangles, planar) = face.ok_or_else(|| need("insertion_face"))?;
    if all_in && !planar {
        return Err(a.error(
            all_in_at,
            format!("Fix insert/stream (id {id}): using all_in yes requires you to use a fix mesh/surface/planar"),
        ));
    }
    let total = total.ok_or_else(|| {
        a.error(
            2,
            "Fix insert/stream: must define either 'nparticles' or 'mass'",
        )
    })?;
    let rate = rate.ok_or_else(|| {
        a.error(
            2,
            "Fix insert/stream: must define either 'massrate' or 'particlerate'",
        )
    })?;
    if extrude.is_some() == every.is_some() {
        return Err(a.error(
            2,
            "Fix insert/stream: must define either 'insert_every' or 'extrude_length'",
        ));
    }
    if extrude.is_some() && duration.is_some() {
        return Err(a.error(
            2,
            format!("Fix insert/stream (id {id}): must not provide both 'extrude_length' and 'duration'"),
        ));
    }
    Ok(FixKind::InsertStream(Box::new(
        crate::engine::fixes::StreamFix {
            id: id.to_string(),
            seed,
            distribution,
            triangles,
            face_id,
            all_in,
            extrude,
            every,
            duration,
            total,
            rate,
            velocity,
            omega,
            overlapcheck: overlap,
            maxattempt,
            ntry_mc,
            verbose,
            start,
            state: None,
            restored: None,
        },
    )))
}
