//! `fix mesh/surface` (triangle meshes that walls and insertion faces use) and the
//! `initial_integrate` motion of `fix move/mesh`.

use super::{Fix, FixKind};

/// `fix mesh/surface file F type T [scale|move|rotate ...] [curvature ...]`.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshFix {
    /// The file it was read from.
    pub file: String,
    /// The wall's atom type (material).
    pub wall_type: usize,
    /// The triangles after scale/move/rotate, with their geometry and topology (length).
    pub mesh: crate::engine::mesh::TriMesh,
    /// Velocities of each triangle's nodes (length/time), for moving meshes and conveyors.
    pub node_v: Option<Vec<[[f64; 3]; 3]>>,
    /// `surface_vel vx vy vz` (length/time): the conveyor velocity, projected per triangle.
    pub surface_vel: Option<[f64; 3]>,
    /// `temperature T`: the mesh is held at T (K) for heat conduction into touching particles.
    pub temperature: Option<f64>,
    /// Defined as `mesh/surface/planar`.
    pub planar: bool,
    /// Nodes at the last refresh of a moving mesh (for the half-skin rebuild test).
    pub nodes_at_refresh: Vec<[[f64; 3]; 3]>,
    /// `mesh/surface/stress`: triangle forces, stresses and wear.
    pub stress: Option<crate::engine::mesh_stress::MeshStress>,
    /// `mesh/surface/stress/servo`: the controller that moves the mesh.
    pub servo: Option<Box<crate::engine::mesh_servo::MeshServo>>,
    /// LIGGGHTS's line of the mesh's first run setup ("Import and parallelization of mesh
    /// ... successful") has been printed.
    pub announced: bool,
}

impl MeshFix {
    /// The global value `f_ID[i]` (1-based) of the servo module, else of the stress module
    /// (None: neither has it).
    pub fn value(&self, i: usize) -> Option<f64> {
        let servo = self.servo.as_ref().and_then(|s| s.value(i));
        servo.or_else(|| self.stress.as_ref().and_then(|s| s.value(i)))
    }

    /// The triangles (nodes in STL order).
    pub fn triangles(&self) -> &[crate::io::stl::Triangle] {
        &self.mesh.nodes
    }

    /// LIGGGHTS's conveyor velocity of each node: the surface velocity with its component
    /// along the triangle normal removed, rescaled to the full speed.
    pub fn set_surface_velocity(&mut self) {
        let Some(v) = self.surface_vel else { return };
        let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let mut node_v = Vec::with_capacity(self.mesh.len());
        for n in &self.mesh.normal {
            let s = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
            let mut t = [v[0] - s * n[0], v[1] - s * n[1], v[2] - s * n[2]];
            let mag = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
            if mag > 0.0 {
                let inv = 1. / mag;
                t = t.map(|c| speed * (inv * c));
            }
            node_v.push([t; 3]);
        }
        self.node_v = Some(node_v);
    }
}

/// `fix move/mesh` in `initial_integrate`: every mover in definition order moves its mesh
/// and adds its node velocities (the first mover of a mesh zeroes them first); the rotation
/// centres of the movers after it follow the displacement.
pub fn move_meshes(fixes: &mut [Fix], dt: f64) {
    let movers: Vec<usize> = (0..fixes.len())
        .filter(|&k| fixes[k].kind.mover().is_some())
        .collect();
    for (pos, &k) in movers.iter().enumerate() {
        let mut kind = std::mem::replace(&mut fixes[k].kind, FixKind::Lent);
        let Some(mv) = kind.mover_mut() else {
            fixes[k].kind = kind;
            continue;
        };
        let first = !movers[..pos]
            .iter()
            .any(|&e| fixes[e].kind.mover().is_some_and(|o| o.mesh == mv.mesh));
        let mut shift = None;
        if let Some(m) = super::mesh_named_mut(fixes, &mv.mesh) {
            let n = m.mesh.len();
            let v = m.node_v.get_or_insert_with(|| vec![[[0.0; 3]; 3]; n]);
            if first {
                v.iter_mut().for_each(|t| *t = [[0.0; 3]; 3]);
            }
            let d = mv.step(&mut m.mesh, v, dt);
            mv.follow(&d);
            if let Some(st) = m.stress.as_mut() {
                crate::engine::mesh_motion::follow_point(&mut st.reference, &d);
            }
            shift = Some(d);
        }
        let mesh = mv.mesh.clone();
        fixes[k].kind = kind;
        if let Some(d) = shift {
            for &later in &movers[pos + 1..] {
                if let Some(o) = fixes[later].kind.mover_mut() {
                    if o.mesh == mesh {
                        o.follow(&d);
                    }
                }
            }
        }
    }
}
