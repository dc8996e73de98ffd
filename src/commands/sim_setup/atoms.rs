//! `create_atoms`, `displace_atoms` and `delete_atoms`.

use super::*;

pub(super) fn create_atoms(a: &Args, ctx: &mut Ctx) -> Result {
    ctx.reshape_regions(false)
        .map_err(|e| a.engine_error(0, e))?;
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
    let planar = ctx.sim.dimension == 2;
    let before = ctx.sim.particles.len();
    let new = NewAtoms {
        kind: kind as u32,
        region,
        next_id: ctx.sim.particles.max_id() + 1,
    };
    let built = match style {
        "random" => new.random(a, ctx)?,
        "single" => new.single(a, ctx, lattice_units)?,
        _ => new.lattice(a, ctx)?,
    };
    if !built {
        // a dry run validates the count but does not build the atoms
        return Ok(());
    }
    if planar {
        // discs: LIGGGHTS gives 2d atoms the mass of their area
        let p = &mut ctx.sim.particles;
        for k in before..p.len() {
            p.mass[k] = crate::engine::planar::disc_mass(p.radius[k], p.density[k]);
        }
    }
    ctx.say(&format!(
        "Created {} atoms\n",
        ctx.sim.particles.len() - before
    ));
    Ok(())
}

/// What `create_atoms` makes: atoms of one type, inside a region or not, numbered on from
/// an ID. Each style gives whether it built the atoms (a dry run of many does not).
struct NewAtoms {
    kind: u32,
    region: Option<usize>,
    next_id: i64,
}

impl NewAtoms {
    /// `random N SEED REGION`: N positions uniform in the box (cut to the region's extent),
    /// redrawn until inside the region, from one Park-Miller stream seeded by the deck.
    fn random(&self, a: &Args, ctx: &mut Ctx) -> std::result::Result<bool, CommandError> {
        let (kind, region, mut next_id) = (self.kind, self.region, self.next_id);
        let d = ctx.sim.domain.clone();
        let planar = ctx.sim.dimension == 2;
        let zmid = d.lo[2] + 0.5 * (d.hi[2] - d.lo[2]);
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
        too_many_atoms(count as f64, next_id, "atoms requested")
            .map_err(|e| a.error(2, e.to_string()))?;
        if ctx.sys.mode == Mode::Check && count as f64 > CHECK_BUILD_LIMIT {
            // a dry run validates the count but does not build the atoms
            ctx.sim.inserts_atoms = true;
            return Ok(false);
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
                let mut x = [
                    lo[0] + rng.uniform() * (hi[0] - lo[0]),
                    lo[1] + rng.uniform() * (hi[1] - lo[1]),
                    lo[2] + rng.uniform() * (hi[2] - lo[2]),
                ];
                if planar {
                    // in 2d every atom sits at the box's mid-plane (its z was drawn all the same)
                    x[2] = zmid;
                }
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
            ctx.sim.particles.push(next_id, kind, x, 0.5, 1.0);
            next_id += 1;
        }
        Ok(true)
    }

    /// `single X Y Z`: one atom, if inside the box (lattice units unless `units box`).
    fn single(
        &self,
        a: &Args,
        ctx: &mut Ctx,
        lattice_units: bool,
    ) -> std::result::Result<bool, CommandError> {
        let (kind, next_id) = (self.kind, self.next_id);
        let d = ctx.sim.domain.clone();
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
            ctx.sim.particles.push(next_id, kind, x, 0.5, 1.0);
        }
        Ok(true)
    }

    /// `box` or `region ID`: the lattice points in the box (and the region).
    fn lattice(&self, a: &Args, ctx: &mut Ctx) -> std::result::Result<bool, CommandError> {
        let (kind, region, mut next_id) = (self.kind, self.region, self.next_id);
        let d = ctx.sim.domain.clone();
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
        too_many_atoms(points, next_id, "lattice points in the box")
            .map_err(|e| a.error(1, e.to_string()))?;
        if ctx.sys.mode == Mode::Check && points > CHECK_BUILD_LIMIT {
            // a dry run validates the count but does not build the atoms
            ctx.sim.inserts_atoms = true;
            return Ok(false);
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
                        ctx.sim.particles.push(next_id, kind, x, 0.5, 1.0);
                        next_id += 1;
                    }
                }
            }
        }
        Ok(true)
    }
}

/// LIGGGHTS numbers atoms with ints: IDs beyond this are refused.
pub(super) const MAX_ATOM_ID: f64 = 2_147_483_647.0;

/// Check mode validates `create_atoms` counts above this but does not build the atoms.
pub(super) const CHECK_BUILD_LIMIT: f64 = 2.0e6;

/// Tries for one `create_atoms random` position before the region is deemed empty.
pub(super) const MAX_RANDOM_TRIES: u64 = 10_000_000;

/// More atoms asked for than LIGGGHTS's int IDs can number.
#[derive(Debug, thiserror::Error)]
#[error("New atom IDs exceed maximum allowed ID: {count} {what} (at most {MAX_ATOM_ID} atoms can be numbered)")]
pub(super) struct TooManyAtoms {
    /// How many were asked for, as LIGGGHTS prints it.
    count: String,
    /// What they are ("atoms requested", "lattice points in the box").
    what: &'static str,
}

/// Can up to `count` atoms (`what` they are) be numbered from `next_id`?
pub(super) fn too_many_atoms(
    count: f64,
    next_id: i64,
    what: &'static str,
) -> std::result::Result<(), TooManyAtoms> {
    let last = count + next_id as f64 - 1.0;
    if last.is_nan() || last > MAX_ATOM_ID {
        return Err(TooManyAtoms {
            count: g(count),
            what,
        });
    }
    Ok(())
}

pub(super) fn displace_atoms(a: &Args, ctx: &mut Ctx) -> Result {
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

pub(super) fn delete_atoms(a: &Args, ctx: &mut Ctx) -> Result {
    ctx.reshape_regions(false)
        .map_err(|e| a.engine_error(0, e))?;
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
            crate::commands::system_init::system_init(a, ctx, Some("delete_atoms"))?;
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
    ctx.sim.remove_between_runs(&remove);
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
