//! `fix ave/atom`: per-particle time averages of atom attributes, per-atom computes, fixes
//! and atom-style variables, sampled every `every` steps, `repeat` samples ending on every
//! multiple of `freq` (LIGGGHTS 3.8.0's schedule). The averages live in a per-particle
//! array that follows the particles.

use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStyle, PerAtomShape, SetupPass};
use crate::engine::particles::Particles;
use crate::engine::sim::{Simulation, VariableSource};
use crate::io::dump::Column;

/// One averaged input.
#[derive(Debug, Clone, PartialEq)]
pub enum AtomInput {
    /// `x y z vx vy vz fx fy fz`.
    Atom(Column),
    /// A per-atom compute `c_ID` or column `c_ID[N]` (1-based).
    Compute(String, Option<usize>),
    /// A per-atom fix `f_ID` or column `f_ID[N]`.
    Fix(String, Option<usize>),
    /// An atom-style variable `v_name`.
    Variable(String),
}

/// `fix ID GROUP ave/atom NEVERY NREPEAT NFREQ input ...`.
#[derive(Debug, Clone, PartialEq)]
pub struct AveAtom {
    /// Steps between samples.
    pub every: i64,
    /// Samples per average.
    pub repeat: i64,
    /// Steps between averages.
    pub freq: i64,
    /// The inputs, one column each.
    pub inputs: Vec<AtomInput>,
    /// The next step that samples.
    pub nvalid: i64,
    /// Samples taken towards the current average.
    pub irepeat: i64,
    /// Name of the per-particle array holding the sums and averages.
    pub array: String,
}

impl AveAtom {
    /// The first sampling step at or after `step` (LIGGGHTS's `nextvalid`).
    pub fn next_valid(&self, step: i64) -> i64 {
        let mut nvalid = (step / self.freq) * self.freq + self.freq;
        if nvalid - self.freq == step && self.repeat == 1 {
            nvalid = step;
        } else {
            nvalid -= (self.repeat - 1) * self.every;
        }
        if nvalid < step {
            nvalid += self.freq;
        }
        nvalid
    }
}

impl Simulation {
    /// The per-atom values of one input (one per local particle).
    pub(crate) fn ave_atom_input(
        &self,
        input: &AtomInput,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<f64>, EngineError> {
        let p = &self.particles;
        Ok(match input {
            AtomInput::Atom(col) => (0..p.len())
                .map(|i| col.value(p, &self.domain, i))
                .collect(),
            AtomInput::Compute(id, index) => {
                let c =
                    self.computes.iter().find(|c| &c.id == id).ok_or_else(|| {
                        format!("Compute ID for fix ave/atom does not exist: {id}")
                    })?;
                let data = c.per_atom(self, vars)?;
                let col = crate::engine::computes::column_of(c, *index)?;
                (0..p.len()).map(|i| data.get(i, col)).collect()
            }
            AtomInput::Fix(id, index) => {
                let (data, col) = crate::engine::fix_columns::per_atom(self, id, *index)?;
                (0..p.len()).map(|i| data.get(i, col)).collect()
            }
            AtomInput::Variable(name) => vars.atom(self, name)?,
        })
    }
}

impl AveAtom {
    /// LIGGGHTS's `end_of_step`: one sample of the inputs of the particles in `group` added
    /// to the per-particle sums, which become averages when the sample completes them.
    fn sample(
        &mut self,
        sim: &mut Simulation,
        group: u32,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = sim.step;
        let n = self.inputs.len();
        let columns = self
            .inputs
            .iter()
            .map(|input| sim.ave_atom_input(input, vars))
            .collect::<Result<Vec<_>, _>>()?;
        let p = &mut sim.particles;
        let a = p.extra_index(&self.array, n);
        let mask = &p.mask;
        let data = &mut p.extra[a].data;
        if self.irepeat == 0 {
            data.fill(0.0);
        }
        for (m, column) in columns.iter().enumerate() {
            for (i, value) in column.iter().enumerate() {
                if mask[i] & group != 0 {
                    data[i * n + m] += value;
                }
            }
        }
        self.irepeat += 1;
        if self.irepeat < self.repeat {
            self.nvalid += self.every;
        } else {
            self.irepeat = 0;
            self.nvalid = step + self.freq - (self.repeat - 1) * self.every;
            let repeat = self.repeat as f64;
            for v in data.iter_mut() {
                *v /= repeat;
            }
        }
        Ok(())
    }
}

/// The per-atom shape of a fix whose values are `n` columns of a per-particle array: a
/// vector for one column.
pub(crate) fn columns_shape(n: usize) -> PerAtomShape {
    if n == 1 {
        PerAtomShape::Vector
    } else {
        PerAtomShape::Array(n)
    }
}

/// The `n` columns of per-particle array `name`, row by row in particle order (zeros when
/// the array is missing).
pub(crate) fn array_values(p: &Particles, name: &str, n: usize) -> Vec<f64> {
    p.extra
        .iter()
        .find(|e| e.name == name && e.width == n)
        .map_or_else(|| vec![0.0; n * p.len()], |e| e.data.clone())
}

impl FixStyle for AveAtom {
    fn name(&self) -> &str {
        "ave/atom"
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
        self.nvalid == step
    }

    fn end_of_step_sim(
        &mut self,
        sim: &mut Simulation,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let group = sim.fixes[k].group;
        self.sample(sim, group, vars)
    }

    fn setup_pass(&self) -> Option<SetupPass> {
        Some(SetupPass::AtomAverages)
    }

    /// Averages left behind rescheduled (LIGGGHTS's `init`), then a sample if one is due
    /// now (its `setup`).
    fn setup_sim(
        &mut self,
        sim: &mut Simulation,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = sim.step;
        if self.nvalid < step {
            self.irepeat = 0;
            self.nvalid = self.next_valid(step);
        }
        if self.nvalid != step {
            return Ok(());
        }
        let group = sim.fixes[k].group;
        self.sample(sim, group, vars)
    }

    /// The averages as they stand (others may read them while the fix samples).
    fn stand_in(&self) -> Option<Box<dyn FixStyle>> {
        Some(Box::new(self.clone()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_schedule_ends_on_multiples_of_freq() {
        let mut a = AveAtom {
            every: 2,
            repeat: 3,
            freq: 10,
            inputs: Vec::new(),
            nvalid: 0,
            irepeat: 0,
            array: "a".into(),
        };
        assert_eq!(a.next_valid(0), 6);
        assert_eq!(a.next_valid(7), 16);
        a.repeat = 1;
        assert_eq!(a.next_valid(0), 0);
        assert_eq!(a.next_valid(3), 10);
    }
}
