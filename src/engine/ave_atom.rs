//! `fix ave/atom`: per-particle time averages of atom attributes, per-atom computes, fixes
//! and atom-style variables, sampled every `every` steps, `repeat` samples ending on every
//! multiple of `freq` (LIGGGHTS 3.8.0's schedule). The averages live in a per-particle
//! array that follows the particles.

use crate::engine::error::EngineError;
use crate::engine::fixes::FixKind;
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

    /// LIGGGHTS's `end_of_step` of the `fix ave/atom` at `fixes[k]` (also run at setup).
    pub(crate) fn ave_atom_step(
        &mut self,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = self.step;
        let (group, ave) = match &self.fixes[k].kind {
            FixKind::AveAtom(a) if a.nvalid == step => (self.fixes[k].group, a.clone()),
            _ => return Ok(()),
        };
        let n = ave.inputs.len();
        let columns = ave
            .inputs
            .iter()
            .map(|input| self.ave_atom_input(input, vars))
            .collect::<Result<Vec<_>, _>>()?;
        let p = &mut self.particles;
        let a = p.extra_index(&ave.array, n);
        let mask = &p.mask;
        let data = &mut p.extra[a].data;
        if ave.irepeat == 0 {
            data.fill(0.0);
        }
        for (m, column) in columns.iter().enumerate() {
            for (i, value) in column.iter().enumerate() {
                if mask[i] & group != 0 {
                    data[i * n + m] += value;
                }
            }
        }
        let FixKind::AveAtom(state) = &mut self.fixes[k].kind else {
            unreachable!("matched above")
        };
        state.irepeat += 1;
        if state.irepeat < state.repeat {
            state.nvalid += state.every;
        } else {
            state.irepeat = 0;
            state.nvalid = step + state.freq - (state.repeat - 1) * state.every;
            let repeat = state.repeat as f64;
            for v in data.iter_mut() {
                *v /= repeat;
            }
        }
        Ok(())
    }

    /// At a run's setup: reschedule averages left behind (LIGGGHTS's `init`), then sample
    /// those due now (its `setup`).
    pub(crate) fn setup_ave_atom(
        &mut self,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = self.step;
        for k in 0..self.fixes.len() {
            if let FixKind::AveAtom(a) = &mut self.fixes[k].kind {
                if a.nvalid < step {
                    a.irepeat = 0;
                    a.nvalid = a.next_valid(step);
                }
                self.ave_atom_step(k, vars)?;
            }
        }
        Ok(())
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
