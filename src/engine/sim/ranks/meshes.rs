//! Mesh walls on more than one rank: each rank computes the mesh contacts of the particles
//! it owns, with every mesh whole on every rank (static meshes and meshes `fix move/mesh`
//! moves alike: each rank moves its copy the same way). A particle's candidate triangles
//! and contact history per mesh (LIGGGHTS's `neighlist/mesh` and `contacthistory/mesh`)
//! travel with it between ranks, encoded into its [`PartnerHistory`] record.

use super::*;
use crate::engine::decomp::PartnerHistory;
use crate::engine::mesh_wall::Tracker;
use std::collections::HashMap;

/// The mesh walls' trackers, per mesh wall fix in fix order (one tracker per mesh).
pub(super) type WallTrackers = Vec<Vec<Tracker>>;

impl Simulation {
    /// Write the mesh walls' records of the particles with atom IDs `ids` (the rows of
    /// `hist`) into `hist.attached`: per mesh wall in fix order, its tracker count, then
    /// each tracker's record of the particle ([`Tracker::encode`]).
    pub(super) fn attach_wall_state(&self, hist: &mut PartnerHistory, ids: &[i64]) {
        hist.attached.resize(ids.len(), Vec::new());
        for f in &self.fixes {
            let Some(w) = f.kind.mesh_wall() else {
                continue;
            };
            let index: Vec<HashMap<i64, usize>> = w
                .trackers
                .iter()
                .map(|t| t.ids().iter().enumerate().map(|(k, &id)| (id, k)).collect())
                .collect();
            for (id, out) in ids.iter().zip(hist.attached.iter_mut()) {
                out.push(w.trackers.len() as f64);
                for (t, index) in w.trackers.iter().zip(&index) {
                    t.encode(index.get(id).copied(), out);
                }
            }
        }
    }

    /// The mesh walls' trackers made again for the particles with atom IDs `ids` from
    /// their records `attached` (written by [`Self::attach_wall_state`] on any rank).
    pub(super) fn restore_wall_state(
        &mut self,
        attached: &[Vec<f64>],
        ids: &[i64],
    ) -> Result<(), EngineError> {
        let cut = || {
            EngineError::Invalid("a mesh wall's contact record between ranks is cut short".into())
        };
        let mut at = vec![0usize; ids.len()];
        for f in &mut self.fixes {
            let Some(w) = f.kind.mesh_wall_mut() else {
                continue;
            };
            let n = w.trackers.len();
            let mut trackers = vec![Tracker::default(); n];
            for (i, &id) in ids.iter().enumerate() {
                let record = attached.get(i).ok_or_else(cut)?;
                let count = *record.get(at[i]).ok_or_else(cut)?;
                if count != n as f64 {
                    return Err(EngineError::Invalid(format!(
                        "ranks disagree on the meshes of fix {} ({count} and {n})",
                        f.id
                    )));
                }
                at[i] += 1;
                for t in &mut trackers {
                    let rest = record.get(at[i]..).ok_or_else(cut)?;
                    at[i] += t.push_decoded(id, rest).ok_or_else(cut)?;
                }
            }
            w.trackers = trackers;
        }
        Ok(())
    }

    /// A copy of the mesh walls' trackers, to put back with [`Self::put_wall_trackers`].
    pub(super) fn save_wall_trackers(&self) -> WallTrackers {
        let walls = self.fixes.iter().filter_map(|f| f.kind.mesh_wall());
        walls.map(|w| w.trackers.clone()).collect()
    }

    /// Put back the trackers [`Self::save_wall_trackers`] copied.
    pub(super) fn put_wall_trackers(&mut self, saved: WallTrackers) {
        let walls = self.fixes.iter_mut().filter_map(|f| f.kind.mesh_wall_mut());
        for (w, t) in walls.zip(saved) {
            w.trackers = t;
        }
    }

    /// LIGGGHTS's mesh setup at a run's start on ranks, as on one process: the meshes'
    /// topology in the current box, their surface vectors, the moving meshes' reference
    /// nodes and the node velocities the first movers zero before the setup forces.
    pub(super) fn rank_mesh_setup(&mut self) -> Result<(), EngineError> {
        self.build_mesh_topology()?;
        self.refresh_all_mesh_surfaces();
        self.refresh_moving_meshes(true);
        self.zero_mesh_velocities(true);
        Ok(())
    }
}
