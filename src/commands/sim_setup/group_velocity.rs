//! `group` and `velocity`.

use super::*;
use crate::engine::sim::Simulation;

pub(super) fn group(a: &Args, ctx: &mut Ctx) -> Result {
    ctx.reshape_regions(false)
        .map_err(|e| a.engine_error(0, e))?;
    a.count(
        2..=usize::MAX,
        "group ID region|type|id|subtract|union|intersect|delete|clear ...",
    )?;
    let name = a.word(0)?;
    let style = a.word(1)?;
    let mut by_variable = None;
    match style {
        "variable" => by_variable = Some(crate::commands::group_variable::selected(a, ctx)?),
        "initialize" => crate::commands::group_variable::initialize(a)?,
        _ => {}
    }
    let sim = &mut ctx.sim;
    if style == "delete" {
        return delete_group(a, sim, name);
    }
    let bit = group_bit_or_new(a, sim, name)?;
    if style == "clear" {
        sim.particles.mask.iter_mut().for_each(|m| *m &= !bit);
        return Ok(());
    }
    let selected = match style {
        // a dry run that cannot evaluate the variable selects nobody
        "variable" => by_variable
            .flatten()
            .unwrap_or_else(|| vec![false; sim.particles.len()]),
        _ => select(a, sim, style)?,
    };
    let count = add_to_group(&mut sim.particles.mask, &selected, bit);
    ctx.say(&format!("{count} atoms in group {name}\n"));
    Ok(())
}

/// `group ID delete`: group `name` removed from every particle and its slot freed.
fn delete_group(a: &Args, sim: &mut Simulation, name: &str) -> Result {
    if name == "all" {
        return Err(a.error(0, "Cannot delete group all"));
    }
    let bit = sim
        .group_bit(name)
        .ok_or_else(|| a.error(0, "Could not find group delete group ID"))?;
    sim.particles.mask.iter_mut().for_each(|m| *m &= !bit);
    let idx = bit.trailing_zeros() as usize;
    sim.groups[idx] = String::new();
    Ok(())
}

/// The bit of group `name`, defined in the first free slot when it is new (at most 32
/// groups).
fn group_bit_or_new(
    a: &Args,
    sim: &mut Simulation,
    name: &str,
) -> std::result::Result<u32, CommandError> {
    if let Some(b) = sim.group_bit(name) {
        return Ok(b);
    }
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
    Ok(1u32 << slot)
}

/// The particles group style `style` selects (every style but `delete`, `clear` and
/// `variable`), one flag per particle.
fn select(a: &Args, sim: &Simulation, style: &str) -> std::result::Result<Vec<bool>, CommandError> {
    let p = &sim.particles;
    let n = p.len();
    match style {
        "region" => {
            let r = sim
                .regions
                .find(a.word(2)?)
                .ok_or_else(|| a.error(2, "Group region ID does not exist"))?;
            Ok((0..n).map(|i| sim.regions.matches(r, p.x[i])).collect())
        }
        "type" => select_by_number(a, &p.kind.iter().map(|&k| k as i64).collect::<Vec<_>>()),
        "id" => select_by_number(a, &p.id),
        "initialize" => Ok(vec![false; n]),
        "subtract" | "union" | "intersect" => combine_groups(a, sim, style),
        _ => Err(a.keyword_error(
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
        )),
    }
}

/// `group ID subtract|union|intersect G1 G2 ...`: the particles in the first group but
/// none of the others, in any of the groups, or in all of them.
fn combine_groups(
    a: &Args,
    sim: &Simulation,
    style: &str,
) -> std::result::Result<Vec<bool>, CommandError> {
    let mut bits = Vec::new();
    for k in 2..a.len() {
        bits.push(
            sim.group_bit(a.word(k)?)
                .ok_or_else(|| a.error(k, "Group ID does not exist"))?,
        );
    }
    let m = &sim.particles.mask;
    Ok((0..m.len())
        .map(|i| match style {
            "subtract" => m[i] & bits[0] != 0 && bits[1..].iter().all(|b| m[i] & b == 0),
            "union" => bits.iter().any(|b| m[i] & b != 0),
            _ => bits.iter().all(|b| m[i] & b != 0),
        })
        .collect())
}

/// Add the `selected` particles to the group of `bit`: the count of particles in the group
/// then.
fn add_to_group(mask: &mut [u32], selected: &[bool], bit: u32) -> usize {
    let mut count = 0;
    for (m, s) in mask.iter_mut().zip(selected) {
        if *s {
            *m |= bit;
        }
        if *m & bit != 0 {
            count += 1;
        }
    }
    count
}

/// `group ID type|id ...`: the particles whose type or ID (`values`) passes the test of the
/// words from 2 on (`< N`, `<> N M`, ..., or values and ranges `A:B[:STEP]`).
fn select_by_number(a: &Args, values: &[i64]) -> std::result::Result<Vec<bool>, CommandError> {
    let op = a.word(2)?;
    let mut sel = vec![false; values.len()];
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
        Ok(sel)
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
            for (s, v) in sel.iter_mut().zip(values) {
                *s |= *v >= lo && *v <= hi && (*v - lo) % step == 0;
            }
        }
        Ok(sel)
    }
}

/// `velocity GROUP set|ramp|zero ...`: the group, the style and its options read as
/// LIGGGHTS reads them, then the style's velocities set.
pub(super) fn velocity(a: &Args, ctx: &mut Ctx) -> Result {
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
    let first_option = velocity_first_option(a, style)?;
    a.count(
        first_option..=usize::MAX,
        "velocity GROUP set VX VY VZ | ramp VDIM VLO VHI DIM CLO CHI | zero linear|angular",
    )?;
    let (sum, lattice_units) = velocity_options(a, first_option)?;
    let scale = if lattice_units {
        match &ctx.sim.lattice {
            Some((spacing, _)) => *spacing,
            None => return Err(a.error(0, "Use of velocity with undefined lattice")),
        }
    } else {
        1.0
    };
    if style == "set" && ctx.sim.dimension == 2 {
        check_planar_set(a)?;
    }
    if style == "set" && (2..5).any(|d| a.word(d).is_ok_and(|w| w.starts_with("v_"))) {
        return crate::commands::velocity_vars::set(a, ctx, bit, sum, scale);
    }
    let sim = &mut *ctx.sim;
    match style {
        "set" => velocity_set(a, sim, bit, sum, scale),
        "ramp" => velocity_ramp(a, sim, bit, sum, scale),
        _ => velocity_zero(a, sim, bit),
    }
}

/// The index of the first option word of velocity style `style` (LIGGGHTS's errors for the
/// styles it lacks).
fn velocity_first_option(a: &Args, style: &str) -> std::result::Result<usize, CommandError> {
    match style {
        "set" => Ok(5),
        "ramp" => Ok(8),
        "zero" => Ok(3),
        "create" => Err(a
            .error(1, "Illegal velocity command")
            .with_help("LIGGGHTS 3.8.0 has velocity set, ramp and zero")),
        other => Err(a
            .keyword_error(1, &["set", "ramp", "zero"])
            .with_help(format!("velocity {other}"))),
    }
}

/// The velocity options from word `first` on: `sum` and lattice `units` (LIGGGHTS's
/// defaults: units box, sum no); the others are checked and take no effect.
fn velocity_options(a: &Args, first: usize) -> std::result::Result<(bool, bool), CommandError> {
    let (mut sum, mut lattice_units) = (false, false);
    let mut i = first;
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
    Ok((sum, lattice_units))
}

/// LIGGGHTS's refusal of a z velocity other than 0 or NULL in a 2d `velocity set`.
fn check_planar_set(a: &Args) -> Result {
    let vz = a.word(4)?;
    if vz.starts_with("v_") {
        return Err(a.error(4, "Cannot set variable z velocity for 2d simulation"));
    }
    if vz != "NULL" && a.real(4)? != 0.0 {
        return Err(a.error(4, "Cannot set non-zero z velocity for 2d simulation"));
    }
    Ok(())
}

/// `velocity GROUP set VX VY VZ` with constants (velocity; NULL leaves a component), scaled
/// by `scale` and added when `sum`.
fn velocity_set(
    a: &Args,
    sim: &mut crate::engine::sim::Simulation,
    bit: u32,
    sum: bool,
    scale: f64,
) -> Result {
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
    Ok(())
}

/// `velocity GROUP ramp VDIM VLO VHI DIM CLO CHI`: the velocity component VDIM from VLO to
/// VHI (velocity) along coordinate DIM from CLO to CHI (length), scaled by `scale`.
fn velocity_ramp(
    a: &Args,
    sim: &mut crate::engine::sim::Simulation,
    bit: u32,
    sum: bool,
    scale: f64,
) -> Result {
    let dim = |k: usize, names: &[&str]| -> std::result::Result<usize, CommandError> {
        let w = a.word(k)?;
        names
            .iter()
            .position(|n| *n == w)
            .ok_or_else(|| a.error(k, "Illegal velocity command"))
    };
    let vdim = dim(2, &["vx", "vy", "vz"])?;
    if vdim == 2 && sim.dimension == 2 {
        return Err(a.error(2, "Velocity ramp in z for a 2d problem"));
    }
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
    Ok(())
}

/// `velocity GROUP zero linear|angular|angularIndividual`.
fn velocity_zero(a: &Args, sim: &mut crate::engine::sim::Simulation, bit: u32) -> Result {
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
    Ok(())
}

/// `velocity zero linear`: subtract the group's centre-of-mass velocity.
pub(super) fn zero_momentum(sim: &mut crate::engine::sim::Simulation, members: &[usize]) {
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
pub(super) fn zero_rotation(sim: &mut crate::engine::sim::Simulation, members: &[usize]) {
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
        crate::engine::momentum::add_inertia(&mut t, [dx, dy, dz], m);
    }
    crate::engine::momentum::mirror_inertia(&mut t);
    let w = crate::engine::momentum::omega(l, t);
    for &k in members {
        let u = unwrap(p, k);
        let (dx, dy, dz) = (u[0] - cm[0], u[1] - cm[1], u[2] - cm[2]);
        p.v[k][0] -= w[1] * dz - w[2] * dy;
        p.v[k][1] -= w[2] * dx - w[0] * dz;
        p.v[k][2] -= w[0] * dy - w[1] * dx;
    }
}
