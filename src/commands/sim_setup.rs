//! Commands that build the simulation: styles and units, the box, regions, atoms, groups,
//! per-atom values, velocities, neighbour settings and the time step.

use crate::commands::registry::{self, Handler};
use crate::commands::{Args, Ctx};
use crate::commands::{At, CommandError};
use crate::engine::domain::parse_boundary;
use crate::engine::error::EngineError;
use crate::engine::region::RegionContext;
use crate::script::system::Mode;
use crate::util::numbers::inumeric;

type Result = std::result::Result<(), CommandError>;

/// The setup commands and their handlers.
pub const COMMANDS: &[(&str, Handler)] = &[
    ("atom_style", atom_style),
    ("atom_modify", atom_modify),
    ("boundary", boundary),
    ("units", units),
    ("dimension", |a, _| dimension(a)),
    ("newton", |a, _| one_of(a, "newton", &["on", "off"], 1..=2)),
    ("suffix", suffix),
    ("package", package),
    ("communicate", communicate),
    ("comm_modify", communicate),
    ("processors", |a, _| processors(a)),
    ("region", region),
    ("create_box", create_box),
    ("change_box", super::change_box::change_box),
    ("compute_modify", super::compute_modify::compute_modify),
    ("create_atoms", create_atoms),
    ("lattice", lattice),
    ("displace_atoms", displace_atoms),
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
    a.count(1..=1, "atom_style granular|sphere")?;
    registry::require_style(a, "atom_style")?;
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

fn dimension(a: &Args) -> Result {
    a.count(1..=1, "dimension 3")?;
    match a.int(0)? {
        3 => Ok(()),
        2 => Err(a.unsupported(0, "dimension 2")),
        _ => Err(a.error(0, "Illegal dimension command")),
    }
}

/// `suffix fast|on|off` (LAMMPS's accelerator switch): the fast engine path.
fn suffix(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "suffix fast|off")?;
    let fast = crate::cli::parse_suffix(a.word(0)?)
        .map_err(|m| a.error(0, &m).with_help(crate::cli::SUFFIX_HELP))?;
    ctx.sim.accel.fast = fast;
    Ok(())
}

/// `package fast N`: the engine's thread count.
fn package(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(2..=2, "package fast N")?;
    let n = crate::cli::parse_package(a.word(0)?, a.word(1)?)
        .map_err(|m| a.error(0, &m).with_help(crate::cli::PACKAGE_HELP))?;
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

fn processors(a: &Args) -> Result {
    a.count(3..=usize::MAX, "processors Px Py Pz")?;
    for i in 0..3 {
        let w = a.word(i)?;
        if w != "*" {
            a.int(i)?;
        }
    }
    if a.len() > 3 {
        return Err(a.unsupported(3, "processors keywords"));
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
        EngineError::Invalid(m) => a.error(1, m),
    })?;
    let index = ctx.sim.regions.list.len() - 1;
    if let Some(name) = ctx.sim.regions.radius_variable(index) {
        let style = a.word(1)?;
        let at = (2..a.len()).find(|&i| a.word(i).is_ok_and(|w| w.starts_with("v_")));
        let problem = match ctx.vars.get(name).map(|v| v.style) {
            None => Some(format!("Variable name for region {style} does not exist")),
            Some(crate::script::variables::Style::Equal) => None,
            Some(_) => Some(format!("Variable for region {style} is invalid style")),
        };
        if let Some(m) = problem {
            ctx.sim.regions.list.pop();
            return Err(a.error(at.unwrap_or(1), &m));
        }
        if ctx.sys.mode == Mode::Run {
            ctx.reshape_regions(true).map_err(|m| a.error(1, &m))?;
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
                Some(crate::script::variables::Style::Equal) => None,
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
            ctx.reshape_regions(true).map_err(|m| a.error(1, &m))?;
        }
    }
    Ok(())
}

fn create_box(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(2..=usize::MAX, "create_box N region-ID")?;
    if ctx.sim.domain.exists {
        return Err(a.error(0, "Cannot create_box after simulation box is defined"));
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
        "Created orthogonal box = ({} {} {}) to ({} {} {})\n  1 by 1 by 1 MPI processor grid\n",
        g(lo[0]),
        g(lo[1]),
        g(lo[2]),
        g(hi[0]),
        g(hi[1]),
        g(hi[2])
    ));
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
    if !registry::runs_style("lattice", style) && !LATTICE_STYLES.contains(&style) {
        return Err(a.keyword_error(0, LATTICE_STYLES));
    }
    registry::require_style(a, "lattice")?;
    let mut basis: Vec<[f64; 3]> = match style {
        "none" | "custom" => Vec::new(),
        "sc" => vec![[0.0; 3]],
        "bcc" => vec![[0.0; 3], [0.5, 0.5, 0.5]],
        "fcc" => vec![[0.0; 3], [0.5, 0.5, 0.0], [0.5, 0.0, 0.5], [0.0, 0.5, 0.5]],
        _ => return Err(a.unsupported(0, &format!("lattice {style}"))),
    };
    let mut origin = [0.0; 3];
    let mut primitive = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut i = 2;
    while i < a.len() {
        let w = a.word(i)?;
        match w {
            "origin" | "a1" | "a2" | "a3" | "basis" => {
                if i + 4 > a.len() {
                    return Err(a.error(i, "Illegal lattice command"));
                }
                if w != "origin" && style != "custom" {
                    return Err(
                        a.error(i, "Invalid option in lattice command for non-custom style")
                    );
                }
                let mut v = [0.0; 3];
                for (k, o) in v.iter_mut().enumerate() {
                    *o = a.real(i + 1 + k)?;
                }
                let fraction = |k: usize| (0.0..1.0).contains(&v[k]);
                match w {
                    "origin" | "basis" => {
                        if let Some(k) = (0..3).find(|&k| !fraction(k)) {
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
            w => return Err(a.unsupported(i, &format!("lattice keyword {w}"))),
        }
    }
    let mut spacing = [scale; 3];
    ctx.sim.lattice_cell = None;
    if style == "custom" {
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

fn create_atoms(a: &Args, ctx: &mut Ctx) -> Result {
    ctx.reshape_regions(false).map_err(|m| a.error(0, &m))?;
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Create_atoms command before simulation box is defined"));
    }
    a.count(
        2..=usize::MAX,
        "create_atoms TYPE single X Y Z | box | region ID [units box|lattice]",
    )?;
    let kind = a.int(0)?;
    if kind < 1 || kind > ctx.sim.ntypes as i64 {
        return Err(a.error(0, "Invalid atom type in create_atoms command"));
    }
    let style = a.word_in(1, &["single", "box", "region", "random"])?;
    let mut i = match style {
        "single" => 5,
        "box" => 2,
        "region" => 3,
        _ => 5,
    };
    let region_word = match style {
        "region" => Some(a.word(2)?),
        "random" => Some(a.word(4)?).filter(|w| *w != "NULL"),
        _ => None,
    };
    let region = match region_word {
        Some(w) => Some(ctx.sim.regions.find(w).ok_or_else(|| {
            a.error(
                if style == "region" { 2 } else { 4 },
                "Create_atoms region ID does not exist",
            )
        })?),
        None => None,
    };
    let mut lattice_units = ctx.sim.lattice.as_ref().is_some_and(|l| !l.1.is_empty());
    while i < a.len() {
        match a.word(i)? {
            "units" => {
                lattice_units = a.word_in(i + 1, &["box", "lattice"])? == "lattice";
                i += 2;
            }
            _ => return Err(a.unsupported(i, &format!("create_atoms keyword {}", a.word(i)?))),
        }
    }
    let d = ctx.sim.domain.clone();
    let before = ctx.sim.particles.len();
    let mut next_id = ctx.sim.particles.max_id() + 1;
    if style == "random" {
        // N positions uniform in the box (cut to the region's extent), redrawn until
        // inside the region, from one Park-Miller stream seeded by the deck
        let count = a.int(2)?;
        let seed = a.int(3)?;
        if count < 0 {
            return Err(a.error(2, "Illegal create_atoms command"));
        }
        if !ctx.sim.seed_tolerant {
            crate::util::random::check_seed(seed).map_err(|m| a.error(3, &m))?;
        }
        if seed <= 0 || seed > i32::MAX as i64 {
            return Err(a.error(3, "Illegal create_atoms command"));
        }
        let mut rng = crate::util::random::RanPark::new(seed as i32).map_err(|m| a.error(3, &m))?;
        if let Some(m) = too_many_atoms(count as f64, next_id, "atoms requested") {
            return Err(a.error(2, &m));
        }
        if ctx.sys.mode == Mode::Check && count as f64 > CHECK_BUILD_LIMIT {
            // a dry run validates the count but does not build the atoms
            ctx.sim.inserts_atoms = true;
            return Ok(());
        }
        ctx.sim
            .particles
            .try_reserve(count as usize)
            .map_err(|m| a.error(2, &m))?;
        let (mut lo, mut hi) = (d.lo, d.hi);
        if let Some((elo, ehi)) = region.and_then(|r| ctx.sim.regions.extent(r)) {
            for k in 0..3 {
                lo[k] = lo[k].max(elo[k]);
                hi[k] = hi[k].min(ehi[k]);
            }
        }
        if (0..3).any(|k| lo[k] > hi[k]) {
            return Err(a.error(4, "No overlap of box and region for create_atoms"));
        }
        for _ in 0..count {
            let mut tries = 0u64;
            let x = loop {
                let x = [
                    lo[0] + rng.uniform() * (hi[0] - lo[0]),
                    lo[1] + rng.uniform() * (hi[1] - lo[1]),
                    lo[2] + rng.uniform() * (hi[2] - lo[2]),
                ];
                if region.is_none_or(|r| ctx.sim.regions.matches(r, x)) {
                    break x;
                }
                // a region without volume inside the box would be searched forever
                tries += 1;
                if tries == MAX_RANDOM_TRIES {
                    return Err(a.error(
                        4,
                        format!(
                            "Could not create all random atoms: no position inside the region in {MAX_RANDOM_TRIES} tries (has it any volume inside the box?)"
                        ),
                    ));
                }
            };
            ctx.sim.particles.push(next_id, kind as u32, x, 0.5, 1.0);
            next_id += 1;
        }
    } else if style == "single" {
        let mut x = [a.real(2)?, a.real(3)?, a.real(4)?];
        if lattice_units {
            let (scale, basis) = ctx
                .sim
                .lattice
                .clone()
                .ok_or_else(|| a.error(1, "Cannot create atoms with undefined lattice"))?;
            if basis.is_empty() {
                return Err(a
                    .error(1, "Cannot create atoms with undefined lattice")
                    .with_help("add 'units box'"));
            }
            let o = ctx.sim.lattice_origin;
            x = [0, 1, 2].map(|k| x[k] * scale + scale * o[k]);
        }
        if (0..3).all(|k| x[k] >= d.lo[k] && x[k] < d.hi[k]) {
            ctx.sim.particles.push(next_id, kind as u32, x, 0.5, 1.0);
        }
    } else {
        let Some((scale, basis)) = ctx.sim.lattice.clone().filter(|l| !l.1.is_empty()) else {
            return Err(a.error(1, "Cannot create atoms with undefined lattice"));
        };
        // LIGGGHTS shrinks the insertion box slightly along periodic directions so exactly
        // one of two boundary images is created
        let mut lo = d.lo;
        let mut hi = d.hi;
        for k in 0..3 {
            if d.periodic(k) {
                let eps = d.length(k) * 1.0e-6;
                lo[k] -= eps;
                hi[k] -= 2.0 * eps;
            }
        }
        // lattice index ranges covering the box, as LIGGGHTS's loop bounds (in doubles first,
        // so that a lattice far finer than the box is refused before anything is counted)
        let range = |k: usize| {
            let (a0, a1) = (d.lo[k] / scale, d.hi[k] / scale);
            let (mn, mx) = (a0.min(a1), a0.max(a1));
            let mut l = mn.trunc() - 1.0;
            if mn < 0.0 {
                l -= 1.0;
            }
            (l, mx.trunc() + 1.0)
        };
        let cell = ctx.sim.lattice_cell.clone();
        let bounds = match &cell {
            Some(c) => c.ranges(d.lo, d.hi),
            None => [range(0), range(1), range(2)],
        };
        let points = bounds.iter().map(|(l, h)| h - l + 1.0).product::<f64>() * basis.len() as f64;
        if let Some(m) = too_many_atoms(points, next_id, "lattice points in the box") {
            return Err(a.error(1, &m));
        }
        if ctx.sys.mode == Mode::Check && points > CHECK_BUILD_LIMIT {
            // a dry run validates the count but does not build the atoms
            ctx.sim.inserts_atoms = true;
            return Ok(());
        }
        // room for every lattice point in the region's bounding box (all of them, at most)
        let mut room = points;
        if let Some((elo, ehi)) = region.and_then(|r| ctx.sim.regions.extent(r)) {
            let inside = (0..3)
                .map(|k| ((ehi[k].min(d.hi[k]) - elo[k].max(d.lo[k])) / scale + 2.0).max(0.0))
                .product::<f64>()
                * basis.len() as f64;
            room = room.min(inside);
        }
        ctx.sim
            .particles
            .try_reserve(room as usize)
            .map_err(|m| a.error(1, &m))?;
        let [(ilo, ihi), (jlo, jhi), (klo, khi)] = bounds.map(|(l, h)| (l as i64, h as i64));
        for kk in klo..=khi {
            for jj in jlo..=jhi {
                for ii in ilo..=ihi {
                    for b in &basis {
                        let o = ctx.sim.lattice_origin;
                        let x = match &cell {
                            Some(c) => {
                                c.to_box([ii as f64 + b[0], jj as f64 + b[1], kk as f64 + b[2]])
                            }
                            None => [
                                (ii as f64 + b[0]) * scale + scale * o[0],
                                (jj as f64 + b[1]) * scale + scale * o[1],
                                (kk as f64 + b[2]) * scale + scale * o[2],
                            ],
                        };
                        if let Some(r) = region {
                            if !ctx.sim.regions.matches(r, x) {
                                continue;
                            }
                        }
                        if (0..3).any(|k| x[k] < lo[k] || x[k] >= hi[k]) {
                            continue;
                        }
                        ctx.sim.particles.push(next_id, kind as u32, x, 0.5, 1.0);
                        next_id += 1;
                    }
                }
            }
        }
    }
    ctx.say(&format!(
        "Created {} atoms\n",
        ctx.sim.particles.len() - before
    ));
    Ok(())
}

/// LIGGGHTS numbers atoms with ints: IDs beyond this are refused.
const MAX_ATOM_ID: f64 = 2_147_483_647.0;

/// Check mode validates `create_atoms` counts above this but does not build the atoms.
const CHECK_BUILD_LIMIT: f64 = 2.0e6;

/// Tries for one `create_atoms random` position before the region is deemed empty.
const MAX_RANDOM_TRIES: u64 = 10_000_000;

/// The error for creating up to `count` atoms (`what` they are) numbered from `next_id`, if
/// LIGGGHTS cannot number them.
fn too_many_atoms(count: f64, next_id: i64, what: &str) -> Option<String> {
    let last = count + next_id as f64 - 1.0;
    (last.is_nan() || last > MAX_ATOM_ID).then(|| {
        format!(
            "New atom IDs exceed maximum allowed ID: {} {what} (at most {} atoms can be numbered)",
            g(count),
            MAX_ATOM_ID
        )
    })
}

fn displace_atoms(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(2..=usize::MAX, "displace_atoms GROUP move|random ...")?;
    let bit = ctx
        .sim
        .group_bit(a.word(0)?)
        .ok_or_else(|| a.error(0, "Could not find displace_atoms group ID"))?;
    let style = a.word(1)?;
    let nopt = match style {
        "move" => 5,
        "random" => 6,
        other => return Err(a.unsupported(1, &format!("displace_atoms {other}"))),
    };
    let mut scale = 1.0;
    let mut i = nopt;
    while i < a.len() {
        match (a.word(i)?, a.word(i + 1)?) {
            ("units", "box") => scale = 1.0,
            ("units", "lattice") => {
                scale =
                    ctx.sim.lattice.as_ref().map(|l| l.0).ok_or_else(|| {
                        a.error(i + 1, "Use of displace_atoms with undefined lattice")
                    })?
            }
            _ => return Err(a.keyword_error(i, &["units"])),
        }
        i += 2;
    }
    let del = [scale * a.real(2)?, scale * a.real(3)?, scale * a.real(4)?];
    let p = &mut ctx.sim.particles;
    if style == "random" {
        let seed = a.int(5)?;
        if !ctx.sim.seed_tolerant {
            crate::util::random::check_seed(seed).map_err(|m| a.error(5, &m))?;
        }
        if seed <= 0 || seed > i32::MAX as i64 {
            return Err(a.error(5, "Illegal displace_atoms random command"));
        }
        let mut rng = crate::util::random::RanPark::new(seed as i32).map_err(|m| a.error(5, &m))?;
        for k in 0..p.len() {
            if p.mask[k] & bit != 0 {
                rng.reset_at(seed as i32, p.x[k]);
                for (x, shift) in p.x[k].iter_mut().zip(del) {
                    *x += shift * 2.0 * (rng.uniform() - 0.5);
                }
            }
        }
    } else {
        for k in 0..p.len() {
            if p.mask[k] & bit != 0 {
                for (x, shift) in p.x[k].iter_mut().zip(del) {
                    *x += shift;
                }
            }
        }
    }
    let domain = ctx.sim.domain.clone();
    for k in 0..p.len() {
        domain.remap(&mut p.x[k], &mut p.image[k]);
    }
    Ok(())
}

fn delete_atoms(a: &Args, ctx: &mut Ctx) -> Result {
    ctx.reshape_regions(false).map_err(|m| a.error(0, &m))?;
    a.count(
        2..=usize::MAX,
        "delete_atoms group|region ID | overlap CUT G1 G2 [compress yes|no]",
    )?;
    let p = &ctx.sim.particles;
    let remove: Vec<bool> = match a.word(0)? {
        "group" => {
            let bit = ctx
                .sim
                .group_bit(a.word(1)?)
                .ok_or_else(|| a.error(1, "Could not find delete_atoms group ID"))?;
            p.mask.iter().map(|m| m & bit != 0).collect()
        }
        "region" => {
            let r = ctx
                .sim
                .regions
                .find(a.word(1)?)
                .ok_or_else(|| a.error(1, "Could not find delete_atoms region ID"))?;
            p.x.iter().map(|x| ctx.sim.regions.matches(r, *x)).collect()
        }
        "overlap" => {
            a.count(4..=usize::MAX, "delete_atoms overlap CUTOFF GROUP1 GROUP2")?;
            let cut = a.real(1)?;
            let mut bits = [0u32; 2];
            for (k, b) in bits.iter_mut().enumerate() {
                *b = ctx
                    .sim
                    .group_bit(a.word(2 + k)?)
                    .ok_or_else(|| a.error(2 + k, "Could not find delete_atoms group ID"))?;
            }
            if ctx.sys.mode == Mode::Run {
                ctx.out.screen("System init for delete_atoms ...\n");
            }
            if ctx.sim.pair_selection.is_none() {
                return Err(a.error(0, "Delete_atoms requires a pair style be defined"));
            }
            if cut > ctx.sim.neighbor_cutoff() {
                return Err(a.error(1, "Delete_atoms cutoff > neighbor cutoff"));
            }
            ctx.sim
                .overlapping(cut, bits[0], bits[1])
                .map_err(|m| a.error(0, &m))?
        }
        "porosity" => return Err(a.unsupported(0, "delete_atoms porosity")),
        _ => return Err(a.keyword_error(0, &["group", "region", "overlap", "porosity"])),
    };
    let p = &ctx.sim.particles;
    let mut compress = true;
    let mut i = if a.word(0)? == "overlap" { 4 } else { 2 };
    while i < a.len() {
        match a.word(i)? {
            "compress" => compress = a.word_in(i + 1, &["yes", "no"])? == "yes",
            other => return Err(a.unsupported(i, &format!("delete_atoms keyword {other}"))),
        }
        i += 2;
    }
    let before = p.len();
    // as LIGGGHTS: each deleted particle's slot is taken by the last one
    ctx.sim.particles.remove_filling_from_last(&remove);
    let p = &mut ctx.sim.particles;
    if compress {
        // IDs 1..N in memory order (LIGGGHTS's memory order also reflects its spatial sort
        // and the slots filled above)
        for (k, id) in p.id.iter_mut().enumerate() {
            *id = k as i64 + 1;
        }
    }
    let after = p.len();
    ctx.say(&format!(
        "Deleted {} atoms, new total = {after}\n",
        before - after
    ));
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

fn group(a: &Args, ctx: &mut Ctx) -> Result {
    ctx.reshape_regions(false).map_err(|m| a.error(0, &m))?;
    a.count(
        2..=usize::MAX,
        "group ID region|type|id|subtract|union|intersect|delete|clear ...",
    )?;
    let name = a.word(0)?;
    let style = a.word(1)?;
    let mut by_variable = None;
    match style {
        "variable" => by_variable = Some(super::group_variable::selected(a, ctx)?),
        "initialize" => super::group_variable::initialize(a)?,
        _ => {}
    }
    let sim = &mut ctx.sim;
    if style == "delete" {
        if name == "all" {
            return Err(a.error(0, "Cannot delete group all"));
        }
        let bit = sim
            .group_bit(name)
            .ok_or_else(|| a.error(0, "Could not find group delete group ID"))?;
        sim.particles.mask.iter_mut().for_each(|m| *m &= !bit);
        let idx = bit.trailing_zeros() as usize;
        sim.groups[idx] = String::new();
        return Ok(());
    }
    let bit = match sim.group_bit(name) {
        Some(b) => b,
        None => {
            let slot = match sim.groups.iter().position(String::is_empty) {
                Some(s) => s,
                None => {
                    if sim.groups.len() >= 32 {
                        return Err(a.error(0, "Too many groups"));
                    }
                    sim.groups.push(String::new());
                    sim.groups.len() - 1
                }
            };
            sim.groups[slot] = name.to_string();
            1u32 << slot
        }
    };
    let p = &sim.particles;
    let n = p.len();
    let selected: Vec<bool> = match style {
        "clear" => {
            sim.particles.mask.iter_mut().for_each(|m| *m &= !bit);
            return Ok(());
        }
        "region" => {
            let r = sim
                .regions
                .find(a.word(2)?)
                .ok_or_else(|| a.error(2, "Group region ID does not exist"))?;
            (0..n).map(|i| sim.regions.matches(r, p.x[i])).collect()
        }
        "type" | "id" => {
            let values: Vec<i64> = (0..n)
                .map(|i| {
                    if style == "type" {
                        p.kind[i] as i64
                    } else {
                        p.id[i]
                    }
                })
                .collect();
            let op = a.word(2)?;
            let mut sel = vec![false; n];
            // LIGGGHTS 3.8.0 tests only these operators; `==` and `!=` fall through to the
            // list of values, where atoi reads them as 0 (so `type != 1` selects type 1)
            if a.len() > 3 && matches!(op, "<" | ">" | "<=" | ">=" | "<>") {
                let want = if op == "<>" { 5 } else { 4 };
                if a.len() != want {
                    return Err(a.error(2, "Illegal group command"));
                }
                let bound = |k: usize| inumeric(a.word(k)?).map_err(|m| a.error(k, &m));
                let v1 = bound(3)?;
                let v2 = if op == "<>" { bound(4)? } else { 0 };
                sel = values
                    .iter()
                    .map(|&v| match op {
                        "<" => v < v1,
                        ">" => v > v1,
                        "<=" => v <= v1,
                        ">=" => v >= v1,
                        "==" => v == v1,
                        "!=" => v != v1,
                        _ => v >= v1 && v <= v2,
                    })
                    .collect();
                sel
            } else {
                // values and ranges a:b[:step], read with C's atoi as LIGGGHTS does
                let atoi = |t: &str| crate::util::numbers::c_atof(t).trunc() as i64;
                for k in 2..a.len() {
                    let w = a.word(k)?;
                    let parts: Vec<&str> = w.split(':').collect();
                    let (lo, hi, step) = if parts.len() > 1 {
                        let step = parts.get(2).map_or(1, |t| atoi(t));
                        (atoi(parts[0]), atoi(parts[1]), step)
                    } else {
                        (atoi(w), atoi(w), 1)
                    };
                    if step == 0 {
                        return Err(a.error(k, "Illegal group command"));
                    }
                    for (s, v) in sel.iter_mut().zip(&values) {
                        *s |= *v >= lo && *v <= hi && (*v - lo) % step == 0;
                    }
                }
                sel
            }
        }
        // a dry run that cannot evaluate the variable selects nobody
        "variable" => by_variable.flatten().unwrap_or_else(|| vec![false; n]),
        "initialize" => vec![false; n],
        "subtract" | "union" | "intersect" => {
            let mut bits = Vec::new();
            for k in 2..a.len() {
                bits.push(
                    sim.group_bit(a.word(k)?)
                        .ok_or_else(|| a.error(k, "Group ID does not exist"))?,
                );
            }
            let m = &p.mask;
            (0..n)
                .map(|i| match style {
                    "subtract" => m[i] & bits[0] != 0 && bits[1..].iter().all(|b| m[i] & b == 0),
                    "union" => bits.iter().any(|b| m[i] & b != 0),
                    _ => bits.iter().all(|b| m[i] & b != 0),
                })
                .collect()
        }
        _ => {
            return Err(a.keyword_error(
                1,
                &[
                    "region",
                    "type",
                    "id",
                    "subtract",
                    "union",
                    "intersect",
                    "variable",
                    "initialize",
                    "delete",
                    "clear",
                ],
            ))
        }
    };
    let mut count = 0;
    for (m, s) in sim.particles.mask.iter_mut().zip(&selected) {
        if *s {
            *m |= bit;
        }
        if *m & bit != 0 {
            count += 1;
        }
    }
    ctx.say(&format!("{count} atoms in group {name}\n"));
    Ok(())
}

fn velocity(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(2..=usize::MAX, "velocity GROUP set|zero|ramp ...")?;
    let bit = ctx
        .sim
        .group_bit(a.word(0)?)
        .ok_or_else(|| a.error(0, "Could not find velocity group ID"))?;
    // a check cannot know atoms that insertion fixes would have added by now
    if ctx.sim.particles.is_empty() && !(ctx.sys.mode == Mode::Check && ctx.sim.inserts_atoms) {
        return Err(a.error(0, "Velocity command with no atoms existing"));
    }
    let style = a.word(1)?;
    let first_option = match style {
        "set" => 5,
        "ramp" => 8,
        "zero" => 3,
        "create" => {
            return Err(a
                .error(1, "Illegal velocity command")
                .with_help("LIGGGHTS 3.8.0 has velocity set, ramp and zero"))
        }
        other => {
            return Err(a
                .keyword_error(1, &["set", "ramp", "zero"])
                .with_help(format!("velocity {other}")))
        }
    };
    a.count(
        first_option..=usize::MAX,
        "velocity GROUP set VX VY VZ | ramp VDIM VLO VHI DIM CLO CHI | zero linear|angular",
    )?;
    // options (LIGGGHTS's defaults: units box, sum no)
    let (mut sum, mut lattice_units) = (false, false);
    let mut i = first_option;
    while i < a.len() {
        match a.word(i)? {
            "sum" => sum = a.word_in(i + 1, &["yes", "no"])? == "yes",
            "units" => lattice_units = a.word_in(i + 1, &["box", "lattice"])? == "lattice",
            "dist" => {
                a.word_in(i + 1, &["uniform", "gaussian"])?;
            }
            "mom" | "rot" => {
                a.word_in(i + 1, &["yes", "no"])?;
            }
            "loop" => {
                a.word_in(i + 1, &["all", "local", "geom"])?;
            }
            "rigid" => return Err(a.unsupported(i, "velocity rigid")),
            _ => return Err(a.error(i, "Illegal velocity command")),
        }
        i += 2;
    }
    let scale = if lattice_units {
        match &ctx.sim.lattice {
            Some((spacing, _)) => *spacing,
            None => return Err(a.error(0, "Use of velocity with undefined lattice")),
        }
    } else {
        1.0
    };
    if style == "set" && (2..5).any(|d| a.word(d).is_ok_and(|w| w.starts_with("v_"))) {
        return super::velocity_vars::set(a, ctx, bit, sum, scale);
    }
    let sim = &mut *ctx.sim;
    match style {
        "set" => {
            let mut v = [None; 3];
            for (d, slot) in v.iter_mut().enumerate() {
                let w = a.word(2 + d)?;
                if w != "NULL" {
                    if w.starts_with("v_") {
                        return Err(a.unsupported(2 + d, "velocity set with variables"));
                    }
                    *slot = Some(scale * a.real(2 + d)?);
                }
            }
            let p = &mut sim.particles;
            for k in 0..p.len() {
                if p.mask[k] & bit != 0 {
                    for (d, component) in v.iter().enumerate() {
                        if let Some(value) = *component {
                            if sum {
                                p.v[k][d] += value;
                            } else {
                                p.v[k][d] = value;
                            }
                        }
                    }
                }
            }
        }
        "ramp" => {
            let dim = |k: usize, names: &[&str]| -> std::result::Result<usize, CommandError> {
                let w = a.word(k)?;
                names
                    .iter()
                    .position(|n| *n == w)
                    .ok_or_else(|| a.error(k, "Illegal velocity command"))
            };
            let vdim = dim(2, &["vx", "vy", "vz"])?;
            let (vlo, vhi) = (scale * a.real(3)?, scale * a.real(4)?);
            let cdim = dim(5, &["x", "y", "z"])?;
            let (clo, chi) = (scale * a.real(6)?, scale * a.real(7)?);
            let p = &mut sim.particles;
            for k in 0..p.len() {
                if p.mask[k] & bit != 0 {
                    // max then min as LIGGGHTS's MAX and MIN: a NaN becomes 0, clamp keeps it
                    #[allow(clippy::manual_clamp)]
                    let fraction = ((p.x[k][cdim] - clo) / (chi - clo)).max(0.0).min(1.0);
                    let vramp = vlo + fraction * (vhi - vlo);
                    if sum {
                        p.v[k][vdim] += vramp;
                    } else {
                        p.v[k][vdim] = vramp;
                    }
                }
            }
        }
        _ => {
            let members: Vec<usize> = (0..sim.particles.len())
                .filter(|&k| sim.particles.mask[k] & bit != 0)
                .collect();
            if members.is_empty() {
                return Err(a.error(0, "Cannot zero momentum of no atoms"));
            }
            match a.word_in(2, &["linear", "angular", "angularIndividual"])? {
                "linear" => zero_momentum(sim, &members),
                "angular" => zero_rotation(sim, &members),
                _ => {
                    for &k in &members {
                        sim.particles.omega[k] = [0.0; 3];
                    }
                }
            }
        }
    }
    Ok(())
}

/// `velocity zero linear`: subtract the group's centre-of-mass velocity.
fn zero_momentum(sim: &mut crate::engine::sim::Simulation, members: &[usize]) {
    let p = &mut sim.particles;
    let mass: f64 = members.iter().fold(0.0, |s, &k| s + p.mass[k]);
    let mut vcm = [0.0; 3];
    for &k in members {
        for (c, v) in vcm.iter_mut().zip(p.v[k]) {
            *c += v * p.mass[k];
        }
    }
    if mass > 0.0 {
        for c in &mut vcm {
            *c /= mass;
        }
    }
    for &k in members {
        for (v, c) in p.v[k].iter_mut().zip(vcm) {
            *v -= c;
        }
    }
}

/// `velocity zero angular`: remove the group's rigid rotation about its centre of mass
/// (point masses, unwrapped positions), as LIGGGHTS's group angmom/inertia/omega do.
fn zero_rotation(sim: &mut crate::engine::sim::Simulation, members: &[usize]) {
    let domain = &sim.domain;
    let p = &mut sim.particles;
    let unwrap = |p: &crate::engine::particles::Particles, k: usize| -> [f64; 3] {
        let mut u = [0.0; 3];
        for (d, ud) in u.iter_mut().enumerate() {
            *ud = p.x[k][d] + p.image[k][d] as f64 * domain.length(d);
        }
        u
    };
    let mass: f64 = members.iter().fold(0.0, |s, &k| s + p.mass[k]);
    let mut cm = [0.0; 3];
    for &k in members {
        let u = unwrap(p, k);
        for d in 0..3 {
            cm[d] += u[d] * p.mass[k];
        }
    }
    if mass > 0.0 {
        for c in &mut cm {
            *c /= mass;
        }
    }
    let mut l = [0.0; 3];
    let mut t = [[0.0; 3]; 3];
    for &k in members {
        let u = unwrap(p, k);
        let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
        let m = p.mass[k];
        let v = p.v[k];
        l[0] += m * (dy * v[2] - dz * v[1]);
        l[1] += m * (dz * v[0] - dx * v[2]);
        l[2] += m * (dx * v[1] - dy * v[0]);
        t[0][0] += m * (dy * dy + dz * dz);
        t[1][1] += m * (dx * dx + dz * dz);
        t[2][2] += m * (dx * dx + dy * dy);
        t[0][1] -= m * dx * dy;
        t[1][2] -= m * dy * dz;
        t[0][2] -= m * dx * dz;
    }
    t[1][0] = t[0][1];
    t[2][1] = t[1][2];
    t[2][0] = t[0][2];
    let w = crate::engine::momentum::omega(l, t);
    for &k in members {
        let u = unwrap(p, k);
        let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
        p.v[k][0] -= w[1] * dz - w[2] * dy;
        p.v[k][1] -= w[2] * dx - w[0] * dz;
        p.v[k][2] -= w[0] * dy - w[1] * dx;
    }
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

/// `read_data FILE`: box, atom types, atoms and velocities of a granular data file.
fn read_data(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "read_data FILE")?;
    if ctx.sim.domain.exists {
        return Err(a.error(0, "Cannot read_data after simulation box is defined"));
    }
    let name = a.word(0)?;
    let text = if name.ends_with(".gz") {
        crate::io::diff::read_text(&ctx.sys.resolve(name).to_string_lossy())
            .map_err(|e| e.to_string())
    } else {
        ctx.sys.read(name).map_err(|e| e.to_string())
    }
    .map_err(|m| a.file_error(0, format!("Cannot open file {name}: {m}")))?;
    let data = crate::io::data::parse(&text, name).map_err(|m| a.error(0, &m))?;
    crate::engine::checks::check_ntypes(data.ntypes as i64)
        .map_err(|m| a.error(0, format!("{name}: {m}")))?;
    let sim = &mut *ctx.sim;
    sim.domain.create(data.lo, data.hi);
    sim.ntypes = data.ntypes;
    for atom in &data.atoms {
        let mut x = atom.x;
        let mut image = atom.image;
        for d in 0..3 {
            let inside = x[d] >= data.lo[d] && x[d] < data.hi[d];
            if !inside && !sim.domain.periodic(d) {
                return Err(a.error(
                    0,
                    format!(
                        "Did not assign all atoms correctly: {name}: atom {} at ({}, {}, {}) lies outside the box",
                        atom.id, x[0], x[1], x[2]
                    ),
                ));
            }
        }
        sim.domain.remap(&mut x, &mut image);
        sim.particles
            .push(atom.id, atom.kind, x, 0.5 * atom.diameter, atom.density);
        let i = sim.particles.len() - 1;
        let p = &mut sim.particles;
        p.image[i] = image;
        p.v[i] = atom.v;
        p.omega[i] = atom.omega;
        if atom.diameter == 0.0 {
            p.mass[i] = atom.density; // a point particle's density column is its mass
        }
    }
    let (lo, hi) = (data.lo, data.hi);
    ctx.say(&format!(
        "Reading data file ...\n  orthogonal box = ({} {} {}) to ({} {} {})\n  1 by 1 by 1 MPI processor grid\n  {} atoms\n",
        g(lo[0]),
        g(lo[1]),
        g(lo[2]),
        g(hi[0]),
        g(hi[1]),
        g(hi[2]),
        data.atoms.len()
    ));
    if data.velocities > 0 {
        ctx.say(&format!("  {} velocities\n", data.velocities));
    }
    Ok(())
}

/// `write_data FILE`: the granular data file of the current state, written atomically.
fn write_data(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "write_data FILE")?;
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Write_data command before simulation box is defined"));
    }
    let name = a.word(0)?;
    if ctx.sys.mode != Mode::Run {
        return Ok(());
    }
    // as LIGGGHTS: positions wrapped and the box shrink-wrapped before writing
    ctx.sim.pbc_and_box().map_err(|m| a.error(0, &m))?;
    let text = crate::io::data::write(
        &ctx.sim.particles,
        &ctx.sim.domain,
        ctx.sim.ntypes,
        ctx.sim.step,
        concat!("regolith ", env!("CARGO_PKG_VERSION")),
    );
    let path = ctx.sys.resolve(name).to_string_lossy().into_owned();
    crate::io::write_atomically(&path, text.as_bytes())
        .map_err(|e| a.file_error(0, format!("Cannot open data file {name}: {e}")))
}

/// `read_restart FILE` (a `*` picks the largest step, a `%` the multi-file form).
fn read_restart(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "read_restart FILE")?;
    if ctx.sim.domain.exists {
        return Err(a.error(0, "Cannot read_restart after simulation box is defined"));
    }
    let name = a.word(0)?;
    let mut path = ctx.sys.resolve(name).to_string_lossy().into_owned();
    if path.contains('*') {
        // the largest step on disk, or among the files a dry run's deck wrote before
        let on_disk = crate::io::diff::expand(&path)
            .ok()
            .and_then(|mut v| v.pop());
        let disk_step = on_disk.as_deref().map(step_of_name);
        let kept = ctx.sys.kept_matching(&path).pop();
        path = match (on_disk, kept) {
            (Some(d), Some((k, kept))) => {
                if disk_step.is_some_and(|s| s > k) {
                    d
                } else {
                    kept
                }
            }
            (Some(d), None) => d,
            (None, Some((_, kept))) => kept,
            (None, None) => return Err(a.error(0, "Found no restart file matching pattern")),
        };
    }
    let r = match ctx.sys.kept_binary(std::path::Path::new(&path)) {
        // check mode: a restart this deck wrote earlier (periodic output holds its own step)
        Some(kept) => crate::io::restart::Restart::parse(&kept.bytes, &path, None).map(|mut r| {
            if let Some(step) = kept.step {
                r.set_step(step);
            }
            r
        }),
        None => crate::io::restart::read(&path),
    }
    // the file as the deck names it (not the folder it was resolved against)
    .map_err(|e| a.error(0, e.to_string().replace(&path, name)))?;
    ctx.say("Reading restart file ...\n");
    let pair = ctx.sim.load_restart(&r).map_err(|m| a.error(0, &m))?;
    ctx.sim.restart_in_progress = !r.global_fixes.is_empty() || !r.peratom_fixes.is_empty();
    ctx.sim.extras.restart_peratom_fixes = r.peratom_fixes.len();
    ctx.sim.restart_fixes = r.global_fixes.clone();
    ctx.sim.restart_peratom = r
        .peratom_fixes
        .iter()
        .map(|f| (f.id.clone(), f.style.clone()))
        .collect();
    let line = format!(
        "{}  1 by 1 by 1 MPI processor grid\n  {} atoms\n",
        super::change_box::orthogonal_box_line(ctx.sim.domain.lo, ctx.sim.domain.hi),
        ctx.sim.particles.len()
    );
    ctx.say(&line);
    // the pair style stored in the file, as LIGGGHTS recreates it (decks usually repeat it)
    if let Some(words) = pair {
        for text in [format!("pair_style {words}"), "pair_coeff * *".to_string()] {
            let words = crate::script::line::split_words(&text)
                .map_err(|_| a.error(0, "restart: bad stored pair style"))?;
            let cmd = crate::commands::CommandLine {
                words,
                text: text.clone(),
                location: a.cmd.location.clone(),
            };
            let args = Args { cmd: &cmd };
            if let Some(run) = registry::handler(cmd.name()) {
                run(&args, ctx).map_err(|e| CommandError::Reported(e.into_diagnostic(&cmd)))?;
            }
        }
    }
    Ok(())
}

/// The step in a restart file's name: its last run of digits (0 if none).
fn step_of_name(path: &str) -> i64 {
    let name = path.rsplit('/').next().unwrap_or(path);
    let digits: Vec<char> = name
        .chars()
        .rev()
        .skip_while(|c| !c.is_ascii_digit())
        .take_while(|c| c.is_ascii_digit())
        .collect();
    digits.iter().rev().collect::<String>().parse().unwrap_or(0)
}

/// `write_restart FILE`: the current state, atomically, after wrapping positions and the
/// box as LIGGGHTS does.
fn write_restart(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "write_restart FILE")?;
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Write_restart command before simulation box is defined"));
    }
    let path = ctx.sys.resolve(a.word(0)?).to_string_lossy().into_owned();
    let path = path.replace('*', &ctx.sim.step.to_string());
    ctx.sim.check_restart_size().map_err(|m| a.error(0, &m))?;
    if ctx.sys.mode != Mode::Run {
        // check mode: keep the file in memory for a later read_restart of the same deck
        let partners = ctx.sim.contact_partners();
        let bytes = ctx.sim.to_restart(&partners).to_bytes();
        ctx.sys.keep_binary(std::path::Path::new(&path), bytes);
        return Ok(());
    }
    ctx.sim.save_restart(&path).map_err(|m| a.error(0, &m))
}

/// `restart 0` | `restart N ROOT` (`*` becomes the step; without one, `.STEP` is
/// appended) | `restart N FILE1 FILE2` (written in turn).
fn restart(a: &Args, ctx: &mut Ctx) -> Result {
    use crate::engine::sim::RestartOutput;
    a.count(1..=3, "restart 0 | restart N ROOT | restart N FILE1 FILE2")?;
    if a.word(0)?.starts_with("v_") {
        return Err(a.unsupported(0, "restart with a variable interval"));
    }
    let every = a.int(0)?;
    if every == 0 {
        if a.len() != 1 {
            return Err(a.error(0, "Illegal restart command"));
        }
        ctx.sim.restart_output = [None, None];
        return Ok(());
    }
    if every < 0 || a.len() == 1 {
        return Err(a.error(0, "Illegal restart command"));
    }
    let resolve = |w: &str| ctx.sys.resolve(w).to_string_lossy().into_owned();
    let files = if a.len() == 2 {
        let mut root = resolve(a.word(1)?);
        if !root.contains('*') {
            root.push_str(".*");
        }
        vec![root]
    } else {
        vec![resolve(a.word(1)?), resolve(a.word(2)?)]
    };
    let slot = files.len() - 1;
    ctx.sim.restart_output[slot] = Some(RestartOutput {
        every,
        files,
        toggle: 0,
        last: None,
    });
    Ok(())
}
