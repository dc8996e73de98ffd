//! `fix wall/gran model ... mesh n_meshes N meshes M1 M2 ...`: granular contacts of spheres
//! with triangle meshes, as LIGGGHTS 3.8.0 computes them.
//!
//! Each particle keeps, per mesh, the triangles it may touch (rebuilt with the pair list) and
//! one history slot per candidate triangle. A touching triangle reports its closest active
//! feature; a new face contact is suppressed when the particle already touched a coplanar
//! neighbour triangle this step, and inherits the history of coplanar neighbours it touched
//! the step before, so a sphere rolling across a flat mesh feels one continuous contact. A
//! slot dies on the first step without contact. The wall is a body of infinite radius and
//! mass; moving meshes and conveyor belts give it a velocity interpolated at the contact.

use crate::engine::contact::multicontact::Entry;
use crate::engine::contact::multicontact_wall::{apart, touching, WALL_HISTORY, WALL_REACH};
use crate::engine::contact::{
    CohesionModel, ContactKernel, ContactModel, Material, MaterialInput, NormalModel, RollingModel,
    TangentialModel, WallInput,
};
use crate::engine::error::EngineError;
use crate::engine::granular::Selection;
use crate::engine::granular::WallStore;
use crate::engine::heat::WallHeat;
use crate::engine::mesh::TriMesh;
use crate::engine::mesh_stress::StressContact;
use crate::engine::particles::Particles;

/// Most history doubles a mesh contact can hold.
pub const MAX_HISTORY: usize = 8;

/// One particle's mesh contacts as a restart file keeps them: (triangle id, history values).
pub type MeshContacts = Vec<(i32, Vec<f64>)>;

/// One history slot of a particle: the triangle it belongs to (-1: free) and its values.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Slot {
    partner: i32,
    keep: bool,
    hist: [f64; MAX_HISTORY],
}

const FREE: Slot = Slot {
    partner: -1,
    keep: false,
    hist: [0.0; MAX_HISTORY],
};

/// Per-mesh contact bookkeeping of every particle (LIGGGHTS's neighlist/mesh and
/// contacthistory/mesh).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Tracker {
    /// Atom ID of each particle index when the lists were last built.
    ids: Vec<i64>,
    /// Candidate triangles of each particle, in ID order.
    cand: Vec<Vec<u32>>,
    /// History slots of each particle (as many as candidates).
    slots: Vec<Vec<Slot>>,
}

impl Tracker {
    /// Entries in the candidate lists (LIGGGHTS's total number of contacts of a mesh
    /// neighbour list: particle-triangle pairs within reach at the last build).
    pub fn candidate_count(&self) -> usize {
        self.cand.iter().map(Vec::len).sum()
    }

    /// Candidate triangles of particle `i` (LIGGGHTS's `n_neighs_mesh`).
    pub fn candidates_of(&self, i: usize) -> usize {
        self.cand.get(i).map_or(0, Vec::len)
    }

    /// The multicontact surface values (the first four history values) of particle `i`'s
    /// contacts, as `fix multicontact/halfspace` reads them: the values of the k-th used
    /// slot under the triangle ID of the k-th slot (LIGGGHTS pairs them so; the two differ
    /// when a free slot comes before a used one).
    pub fn multicontact_entries(&self, i: usize) -> Vec<(i32, Entry)> {
        let Some(slots) = self.slots.get(i) else {
            return Vec::new();
        };
        slots
            .iter()
            .filter(|s| s.partner >= 0)
            .enumerate()
            .map(|(k, s)| {
                (
                    slots[k].partner,
                    [s.hist[0], s.hist[1], s.hist[2], s.hist[3]],
                )
            })
            .collect()
    }

    /// Contacts (triangle, history) of the particle with atom ID `id`, for restarts and
    /// reports.
    pub fn contacts_of(&self, index: usize) -> Vec<(i32, Vec<f64>)> {
        self.slots.get(index).map_or(Vec::new(), |s| {
            s.iter()
                .filter(|s| s.partner >= 0)
                .map(|s| (s.partner, s.hist.to_vec()))
                .collect()
        })
    }

    /// A tracker holding the contacts a restart file stored: per atom ID, (triangle id,
    /// history) in slot order (LIGGGHTS's `tracker_<mesh>`). The candidate lists are built,
    /// and contacts no longer in reach dropped, at the first force computation.
    pub fn from_restart(
        ids: &[i64],
        stored: &std::collections::HashMap<i64, Vec<(i32, Vec<f64>)>>,
    ) -> Tracker {
        let slots = ids
            .iter()
            .map(|id| {
                stored.get(id).map_or(Vec::new(), |list| {
                    list.iter()
                        .map(|(tri, h)| {
                            let mut hist = [0.0; MAX_HISTORY];
                            let n = h.len().min(MAX_HISTORY);
                            hist[..n].copy_from_slice(&h[..n]);
                            Slot {
                                partner: *tri,
                                keep: false,
                                hist,
                            }
                        })
                        .collect()
                })
            })
            .collect();
        Tracker {
            ids: ids.to_vec(),
            cand: vec![Vec::new(); ids.len()],
            slots,
        }
    }

    /// What a restart file keeps of this tracker for the particles with atom IDs `ids`:
    /// each one's number of candidate triangles (LIGGGHTS's `n_neighs_mesh_<mesh>`) and its
    /// contacts, (triangle id, the first `width` history values), in LIGGGHTS's packed slot
    /// order.
    pub fn restart_entries(&self, ids: &[i64], width: usize) -> Vec<(usize, MeshContacts)> {
        let index: std::collections::HashMap<i64, usize> =
            self.ids.iter().enumerate().map(|(k, &t)| (t, k)).collect();
        ids.iter()
            .map(|id| {
                let Some(&k) = index.get(id) else {
                    return (0, Vec::new());
                };
                let mut slots = self.slots.get(k).cloned().unwrap_or_default();
                pack(&mut slots);
                let contacts = slots
                    .iter()
                    .filter(|s| s.partner >= 0)
                    .map(|s| (s.partner, s.hist[..width].to_vec()))
                    .collect();
                (self.cand.get(k).map_or(0, Vec::len), contacts)
            })
            .collect()
    }

    /// Atom IDs of the particles the per-particle records belong to, by index.
    pub fn ids(&self) -> &[i64] {
        &self.ids
    }

    /// Append the record of particle `index` (None: a particle without one) to `out` as it
    /// travels between ranks: its candidate triangles, then its used history slots packed
    /// as a rebuild packs them (triangle id and [`MAX_HISTORY`] values each).
    pub fn encode(&self, index: Option<usize>, out: &mut Vec<f64>) {
        let cand = index
            .and_then(|i| self.cand.get(i))
            .map_or(&[][..], Vec::as_slice);
        out.push(cand.len() as f64);
        out.extend(cand.iter().map(|&t| f64::from(t)));
        let mut slots = index
            .and_then(|i| self.slots.get(i))
            .cloned()
            .unwrap_or_default();
        pack(&mut slots);
        let used = slots.iter().take_while(|s| s.partner >= 0);
        out.push(used.clone().count() as f64);
        for s in used {
            out.push(f64::from(s.partner));
            out.extend_from_slice(&s.hist);
        }
    }

    /// Append the particle with atom ID `id` and the record [`Self::encode`] wrote at the
    /// start of `record`; the doubles it took (None: the record is cut short).
    pub fn push_decoded(&mut self, id: i64, record: &[f64]) -> Option<usize> {
        let mut at = 0;
        let mut next = || {
            let v = record.get(at).copied();
            at += 1;
            v
        };
        let ncand = next()? as usize;
        let cand = (0..ncand)
            .map(|_| next().map(|t| t as u32))
            .collect::<Option<Vec<u32>>>()?;
        let nused = next()? as usize;
        let mut slots = Vec::with_capacity(nused);
        for _ in 0..nused {
            let partner = next()? as i32;
            let mut hist = [0.0; MAX_HISTORY];
            for h in &mut hist {
                *h = next()?;
            }
            slots.push(Slot {
                partner,
                keep: false,
                hist,
            });
        }
        self.ids.push(id);
        self.cand.push(cand);
        self.slots.push(slots);
        Some(at)
    }

    /// Reorder the per-particle records with the particles (`order`: new index -> old).
    pub fn permute(&mut self, order: &[usize]) {
        if self.ids.len() == order.len() {
            self.ids = order.iter().map(|&k| self.ids[k]).collect();
        }
        if self.cand.len() == order.len() {
            self.cand = order
                .iter()
                .map(|&k| std::mem::take(&mut self.cand[k]))
                .collect();
        }
        if self.slots.len() == order.len() {
            self.slots = order
                .iter()
                .map(|&k| std::mem::take(&mut self.slots[k]))
                .collect();
        }
    }

    /// Rebuild the candidate lists after the pair list was rebuilt: slots follow their atoms
    /// (by ID) through reordering, are packed, and lose triangles no longer listed.
    pub fn rebuild(&mut self, p: &Particles, mesh: &MeshRef, skin: f64) {
        // LIGGGHTS's sort_contacts: used slots packed to the front (not order-preserving)
        for s in &mut self.slots {
            pack(s);
        }
        // follow the atoms
        if self.ids != p.id {
            let mut old: std::collections::HashMap<i64, Vec<Slot>> =
                std::collections::HashMap::with_capacity(self.ids.len());
            for (k, s) in std::mem::take(&mut self.slots).into_iter().enumerate() {
                if !s.is_empty() {
                    old.insert(self.ids[k], s);
                }
            }
            self.slots =
                p.id.iter()
                    .map(|id| old.remove(id).unwrap_or_default())
                    .collect();
            self.ids = p.id.clone();
        }
        self.cand = candidates(p, mesh, skin);
        for (s, cand) in self.slots.iter_mut().zip(&self.cand) {
            // cleanUpContactJumps: drop partners no longer listed (the last used slot moves in)
            let mut k = 0;
            while k < s.len() {
                if s[k].partner >= 0 && cand.binary_search(&(s[k].partner as u32)).is_err() {
                    let last = s.iter().rposition(|x| x.partner >= 0).unwrap_or(k);
                    s[k] = s[last];
                    s[last] = FREE;
                    if last == k {
                        k += 1;
                    }
                } else {
                    k += 1;
                }
            }
            let used: Vec<Slot> = s.iter().copied().filter(|x| x.partner >= 0).collect();
            s.clear();
            s.extend(used);
            s.resize(cand.len().max(s.len()), FREE);
        }
    }
}

/// Pack used slots to the front by swapping the first free slot with the last used one.
fn pack(s: &mut [Slot]) {
    loop {
        let free = s.iter().position(|x| x.partner < 0);
        let used = s.iter().rposition(|x| x.partner >= 0);
        match (free, used) {
            (Some(f), Some(u)) if f < u => {
                s.swap(f, u);
            }
            _ => return,
        }
    }
}

/// Candidate triangles of each particle: those a sphere of its radius times the contact
/// distance factor plus `skin` may reach (LIGGGHTS's prism test), found through a grid of
/// the particles.
fn candidates(p: &Particles, mesh: &MeshRef, skin: f64) -> Vec<Vec<u32>> {
    let n = p.len();
    let mut cand = vec![Vec::new(); n];
    let members: Vec<usize> = (0..n).filter(|&i| p.mask[i] & mesh.group != 0).collect();
    if members.is_empty() || mesh.mesh.is_empty() {
        return cand;
    }
    let rmax = members.iter().map(|&i| p.radius[i]).fold(0.0, f64::max);
    let reach_max = rmax * mesh.factor + skin;
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &i in &members {
        for d in 0..3 {
            lo[d] = lo[d].min(p.x[i][d]);
            hi[d] = hi[d].max(p.x[i][d]);
        }
    }
    // cells at least the reach wide, and not many more cells than particles
    let mut h = (2.0 * reach_max).max(1e-300);
    let cells_for = |h: f64| -> f64 {
        (0..3)
            .map(|d| ((hi[d] - lo[d]) / h).floor() + 1.0)
            .product()
    };
    while cells_for(h) > 8.0 * members.len() as f64 + 64.0 {
        h *= 2.0;
    }
    let dims = [0, 1, 2].map(|d| (((hi[d] - lo[d]) / h).floor() as usize) + 1);
    let cell_of =
        |x: [f64; 3]| [0, 1, 2].map(|d| (((x[d] - lo[d]) / h).floor() as usize).min(dims[d] - 1));
    let flat = |c: [usize; 3]| (c[2] * dims[1] + c[1]) * dims[0] + c[0];
    let mut heads = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
    for &i in &members {
        heads[flat(cell_of(p.x[i]))].push(i);
    }
    let m = mesh.mesh;
    for t in 0..m.len() {
        let mut blo = [f64::INFINITY; 3];
        let mut bhi = [f64::NEG_INFINITY; 3];
        for node in &m.nodes[t] {
            for d in 0..3 {
                blo[d] = blo[d].min(node[d] - reach_max);
                bhi[d] = bhi[d].max(node[d] + reach_max);
            }
        }
        if (0..3).any(|d| bhi[d] < lo[d] || blo[d] > hi[d]) {
            continue;
        }
        let c0 = cell_of([0, 1, 2].map(|d| blo[d].max(lo[d])));
        let c1 = cell_of([0, 1, 2].map(|d| bhi[d].min(hi[d])));
        for cz in c0[2]..=c1[2] {
            for cy in c0[1]..=c1[1] {
                for cx in c0[0]..=c1[0] {
                    for &i in &heads[flat([cx, cy, cz])] {
                        if m.near(t, p.x[i], p.radius[i] * mesh.factor + skin) {
                            cand[i].push(t as u32);
                        }
                    }
                }
            }
        }
    }
    cand
}

/// What the force loop needs of one mesh.
pub struct MeshRef<'a> {
    /// The mesh.
    pub mesh: &'a TriMesh,
    /// Its atom type (material).
    pub wall_type: usize,
    /// Particles it acts on: mask bits (LIGGGHTS's mesh group bit OR'd with the wall fix's
    /// group index, a quirk kept for identical results).
    pub group: u32,
    /// Velocities of each triangle's nodes (moving meshes, conveyor belts), if any.
    pub node_v: Option<&'a [[[f64; 3]; 3]]>,
    /// A `fix move/mesh` moves it (its contact lists use the full skin).
    pub moving: bool,
    /// `mesh/surface/stress`: record each contact for the mesh's forces and wear.
    pub stress: bool,
    /// The contact distance factor its neighbour lists use (1; 2 with `surface
    /// multicontact`).
    pub factor: f64,
    /// `surface multicontact`: the mesh's contacts `fix multicontact/halfspace` gathered.
    pub multicontact: Option<&'a WallStore>,
    /// `temperature T`: the mesh's fixed temperature (K), conducting into touching particles.
    pub temperature: Option<f64>,
}

/// One particle-triangle contact as the contact model evaluated it: what `compute
/// wall/gran/local` reports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallContact {
    /// Index of the mesh in the wall's `meshes` list.
    pub mesh: usize,
    /// Triangle id (STL order).
    pub tri: u32,
    /// Particle index.
    pub particle: usize,
    /// Vector from the particle centre to the closest wall point (m).
    pub to_wall: [f64; 3],
    /// Wall velocity at the contact (m/s).
    pub v_wall: [f64; 3],
    /// Signed gap (m, negative when overlapping).
    pub gap: f64,
    /// The contact model's force, torque and normal on the particle.
    pub out: crate::engine::contact::WallOutput,
    /// The contact's history after the evaluation (the first `history_width` values).
    pub hist: [f64; MAX_HISTORY],
}

/// Read-only particles for a force pass that applies nothing.
pub struct ReadOnly<'a>(pub &'a Particles);

impl AsRef<Particles> for ReadOnly<'_> {
    fn as_ref(&self) -> &Particles {
        self.0
    }
}

/// Mesh wall contacts with a contact model, monomorphised for its sub-models.
pub trait MeshWallInteraction: Send {
    /// Doubles of history per contact.
    fn history_width(&self) -> usize;
    /// Add the forces and torques of every mesh in `meshes` (in order) to the particles;
    /// `trackers[k]` belongs to `meshes[k]`. Contacts with meshes that keep stresses are
    /// appended to `records` with the mesh's index. With `heat`, meshes at a fixed
    /// temperature conduct into the particles they touch.
    #[allow(clippy::too_many_arguments)]
    fn compute(
        &self,
        p: &mut Particles,
        meshes: &[MeshRef],
        trackers: &mut [Tracker],
        dt: f64,
        update: bool,
        records: &mut Vec<(usize, StressContact)>,
        heat: Option<&WallHeat>,
    );
    /// The contacts a second force pass finds, applying nothing and advancing no history
    /// (LIGGGHTS's compute wall/gran/local re-runs the wall's loop this way at output).
    fn contacts(
        &self,
        p: &Particles,
        meshes: &[MeshRef],
        trackers: &mut [Tracker],
        dt: f64,
    ) -> Vec<WallContact>;
}

/// A contact model acting between particles and meshes.
pub struct MeshWallGran<N, T, C, R> {
    /// The composed contact model.
    pub model: ContactModel<N, T, C, R>,
    /// Coefficients per (particle type, mesh type).
    pub material: Material,
    /// `surface multicontact` (the model is its dry rest): its surface values lead each
    /// contact's history, and contacts apart by less than the radius are kept.
    pub multicontact: bool,
    /// Contacts resolved farther than this (m, LIGGGHTS's `cutneighmax`) are skipped
    /// (multicontact).
    pub cutneighmax: f64,
}

/// Find or make the slot of a touching contact with triangle `id` (LIGGGHTS's
/// handleContact); None when a coplanar neighbour already counted this contact.
#[inline]
fn handle_contact(slots: &mut [Slot], id: u32, face: bool, mesh: &TriMesh) -> Option<usize> {
    let id = id as i32;
    if let Some(k) = slots.iter().position(|s| s.partner == id) {
        slots[k].keep = true;
        return Some(k);
    }
    let coplanar = |other: i32| {
        mesh.coplanar_neighbors[id as usize]
            .binary_search(&(other as u32))
            .is_ok()
    };
    if face
        && slots
            .iter()
            .any(|s| s.partner >= 0 && s.keep && coplanar(s.partner))
    {
        return None;
    }
    let k = slots.iter().position(|s| s.partner < 0)?;
    slots[k] = Slot {
        partner: id,
        keep: true,
        hist: [0.0; MAX_HISTORY],
    };
    if face {
        for j in 0..slots.len() {
            if j != k && slots[j].partner >= 0 && coplanar(slots[j].partner) {
                slots[k].hist = slots[j].hist;
            }
        }
    }
    Some(k)
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> MeshWallInteraction
    for MeshWallGran<N, T, C, R>
{
    fn history_width(&self) -> usize {
        self.surface_len() + self.model.history_len()
    }

    fn compute(
        &self,
        p: &mut Particles,
        meshes: &[MeshRef],
        trackers: &mut [Tracker],
        dt: f64,
        update: bool,
        records: &mut Vec<(usize, StressContact)>,
        heat: Option<&WallHeat>,
    ) {
        self.pass(
            p,
            meshes,
            trackers,
            dt,
            update,
            &mut |p: &mut Particles, c: &WallContact| {
                let i = c.particle;
                let before = p.f[i];
                for d in 0..3 {
                    p.f[i][d] += c.out.f[d];
                    p.torque[i][d] += c.out.t[d];
                }
                if meshes[c.mesh].stress {
                    let after = p.f[i];
                    records.push((
                        c.mesh,
                        StressContact {
                            tri: c.tri,
                            particle: i,
                            force: [0, 1, 2].map(|d| after[d] - before[d]),
                            to_wall: c.to_wall,
                            v_wall: c.v_wall,
                        },
                    ));
                }
                // LIGGGHTS adds the wall's heat flow after the contact's force
                if let (Some(h), Some(t_wall)) = (heat, meshes[c.mesh].temperature) {
                    h.add(p, i, p.radius[i], -c.gap, meshes[c.mesh].wall_type, t_wall);
                }
            },
        );
    }

    fn contacts(
        &self,
        p: &Particles,
        meshes: &[MeshRef],
        trackers: &mut [Tracker],
        dt: f64,
    ) -> Vec<WallContact> {
        let mut out = Vec::new();
        self.pass(
            &mut ReadOnly(p),
            meshes,
            trackers,
            dt,
            false,
            &mut |_, c| out.push(*c),
        );
        out
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>
    MeshWallGran<N, T, C, R>
{
    /// History values of the surface model before the dry models' (4 with `surface
    /// multicontact`).
    fn surface_len(&self) -> usize {
        if self.multicontact {
            WALL_HISTORY
        } else {
            0
        }
    }

    /// LIGGGHTS's mesh loop: every mesh, every particle, every candidate triangle; each
    /// touching contact is evaluated and handed to `sink` with the particles.
    #[inline]
    fn pass<P: AsRef<Particles>, S: FnMut(&mut P, &WallContact)>(
        &self,
        p: &mut P,
        meshes: &[MeshRef],
        trackers: &mut [Tracker],
        dt: f64,
        update: bool,
        sink: &mut S,
    ) {
        let off = self.surface_len();
        let w = self.model.history_len();
        for (mesh_index, (mref, tr)) in meshes.iter().zip(trackers.iter_mut()).enumerate() {
            let m = mref.mesh;
            for i in 0..p.as_ref().len().min(tr.cand.len()) {
                if tr.cand[i].is_empty() {
                    continue;
                }
                let slots = &mut tr.slots[i];
                for s in slots.iter_mut() {
                    s.keep = false;
                }
                let ncand = tr.cand[i].len();
                for &t in &tr.cand[i] {
                    let q = p.as_ref();
                    // multicontact: the radius at this triangle is changed by the half-space step
                    let radius = match mref.multicontact {
                        Some(s) => q.radius[i] + s.change(i, t as i32, ncand).unwrap_or(0.0),
                        None => q.radius[i],
                    };
                    let Some(c) = m.closest(t as usize, q.x[i], radius) else {
                        continue;
                    };
                    if self.multicontact && c.gap > self.cutneighmax {
                        continue;
                    }
                    let touches = c.gap <= 0.0;
                    // a NaN gap is no contact
                    let close = self.multicontact && c.gap < WALL_REACH * q.radius[i];
                    if !(touches || close) {
                        continue;
                    }
                    let Some(k) = handle_contact(slots, t, c.face, m) else {
                        continue;
                    };
                    let (hs, hm) = slots[k].hist[..off + w].split_at_mut(off);
                    if !touches {
                        if update {
                            apart(hs, c.to_wall, radius);
                        }
                        self.model.surfaces_close(hm);
                        continue;
                    }
                    let v_wall = mref
                        .node_v
                        .map_or([0.0; 3], |v| wall_velocity(&v[t as usize], c.bary));
                    let input = WallInput {
                        x: q.x[i],
                        gap: c.gap,
                        to_wall: c.to_wall,
                        radius,
                        mass: q.mass[i],
                        v: q.v[i],
                        omega: q.omega[i],
                        v_wall,
                        dt,
                        update_history: update,
                        coeffs: self.material.pair(q.kind[i] as usize, mref.wall_type),
                    };
                    let out = self.model.wall_force(&input, hm);
                    if self.multicontact && update {
                        touching(hs, c.to_wall, out.f, out.en);
                    }
                    let hist = slots[k].hist;
                    sink(
                        p,
                        &WallContact {
                            mesh: mesh_index,
                            tri: t,
                            particle: i,
                            to_wall: c.to_wall,
                            v_wall,
                            gap: c.gap,
                            out,
                            hist,
                        },
                    );
                }
                // a contact not touched this step is gone, and so is its history
                for s in slots.iter_mut() {
                    if s.partner >= 0 && !s.keep {
                        *s = FREE;
                    }
                }
            }
        }
    }
}

/// Build the mesh wall interaction for a selection, monomorphised once per run. With
/// `surface multicontact` the dry rest of the selection is built, and `cutneighmax` (m) is
/// LIGGGHTS's.
pub fn build(
    sel: &Selection,
    input: &MaterialInput,
    cutneighmax: f64,
) -> Result<Box<dyn MeshWallInteraction>, EngineError> {
    let multicontact = sel.surface == "multicontact";
    let mut dry = sel.clone();
    if multicontact {
        dry.surface = "default".into();
    }
    let model = crate::engine::contact::AnyContactModel::new(&dry).map_err(|e| e.to_string())?;
    let surface = if multicontact { WALL_HISTORY } else { 0 };
    if surface + model.history_len() > MAX_HISTORY {
        return Err(format!(
            "fix wall/gran mesh: contact models with more than {MAX_HISTORY} history values are not supported"
        ).into());
    }
    let material = Material::new(input, &model.properties())?;
    struct Make(Material, bool, f64);
    impl ContactKernel for Make {
        type Output = Box<dyn MeshWallInteraction>;
        fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
            self,
            m: &ContactModel<N, T, C, R>,
        ) -> Self::Output {
            Box::new(MeshWallGran {
                model: *m,
                material: self.0,
                multicontact: self.1,
                cutneighmax: self.2,
            })
        }
    }
    Ok(model.dispatch(Make(material, multicontact, cutneighmax)))
}

/// The velocity (m/s) of a triangle's surface at barycentric point `b`, from its nodes'
/// velocities `v` (LIGGGHTS's sum order).
fn wall_velocity(v: &[[f64; 3]; 3], b: [f64; 3]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for d in 0..3 {
        out[d] = (b[0] * v[0][d] + b[1] * v[1][d]) + b[2] * v[2][d];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn slot(partner: i32, keep: bool, v: f64) -> Slot {
        Slot {
            partner,
            keep,
            hist: [v; MAX_HISTORY],
        }
    }

    #[test]
    fn packing_swaps_the_last_used_slot_into_the_first_hole() {
        let mut s = [
            slot(1, false, 1.),
            FREE,
            slot(2, false, 2.),
            slot(3, false, 3.),
        ];
        pack(&mut s);
        let order: Vec<i32> = s.iter().map(|x| x.partner).collect();
        assert_eq!(order, vec![1, 3, 2, -1]);
    }

    #[test]
    fn a_particle_record_between_ranks_is_the_packed_slots_and_candidates() {
        let t = Tracker {
            ids: vec![4, 9],
            cand: vec![vec![0, 3, 5], vec![]],
            slots: vec![vec![slot(3, true, 1.5), FREE, slot(5, false, -2.0)], vec![]],
        };
        let mut out = Vec::new();
        t.encode(Some(0), &mut out);
        let first = out.len();
        t.encode(None, &mut out);
        assert_eq!(out.len(), first + 2, "no candidates, no slots");
        let mut back = Tracker::default();
        assert_eq!(back.push_decoded(4, &out), Some(first));
        assert_eq!(back.push_decoded(7, &out[first..]), Some(2));
        assert_eq!(back.push_decoded(8, &out[..first - 1]), None);
        assert_eq!(back.ids, vec![4, 7]);
        assert_eq!(back.cand, vec![vec![0, 3, 5], vec![]]);
        // the used slots packed as a rebuild packs them, their values bit for bit
        let mut packed = t.slots[0].clone();
        pack(&mut packed);
        packed.truncate(2);
        packed.iter_mut().for_each(|s| s.keep = false);
        assert_eq!(back.slots, vec![packed, vec![]]);
    }

    #[test]
    fn coplanar_face_contacts_count_once_and_pass_history_on() {
        let t0 = [[-0.05, -0.05, 0.], [0.05, -0.05, 0.], [0.05, 0.05, 0.]];
        let t1 = [[-0.05, -0.05, 0.], [0.05, 0.05, 0.], [-0.05, 0.05, 0.]];
        let mut m = TriMesh::new(&[t0, t1], crate::engine::mesh::MeshSettings::default());
        m.build_topology([-0.1; 3], [0.1; 3], "square").unwrap();
        // a contact kept on triangle 0 this step suppresses a new face contact on 1
        let mut s = vec![slot(0, true, 5.), FREE];
        assert_eq!(handle_contact(&mut s, 1, true, &m), None);
        // from the step before (not yet kept), triangle 1 inherits its history
        let mut s = vec![slot(0, false, 5.), FREE];
        assert_eq!(handle_contact(&mut s, 1, true, &m), Some(1));
        assert_eq!(s[1].hist[0], 5.);
        // an existing slot is found again
        assert_eq!(handle_contact(&mut s, 0, true, &m), Some(0));
        assert!(s[0].keep);
    }
}
