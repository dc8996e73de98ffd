//! Particle insertion during a run: insertion streams (`fix insert/stream`), the other
//! insertion fixes, and meshes that must stay inside the box.

use super::*;
use crate::engine::fixes::mesh_named_mut;

impl Simulation {
    pub(super) fn insert_world(&self) -> (Vec<[f64; 3]>, [bool; 3], bool) {
        let periodic = [0, 1, 2].map(|d| self.domain.periodic(d));
        (self.particles.x.clone(), periodic, self.box_changes())
    }

    /// LIGGGHTS's init checks of the `fix insert/stream` at `k` (every run; nothing for a
    /// fix of another style).
    fn stream_init_checks(&self, k: usize) -> Result<(), EngineError> {
        use crate::engine::insert::Velocity;
        let Some(sf) = self.fixes[k].kind.stream() else {
            return Ok(());
        };
        if self.clumps().is_some() && !matches!(sf.velocity, Velocity::Constant(_)) {
            return Err(format!("Fix insert/stream (id {}): Currently only fix insert/stream with multisphere particles only supports constant velocity", sf.id).into());
        }
        if sf.triangles.is_empty() {
            return Err(format!(
                "Fix insert/stream (id {}): must define an insertion face",
                sf.id
            )
            .into());
        }
        Ok(())
    }

    /// What the first setup of the `fix insert/stream` at `k` computes, with LIGGGHTS's
    /// checks in its order (its `calc_insertion_properties`): the face's normal along the
    /// velocity, the normal velocity (length/time), the steps between insertions and the
    /// extrusion length (length), the particles in all and the rates, and its distribution.
    fn stream_plan(&self, k: usize) -> Result<Option<StreamPlan>, EngineError> {
        let Some(sf) = self.fixes[k].kind.stream() else {
            return Ok(None);
        };
        let dist = self
            .fixes
            .iter()
            .filter(|f| f.id == sf.distribution)
            .find_map(|f| f.kind.distribution().cloned())
            .ok_or_else(|| {
                format!(
                    "Fix insert: could not find distribution {}",
                    sf.distribution
                )
            })?;
        // the face's triangles must lie in one plane with their neighbours (known once the
        // mesh topology is built)
        if let Some(face) = crate::engine::fixes::mesh_named(&self.fixes, &sf.face_id) {
            let m = &face.mesh;
            if m.neighbors.len() == m.len() && !crate::engine::massflow::Massflow::planar(m) {
                return Err(format!(
                    "Fix insert/stream (id {}): command requires a planar face for insertion",
                    sf.id
                )
                .into());
            }
        }
        if sf.all_in && !sf.planar {
            return Err(format!("Fix insert/stream (id {}): using all_in yes requires you to use a fix mesh/surface/planar", sf.id).into());
        }
        let (normal, v_normal, vn) = normal_velocity(sf, face_normal(&sf.triangles[0]))?;
        let (every, extrude) = stream_interval(sf, dist.max_radius, self.dt, vn)?;
        // nparticles from mass, and the other rate, from the expected particle mass
        let (total, rates) = stream_amounts(sf, dist.mass_expect)?;
        Ok(Some(StreamPlan {
            normal,
            v_normal,
            every,
            extrude,
            total,
            rates,
            dist,
        }))
    }

    /// A dry run's checks of every `fix insert/stream`, those LIGGGHTS makes at the run's
    /// init and at its first setup.
    pub(super) fn check_streams(&self) -> Result<(), EngineError> {
        for k in 0..self.fixes.len() {
            self.stream_init_checks(k)?;
            if self.fixes[k]
                .kind
                .stream()
                .is_some_and(|sf| sf.state.is_none())
            {
                self.stream_plan(k)?;
            }
        }
        Ok(())
    }

    /// First run's setup of the `fix insert/stream` at `k`: face normal, normal velocity,
    /// interval.
    pub(super) fn setup_stream(&mut self, k: usize, out: Sink<'_>) -> Result<(), EngineError> {
        self.stream_init_checks(k)?;
        let Some((state, dist)) = self.new_stream_state(k)? else {
            return Ok(());
        };
        for l in state.setup_lines(&dist) {
            out(&format!("{l}\n"));
        }
        if let Some(sf) = self.fixes[k].kind.stream_mut() {
            sf.state = Some(state);
        }
        Ok(())
    }

    /// A dry run's look at each new stream's first insertion: LIGGGHTS's Monte Carlo share
    /// of the extruded face inside the box, as the run draws it (in a box whose faces stay
    /// put until then).
    pub(super) fn check_stream_extrusions(&mut self) -> Result<(), EngineError> {
        if self.domain.shrinks() {
            return Ok(());
        }
        for k in 0..self.fixes.len() {
            let fresh = self.fixes[k]
                .kind
                .stream()
                .is_some_and(|sf| sf.state.is_none());
            if !fresh {
                continue;
            }
            if let Some((state, _)) = self.new_stream_state(k)? {
                state.check_first_extrusion(self.domain.lo, self.domain.hi)?;
            }
        }
        Ok(())
    }

    /// The state of the `fix insert/stream` at `k` at its first run's setup, and its
    /// distribution (None when it has one already or inserts nothing).
    fn new_stream_state(
        &mut self,
        k: usize,
    ) -> Result<
        Option<(
            crate::engine::insert::InsertStream,
            crate::engine::insert::Distribution,
        )>,
        EngineError,
    > {
        use crate::engine::insert::InsertStream;
        let dt = self.dt;
        let Some(sf) = self.fixes[k].kind.stream() else {
            return Ok(None);
        };
        if sf.state.is_some() {
            return Ok(None);
        }
        let Some(plan) = self.stream_plan(k)? else {
            return Ok(None);
        };
        let StreamPlan {
            normal: n,
            v_normal,
            every,
            extrude,
            total,
            rates,
            dist,
        } = plan;
        let t = sf.triangles[0];
        let triangles = sf.triangles.clone();
        let (all_in, face_id) = (sf.all_in, sf.face_id.clone());
        let face = self.stream_face(triangles, all_in, &face_id)?;
        let moving = if self.stream_integrator() == Some(k) {
            self.releases_pending(self.fixes[k].group)
        } else {
            Vec::new()
        };
        let Some(sf) = self.fixes[k].kind.stream() else {
            return Ok(None);
        };
        let restored = sf.restored;
        let state = InsertStream {
            id: sf.id.clone(),
            distribution: sf.distribution.clone(),
            face,
            normal: n,
            v_normal,
            p_ref: t[0],
            extrude,
            every,
            per_insertion: rates.0 * (every as f64 * dt),
            rates,
            total,
            velocity: sf.velocity,
            omega: sf.omega,
            overlapcheck: sf.overlapcheck,
            maxattempt: sf.maxattempt,
            ntry_mc: sf.ntry_mc,
            verbose: sf.verbose,
            rng: crate::util::random::RanPark::new(restored.map_or(sf.seed, |r| r.rng_state))?,
            next: Some(sf.start),
            measured: false,
            inserted: restored.map_or(0, |r| r.inserted),
            inserted_mass: restored.map_or(0.0, |r| r.mass),
            moving,
            first_step: restored.map_or(sf.start, |r| r.first_step),
            random_orientation: sf.random_orientation,
        };
        Ok(Some((state, dist)))
    }

    /// The insertion face of a stream: its triangles, and with `all_in` the mesh fix
    /// `face_id`'s test for whole particles inside (its topology built if need be).
    fn stream_face(
        &mut self,
        triangles: Vec<crate::io::stl::Triangle>,
        all_in: bool,
        face_id: &str,
    ) -> Result<crate::engine::insert::Face, EngineError> {
        let mut face = crate::engine::insert::Face::new(triangles);
        if all_in {
            let (lo, hi) = (self.domain.lo, self.domain.hi);
            if let Some(m) = mesh_named_mut(&mut self.fixes, face_id) {
                if !m.mesh.has_topology {
                    m.mesh.build_topology(lo, hi, face_id)?;
                }
                face.within = Some(crate::engine::insert::Within::new(&m.mesh));
            }
        }
        Ok(face)
    }

    /// `fix insert/stream` insertions due at this step.
    pub(super) fn insert_streams(&mut self, out: Sink<'_>) -> Result<(), EngineError> {
        let step = self.step;
        for k in 0..self.fixes.len() {
            let Some(sf) = self.fixes[k].kind.stream() else {
                continue;
            };
            if sf.state.as_ref().is_none_or(|s| s.next != Some(step)) {
                continue;
            }
            self.insert_rebuild_at = Some(step);
            let clock = self.fixes[k].clock.start();
            let group = self.fixes[k].group;
            let dist_id = sf.distribution.clone();
            let (dk, mut dist) = self.distribution_of(&dist_id)?;
            let (x, periodic, box_changes) = self.insert_world();
            let bodies = self.clumps().map(|c| c.bounds()).unwrap_or_default();
            let (placed, lines) = {
                let world = crate::engine::insert::World {
                    x: &x,
                    radius: &self.particles.radius,
                    mass: &self.particles.mass,
                    lo: self.domain.lo,
                    hi: self.domain.hi,
                    periodic,
                    box_changes,
                    members: crate::engine::clumps::body_tags(&self.particles),
                    bodies: &bodies,
                };
                let sf = self.fixes[k].kind.stream_mut().expect("a stream");
                let state = sf.state.as_mut().expect("set up");
                // printed before the insertion, which may refuse the face
                if state.extrusion_leaves(world.lo, world.hi) {
                    out("WARNING: Fix insert/stream: Extruded insertion face extends outside domain, may not insert all particles correctly (./src/fix_insert_stream.cpp:561)\n");
                }
                state.insert(step, &mut dist, &world, box_changes)
            }?;
            if let Some(d) = self.fixes[dk].kind.distribution_mut() {
                *d = dist.clone();
            }
            let first_new = self.particles.len();
            self.add_stream_particles(placed, &dist, group)?;
            self.record_stream_releases(k, first_new);
            for l in lines {
                out(&format!("{l}\n"));
            }
            self.fixes[k].clock.stop(clock);
        }
        Ok(())
    }

    /// Add a stream's placed particles (template, position, velocity, clump axes) with new
    /// IDs after the largest, in group `group` too.
    fn add_stream_particles(
        &mut self,
        placed: Vec<crate::engine::insert::NewParticle>,
        dist: &crate::engine::insert::Distribution,
        group: u32,
    ) -> Result<(), EngineError> {
        let mut tag = self.particles.max_id();
        for (t, xp, v, axes) in placed {
            let tpl = &dist.templates[t];
            if let Some(c) = &tpl.clump {
                self.insert_clump(c, axes, tag + 1, xp, v, [0.0; 3], group)?;
                tag += c.displace.len() as i64;
                continue;
            }
            tag += 1;
            self.particles
                .push(tag, tpl.atom_type, xp, tpl.radius, tpl.density);
            let i = self.particles.len() - 1;
            self.particles.mass[i] = tpl.mass;
            self.particles.v[i] = v;
            self.particles.mask[i] |= group;
        }
        Ok(())
    }

    /// Record stream fix `k`'s release data for the particles it inserted from index
    /// `first_new` on, and hand those in the integrating stream's group to it.
    fn record_stream_releases(&mut self, k: usize, first_new: usize) {
        let step = self.step;
        // the release step: a clump's from its centre of mass (LIGGGHTS's calc_n_steps)
        let dt = self.dt;
        let sf = self.fixes[k].kind.stream().expect("a stream");
        let st = sf.state.as_ref().expect("set up");
        let (p_ref, normal, v_normal) = (st.p_ref, st.normal, st.v_normal);
        let ba = crate::engine::clumps::body_array(&self.particles);
        let mut new = Vec::with_capacity(self.particles.len() - first_new);
        for i in first_new..self.particles.len() {
            let body = ba.map_or(-1.0, |b| self.particles.extra[b].data[i]);
            let steps = match self.clumps_mut() {
                Some(ms) if body >= 0.0 => ms.stream_steps(body, step, dt, p_ref, normal, v_normal),
                _ => None,
            };
            new.push((self.particles.id[i], self.particles.x[i], steps));
        }
        let sf = self.fixes[k].kind.stream_mut().expect("a stream");
        let records = sf.state.as_mut().expect("set up").record(step, dt, &new);
        // the new atoms are the last ones, in the order of their records
        let first = self.particles.len() - records.len();
        self.store_releases(first, &records);
        // the integrating stream moves them, if they are in its group
        if let Some(ki) = self.stream_integrator() {
            let g = self.fixes[ki].group;
            let mask = &self.particles.mask[first..];
            if let Some(sf) = self.fixes[ki].kind.stream_mut() {
                if let Some(state) = sf.state.as_mut() {
                    state.moving.extend(
                        records
                            .into_iter()
                            .zip(mask)
                            .filter(|(_, &m)| m & g != 0)
                            .map(|(r, _)| r),
                    );
                }
            }
        }
    }

    /// `fix insert/stream`'s end of step: particles not yet released move at the normal
    /// velocity from where they were inserted, without forces; at the release step they
    /// get their final velocity and spin.
    pub(super) fn move_streams(&mut self) {
        self.move_stream_particles(None);
    }

    /// [`Self::move_streams`] over the particles held here. On ranks (`ranks` given) a
    /// particle not held is another rank's: its record stays until its release step (every
    /// rank keeps the same records) and is marked as elsewhere, looked for again only when
    /// particles may have arrived (`ranks` true: a build since the last move); on one
    /// process it is gone.
    pub(super) fn move_stream_particles(&mut self, ranks: Option<bool>) {
        let owned_only = ranks.is_some();
        let arrived = ranks.unwrap_or(true);
        let (step, dt) = (self.step, self.dt);
        // the particles' places by ID, made only when a hint is stale (after a reorder)
        let mut index: Option<crate::engine::neighbor::IdIndex> = None;
        // members of clumps are released through their body
        let ba = crate::engine::clumps::body_array(&self.particles);
        let mut releases: Vec<(f64, [f64; 3], [f64; 3])> = Vec::new();
        for k in 0..self.fixes.len() {
            let Some(sf) = self.fixes[k].kind.stream_mut() else {
                continue;
            };
            let Some(state) = sf.state.as_mut() else {
                continue;
            };
            if state.moving.is_empty() {
                continue;
            }
            let p = &mut self.particles;
            state.moving.retain_mut(|r| {
                let (vn, omega) = (r.v_int, r.omega);
                if p.id.get(r.at) != Some(&r.id) {
                    // another rank's since the last look, and none has arrived since
                    if r.at == usize::MAX && !arrived {
                        return step < r.release;
                    }
                    let map =
                        index.get_or_insert_with(|| crate::engine::neighbor::IdIndex::new(&p.id));
                    let Some(i) = map.get(r.id) else {
                        r.at = usize::MAX;
                        return owned_only && step < r.release;
                    };
                    r.at = i;
                }
                let i = r.at;
                if step >= r.release {
                    if let Some(tag) = ba.map(|b| p.extra[b].data[i]).filter(|&t| t >= 0.0) {
                        releases.push((tag, r.v_final, omega));
                        return false;
                    }
                }
                let s = step.min(r.release);
                let te = (s - r.inserted) as f64 * dt;
                p.x[i] = [0, 1, 2].map(|d| r.x[d] + vn[d] * te);
                p.f[i] = [0.0; 3];
                p.torque[i] = [0.0; 3];
                if step >= r.release {
                    p.v[i] = r.v_final;
                    p.omega[i] = omega;
                    return false;
                }
                p.v[i] = vn;
                p.omega[i] = [0.0; 3];
                true
            });
        }
        if !releases.is_empty() {
            if let Some(ms) = self.clumps_mut() {
                for (tag, v, omega) in releases {
                    ms.release(tag, step, v, omega);
                }
            }
        }
    }

    /// First run's setup of `fix insert/pack`: region generator and volume.
    pub(super) fn setup_insertions(&mut self, out: Sink<'_>) -> Result<(), EngineError> {
        // in the order of the fixes, as LIGGGHTS sets them up
        for k in 0..self.fixes.len() {
            if self.fixes[k].kind.stream().is_some() {
                self.setup_stream(k, out)?;
                continue;
            }
            let Some(ins) = self.fixes[k].kind.insert_pack() else {
                continue;
            };
            let dist_id = ins.distribution.clone();
            let (_, dist) = self.distribution_of(&dist_id)?;
            let (x, periodic, box_changes) = self.insert_world();
            let bodies = self.clumps().map(|c| c.bounds()).unwrap_or_default();
            let world = crate::engine::insert::World {
                x: &x,
                radius: &self.particles.radius,
                mass: &self.particles.mass,
                lo: self.domain.lo,
                hi: self.domain.hi,
                periodic,
                box_changes,
                members: crate::engine::clumps::body_tags(&self.particles),
                bodies: &bodies,
            };
            let regions = self.regions.clone();
            let dt = self.dt;
            let Some(ins) = self.fixes[k].kind.insert_pack_mut() else {
                continue;
            };
            let lines = ins.setup(&regions, &dist, &world, dt)?;
            for l in lines {
                out(&format!("{l}\n"));
            }
        }
        Ok(())
    }

    /// `fix insert/pack` insertions due at this step.
    pub(super) fn insert_particles(&mut self, out: Sink<'_>) -> Result<(), EngineError> {
        let step = self.step;
        for k in 0..self.fixes.len() {
            let Some(ins) = self.fixes[k].kind.insert_pack() else {
                continue;
            };
            if ins.next != Some(step) {
                continue;
            }
            self.insert_rebuild_at = Some(step);
            let clock = self.fixes[k].clock.start();
            let dist_id = ins.distribution.clone();
            let group = self.fixes[k].group;
            let (dk, mut dist) = self.distribution_of(&dist_id)?;
            let (x, periodic, box_changes) = self.insert_world();
            let bodies = self.clumps().map(|c| c.bounds()).unwrap_or_default();
            let regions = self.regions.clone();
            let (placed, lines) = {
                let world = crate::engine::insert::World {
                    x: &x,
                    radius: &self.particles.radius,
                    mass: &self.particles.mass,
                    lo: self.domain.lo,
                    hi: self.domain.hi,
                    periodic,
                    box_changes,
                    members: crate::engine::clumps::body_tags(&self.particles),
                    bodies: &bodies,
                };
                let ins = self.fixes[k]
                    .kind
                    .insert_pack_mut()
                    .expect("an insert/pack");
                ins.insert(step, &regions, &mut dist, &world)
            }?;
            let omega = self.fixes[k]
                .kind
                .insert_pack()
                .map_or([0.0; 3], |ins| ins.omega);
            if let Some(d) = self.fixes[dk].kind.distribution_mut() {
                *d = dist.clone();
            }
            let mut tag = self.particles.max_id();
            for (t, xp, v, axes) in placed {
                let tpl = &dist.templates[t];
                if let Some(c) = &tpl.clump {
                    self.insert_clump(c, axes, tag + 1, xp, v, omega, group)?;
                    tag += c.displace.len() as i64;
                    continue;
                }
                tag += 1;
                self.particles
                    .push(tag, tpl.atom_type, xp, tpl.radius, tpl.density);
                let i = self.particles.len() - 1;
                self.particles.mass[i] = tpl.mass;
                self.particles.v[i] = v;
                self.particles.omega[i] = omega;
                self.particles.mask[i] |= group;
            }
            for l in lines {
                out(&format!("{l}\n"));
            }
            self.fixes[k].clock.stop(clock);
        }
        Ok(())
    }

    /// LIGGGHTS's check at setup: mesh triangles whose centre lies outside the box (along
    /// directions with fixed or periodic faces; the faces padded by 1e-8 length) are an error.
    pub(super) fn check_meshes_in_box(&self) -> Result<(), EngineError> {
        for k in 0..self.fixes.len() {
            self.check_mesh_in_box(k)?;
        }
        Ok(())
    }

    /// [`Simulation::check_meshes_in_box`] for the mesh of fix `k` (nothing for another fix).
    pub fn check_mesh_in_box(&self, k: usize) -> Result<(), EngineError> {
        let d = &self.domain;
        let f = &self.fixes[k];
        if let Some(m) = f.kind.mesh() {
            let lost = m
                .triangles()
                .iter()
                .filter(|t| {
                    (0..3).any(|k| {
                        let c = (t[0][k] + t[1][k] + t[2][k]) / 3.0;
                        let fixed = d.boundary[k].iter().all(|b| {
                            matches!(
                                b,
                                crate::engine::domain::Boundary::Fixed
                                    | crate::engine::domain::Boundary::Periodic
                            )
                        });
                        // LIGGGHTS pads the box faces by SMALL_DMBRDR against round-off
                        fixed && !(c >= d.lo[k] - 1.0e-8 && c < d.hi[k] + 1.0e-8)
                    })
                })
                .count();
            if lost > 0 {
                let all = if lost == m.triangles().len() {
                    "All "
                } else {
                    ""
                };
                return Err(format!(
                    "Mesh (id {}): {all}{lost} mesh elements have been lost / left the domain. \nPlease use 'boundary m m m' or scale/translate/rotate the mesh or change its dynamics",
                    f.id
                ).into());
            }
        }
        Ok(())
    }

    /// The index of the insertion fixes' distribution `id` among the fixes and a copy of it
    /// (the insertion draws from the copy, which then replaces it), or LIGGGHTS's error.
    fn distribution_of(
        &self,
        id: &str,
    ) -> Result<(usize, crate::engine::insert::Distribution), EngineError> {
        match crate::engine::fixes::distribution_named(&self.fixes, id) {
            None => Err(format!("Fix insert: could not find distribution {id}").into()),
            Some((_, None)) => {
                Err(format!("Fix insert: {id} is not a particle distribution").into())
            }
            Some((k, Some(d))) => Ok((k, d.clone())),
        }
    }

    /// The fix moving every stream's particles until release: the first insert/stream
    /// (LIGGGHTS's i_am_integrator).
    pub(super) fn stream_integrator(&self) -> Option<usize> {
        self.fixes.iter().position(|f| f.kind.stream().is_some())
    }
}

/// What a stream's first setup computes ([`Simulation::stream_plan`]).
struct StreamPlan {
    /// The face's unit normal, turned along the insertion velocity.
    normal: [f64; 3],
    /// The insertion velocity's part along the normal (length/time).
    v_normal: [f64; 3],
    /// Steps between insertions.
    every: i64,
    /// The extrusion length (length).
    extrude: f64,
    /// The particles to insert in all.
    total: i64,
    /// Particles and mass per time.
    rates: (f64, f64),
    /// A copy of the stream's distribution.
    dist: crate::engine::insert::Distribution,
}

/// The unit normal of triangle `t`, as LIGGGHTS computes it from its first two edges.
fn face_normal(t: &crate::io::stl::Triangle) -> [f64; 3] {
    let mut ev = [[0.0; 3]; 2];
    for (j, e) in ev.iter_mut().enumerate() {
        let d = [0, 1, 2].map(|c| t[j + 1][c] - t[j][c]);
        let inv = 1.0 / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        *e = d.map(|c| inv * c);
    }
    let c = [
        ev[0][1] * ev[1][2] - ev[0][2] * ev[1][1],
        ev[0][2] * ev[1][0] - ev[0][0] * ev[1][2],
        ev[0][0] * ev[1][1] - ev[0][1] * ev[1][0],
    ];
    let inv = 1.0 / (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
    c.map(|x| inv * x)
}

/// The face normal `n` turned along the stream's velocity, the velocity's normal part
/// (length/time) and its magnitude; LIGGGHTS's error for a velocity along the face.
fn normal_velocity(
    sf: &crate::engine::fixes::StreamFix,
    mut n: [f64; 3],
) -> Result<([f64; 3], [f64; 3], f64), EngineError> {
    use crate::engine::insert::Velocity;
    let v = match sf.velocity {
        Velocity::Constant(v) | Velocity::Uniform(v, _) | Velocity::Gaussian(v, _) => v,
    };
    if v[0] * n[0] + v[1] * n[1] + v[2] * n[2] < 0.0 {
        n = n.map(|x| -x);
    }
    let dot = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
    let v_normal = n.map(|x| x * dot);
    let vn =
        (v_normal[0] * v_normal[0] + v_normal[1] * v_normal[1] + v_normal[2] * v_normal[2]).sqrt();
    if vn < 1e-3 {
        return Err(format!(
            "Fix insert/stream (id {}): insertion velocity projected on face normal is < 1e-3",
            sf.id
        )
        .into());
    }
    Ok((n, v_normal, vn))
}

/// A stream's steps between insertions and extrusion length (length), from
/// `extrude_length` or `insert_every` (`rbound`: the largest bounding radius, length; `vn`:
/// the normal speed), with LIGGGHTS's checks.
fn stream_interval(
    sf: &crate::engine::fixes::StreamFix,
    rbound: f64,
    dt: f64,
    vn: f64,
) -> Result<(i64, f64), EngineError> {
    // an extrude_length of 0 is none (LIGGGHTS's default)
    let given = sf.extrude.filter(|&l| l > 0.0);
    let refuse =
        |what: &str| -> EngineError { format!("Fix insert/stream (id {}): {what}", sf.id).into() };
    match (given, sf.every) {
        (None, None) => {
            return Err(refuse(
                "must define either 'insert_every' or 'extrude_length'",
            ))
        }
        (Some(_), Some(_)) => {
            return Err(refuse(
                "must not provide both 'insert_every' and 'extrude_length'",
            ))
        }
        (Some(_), None) if sf.duration.is_some() => {
            return Err(refuse(
                "must not provide both 'extrude_length' and 'duration'",
            ))
        }
        _ => {}
    }
    match (given, sf.every) {
        (Some(l), _) => {
            if l < 3.0 * rbound && (sf.all_in || sf.overlapcheck) {
                return Err(format!(
                    "Fix insert/stream (id {}): 'extrude_length' is too small",
                    sf.id
                )
                .into());
            }
            let every = ((l + 1e-14) / (dt * vn)) as i32 as i64;
            if every == 0 {
                return Err(format!("Fix insert/stream (id {}): insertion velocity too high or extrude_length too low", sf.id).into());
            }
            Ok((every, l))
        }
        (None, Some(e)) => {
            if e < 1 {
                return Err(format!(
                    "Fix insert/stream (id {}): 'insert_every' must be > 0",
                    sf.id
                )
                .into());
            }
            // particles travel `duration` steps (default: insert_every) in the zone
            let duration = sf.duration.unwrap_or(e);
            if duration > e {
                return Err(format!(
                    "Fix insert/stream (id {}): 'duration' > 'insert_every' not allowed",
                    sf.id
                )
                .into());
            }
            let l = duration as f64 * dt * vn;
            if l < 2.0 * rbound {
                return Err(format!("Fix insert/stream (id {}): 'insert_every' or 'vel' is too small, or (bounding) radius of inserted particles too large", sf.id).into());
            }
            Ok((e, l))
        }
        (None, None) => unreachable!("refused above"),
    }
}

/// A stream's particles in all, and its rates (particles and mass per time), from
/// `nparticles` or `mass` and `particlerate` or `massrate` (`me`: the expected particle
/// mass).
fn stream_amounts(
    sf: &crate::engine::fixes::StreamFix,
    me: f64,
) -> Result<(i64, (f64, f64)), EngineError> {
    let refuse =
        |what: &str| -> EngineError { format!("Fix insert/stream (id {}): {what}", sf.id).into() };
    let total = match sf.total {
        None => return Err(refuse("must define either 'nparticles' or 'mass'")),
        Some(Ok(n)) => n,
        Some(Err(mass)) => {
            if mass / me > 2.0e9 {
                return Err(format!("Fix insert/stream (id {}): you are attempting to insert more than 2e9 particles. Reduce the mass to be inserted or increase the particle diameter", sf.id).into());
            }
            ((mass + 1e-14) / me) as i64
        }
    };
    let rates = match sf.rate {
        None => return Err(refuse("must define either 'massrate' or 'particlerate'")),
        Some(Ok(n)) => (n, n * me),
        Some(Err(m)) => (m / me, m),
    };
    Ok((total, rates))
}
