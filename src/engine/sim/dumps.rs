//! Dump snapshots: which dumps are due at a step; each dump's style writes its snapshot (see
//! [`crate::engine::dump_style`]).

use super::*;
use crate::engine::dump_style::{DumpAt, SharedLocalRows};

impl Simulation {
    /// Write the dumps due at this step (`setup`: the setup of a run, where `dump_modify
    /// first yes` writes).
    pub(crate) fn write_dumps(
        &mut self,
        setup: bool,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.write_dumps_with(setup, vars, SharedLocalRows::new())
    }

    /// [`Self::write_dumps`] with the rows of local computes already evaluated at this
    /// step (on several ranks: every rank's rows gathered).
    pub(crate) fn write_dumps_with(
        &mut self,
        setup: bool,
        vars: &mut dyn VariableSource,
        mut local_rows: SharedLocalRows,
    ) -> Result<(), EngineError> {
        let step = self.step;
        for k in 0..self.dumps.len() {
            if !self.dump_due(k, setup) {
                continue;
            }
            self.dumps[k].last_written = Some(step);
            let dump = &self.dumps[k];
            let mut at = DumpAt {
                sim: self,
                dump,
                local_rows: &mut local_rows,
            };
            let text = dump.style.snapshot(&mut at, vars)?;
            self.write_dump_text(k, step, &text)?;
        }
        Ok(())
    }

    /// Whether dump `k` writes at this step: on its interval, or at the first setup with
    /// `dump_modify first yes`, and never twice at one step.
    pub(super) fn dump_due(&self, k: usize, setup: bool) -> bool {
        let d = &self.dumps[k];
        (self.step % d.every == 0 || (setup && d.first && d.last_written.is_none()))
            && d.last_written != Some(self.step)
    }
}
