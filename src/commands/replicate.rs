//! `replicate NX NY NZ offset OX OY OZ [shift SX SY SZ]`: LIGGGHTS 3.8.0's own replicate
//! (not LAMMPS's): the box grows to N times its length from its lower corner (moved by the
//! shift), the particles are shifted, and each copy (i, j, k) in that nesting order is the
//! shifted originals moved by (i OX, j OY, k OZ), with every per-atom value copied and the
//! ID raised by the particle count when the copy began.

use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

type Result = std::result::Result<(), CommandError>;

/// Why regolith does not replicate this simulation yet: per-atom state of fixes and
/// computes that LIGGGHTS copies with the atoms (contact history, start positions, ...).
fn unsupported_state(ctx: &Ctx) -> Option<String> {
    let sim = &ctx.sim;
    if sim.has_run || sim.pending_history.is_some() || !sim.restart_peratom.is_empty() {
        return Some(
            "replicate after a run or a restart file (the copies' contact history and per-atom fix state)"
                .into(),
        );
    }
    for f in &sim.fixes {
        let keeps_state = match &f.kind {
            FixKind::Style(s) => s.keeps_per_atom_state(),
            _ => false,
        };
        if keeps_state {
            return Some(format!(
                "replicate with fix {} ({}) defined (its per-atom state for the copies)",
                f.id, f.style
            ));
        }
    }
    if let Some(c) = sim
        .computes
        .iter()
        .find(|c| c.style().keeps_per_atom_state())
    {
        return Some(format!(
            "replicate with compute {} ({}) defined (its start positions for the copies)",
            c.id, c.style
        ));
    }
    None
}

/// `replicate NX NY NZ offset OX OY OZ [shift SX SY SZ]`, with LIGGGHTS 3.8.0's errors
/// (it wants more than seven words: `shift` or one more word after the offset).
pub fn replicate(a: &Args, ctx: &mut Ctx) -> Result {
    const ILLEGAL: &str = "Illegal replicate command";
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Replicate command before simulation box is defined"));
    }
    if a.len() <= 7 {
        return Err(a
            .error(a.len().saturating_sub(1), ILLEGAL)
            .with_help("replicate NX NY NZ offset OX OY OZ shift SX SY SZ"));
    }
    let int = |i: usize| -> std::result::Result<i64, CommandError> {
        crate::util::numbers::inumeric(a.word(i)?).map_err(|e| a.error(i, e.to_string()))
    };
    let n = [int(0)?, int(1)?, int(2)?];
    if a.word(3)? != "offset" {
        return Err(a.error(3, "Could not find offset keyword in replicate command"));
    }
    let offset = [a.real(4)?, a.real(5)?, a.real(6)?];
    let mut shift = [0.0; 3];
    if a.word(7)? == "shift" {
        if a.len() != 11 {
            return Err(a.error(7, "Invalid replicate command"));
        }
        shift = [a.real(8)?, a.real(9)?, a.real(10)?];
    }
    if n.iter().any(|&k| k <= 0) {
        return Err(a.error(0, ILLEGAL));
    }
    if ctx.sim.dimension == 2 && n[2] != 1 {
        return Err(a.error(2, "Cannot replicate 2d simulation in z dimension"));
    }
    if let Some(what) = unsupported_state(ctx) {
        return Err(a.unsupported(0, &what));
    }
    if ctx.sys.mode == crate::lang::system::Mode::Run {
        // screen only, as LIGGGHTS prints it
        ctx.out.screen("Replicating atoms ...\n");
    }
    if (0..3).any(|d| n[d] > 1 && !ctx.sim.domain.periodic(d)) {
        ctx.say("WARNING: Replicating in a non-periodic dimension\n");
    }
    let box_line = crate::commands::change_box::orthogonal_box_line;
    let domain = &ctx.sim.domain;
    let old_prd = [0, 1, 2].map(|d| domain.length(d));
    let old = box_line(domain.lo, domain.hi);
    ctx.say(&format!("  old: {}", old.trim_start()));
    let domain = &mut ctx.sim.domain;
    for d in 0..3 {
        domain.lo[d] += shift[d];
        domain.hi[d] = domain.lo[d] + n[d] as f64 * old_prd[d];
    }
    let new = box_line(domain.lo, domain.hi);
    ctx.say(&format!("  new: {}", new.trim_start()));
    ctx.sim
        .domain
        .reset_initial()
        .map_err(|e| a.error(0, e.to_string()))?;
    let prd = [0, 1, 2].map(|d| ctx.sim.domain.length(d));
    let grid = crate::commands::processors::grid_lines(a, ctx, prd, 0)?;
    ctx.say(&grid);
    let fin = box_line(ctx.sim.domain.lo, ctx.sim.domain.hi);
    ctx.say(&format!("  fin: {}", fin.trim_start()));
    copy_particles(&mut ctx.sim.particles, n, offset, shift);
    Ok(())
}

/// LIGGGHTS's copying loop: the originals shifted, then one block of copies per (i, j, k)
/// other than (0, 0, 0), i slowest, k fastest.
fn copy_particles(
    p: &mut crate::engine::particles::Particles,
    n: [i64; 3],
    offset: [f64; 3],
    shift: [f64; 3],
) {
    let originals = p.len();
    for x in &mut p.x {
        for d in 0..3 {
            x[d] += shift[d];
        }
    }
    for i in 0..n[0] {
        for j in 0..n[1] {
            for k in 0..n[2] {
                if i + j + k == 0 {
                    continue;
                }
                let first = p.len();
                let step = [i, j, k];
                for l in 0..originals {
                    copy_one(p, l);
                    let c = p.len() - 1;
                    for d in 0..3 {
                        p.x[c][d] += step[d] as f64 * offset[d];
                    }
                    p.id[c] += first as i64;
                }
            }
        }
    }
}

/// Append a copy of particle `l` with all its per-atom values.
fn copy_one(p: &mut crate::engine::particles::Particles, l: usize) {
    p.push(p.id[l], p.kind[l], p.x[l], p.radius[l], p.density[l]);
    let c = p.len() - 1;
    p.mask[c] = p.mask[l];
    p.v[c] = p.v[l];
    p.f[c] = p.f[l];
    p.omega[c] = p.omega[l];
    p.torque[c] = p.torque[l];
    p.mass[c] = p.mass[l];
    p.image[c] = p.image[l];
    for e in &mut p.extra {
        let w = e.width;
        let row: Vec<f64> = e.data[l * w..(l + 1) * w].to_vec();
        e.data[c * w..(c + 1) * w].copy_from_slice(&row);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::particles::Particles;

    #[test]
    fn copies_come_block_by_block_with_raised_ids() {
        let mut p = Particles::default();
        p.push(1, 1, [0.1, 0.2, 0.3], 0.01, 2500.0);
        p.push(2, 1, [0.4, 0.5, 0.6], 0.02, 2500.0);
        p.v[1] = [1.0, 2.0, 3.0];
        copy_particles(&mut p, [2, 2, 1], [1.0, 1.0, 0.0], [0.5, 0.0, 0.0]);
        assert_eq!(p.len(), 8);
        assert_eq!(p.id, vec![1, 2, 3, 4, 5, 6, 7, 8]);
        // block (0, 1, 0) first, then (1, 0, 0), then (1, 1, 0)
        assert_eq!(p.x[2], [0.1 + 0.5, 0.2 + 1.0, 0.3]);
        assert_eq!(p.x[4], [(0.1 + 0.5) + 1.0, 0.2, 0.3]);
        assert_eq!(p.x[7], [(0.4 + 0.5) + 1.0, 0.5 + 1.0, 0.6]);
        assert_eq!(p.v[7], [1.0, 2.0, 3.0]);
        assert_eq!(p.radius[5], 0.02);
    }
}
