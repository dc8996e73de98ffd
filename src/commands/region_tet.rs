//! `region ID mesh/tet file F scale S move DX DY DZ rotate AX AY AZ units box`: a region of
//! the tetrahedra of a VTK file, with LIGGGHTS's notes about the file.

use crate::commands::args::Args;
use crate::commands::error::CommandError;
use crate::commands::Ctx;
use crate::engine::error::EngineError;
use crate::engine::region::RegionContext;

/// Define the region from the command's `words` (after the command name).
pub fn define(a: &Args, ctx: &mut Ctx, words: &[&str]) -> Result<(), CommandError> {
    let d = &ctx.sim.domain;
    let rctx = RegionContext {
        bounds: d.exists.then_some((d.lo, d.hi)),
        lattice: None,
    };
    let sys = &*ctx.sys;
    let read = |name: &str| {
        sys.read(name)
            .map_err(|e| EngineError::File(format!("Cannot open mesh file {name}: {e}")))
    };
    let notes = ctx
        .sim
        .regions
        .define_tet(words, rctx, &read)
        .map_err(|e| match e {
            EngineError::Unsupported(what) => a.unsupported(1, &what),
            EngineError::File(m) => a.file_error(3, m),
            other => a.error(1, other.to_string()),
        })?;
    for _ in 0..notes.empty_lines {
        ctx.say("Note: Skipping empty line in VTK mesh file\n");
    }
    if notes.other_cells {
        ctx.say("WARNING: VTK file contains other types than tetrahedra - only tets are currently supported in LIGGGHTS, other cells are discarded (./src/input_mesh_tet.cpp:319)\n");
    }
    Ok(())
}
