//! `dump local/gran/vtk`: the contacts of a `pair/gran/local` or `wall/gran/local` compute
//! as VTK lines with LIGGGHTS's fixed cell arrays (legacy `.vtk`, XML `.vtp` or `.vtu`).

use crate::commands::dump::{no_columns, Built, DumpDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::dump_style::{DumpAt, DumpStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;

/// The declared signature of `local/gran/vtk`.
pub const SPEC: Spec = style(
    "dump",
    "local/gran/vtk",
    "dump ID GROUP local/gran/vtk N FILE.vtk|FILE.vtp|FILE.vtu COMPUTE",
    &[],
    "the contacts of a compute pair/gran/local or wall/gran/local as VTK lines (legacy .vtk, XML .vtp polydata or .vtu grid)",
);

/// `dump local/gran/vtk` of one local compute.
#[derive(Debug)]
pub struct LocalGranVtk {
    /// The compute ID.
    compute: String,
}

impl DumpStyle for LocalGranVtk {
    fn name(&self) -> &str {
        "local/gran/vtk"
    }

    fn snapshot(
        &self,
        at: &mut DumpAt,
        _vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        let rows = at.local_rows(&self.compute)?;
        crate::engine::local_vtk::snapshot(at.sim, &self.compute, &at.dump.file, &rows)
    }

    fn local_computes(&self) -> Vec<String> {
        vec![self.compute.clone()]
    }

    fn whole_files(&self) -> bool {
        true
    }
}

/// `dump ID GROUP local/gran/vtk N FILE COMPUTE`: the compute a `pair/gran/local` (with
/// positions), the file not a parallel name.
pub fn build(a: &Args, ctx: &mut Ctx, def: &DumpDef) -> Result<Built, CommandError> {
    if a.len() < 6 {
        return Err(a
            .error(4, "dump local/gran/vtk requires 6 arguments")
            .with_help("name a compute pair/gran/local after the file"));
    }
    super::vtk_file_type(def.file, "local/gran/vtk", &super::PARTICLE_VTK_SUFFIXES)
        .map_err(|m| a.error(4, m))?;
    let cid = a.word(5)?;
    let fields = ctx
        .sim
        .computes
        .iter()
        .find(|c| c.id == cid)
        .and_then(|c| c.style().local_fields())
        .ok_or_else(|| {
            a.error(
                5,
                "dump local/gran/vtk requires a valid ID of a compute pair/gran/local to be provided",
            )
        })?;
    if !fields.contains(&crate::engine::computes::LocalField::Pos) {
        return Err(a.error(
            5,
            "dump local/gran/vtk requires a valid ID of a compute pair/gran/local that writes the positions",
        ));
    }
    if crate::io::vtk::is_parallel(def.file) {
        // LIGGGHTS 3.8.0's parallel names set its old `%` flag, which the style then refuses
        return Err(a.error(4, "dump local/gran/vtk no longer allow parallel writing by setting the % character. Instead use a filename with suffix .pvtX (X = {u, p})."));
    }
    let compute = cid.to_string();
    Ok((no_columns(), Box::new(LocalGranVtk { compute })))
}
