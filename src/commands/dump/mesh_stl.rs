//! `dump mesh/stl` (and its other name `stl`): the triangles of mesh fixes as ASCII STL.

use crate::commands::dump::{style_words, Built, DumpDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::dump_style::{DumpAt, DumpStyle};
use crate::engine::error::EngineError;
use crate::engine::fixes::{mesh_named, meshes};
use crate::engine::sim::VariableSource;

/// The declared signature of `mesh/stl`.
pub const SPEC: Spec = style(
    "dump",
    "mesh/stl",
    "dump ID GROUP mesh/stl N FILE [MESH ...]",
    &[],
    "meshes as STL",
);

/// The declared signature of `stl`.
pub const STL: Spec = style(
    "dump",
    "stl",
    "dump ID GROUP stl N FILE [MESH ...]",
    &[],
    "the same as mesh/stl",
);

/// `dump mesh/stl`: the triangles of these mesh fixes (all when empty).
#[derive(Debug)]
pub struct MeshStl {
    /// The style name as written (`mesh/stl` or `stl`).
    name: String,
    /// The mesh fix IDs.
    ids: Vec<String>,
}

impl DumpStyle for MeshStl {
    fn name(&self) -> &str {
        &self.name
    }

    fn snapshot(
        &self,
        at: &mut DumpAt,
        _vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        let (mut triangles, mut normals) = (Vec::new(), Vec::new());
        for (f, m) in meshes(&at.sim.fixes) {
            if self.ids.is_empty() || self.ids.contains(&f.id) {
                triangles.extend_from_slice(m.triangles());
                normals.extend_from_slice(&m.mesh.normal);
            }
        }
        Ok(crate::io::stl::write_ascii(&triangles, &normals).into_bytes())
    }

    fn whole_files(&self) -> bool {
        true
    }
}

/// `dump ID GROUP mesh/stl N FILE [MESH ...]`: each MESH a `fix mesh/surface`.
pub fn build(a: &Args, ctx: &mut Ctx, def: &DumpDef) -> Result<Built, CommandError> {
    let ids: Vec<String> = style_words(a)?.into_iter().map(str::to_string).collect();
    for (k, id) in ids.iter().enumerate() {
        if mesh_named(&ctx.sim.fixes, id).is_none() {
            return Err(a.error(
                5 + k,
                "Could not find fix mesh/surface ID for dump mesh/stl",
            ));
        }
    }
    let name = def.style.to_string();
    Ok((super::no_columns(), Box::new(MeshStl { name, ids })))
}
