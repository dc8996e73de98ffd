//! Dump snapshots: which dumps are due at a step, and the text of each style's snapshot.

use super::*;
use crate::engine::computes::PerAtom;
use crate::engine::fixes::MeshFix;
use crate::io::dump::Column;
use std::collections::HashMap;
use std::rc::Rc;

/// A local compute's rows, evaluated once per step however many columns and dumps read
/// them: (columns, values row by row), by compute ID.
type LocalRows = HashMap<String, Rc<(usize, Vec<f64>)>>;

/// The per-atom values of a dump's reference columns (`c_`, `f_`, `v_`): the values and the
/// column among them.
type References = [(PerAtom, usize)];

impl Simulation {
    /// Write the dumps due at this step (`setup`: the setup of a run, where `dump_modify
    /// first yes` writes).
    pub(crate) fn write_dumps(
        &mut self,
        setup: bool,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = self.step;
        let mut local_rows = LocalRows::new();
        for k in 0..self.dumps.len() {
            if !self.dump_due(k, setup) {
                continue;
            }
            self.dumps[k].last_written = Some(step);
            let text = if let Some(cols) = self.dumps[k].local.clone() {
                self.local_dump_text(k, &cols, &mut local_rows)?
            } else if let DumpStyle::EulerVtk = &self.dumps[k].style {
                self.euler_vtk()?.into_bytes()
            } else if let DumpStyle::LocalGranVtk(cid) = &self.dumps[k].style {
                crate::engine::local_vtk::snapshot(self, cid, &self.dumps[k].file)?
            } else {
                self.atom_dump_text(k, vars)?
            };
            self.write_dump_text(k, step, &text)?;
        }
        Ok(())
    }

    /// Whether dump `k` writes at this step: on its interval, or at the first setup with
    /// `dump_modify first yes`, and never twice at one step.
    fn dump_due(&self, k: usize, setup: bool) -> bool {
        let d = &self.dumps[k];
        (self.step % d.every == 0 || (setup && d.first && d.last_written.is_none()))
            && d.last_written != Some(self.step)
    }

    /// The snapshot of `dump local` `k` with the (compute ID, column) columns `cols`.
    fn local_dump_text(
        &self,
        k: usize,
        cols: &[(String, usize)],
        local_rows: &mut LocalRows,
    ) -> Result<Vec<u8>, EngineError> {
        let mut data = Vec::new();
        for (cid, col) in cols {
            let c = self
                .computes
                .iter()
                .find(|c| &c.id == cid)
                .ok_or_else(|| format!("Could not find dump local compute ID {cid}"))?;
            let evaluated = match local_rows.get(cid) {
                Some(r) => r.clone(),
                None => {
                    let r = Rc::new(c.local(self)?);
                    local_rows.insert(cid.clone(), r.clone());
                    r
                }
            };
            let ncols = evaluated.0;
            if *col >= ncols.max(1) {
                return Err(format!(
                    "Dump local compute vector is accessed out-of-range: c_{cid}[{}] of a compute with {ncols} column(s)",
                    col + 1
                ).into());
            }
            data.push((evaluated, *col));
        }
        let nrows = data.first().map_or(0, |d| d.0 .1.len() / d.0 .0.max(1));
        let mut text = Vec::new();
        crate::io::dump::write_local(
            &mut text,
            self.step,
            &self.domain,
            &self.dumps[k].layout.names,
            self.dumps[k].layout.format.as_deref(),
            nrows,
            |r, c| data[c].0 .1[r * data[c].0 .0 + data[c].1],
        )
        .map_err(|e| e.to_string())?;
        Ok(text)
    }

    /// The snapshot of per-atom (or mesh) dump `k`.
    fn atom_dump_text(
        &self,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        let step = self.step;
        // per-atom values of the compute columns, evaluated once per snapshot
        let mut columns = Vec::new();
        for col in &self.dumps[k].layout.columns {
            if let Column::Reference(name) = col {
                columns.push(self.dump_reference(name, vars)?);
            }
        }
        let dump = &self.dumps[k];
        let mut text = Vec::new();
        let p = &self.particles;
        match &dump.style {
            // LAMMPS's binary format for names ending in .bin, as LIGGGHTS's dump custom
            DumpStyle::Text if dump.file.ends_with(".bin") => dump
                .layout
                .write_binary_snapshot(&mut text, step, p, dump.group, &self.domain, |c, i| {
                    columns[c].0.get(i, columns[c].1)
                })
                .map_err(|e| e.to_string())?,
            DumpStyle::Text => dump
                .layout
                .write_snapshot(&mut text, step, p, dump.group, &self.domain, |c, i| {
                    columns[c].0.get(i, columns[c].1)
                })
                .map_err(|e| e.to_string())?,
            DumpStyle::Xyz(elements) => {
                xyz_text(&mut text, step, p, dump.group, elements).map_err(|e| e.to_string())?
            }
            DumpStyle::MeshStl(ids) => text.extend_from_slice(self.mesh_stl_text(ids).as_bytes()),
            DumpStyle::MeshVtk(spec) => self.mesh_vtk_text(&mut text, spec)?,
            // written before the per-atom columns are evaluated
            DumpStyle::LocalGranVtk(_) | DumpStyle::EulerVtk => {}
            DumpStyle::Vtk(fields) => self.vtk_text(&mut text, dump, &columns, fields)?,
        }
        Ok(text)
    }

    /// `dump mesh/stl`: the triangles of the mesh fixes `ids` (all when empty) as ASCII STL.
    fn mesh_stl_text(&self, ids: &[String]) -> String {
        let (mut triangles, mut normals) = (Vec::new(), Vec::new());
        for f in &self.fixes {
            if let FixKind::Mesh(m) = &f.kind {
                if ids.is_empty() || ids.contains(&f.id) {
                    triangles.extend_from_slice(m.triangles());
                    normals.extend_from_slice(&m.mesh.normal);
                }
            }
        }
        crate::io::stl::write_ascii(&triangles, &normals)
    }

    /// `dump mesh/vtk`: the meshes `spec` names (all when none) with their per-triangle data.
    fn mesh_vtk_text(
        &self,
        text: &mut Vec<u8>,
        spec: &crate::io::mesh_vtk::MeshDumpSpec,
    ) -> Result<(), EngineError> {
        let meshes: Vec<&MeshFix> = if spec.meshes.is_empty() {
            self.fixes
                .iter()
                .filter_map(|f| match &f.kind {
                    FixKind::Mesh(m) => Some(&**m),
                    _ => None,
                })
                .collect()
        } else {
            spec.meshes
                .iter()
                .filter_map(|id| {
                    self.fixes.iter().find_map(|f| match &f.kind {
                        FixKind::Mesh(m) if &f.id == id => Some(&**m),
                        _ => None,
                    })
                })
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
        let snaps: Vec<crate::io::mesh_vtk::MeshSnapshot> = meshes
            .iter()
            .zip(&counts)
            .map(|(m, c)| {
                let st = m.stress.as_ref();
                crate::io::mesh_vtk::MeshSnapshot {
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
        crate::io::mesh_vtk::write_mesh_vtk(text, spec, &snaps).map_err(|e| e.to_string())?;
        Ok(())
    }

    /// `dump custom/vtk` (`atom/vtk`): the group's particles with the layout's columns
    /// (`columns`: the reference columns' values).
    fn vtk_text(
        &self,
        text: &mut Vec<u8>,
        dump: &Dump,
        columns: &References,
        fields: &[crate::io::vtk::Field],
    ) -> Result<(), EngineError> {
        let p = &self.particles;
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
        let domain = &self.domain;
        let value = |c: usize, i: usize| match &cols[c] {
            Column::Reference(_) => {
                let (values, col) = &columns[reference[c]];
                values.get(i, *col)
            }
            other => other.value(p, domain, i),
        };
        use crate::io::vtk::{
            write_particles, write_particles_binary, write_particles_xml, Flavor,
        };
        let binary = dump.layout.binary;
        match Flavor::of(&dump.file) {
            Some(f @ (Flavor::PolyData | Flavor::Unstructured)) => {
                write_particles_xml(text, f, binary, &atoms, fields, |i| p.x[i], value)
            }
            _ if binary => write_particles_binary(text, &atoms, fields, |i| p.x[i], value),
            _ => write_particles(text, &atoms, fields, |i| p.x[i], value),
        }
        .map_err(|e| e.to_string())?;
        Ok(())
    }
}

/// `dump xyz`: the group's particles as `ELEMENT x y z` lines (`elements`: the names of the
/// types, else the type number).
fn xyz_text(
    text: &mut Vec<u8>,
    step: i64,
    p: &Particles,
    group: u32,
    elements: &[String],
) -> std::io::Result<()> {
    use std::io::Write;
    let atoms: Vec<usize> = (0..p.len()).filter(|&i| p.mask[i] & group != 0).collect();
    writeln!(text, "{}\nAtoms. Timestep: {step}", atoms.len())?;
    for &i in &atoms {
        let t = p.kind[i] as usize;
        let element = elements
            .get(t.wrapping_sub(1))
            .cloned()
            .unwrap_or_else(|| t.to_string());
        let g = crate::util::format::g;
        let x = p.x[i];
        writeln!(text, "{element} {} {} {}", g(x[0]), g(x[1]), g(x[2]))?;
    }
    Ok(())
}
