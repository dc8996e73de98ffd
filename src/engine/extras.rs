//! Engine state of the commands added for researchers' own decks (issue 15), kept apart
//! from the core simulation so that each feature lives in a file of its own.

use crate::error::Location;
use std::collections::HashMap;

/// Where a deck defined something (file and line, the line's text and the word's span), for
/// errors LIGGGHTS only finds when a run starts.
#[derive(Debug, Clone)]
pub struct Origin {
    /// File and line.
    pub location: Location,
    /// The command as executed.
    pub text: String,
    /// Byte range of the word to point at.
    pub span: (usize, usize),
}

/// State of the issue-15 commands.
#[derive(Default)]
pub struct Extras {
    /// `fix property/global NAME ...`: the line that last defined each property name.
    pub property_origins: HashMap<String, Origin>,
    /// `thermo_log FILE`: thermo headers and lines also go to this file.
    pub thermo_file: Option<std::fs::File>,
    /// `modify_timing off|on|verbose` (0, 1, 2).
    pub modify_timing: u8,
    /// `neigh_modify binsize`: the neighbour bin size (length; 0 for LIGGGHTS's default,
    /// half the neighbour cutoff). The bins order each particle's partners, and with them
    /// the round-off of its contact sums, on the exact path.
    pub neigh_binsize: f64,
    /// `compute_modify` settings (and setup atom counts of temperature computes) by ID.
    pub compute_settings: HashMap<String, crate::engine::temperature::ComputeSettings>,
    /// Fixes with per-atom state in the last restart file read (LIGGGHTS then refuses
    /// `change_box` without `force`).
    pub restart_peratom_fixes: usize,
}

/// Copy thermo output to the `thermo_log` file, if one is open.
pub fn tee(file: &mut Option<std::fs::File>, text: &str) {
    use std::io::Write;
    if let Some(f) = file {
        // a failing thermo log must not stop the run (LIGGGHTS ignores fprintf's result)
        let _ = f.write_all(text.as_bytes());
    }
}

impl crate::engine::sim::Simulation {
    /// Write dump `k` now, whatever its interval (`write_dump`), leaving the others alone.
    pub fn write_single_dump(
        &mut self,
        k: usize,
        vars: &mut dyn crate::engine::sim::VariableSource,
    ) -> Result<(), crate::engine::error::EngineError> {
        let mut others = std::mem::take(&mut self.dumps);
        self.dumps.push(others.remove(k));
        let result = self.write_dumps(false, vars);
        let dump = self.dumps.pop().expect("pushed above");
        others.insert(k, dump);
        self.dumps = others;
        result
    }
}
