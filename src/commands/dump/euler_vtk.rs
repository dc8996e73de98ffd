//! `dump euler/vtk`: the cells of the first `fix ave/euler` as legacy VTK points (average
//! velocity, volume fraction, radius, pressure), one file per snapshot.

use crate::commands::dump::{no_columns, Built, DumpDef};
use crate::commands::fix::ave_euler::AveEuler;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::dump_style::{DumpAt, DumpStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;

/// The declared signature of `euler/vtk`.
pub const SPEC: Spec = style(
    "dump",
    "euler/vtk",
    "dump ID GROUP euler/vtk N FILE*.vtk",
    &[],
    "the cells of the first fix ave/euler as legacy VTK points (average velocity, volume fraction, radius, pressure)",
);

/// `dump euler/vtk`.
#[derive(Debug)]
pub struct EulerVtk;

impl DumpStyle for EulerVtk {
    fn name(&self) -> &str {
        "euler/vtk"
    }

    fn snapshot(
        &self,
        at: &mut DumpAt,
        _vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        let text: String = (at.sim.fixes.iter())
            .filter(|f| f.style == "ave/euler")
            .find_map(|f| f.kind.style_as::<AveEuler>())
            .map(|a| a.grid.vtk())
            .ok_or("Illegal dump euler/vtk command, need a fix ave/euler")?;
        Ok(text.into_bytes())
    }

    fn whole_files(&self) -> bool {
        true
    }
}

/// `dump ID GROUP euler/vtk N FILE*.vtk`.
pub fn build(a: &Args, _ctx: &mut Ctx, def: &DumpDef) -> Result<Built, CommandError> {
    if !def.file.contains('*') {
        return Err(a.error(4, "You should use a filename like 'dump*.vtk' for the 'dump euler/vtk' command to produce one file per time-step"));
    }
    Ok((no_columns(), Box::new(EulerVtk)))
}
