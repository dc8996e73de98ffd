//! `fix insert/stream`: the insertion face, the volume particles are placed in, their
//! release onto the integrator, and the restart state of the stream.

use super::*;

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
pub(super) const MAXTRY_WITHIN: usize = 500;

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
pub(super) fn first_extreme(v: &[f64; 6], better: impl Fn(f64, f64) -> bool) -> usize {
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
pub(super) fn edge_point_dist(e: &TriangleEdges, i: usize, p: [f64; 3]) -> f64 {
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
    /// Where the particle stood in the particle arrays when last moved (a hint, checked
    /// against its ID before use; `usize::MAX` when not known).
    pub at: usize,
}

/// Width of LIGGGHTS's per-atom release data (`release_fix_insert_stream`).
pub const RELEASE_WIDTH: usize = 14;

/// Name of the per-atom release data, as LIGGGHTS's insert/stream names its property/atom.
pub const RELEASE_NAME: &str = "release_fix_insert_stream";

/// LIGGGHTS's tolerance when it turns stored steps back into integers.
pub(super) const STEP_TINY: f64 = 1e-14;

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
            at: usize::MAX,
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
    /// Total to insert ([`UNLIMITED`] for `nparticles INF` or `mass INF`).
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
    /// `orientation random`.
    pub random_orientation: bool,
}

/// The total of `nparticles INF` and `mass INF`: particles are inserted at the rate until
/// the runs end.
pub const UNLIMITED: i64 = i64::MAX;

impl InsertStream {
    /// The setup line LIGGGHTS prints.
    pub fn setup_lines(&self, dist: &Distribution) -> Vec<String> {
        let (rate, mass_rate) = self.rates;
        let f = |spec: &str, v: f64| crate::util::format::with_spec(spec, v).unwrap_or_default();
        if self.total == UNLIMITED {
            // without a total LIGGGHTS prints the rates alone
            return vec![format!(
                "INFO: Particle insertion {}: {} particles every {} steps - particle rate {}  (mass rate {})",
                self.id,
                f("%f", self.per_insertion),
                self.every,
                f("%f", rate),
                f("%e", mass_rate),
            )];
        }
        vec![format!(
            "INFO: Particle insertion {}: {} particles every {} steps - particle rate {}  (mass rate {})\n      {} particles (mass {}) within {} steps",
            self.id,
            f("%f", self.per_insertion),
            self.every,
            f("%f", rate),
            f("%e", mass_rate),
            self.total,
            f("%e", self.total as f64 * dist.mass_expect),
            // LIGGGHTS's final insertion step minus the first
            if self.total as f64 <= self.per_insertion {
                0
            } else {
                ((self.total as f64 / self.per_insertion) as i32 as f64 * self.every as f64) as i32
            }
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
        let n = self.count_this_insertion();
        if !self.measured || box_changes {
            self.check_extrusion_inside_box(w.lo, w.hi)?;
        }
        let list = dist.list(n)?;
        if !list.is_empty() {
            lines.extend(narrow_box_warning(w, dist.max_radius));
        }
        // LIGGGHTS's nearby test uses the largest sphere radius (a clump's largest member)
        let near = if self.overlapcheck {
            self.atoms_near_extrusion(w, dist.max_sphere_radius())
        } else {
            Vec::new()
        };
        let placed = self.place_templates(&list, dist, w, near, &mut lines);
        self.account_inserted(step, n, &placed, dist, &mut lines);
        Ok((placed, lines))
    }

    /// The Monte Carlo test of the first insertion on a copy of this new stream (its
    /// random numbers drawn as that insertion draws them), in the box `lo`..`hi` (length).
    pub fn check_first_extrusion(&self, lo: [f64; 3], hi: [f64; 3]) -> Result<(), EngineError> {
        let mut copy = self.clone();
        copy.count_this_insertion();
        copy.check_extrusion_inside_box(lo, hi)
    }

    /// How many particles this insertion asks for: the mean per insertion plus a uniform
    /// draw, truncated, and never past the total.
    fn count_this_insertion(&mut self) -> i64 {
        let mut n = (self.per_insertion + self.rng.uniform()) as i64;
        if self.inserted + n > self.total {
            n = self.total - self.inserted;
        }
        if self.inserted + n >= self.total {
            n = (self.total - self.inserted).max(0);
        }
        n
    }

    /// LIGGGHTS's Monte Carlo share of the extruded face inside the box (`ntry_mc`
    /// samples): below 0.9 or above 1.1 it refuses to insert.
    fn check_extrusion_inside_box(
        &mut self,
        lo: [f64; 3],
        hi: [f64; 3],
    ) -> Result<(), EngineError> {
        let mut inside = 0i64;
        for _ in 0..self.ntry_mc {
            let p = self.face.random_point();
            let r = -self.rng.uniform() * self.extrude;
            let q = [0, 1, 2].map(|d| p[d] + r * self.normal[d]);
            if (0..3).all(|d| q[d] >= lo[d] && q[d] < hi[d]) {
                inside += 1;
            }
        }
        self.measured = true;
        let share = inside as f64 / self.ntry_mc.max(1) as f64;
        if !(0.9..=1.1).contains(&share) {
            return Err(format!(
                "Fix insert/stream (id {}): insertion volume could not be distributed \
                 properly in parallel. Bad decomposition or insertion face extrusion is too \
                 small or outside domain",
                self.id
            )
            .into());
        }
        Ok(())
    }

    /// Existing atoms (position, radius) a new particle could overlap: within `rmax`
    /// (length) above the face, or the extrusion plus three `rmax` below it, and over the face.
    fn atoms_near_extrusion(&self, w: &World, rmax: f64) -> Vec<([f64; 3], f64)> {
        let nrm = self.normal;
        let mut near = Vec::new();
        for i in 0..w.x.len() {
            let x = w.x[i];
            let dn = (x[0] - self.p_ref[0]) * nrm[0]
                + (x[1] - self.p_ref[1]) * nrm[1]
                + (x[2] - self.p_ref[2]) * nrm[2];
            if dn > rmax || dn < -(self.extrude + 3.0 * rmax) {
                continue;
            }
            if self
                .face
                .covers([x[0] + nrm[0] * dn, x[1] + nrm[1] * dn, x[2] + nrm[2] * dn])
            {
                near.push((x, w.radius[i]));
            }
        }
        near
    }

    /// Places the templates of `list` in turn, at most `maxattempt` tries each on average
    /// (the tries are shared), each clear of `near` when `overlapcheck` is on; a placed
    /// particle joins `near`.
    fn place_templates(
        &mut self,
        list: &[usize],
        dist: &Distribution,
        w: &World,
        mut near: Vec<([f64; 3], f64)>,
        lines: &mut Vec<String>,
    ) -> Vec<NewParticle> {
        let maxtry = (list.len() as i64).saturating_mul(self.maxattempt);
        let mut ntry = 0;
        let mut placed: Vec<NewParticle> = Vec::new();
        while ntry < maxtry && placed.len() < list.len() {
            let t = list[placed.len()];
            let rad = dist.templates[t].radius;
            let mut done = false;
            while !done && ntry < maxtry {
                let p = self.draw_position(rad, w, &mut ntry, maxtry, lines);
                if ntry < maxtry {
                    let axes = if self.random_orientation {
                        random_orientation(&mut self.rng, &dist.templates[t])
                    } else {
                        None
                    };
                    // every sphere of the template (a clump's members) against the near ones
                    let spheres = dist.templates[t].spheres_at(p, axes.as_ref());
                    if !self.overlapcheck || clear_of(&spheres, &near) {
                        near.extend(spheres);
                        placed.push((t, p, self.v_normal, axes));
                        done = true;
                    }
                }
            }
        }
        placed
    }

    /// A centre for a sphere of radius `rad` (length): a point on the face pushed back
    /// into the extrusion, redrawn (counting each draw in `ntry`) while it lies outside
    /// the box or, with `overlapcheck`, closer than `rad` to the box's walls.
    fn draw_position(
        &mut self,
        rad: f64,
        w: &World,
        ntry: &mut i64,
        maxtry: i64,
        lines: &mut Vec<String>,
    ) -> [f64; 3] {
        let nrm = self.normal;
        let in_box = |p: [f64; 3]| (0..3).all(|d| p[d] >= w.lo[d] && p[d] < w.hi[d]);
        loop {
            let p = if self.face.within.is_some() {
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
            let p = [p[0] + nrm[0] * r, p[1] + nrm[1] * r, p[2] + nrm[2] * r];
            *ntry += 1;
            let bad =
                !in_box(p) || (self.overlapcheck && super::place::subdomain_distance(w, p) < rad);
            if !(*ntry < maxtry && bad) {
                return p;
            }
        }
    }

    /// Adds the placed particles to the running totals, schedules the next insertion and
    /// writes LIGGGHTS's report (`verbose`) and its warning when fewer than `n` were placed.
    fn account_inserted(
        &mut self,
        step: i64,
        n: i64,
        placed: &[NewParticle],
        dist: &Distribution,
        lines: &mut Vec<String>,
    ) {
        let m: f64 = placed.iter().map(|(t, ..)| dist.templates[*t].mass).sum();
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
    }

    /// Whether the bounding box of the face and its extrusion reaches outside the box `lo`..`hi`
    /// (length), as LIGGGHTS checks before each insertion (a corner exactly on the box
    /// surface is inside; the extruded corner is the face's plus -extrude times the normal,
    /// rounded as LIGGGHTS rounds it).
    pub fn extrusion_leaves(&self, lo: [f64; 3], hi: [f64; 3]) -> bool {
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        for v in self.face.triangles.iter().flatten() {
            for k in 0..3 {
                min[k] = min[k].min(v[k]);
                max[k] = max[k].max(v[k]);
            }
        }
        let shift = self.normal.map(|n| n * -self.extrude);
        let low = [0, 1, 2].map(|k| min[k].min(min[k] + shift[k]));
        let high = [0, 1, 2].map(|k| max[k].max(max[k] + shift[k]));
        let inside = |p: [f64; 3]| (0..3).all(|k| p[k] >= lo[k] && p[k] <= hi[k]);
        !(inside(low) && inside(high))
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

    /// Release data of the atoms just inserted (ID, position, and the steps to release of
    /// a clump's member, else from the atom's own distance to the face), final velocities
    /// drawn now; returns the new records.
    pub fn record(
        &mut self,
        step: i64,
        dt: f64,
        atoms: &[(i64, [f64; 3], Option<i64>)],
    ) -> Vec<Release> {
        let mut out = Vec::with_capacity(atoms.len());
        let vn = {
            let v = self.v_normal;
            (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
        };
        for &(id, x, member_steps) in atoms {
            let rel = [0, 1, 2].map(|k| self.p_ref[k] - x[k]);
            let dn = rel[0] * self.normal[0] + rel[1] * self.normal[1] + rel[2] * self.normal[2];
            let steps = member_steps.unwrap_or(((dn + 1e-14) / (vn * dt)) as i64);
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
                at: usize::MAX,
            });
        }
        out
    }
}

/// Whether every sphere (centre, radius; length) is clear of every `near` sphere; a NaN
/// distance counts as clear, as in LIGGGHTS.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
fn clear_of(spheres: &[([f64; 3], f64)], near: &[([f64; 3], f64)]) -> bool {
    spheres.iter().all(|&(s, rs_new)| {
        near.iter().all(|(q, rq)| {
            let d = [s[0] - q[0], s[1] - q[1], s[2] - q[2]];
            let rs = rs_new + rq;
            !(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= rs * rs)
        })
    })
}
