//! `fix store/state`: a per-particle snapshot of atom attributes, per-atom computes, fixes
//! and atom-style variables, taken when the fix is defined (attributes) and at the first
//! run's setup (computes, fixes, variables), then every N steps if N > 0 (LIGGGHTS 3.8.0's
//! fix_store_state.cpp). The values live in a per-particle array that follows the particles.

use crate::engine::ave_atom::AtomInput;
use crate::engine::ave_atom::{array_values, columns_shape};
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStyle, PerAtomShape, SetupPass};
use crate::engine::particles::Particles;
use crate::engine::sim::{Simulation, VariableSource};
use crate::io::dump::Column;

/// `fix ID GROUP store/state N input ... [com yes|no]`.
#[derive(Debug, Clone, PartialEq)]
pub struct StoreState {
    /// Steps between snapshots (0: only the first).
    pub every: i64,
    /// The stored inputs, one column each.
    pub inputs: Vec<AtomInput>,
    /// `com yes`: unwrapped positions relative to the group's centre of mass.
    pub com: bool,
    /// The computes, fixes and variables are still to be stored (at the first setup).
    pub first: bool,
    /// Name of the per-particle array holding the values.
    pub array: String,
}

/// Which inputs a snapshot stores.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Snapshot {
    /// Atom attributes only (when the fix is defined).
    Attributes,
    /// Computes, fixes and variables only (the first run's setup).
    References,
    /// Everything (every N steps).
    All,
}

impl Simulation {
    /// One input's per-particle values for the particles in `group` (`None` for those
    /// outside it: attributes then store 0, computes and fixes keep the old value).
    fn store_input(
        &self,
        input: &AtomInput,
        group: u32,
        com: Option<[f64; 3]>,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<Option<f64>>, EngineError> {
        let p = &self.particles;
        let inside = |i: usize| p.mask[i] & group != 0;
        Ok(match input {
            AtomInput::Atom(col) => (0..p.len())
                .map(|i| {
                    Some(if !inside(i) {
                        0.0
                    } else {
                        let v = col.value(p, &self.domain, i);
                        match (col, com) {
                            (Column::Unwrapped(d), Some(cm)) => v - cm[*d],
                            _ => v,
                        }
                    })
                })
                .collect(),
            AtomInput::Compute(id, index) => {
                let c = self.computes.iter().find(|c| &c.id == id).ok_or_else(|| {
                    format!("Compute ID for fix store/state does not exist: {id}")
                })?;
                let data = c.per_atom(self, vars)?;
                let col = crate::engine::computes::column_of(c, *index)?;
                (0..p.len())
                    .map(|i| inside(i).then(|| data.get(i, col)))
                    .collect()
            }
            AtomInput::Fix(id, index) => {
                let (data, col) = crate::engine::fix_columns::per_atom(self, id, *index)?;
                (0..p.len())
                    .map(|i| inside(i).then(|| data.get(i, col)))
                    .collect()
            }
            // an atom-style variable is 0 outside the group
            AtomInput::Variable(name) => {
                let values = vars.atom(self, name)?;
                (0..p.len())
                    .map(|i| Some(if inside(i) { values[i] } else { 0.0 }))
                    .collect()
            }
        })
    }

    /// Store the inputs `which` selects of `s` for the particles of `group`.
    pub(crate) fn store_snapshot(
        &mut self,
        s: &StoreState,
        group: u32,
        which: Snapshot,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let com = s
            .com
            .then(|| crate::engine::computes::center_of_mass(&self.particles, &self.domain, group));
        let n = s.inputs.len();
        let mut columns = Vec::with_capacity(n);
        for input in &s.inputs {
            let attribute = matches!(input, AtomInput::Atom(_));
            let wanted = match which {
                Snapshot::Attributes => attribute,
                Snapshot::References => !attribute,
                Snapshot::All => true,
            };
            columns.push(if wanted {
                Some(self.store_input(input, group, com, vars)?)
            } else {
                None
            });
        }
        let p = &mut self.particles;
        let a = p.extra_index(&s.array, n);
        let data = &mut p.extra[a].data;
        for (m, column) in columns.iter().enumerate() {
            for (i, value) in column.iter().flatten().enumerate() {
                if let Some(v) = value {
                    data[i * n + m] = *v;
                }
            }
        }
        Ok(())
    }
}

impl FixStyle for StoreState {
    fn name(&self) -> &str {
        "store/state"
    }

    fn reads_computes(&self) -> bool {
        true
    }

    fn array_unsupported(&self) -> bool {
        true
    }

    fn per_atom_shape(&self) -> PerAtomShape {
        columns_shape(self.inputs.len())
    }

    fn per_atom(&self, p: &Particles) -> Vec<f64> {
        array_values(p, &self.array, self.inputs.len())
    }

    fn end_of_step_sim_due(&self, step: i64) -> bool {
        self.every > 0 && step % self.every == 0
    }

    fn end_of_step_sim(
        &mut self,
        sim: &mut Simulation,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let group = sim.fixes[k].group;
        sim.store_snapshot(self, group, Snapshot::All, vars)
    }

    fn setup_pass(&self) -> Option<SetupPass> {
        Some(SetupPass::Snapshots)
    }

    /// The first run stores the computes, fixes and variables.
    fn setup_sim(
        &mut self,
        sim: &mut Simulation,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        if !self.first {
            return Ok(());
        }
        let group = sim.fixes[k].group;
        sim.store_snapshot(self, group, Snapshot::References, vars)?;
        self.first = false;
        Ok(())
    }

    /// The values as they stand (others may read them while the fix stores).
    fn stand_in(&self) -> Option<Box<dyn FixStyle>> {
        Some(Box::new(self.clone()))
    }
}
