//! Particle insertion as LIGGGHTS 3.8.0 does it (docs/notes/insertion.md): sphere templates,
//! discrete distributions and `fix insert/pack`, with LIGGGHTS's three Park-Miller streams
//! (region: positions and the Monte Carlo region volume; fix: targets and velocities;
//! distribution: leftover particles), its draw order, placement order, overlap rule and
//! messages, so that inserted atoms agree with LIGGGHTS's bit for bit.

use crate::engine::error::EngineError;
use crate::engine::region::{Regions, Shape};
use crate::util::random::RanPark;

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
            rng_state: (0, 0),
            clump: Some(Box::new(t.clone())),
        }
    }

    /// Member sphere centres (length) and radii of this template placed at `p` (a clump's
    /// centre of mass, unrotated; a sphere's centre).
    pub fn spheres_at(&self, p: [f64; 3]) -> Vec<([f64; 3], f64)> {
        match &self.clump {
            None => vec![(p, self.radius)],
            Some(c) => {
                let (ex, ey, ez) = (&c.axes[0], &c.axes[1], &c.axes[2]);
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
    /// `insert/rate/region`: (nparticles, particlerate in 1/time).
    pub rate: Option<(i64, f64)>,
    /// `insert/rate/region ... massrate M`: the mass rate as given (mass/time), which
    /// LIGGGHTS prints instead of particle rate x expected mass.
    pub mass_rate: Option<f64>,
    /// `insert/rate/region`: particles per insertion (mean), from the rate at setup.
    pub per_insertion: f64,
}

/// A new particle: template index, position and velocity.
pub type NewParticle = (usize, [f64; 3], [f64; 3]);

/// Number of interior faces of a block or cylinder closer than `cut` to `x` (0 outside).
pub fn surface_interior(shape: &Shape, x: [f64; 3], cut: f64) -> usize {
    match shape {
        Shape::Block { lo, hi } => {
            if !(0..3).all(|d| x[d] >= lo[d] && x[d] <= hi[d]) {
                return 0;
            }
            (0..3)
                .map(|d| (x[d] - lo[d] < cut) as usize + (hi[d] - x[d] < cut) as usize)
                .sum()
        }
        Shape::Cylinder {
            axis,
            c1,
            c2,
            radius,
            lo,
            hi,
        } => {
            let (a1, a2) = cross_axes(*axis);
            let (d1, d2) = (x[a1] - c1, x[a2] - c2);
            let r = (d1 * d1 + d2 * d2).sqrt();
            let a = x[*axis];
            if r > *radius || a < *lo || a > *hi {
                return 0;
            }
            (radius - r < cut && r > 0.0) as usize
                + (a - lo < cut) as usize
                + (hi - a < cut) as usize
        }
        _ => 0,
    }
}

/// Whether `x` lies outside a block or cylinder but closer than `cut` to its surface.
pub fn surface_exterior(shape: &Shape, x: [f64; 3], cut: f64) -> bool {
    let dist = |p: [f64; 3]| {
        let d = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    };
    match shape {
        Shape::Block { lo, hi } => {
            if (0..3).any(|d| x[d] <= lo[d] - cut || x[d] >= hi[d] + cut) {
                return false;
            }
            if (0..3).all(|d| x[d] > lo[d] && x[d] < hi[d]) {
                return false;
            }
            let p = [0, 1, 2].map(|d| x[d].clamp(lo[d], hi[d]));
            dist(p) < cut
        }
        Shape::Cylinder {
            axis,
            c1,
            c2,
            radius,
            lo,
            hi,
        } => {
            let (a1, a2) = cross_axes(*axis);
            let (d1, d2) = (x[a1] - c1, x[a2] - c2);
            let r = (d1 * d1 + d2 * d2).sqrt();
            let a = x[*axis];
            if r >= radius + cut || a <= lo - cut || a >= hi + cut {
                return false;
            }
            if r < *radius && a > *lo && a < *hi {
                return false;
            }
            let mut p = x;
            if r > *radius {
                p[a1] = c1 + (x[a1] - c1) * radius / r;
                p[a2] = c2 + (x[a2] - c2) * radius / r;
            }
            p[*axis] = a.clamp(*lo, *hi);
            dist(p) < cut
        }
        _ => false,
    }
}

/// Contacts (vectors from the surface point to `x`) of `x` with region `index`'s surface
/// within `cut`, honouring `side` as LIGGGHTS's `Region::surface` does; intersections keep a
/// sub-region's contact only where its surface point lies in all the other sub-regions.
pub fn surface_contacts(regions: &Regions, index: usize, x: [f64; 3], cut: f64) -> Vec<[f64; 3]> {
    let r = &regions.list[index];
    surface_contacts_side(regions, index, x, cut, r.interior)
}

fn surface_contacts_side(
    regions: &Regions,
    index: usize,
    x: [f64; 3],
    cut: f64,
    interior: bool,
) -> Vec<[f64; 3]> {
    let r = &regions.list[index];
    let mut out = Vec::new();
    match &r.shape {
        Shape::Block { lo, hi } => {
            if interior {
                if !(0..3).all(|d| x[d] >= lo[d] && x[d] <= hi[d]) {
                    return out;
                }
                for d in 0..3 {
                    let delta = x[d] - lo[d];
                    if delta < cut {
                        let mut v = [0.0; 3];
                        v[d] = delta;
                        out.push(v);
                    }
                    let delta = hi[d] - x[d];
                    if delta < cut {
                        let mut v = [0.0; 3];
                        v[d] = -delta;
                        out.push(v);
                    }
                }
            } else {
                if (0..3).any(|d| x[d] <= lo[d] - cut || x[d] >= hi[d] + cut) {
                    return out;
                }
                if (0..3).all(|d| x[d] > lo[d] && x[d] < hi[d]) {
                    return out;
                }
                let p = [0, 1, 2].map(|d| x[d].clamp(lo[d], hi[d]));
                let v = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
                if (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() < cut {
                    out.push(v);
                }
            }
        }
        Shape::Cylinder {
            axis,
            c1,
            c2,
            radius,
            lo,
            hi,
        } => {
            let (a1, a2) = cross_axes(*axis);
            let (d1, d2) = (x[a1] - c1, x[a2] - c2);
            let rr = (d1 * d1 + d2 * d2).sqrt();
            let a = x[*axis];
            if interior {
                if rr > *radius || a < *lo || a > *hi {
                    return out;
                }
                let delta = radius - rr;
                if delta < cut && rr > 0.0 {
                    let mut v = [0.0; 3];
                    v[a1] = d1 * (1.0 - radius / rr);
                    v[a2] = d2 * (1.0 - radius / rr);
                    out.push(v);
                }
                let delta = a - lo;
                if delta < cut {
                    let mut v = [0.0; 3];
                    v[*axis] = delta;
                    out.push(v);
                }
                let delta = hi - a;
                if delta < cut {
                    let mut v = [0.0; 3];
                    v[*axis] = -delta;
                    out.push(v);
                }
            } else {
                if rr >= radius + cut || a <= lo - cut || a >= hi + cut {
                    return out;
                }
                if rr < *radius && a > *lo && a < *hi {
                    return out;
                }
                let mut p = x;
                if rr > *radius {
                    p[a1] = c1 + d1 * radius / rr;
                    p[a2] = c2 + d2 * radius / rr;
                }
                p[*axis] = if a < *lo {
                    *lo
                } else if a > *hi {
                    *hi
                } else {
                    a
                };
                let v = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
                if (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() < cut {
                    out.push(v);
                }
            }
        }
        Shape::Intersect(members) => {
            // interior: sub-region contacts whose point is in all the others; exterior:
            // with every sub-region's side flipped, points in none of the others
            for (k, &m) in members.iter().enumerate() {
                let side = regions.list[m].interior == interior;
                for v in surface_contacts_side(regions, m, x, cut, side) {
                    let p = [x[0] - v[0], x[1] - v[1], x[2] - v[2]];
                    // with the sides flipped for the exterior, "in none of the flipped others"
                    // is again "in all of the others"
                    let keep = members
                        .iter()
                        .enumerate()
                        .filter(|(j, _)| *j != k)
                        .all(|(_, &o)| regions.matches(o, p));
                    if keep {
                        out.push(v);
                    }
                }
            }
        }
        _ => {}
    }
    out
}

fn cross_axes(axis: usize) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

fn inside(shape: &Shape, x: [f64; 3]) -> bool {
    match shape {
        Shape::Block { lo, hi } => (0..3).all(|d| x[d] >= lo[d] && x[d] <= hi[d]),
        Shape::Cylinder {
            axis,
            c1,
            c2,
            radius,
            lo,
            hi,
        } => {
            let (a1, a2) = cross_axes(*axis);
            let (d1, d2) = (x[a1] - c1, x[a2] - c2);
            (d1 * d1 + d2 * d2).sqrt() <= *radius && x[*axis] >= *lo && x[*axis] <= *hi
        }
        _ => false,
    }
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
    fn shape<'r>(&self, regions: &'r Regions) -> &'r Shape {
        &regions.list[self.region].shape
    }

    /// The Monte Carlo region volume with the region generator (3 draws per sample).
    fn volume_mc(&mut self, regions: &Regions, w: &World, max_radius: f64) {
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
        let vbox = (ehi[0] - elo[0]) * (ehi[1] - elo[1]) * (ehi[2] - elo[2]);
        self.region_volume = hits as f64 / self.ntry_mc as f64 * vbox;
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
        self.volume_mc(regions, w, dist.max_radius);
        if self.region_volume <= 0.0 {
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
                let within = if total as f64 <= self.per_insertion {
                    0
                } else {
                    ((total as f64 / self.per_insertion) as i64).saturating_mul(self.every)
                };
                lines.push(format!(
                    "INFO: Particle insertion {}: {} particles every {} steps - particle rate {}  (mass rate {})\n      {} particles (mass {}) within {} steps",
                    self.id,
                    f("%f", self.per_insertion),
                    self.every,
                    f("%f", rate),
                    f("%e", self.mass_rate.unwrap_or(rate * dist.mass_expect)),
                    total,
                    f("%e", total as f64 * dist.mass_expect),
                    within
                ));
            }
        }
        Ok(lines)
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
        // how many: the region's content now
        let (mut np, mut vol, mut mass) = (0i64, 0.0, 0.0);
        for i in 0..w.x.len() {
            if regions.matches(self.region, w.x[i]) {
                np += 1;
                let r = w.radius[i];
                vol += 4.0 * std::f64::consts::PI / 3.0 * r * r * r;
                mass += w.mass[i];
            }
        }
        let (mut n, mut ratio) = match (self.rate, self.target) {
            (Some((total, _)), _) => {
                let mut n = (self.per_insertion + self.rng.uniform()) as i64;
                if self.inserted + n > total {
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
        if w.box_changes {
            self.volume_mc(regions, w, dist.max_radius);
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
        let exact_near = matches!(shape, Shape::Block { .. } | Shape::Cylinder { .. });
        // a clump's members reach up to two bounding radii from its centre of mass
        let reach = if dist.templates.iter().any(|t| t.clump.is_some()) {
            2.0 * maxrad
        } else {
            maxrad
        };
        let bblo = [0, 1, 2].map(|d| elo[d].max(w.lo[d]) - 2.0 * reach);
        let bbhi = [0, 1, 2].map(|d| ehi[d].min(w.hi[d]) + 2.0 * reach);
        let mut near: Vec<([f64; 3], f64)> = Vec::new();
        if self.overlapcheck {
            let len = [0, 1, 2].map(|d| w.hi[d] - w.lo[d]);
            let shifts = |d: usize| {
                if w.periodic[d] {
                    vec![0.0, -len[d], len[d]]
                } else {
                    vec![0.0]
                }
            };
            for i in 0..w.x.len() {
                let cut = if self.all_in {
                    reach
                } else {
                    w.radius[i] + reach
                };
                for sx in shifts(0) {
                    for sy in shifts(1) {
                        for sz in shifts(2) {
                            let x = [w.x[i][0] + sx, w.x[i][1] + sy, w.x[i][2] + sz];
                            // an atom farther than cut outside the region cannot touch a
                            // new particle, so intersections keep a superset
                            if exact_near
                                && !(inside(&shape, x) || surface_exterior(&shape, x, cut))
                            {
                                continue;
                            }
                            if !(0..3).all(|d| x[d] >= bblo[d] && x[d] <= bbhi[d]) {
                                continue;
                            }
                            near.push((x, w.radius[i]));
                        }
                    }
                }
            }
        }
        let maxtry = if ratio.is_nan() || ratio >= 1.0 {
            nlist.saturating_mul(self.maxattempt)
        } else {
            (nlist.saturating_mul(self.maxattempt) as f64 / (1.0 - ratio)) as i64
        };
        let lo = [0, 1, 2].map(|d| elo[d].max(w.lo[d]));
        let hi = [0, 1, 2].map(|d| ehi[d].min(w.hi[d]));
        let diff = [0, 1, 2].map(|d| hi[d] - lo[d]);
        let all_in = self.all_in;
        let region = self.region;
        let gen = |rng: &mut RanPark, rb: f64| loop {
            let p = [
                lo[0] + rng.uniform() * diff[0],
                lo[1] + rng.uniform() * diff[1],
                lo[2] + rng.uniform() * diff[2],
            ];
            if all_in {
                if regions.matches(region, p) && surface_contacts(regions, region, p, rb).is_empty()
                {
                    return p;
                }
            } else if regions.matches(region, p) {
                return p;
            }
        };
        let dist_sub = |p: [f64; 3]| {
            let dlo = (0..3)
                .map(|d| (w.lo[d] - p[d]).abs())
                .fold(f64::INFINITY, f64::min);
            let dhi = (0..3)
                .map(|d| (w.hi[d] - p[d]).abs())
                .fold(f64::INFINITY, f64::min);
            if dlo < dhi {
                dlo
            } else {
                dhi
            }
        };
        let velocity = |rng: &mut RanPark| match self.velocity {
            Velocity::Constant(v) => v,
            Velocity::Uniform(v, dv) => {
                [0, 1, 2].map(|d| v[d] + dv[d] * 2.0 * (rng.uniform() - 0.50))
            }
            Velocity::Gaussian(v, s) => [0, 1, 2].map(|d| v[d] + s[d] * rng.gaussian()),
        };
        let mut placed: Vec<NewParticle> = Vec::new();
        let mut ntry = 0i64;
        let nl = nlist as usize;
        if self.overlapcheck {
            while ntry < maxtry && placed.len() < nl {
                let t = list[placed.len()];
                let rb = dist.templates[t].radius;
                if self.verbose && nl >= 10 && placed.len().is_multiple_of(nl / 10) {
                    lines.push(format!(
                        "insertion: proc 0 at {} %",
                        10 * placed.len() / (nl / 10)
                    ));
                }
                let mut done = false;
                while !done && ntry < maxtry {
                    let mut p;
                    loop {
                        p = gen(&mut self.region_rng, rb);
                        ntry += 1;
                        if !(self.check_dist && ntry < maxtry && dist_sub(p) < rb) {
                            break;
                        }
                    }
                    if ntry == maxtry {
                        break;
                    }
                    let v = velocity(&mut self.rng);
                    // every sphere of the template (a clump's members) against the near
                    // ones; a NaN distance counts as clear, as in LIGGGHTS
                    let spheres = dist.templates[t].spheres_at(p);
                    #[allow(clippy::neg_cmp_op_on_partial_ord)]
                    let clear = spheres.iter().all(|&(s, rs_new)| {
                        near.iter().all(|(q, rq)| {
                            let d = [s[0] - q[0], s[1] - q[1], s[2] - q[2]];
                            let rs = rs_new + rq;
                            !(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= rs * rs)
                        })
                    });
                    if clear {
                        near.extend(spheres);
                        placed.push((t, p, v));
                        done = true;
                    }
                }
            }
        } else {
            for (k, &t) in list.iter().enumerate() {
                if self.verbose && nl >= 10 && k % (nl / 10) == 0 {
                    lines.push(format!("insertion: proc 0 at {} %", 10 * k / (nl / 10)));
                }
                let p = gen(&mut self.region_rng, dist.templates[t].radius);
                let v = velocity(&mut self.rng);
                placed.push((t, p, v));
            }
        }
        let m: f64 = placed.iter().map(|(t, _, _)| dist.templates[*t].mass).sum();
        self.inserted += placed.len() as i64;
        self.inserted_mass += m;
        if let Some((total, _)) = self.rate {
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
        Ok((placed, lines))
    }
}

/// A triangle mesh as an insertion face: LIGGGHTS's area-weighted triangle choice and
/// barycentric sampling, with the mesh's own generator (seed 179424799, never reset).
#[derive(Debug, Clone)]
pub struct Face {
    /// The triangles (length).
    pub triangles: Vec<crate::io::stl::Triangle>,
    /// Cumulative areas.
    pub acc: Vec<f64>,
    /// Total area (length^2).
    pub total: f64,
    /// The mesh generator.
    pub rng: RanPark,
    /// Edge lists for `all_in yes` (planar faces only).
    pub within: Option<Within>,
}

/// LIGGGHTS's TriMeshPlanar edge lists for `all_in yes`: for each triangle, up to six
/// (triangle, active edge) pairs to test a sampled point against, and the smallest of their
/// recorded distances. LIGGGHTS fills the six slots with every pairing of an active edge
/// with this triangle's edges and, once full, overwrites the slot with the largest
/// distance unconditionally; the lists are therefore not the six nearest edges, and a
/// point can land closer than its radius to an active edge missing from its list. This
/// is reproduced as it is.
#[derive(Debug, Clone)]
pub struct Within {
    /// Per triangle, the (triangle, edge) pairs, `None` past the filled slots.
    pub nearest: Vec<[Option<(usize, usize)>; 6]>,
    /// Per triangle, the smallest recorded distance (length; 1e8 while slots are empty).
    pub min_dist: Vec<f64>,
    /// Per triangle: nodes, unit edge vectors, edge lengths and in-plane edge normals.
    pub edges: Vec<TriangleEdges>,
}

/// One triangle's nodes, unit edge vectors, edge lengths (length) and in-plane edge normals.
pub type TriangleEdges = ([[f64; 3]; 3], [[f64; 3]; 3], [f64; 3], [[f64; 3]; 3]);

/// Most samples `all_in yes` draws for one point before it warns and keeps the last.
const MAXTRY_WITHIN: usize = 500;

impl Within {
    /// From a mesh with its topology built.
    pub fn new(mesh: &crate::engine::mesh::TriMesh) -> Within {
        let n = mesh.len();
        let edges: Vec<_> = (0..n)
            .map(|t| {
                (
                    mesh.nodes[t],
                    mesh.edge_vec[t],
                    mesh.edge_len[t],
                    mesh.edge_norm[t],
                )
            })
            .collect();
        let mut nearest = Vec::with_capacity(n);
        let mut min_dist = Vec::with_capacity(n);
        for edges_i in &edges {
            let mut slots = [None; 6];
            let mut dists = [1e8; 6];
            let mut filled = 0;
            for j in 0..n {
                if !mesh.edge_active[j].iter().any(|&a| a) {
                    continue;
                }
                for ie in 0..3 {
                    for je in 0..3 {
                        if !mesh.edge_active[j][je] {
                            continue;
                        }
                        // LIGGGHTS measures node je of j against edge ie of i
                        let d = edge_point_dist(edges_i, ie, mesh.nodes[j][je]);
                        let k = if filled < 6 {
                            filled += 1;
                            filled - 1
                        } else {
                            first_extreme(&dists, |a, b| a > b)
                        };
                        slots[k] = Some((j, je));
                        dists[k] = d;
                    }
                }
            }
            nearest.push(slots);
            min_dist.push(dists[first_extreme(&dists, |a, b| a < b)]);
        }
        Within {
            nearest,
            min_dist,
            edges,
        }
    }

    /// `p` (sampled on triangle `t`) is at least `delta` from the listed edges.
    fn far_enough(&self, t: usize, p: [f64; 3], delta: f64) -> bool {
        // a NaN distance is far enough, as in LIGGGHTS
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(self.min_dist[t] < delta) {
            return true;
        }
        for &(j, e) in self.nearest[t].iter().map_while(|s| s.as_ref()) {
            let d = edge_point_dist(&self.edges[j], e, p);
            if d.min(2.0 * delta) < delta {
                return false;
            }
        }
        true
    }
}

/// Index of the first extreme value (`better(a, b)`: a replaces b).
fn first_extreme(v: &[f64; 6], better: impl Fn(f64, f64) -> bool) -> usize {
    let mut k = 0;
    for i in 1..6 {
        if better(v[i], v[k]) {
            k = i;
        }
    }
    k
}

/// LIGGGHTS's edge–point distance: to the start node before the edge, to the end node past
/// it, else along the in-plane edge normal (length).
#[allow(clippy::type_complexity)]
fn edge_point_dist(e: &TriangleEdges, i: usize, p: [f64; 3]) -> f64 {
    let (nodes, vec, len, norm) = e;
    let a = nodes[i];
    let d = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    let along = vec[i][0] * d[0] + vec[i][1] * d[1] + vec[i][2] * d[2];
    let mag = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if along < 0.0 {
        mag(d)
    } else if along > len[i] {
        let b = nodes[(i + 1) % 3];
        mag([p[0] - b[0], p[1] - b[1], p[2] - b[2]])
    } else {
        (norm[i][0] * d[0] + norm[i][1] * d[1] + norm[i][2] * d[2]).abs()
    }
}

impl Face {
    /// From a mesh's triangles.
    pub fn new(triangles: Vec<crate::io::stl::Triangle>) -> Face {
        let mut acc = Vec::with_capacity(triangles.len());
        let mut total = 0.0;
        for t in &triangles {
            let mut ev = [[0.0; 3]; 3];
            let mut len = [0.0; 3];
            for j in 0..3 {
                let d = [0, 1, 2].map(|k| t[(j + 1) % 3][k] - t[j][k]);
                len[j] = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let inv = 1.0 / len[j];
                ev[j] = d.map(|c| inv * c);
            }
            let c = [
                ev[0][1] * ev[1][2] - ev[0][2] * ev[1][1],
                ev[0][2] * ev[1][0] - ev[0][0] * ev[1][2],
                ev[0][0] * ev[1][1] - ev[0][1] * ev[1][0],
            ];
            let a = 0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt() * len[0] * len[1];
            acc.push(match acc.last() {
                Some(l) => l + a,
                None => a,
            });
            total += a;
        }
        Face {
            triangles,
            acc,
            total: total + 0.0,
            rng: RanPark::new(179424799).expect("positive seed"),
            within: None,
        }
    }

    fn search(&self, a: f64, lo: usize, hi: usize) -> usize {
        let acc = &self.acc;
        if (lo < 1 || a > acc[lo - 1]) && a <= acc[lo] {
            return lo;
        }
        if (hi < 1 || a > acc[hi - 1]) && a <= acc[hi] {
            return hi;
        }
        let mid = (lo + hi) / 2;
        if a > acc[mid] {
            self.search(a, mid, hi)
        } else {
            self.search(a, lo, mid)
        }
    }

    /// A random point on the face.
    pub fn random_point(&mut self) -> [f64; 3] {
        self.random_point_on().0
    }

    /// A random point at least `delta` from the face's active edges (`all_in yes`), as
    /// LIGGGHTS's generateRandomOwnedGhostWithin; `false` when it gave up after 500 samples.
    pub fn random_point_within(&mut self, delta: f64) -> ([f64; 3], bool) {
        let mut ntry = 0;
        loop {
            ntry += 1;
            let (p, t) = self.random_point_on();
            let far = match &self.within {
                Some(w) => w.far_enough(t, p, delta),
                None => true,
            };
            if far || ntry >= MAXTRY_WITHIN {
                return (p, ntry != MAXTRY_WITHIN);
            }
        }
    }

    /// A random point on the face and its triangle.
    fn random_point_on(&mut self) -> ([f64; 3], usize) {
        let r = self.rng.uniform() * self.total;
        let c = self.search(r, 0, self.triangles.len() - 1);
        let (u, v) = loop {
            let u = self.rng.uniform();
            let v = self.rng.uniform();
            // LIGGGHTS's test, NaN included
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            if !(u + v > 1.0) {
                break (u, v);
            }
        };
        let (b0, b1, b2) = (1.0 - u - v, v, u);
        let n = &self.triangles[c];
        (
            [0, 1, 2].map(|k| b0 * n[0][k] + b1 * n[1][k] + b2 * n[2][k]),
            c,
        )
    }

    /// Whether `x`'s projection lies on the face (barycentric test, tolerance 1e-8).
    pub fn covers(&self, x: [f64; 3]) -> bool {
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        self.triangles.iter().any(|t| {
            let v0 = [0, 1, 2].map(|k| t[2][k] - t[0][k]);
            let v1 = [0, 1, 2].map(|k| t[1][k] - t[0][k]);
            let v2 = [0, 1, 2].map(|k| x[k] - t[0][k]);
            let (d00, d01, d02, d11, d12) = (
                dot(v0, v0),
                dot(v0, v1),
                dot(v0, v2),
                dot(v1, v1),
                dot(v1, v2),
            );
            let inv = 1.0 / (d00 * d11 - d01 * d01);
            let u = (d11 * d02 - d01 * d12) * inv;
            let v = (d00 * d12 - d01 * d02) * inv;
            u > -1e-8 && v > -1e-8 && u + v < 1.0 + 1e-8
        })
    }
}

/// One particle on its way from an insertion face: moved at `v_normal` until released.
#[derive(Debug, Clone, PartialEq)]
pub struct Release {
    /// Atom ID.
    pub id: i64,
    /// Where it was inserted (length).
    pub x: [f64; 3],
    /// The insertion step.
    pub inserted: i64,
    /// The release step.
    pub release: i64,
    /// Velocity while moving to the release point (length/time).
    pub v_int: [f64; 3],
    /// Velocity after release (length/time).
    pub v_final: [f64; 3],
    /// Angular velocity after release (1/time).
    pub omega: [f64; 3],
}

/// Width of LIGGGHTS's per-atom release data (`release_fix_insert_stream`).
pub const RELEASE_WIDTH: usize = 14;

/// Name of the per-atom release data, as LIGGGHTS's insert/stream names its property/atom.
pub const RELEASE_NAME: &str = "release_fix_insert_stream";

/// LIGGGHTS's tolerance when it turns stored steps back into integers.
const STEP_TINY: f64 = 1e-14;

impl Release {
    /// The 14 values LIGGGHTS keeps per atom: insertion position, insertion step, release
    /// step, integration velocity, release velocity, release angular velocity.
    pub fn row(&self) -> [f64; RELEASE_WIDTH] {
        let mut r = [0.0; RELEASE_WIDTH];
        r[..3].copy_from_slice(&self.x);
        r[3] = self.inserted as f64;
        r[4] = self.release as f64;
        r[5..8].copy_from_slice(&self.v_int);
        r[8..11].copy_from_slice(&self.v_final);
        r[11..14].copy_from_slice(&self.omega);
        r
    }

    /// A particle still on its way at `step`, from its stored row (None: not a stream
    /// particle, or already released), read as LIGGGHTS's end_of_step reads it.
    pub fn from_row(id: i64, r: &[f64], step: i64) -> Option<Release> {
        if r[3].abs() <= 1e-13 {
            return None;
        }
        let release = (r[4] + STEP_TINY) as i32 as i64;
        if step > release {
            return None;
        }
        Some(Release {
            id,
            x: [r[0], r[1], r[2]],
            inserted: (r[3] + STEP_TINY) as i32 as i64,
            release,
            v_int: [r[5], r[6], r[7]],
            v_final: [r[8], r[9], r[10]],
            omega: [r[11], r[12], r[13]],
        })
    }
}

/// What a restart file stored for an insertion fix (LIGGGHTS's FixInsert::write_restart).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InsertRestart {
    /// State of the fix generator.
    pub rng_state: i32,
    /// Particles inserted so far.
    pub inserted: i64,
    /// First insertion step.
    pub first_step: i64,
    /// Next insertion step (0: insertion had finished).
    pub next: i64,
    /// Mass inserted so far (mass).
    pub mass: f64,
}

impl InsertRestart {
    /// Parse the 5 doubles of the stored state.
    pub fn parse(bytes: &[u8]) -> Result<InsertRestart, EngineError> {
        if bytes.len() < 40 {
            return Err(format!(
                "stored insertion state has {} bytes, expected 40",
                bytes.len()
            )
            .into());
        }
        let d = |k: usize| f64::from_le_bytes(bytes[8 * k..8 * k + 8].try_into().expect("8"));
        Ok(InsertRestart {
            rng_state: d(0) as i32,
            inserted: d(1) as i32 as i64,
            first_step: d(2) as i32 as i64,
            next: d(3) as i64,
            mass: d(4),
        })
    }

    /// The 5 doubles LIGGGHTS stores.
    pub fn bytes(&self) -> Vec<u8> {
        [
            self.rng_state as f64,
            self.inserted as f64,
            self.first_step as f64,
            self.next as f64,
            self.mass,
        ]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect()
    }
}

/// `fix insert/stream`.
#[derive(Debug, Clone)]
pub struct InsertStream {
    /// Fix ID.
    pub id: String,
    /// The distribution fix's ID.
    pub distribution: String,
    /// The insertion face.
    pub face: Face,
    /// Unit face normal, pointing along the insertion velocity.
    pub normal: [f64; 3],
    /// Velocity component along the normal (length/time).
    pub v_normal: [f64; 3],
    /// First node of the first triangle.
    pub p_ref: [f64; 3],
    /// Extrusion length (length).
    pub extrude: f64,
    /// Steps between insertions.
    pub every: i64,
    /// Particles per insertion (mean).
    pub per_insertion: f64,
    /// Particle rate (1/time) and mass rate (mass/time), as LIGGGHTS prints them.
    pub rates: (f64, f64),
    /// Total to insert.
    pub total: i64,
    /// `vel` of the released particles.
    pub velocity: Velocity,
    /// Angular velocity after release (1/time).
    pub omega: [f64; 3],
    /// `overlapcheck`.
    pub overlapcheck: bool,
    /// `maxattempt`.
    pub maxattempt: i64,
    /// `ntry_mc`.
    pub ntry_mc: i64,
    /// `verbose`.
    pub verbose: bool,
    /// The fix generator.
    pub rng: RanPark,
    /// The next insertion step.
    pub next: Option<i64>,
    /// First insertion done (the face measurement runs at the first and, if the box can
    /// change, every insertion).
    pub measured: bool,
    /// Particles inserted so far.
    pub inserted: i64,
    /// Their mass (mass).
    pub inserted_mass: f64,
    /// Particles not yet released.
    pub moving: Vec<Release>,
    /// First insertion step (kept for restart files).
    pub first_step: i64,
}

impl InsertStream {
    /// The setup line LIGGGHTS prints.
    pub fn setup_lines(&self, dist: &Distribution) -> Vec<String> {
        let (rate, mass_rate) = self.rates;
        let f = |spec: &str, v: f64| crate::util::format::with_spec(spec, v).unwrap_or_default();
        vec![format!(
            "INFO: Particle insertion {}: {} particles every {} steps - particle rate {}  (mass rate {})\n      {} particles (mass {}) within {} steps",
            self.id,
            f("%f", self.per_insertion),
            self.every,
            f("%f", rate),
            f("%e", mass_rate),
            self.total,
            f("%e", self.total as f64 * dist.mass_expect),
            ((self.total as f64 / self.per_insertion).ceil() as i64)
                .saturating_sub(1)
                .max(0)
                .saturating_mul(self.every)
        )]
    }

    /// One insertion at `step`: new particles (template, position, velocity = v_normal) and
    /// the lines LIGGGHTS prints; the release data of the new atoms is recorded by
    /// [`InsertStream::record`] once they have IDs.
    pub fn insert(
        &mut self,
        step: i64,
        dist: &mut Distribution,
        w: &World,
        box_changes: bool,
    ) -> Result<(Vec<NewParticle>, Vec<String>), EngineError> {
        let mut lines = Vec::new();
        let mut n = (self.per_insertion + self.rng.uniform()) as i64;
        if self.inserted + n > self.total {
            n = self.total - self.inserted;
        }
        if self.inserted + n >= self.total {
            n = (self.total - self.inserted).max(0);
        }
        if !self.measured || box_changes {
            for _ in 0..self.ntry_mc {
                self.face.random_point();
                self.rng.uniform();
            }
            self.measured = true;
        }
        let list = dist.list(n)?;
        let maxrad = dist.max_radius;
        if !list.is_empty() {
            lines.extend(narrow_box_warning(w, maxrad));
        }
        let nrm = self.normal;
        let mut near: Vec<([f64; 3], f64)> = Vec::new();
        if self.overlapcheck {
            for i in 0..w.x.len() {
                let x = w.x[i];
                let dn = (x[0] - self.p_ref[0]) * nrm[0]
                    + (x[1] - self.p_ref[1]) * nrm[1]
                    + (x[2] - self.p_ref[2]) * nrm[2];
                if dn > maxrad || dn < -(self.extrude + 3.0 * maxrad) {
                    continue;
                }
                if self
                    .face
                    .covers([x[0] + nrm[0] * dn, x[1] + nrm[1] * dn, x[2] + nrm[2] * dn])
                {
                    near.push((x, w.radius[i]));
                }
            }
        }
        let in_sub = |p: [f64; 3]| (0..3).all(|d| p[d] >= w.lo[d] && p[d] < w.hi[d]);
        let dist_sub = |p: [f64; 3]| {
            let dlo = (0..3)
                .map(|d| (w.lo[d] - p[d]).abs())
                .fold(f64::INFINITY, f64::min);
            let dhi = (0..3)
                .map(|d| (w.hi[d] - p[d]).abs())
                .fold(f64::INFINITY, f64::min);
            if dlo < dhi {
                dlo
            } else {
                dhi
            }
        };
        let maxtry = (list.len() as i64).saturating_mul(self.maxattempt);
        let mut ntry = 0;
        let mut placed: Vec<NewParticle> = Vec::new();
        while ntry < maxtry && placed.len() < list.len() {
            let t = list[placed.len()];
            let rad = dist.templates[t].radius;
            let mut done = false;
            while !done && ntry < maxtry {
                let mut p;
                loop {
                    p = if self.face.within.is_some() {
                        let (q, ok) = self.face.random_point_within(rad);
                        if !ok {
                            lines.push(
                                "WARNING: 'All_in yes' did not succeed (./src/tri_mesh_planar_I.h:95)"
                                    .into(),
                            );
                        }
                        q
                    } else {
                        self.face.random_point()
                    };
                    let r = if self.overlapcheck {
                        -(self.rng.uniform() * self.extrude + rad + 0.0)
                    } else {
                        -(self.rng.uniform() * (self.extrude - 2.0 * rad) + rad + 0.0)
                    };
                    p = [p[0] + nrm[0] * r, p[1] + nrm[1] * r, p[2] + nrm[2] * r];
                    ntry += 1;
                    let bad = !in_sub(p) || (self.overlapcheck && dist_sub(p) < rad);
                    if !(ntry < maxtry && bad) {
                        break;
                    }
                }
                if ntry < maxtry {
                    // a NaN distance counts as clear, as in LIGGGHTS
                    #[allow(clippy::neg_cmp_op_on_partial_ord)]
                    let clear = !self.overlapcheck
                        || near.iter().all(|(q, rq)| {
                            let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
                            let rs = rad + rq;
                            !(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= rs * rs)
                        });
                    if clear {
                        near.push((p, rad));
                        placed.push((t, p, self.v_normal));
                        done = true;
                    }
                }
            }
        }
        let m: f64 = placed.iter().map(|(t, _, _)| dist.templates[*t].mass).sum();
        self.inserted += placed.len() as i64;
        self.inserted_mass += m;
        self.next = if self.inserted < self.total {
            Some(step + self.every)
        } else {
            None
        };
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
        if (placed.len() as i64) < n {
            lines.push("WARNING: Particle insertion: Less insertions than requested (./src/fix_insert.cpp:814)".into());
        }
        Ok((placed, lines))
    }

    /// The state a restart file keeps (LIGGGHTS's FixInsert::write_restart).
    pub fn restart_state(&self) -> InsertRestart {
        InsertRestart {
            rng_state: self.rng.state(),
            inserted: self.inserted,
            first_step: self.first_step,
            next: self.next.unwrap_or(0),
            mass: self.inserted_mass,
        }
    }

    /// Release data of the atoms just inserted (ID, position), final velocities drawn now;
    /// returns the new records.
    pub fn record(&mut self, step: i64, dt: f64, atoms: &[(i64, [f64; 3])]) -> Vec<Release> {
        let mut out = Vec::with_capacity(atoms.len());
        let vn = {
            let v = self.v_normal;
            (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
        };
        for &(id, x) in atoms {
            let rel = [0, 1, 2].map(|k| self.p_ref[k] - x[k]);
            let dn = rel[0] * self.normal[0] + rel[1] * self.normal[1] + rel[2] * self.normal[2];
            let steps = ((dn + 1e-14) / (vn * dt)) as i64;
            let v_final = match self.velocity {
                Velocity::Constant(v) => v,
                Velocity::Uniform(v, dv) => {
                    [0, 1, 2].map(|d| v[d] + dv[d] * 2.0 * (self.rng.uniform() - 0.50))
                }
                Velocity::Gaussian(v, s) => [0, 1, 2].map(|d| v[d] + s[d] * self.rng.gaussian()),
            };
            out.push(Release {
                id,
                x,
                inserted: step,
                release: step + steps,
                v_int: self.v_normal,
                v_final,
                omega: self.omega,
            });
        }
        out
    }
}
