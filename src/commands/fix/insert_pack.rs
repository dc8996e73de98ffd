//! `fix insert/pack` and `fix insert/rate/region`: particles inserted into a region.

use super::insertion::{keyword, yes, Family, Insertion, Schedule};
use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec, INSERT_KEYWORDS};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStyle, RestoreError};
use crate::engine::insert::{InsertPack, InsertRestart, Target};
use crate::engine::region::Shape;

/// The declared signature of `insert/pack`.
pub const SPEC: Spec = style(
    "fix",
    "insert/pack",
    "fix ID GROUP insert/pack seed SEED distributiontemplate D region R ...",
    INSERT_KEYWORDS,
    "fill a region with particles to a count, mass or volume fraction",
);

/// The declared signature of `insert/rate/region`.
pub const RATE_REGION: Spec = style(
    "fix",
    "insert/rate/region",
    "fix ID GROUP insert/rate/region seed SEED distributiontemplate D nparticles N particlerate R insert_every N region R",
    INSERT_KEYWORDS,
    "insert particles into a region at a rate",
);

/// `fix ID GROUP insert/pack seed S distributiontemplate D [keywords]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    ctx.sim.inserts_atoms = true;
    a.count(
        5..=usize::MAX,
        "fix ID GROUP insert/pack seed S distributiontemplate D region R ...",
    )?;
    let mut pack = PackArgs::new(fix.style == "insert/rate/region", ctx.sim.step);
    let families: [Family<PackArgs>; 5] = [
        |s, a, ctx, i, w| s.common.keyword(a, ctx, i, w),
        PackArgs::placement,
        |s, a, ctx, i, w| s.schedule.keyword(a, ctx, i, w),
        PackArgs::switches,
        PackArgs::rate_keyword,
    ];
    // LIGGGHTS reads the general insertion keywords first, then the region keywords of
    // insert/pack; a general one after those ends insert/pack's parsing, an error there
    let mut own_part = false;
    let mut i = 3;
    while i < a.len() {
        let w = a.word(i)?;
        if OWN.contains(&w) {
            own_part = true;
        } else if own_part {
            let what = if pack.rate_style {
                "unknown keyword or wrong keyword order"
            } else {
                "unknown keyword"
            };
            return Err(a.error(i, format!("Fix {} (id {}): {what}", fix.style, fix.id)));
        }
        match keyword(&mut pack, &families, a, ctx, i, w)? {
            Some(used) => i += used,
            None => return Err(unknown(a, i, w, fix.style)),
        }
    }
    pack.common.check_seeds(a, ctx)?;
    pack.finish(a, ctx, fix)
}

/// insert/pack's own keywords (after the general insertion keywords).
const OWN: &[&str] = &[
    "region",
    "volumefraction_region",
    "particles_in_region",
    "mass_in_region",
    "ntry_mc",
    "warn_region",
    "check_dist_from_subdomain_border",
];

/// The keywords of `fix insert/pack` and `insert/rate/region` as given.
struct PackArgs {
    /// The keywords every insertion fix takes.
    common: Insertion,
    /// The style is `insert/rate/region`.
    rate_style: bool,
    /// `region R`: its index and ID.
    region: Option<(usize, String)>,
    /// `particles_in_region`, `volumefraction_region` or `mass_in_region`.
    target: Option<Target>,
    /// `insert_every N|once` and `start N`.
    schedule: Schedule,
    /// `all_in yes|no`.
    all_in: bool,
    /// `ntry_mc N`.
    ntry_mc: i64,
    /// `check_dist_from_subdomain_border yes|no`.
    check_dist: bool,
    /// `nparticles N` (insert/rate/region).
    nparticles: Option<i64>,
    /// `particlerate R` (particles per time, insert/rate/region).
    particlerate: Option<f64>,
    /// `mass M` (insert/rate/region).
    mass: Option<f64>,
    /// `massrate R` (mass per time, insert/rate/region).
    massrate: Option<f64>,
    /// `nparticles INF` or `mass INF` (insert/rate/region): no end to the insertions.
    unbounded: bool,
}

/// A keyword no family knows: LIGGGHTS's keywords regolith does not run, else the known ones.
fn unknown(a: &Args, i: usize, w: &str, style: &str) -> CommandError {
    if matches!(
        w,
        "set_property" | "compress_tags" | "nparticles" | "mass" | "massrate" | "particlerate"
    ) {
        return a.unsupported(i, &format!("fix {style} {w}"));
    }
    a.keyword_error(
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
    )
}

/// Whether region `k` is one insert/pack fills by itself: a static block, cylinder or wedge.
fn simple_region(ctx: &Ctx, k: usize) -> bool {
    let r = &ctx.sim.regions.list[k];
    !r.is_dynamic()
        && matches!(
            r.shape,
            Shape::Block { .. } | Shape::Cylinder { .. } | Shape::Wedge(_)
        )
}

/// The `region` ID at word `i`: its index and ID, when insert/pack fills such a region.
fn insertion_region(a: &Args, ctx: &Ctx, i: usize) -> Result<(usize, String), CommandError> {
    let r = a.word(i)?;
    let k = ctx
        .sim
        .regions
        .find(r)
        .ok_or_else(|| a.error(i, "Fix insert/pack: region ID does not exist"))?;
    let reg = &ctx.sim.regions.list[k];
    // a tet region (either side: LIGGGHTS refuses `side out` when it draws)
    let tet = matches!(reg.shape, Shape::TetMesh(_));
    let ok = tet
        || reg.interior
            && match &reg.shape {
                Shape::Intersect(m) => m.iter().all(|&k| simple_region(ctx, k)),
                _ => simple_region(ctx, k),
            };
    if !ok {
        return Err(a.unsupported(
            i,
            "fix insert/pack into regions other than blocks, cylinders, wedges and their intersections (side in) and mesh/tet",
        ));
    }
    Ok((k, r.to_string()))
}

impl PackArgs {
    /// LIGGGHTS's defaults at step `step`.
    fn new(rate_style: bool, step: i64) -> PackArgs {
        PackArgs {
            common: Insertion::default(),
            rate_style,
            region: None,
            target: None,
            schedule: Schedule::new(step, true),
            all_in: false,
            ntry_mc: 100000,
            check_dist: true,
            nparticles: None,
            particlerate: None,
            mass: None,
            massrate: None,
            unbounded: false,
        }
    }

    /// Where and how much: `region` and the amount in it.
    fn placement(
        &mut self,
        a: &Args,
        ctx: &Ctx,
        i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        match w {
            "region" => self.region = Some(insertion_region(a, ctx, i + 1)?),
            "particles_in_region" => {
                let n = a.int32(i + 1)?;
                if n <= 0 {
                    return Err(a.error(i + 1, "Fix insert/pack: particles_in_region must be > 0"));
                }
                self.target = Some(Target::Count(n));
            }
            "volumefraction_region" => {
                let f = a.real(i + 1)?;
                if !(0.0..=1.0).contains(&f) {
                    return Err(a.error(
                        i + 1,
                        "Fix insert/pack: volumefraction_region must be between 0 and 1",
                    ));
                }
                self.target = Some(Target::VolumeFraction(f));
            }
            "mass_in_region" => {
                let m = a.real(i + 1)?;
                if m <= 0.0 {
                    return Err(a.error(i + 1, "Fix insert/pack: mass_in_region must be > 0"));
                }
                self.target = Some(Target::Mass(m));
            }
            _ => return Ok(None),
        }
        Ok(Some(2))
    }

    /// The placement switches: `all_in`, `check_dist_from_subdomain_border`, `warn_region`,
    /// `ntry_mc`, `random_distribute`.
    fn switches(
        &mut self,
        a: &Args,
        _ctx: &Ctx,
        i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        match w {
            "all_in" => self.all_in = yes(a, i + 1)?,
            "check_dist_from_subdomain_border" => self.check_dist = yes(a, i + 1)?,
            "warn_region" => {
                yes(a, i + 1)?;
            }
            "ntry_mc" => {
                self.ntry_mc = a.int32(i + 1)?;
                if self.ntry_mc < 1000 {
                    return Err(a.error(i + 1, "Fix insert/pack: ntry_mc must be > 1000"));
                }
            }
            "random_distribute" => {
                if a.word_in(i + 1, &["exact", "uncorrelated"])? == "uncorrelated" {
                    return Err(
                        a.unsupported(i + 1, "fix insert/pack random_distribute uncorrelated")
                    );
                }
            }
            _ => return Ok(None),
        }
        Ok(Some(2))
    }

    /// insert/rate/region's amounts: `nparticles`, `particlerate`, `mass`, `massrate`.
    fn rate_keyword(
        &mut self,
        a: &Args,
        _ctx: &Ctx,
        i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        if !self.rate_style {
            return Ok(None);
        }
        match w {
            // LIGGGHTS reads INF as "no total", leaving the other amount as it was
            "nparticles" | "mass" if a.word(i + 1)? == "INF" => self.unbounded = true,
            "nparticles" => self.nparticles = Some(a.int32(i + 1)?),
            "particlerate" => self.particlerate = Some(a.real(i + 1)?),
            "mass" => self.mass = Some(a.real(i + 1)?),
            "massrate" => self.massrate = Some(a.real(i + 1)?),
            _ => return Ok(None),
        }
        Ok(Some(2))
    }

    /// insert/rate/region's particles per insertion run and rate (particles per time), and
    /// the mass rate when given; LIGGGHTS's errors for amounts given twice or not at all.
    #[allow(clippy::type_complexity)]
    fn rate(
        &self,
        a: &Args,
        ctx: &Ctx,
        id: &str,
        distribution: &str,
    ) -> Result<(Option<(Option<i64>, f64)>, Option<f64>), CommandError> {
        if !self.rate_style {
            return Ok((None, None));
        }
        if self.target.is_some() {
            return Err(a.error(2, "Fix insert/rate/region: particles_in_region, volumefraction_region and mass_in_region are insert/pack keywords"));
        }
        // mass and massrate count in particles of the distribution's expected mass
        let mass_expect = ctx
            .sim
            .fixes
            .iter()
            .filter(|f| f.id == distribution)
            .find_map(|f| Some(f.kind.distribution()?.mass_expect))
            .unwrap_or(1.0);
        let (nparticles, mass) = (self.nparticles, self.mass);
        let (particlerate, massrate) = (self.particlerate, self.massrate);
        if nparticles.is_some_and(|n| n > 0) && mass.is_some_and(|m| m > 0.0) {
            return Err(a.error(2, format!("Fix insert/rate/region (id {id}): must not define both 'nparticles' and 'mass'")));
        }
        if particlerate.is_some_and(|r| r > 0.0) && massrate.is_some_and(|r| r > 0.0) {
            return Err(a.error(2, format!("Fix insert/rate/region (id {id}): both 'nflowrate' and 'massflowrate' not allowed")));
        }
        let n = match (nparticles.filter(|&n| n != 0), mass.filter(|&m| m > 0.0)) {
            _ if self.unbounded => None,
            (Some(n), _) => Some(n),
            (None, Some(m)) => Some((m / mass_expect) as i32 as i64),
            (None, None) => {
                return Err(a.error(
                    2,
                    format!(
                    "Fix insert/rate/region (id {id}): must define either 'nparticles' or 'mass'"
                ),
                ))
            }
        };
        let mut mass_rate = None;
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
        Ok((Some((n, r)), mass_rate))
    }

    /// The fix from the keywords, after LIGGGHTS's checks of what they must define.
    fn finish(self, a: &Args, ctx: &Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
        let FixDef { id, style, .. } = *fix;
        let seed = self
            .common
            .seed
            .ok_or_else(|| a.error(2, "Fix insert: have to define 'seed'"))?;
        let distribution = self
            .common
            .distribution
            .clone()
            .ok_or_else(|| a.error(2, "Fix insert: have to define a 'distributiontemplate'"))?;
        let (region, region_id) = self
            .region
            .clone()
            .ok_or_else(|| a.error(2, "Fix insert/pack: must define an insertion region"))?;
        let all_in = self.all_in;
        if all_in && matches!(ctx.sim.regions.list[region].shape, Shape::TetMesh(_)) {
            return Err(a.unsupported(2, &format!("fix {style} all_in yes in a mesh/tet region")));
        }
        if all_in && ctx.sim.regions.has_wedge(region) {
            return Err(a.unsupported(2, &format!("fix {style} all_in yes in a wedge region")));
        }
        let (rate, mass_rate) = self.rate(a, ctx, id, &distribution)?;
        let target = match (rate, self.target) {
            (Some(_), _) => Target::Count(1),
            (None, Some(t)) => t,
            (None, None) => return Err(a.error(2, "Fix insert/pack: must define exactly one keyword out of 'volumefraction_region', 'particles_in_region', and 'mass_in_region'")),
        };
        let every = self
            .schedule
            .every
            .ok_or_else(|| a.error(2, "Fix insert/pack: must define 'insert_every'"))?;
        let clumps = ctx.sim.fixes.iter().any(|f| {
            f.id == distribution
                && f.kind
                    .distribution()
                    .is_some_and(|d| d.templates.iter().any(|t| t.clump.is_some()))
        });
        if clumps && rate.is_some() {
            return Err(a.unsupported(2, &format!("fix {style} of multisphere clumps")));
        }
        let common = self.common;
        Ok(Box::new(InsertPack {
            id: id.to_string(),
            distribution,
            region,
            region_id,
            target,
            every,
            next: Some(self.schedule.start),
            first_step: self.schedule.start,
            overlapcheck: common.overlapcheck,
            all_in,
            maxattempt: common.maxattempt,
            ntry_mc: self.ntry_mc,
            check_dist: self.check_dist,
            verbose: common.verbose,
            velocity: common.velocity,
            omega: common.omega,
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
            random_orientation: common.random_orientation,
        }))
    }
}

/// `insert/pack` and `insert/rate/region` insert at their steps in the run's insertion
/// pass, which finds them by type ([`FixKind::insert_pack`]).
///
/// [`FixKind::insert_pack`]: crate::engine::fixes::FixKind::insert_pack
impl FixStyle for InsertPack {
    fn name(&self) -> &str {
        if self.rate.is_some() {
            "insert/rate/region"
        } else {
            "insert/pack"
        }
    }

    /// The fix generator, the counts so far, the first and the next insertion step.
    fn restart_state(&self) -> Option<Vec<u8>> {
        let state = InsertRestart {
            rng_state: self.rng.state(),
            inserted: self.inserted,
            first_step: self.first_step,
            next: self.next.unwrap_or(0),
            mass: self.inserted_mass,
        };
        Some(state.bytes())
    }

    fn restore_state(&mut self, state: &[u8]) -> Result<(), RestoreError> {
        let r = InsertRestart::parse(state).map_err(|e| RestoreError::Malformed(e.to_string()))?;
        self.rng.reset(r.rng_state)?;
        self.inserted = r.inserted;
        self.inserted_mass = r.mass;
        if r.next != 0 {
            self.next = Some(r.next);
        }
        Ok(())
    }

    fn array_unsupported(&self) -> bool {
        true
    }
}
