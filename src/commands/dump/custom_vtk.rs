//! `dump custom/vtk`: the group's particles with the chosen columns as VTK files (legacy
//! `.vtk`, XML `.vtp`/`.vtu`, parallel `.pvtp`/`.pvtu` masters with their one piece), each
//! with the box's bounding-box file beside it.

use crate::commands::dump::{Built, DumpDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::dump_style::{write_file, DumpAt, DumpStyle, WholeSnapshot};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;
use crate::io::dump::Column;
use crate::io::vtk::Flavor;

/// The declared signature of `custom/vtk`.
pub const SPEC: Spec = style(
    "dump",
    "custom/vtk",
    "dump ID GROUP custom/vtk N FILE.vtk|vtp|vtu|pvtp|pvtu COLUMN ...",
    &[],
    "chosen per-particle columns as VTK files (.pvtp/.pvtu: a parallel master file and its one piece FILE_0.vtp/.vtu)",
);

/// `dump custom/vtk` with the VTK fields of its columns.
#[derive(Debug)]
pub struct CustomVtk {
    /// The point-data fields the columns make.
    fields: Vec<crate::io::vtk::Field>,
}

impl DumpStyle for CustomVtk {
    fn name(&self) -> &str {
        "custom/vtk"
    }

    fn snapshot(
        &self,
        at: &mut DumpAt,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        let columns = at.references(vars)?;
        let (sim, dump) = (at.sim, at.dump);
        let p = &sim.particles;
        let mut atoms: Vec<usize> = (0..p.len())
            .filter(|&i| p.mask[i] & dump.group != 0)
            .collect();
        if dump.layout.sort_by_id {
            atoms.sort_by_key(|&i| p.id[i]);
        }
        // column index -> index among the reference columns
        let cols = &dump.layout.columns;
        let mut reference = vec![usize::MAX; cols.len()];
        let mut r = 0;
        for (c, col) in cols.iter().enumerate() {
            if let Column::Reference(_) = col {
                reference[c] = r;
                r += 1;
            }
        }
        let domain = &sim.domain;
        let value = |c: usize, i: usize| match &cols[c] {
            Column::Reference(_) => {
                let (values, col) = &columns[reference[c]];
                values.get(i, *col)
            }
            other => other.value(p, domain, i),
        };
        use crate::io::vtk::{write_particles, write_particles_binary, write_particles_xml};
        let (binary, fields) = (dump.layout.binary, &self.fields[..]);
        let mut text = Vec::new();
        match Flavor::of(&dump.file) {
            Some(f @ (Flavor::PolyData | Flavor::Unstructured)) => {
                write_particles_xml(&mut text, f, binary, &atoms, fields, |i| p.x[i], value)
            }
            _ if binary => write_particles_binary(&mut text, &atoms, fields, |i| p.x[i], value),
            _ => write_particles(&mut text, &atoms, fields, |i| p.x[i], value),
        }
        .map_err(|e| e.to_string())?;
        Ok(text)
    }

    fn whole_files(&self) -> bool {
        true
    }

    /// One snapshot per file (overwritten without `*`), and the box beside it.
    fn write_whole(&self, out: &WholeSnapshot) -> Result<(), EngineError> {
        let mut bbox = Vec::new();
        match Flavor::of(out.file) {
            Some(Flavor::Legacy) | None if out.binary => {
                crate::io::vtk::write_bounding_box_binary(&mut bbox, out.domain)
            }
            Some(Flavor::Legacy) | None => {
                crate::io::vtk::write_bounding_box(&mut bbox, out.domain)
            }
            Some(_) => crate::io::vtk::write_bounding_box_xml(&mut bbox, out.domain, out.binary),
        }
        .map_err(|e| e.to_string())?;
        let name = out.name;
        if crate::io::vtk::is_parallel(name) {
            // the master file names its one piece (the process-0 file LIGGGHTS writes)
            let piece = crate::io::vtk::piece_name(name);
            let source = piece.rsplit('/').next().unwrap_or(&piece);
            let flavor = Flavor::of(name).expect("a parallel VTK name");
            let master =
                crate::io::vtk::parallel_master(&String::from_utf8_lossy(out.text), source, flavor);
            write_file(&piece, out.text)?;
            write_file(name, master.as_bytes())?;
        } else {
            write_file(name, out.text)?;
        }
        let box_name = crate::io::vtk::bounding_box_name(out.file, out.step_text);
        write_file(&box_name, &bbox)
    }

    fn takes_binary(&self) -> Option<bool> {
        Some(true)
    }
}

/// `dump ID GROUP custom/vtk N FILE COLUMN ...`.
pub fn build(a: &Args, ctx: &mut Ctx, def: &DumpDef) -> Result<Built, CommandError> {
    check_vtk_file(a, def.file)?;
    let layout = super::custom::columns(a, ctx)?;
    let fields = crate::io::vtk::fields(&layout.names);
    Ok((layout, Box::new(CustomVtk { fields })))
}

/// The file of `dump custom/vtk`: a VTK file name LIGGGHTS accepts.
fn check_vtk_file(a: &Args, file: &str) -> Result<(), CommandError> {
    super::vtk_file_type(file, "custom/vtk", &super::PARTICLE_VTK_SUFFIXES)
        .map_err(|m| a.error(4, m))?;
    // the suffixes allowed are the ones regolith writes
    debug_assert!(Flavor::of(file).is_some());
    Ok(())
}
