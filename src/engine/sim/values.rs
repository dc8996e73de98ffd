//! End-of-step work and the values others read: averaging fixes, the global values of
//! fixes and computes, group bits and the simulated time.

use super::*;

impl Simulation {
    /// The largest squared node speed (length^2/time^2) of the moving meshes (a fix
    /// move/mesh or a servo on them) of the last mesh wall, as LIGGGHTS's fix
    /// check/timestep/gran takes it; 0 without one.
    pub(crate) fn moving_mesh_vmax_sqr(&self) -> f64 {
        let Some(wall) = self.fixes.iter().rev().find_map(|f| f.kind.mesh_wall()) else {
            return 0.0;
        };
        let mut vmax_sqr: f64 = 0.0;
        for id in &wall.meshes {
            let Some(mesh) = self
                .fixes
                .iter()
                .find(|f| &f.id == id)
                .and_then(|f| f.kind.mesh())
            else {
                continue;
            };
            let moved = self
                .fixes
                .iter()
                .any(|f| f.kind.mover().is_some_and(|m| &m.mesh == id));
            if !(moved || mesh.servo.is_some()) {
                continue;
            }
            for v in mesh.node_v.iter().flatten().flatten() {
                let sq = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
                if sq > vmax_sqr {
                    vmax_sqr = sq;
                }
            }
        }
        vmax_sqr
    }

    /// The `end_of_step` phase: fixes that check or report every N steps.
    pub(super) fn end_of_step(
        &mut self,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.move_streams();
        let (step, dt, skin) = (self.step, self.dt, self.neighbor.skin);
        let contact = self.neighbor.cutneighmax - skin;
        let tallied = self.virial_step == Some(step);
        let mesh_vmax_sqr = self.moving_mesh_vmax_sqr();
        for k in 0..self.fixes.len() {
            let fix = &mut self.fixes[k];
            let clock = fix.clock.start();
            if let FixKind::Style(s) = &mut fix.kind {
                s.end_of_step(
                    &mut self.particles,
                    &fixes::FixStep {
                        group: fix.group,
                        step,
                        dt,
                        domain: &self.domain,
                        virial: if tallied { &self.virial } else { &[] },
                        contact,
                        skin,
                        regions: Some(&self.regions),
                        mesh_vmax_sqr,
                    },
                );
                if s.outputs_at(step) {
                    self.fix_style_output(k, out, vars)?;
                }
                self.fix_style_end_of_step_sim(k, vars)?;
            }
            self.fixes[k].clock.stop(clock);
        }
        Ok(())
    }

    /// One input value of `fix ave/time`.
    pub(crate) fn ave_input(
        &self,
        input: &fixes::AveInput,
        vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        match input {
            fixes::AveInput::Compute(id, i) => self.compute_value(id, *i, vars),
            fixes::AveInput::Fix(id, i) => self.fix_value(id, *i),
            fixes::AveInput::Variable(name) => Ok(vars.equal(self, name)?),
        }
    }

    /// The `setup_values` hook of every module fix style, in fix order, after the setup
    /// force evaluation.
    pub(super) fn setup_fix_values(&mut self) {
        let step = self.step;
        let tallied = self.virial_step == Some(step);
        let contact = self.neighbor.cutneighmax - self.neighbor.skin;
        let mesh_vmax_sqr = self.moving_mesh_vmax_sqr();
        for fix in &mut self.fixes {
            if let FixKind::Style(s) = &mut fix.kind {
                s.setup_values(
                    &self.particles,
                    &fixes::FixStep {
                        group: fix.group,
                        step,
                        dt: self.dt,
                        domain: &self.domain,
                        virial: if tallied { &self.virial } else { &[] },
                        contact,
                        skin: self.neighbor.skin,
                        regions: Some(&self.regions),
                        mesh_vmax_sqr,
                    },
                );
            }
        }
    }

    /// Value of `f_ID[i][j]` (1-based) for fixes with a global array.
    pub fn fix_array_value(&self, id: &str, i: usize, j: usize) -> Result<f64, EngineError> {
        let fix = self
            .fixes
            .iter()
            .find(|f| f.id == id)
            .ok_or_else(|| format!("Could not find fix ID {id}"))?;
        match &fix.kind {
            FixKind::Style(s) if !s.array_unsupported() => {
                match s.array_value(i, j, self.run_bounds.is_some()) {
                    Some(v) => v,
                    None => Err("Mismatched fix in variable formula".into()),
                }
            }
            _ => Err(EngineError::Unsupported(format!(
                "f_{id}[i][j] of fix {}",
                fix.style
            ))),
        }
    }

    /// Value of `f_ID[i]` (1-based) for fixes with a global vector.
    pub fn fix_value(&self, id: &str, index: Option<usize>) -> Result<f64, EngineError> {
        let fix = self
            .fixes
            .iter()
            .find(|f| f.id == id)
            .ok_or_else(|| format!("Could not find fix ID {id}"))?;
        if let Some(v) = self.heat_value(id, index) {
            return v;
        }
        match (&fix.kind, index) {
            (kind, Some(i)) if kind.mesh().and_then(|m| m.value(i)).is_some() => {
                Ok(kind.mesh().and_then(|m| m.value(i)).unwrap_or(0.0))
            }
            (FixKind::Style(s), _) if s.global_freq() == 0 && self.run_bounds.is_some() => {
                Err(crate::engine::global_values::zero_freq(id))
            }
            // read once: a value may be consumed by its reading (fix property/atom/tracer)
            (FixKind::Style(s), i) => s
                .value(i)
                .ok_or_else(|| format!("fix {id} ({}) has no such value", fix.style).into()),
            _ => Err(format!("fix {id} ({}) has no such value", fix.style).into()),
        }
    }

    /// Value of `c_ID` (index None) or `c_ID[i]`.
    pub fn compute_value(
        &self,
        id: &str,
        index: Option<usize>,
        vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        let c = self
            .computes
            .iter()
            .find(|c| c.id == id)
            .ok_or_else(|| format!("Could not find thermo/variable compute ID {id}"))?;
        match index {
            None => c.scalar(self, vars),
            Some(i) => c.vector(i, self, vars),
        }
    }

    /// The per-atom values behind a dump column `c_ID` / `c_ID[N]` / `v_name`, and its
    /// column.
    pub(crate) fn dump_reference(
        &self,
        name: &str,
        vars: &mut dyn VariableSource,
    ) -> Result<(crate::engine::computes::PerAtom, usize), EngineError> {
        if let Some(var) = name.strip_prefix("v_") {
            let values = vars.atom(self, var)?;
            return Ok((crate::engine::computes::PerAtom { columns: 1, values }, 0));
        }
        if let Some(body) = name.strip_prefix("f_") {
            let (id, index) = crate::util::numbers::split_reference(body)
                .ok_or_else(|| format!("Invalid attribute {name} in dump custom command"))?;
            return crate::engine::fix_columns::per_atom(self, id, index);
        }
        let body = name
            .strip_prefix("c_")
            .ok_or_else(|| format!("Invalid attribute {name} in dump custom command"))?;
        let (id, index) = crate::util::numbers::split_reference(body)
            .ok_or_else(|| format!("Invalid attribute {name} in dump custom command"))?;
        let c = self
            .computes
            .iter()
            .find(|c| c.id == id)
            .ok_or_else(|| format!("Could not find dump custom compute ID {id}"))?;
        let col = crate::engine::computes::column_of(c, index)?;
        Ok((c.per_atom(self, vars)?, col))
    }

    /// Bit mask of group `name`.
    pub fn group_bit(&self, name: &str) -> Option<u32> {
        self.groups
            .iter()
            .position(|g| g == name)
            .map(|i| 1u32 << i)
    }

    /// Simulated time at the current step (time units).
    pub fn time(&self) -> f64 {
        self.atime + (self.step - self.atime_step) as f64 * self.dt
    }
}
