//! `dump mesh/vtk` (and LIGGGHTS's `mesh/gran/VTK`): meshes with their per-triangle data
//! (areas, stresses, wear, node velocities, active edges and corners) as legacy VTK.

use crate::commands::dump::{style_words, Built, DumpDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::dump_style::{DumpAt, DumpStyle};
use crate::engine::error::EngineError;
use crate::engine::fixes::{mesh_named, meshes, MeshFix};
use crate::engine::sim::VariableSource;
use crate::io::mesh_vtk::{MeshDumpSpec, MeshSnapshot};

/// The declared signature of `mesh/vtk`.
pub const SPEC: Spec = style(
    "dump",
    "mesh/vtk",
    "dump ID GROUP mesh/vtk N FILE [MESH ...]",
    &[],
    "meshes as VTK",
);

/// The declared signature of `mesh/gran/VTK`.
pub const GRAN: Spec = style(
    "dump",
    "mesh/gran/VTK",
    "dump ID GROUP mesh/gran/VTK N FILE [MESH ...]",
    &[],
    "meshes as legacy VTK",
);

/// `dump mesh/vtk`: the meshes and data its keywords name.
#[derive(Debug)]
pub struct MeshVtk {
    /// The style name as written (`mesh/vtk` or `mesh/gran/VTK`).
    name: String,
    /// The meshes (all when none) and the data written.
    spec: MeshDumpSpec,
}

impl DumpStyle for MeshVtk {
    fn name(&self) -> &str {
        &self.name
    }

    fn snapshot(
        &self,
        at: &mut DumpAt,
        _vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        let fixes = &at.sim.fixes;
        let meshes: Vec<&MeshFix> = if self.spec.meshes.is_empty() {
            meshes(fixes).map(|(_, m)| m).collect()
        } else {
            (self.spec.meshes.iter())
                .filter_map(|id| mesh_named(fixes, id))
                .collect()
        };
        let counts: Vec<(Vec<i32>, Vec<i32>, Vec<i32>)> = meshes
            .iter()
            .map(|m| {
                let mm = &m.mesh;
                let count = |v: &[bool; 3]| v.iter().filter(|&&b| b).count() as i32;
                (
                    mm.edge_active.iter().map(count).collect(),
                    mm.corner_active.iter().map(count).collect(),
                    mm.neighbors.iter().map(|n| n.len() as i32).collect(),
                )
            })
            .collect();
        let snaps: Vec<MeshSnapshot> = meshes
            .iter()
            .zip(&counts)
            .map(|(m, c)| {
                let st = m.stress.as_ref();
                MeshSnapshot {
                    nodes: &m.mesh.nodes,
                    area: Some(&m.mesh.area),
                    sigma_n: st.filter(|s| s.stress).map(|s| &s.sigma_n[..]),
                    sigma_t: st.filter(|s| s.stress).map(|s| &s.sigma_t[..]),
                    force: st.filter(|s| s.stress).map(|s| &s.f[..]),
                    wear: st.filter(|s| s.wear_on).map(|s| &s.wear[..]),
                    node_vel: m.node_v.as_deref(),
                    active_edges: Some(&c.0),
                    active_corners: Some(&c.1),
                    nneighs: Some(&c.2),
                    ..Default::default()
                }
            })
            .collect();
        let mut text = Vec::new();
        crate::io::mesh_vtk::write_mesh_vtk(&mut text, &self.spec, &snaps)
            .map_err(|e| e.to_string())?;
        Ok(text)
    }

    fn whole_files(&self) -> bool {
        true
    }
}

/// `dump ID GROUP mesh/vtk N FILE.vtk [MESH ...] [KEYWORD ...]`.
pub fn build(a: &Args, ctx: &mut Ctx, def: &DumpDef) -> Result<Built, CommandError> {
    let style = def.style;
    let words = style_words(a)?;
    let fixes = &ctx.sim.fixes;
    let spec =
        crate::io::mesh_vtk::parse_keywords(&words, |w| mesh_named(fixes, w).is_some(), |_| false)
            .map_err(|m| a.error(5, format!("dump {style}: {m}")))?;
    // LIGGGHTS checks the file name after the keywords
    super::vtk_file_type(def.file, style, &[".vtk", ".vtp", ".pvtp"]).map_err(|m| a.error(4, m))?;
    if !def.file.ends_with(".vtk") {
        return Err(a.unsupported(
            4,
            &format!("dump {style} to XML or parallel VTK files (regolith writes legacy .vtk)"),
        ));
    }
    let name = style.to_string();
    Ok((super::no_columns(), Box::new(MeshVtk { name, spec })))
}
