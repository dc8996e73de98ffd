//! `fix insert/pack` and `fix insert/rate/region`: particles inserted into a region.

use super::seed_arg;
use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP insert/pack seed S distributiontemplate D [keywords]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let FixDef { id, style, .. } = *fix;
    ctx.sim.inserts_atoms = true;
    let rate_style = style == "insert/rate/region";
    let (mut nparticles, mut particlerate): (Option<i64>, Option<f64>) = (None, None);
    let (mut mass, mut massrate): (Option<f64>, Option<f64>) = (None, None);
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
    let mut random_orientation = false;
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
                    !r.is_dynamic()
                        && matches!(
                            r.shape,
                            crate::engine::region::Shape::Block { .. }
                                | crate::engine::region::Shape::Cylinder { .. }
                                | crate::engine::region::Shape::Wedge(_)
                        )
                };
                // a tet region (either side: LIGGGHTS refuses `side out` when it draws)
                let tet = matches!(reg.shape, crate::engine::region::Shape::TetMesh(_));
                let ok = tet
                    || reg.interior
                        && match &reg.shape {
                            crate::engine::region::Shape::Intersect(m) => {
                                m.iter().all(|&k| simple(k))
                            }
                            _ => simple(k),
                        };
                if !ok {
                    return Err(a.unsupported(
                        i + 1,
                        "fix insert/pack into regions other than blocks, cylinders, wedges and their intersections (side in) and mesh/tet",
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
                let used;
                (velocity, used) = super::insertion_velocity(a, i)?;
                i += used;
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
            "mass" if rate_style => {
                if a.word(i + 1)? == "INF" {
                    return Err(a.unsupported(i + 1, "fix insert/rate/region mass INF"));
                }
                mass = Some(a.real(i + 1)?);
                i += 2;
            }
            "massrate" if rate_style => {
                massrate = Some(a.real(i + 1)?);
                i += 2;
            }
            "orientation" => {
                random_orientation = super::orientation_arg(a, i)?;
                i += 2;
            }
            w @ ("set_property" | "compress_tags" | "nparticles" | "mass" | "massrate"
            | "particlerate") => return Err(a.unsupported(i, &format!("fix {style} {w}"))),
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
                        "orientation",
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
    if all_in
        && matches!(
            ctx.sim.regions.list[region].shape,
            crate::engine::region::Shape::TetMesh(_)
        )
    {
        return Err(a.unsupported(2, &format!("fix {style} all_in yes in a mesh/tet region")));
    }
    if all_in && ctx.sim.regions.has_wedge(region) {
        return Err(a.unsupported(2, &format!("fix {style} all_in yes in a wedge region")));
    }
    let mut mass_rate = None;
    let rate = if rate_style {
        if target.is_some() {
            return Err(a.error(2, "Fix insert/rate/region: particles_in_region, volumefraction_region and mass_in_region are insert/pack keywords"));
        }
        // mass and massrate count in particles of the distribution's expected mass
        let mass_expect = ctx
            .sim
            .fixes
            .iter()
            .find_map(|f| match &f.kind {
                FixKind::Distribution(d) if f.id == distribution => Some(d.mass_expect),
                _ => None,
            })
            .unwrap_or(1.0);
        if nparticles.is_some_and(|n| n > 0) && mass.is_some_and(|m| m > 0.0) {
            return Err(a.error(2, format!("Fix insert/rate/region (id {id}): must not define both 'nparticles' and 'mass'")));
        }
        if particlerate.is_some_and(|r| r > 0.0) && massrate.is_some_and(|r| r > 0.0) {
            return Err(a.error(2, format!("Fix insert/rate/region (id {id}): both 'nflowrate' and 'massflowrate' not allowed")));
        }
        let n = match (nparticles.filter(|&n| n != 0), mass.filter(|&m| m > 0.0)) {
            (Some(n), _) => n,
            (None, Some(m)) => (m / mass_expect) as i32 as i64,
            (None, None) => {
                return Err(a.error(
                    2,
                    format!(
                    "Fix insert/rate/region (id {id}): must define either 'nparticles' or 'mass'"
                ),
                ))
            }
        };
        let r = match (particlerate.filter(|&r| r != 0.0), massrate.filter(|&r| r != 0.0)) {
            (Some(r), _) => r,
            (None, Some(m)) => {
                mass_rate = Some(m);
                m / mass_expect
            }
            (None, None) => {
                return Err(a.error(2, format!("Fix insert/rate/region (id {id}): must define either 'massrate' or 'particlerate'")))
            }
        };
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
    let clumps = ctx.sim.fixes.iter().any(|f| {
        matches!(&f.kind, FixKind::Distribution(d)
            if f.id == distribution && d.templates.iter().any(|t| t.clump.is_some()))
    });
    if clumps && rate.is_some() {
        return Err(a.unsupported(2, &format!("fix {} of multisphere clumps", fix.style)));
    }
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
        mass_rate,
        per_insertion: 0.0,
        random_orientation,
    })))
}
