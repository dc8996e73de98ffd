//! Commands that build the simulation: styles and units, the box, regions, atoms, groups,
//! per-atom values, velocities, neighbour settings and the time step.

use crate::commands::registry::{self, Handler};
use crate::commands::{Args, Ctx};
use crate::commands::{At, CommandError};
use crate::engine::domain::parse_boundary;
use crate::engine::error::EngineError;
use crate::engine::region::RegionContext;
use crate::lang::system::Mode;
use crate::util::numbers::inumeric;

mod atoms;
mod files;
mod group_velocity;

use atoms::*;
use files::*;
use group_velocity::*;

type Result = std::result::Result<(), CommandError>;

/// The setup commands and their handlers.
pub const COMMANDS: &[(&str, Handler)] = &[
    ("atom_style", atom_style),
    ("atom_modify", atom_modify),
    ("boundary", boundary),
    ("units", units),
    ("dimension", dimension),
    ("newton", |a, ctx| {
        one_of(a, "newton", &["on", "off"], 1..=2)?;
        ctx.sim.newton_pair = a.word(0)? == "on";
        Ok(())
    }),
    ("suffix", suffix),
    ("package", package),
    ("communicate", communicate),
    ("comm_modify", communicate),
    ("processors", super::processors::processors),
    ("balance", super::balance::balance),
    ("region", region),
    ("create_box", create_box),
    ("change_box", super::change_box::change_box),
    ("compute_modify", super::compute_modify::compute_modify),
    ("fix_modify", super::fix_modify::fix_modify),
    ("create_atoms", create_atoms),
    ("lattice", lattice),
    ("displace_atoms", displace_atoms),
    ("read_dump", super::read_dump::read_dump),
    ("replicate", super::replicate::replicate),
    ("delete_atoms", delete_atoms),
    ("set", super::set::set),
    ("group", group),
    ("velocity", velocity),
    ("neighbor", neighbor),
    ("neigh_modify", neigh_modify),
    ("timestep", timestep),
    ("reset_timestep", reset_timestep),
    ("read_data", read_data),
    ("read_restart", read_restart),
    ("write_restart", write_restart),
    ("restart", restart),
    ("write_data", write_data),
];

fn atom_style(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=usize::MAX, "atom_style granular|sphere")?;
    if a.word(0)? == "hybrid" {
        return hybrid_atom_style(a);
    }
    registry::require_style(a, "atom_style")?;
    match a.word(0)? {
        _ if a.len() > 1 => {
            // a style without arguments given some (LIGGGHTS's AtomVec::settings)
            return Err(a.error(1, "Invalid atom_style command"));
        }
        _ => {}
    }
    match a.word(0)? {
        "granular" | "sphere" => {
            if ctx.sim.domain.exists {
                return Err(a.error(0, "Atom_style command after simulation box is defined"));
            }
            Ok(())
        }
        other => Err(a.unsupported(0, &format!("atom_style {other}"))),
    }
}

/// `atom_style hybrid S1 S2 ...`: LIGGGHTS's errors (a first word that is no style, a style
/// twice, words after a style that takes none); a valid one is not supported yet.
fn hybrid_atom_style(a: &Args) -> Result {
    use super::names::{is_known, NameKind};
    let mut seen: Vec<&str> = Vec::new();
    for i in 1..a.len() {
        let w = a.word(i)?;
        if is_known(NameKind::AtomStyle, w) && w != "hybrid" {
            if seen.contains(&w) {
                return Err(a.error(i, "Atom style hybrid cannot use same atom style twice"));
            }
            seen.push(w);
        } else if seen.is_empty() {
            return Err(a.error(i, "Invalid atom style"));
        } else {
            return Err(a.error(i, "Invalid atom_style command"));
        }
    }
    Err(a.unsupported(0, "atom_style hybrid"))
}

fn atom_modify(a: &Args, ctx: &mut Ctx) -> Result {
    let mut i = 0;
    while i < a.len() {
        match a.word(i)? {
            "map" => {
                a.word_in(i + 1, &["array", "hash"])?;
                i += 2;
            }
            "sort" => {
                // the particle order matters: it decides the summation order of forces
                // and the IDs `delete_atoms compress` hands out
                let every = a.int(i + 1)?;
                let binsize = a.real(i + 2)?;
                if every < 0 || binsize < 0.0 {
                    return Err(a.error(i + 1, "Illegal atom_modify command"));
                }
                ctx.sim.sort_every = every;
                ctx.sim.sort_binsize = binsize;
                i += 3;
            }
            "first" => return Err(a.unsupported(i, "atom_modify first")),
            _ => return Err(a.keyword_error(i, &["map", "sort"])),
        }
    }
    Ok(())
}

fn boundary(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(3..=3, "boundary X Y Z (p, f, s, m or two of them each)")?;
    if ctx.sim.domain.exists {
        return Err(a.error(0, "Boundary command after simulation box is defined"));
    }
    let words = [a.word(0)?, a.word(1)?, a.word(2)?];
    ctx.sim.domain.boundary = parse_boundary(&words).map_err(|m| a.error(0, &m))?;
    Ok(())
}

fn units(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "units si|cgs")?;
    if ctx.sim.domain.exists {
        return Err(a.error(0, "Units command after simulation box is defined"));
    }
    use crate::engine::contact::UnitStyle;
    // LIGGGHTS's defaults per style: time step 1e-8 and a neighbour skin of 1 mm
    let (style, skin) = match a.word(0)? {
        "si" => (UnitStyle::Si, 0.001),
        "cgs" => (UnitStyle::Cgs, 0.1),
        "lj" | "real" | "metal" | "micro" | "nano" | "electron" => {
            return Err(a.unsupported(0, &format!("units {}", a.word(0)?)))
        }
        _ => return Err(a.error(0, "Illegal units command")),
    };
    ctx.sim.units = style;
    ctx.sim.dt = 1.0e-8;
    ctx.sim.neighbor.skin = skin;
    Ok(())
}

fn dimension(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "dimension 2|3")?;
    if ctx.sim.domain.exists {
        return Err(a.error(0, "Dimension command after simulation box is defined"));
    }
    match a.int(0)? {
        d @ (2 | 3) => {
            ctx.sim.dimension = d as u32;
            Ok(())
        }
        _ => Err(a.error(0, "Illegal dimension command")),
    }
}

/// `suffix fast|on|off` (LAMMPS's accelerator switch): the fast engine path.
fn suffix(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "suffix fast|off")?;
    let fast = crate::engine::accel::parse_suffix(a.word(0)?).map_err(|m| {
        a.error(0, m.to_string())
            .with_help(crate::engine::accel::SUFFIX_HELP)
    })?;
    ctx.sim.accel.fast = fast;
    Ok(())
}

/// `package fast N`: the engine's thread count.
fn package(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(2..=2, "package fast N")?;
    let n = crate::engine::accel::parse_package(a.word(0)?, a.word(1)?).map_err(|m| {
        a.error(0, m.to_string())
            .with_help(crate::engine::accel::PACKAGE_HELP)
    })?;
    ctx.sim.accel.ask_threads(Some(n));
    Ok(())
}

fn one_of(a: &Args, cmd: &str, allowed: &[&str], count: std::ops::RangeInclusive<usize>) -> Result {
    a.count(count, &format!("{cmd} {}", allowed.join("|")))?;
    for i in 0..a.len() {
        a.word_in(i, allowed)?;
    }
    Ok(())
}

fn communicate(a: &Args, ctx: &mut Ctx) -> Result {
    // one process: communication settings change nothing, but they must be valid
    let mut i = 0;
    while i < a.len() {
        match a.word(i)? {
            "single" | "multi" => i += 1,
            "vel" => {
                ctx.sim.comm_vel = a.word_in(i + 1, &["yes", "no"])? == "yes";
                i += 2;
            }
            "cutoff" => {
                a.real(i + 1)?;
                i += 2;
            }
            "group" => {
                a.word(i + 1)?;
                i += 2;
            }
            _ => return Err(a.keyword_error(i, &["single", "multi", "vel", "cutoff", "group"])),
        }
    }
    Ok(())
}

fn region(a: &Args, ctx: &mut Ctx) -> Result {
    let words: Vec<&str> = (0..a.len())
        .map(|i| a.word(i))
        .collect::<std::result::Result<_, _>>()?;
    let d = &ctx.sim.domain;
    if words.get(1) == Some(&"mesh/tet") {
        return crate::commands::region_tet::define(a, ctx, &words);
    }
    let rctx = RegionContext {
        bounds: d.exists.then_some((d.lo, d.hi)),
        lattice: ctx
            .sim
            .lattice
            .as_ref()
            .filter(|l| !l.1.is_empty() || l.0 > 0.0)
            .map(|l| {
                ctx.sim
                    .lattice_cell
                    .as_ref()
                    .map_or([l.0; 3], |c| c.spacing)
            }),
    };
    ctx.sim.regions.define(&words, rctx).map_err(|e| match e {
        EngineError::Unsupported(what) => CommandError::unsupported(what, At::Line),
        other => a.error(1, other.to_string()),
    })?;
    let index = ctx.sim.regions.list.len() - 1;
    if let Some(name) = ctx.sim.regions.radius_variable(index) {
        let style = a.word(1)?;
        let at = (2..a.len()).find(|&i| a.word(i).is_ok_and(|w| w.starts_with("v_")));
        let problem = match ctx.vars.get(name).map(|v| v.style) {
            None => Some(format!("Variable name for region {style} does not exist")),
            Some(crate::lang::variables::Style::Equal) => None,
            Some(_) => Some(format!("Variable for region {style} is invalid style")),
        };
        if let Some(m) = problem {
            ctx.sim.regions.list.pop();
            return Err(a.error(at.unwrap_or(1), &m));
        }
        if ctx.sys.mode == Mode::Run {
            ctx.reshape_regions(true)
                .map_err(|e| a.engine_error(1, e))?;
        }
    }
    if let Some(m) = &ctx.sim.regions.list[index].motion {
        let mut problem = None;
        for (name, wrong_style) in m.variables() {
            let at = (2..a.len())
                .find(|&i| a.word(i).ok() == Some(&format!("v_{name}")))
                .unwrap_or(1);
            problem = match ctx.vars.get(name).map(|v| v.style) {
                None => Some((at, "Variable name for region does not exist")),
                Some(crate::lang::variables::Style::Equal) => None,
                Some(_) => Some((at, wrong_style)),
            };
            if problem.is_some() {
                break;
            }
        }
        if let Some((at, m)) = problem {
            ctx.sim.regions.list.pop();
            return Err(a.error(at, m));
        }
        if ctx.sys.mode == Mode::Run {
            ctx.reshape_regions(true)
                .map_err(|e| a.engine_error(1, e))?;
        }
    }
    Ok(())
}

fn create_box(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(2..=usize::MAX, "create_box N region-ID")?;
    if ctx.sim.domain.exists {
        return Err(a.error(0, "Cannot create_box after simulation box is defined"));
    }
    if ctx.sim.dimension == 2 && !ctx.sim.domain.periodic(2) {
        return Err(a.error(0, "Cannot run 2d simulation with nonperiodic Z dimension"));
    }
    let ntypes = a.int(0)?;
    if ntypes < 1 {
        return Err(a.error(0, "Illegal create_box command"));
    }
    crate::engine::checks::check_ntypes(ntypes).map_err(|m| a.error(0, &m))?;
    if a.len() > 2 {
        return Err(a.unsupported(2, "create_box keywords"));
    }
    let rid = a.word(1)?;
    let index = ctx
        .sim
        .regions
        .find(rid)
        .ok_or_else(|| a.error(1, "Create_box region ID does not exist"))?;
    let (lo, hi) = ctx
        .sim
        .regions
        .extent(index)
        .ok_or_else(|| a.error(1, "Create_box region does not support a bounding box"))?;
    // LIGGGHTS's wedge-shaped domain (`-domain wedge`) is not in regolith's command line
    if ctx.sim.regions.list[index].style == "wedge" {
        return Err(a.error(
            1,
            "Create_box with wedge region requires you to start with the '-domain wedge' command line option",
        ));
    }
    // LIGGGHTS's check, and a length a double can hold
    if let Some(d) = (0..3).find(|&d| !(lo[d] < hi[d] && (hi[d] - lo[d]).is_finite())) {
        return Err(a.error(
            1,
            format!(
                "Box bounds are invalid ({} {} along {})",
                g(lo[d]),
                g(hi[d]),
                ["x", "y", "z"][d]
            ),
        ));
    }
    ctx.sim.domain.create(lo, hi);
    ctx.sim.ntypes = ntypes as u32;
    ctx.say(&format!(
        "Created orthogonal box = ({} {} {}) to ({} {} {})\n",
        g(lo[0]),
        g(lo[1]),
        g(lo[2]),
        g(hi[0]),
        g(hi[1]),
        g(hi[2])
    ));
    let grid = super::processors::grid_lines(a, ctx, [0, 1, 2].map(|d| hi[d] - lo[d]), 1)?;
    ctx.say(&grid);
    Ok(())
}

fn g(x: f64) -> String {
    crate::util::format::g(x)
}

/// The lattice styles of LIGGGHTS 3.8.0 (those regolith runs are in [`registry::STYLES`]).
pub const LATTICE_STYLES: &[&str] = &[
    "none", "sc", "bcc", "fcc", "hcp", "diamond", "sq", "sq2", "hex", "custom",
];

fn lattice(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(2..=usize::MAX, "lattice sc|bcc|fcc|none SCALE")?;
    let style = a.word(0)?;
    let scale = a.real(1)?;
    if scale <= 0.0 {
        return Err(a.error(1, "Illegal lattice command"));
    }
    check_lattice_style(a, ctx, style)?;
    let mut basis = unit_cell_basis(a, style)?;
    let (origin, mut primitive) = lattice_keywords(a, style, &mut basis)?;
    check_lattice_2d(a, ctx, origin, &primitive)?;
    if style == "hex" {
        // the hexagonal cell is sqrt(3) times taller than wide
        primitive[1][1] = 3f64.sqrt();
    }
    let mut spacing = [scale; 3];
    ctx.sim.lattice_cell = None;
    if style == "custom" || style == "hex" {
        if basis.is_empty() {
            return Err(a
                .error(0, "No basis atoms in lattice")
                .with_help("add basis x y z (fractions of the cell)"));
        }
        let cell = crate::engine::lattice::Cell::new(scale, primitive, origin)
            .map_err(|m| a.error(0, &m))?;
        spacing = cell.spacing;
        ctx.sim.lattice_cell = Some(cell);
    }
    ctx.sim.lattice = Some((scale, basis));
    ctx.sim.lattice_origin = origin;
    ctx.say(&format!(
        "Lattice spacing in x,y,z = {} {} {}\n",
        g(spacing[0]),
        g(spacing[1]),
        g(spacing[2])
    ));
    Ok(())
}

/// LIGGGHTS's checks of a lattice style: a known style, made for the simulation's
/// dimension (checked before anything else), and one regolith runs.
fn check_lattice_style(a: &Args, ctx: &Ctx, style: &str) -> Result {
    if !registry::runs_style("lattice", style) && !LATTICE_STYLES.contains(&style) {
        return Err(a.keyword_error(0, LATTICE_STYLES));
    }
    let planar = matches!(style, "sq" | "sq2" | "hex");
    let spatial = matches!(style, "sc" | "bcc" | "fcc" | "hcp" | "diamond");
    if (ctx.sim.dimension == 2 && spatial) || (ctx.sim.dimension == 3 && planar) {
        return Err(a
            .error(0, "Lattice style incompatible with simulation dimension")
            .with_help("sq, sq2 and hex are 2d lattices; sc, bcc, fcc, hcp and diamond 3d"));
    }
    registry::require_style(a, "lattice")
}

/// The basis atoms of lattice `style`'s unit cell (fractions of the cell; none for
/// `custom`, whose `basis` keywords add them).
fn unit_cell_basis(a: &Args, style: &str) -> std::result::Result<Vec<[f64; 3]>, CommandError> {
    Ok(match style {
        "none" | "custom" => Vec::new(),
        "sc" | "sq" => vec![[0.0; 3]],
        "bcc" => vec![[0.0; 3], [0.5, 0.5, 0.5]],
        "fcc" => vec![[0.0; 3], [0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]],
        "sq2" | "hex" => vec![[0.0; 3], [0.5, 0.5, 0.0]],
        _ => return Err(a.unsupported(0, &format!("lattice {style}"))),
    })
}

/// The lattice's keywords `origin`, `a1`, `a2`, `a3` and `basis` (the last four with
/// `custom` only): the origin (fractions of the cell) and the primitive vectors; `basis`
/// atoms are added to `basis`.
fn lattice_keywords(
    a: &Args,
    style: &str,
    basis: &mut Vec<[f64; 3]>,
) -> std::result::Result<([f64; 3], [[f64; 3]; 3]), CommandError> {
    let mut origin = [0.0; 3];
    let mut primitive = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut i = 2;
    while i < a.len() {
        let w = a.word(i)?;
        if !matches!(w, "origin" | "a1" | "a2" | "a3" | "basis") {
            return Err(a.unsupported(i, &format!("lattice keyword {w}")));
        }
        if i + 4 > a.len() {
            return Err(a.error(i, "Illegal lattice command"));
        }
        if w != "origin" && style != "custom" {
            return Err(a.error(i, "Invalid option in lattice command for non-custom style"));
        }
        let mut v = [0.0; 3];
        for (k, o) in v.iter_mut().enumerate() {
            *o = a.real(i + 1 + k)?;
        }
        match w {
            "origin" | "basis" => {
                if let Some(k) = (0..3).find(|&k| !(0.0..1.0).contains(&v[k])) {
                    return Err(a
                        .error(i + 1 + k, "Illegal lattice command")
                        .with_help("each value must be at least 0 and less than 1"));
                }
                if w == "origin" {
                    origin = v;
                } else {
                    basis.push(v);
                }
            }
            "a1" => primitive[0] = v,
            "a2" => primitive[1] = v,
            _ => primitive[2] = v,
        }
        i += 4;
    }
    Ok((origin, primitive))
}

/// In 2d LIGGGHTS refuses an origin or primitive vectors that leave the xy plane.
fn check_lattice_2d(a: &Args, ctx: &Ctx, origin: [f64; 3], primitive: &[[f64; 3]; 3]) -> Result {
    if ctx.sim.dimension == 2
        && (origin[2] != 0.0
            || primitive[0][2] != 0.0
            || primitive[1][2] != 0.0
            || primitive[2][0] != 0.0
            || primitive[2][1] != 0.0)
    {
        return Err(a
            .error(0, "Lattice settings are not compatible with 2d simulation")
            .with_help("in 2d the origin's z and the a1, a2 z and a3 x, y components must be 0"));
    }
    Ok(())
}

/// Atoms selected by `set atom|type|group|region ID`.
pub(super) fn selection(a: &Args, ctx: &Ctx) -> std::result::Result<Vec<usize>, CommandError> {
    let p = &ctx.sim.particles;
    let what = a.word_in(0, &["atom", "type", "group", "region", "mol"])?;
    let id = a.word(1)?;
    Ok(match what {
        "atom" | "type" => {
            let (lo, hi) =
                crate::util::numbers::bounds(id, i64::MAX / 4).map_err(|m| a.error(1, &m))?;
            (0..p.len())
                .filter(|&i| {
                    let v = if what == "atom" {
                        p.id[i]
                    } else {
                        p.kind[i] as i64
                    };
                    v >= lo && v <= hi
                })
                .collect()
        }
        "group" => {
            let bit = ctx
                .sim
                .group_bit(id)
                .ok_or_else(|| a.error(1, "Set group ID does not exist"))?;
            (0..p.len()).filter(|&i| p.mask[i] & bit != 0).collect()
        }
        "region" => {
            let r = ctx
                .sim
                .regions
                .find(id)
                .ok_or_else(|| a.error(1, "Set region ID does not exist"))?;
            (0..p.len())
                .filter(|&i| ctx.sim.regions.matches(r, p.x[i]))
                .collect()
        }
        _ => return Err(a.unsupported(0, "set mol")),
    })
}

fn neighbor(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(2..=2, "neighbor SKIN bin")?;
    let skin = a.real(0)?;
    if skin < 0.0 {
        return Err(a.error(0, "Illegal neighbor command"));
    }
    match a.word(1)? {
        "bin" => {}
        "nsq" | "multi" => return Err(a.unsupported(1, &format!("neighbor {}", a.word(1)?))),
        _ => return Err(a.error(1, "Illegal neighbor command")),
    }
    ctx.sim.neighbor.skin = skin;
    Ok(())
}

fn neigh_modify(a: &Args, ctx: &mut Ctx) -> Result {
    let mut i = 0;
    while i < a.len() {
        let n = &mut ctx.sim.neighbor;
        match a.word(i)? {
            "every" => n.every = positive(a, i + 1)?,
            "delay" => n.delay = a.int(i + 1)?.max(0) as u64,
            "check" => n.check = a.word_in(i + 1, &["yes", "no"])? == "yes",
            // capacity hints for LIGGGHTS's fixed-size pages; regolith's lists grow as needed
            "one" | "page" => {
                positive(a, i + 1)?;
            }
            "exclude" => {
                match a.word(i + 1)? {
                    "type" => {
                        let (t1, t2) = (a.int(i + 2)?, a.int(i + 3)?);
                        let ntypes = ctx.sim.ntypes as i64;
                        if !(1..=ntypes).contains(&t1) || !(1..=ntypes).contains(&t2) {
                            return Err(a.error(i + 2, "Illegal neigh_modify command"));
                        }
                        ctx.sim.neighbor.exclude_types.push((t1 as u32, t2 as u32));
                        i += 4;
                    }
                    "group" => {
                        let mut bits = [0u32; 2];
                        for (k, b) in bits.iter_mut().enumerate() {
                            let name = a.word(i + 2 + k)?;
                            *b = ctx.sim.group_bit(name).ok_or_else(|| {
                                a.error(i + 2 + k, "Invalid group ID in neigh_modify command")
                            })?;
                        }
                        ctx.sim.neighbor.exclude_groups.push((bits[0], bits[1]));
                        i += 4;
                    }
                    "none" => {
                        ctx.sim.neighbor.exclude_types.clear();
                        ctx.sim.neighbor.exclude_groups.clear();
                        i += 2;
                    }
                    "molecule" => return Err(a.unsupported(i + 1, "neigh_modify exclude molecule")),
                    _ => return Err(a.keyword_error(i + 1, &["type", "group", "molecule", "none"])),
                }
                continue;
            }
            "binsize" => {
                // LIGGGHTS scales it by the coarse-graining factor, which regolith has not
                ctx.sim.extras.neigh_binsize = a.real(i + 1)?.max(0.0);
            }
            "include" | "contact_distance_factor" => {
                return Err(a.unsupported(i, &format!("neigh_modify {}", a.word(i)?)))
            }
            _ => {
                return Err(a.keyword_error(
                    i,
                    &[
                        "every", "delay", "check", "one", "page", "exclude", "binsize",
                    ],
                ))
            }
        }
        i += 2;
    }
    Ok(())
}

fn positive(a: &Args, i: usize) -> std::result::Result<u64, CommandError> {
    let v = a.int(i)?;
    if v <= 0 {
        return Err(a.error(i, "expected a positive integer"));
    }
    Ok(v as u64)
}

fn timestep(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "timestep DT")?;
    // LIGGGHTS changes only dt here; elapsed time is brought up to date at run ends
    ctx.sim.dt = a.real(0)?;
    Ok(())
}

fn reset_timestep(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "reset_timestep N")?;
    let n = a.int(0)?;
    if n < 0 {
        return Err(a.error(0, "Timestep must be >= 0"));
    }
    ctx.sim.reset_timestep(n);
    Ok(())
}
