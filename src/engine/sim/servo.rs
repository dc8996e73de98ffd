//! Servo meshes (`fix mesh/surface/stress/servo`) during a run: LIGGGHTS's checks and setup
//! at a run's start, the motion at `initial_integrate` and the controller after the forces.

use super::*;
use crate::engine::fixes::{first_wall_on, mesh_named_mut, moves_mesh};

impl Simulation {
    /// IDs of the meshes a servo drives.
    pub(super) fn servo_meshes(&self) -> Vec<String> {
        self.fixes
            .iter()
            .filter(|f| f.kind.mesh().is_some_and(|m| m.servo.is_some()))
            .map(|f| f.id.clone())
            .collect()
    }

    /// A run's start: LIGGGHTS's checks (a granular wall uses the mesh, no `fix move/mesh`
    /// moves it, `vel_max < skin / (2 dt)`), then the origin of the displacement and the
    /// auto mode's slow speed from the smallest particle radius.
    pub(super) fn servo_setup(&mut self) -> Result<(), EngineError> {
        let r_min = self.particles.radius.iter().copied().reduce(f64::min);
        let (skin, dt) = (self.neighbor.skin, self.dt);
        for id in self.servo_meshes() {
            let walled = first_wall_on(&self.fixes, &id).is_some();
            if !walled {
                return Err(format!("Fix mesh/surface/stress/servo (id {id}): The servo-wall requires a contact model. Therefore, it has to be used for a fix wall/gran too.").into());
            }
            if moves_mesh(&self.fixes, &id) {
                return Err(format!("Fix mesh/surface/stress/servo (id {id}): this fix does not allow superposition with moving mesh fixes").into());
            }
            let Some(m) = mesh_named_mut(&mut self.fixes, &id) else {
                continue;
            };
            let Some(s) = m.servo.as_mut() else { continue };
            if s.vel_max >= skin / (2. * dt) {
                return Err(format!(
                    "Fix mesh/surface/stress/servo (id {id}): vel_max < skin/(2.*dt) required"
                )
                .into());
            }
            s.setup(&m.mesh, r_min, dt);
        }
        Ok(())
    }

    /// After a list build: every mesh with a stress module (servo meshes among them)
    /// remembers the particles' neighbour bins, the order in which LIGGGHTS lists them for
    /// its triangles and sums their forces on the mesh.
    pub(super) fn servo_bins(&mut self) {
        let stressed = |f: &Fix| f.kind.mesh().is_some_and(|m| m.stress.is_some());
        if !self.fixes.iter().any(stressed) {
            return;
        }
        let order = crate::engine::neighbor::BinOrder::sized(
            self.domain.lo,
            self.domain.hi,
            self.neighbor.cutneighmax,
            self.extras.neigh_binsize,
        );
        let bins: std::sync::Arc<Vec<[i64; 3]>> =
            std::sync::Arc::new(self.particles.x.iter().map(|x| order.bin(*x)).collect());
        for f in &mut self.fixes {
            if let Some(st) = f.kind.mesh_mut().and_then(|m| m.stress.as_mut()) {
                st.bins = std::sync::Arc::clone(&bins);
            }
        }
    }

    /// `initial_integrate`: each servo moves its mesh; the stress module's reference point
    /// follows the centre of mass.
    pub(super) fn servo_initial_integrate(&mut self) {
        let dt = self.dt;
        for f in &mut self.fixes {
            let Some(m) = f.kind.mesh_mut() else {
                continue;
            };
            let Some(s) = m.servo.as_mut() else { continue };
            s.initial_integrate(&mut m.mesh, dt);
            if let Some(st) = m.stress.as_mut() {
                st.reference = s.xcm;
            }
        }
    }

    /// After the stress module's totals: each servo's controller sets the next step's
    /// velocity of its mesh (every node moves with it).
    pub(super) fn servo_final_integrate(
        &mut self,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let dt = self.dt;
        for id in self.servo_meshes() {
            // a variable set point, evaluated before this servo's controller
            let variable = mesh_named_mut(&mut self.fixes, &id)
                .and_then(|m| m.servo.as_ref())
                .filter(|s| s.integrate)
                .and_then(|s| s.set_point_var.clone());
            if let Some(name) = variable {
                let target = vars.equal(self, &name)?;
                if target == 0. {
                    return Err(format!("Fix mesh/surface/stress/servo (id {id}): Set point (desired force/torque/shear) has to be != 0.0").into());
                }
                if let Some(s) = mesh_named_mut(&mut self.fixes, &id).and_then(|m| m.servo.as_mut())
                {
                    s.set_point = -target;
                }
            }
            // entries in the mesh's contact lists (of the first wall that uses it)
            let near = first_wall_on(&self.fixes, &id)
                .and_then(|(_, w, k)| w.trackers.get(k))
                .map_or(0, |t| t.candidate_count());
            let Some(m) = mesh_named_mut(&mut self.fixes, &id) else {
                continue;
            };
            let f_total = m.stress.as_ref().map_or([0.0; 3], |st| st.f_total);
            let Some(s) = m.servo.as_mut() else { continue };
            if !s.integrate {
                continue;
            }
            s.final_integrate(f_total, near, dt);
            let v = s.vcm;
            let n = m.mesh.len();
            m.node_v = Some(vec![[v; 3]; n]);
        }
        Ok(())
    }
}
