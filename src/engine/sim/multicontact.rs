//! `fix multicontact/halfspace` with walls: before each force evaluation the walls' contacts
//! are gathered from their history into their stores, which the pair style's half-space
//! step reads after each particle's pair contacts and the wall loops read back.

use super::*;
use crate::engine::contact::multicontact_wall::WALL_HISTORY;
use crate::engine::granular::WallStore;

impl Simulation {
    /// LIGGGHTS's `pre_force` of the fix for the walls: every wall store (primitive walls
    /// and meshes, in wall order) is cleared, laid out anew when due, and given the wall
    /// contacts of each particle of the fix's group. The stores are handed to the pair
    /// style for its half-space step; [`Self::multicontact_walls_back`] returns them.
    pub(super) fn multicontact_walls_to_pair(&mut self, update: bool) {
        let Some(pair) = self.pair.as_mut() else {
            return;
        };
        let Some(slot) = pair.multicontact_walls() else {
            return;
        };
        slot.clear();
        let group = self
            .fixes
            .iter()
            .find(|f| matches!(&f.kind, FixKind::Style(s) if s.multicontact_prefactor().is_some()))
            .map_or(0, |f| f.group);
        let list = (self.list.builds, self.neighbor.skin);
        let moving_skin = self.box_changes();
        let mut stores = Vec::new();
        for k in 0..self.fixes.len() {
            let mut kind = std::mem::replace(&mut self.fixes[k].kind, FixKind::Lent);
            if let Some(w) = kind.style_as_mut::<fixes::WallFix>() {
                if let Some(mut s) = w.multicontact.take() {
                    let width = w.model.as_ref().map_or(0, |m| m.history_width());
                    let hist = self
                        .particles
                        .extra
                        .iter()
                        .find(|e| e.name == w.history_name && e.width == width)
                        .map(|e| (&e.data[..], e.width));
                    primitive_entries(&mut s, &self.particles, group, &w.plane, hist, list, update);
                    stores.push(s);
                }
            }
            match kind.mesh_wall_mut() {
                Some(w) if !w.multicontact.is_empty() => {
                    fixes::refresh_trackers(&self.fixes, w, &self.particles, list, moving_skin);
                    for (s, tr) in w.multicontact.iter_mut().zip(&w.trackers) {
                        let p = &self.particles;
                        let rebuild = s.due(list.0, !update);
                        s.clear(&p.id, rebuild, |i| tr.candidates_of(i));
                        for i in (0..p.len()).filter(|&i| p.mask[i] & group != 0) {
                            for (tri, e) in tr.multicontact_entries(i) {
                                s.add(i, tri, e);
                            }
                        }
                    }
                    stores.append(&mut w.multicontact);
                }
                _ => {}
            }
            self.fixes[k].kind = kind;
        }
        if let Some(slot) = self.pair.as_mut().and_then(|p| p.multicontact_walls()) {
            *slot = stores;
        }
    }

    /// Give the wall stores back to their walls after the pair style's evaluation; after
    /// a setup evaluation (`update` false) each store is laid out anew, empty, as LIGGGHTS's
    /// stores clear themselves in their own setup.
    pub(super) fn multicontact_walls_back(&mut self, update: bool) {
        let Some(slot) = self.pair.as_mut().and_then(|p| p.multicontact_walls()) else {
            return;
        };
        let mut stores = std::mem::take(slot).into_iter();
        let half = 0.5 * self.neighbor.skin;
        let p = &self.particles;
        for f in &mut self.fixes {
            if let Some(w) = f.kind.style_as_mut::<fixes::WallFix>() {
                if w.selection.surface == "multicontact" {
                    w.multicontact = stores.next();
                    if let Some(s) = w.multicontact.as_mut().filter(|_| !update) {
                        let shape = w.plane;
                        s.clear(&p.id, true, |i| {
                            usize::from(shape.near(p.x[i], p.radius[i], half))
                        });
                    }
                }
                continue;
            }
            match f.kind.mesh_wall_mut() {
                Some(w) if w.selection.surface == "multicontact" => {
                    w.multicontact = stores.by_ref().take(w.meshes.len()).collect();
                    if !update {
                        for (s, tr) in w.multicontact.iter_mut().zip(&w.trackers) {
                            s.clear(&p.id, true, |i| tr.candidates_of(i));
                        }
                    }
                }
                _ => {}
            }
        }
    }
}

/// A primitive wall's store for this evaluation: particles near the wall (half the skin)
/// reserve a slot at a rebuild; each particle of `group` whose history `hist` (particle-
/// major, the surface values first) holds a surface position adds it with its force.
fn primitive_entries(
    s: &mut WallStore,
    p: &Particles,
    group: u32,
    shape: &crate::engine::granular::Primitive,
    hist: Option<(&[f64], usize)>,
    list: (u64, f64),
    update: bool,
) {
    let rebuild = s.due(list.0, !update);
    let half = 0.5 * list.1;
    s.clear(&p.id, rebuild, |i| {
        usize::from(shape.near(p.x[i], p.radius[i], half))
    });
    let Some((hist, width)) = hist.filter(|h| h.1 >= WALL_HISTORY) else {
        return;
    };
    for i in (0..p.len()).filter(|&i| p.mask[i] & group != 0) {
        let h = &hist[i * width..i * width + WALL_HISTORY];
        if h[0] * h[0] + h[1] * h[1] + h[2] * h[2] > 1e-14 {
            s.add(i, 1, [h[0], h[1], h[2], h[3]]);
        }
    }
}
