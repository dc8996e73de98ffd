//! `processors Px Py Pz [grid ...] [map ...] [part ...] [file ...]` as LIGGGHTS 3.8.0 reads
//! it, and the grid line the box-creating commands print.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::engine::procmap::{self, GridStyle, MapStyle, Processors};

type Result = std::result::Result<(), CommandError>;

/// The map styles that name an axis order (fastest-varying axis first).
const AXES: &[&str] = &["xyz", "xzy", "yxz", "yzx", "zxy", "zyx"];

/// The `processors` command: the settings are kept for the box-creating command.
pub fn processors(a: &Args, ctx: &mut Ctx) -> Result {
    let illegal = |i: usize| a.error(i, "Illegal processors command");
    if ctx.sim.domain.exists {
        return Err(a.error(0, "Processors command after simulation box is defined"));
    }
    a.count(3..=usize::MAX, "processors Px Py Pz [keyword args ...]")?;
    // settings not given here stay as an earlier processors command left them
    let mut p = ctx.sim.procs.clone();
    for d in 0..3 {
        p.user[d] = star_or_int(a, d)?;
    }
    if let Some(d) = (0..3).find(|&d| p.user[d] < 0) {
        return Err(illegal(d));
    }
    let product = p.user.iter().product::<i64>();
    if product != 0 && product != p.nprocs {
        return Err(a.error(0, "Specified processors != physical processors"));
    }
    let mut i = 3;
    while i < a.len() {
        match a.word(i)? {
            "grid" => {
                if i + 2 > a.len() {
                    return Err(illegal(i));
                }
                match a.word(i + 1)? {
                    "onelevel" => p.grid = GridStyle::OneLevel,
                    "twolevel" => {
                        if i + 6 > a.len() {
                            return Err(illegal(i + 1));
                        }
                        let ncores = a.int(i + 2)?;
                        let mut user_cores = [0; 3];
                        for (d, c) in user_cores.iter_mut().enumerate() {
                            *c = star_or_int(a, i + 3 + d)?;
                        }
                        if ncores <= 0 || user_cores.iter().any(|&c| c < 0) {
                            return Err(illegal(i + 2));
                        }
                        p.grid = GridStyle::TwoLevel { ncores, user_cores };
                        i += 4;
                    }
                    "numa" => p.grid = GridStyle::Numa,
                    // LIGGGHTS 3.8.0 compares `grid`, not its argument, with "custom": a
                    // custom grid file is never accepted
                    _ => return Err(illegal(i + 1)),
                }
                i += 2;
            }
            "map" => {
                if i + 2 > a.len() {
                    return Err(illegal(i));
                }
                p.map = match a.word(i + 1)? {
                    "cart" => MapStyle::Cart,
                    "cart/reorder" => MapStyle::CartReorder,
                    w if AXES.contains(&w) => {
                        let b = w.as_bytes();
                        MapStyle::Axes([0, 1, 2].map(|k| usize::from(b[k] - b'x')))
                    }
                    _ => return Err(illegal(i + 1)),
                };
                i += 2;
            }
            "part" => {
                if i + 4 > a.len() {
                    return Err(illegal(i));
                }
                // one partition (the world): there is no other to send to or receive from
                return Err(a.error(
                    i,
                    "Cannot use processors part command without using partitions",
                ));
            }
            "file" => {
                if i + 2 > a.len() {
                    return Err(illegal(i));
                }
                p.file = Some(a.word(i + 1)?.to_string());
                i += 2;
            }
            _ => return Err(a.keyword_error(i, &["grid", "map", "part", "file"])),
        }
    }
    if p.grid == GridStyle::Numa && p.map != MapStyle::Cart {
        return Err(a.error(0, "Processors grid numa and map style are incompatible"));
    }
    ctx.sim.procs = p;
    Ok(())
}

/// `*` (0: chosen by LIGGGHTS) or a count.
fn star_or_int(a: &Args, i: usize) -> std::result::Result<i64, CommandError> {
    match a.word(i)? {
        "*" => Ok(0),
        _ => a.int32(i),
    }
}

/// Choose the grid for the box just created (lengths `prd`, length), as the box-creating
/// command at argument `at` does: the lines LIGGGHTS prints for it (also kept with the
/// command's line), or its error. With `file`, one process writes the mapping of ranks to the
/// grid (with more than one rank the run is refused before it writes anything).
pub fn grid_lines(
    a: &Args,
    ctx: &mut Ctx,
    prd: [f64; 3],
    at: usize,
) -> std::result::Result<String, CommandError> {
    let p: &Processors = &ctx.sim.procs;
    let grid = procmap::choose_grid(p, prd).map_err(|m| a.error(at, m))?;
    let lines = grid.lines();
    if p.nprocs == 1 {
        if let Some(file) = p.file.clone() {
            let text = procmap::mapping_file(p, &grid, &[crate::util::comm::host_name()]);
            ctx.sys
                .write(&file, &text, false)
                .map_err(|_| a.file_error(at, "Cannot open processors output file"))?;
        }
    }
    ctx.sim
        .procs
        .reported
        .push((lines.clone(), Some(a.cmd.location.clone())));
    Ok(lines)
}
