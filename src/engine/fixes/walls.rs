//! `fix wall/gran`: granular walls, primitive planes and triangle meshes, and the force
//! pass of the mesh walls.

use super::{Fix, ForcePass};
use crate::engine::particles::Particles;

/// A primitive granular wall: its models, the plane, and the built interaction.
pub struct WallFix {
    /// Selected contact models.
    pub selection: crate::engine::granular::Selection,
    /// The plane.
    pub plane: crate::engine::granular::Primitive,
    /// The wall's atom type (for material coefficients).
    pub wall_type: usize,
    /// `shear dim vshear`: the wall surface moves along `dim` at `vshear` (m/s); for a
    /// cylinder sheared across its axis, it turns about the axis at `vshear` (rad/s).
    pub shear: Option<(usize, f64)>,
    /// Built at each run from the current materials.
    pub model: Option<Box<dyn crate::engine::granular::WallInteraction>>,
    /// Name of the per-particle history array (`history_<fix ID>`, as in LIGGGHTS restarts).
    pub history_name: String,
    /// `surface multicontact`: the wall's contacts `fix multicontact/halfspace` gathers.
    pub multicontact: Option<crate::engine::granular::WallStore>,
}

/// Doubles of history per wall contact of the contact model `selection` names, before a
/// run has built it (0: the model keeps no history).
pub fn dry_history_width(selection: &crate::engine::granular::Selection) -> usize {
    let mut dry = selection.clone();
    let mut surface = 0;
    if dry.surface == "multicontact" {
        dry.surface = "default".into();
        surface = crate::engine::contact::multicontact_wall::WALL_HISTORY;
    }
    crate::engine::contact::AnyContactModel::new(&dry).map_or(0, |m| surface + m.history_len())
}

/// `fix wall/gran model ... mesh n_meshes N meshes ...`.
pub struct MeshWallFix {
    /// Selected contact models.
    pub selection: crate::engine::granular::Selection,
    /// IDs of the `fix mesh/surface` meshes, in the order given.
    pub meshes: Vec<String>,
    /// Index of the fix's group (LIGGGHTS ORs it into the mesh group bits).
    pub group_index: u32,
    /// Built at each run from the current materials.
    pub model: Option<Box<dyn crate::engine::mesh_wall::MeshWallInteraction>>,
    /// Contact bookkeeping per mesh (kept across runs).
    pub trackers: Vec<crate::engine::mesh_wall::Tracker>,
    /// The pair-list build the trackers' candidate lists belong to.
    pub built: Option<u64>,
    /// `surface multicontact`: each mesh's contacts `fix multicontact/halfspace` gathers
    /// (empty for other surface models).
    pub multicontact: Vec<crate::engine::granular::WallStore>,
}

impl MeshWallFix {
    /// Doubles of history per contact of its contact model (the model of the current run,
    /// or the one its selection gives before the first run).
    pub fn history_width(&self) -> usize {
        match &self.model {
            Some(m) => m.history_width(),
            None => dry_history_width(&self.selection),
        }
    }
}

/// The meshes of a mesh wall, in its `meshes` order, as its force loop sees them.
fn mesh_refs<'a>(
    fixes: &'a [Fix],
    w: &'a MeshWallFix,
) -> Vec<crate::engine::mesh_wall::MeshRef<'a>> {
    let factor = if w.multicontact.is_empty() {
        1.0
    } else {
        crate::engine::contact::multicontact::CONTACT_DISTANCE_FACTOR
    };
    w.meshes
        .iter()
        .enumerate()
        .filter_map(|(k, id)| {
            fixes.iter().find_map(|f| match f.kind.mesh() {
                Some(m) if &f.id == id => {
                    let moving = m.servo.is_some() || super::moves_mesh(fixes, id);
                    Some(crate::engine::mesh_wall::MeshRef {
                        moving,
                        stress: m.stress.is_some(),
                        mesh: &m.mesh,
                        wall_type: m.wall_type,
                        group: f.group | w.group_index,
                        node_v: m.node_v.as_deref(),
                        factor,
                        multicontact: w.multicontact.get(k),
                        temperature: m.temperature,
                    })
                }
                _ => None,
            })
        })
        .collect()
}

/// The contacts of the mesh wall fix `fixes[k]` as a second force pass finds them, with
/// nothing applied and no history advanced (`compute wall/gran/local`); empty before the
/// wall's first run.
pub fn mesh_wall_contacts(
    fixes: &[Fix],
    k: usize,
    p: &Particles,
    dt: f64,
) -> Vec<crate::engine::mesh_wall::WallContact> {
    let Some(w) = fixes[k].kind.mesh_wall() else {
        return Vec::new();
    };
    let Some(model) = w.model.as_ref() else {
        return Vec::new();
    };
    let refs = mesh_refs(fixes, w);
    if w.trackers.len() != refs.len() {
        return Vec::new();
    }
    let mut trackers = w.trackers.clone();
    model.contacts(p, &refs, &mut trackers, dt)
}

/// Rebuild the candidate lists of the mesh wall `w`'s trackers after a pair-list build
/// (`list`: its build count and skin; `moving_skin`: mesh lists use the full skin).
pub fn refresh_trackers(
    fixes: &[Fix],
    w: &mut MeshWallFix,
    p: &Particles,
    list: (u64, f64),
    moving_skin: bool,
) {
    let mut trackers = std::mem::take(&mut w.trackers);
    let mut built = w.built;
    let refs = mesh_refs(fixes, w);
    if trackers.len() != refs.len() {
        trackers = vec![Default::default(); refs.len()];
        built = None;
    }
    if built != Some(list.0) {
        for (tr, m) in trackers.iter_mut().zip(&refs) {
            let skin = if moving_skin || m.moving {
                list.1
            } else {
                0.5 * list.1
            };
            tr.rebuild(p, m, skin);
        }
    }
    drop(refs);
    w.built = Some(list.0);
    w.trackers = trackers;
}

/// The forces of the mesh wall `w` on the particles, its meshes among `fixes` (where the
/// wall's own slot is lent out meanwhile); their stress modules sum the contacts' forces.
pub fn mesh_wall_force(
    w: &mut MeshWallFix,
    fixes: &mut [Fix],
    p: &mut Particles,
    dt: f64,
    pass: &ForcePass,
) {
    let Some(model) = w.model.take() else {
        return;
    };
    let mesh_fix: Vec<usize> = w
        .meshes
        .iter()
        .filter_map(|id| {
            fixes
                .iter()
                .position(|f| &f.id == id && f.kind.mesh().is_some())
        })
        .collect();
    refresh_trackers(fixes, w, p, pass.list, pass.moving_skin);
    let mut trackers = std::mem::take(&mut w.trackers);
    let refs = mesh_refs(fixes, w);
    let mut records = Vec::new();
    // the first heat fix's arrays take the flow of meshes at a fixed temperature
    let heat = if pass.update && refs.iter().any(|m| m.temperature.is_some()) {
        fixes.iter().find_map(|f| {
            f.kind
                .style_as::<crate::engine::heat::HeatGran>()
                .and_then(|h| crate::engine::heat::WallHeat::new(h, p))
        })
    } else {
        None
    };
    model.compute(
        p,
        &refs,
        &mut trackers,
        dt,
        pass.update,
        &mut records,
        heat.as_ref(),
    );
    drop(refs);
    w.trackers = trackers;
    w.model = Some(model);
    stress_order(fixes, &mesh_fix, &mut records);
    add_mesh_stresses(fixes, &mesh_fix, &records, p, dt);
}

/// A stress mesh sums its force and wear in LIGGGHTS's loop order (a servo feeds it back on
/// the motion; `f_ID[1..6]` and the stresses show it to the last digit): its contacts among
/// `records` (mesh index among `mesh_fix`, contact) are put in that order, after the others.
fn stress_order(
    fixes: &[Fix],
    mesh_fix: &[usize],
    records: &mut Vec<(usize, crate::engine::mesh_stress::StressContact)>,
) {
    for (k, &at) in mesh_fix.iter().enumerate() {
        let Some(st) = fixes[at].kind.mesh().and_then(|m| m.stress.as_ref()) else {
            continue;
        };
        let mut own: Vec<_> = records.iter().filter(|r| r.0 == k).map(|r| r.1).collect();
        if own.len() < 2 {
            continue;
        }
        crate::engine::mesh_servo::order_contacts(&mut own, &st.bins);
        records.retain(|r| r.0 != k);
        records.extend(own.into_iter().map(|c| (k, c)));
    }
}

/// Each contact of `records` added to its mesh's stress module (meshes with one), for
/// particles of the mesh fix's group.
fn add_mesh_stresses(
    fixes: &mut [Fix],
    mesh_fix: &[usize],
    records: &[(usize, crate::engine::mesh_stress::StressContact)],
    p: &Particles,
    dt: f64,
) {
    for (mesh_index, c) in records {
        let f = &mut fixes[mesh_fix[*mesh_index]];
        if p.mask[c.particle] & f.group == 0 {
            continue;
        }
        let Some(m) = f.kind.mesh_mut() else {
            continue;
        };
        let t = c.tri as usize;
        let (normal, area) = (m.mesh.normal[t], m.mesh.area[t]);
        if let Some(st) = m.stress.as_mut() {
            st.add(
                c,
                p.x[c.particle],
                p.v[c.particle],
                normal,
                area,
                m.wall_type,
                p.kind[c.particle] as usize,
                dt,
            );
        }
    }
}
