//! Where `fix insert/pack` places its particles: random points of the region (or of a tet
//! mesh's tetrahedra), the particles near the region a new one must not overlap, and the
//! two placement loops (with LIGGGHTS's overlap check and without it), each drawing from
//! the region and fix generators in LIGGGHTS's order.

use super::surface::{inside, surface_contacts, surface_exterior};
use super::tet::{self, TetVolumes};
use super::{random_orientation, Distribution, InsertPack, NewParticle, Velocity, World};
use crate::engine::error::EngineError;
use crate::engine::region::{Regions, Shape};
use crate::engine::tet_mesh::TetMesh;
use crate::util::random::RanPark;

/// Random points of the insertion region: uniform in its part of the box (tested against
/// the region), or a tet mesh's point by volume.
pub(super) struct Sampler<'a> {
    /// The regions.
    pub regions: &'a Regions,
    /// The insertion region's index.
    pub region: usize,
    /// `all_in yes`: a whole particle inside.
    pub all_in: bool,
    /// Lower corner of the region's part of the box (length).
    pub lo: [f64; 3],
    /// Edge lengths of the region's part of the box (length).
    pub diff: [f64; 3],
    /// A tet region's mesh and its volume sums.
    pub tet_mesh: Option<(&'a TetMesh, TetVolumes)>,
    /// The particles and the box.
    pub w: &'a World<'a>,
}

impl Sampler<'_> {
    /// A point in the region's part of the box for a particle of bounding radius `rb`
    /// (length): three draws a try, again until the region holds it.
    fn in_box(&self, rng: &mut RanPark, rb: f64) -> [f64; 3] {
        let (lo, diff) = (self.lo, self.diff);
        loop {
            let p = [
                lo[0] + rng.uniform() * diff[0],
                lo[1] + rng.uniform() * diff[1],
                lo[2] + rng.uniform() * diff[2],
            ];
            if self.all_in {
                if self.regions.matches(self.region, p)
                    && surface_contacts(self.regions, self.region, p, rb).is_empty()
                {
                    return p;
                }
            } else if self.regions.matches(self.region, p) {
                return p;
            }
        }
    }

    /// A random point of the region: a tet region draws a tetrahedron, then a point in it.
    fn point(&self, rng: &mut RanPark, rb: f64) -> Result<[f64; 3], EngineError> {
        if let Some((mesh, vols)) = &self.tet_mesh {
            return tet::random_point(mesh, vols, rng, self.w.lo, self.w.hi);
        }
        Ok(self.in_box(rng, rb))
    }
}

/// The distance of `p` to the nearest face of the (sub-)domain (length), as LIGGGHTS
/// measures it for `check_dist_from_subdomain_border`.
pub(super) fn subdomain_distance(w: &World, p: [f64; 3]) -> f64 {
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
}

/// A new particle's velocity (length/time), drawn from the fix generator.
fn draw_velocity(velocity: Velocity, rng: &mut RanPark) -> [f64; 3] {
    match velocity {
        Velocity::Constant(v) => v,
        Velocity::Uniform(v, dv) => [0, 1, 2].map(|d| v[d] + dv[d] * 2.0 * (rng.uniform() - 0.50)),
        Velocity::Gaussian(v, s) => [0, 1, 2].map(|d| v[d] + s[d] * rng.gaussian()),
    }
}

/// Whether LIGGGHTS reports progress at particle `k` of `nl`.
fn progress_due(verbose: bool, nl: usize, k: usize) -> bool {
    verbose && nl >= 10 && k.is_multiple_of(nl / 10)
}

impl InsertPack {
    /// The existing particles a new one must not overlap: those (and their periodic images)
    /// in the box `bblo`..`bbhi` around the region, and for blocks and cylinders only those
    /// inside or within reach of the surface (centre, radius; length).
    pub(super) fn near_particles(
        &self,
        shape: &Shape,
        w: &World,
        reach: f64,
        bblo: [f64; 3],
        bbhi: [f64; 3],
    ) -> Vec<([f64; 3], f64)> {
        let exact_near = matches!(shape, Shape::Block { .. } | Shape::Cylinder { .. });
        let mut near = Vec::new();
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
                        if exact_near && !(inside(shape, x) || surface_exterior(shape, x, cut)) {
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
        near
    }

    /// Placement with the overlap check: each particle of `list` tries random points until
    /// its spheres clear `near` (then joins it), `maxtry` tries for all of them.
    pub(super) fn place_checked(
        &mut self,
        sampler: &Sampler,
        list: &[usize],
        dist: &Distribution,
        maxtry: i64,
        mut near: Vec<([f64; 3], f64)>,
        lines: &mut Vec<String>,
    ) -> Result<Vec<NewParticle>, EngineError> {
        let mut placed: Vec<NewParticle> = Vec::new();
        let mut ntry = 0i64;
        let nl = list.len();
        while ntry < maxtry && placed.len() < nl {
            let t = list[placed.len()];
            let rb = dist.templates[t].radius;
            if progress_due(self.verbose, nl, placed.len()) {
                lines.push(format!(
                    "insertion: proc 0 at {} %",
                    10 * placed.len() / (nl / 10)
                ));
            }
            let mut done = false;
            while !done && ntry < maxtry {
                let mut p;
                loop {
                    p = sampler.point(&mut self.region_rng, rb)?;
                    ntry += 1;
                    if !(self.check_dist && ntry < maxtry && subdomain_distance(sampler.w, p) < rb)
                    {
                        break;
                    }
                }
                if ntry == maxtry {
                    break;
                }
                let v = draw_velocity(self.velocity, &mut self.rng);
                let axes = if self.random_orientation {
                    random_orientation(&mut self.rng, &dist.templates[t])
                } else {
                    None
                };
                // every sphere of the template (a clump's members) against the near
                // ones; a NaN distance counts as clear, as in LIGGGHTS
                let spheres = dist.templates[t].spheres_at(p, axes.as_ref());
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
                    placed.push((t, p, v, axes));
                    done = true;
                }
            }
        }
        Ok(placed)
    }

    /// Placement without the overlap check: one random point per particle of `list`.
    pub(super) fn place_unchecked(
        &mut self,
        sampler: &Sampler,
        list: &[usize],
        dist: &Distribution,
        lines: &mut Vec<String>,
    ) -> Result<Vec<NewParticle>, EngineError> {
        let mut placed: Vec<NewParticle> = Vec::new();
        let nl = list.len();
        for (k, &t) in list.iter().enumerate() {
            if progress_due(self.verbose, nl, k) {
                lines.push(format!("insertion: proc 0 at {} %", 10 * k / (nl / 10)));
            }
            let p = sampler.point(&mut self.region_rng, dist.templates[t].radius)?;
            let v = draw_velocity(self.velocity, &mut self.rng);
            let axes = if self.random_orientation {
                random_orientation(&mut self.rng, &dist.templates[t])
            } else {
                None
            };
            placed.push((t, p, v, axes));
        }
        Ok(placed)
    }
}
