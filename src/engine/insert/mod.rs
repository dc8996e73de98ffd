//! Particle insertion as LIGGGHTS 3.8.0 does it (docs/notes/insertion.md): sphere templates,
//! discrete distributions and `fix insert/pack`, with LIGGGHTS's three Park-Miller streams
//! (region: positions and the Monte Carlo region volume; fix: targets and velocities;
//! distribution: leftover particles), its draw order, placement order, overlap rule and
//! messages, so that inserted atoms agree with LIGGGHTS's bit for bit.

use crate::engine::error::EngineError;
use crate::engine::region::{Regions, Shape};
use crate::util::random::RanPark;

mod orient;
mod place;
mod stream;
mod surface;
mod tet;

pub use orient::{random_unit_quat, rotate_axes, Axes};

pub use stream::{
    Face, InsertRestart, InsertStream, Release, TriangleEdges, Within, RELEASE_NAME, RELEASE_WIDTH,
    UNLIMITED,
};
pub use surface::{surface_contacts, surface_exterior, surface_interior};

/// `fix particletemplate/sphere`: one particle kind.
#[derive(Debug, Clone, PartialEq)]
pub struct Template {
    /// Fix ID.
    pub id: String,
    /// Atom type of inserted particles.
    pub atom_type: u32,
    /// Radius (length).
    pub radius: f64,
    /// Density (mass/length^3).
    pub density: f64,
    /// Volume, r^3 4 pi / 3 (length^3).
    pub volume: f64,
    /// Mass (mass).
    pub mass: f64,
    /// State of the template's insertion generator and its Monte Carlo seed (constant
    /// templates never draw; both are kept for restart files).
    pub rng_state: (i32, i32),
    /// A multisphere template: its clump (`radius` is then the bounding-sphere radius).
    pub clump: Option<Box<crate::engine::multisphere::ClumpTemplate>>,
}

impl Template {
    /// A template with LIGGGHTS's volume and mass arithmetic.
    pub fn new(id: &str, atom_type: u32, radius: f64, density: f64) -> Template {
        let volume = radius * radius * radius * 4.0 * std::f64::consts::PI / 3.0;
        Template {
            id: id.to_string(),
            atom_type,
            radius,
            density,
            volume,
            mass: density * volume,
            rng_state: (0, 0),
            clump: None,
        }
    }

    /// A multisphere template: bounding radius, sampled volume and mass of the clump.
    pub fn clump(t: &crate::engine::multisphere::ClumpTemplate) -> Template {
        Template {
            id: t.spec.id.clone(),
            atom_type: t.spec.atom_type,
            radius: t.r_bound,
            density: t.density,
            volume: t.volume,
            mass: t.mass,
            // its insertion generator is untouched until it inserts (the Monte Carlo
            // sampling draws from another one): the seed, as LIGGGHTS's seed check sees it
            rng_state: (t.spec.seed, t.spec.seed),
            clump: Some(Box::new(t.clone())),
        }
    }

    /// Member sphere centres (length) and radii of this template placed at `p` (a clump's
    /// centre of mass, with its principal axes `axes`, the template's if None; a sphere's
    /// centre).
    pub fn spheres_at(&self, p: [f64; 3], axes: Option<&Axes>) -> Vec<([f64; 3], f64)> {
        match &self.clump {
            None => vec![(p, self.radius)],
            Some(c) => {
                let a = axes.unwrap_or(&c.axes);
                let (ex, ey, ez) = (&a[0], &a[1], &a[2]);
                c.displace
                    .iter()
                    .zip(&c.radii)
                    .map(|(d, &r)| {
                        let g = [
                            d[0] * ex[0] + d[1] * ey[0] + d[2] * ez[0],
                            d[0] * ex[1] + d[1] * ey[1] + d[2] * ez[1],
                            d[0] * ex[2] + d[1] * ey[2] + d[2] * ez[2],
                        ];
                        ([p[0] + g[0], p[1] + g[1], p[2] + g[2]], r)
                    })
                    .collect()
            }
        }
    }
}

/// `fix particledistribution/discrete[/numberbased|/massbased]`.
#[derive(Debug, Clone)]
pub struct Distribution {
    /// Its generator (leftover particles).
    pub rng: RanPark,
    /// The templates.
    pub templates: Vec<Template>,
    /// Number fractions.
    pub weights: Vec<f64>,
    /// Templates by decreasing volume (insertion order).
    pub order: Vec<usize>,
    /// Expected volume per particle (length^3).
    pub volume_expect: f64,
    /// Expected mass per particle (mass).
    pub mass_expect: f64,
    /// Largest radius (length).
    pub max_radius: f64,
}

impl Distribution {
    /// From templates and weights (mass fractions unless `number_based`).
    pub fn new(
        seed: i32,
        templates: Vec<Template>,
        weights: &[f64],
        number_based: bool,
    ) -> Result<Distribution, EngineError> {
        let rng = RanPark::new(seed)?;
        let mut s = 0.0;
        for x in weights {
            s += x;
        }
        let mut w: Vec<f64> = weights.iter().map(|x| x / s).collect();
        if !number_based {
            w = w.iter().zip(&templates).map(|(x, t)| x / t.mass).collect();
            let mut s = 0.0;
            for x in &w {
                s += x;
            }
            w = w.iter().map(|x| x / s).collect();
        }
        let (mut volume_expect, mut mass_expect) = (0.0, 0.0);
        for (t, x) in templates.iter().zip(&w) {
            volume_expect += t.volume * x;
            mass_expect += t.mass * x;
        }
        // bubble sort by decreasing volume, as LIGGGHTS orders its templates
        let nt = templates.len();
        let mut order: Vec<usize> = (0..nt).collect();
        let mut n = nt;
        loop {
            let mut swapped = false;
            for i in 0..nt.saturating_sub(1) {
                if templates[order[i]].volume < templates[order[i + 1]].volume {
                    order.swap(i, i + 1);
                    swapped = true;
                }
            }
            n = n.saturating_sub(1);
            if !(swapped && n > 0) {
                break;
            }
        }
        let max_radius = templates.iter().map(|t| t.radius).fold(0.0, f64::max);
        Ok(Distribution {
            rng,
            templates,
            weights: w,
            order,
            volume_expect,
            mass_expect,
            max_radius,
        })
    }

    /// The largest sphere radius of the templates (length): a clump's largest member, not
    /// its bounding radius (LIGGGHTS's `max_rad`).
    pub fn max_sphere_radius(&self) -> f64 {
        self.templates
            .iter()
            .map(|t| match &t.clump {
                Some(c) => c.radii.iter().copied().fold(0.0, f64::max),
                None => t.radius,
            })
            .fold(0.0, f64::max)
    }

    /// The templates of `n` particles, largest first (`random_distribute exact`); LIGGGHTS's
    /// "Failed to allocate" when the list and the particles placed from it cannot fit in
    /// memory.
    pub fn list(&mut self, n: i64) -> Result<Vec<usize>, EngineError> {
        // a template index now, a placed particle (template, position, velocity) later
        crate::engine::checks::allocation(n as f64, 8 + 56, "insertion list")?;
        let nt = self.templates.len();
        let mut count: Vec<i64> = self.weights.iter().map(|w| (n as f64 * w) as i64).collect();
        let rem: Vec<f64> = (0..nt)
            .map(|i| n as f64 * self.weights[i] - count[i] as f64)
            .collect();
        let gap = n - count.iter().sum::<i64>();
        for _ in 0..gap {
            let r = self.rng.uniform() * gap as f64;
            let (mut j, mut rsum) = (0, rem[0]);
            while rsum < r && j < nt - 1 {
                j += 1;
                rsum += rem[j];
            }
            count[j] += 1;
        }
        let mut out = Vec::new();
        for &i in &self.order {
            out.extend(std::iter::repeat_n(i, count[i].max(0) as usize));
        }
        Ok(out)
    }
}

/// How much `insert/pack` keeps in its region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// `particles_in_region N`.
    Count(i64),
    /// `volumefraction_region f`.
    VolumeFraction(f64),
    /// `mass_in_region m` (mass).
    Mass(f64),
}

/// Velocities of inserted particles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Velocity {
    /// `vel constant vx vy vz`.
    Constant([f64; 3]),
    /// `vel uniform vx vy vz dvx dvy dvz`.
    Uniform([f64; 3], [f64; 3]),
    /// `vel gaussian vx vy vz sx sy sz`.
    Gaussian([f64; 3], [f64; 3]),
}

/// `fix insert/pack`.
#[derive(Debug, Clone)]
pub struct InsertPack {
    /// Fix ID (for messages).
    pub id: String,
    /// The distribution fix's ID.
    pub distribution: String,
    /// The region's index.
    pub region: usize,
    /// The region's ID (for messages).
    pub region_id: String,
    /// The target.
    pub target: Target,
    /// Steps between insertions (0: once).
    pub every: i64,
    /// The next insertion step (None: no more).
    pub next: Option<i64>,
    /// The first insertion step (`start`, else the step after the definition), which
    /// LIGGGHTS keeps in restart files.
    pub first_step: i64,
    /// `overlapcheck`.
    pub overlapcheck: bool,
    /// `all_in`.
    pub all_in: bool,
    /// `maxattempt`.
    pub maxattempt: i64,
    /// `ntry_mc`.
    pub ntry_mc: i64,
    /// `check_dist_from_subdomain_border`.
    pub check_dist: bool,
    /// `verbose`.
    pub verbose: bool,
    /// Velocity of new particles.
    pub velocity: Velocity,
    /// Angular velocity of new particles (1/time).
    pub omega: [f64; 3],
    /// The fix generator.
    pub rng: RanPark,
    /// The seed (`getSeed`).
    pub seed: i32,
    /// The region generator.
    pub region_rng: RanPark,
    /// Monte Carlo region volume (length^3).
    pub region_volume: f64,
    /// Setup done (first run).
    pub set_up: bool,
    /// Particles inserted so far.
    pub inserted: i64,
    /// Their mass (mass).
    pub inserted_mass: f64,
    /// `insert/rate/region`: (nparticles, None for `INF`; particlerate in 1/time).
    pub rate: Option<(Option<i64>, f64)>,
    /// `insert/rate/region ... massrate M`: the mass rate as given (mass/time), which
    /// LIGGGHTS prints instead of particle rate x expected mass.
    pub mass_rate: Option<f64>,
    /// `insert/rate/region`: particles per insertion (mean), from the rate at setup.
    pub per_insertion: f64,
    /// `orientation random`.
    pub random_orientation: bool,
}

/// A new particle: template index, position, velocity and a clump's principal axes when
/// its orientation was drawn (None: the template's).
pub type NewParticle = (usize, [f64; 3], [f64; 3], Option<Axes>);

/// `orientation random`: a random unit quaternion from the fix generator and, for a
/// clump template, its axes rotated by it (spheres draw too, and keep no orientation).
pub fn random_orientation(rng: &mut RanPark, t: &Template) -> Option<Axes> {
    let q = random_unit_quat(rng);
    t.clump.as_ref().map(|c| rotate_axes(&c.axes, &q))
}

/// What an insertion needs to know about the particles and the box.
pub struct World<'a> {
    /// Positions (length).
    pub x: &'a [[f64; 3]],
    /// Radii (length).
    pub radius: &'a [f64],
    /// Masses (mass).
    pub mass: &'a [f64],
    /// Box bounds (length).
    pub lo: [f64; 3],
    /// Box bounds (length).
    pub hi: [f64; 3],
    /// Periodic directions.
    pub periodic: [bool; 3],
    /// The box can change (a shrink-wrapped face).
    pub box_changes: bool,
    /// Body tags of the atoms (-1 outside a clump; None without clumps): an insertion
    /// region counts a clump once, by its body, not by its members.
    pub members: Option<&'a [f64]>,
    /// The clumps: bounding-sphere centre (length), mass (mass), density (mass/length^3).
    pub bodies: &'a [([f64; 3], f64, f64)],
}

/// LIGGGHTS's warning when the (sub-)domain is narrower than 2.2 bounding radii of the
/// largest particle to insert, given at every insertion that inserts something.
fn narrow_box_warning(w: &World, maxrad: f64) -> Option<String> {
    let d = [0, 1, 2].map(|k| w.hi[k] - w.lo[k]);
    let dim = if d[0] < d[1] && d[0] < d[2] {
        0
    } else if d[1] < d[2] {
        1
    } else {
        2
    };
    (d[dim] < 2.2 * maxrad).then(|| {
        format!(
            "WARNING: Particle insertion on proc 0: sub-domain is smaller than the bounding radius of insert particles to insert: \nMax. bounding sphere diameter is {:.6}, sub-domain extent in {} direction is only {:.6}  (./src/fix_insert.cpp:730)",
            2.0 * maxrad,
            ["x", "y", "z"][dim],
            d[dim]
        )
    })
}

impl InsertPack {
    /// LIGGGHTS's refusals before it places particles in a tet region: the overlap check
    /// asks for the surface distance of every particle the region does not hold (its
    /// periodic images too, which regolith cannot list as LIGGGHTS does), and a `side out`
    /// region has no points to draw.
    fn tet_checks(&self, regions: &Regions, w: &World) -> Result<(), EngineError> {
        if self.overlapcheck && !w.x.is_empty() {
            if w.x.iter().any(|&x| !regions.matches(self.region, x)) {
                return Err(tet::NO_SURFACE.into());
            }
            if w.periodic.iter().any(|&p| p) {
                return Err(EngineError::Unsupported(
                    "fix insert/pack overlap checks in a mesh/tet region of a periodic box".into(),
                ));
            }
        }
        if !regions.list[self.region].interior {
            return Err(tet::SIDE_OUT.into());
        }
        Ok(())
    }

    fn shape<'r>(&self, regions: &'r Regions) -> &'r Shape {
        &regions.list[self.region].shape
    }

    /// The Monte Carlo region volume with the region generator (3 draws per sample); a tet
    /// region's is its tetrahedra's, without draws. Returns this process's share.
    fn volume_mc(
        &mut self,
        regions: &Regions,
        w: &World,
        max_radius: f64,
    ) -> Result<f64, EngineError> {
        if let Shape::TetMesh(mesh) = self.shape(regions) {
            let vols = tet::TetVolumes::of(mesh);
            let (whole, local) = tet::region_volume(mesh, &vols, w.lo, w.hi)?;
            self.region_volume = whole;
            return Ok(local);
        }
        let (elo, ehi) = regions.extent(self.region).unwrap_or(([0.0; 3], [0.0; 3]));
        let mut hits = 0i64;
        for _ in 0..self.ntry_mc {
            let mut p = [0.0; 3];
            for d in 0..3 {
                p[d] = elo[d] + self.region_rng.uniform() * (ehi[d] - elo[d]);
            }
            if !(0..3).all(|d| p[d] >= w.lo[d] && p[d] <= w.hi[d]) {
                continue;
            }
            if regions.matches(self.region, p) {
                hits += 1;
            }
        }
        let _ = max_radius;
        if hits == 0 {
            // no test point fell in the region (a region too small, out of the box, or with
            // NaN bounds): LIGGGHTS stops here
            return Err(EngineError::Invalid(
                "Unable to calculate region volume. Possible sources of error: \n   \
                 (a) region volume is too small or out of domain (you may want to increase \
                 the 'volume_limit' in the input script)\n   (b) particles for insertion are \
                 too large when using all_in yes\n   (c) region is 2d, but should be 3d"
                    .into(),
            ));
        }
        let vbox = (ehi[0] - elo[0]) * (ehi[1] - elo[1]) * (ehi[2] - elo[2]);
        self.region_volume = hits as f64 / self.ntry_mc as f64 * vbox;
        Ok(self.region_volume)
    }

    /// First run's setup: reseed the region generator and measure the region. Returns the
    /// lines LIGGGHTS prints.
    pub fn setup(
        &mut self,
        regions: &Regions,
        dist: &Distribution,
        w: &World,
        dt: f64,
    ) -> Result<Vec<String>, EngineError> {
        if self.set_up {
            return Ok(Vec::new());
        }
        self.set_up = true;
        // C int arithmetic, as LIGGGHTS adds it (a seed near the top wraps and is refused)
        self.region_rng.reset(self.seed.wrapping_add(12))?;
        let local = self.volume_mc(regions, w, dist.max_radius)?;
        let whole = self.region_volume;
        // insert/pack allows a share 0.1 % above the whole, insert/rate/region none
        let over = if self.rate.is_some() {
            local > whole + f64::EPSILON
        } else {
            (local - whole) / whole > 1e-3
        };
        if whole <= 0.0 || local < 0.0 || over {
            return Err("Fix insert: Region volume calculation with MC failed".into());
        }
        let mut lines = vec![format!(
            "INFO: Resetting random generator for region {}",
            self.region_id
        )];
        match self.rate {
            None => lines.push(format!(
                "INFO: Particle insertion {}: inserting every {} steps",
                self.id, self.every
            )),
            Some((total, rate)) => {
                self.per_insertion = rate * (self.every as f64 * dt);
                let f = |spec: &str, v: f64| {
                    crate::util::format::with_spec(spec, v).unwrap_or_default()
                };
                let mut line = format!(
                    "INFO: Particle insertion {}: {} particles every {} steps - particle rate {}  (mass rate {})",
                    self.id,
                    f("%f", self.per_insertion),
                    self.every,
                    f("%f", rate),
                    f("%e", self.mass_rate.unwrap_or(rate * dist.mass_expect)),
                );
                // without a total (INF) LIGGGHTS prints the rates alone
                if let Some(total) = total {
                    let within = if total as f64 <= self.per_insertion {
                        0
                    } else {
                        ((total as f64 / self.per_insertion) as i64).saturating_mul(self.every)
                    };
                    line += &format!(
                        "\n      {} particles (mass {}) within {} steps",
                        total,
                        f("%e", total as f64 * dist.mass_expect),
                        within
                    );
                }
                lines.push(line);
            }
        }
        Ok(lines)
    }

    /// The region's content now: particles (a clump counted once, where its bounding
    /// sphere's centre is), their volume (length^3) and mass.
    fn region_content(&self, regions: &Regions, w: &World) -> (i64, f64, f64) {
        let (mut np, mut vol, mut mass) = (0i64, 0.0, 0.0);
        for i in 0..w.x.len() {
            if w.members.is_some_and(|t| t[i] >= 0.0) {
                continue;
            }
            if regions.matches(self.region, w.x[i]) {
                np += 1;
                let r = w.radius[i];
                vol += 4.0 * std::f64::consts::PI / 3.0 * r * r * r;
                mass += w.mass[i];
            }
        }
        // a clump counts where its bounding sphere's centre is
        for &(xb, m, rho) in w.bodies {
            if regions.matches(self.region, xb) {
                np += 1;
                vol += m / rho;
                mass += m;
            }
        }
        (np, vol, mass)
    }

    /// How many particles this insertion adds (the rate's share, or what the target
    /// lacks; fix generator draws), and how full the region is (NaN for a rate).
    fn how_many(&mut self, regions: &Regions, dist: &Distribution, w: &World) -> (i64, f64) {
        let (np, vol, mass) = self.region_content(regions, w);
        let (mut n, mut ratio) = match (self.rate, self.target) {
            (Some((total, _)), _) => {
                let mut n = (self.per_insertion + self.rng.uniform()) as i64;
                if let Some(total) = total.filter(|&t| self.inserted + n > t) {
                    n = total - self.inserted;
                }
                (n, f64::NAN)
            }
            (None, target) => match target {
                Target::VolumeFraction(f) => (
                    ((f * self.region_volume - vol) / dist.volume_expect + self.rng.uniform())
                        as i64,
                    vol / (f * self.region_volume),
                ),
                Target::Count(c) => (c - np, np as f64 / c as f64),
                Target::Mass(m) => (
                    ((m - mass) / dist.mass_expect + self.rng.uniform()) as i64,
                    mass / m,
                ),
            },
        };
        n = n.max(0);
        if !ratio.is_nan() {
            ratio = ratio.clamp(0.0, 1.0);
        }
        (n, ratio)
    }

    /// One insertion at `step` (due when `self.next == Some(step)`): the new particles in
    /// placement order, and the lines LIGGGHTS prints.
    pub fn insert(
        &mut self,
        step: i64,
        regions: &Regions,
        dist: &mut Distribution,
        w: &World,
    ) -> Result<(Vec<NewParticle>, Vec<String>), EngineError> {
        let mut lines = Vec::new();
        let shape = self.shape(regions).clone();
        self.next = if self.every > 0 {
            Some(step + self.every)
        } else {
            None
        };
        let (n, ratio) = self.how_many(regions, dist, w);
        if w.box_changes {
            self.volume_mc(regions, w, dist.max_radius)?;
        }
        let list = dist.list(n)?;
        if list.is_empty() {
            return Ok((Vec::new(), lines));
        }
        let nlist = list.len() as i64;
        let maxrad = dist.max_radius;
        lines.extend(narrow_box_warning(w, maxrad));
        // existing atoms near the region (periodic images too), then placed ones
        let (elo, ehi) = regions.extent(self.region).unwrap_or(([0.0; 3], [0.0; 3]));
        let tet_mesh = match &shape {
            Shape::TetMesh(m) => Some((m.as_ref(), tet::TetVolumes::of(m))),
            _ => None,
        };
        if tet_mesh.is_some() {
            self.tet_checks(regions, w)?;
        }
        if self.overlapcheck {
            regions.wedge_insert_check(self.region, w.x, w.periodic)?;
        }
        // LIGGGHTS's reach: the largest sphere (a clump's largest member, not its bounding
        // sphere); with clumps the box around the region grows by two bounding radii
        let reach = dist.max_sphere_radius();
        let grow = if dist.templates.iter().any(|t| t.clump.is_some()) {
            2.0 * reach + 2.0 * maxrad
        } else {
            2.0 * reach
        };
        let bblo = [0, 1, 2].map(|d| elo[d].max(w.lo[d]) - grow);
        let bbhi = [0, 1, 2].map(|d| ehi[d].min(w.hi[d]) + grow);
        let near = if self.overlapcheck {
            self.near_particles(&shape, w, reach, bblo, bbhi)
        } else {
            Vec::new()
        };
        let maxtry = if ratio.is_nan() || ratio >= 1.0 {
            nlist.saturating_mul(self.maxattempt)
        } else {
            (nlist.saturating_mul(self.maxattempt) as f64 / (1.0 - ratio)) as i64
        };
        let lo = [0, 1, 2].map(|d| elo[d].max(w.lo[d]));
        let hi = [0, 1, 2].map(|d| ehi[d].min(w.hi[d]));
        let sampler = place::Sampler {
            regions,
            region: self.region,
            all_in: self.all_in,
            lo,
            diff: [0, 1, 2].map(|d| hi[d] - lo[d]),
            tet_mesh,
            w,
        };
        let placed = if self.overlapcheck {
            self.place_checked(&sampler, &list, dist, maxtry, near, &mut lines)?
        } else {
            self.place_unchecked(&sampler, &list, dist, &mut lines)?
        };
        self.count_inserted(step, &placed, nlist, dist, &mut lines);
        Ok((placed, lines))
    }

    /// Count the particles `placed` at `step` (`nlist` were asked for): the totals, the
    /// end of a rate's insertions, and LIGGGHTS's report.
    fn count_inserted(
        &mut self,
        step: i64,
        placed: &[NewParticle],
        nlist: i64,
        dist: &Distribution,
        lines: &mut Vec<String>,
    ) {
        let m: f64 = placed.iter().map(|(t, ..)| dist.templates[*t].mass).sum();
        self.inserted += placed.len() as i64;
        self.inserted_mass += m;
        if let Some((Some(total), _)) = self.rate {
            if self.inserted >= total {
                self.next = None;
            }
        }
        if self.verbose {
            lines.push(format!(
                "INFO: Particle insertion {}: inserted {} particle templates (mass {}) at step {step}\n - a total of {} particle templates (mass {}) inserted so far.",
                self.id,
                placed.len(),
                crate::util::format::with_spec("%e", m).unwrap_or_default(),
                self.inserted,
                crate::util::format::with_spec("%e", self.inserted_mass).unwrap_or_default()
            ));
        }
        if (placed.len() as i64) < nlist {
            lines.push("WARNING: Particle insertion: Less insertions than requested (./src/fix_insert.cpp:814)".into());
        }
    }
}
