//! `change_box GROUP ...`: box bounds (`x|y|z final|delta|scale|volume`, lengths in box or
//! lattice units), boundary conditions, `set` and `remap` of the group's atoms, applied one
//! after another in LIGGGHTS 3.8.0's order: atoms wrapped and the box shrink-wrapped first,
//! each operation followed by LIGGGHTS's `set_initial_box` (padding of `s` faces, new limits
//! of `m` faces), and the box shrink-wrapped and atoms wrapped again at the end.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::engine::domain::{Boundary, BoxError};
use crate::engine::sim::Simulation;
use crate::lang::system::Mode;
use crate::util::format::g;

type Result<T = ()> = std::result::Result<T, CommandError>;

/// LIGGGHTS's BIG: the extent of no atoms, which turns a shrink-wrapped box inside out.
const BIG: f64 = 1.0e20;

/// How an `x`, `y` or `z` operation moves the faces (lengths before the units scale).
#[derive(Clone, Copy)]
enum Flavor {
    Final(f64, f64),
    Delta(f64, f64),
    Scale(f64),
}

/// One operation, in the order given.
enum Op {
    /// A dimension's bounds, and up to two dimensions that keep the volume.
    Bounds {
        dim: usize,
        flavor: Flavor,
        volume: [Option<usize>; 2],
    },
    /// A tilt factor (argument index for messages).
    Tilt(usize),
    /// New boundary letters at these argument indices.
    Boundary(usize),
    Ortho,
    /// Argument index for the report.
    Triclinic(usize),
    Set,
    Remap,
}

/// The box state atoms are remapped from: lower corner and inverse lengths.
type Saved = ([f64; 3], [f64; 3]);

fn illegal(a: &Args, i: usize) -> CommandError {
    a.error(i, "Illegal change_box command")
}

/// `change_box GROUP op ... [units box|lattice]`, keyword `force` anywhere among the ops.
pub fn change_box(a: &Args, ctx: &mut Ctx) -> Result {
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Change_box command before simulation box is defined"));
    }
    if ctx.sim.dimension == 2 {
        return Err(a.unsupported(0, "change_box in a 2d simulation"));
    }
    if a.len() < 2 {
        return Err(illegal(a, a.len().saturating_sub(1)).with_help(
            "change_box GROUP x|y|z final|delta|scale|volume ... boundary X Y Z | set | remap ... [units box|lattice]",
        ));
    }
    if ctx.sys.mode == Mode::Run {
        ctx.out.screen("Changing box ...\n");
    }
    let group = ctx
        .sim
        .group_bit(a.word(0)?)
        .ok_or_else(|| a.error(0, "Could not find change_box group ID"))?;
    let (ops, force, next) = parse_ops(a)?;
    if ctx.sim.extras.restart_peratom_fixes > 0 && !force {
        return Err(a
            .error(
                0,
                "Cannot change_box after reading restart file with per-atom info",
            )
            .with_help("LIGGGHTS allows it with the keyword force at the end of the operations"));
    }
    if ops.is_empty() {
        return Err(illegal(a, next.min(a.len() - 1)));
    }
    let mut lattice_units = false;
    let mut i = next;
    while i < a.len() {
        if a.word(i)? != "units" || i + 1 >= a.len() {
            return Err(illegal(a, i));
        }
        lattice_units = match a.word(i + 1)? {
            "box" => false,
            "lattice" => true,
            _ => return Err(illegal(a, i + 1)),
        };
        i += 2;
    }
    // LIGGGHTS scales every length once any bounds or tilt operation is given in lattice units
    // (no lattice: a spacing of 1)
    let scaled = lattice_units
        && ops
            .iter()
            .any(|op| matches!(op, Op::Bounds { .. } | Op::Tilt(_)));
    let scale = if scaled {
        ctx.sim.lattice.as_ref().map_or(1.0, |l| l.0)
    } else {
        1.0
    };
    apply(a, ctx, &ops, group, scale)
}

/// The operations, whether `force` was given, and the index of the first word after them.
fn parse_ops(a: &Args) -> Result<(Vec<Op>, bool, usize)> {
    let mut ops: Vec<Op> = Vec::new();
    let mut force = false;
    let mut i = 1;
    while i < a.len() {
        match a.word(i)? {
            "x" | "y" | "z" => i = bounds_op(a, i, &mut ops)?,
            "xy" | "xz" | "yz" => {
                match a.word(i + 1)? {
                    "final" | "delta" => {
                        a.real(i + 2)?;
                    }
                    _ => return Err(illegal(a, i + 1)),
                }
                ops.push(Op::Tilt(i));
                i += 3;
            }
            "boundary" => {
                if i + 3 >= a.len() {
                    return Err(illegal(a, a.len() - 1));
                }
                ops.push(Op::Boundary(i + 1));
                i += 4;
            }
            "ortho" => {
                ops.push(Op::Ortho);
                i += 1;
            }
            "triclinic" => {
                ops.push(Op::Triclinic(i));
                i += 1;
            }
            "set" => {
                ops.push(Op::Set);
                i += 1;
            }
            "remap" => {
                ops.push(Op::Remap);
                i += 1;
            }
            "force" => {
                force = true;
                i += 1;
            }
            _ => break,
        }
    }
    Ok((ops, force, i))
}

/// `x|y|z final LO HI`, `delta DLO DHI`, `scale F` or `volume` at word `i`: the operation
/// added to `ops` (`volume` marks the previous one), and the first word after it.
fn bounds_op(a: &Args, i: usize, ops: &mut Vec<Op>) -> Result<usize> {
    let dim = (a.word(i)?.as_bytes()[0] - b'x') as usize;
    if i + 2 > a.len() {
        return Err(illegal(a, i));
    }
    let flavor = match a.word(i + 1)? {
        "final" | "delta" => {
            if i + 3 >= a.len() {
                return Err(illegal(a, a.len() - 1));
            }
            let (u, v) = (a.real(i + 2)?, a.real(i + 3)?);
            if a.word(i + 1)? == "final" {
                Flavor::Final(u, v)
            } else {
                Flavor::Delta(u, v)
            }
        }
        "scale" => {
            if i + 2 >= a.len() {
                return Err(illegal(a, a.len() - 1));
            }
            Flavor::Scale(a.real(i + 2)?)
        }
        "volume" => {
            keep_volume(a, i, dim, ops)?;
            return Ok(i + 2);
        }
        _ => return Err(illegal(a, i + 1)),
    };
    ops.push(Op::Bounds {
        dim,
        flavor,
        volume: [None, None],
    });
    Ok(i + match flavor {
        Flavor::Scale(_) => 3,
        _ => 4,
    })
}

/// `x|y|z volume` at word `i`: dimension `dim` changes so that the previous operation (on
/// another dimension, at most two in a row) keeps the box's volume.
fn keep_volume(a: &Args, i: usize, dim: usize, ops: &mut [Op]) -> Result<()> {
    let prev =
        match ops.last_mut() {
            Some(Op::Bounds {
                dim: d, volume: v, ..
            }) if *d != dim && v[1].is_none() => v,
            _ => return Err(a
                .error(i + 1, "Change_box volume used incorrectly")
                .with_help(
                "volume follows an x, y or z operation on another dimension (at most two in a row)",
            )),
        };
    if prev[0].is_none() {
        prev[0] = Some(dim);
    } else {
        prev[1] = Some(dim);
    }
    Ok(())
}

/// The box state remap converts from.
fn saved(sim: &Simulation) -> Saved {
    let d = &sim.domain;
    (d.lo, [0, 1, 2].map(|k| 1.0 / (d.hi[k] - d.lo[k])))
}

/// LIGGGHTS's `reset_box`: shrink-wrap `s`/`m` faces around the atoms and mesh nodes (an
/// empty extent turns an `s` face inside out: "Illegal simulation box").
fn reset_box(sim: &mut Simulation) -> std::result::Result<(), BoxError> {
    if !sim.domain.shrinks() {
        return Ok(());
    }
    let mut lo = [BIG; 3];
    let mut hi = [-BIG; 3];
    let nodes =
        crate::engine::fixes::meshes(&sim.fixes).flat_map(|(_, m)| m.triangles().iter().flatten());
    let placed = sim
        .particles
        .x
        .iter()
        .filter(|x| x.iter().all(|c| c.is_finite()));
    for x in placed.chain(nodes) {
        for d in 0..3 {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    sim.domain.shrink_wrap(lo, hi)
}

/// Wrap every atom into the periodic directions (LIGGGHTS's pbc and remap).
fn wrap_atoms(sim: &mut Simulation) {
    let p = &mut sim.particles;
    for i in 0..p.len() {
        sim.domain.remap(&mut p.x[i], &mut p.image[i]);
    }
}

fn print_box(ctx: &mut Ctx) {
    let line = orthogonal_box_line(ctx.sim.domain.lo, ctx.sim.domain.hi);
    ctx.say(&line);
}

/// LIGGGHTS's `  orthogonal box = (lo) to (hi)` line, lengths in box units.
pub(crate) fn orthogonal_box_line(lo: [f64; 3], hi: [f64; 3]) -> String {
    format!(
        "  orthogonal box = ({} {} {}) to ({} {} {})\n",
        g(lo[0]),
        g(lo[1]),
        g(lo[2]),
        g(hi[0]),
        g(hi[1]),
        g(hi[2])
    )
}

fn apply(a: &Args, ctx: &mut Ctx, ops: &[Op], group: u32, scale: f64) -> Result {
    let at_box = |e: BoxError| a.error(0, e.to_string());
    wrap_atoms(ctx.sim);
    reset_box(ctx.sim).map_err(at_box)?;
    let mut from = saved(ctx.sim);
    for op in ops {
        match *op {
            Op::Bounds {
                dim,
                flavor,
                volume,
            } => {
                let d = &mut ctx.sim.domain;
                let before = d.length(0) * d.length(1) * d.length(2);
                match flavor {
                    Flavor::Final(lo, hi) => {
                        d.lo[dim] = scale * lo;
                        d.hi[dim] = scale * hi;
                    }
                    Flavor::Delta(lo, hi) => {
                        d.lo[dim] += scale * lo;
                        d.hi[dim] += scale * hi;
                    }
                    Flavor::Scale(f) => stretch(&mut d.lo[dim], &mut d.hi[dim], f),
                }
                if let Some(first) = volume[0] {
                    d.reset_initial().map_err(at_box)?;
                    let now = (d.hi[0] - d.lo[0]) * (d.hi[1] - d.lo[1]) * (d.hi[2] - d.lo[2]);
                    let ratio = before / now;
                    match volume[1] {
                        None => stretch(&mut d.lo[first], &mut d.hi[first], ratio),
                        Some(second) => {
                            for k in [first, second] {
                                stretch(&mut d.lo[k], &mut d.hi[k], ratio.sqrt());
                            }
                        }
                    }
                }
                d.reset_initial().map_err(at_box)?;
                print_box(ctx);
            }
            Op::Tilt(i) => {
                return Err(a.error(i, "Cannot change box tilt factors for orthogonal box"))
            }
            Op::Boundary(i) => set_boundary(a, ctx.sim, i)?,
            Op::Ortho | Op::Triclinic(_) => {
                if !ctx.sim.dumps.is_empty() {
                    return Err(a.error(0, "Cannot change box ortho/triclinic with dumps defined"));
                }
                if let Op::Triclinic(i) = *op {
                    return Err(a.unsupported(i, "change_box triclinic"));
                }
                ctx.sim.domain.reset_initial().map_err(at_box)?;
                print_box(ctx);
            }
            Op::Set => from = saved(ctx.sim),
            Op::Remap => {
                let (lo0, inv0) = from;
                let d = &ctx.sim.domain;
                let (lo1, len1) = (d.lo, [0, 1, 2].map(|k| d.length(k)));
                let p = &mut ctx.sim.particles;
                for i in (0..p.len()).filter(|&i| p.mask[i] & group != 0) {
                    for k in 0..3 {
                        let lamda = inv0[k] * (p.x[i][k] - lo0[k]);
                        p.x[i][k] = len1[k] * lamda + lo1[k];
                    }
                }
                from = saved(ctx.sim);
            }
        }
    }
    reset_box(ctx.sim).map_err(at_box)?;
    wrap_atoms(ctx.sim);
    reset_box(ctx.sim).map_err(at_box)?;
    Ok(())
}

/// Scale the length of `lo`..`hi` by `f` about its midpoint, as LIGGGHTS rounds it.
fn stretch(lo: &mut f64, hi: &mut f64, f: f64) {
    let mid = 0.5 * (*lo + *hi);
    let delta = *lo - mid;
    *lo = mid + f * delta;
    let delta = *hi - mid;
    *hi = mid + f * delta;
}

/// `boundary X Y Z` at argument `i`: a direction turned non-periodic forgets its image
/// counts.
fn set_boundary(a: &Args, sim: &mut Simulation, i: usize) -> Result {
    let mut new = sim.domain.boundary;
    for (d, faces) in new.iter_mut().enumerate() {
        let word = a.word(i + d)?.as_bytes();
        for (side, face) in faces.iter_mut().enumerate() {
            let c = if side == 1 && word.len() > 1 {
                word[1]
            } else {
                word[0]
            };
            *face = match c {
                b'p' => Boundary::Periodic,
                b'f' => Boundary::Fixed,
                b's' => Boundary::Shrink,
                b'm' => Boundary::ShrinkMin,
                _ => {
                    return Err(illegal(a, i + d).with_help(
                        "each face is p, f, s or m (one letter for both faces, or two)",
                    ))
                }
            };
        }
    }
    for d in 0..3 {
        if (new[d][0] == Boundary::Periodic) != (new[d][1] == Boundary::Periodic) {
            return Err(a.error(i + d, "Both sides of boundary must be periodic"));
        }
        if sim.domain.boundary[d][1] == Boundary::Periodic && new[d][1] != Boundary::Periodic {
            sim.particles.image.iter_mut().for_each(|im| im[d] = 0);
        }
    }
    sim.domain.boundary = new;
    sim.domain.reset_initial().map_err(|m| a.error(0, &m))
}
