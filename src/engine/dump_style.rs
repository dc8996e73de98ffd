//! Dump styles as modules: [`DumpStyle`] is what a style writes at each snapshot, how its
//! snapshots reach files and which style-specific `dump_modify` keywords it takes, each hook
//! a default unless the style overrides it. The engine reaches the style a
//! [`Dump`](crate::engine::sim::Dump) holds through these methods, so writing dumps needs no
//! knowledge of any style.
//!
//! A style is one file under `commands/dump/` (its arguments, its state, this trait) and one
//! row in that folder's table.

use crate::engine::computes::PerAtom;
use crate::engine::domain::Domain;
use crate::engine::error::EngineError;
use crate::engine::sim::{Dump, Simulation, VariableSource};
use std::collections::HashMap;
use std::rc::Rc;

/// Local compute rows evaluated once per step however many columns and dumps read them:
/// (columns, values row by row), by compute ID.
pub type SharedLocalRows = HashMap<String, Rc<(usize, Vec<f64>)>>;

/// What a snapshot hook is told: the simulation, the dump and the step's shared values.
pub struct DumpAt<'a> {
    /// The simulation (particles, box, computes, fixes, meshes).
    pub sim: &'a Simulation,
    /// The dump being written (its group, file, layout).
    pub dump: &'a Dump,
    /// Local compute rows already evaluated at this step.
    pub local_rows: &'a mut SharedLocalRows,
}

impl DumpAt<'_> {
    /// The per-atom values of the layout's reference columns (`c_`, `f_`, `v_`) in column
    /// order: the values and the column among them, evaluated once per snapshot.
    pub fn references(
        &self,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<(PerAtom, usize)>, EngineError> {
        let mut columns = Vec::new();
        for col in &self.dump.layout.columns {
            if let crate::io::dump::Column::Reference(name) = col {
                columns.push(self.sim.dump_reference(name, vars)?);
            }
        }
        Ok(columns)
    }

    /// The local rows of compute `cid` now, (columns, values row by row), evaluated at most
    /// once per step.
    pub fn local_rows(&mut self, cid: &str) -> Result<Rc<(usize, Vec<f64>)>, EngineError> {
        if let Some(r) = self.local_rows.get(cid) {
            return Ok(r.clone());
        }
        let c = self
            .sim
            .computes
            .iter()
            .find(|c| c.id == cid)
            .ok_or_else(|| format!("Could not find dump local compute ID {cid}"))?;
        let r = Rc::new(c.local(self.sim)?);
        self.local_rows.insert(cid.to_string(), r.clone());
        Ok(r)
    }
}

/// One snapshot to be written as whole files.
pub struct WholeSnapshot<'a> {
    /// The box (for files written beside the snapshot).
    pub domain: &'a Domain,
    /// The dump's file name as given (a `*` stands for the step).
    pub file: &'a str,
    /// The file name of this snapshot (the step in place of `*`).
    pub name: &'a str,
    /// The step as it is written into file names (`dump_modify pad`).
    pub step_text: &'a str,
    /// `dump_modify binary yes`.
    pub binary: bool,
    /// The snapshot's bytes (gzip-packed for `.gz` names).
    pub text: &'a [u8],
}

/// A dump style: the snapshot it writes and how. Every hook but [`Self::name`] and
/// [`Self::snapshot`] has a default.
pub trait DumpStyle: Send + std::fmt::Debug {
    /// The style's name as decks write it (`custom`).
    fn name(&self) -> &str;

    /// The bytes of one snapshot at the current step.
    fn snapshot(
        &self,
        at: &mut DumpAt,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError>;

    /// IDs of the local computes whose rows the snapshots write (none by default).
    fn local_computes(&self) -> Vec<String> {
        Vec::new()
    }

    /// Whether each snapshot is a whole file (overwritten unless the name has a `*`); else
    /// snapshots are appended to one file for the run (one file per snapshot for `*` names).
    fn whole_files(&self) -> bool {
        false
    }

    /// Write one snapshot as whole files (for [`Self::whole_files`] styles and `*` names):
    /// by default the snapshot's file alone.
    fn write_whole(&self, out: &WholeSnapshot) -> Result<(), EngineError> {
        write_file(out.name, out.text)
    }

    /// The per-type element names `dump_modify element` sets (None: the style ignores them).
    fn elements(&mut self) -> Option<&mut Vec<String>> {
        None
    }

    /// Whether the style takes `dump_modify binary` (Some(true)), refuses it as LIGGGHTS
    /// does (Some(false)), or regolith does not run it with it yet (None).
    fn takes_binary(&self) -> Option<bool> {
        None
    }
}

/// Write `bytes` to `name` whole, with the dump's error if it cannot.
pub fn write_file(name: &str, bytes: &[u8]) -> Result<(), EngineError> {
    crate::io::write_atomically(name, bytes)
        .map_err(|e| format!("Cannot open dump file {name}: {e}").into())
}
