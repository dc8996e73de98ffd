//! Mesh walls during a run: topology, stress phases and moving meshes' velocities.

use super::*;
use crate::engine::fixes::{first_wall_on, mesh_named_mut};

/// LIGGGHTS's error for a wearing stress mesh without `k_finnie` (its run's init), naming
/// the mesh `id`.
pub(crate) fn no_k_finnie(id: &str) -> EngineError {
    format!("Could not locate a fix/property storing value(s) for k_finnie as requested by meshmodule/stress (fix mesh/surface/stress {id} has wear finnie: it needs fix property/global k_finnie peratomtypepair)").into()
}

impl Simulation {
    /// LIGGGHTS's mesh setup at the first run: neighbours and active edges and corners of
    /// every `fix mesh/surface`, within the current box.
    pub(super) fn build_mesh_topology(&mut self) -> Result<(), EngineError> {
        let (lo, hi) = (self.domain.lo, self.domain.hi);
        for f in &mut self.fixes {
            if let Some(m) = f.kind.mesh_mut() {
                if !m.mesh.has_topology {
                    m.mesh.build_topology(lo, hi, &f.id)?;
                }
            }
        }
        Ok(())
    }

    /// The stress module's bookkeeping at a run's setup (clear triangle forces and step wear;
    /// read `k_finnie`), before a step's forces (clear them and the totals) and at the end of
    /// a step (add the step's wear, form the stresses).
    pub(super) fn mesh_stress_phase(&mut self, phase: StressPhase) -> Result<(), EngineError> {
        let k_finnie = match phase {
            StressPhase::Setup => self.property("k_finnie").map(|(_, cols, v)| {
                v.chunks(cols.max(1))
                    .map(|r| r.to_vec())
                    .collect::<Vec<_>>()
            }),
            _ => None,
        };
        for f in &mut self.fixes {
            let Some(m) = f.kind.mesh_mut() else {
                continue;
            };
            let Some(st) = m.stress.as_mut() else {
                continue;
            };
            match phase {
                StressPhase::Setup => {
                    st.clear_triangles();
                    match &k_finnie {
                        Some(k) => st.k_finnie = k.clone(),
                        None if st.wear_on => return Err(no_k_finnie(&f.id)),
                        None => {}
                    }
                }
                StressPhase::PreForce => st.pre_force(),
                StressPhase::EndOfStep => {
                    st.end_of_step(&m.mesh.normal, &m.mesh.area);
                    if let Some(t) = st.first_non_finite() {
                        return Err(format!(
                            "blow-up at step {}: triangle {} of mesh {} has a wear or stress that is not finite (wear {}, stresses {} {}); check k_finnie and the particles' sizes and speeds",
                            self.step,
                            t + 1,
                            f.id,
                            st.wear[t],
                            st.sigma_n.get(t).copied().unwrap_or(0.0),
                            st.sigma_t.get(t).copied().unwrap_or(0.0)
                        ).into());
                    }
                }
            }
        }
        Ok(())
    }

    /// IDs of the meshes a `fix move/mesh` moves, with the index of their first mover.
    pub(super) fn moving_meshes(&self) -> Vec<(String, usize)> {
        let mut out: Vec<(String, usize)> = Vec::new();
        for (k, f) in self.fixes.iter().enumerate() {
            if let Some(mv) = f.kind.mover() {
                if !out.iter().any(|(id, _)| id == &mv.mesh) {
                    out.push((mv.mesh.clone(), k));
                }
            }
        }
        out
    }

    /// LIGGGHTS's setup of every mesh at a run's start (`pbcExchangeBorders` with its setup
    /// flag): the surface vectors of every mesh, moving or not, recomputed from its nodes, so
    /// a mesh that moved in an earlier run gets vectors from where its nodes are now.
    pub(super) fn refresh_all_mesh_surfaces(&mut self) {
        for f in self.fixes.iter_mut() {
            if let Some(m) = f.kind.mesh_mut() {
                m.mesh.recompute_surface();
            }
        }
    }

    /// LIGGGHTS's FixMesh::pre_force for moving meshes: after a re-neighbouring, recompute
    /// the surface vectors from the nodes and remember the nodes; otherwise ask for a
    /// re-neighbouring at the next step once a node has moved more than half the skin.
    pub(super) fn refresh_moving_meshes(&mut self, rebuilt: bool) {
        let limit = 0.25 * self.neighbor.skin * self.neighbor.skin;
        let movers = self.moving_meshes().into_iter().map(|(id, _)| id);
        for id in movers.chain(self.servo_meshes()) {
            let Some(m) = mesh_named_mut(&mut self.fixes, &id) else {
                continue;
            };
            if rebuilt || m.nodes_at_refresh.len() != m.mesh.len() {
                m.mesh.recompute_surface();
                m.nodes_at_refresh = m.mesh.nodes.clone();
                continue;
            }
            let moved = m.mesh.nodes.iter().zip(&m.nodes_at_refresh).any(|(a, b)| {
                (0..3).any(|k| {
                    let d = [a[k][0] - b[k][0], a[k][1] - b[k][1], a[k][2] - b[k][2]];
                    d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > limit
                })
            });
            if moved {
                self.mesh_rebuild_at = Some(self.step + 1);
            }
        }
    }

    /// The first mover's setup zeroes its mesh's node velocities; a mesh wall defined before
    /// that mover computes its setup force with the previous run's velocities (LIGGGHTS
    /// calls the fixes' setups in definition order). `before_force`: the movers defined
    /// before every wall using their mesh; otherwise all of them.
    pub(super) fn zero_mesh_velocities(&mut self, before_force: bool) {
        for (id, first) in self.moving_meshes() {
            let wall = first_wall_on(&self.fixes, &id).map(|(k, _, _)| k);
            let mover_first = wall.is_none_or(|w| first < w);
            if let Some(m) = mesh_named_mut(&mut self.fixes, &id) {
                let n = m.mesh.len();
                match &mut m.node_v {
                    Some(v) if !before_force || mover_first => {
                        v.iter_mut().for_each(|t| *t = [[0.0; 3]; 3])
                    }
                    Some(_) => {}
                    None => m.node_v = Some(vec![[[0.0; 3]; 3]; n]),
                }
            }
        }
    }
}
