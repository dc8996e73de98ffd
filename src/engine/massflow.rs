//! `fix massflow/mesh`: counts the particles (and their mass) that cross a mesh face from its
//! inner to its outer side, as LIGGGHTS 3.8.0 does.
//!
//! Each particle carries a marker (the per-atom property `massflow_ID`): -1 before it was
//! first seen near the face, 0 on the inner side, 1 on the outer side, 2 once counted with
//! `count once`. Every step after the first half-step (LIGGGHTS's `post_integrate`), the
//! particles listed near each triangle are examined, triangle by triangle; the lists are
//! rebuilt when the pair list is, and hold the particles in LIGGGHTS's bin order, so
//! crossings are reported (and their masses summed) in LIGGGHTS's order.

use std::io::Write;
use std::sync::Mutex;

use crate::engine::error::EngineError;
use crate::engine::fixes::{mesh_named, moves_mesh};
use crate::engine::mesh::TriMesh;
use crate::engine::particles::Particles;

/// How the outer side of the face is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Side {
    /// `vec_side vx vy vz`: a vector toward the outer side of a planar face.
    Vector([f64; 3]),
    /// `point_at_outlet x y z` (length): the outer side is away from (or, with
    /// `inside_out`, toward) this point; only spheres touching the face are examined.
    Outlet {
        /// The point (length).
        point: [f64; 3],
        /// `inside_out`: count particles moving toward the point.
        inside_out: bool,
    },
}

/// The output clock of the rates f_ID[3] and f_ID[4]: time since the last output (time).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Clock {
    /// Time accumulated since the last output (time).
    t_count: f64,
    /// The interval of the current output (time).
    delta_t: f64,
    /// True once the values of the last output have been stored.
    reset: bool,
}

/// One `fix massflow/mesh`.
#[derive(Debug)]
pub struct Massflow {
    /// The `fix mesh/surface` ID.
    pub mesh: String,
    /// The outer side.
    pub side: Side,
    /// `count once`: a particle is counted at most once.
    pub once: bool,
    /// `screen yes`: each counted particle is printed.
    pub screen: bool,
    /// `writeTime`: the file lines start with the time.
    pub write_time: bool,
    /// `file`/`append`: each counted particle is written here.
    pub file: Option<std::io::BufWriter<std::fs::File>>,
    /// Name of the per-atom marker (`massflow_ID`), stored as marker + 1 (0 for new atoms).
    pub marker: String,
    /// A point of the face (length): the first node of its first triangle.
    reference: [f64; 3],
    /// The first triangle's normal, turned toward the outer side.
    normal: [f64; 3],
    /// Particle indices near each triangle, in LIGGGHTS's bin order.
    lists: Vec<Vec<u32>>,
    /// Particle indices sorted by x (scratch of the list builds).
    by_x: Vec<u32>,
    /// Mass that has crossed (mass).
    pub mass: f64,
    /// Particles that have crossed.
    pub count: f64,
    /// Mass and count at the previous output.
    last: (f64, f64),
    /// `delete_atoms yes`: counted particles are deleted at the next re-neighbouring.
    pub delete: bool,
    /// IDs of counted particles waiting to be deleted, in counting order.
    pub doomed: Vec<i64>,
    /// Mass (mass) and number of the particles deleted so far.
    pub deleted: (f64, f64),
    /// `sum_property NAME`: the particle array (fix ID) of that per-atom scalar.
    pub property: Option<String>,
    /// The sum of that property over the counted particles.
    pub property_sum: f64,
    /// Output clock (read by thermo through a shared reference).
    clock: Mutex<Clock>,
}

/// LIGGGHTS's message when `vec_side` lies in the face's plane.
const SIDE_IN_PLANE: &str = "need to change 'vec_side', it is currently in or to close to the mesh plane \nThis error may be caused by a moving mesh command, since 'vec_side' is not moved with the mesh.";

impl Massflow {
    /// A fix measuring through `mesh` (its current triangles), or LIGGGHTS's error when
    /// `vec_side` lies (nearly) in the plane of the first triangle.
    pub fn new(
        id: &str,
        mesh_id: &str,
        mesh: &TriMesh,
        side: Side,
    ) -> Result<Massflow, EngineError> {
        let mut m = Massflow {
            mesh: mesh_id.to_string(),
            side,
            once: false,
            screen: false,
            write_time: false,
            file: None,
            marker: format!("massflow_{id}"),
            reference: [0.0; 3],
            normal: [0.0; 3],
            lists: Vec::new(),
            by_x: Vec::new(),
            mass: 0.0,
            count: 0.0,
            last: (0.0, 0.0),
            delete: false,
            doomed: Vec::new(),
            deleted: (0.0, 0.0),
            property: None,
            property_sum: 0.0,
            clock: Mutex::new(Clock {
                t_count: 0.0,
                delta_t: 0.0,
                reset: true,
            }),
        };
        m.set_reference(mesh)?;
        Ok(m)
    }

    /// The reference point and the outward normal from the first triangle.
    fn set_reference(&mut self, mesh: &TriMesh) -> Result<(), EngineError> {
        let (Some(nodes), Some(&n)) = (mesh.nodes.first(), mesh.normal.first()) else {
            return Err("fix massflow/mesh: the mesh has no triangles".into());
        };
        self.reference = nodes[0];
        self.normal = n;
        let s = match self.side {
            Side::Vector(s) => s,
            Side::Outlet { .. } => [0.0; 3],
        };
        let dot = n[0] * s[0] + n[1] * s[1] + n[2] * s[2];
        if dot.abs() < 1e-6 && matches!(self.side, Side::Vector(_)) {
            return Err(SIDE_IN_PLANE.into());
        } else if dot < 0.0 {
            self.normal = [-n[0], -n[1], -n[2]];
        }
        Ok(())
    }

    /// The file header LIGGGHTS writes when the fix is defined.
    pub fn write_header(&mut self) -> std::io::Result<()> {
        let time = if self.write_time { " time " } else { "" };
        if let Some(f) = self.file.as_mut() {
            writeln!(f, "# ID{time} diameter x y z u v w  (ex ey ez, color)")?;
            f.flush()?;
        }
        Ok(())
    }

    /// Rebuild the triangle lists (at each pair-list build): the particles a sphere of its
    /// radius plus `skin` (half the neighbour skin for a still mesh, all of it for a moving
    /// one) may reach, ordered by `bin` key then index as LIGGGHTS's bins list them.
    pub fn rebuild(
        &mut self,
        p: &Particles,
        mesh: &TriMesh,
        skin: f64,
        bin: &dyn Fn(usize) -> [i64; 3],
    ) {
        self.lists.resize_with(mesh.len(), Vec::new);
        self.lists.truncate(mesh.len());
        for l in &mut self.lists {
            l.clear();
        }
        if p.is_empty() {
            return;
        }
        let rmax = p.radius.iter().copied().fold(0.0, f64::max);
        let reach = rmax + skin;
        self.by_x.clear();
        self.by_x.extend(0..p.len() as u32);
        self.by_x
            .sort_by(|&a, &b| p.x[a as usize][0].total_cmp(&p.x[b as usize][0]));
        for (t, list) in self.lists.iter_mut().enumerate() {
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            for node in &mesh.nodes[t] {
                for d in 0..3 {
                    lo[d] = lo[d].min(node[d] - reach);
                    hi[d] = hi[d].max(node[d] + reach);
                }
            }
            let first = self.by_x.partition_point(|&i| p.x[i as usize][0] < lo[0]);
            for &i in &self.by_x[first..] {
                let x = p.x[i as usize];
                if x[0] > hi[0] {
                    break;
                }
                if (1..3).any(|d| x[d] < lo[d] || x[d] > hi[d]) {
                    continue;
                }
                if mesh.near(t, x, p.radius[i as usize] + skin) {
                    list.push(i);
                }
            }
            list.sort_by_key(|&i| {
                let b = bin(i as usize);
                (b[2], b[1], b[0], i)
            });
        }
    }

    /// Whether every triangle lies in one plane with its edge neighbours (LIGGGHTS's
    /// `isPlanar`, after the topology is built).
    pub fn planar(mesh: &TriMesh) -> bool {
        (0..mesh.len()).all(|t| {
            mesh.neighbors[t]
                .iter()
                .all(|n| mesh.coplanar_neighbors[t].contains(n))
        })
    }

    /// Forget the lists (particles were reordered).
    pub fn clear_lists(&mut self) {
        self.lists.clear();
    }

    /// LIGGGHTS's `post_integrate`: examine the listed particles of `group`, count those
    /// that crossed to the outer side, print or write them; `time` is the simulation time
    /// of the step (time), `moving` whether the mesh moves.
    #[allow(clippy::too_many_arguments)]
    pub fn post_integrate(
        &mut self,
        p: &mut Particles,
        group: u32,
        mesh: &TriMesh,
        moving: bool,
        dt: f64,
        time: f64,
        out: &mut dyn FnMut(&str),
    ) -> Result<(), EngineError> {
        if moving {
            self.set_reference(mesh)?;
        }
        {
            let clock = self.clock.get_mut().unwrap_or_else(|e| e.into_inner());
            clock.t_count += dt;
            if !clock.reset {
                self.last = (self.mass, self.count);
                clock.reset = true;
            }
        }
        let k = p.extra_index(&self.marker, 1);
        let prop = self.property.as_ref().map(|n| p.extra_index(n, 1));
        let (mut mass_this, mut count_this, mut property_this) = (0.0, 0.0, 0.0);
        let lists = std::mem::take(&mut self.lists);
        let mut result = Ok(());
        'tris: for (t, list) in lists.iter().enumerate().take(mesh.len()) {
            for &i in list {
                let i = i as usize;
                if i >= p.len() || p.mask[i] & group == 0 {
                    continue;
                }
                let marker = p.extra[k].data[i] - 1.0;
                if marker == 2.0 {
                    continue;
                }
                let (x, r) = (p.x[i], p.radius[i]);
                let closest = mesh.closest(t, x, r);
                let face = closest.is_some_and(|c| c.face);
                let dot = match self.side {
                    Side::Outlet { point, inside_out } => {
                        let Some(c) = closest.filter(|c| c.gap < r) else {
                            continue;
                        };
                        let n = [x[0] - point[0], x[1] - point[1], x[2] - point[2]];
                        let d = c.to_wall[0] * n[0] + c.to_wall[1] * n[1] + c.to_wall[2] * n[2];
                        if inside_out {
                            -d
                        } else {
                            d
                        }
                    }
                    Side::Vector(_) => {
                        let d = [
                            x[0] - self.reference[0],
                            x[1] - self.reference[1],
                            x[2] - self.reference[2],
                        ];
                        d[0] * self.normal[0] + d[1] * self.normal[1] + d[2] * self.normal[2]
                    }
                };
                if marker == -1.0 {
                    p.extra[k].data[i] = if dot <= 0.0 { 1.0 } else { 2.0 };
                    continue;
                }
                if dot > 0.0 && face {
                    if marker == 0.0 {
                        mass_this += p.mass[i];
                        count_this += 1.0;
                        if let Some(q) = prop {
                            property_this += p.extra[q].data[i];
                        }
                        if self.delete {
                            // unseen again, and gone at the next re-neighbouring
                            p.extra[k].data[i] = 0.0;
                            self.doomed.push(p.id[i]);
                        }
                        result = self.report(p, i, time, out);
                        if result.is_err() {
                            break 'tris;
                        }
                    }
                    if !self.delete {
                        p.extra[k].data[i] = if self.once { 3.0 } else { 2.0 };
                    }
                } else if dot <= 0.0 {
                    p.extra[k].data[i] = 1.0;
                }
            }
        }
        self.lists = lists;
        self.mass += mass_this;
        self.count += count_this;
        self.property_sum += property_this;
        result
    }

    /// Print and write one counted particle as LIGGGHTS does (`%4.4g` values).
    fn report(
        &mut self,
        p: &Particles,
        i: usize,
        time: f64,
        out: &mut dyn FnMut(&str),
    ) -> Result<(), EngineError> {
        if !self.screen && self.file.is_none() {
            return Ok(());
        }
        let g = |v: f64| crate::util::format::with_spec("%4.4g", v).unwrap_or_default();
        let (x, v) = (p.x[i], p.v[i]);
        let values = [2.0 * p.radius[i], x[0], x[1], x[2], v[0], v[1], v[2]].map(g);
        if self.screen {
            out(&format!(" {} {} \n ", p.id[i], values.join(" ")));
        }
        if let Some(f) = self.file.as_mut() {
            let mut line = p.id[i].to_string();
            if self.write_time {
                line.push_str(&format!("  {} ", g(time)));
            }
            for v in &values {
                line.push(' ');
                line.push_str(v);
            }
            writeln!(f, "{line}")
                .and_then(|_| f.flush())
                .map_err(|e| format!("fix massflow/mesh: {e}"))?;
        }
        Ok(())
    }

    /// `f_ID[index]` (1-based): crossed mass, count, mass rate and count rate since the
    /// previous output, deleted mass and count (mass, 1, mass/time, 1/time, mass, 1), and
    /// with `sum_property` the property's sum over the counted particles. The first
    /// value read after a step starts a new output interval, as in LIGGGHTS.
    pub fn value(&self, index: usize) -> Option<f64> {
        let mut clock = self.clock.lock().unwrap_or_else(|e| e.into_inner());
        if clock.reset {
            clock.delta_t = clock.t_count;
            clock.t_count = 0.0;
            clock.reset = false;
        }
        let rate = |now: f64, then: f64| {
            if clock.delta_t == 0.0 {
                0.0
            } else {
                (now - then) / clock.delta_t
            }
        };
        match index {
            1 => Some(self.mass),
            2 => Some(self.count),
            3 => Some(rate(self.mass, self.last.0)),
            4 => Some(rate(self.count, self.last.1)),
            5 => Some(self.deleted.0),
            6 => Some(self.deleted.1),
            7 if self.property.is_some() => Some(self.property_sum),
            _ => None,
        }
    }
}

impl crate::engine::fixes::FixStyle for Massflow {
    fn name(&self) -> &str {
        "massflow/mesh"
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        Massflow::value(self, index?)
    }

    fn array_unsupported(&self) -> bool {
        true
    }

    fn keeps_per_atom_state(&self) -> bool {
        true
    }
}

impl crate::engine::sim::Simulation {
    /// LIGGGHTS's `pre_exchange` of `fix massflow/mesh ... delete_atoms yes` (at a
    /// re-neighbouring, before atoms are wrapped): each particle counted since is removed,
    /// in counting order, its slot filled by the last particle.
    pub(crate) fn massflow_delete(&mut self) {
        if !self
            .fixes
            .iter()
            .any(|f| (f.kind.style_as::<Massflow>()).is_some_and(|m| !m.doomed.is_empty()))
        {
            return;
        }
        // the fast path keeps the exact order as ranks: the exact last takes the slot
        self.assign_ranks();
        let order = self
            .particles
            .extra
            .iter()
            .position(|e| e.name == crate::engine::accel::ORDER_ARRAY);
        for f in &mut self.fixes {
            let Some(mf) = f.kind.style_as_mut::<Massflow>() else {
                continue;
            };
            let p = &mut self.particles;
            for id in std::mem::take(&mut mf.doomed) {
                let Some(i) = p.id.iter().position(|&x| x == id) else {
                    continue;
                };
                mf.deleted.0 += p.mass[i];
                mf.deleted.1 += 1.0;
                if let Some(k) = order {
                    let ranks = &mut p.extra[k].data;
                    let last = (0..ranks.len()).max_by(|&a, &b| ranks[a].total_cmp(&ranks[b]));
                    if let Some(m) = last {
                        ranks[m] = ranks[i];
                    }
                }
                p.fill_from_last(i);
            }
        }
    }

    /// Rebuild the triangle lists of every `fix massflow/mesh` (after each pair-list build
    /// and at each run's setup, where a `vec_side` face must also be planar).
    pub(crate) fn massflow_lists(&mut self, setup: bool) -> Result<(), EngineError> {
        use crate::engine::fixes::FixKind;
        if !self
            .fixes
            .iter()
            .any(|f| f.kind.style_as::<Massflow>().is_some())
        {
            return Ok(());
        }
        let order = crate::engine::neighbor::BinOrder::sized(
            self.domain.lo,
            self.domain.hi,
            self.neighbor.cutneighmax,
            self.extras.neigh_binsize,
        );
        for k in 0..self.fixes.len() {
            if self.fixes[k].kind.style_as::<Massflow>().is_none() {
                continue;
            }
            let mut kind = std::mem::replace(&mut self.fixes[k].kind, FixKind::Lent);
            let mut result: Result<(), EngineError> = Ok(());
            if let Some(mf) = kind.style_as_mut::<Massflow>() {
                let moving = moves_mesh(&self.fixes, &mf.mesh);
                let skin = if moving {
                    self.neighbor.skin
                } else {
                    0.5 * self.neighbor.skin
                };
                let mesh = mesh_named(&self.fixes, &mf.mesh).map(|m| &m.mesh);
                if let Some(mesh) = mesh {
                    if setup && matches!(mf.side, Side::Vector(_)) && !Massflow::planar(mesh) {
                        result = Err(format!(
                            "Fix massflow/mesh (id {}): requires a planar face mass flow measurement or using 'point_at_outlet'",
                            self.fixes[k].id
                        ).into());
                    }
                    let p = &self.particles;
                    mf.rebuild(p, mesh, skin, &|i| order.bin(p.x[i]));
                }
            }
            self.fixes[k].kind = kind;
            result?;
        }
        Ok(())
    }

    /// Every `fix massflow/mesh` in definition order after the first half-step (LIGGGHTS's
    /// `post_integrate`).
    pub(crate) fn massflow_phase(&mut self, out: &mut dyn FnMut(&str)) -> Result<(), EngineError> {
        use crate::engine::fixes::FixKind;
        let (dt, time) = (self.dt, self.dt * self.step as f64);
        for k in 0..self.fixes.len() {
            if self.fixes[k].kind.style_as::<Massflow>().is_none() {
                continue;
            }
            let mut kind = std::mem::replace(&mut self.fixes[k].kind, FixKind::Lent);
            let mut result = Ok(());
            if let Some(mf) = kind.style_as_mut::<Massflow>() {
                let moving = moves_mesh(&self.fixes, &mf.mesh);
                let mesh = mesh_named(&self.fixes, &mf.mesh).map(|m| &m.mesh);
                if let Some(mesh) = mesh {
                    result = mf
                        .post_integrate(
                            &mut self.particles,
                            self.fixes[k].group,
                            mesh,
                            moving,
                            dt,
                            time,
                            out,
                        )
                        .map_err(|e| format!("Fix massflow/mesh (id {}): {e}", self.fixes[k].id));
                }
            }
            self.fixes[k].kind = kind;
            result?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::mesh::MeshSettings;

    fn square(z: f64) -> TriMesh {
        let tri = [
            [[-1.0, -1.0, z], [1.0, -1.0, z], [1.0, 1.0, z]],
            [[-1.0, -1.0, z], [1.0, 1.0, z], [-1.0, 1.0, z]],
        ];
        TriMesh::new(&tri, MeshSettings::default())
    }

    #[test]
    fn a_falling_particle_is_counted_once_when_it_crosses() {
        let mesh = square(0.0);
        let mut m = Massflow::new("mf", "sq", &mesh, Side::Vector([0.0, 0.0, -1.0])).unwrap();
        m.once = true;
        let mut p = Particles::default();
        p.push(1, 1, [0.1, 0.2, 0.05], 0.01, 1000.0);
        m.rebuild(&p, &mesh, 0.1, &|_| [0; 3]);
        let mut out = |_: &str| {};
        for z in [0.05, 0.01, -0.01, 0.02, -0.02] {
            p.x[0][2] = z;
            m.post_integrate(&mut p, 1, &mesh, false, 1e-3, 0.0, &mut out)
                .unwrap();
        }
        assert_eq!(m.count, 1.0);
        assert_eq!(m.mass, p.mass[0]);
        // the first read after a step starts the interval: 5 steps of 1 ms
        assert!((m.value(3).unwrap() - p.mass[0] / 5e-3).abs() < 1e-12);
    }

    #[test]
    fn a_side_vector_in_the_plane_is_refused() {
        let mesh = square(0.0);
        assert!(Massflow::new("mf", "sq", &mesh, Side::Vector([1.0, 0.0, 0.0])).is_err());
    }
}
