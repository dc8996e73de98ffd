//! A run's output: restart files, thermo lines and dumps.

use super::*;

impl Simulation {
    /// Write the current state as a restart file (`write_restart`): pair history taken from
    /// the current list, then positions wrapped and the box reset as LIGGGHTS does.
    pub fn save_restart(&mut self, path: &str) -> Result<(), EngineError> {
        self.refuse_clump_restart()?;
        self.check_restart_size()?;
        let partners = self.contact_partners();
        self.pbc_and_box()?;
        let r = self.to_restart(&partners);
        crate::io::restart::write(&r, path).map_err(|e| EngineError::Invalid(e.to_string()))
    }

    /// The `restart` command's files, due at multiples of its interval (not at setup).
    pub(super) fn periodic_restart(&mut self) -> Result<(), EngineError> {
        let mut paths = Vec::new();
        for out in self.restart_output.iter_mut().flatten() {
            if self.step % out.every != 0 || out.last == Some(self.step) {
                continue;
            }
            out.last = Some(self.step);
            paths.push(if out.files.len() == 1 {
                out.files[0].replace('*', &self.step.to_string())
            } else {
                let p = out.files[out.toggle].clone();
                out.toggle = 1 - out.toggle;
                p
            });
        }
        if paths.is_empty() {
            return Ok(());
        }
        // written from the current state without re-wrapping (the run goes on)
        self.check_restart_size()?;
        let partners = self.contact_partners();
        let r = self.to_restart(&partners);
        for path in paths {
            crate::io::restart::write(&r, &path).map_err(|e| e.to_string())?;
        }
        Ok(())
    }

    pub(super) fn thermo_line(
        &mut self,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let values = self.thermo.values(self, vars)?;
        // a value that overflowed (an energy of huge, fast particles) ends the run rather
        // than printing inf or nan
        let bad = values.iter().position(|v| !v.is_finite());
        if let Some(k) = bad {
            return Err(format!(
                "blow-up at step {}: thermo keyword {} is {}; a value of the simulation overflowed (check particle sizes, densities and velocities)",
                self.step,
                self.thermo.fields[k].keyword,
                values[k]
            ).into());
        }
        let cpu = self.loop_clock.map_or(0.0, |t| t.elapsed().as_secs_f64());
        let thermo_file = &mut self.extras.thermo_file;
        self.thermo.line(&values, self.step, cpu, &mut |s: &str| {
            out(s);
            crate::engine::extras::tee(thermo_file, s)
        });
        Ok(())
    }

    /// Write one snapshot's text to dump `k`'s file (one file per step for `*` names,
    /// written whole through a temporary file).
    pub(super) fn write_dump_text(
        &mut self,
        k: usize,
        step: i64,
        text: &[u8],
    ) -> Result<(), EngineError> {
        use std::io::Write;
        let dump = &mut self.dumps[k];
        let multi = dump.file.contains('*');
        let step_text = format!("{step:0width$}", width = dump.pad);
        let name = dump.file.replace('*', &step_text);
        if let Some(dir) = std::path::Path::new(&name).parent() {
            if !dir.as_os_str().is_empty() {
                std::fs::create_dir_all(dir)
                    .map_err(|e| format!("Cannot open dump file {name}: {e}"))?;
            }
        }
        // a .gz name gets gzip: a whole file per snapshot for `*` names, else one stream
        let gzip = name.ends_with(".gz");
        let packed;
        let text = if gzip && multi {
            let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
            enc.write_all(text).map_err(|e| format!("{name}: {e}"))?;
            packed = enc.finish().map_err(|e| format!("{name}: {e}"))?;
            &packed[..]
        } else {
            text
        };
        if let DumpStyle::Vtk(_) = dump.style {
            // one snapshot per file (overwritten without `*`), and the box beside it
            let mut bbox = Vec::new();
            match crate::io::vtk::Flavor::of(&dump.file) {
                Some(crate::io::vtk::Flavor::Legacy) | None => {
                    crate::io::vtk::write_bounding_box(&mut bbox, &self.domain)
                }
                Some(_) => crate::io::vtk::write_bounding_box_xml(&mut bbox, &self.domain),
            }
            .map_err(|e| e.to_string())?;
            crate::io::write_atomically(&name, text)
                .map_err(|e| format!("Cannot open dump file {name}: {e}"))?;
            let box_name = crate::io::vtk::bounding_box_name(&dump.file, &step_text);
            crate::io::write_atomically(&box_name, &bbox)
                .map_err(|e| format!("Cannot open dump file {box_name}: {e}"))?;
        } else if multi
            || matches!(
                dump.style,
                DumpStyle::MeshStl(_)
                    | DumpStyle::MeshVtk(_)
                    | DumpStyle::LocalGranVtk(_)
                    | DumpStyle::EulerVtk
            )
        {
            crate::io::write_atomically(&name, text)
                .map_err(|e| format!("Cannot open dump file {name}: {e}"))?;
        } else {
            if dump.handle.is_none() {
                let f = std::fs::File::create(&name)
                    .map_err(|e| format!("Cannot open dump file {name}: {e}"))?;
                let f = std::io::BufWriter::new(f);
                dump.handle = Some(if gzip {
                    DumpFile::Gzip(flate2::write::GzEncoder::new(
                        f,
                        flate2::Compression::default(),
                    ))
                } else {
                    DumpFile::Plain(f)
                });
            }
            let h = dump.handle.as_mut().expect("opened above");
            h.write_all(text)
                .and_then(|_| h.flush())
                .map_err(|e| format!("{name}: {e}"))?;
        }
        Ok(())
    }

    /// The text of a `dump euler/vtk` snapshot: the first `fix ave/euler`'s cells.
    fn euler_vtk(&self) -> Result<String, EngineError> {
        self.fixes
            .iter()
            .find_map(|f| match &f.kind {
                FixKind::Style(s) if f.style == "ave/euler" => s
                    .as_any()
                    .and_then(|a| a.downcast_ref::<crate::engine::ave_euler::EulerGrid>())
                    .map(|g| g.vtk()),
                _ => None,
            })
            .ok_or_else(|| "Illegal dump euler/vtk command, need a fix ave/euler".into())
    }

    pub(crate) fn write_dumps(
        &mut self,
        setup: bool,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = self.step;
        // a local compute is evaluated once per step, however many columns and dumps use it
        let mut local_rows: std::collections::HashMap<String, std::rc::Rc<(usize, Vec<f64>)>> =
            std::collections::HashMap::new();
        for k in 0..self.dumps.len() {
            let d = &self.dumps[k];
            let due = (step % d.every == 0 || (setup && d.first && d.last_written.is_none()))
                && d.last_written != Some(step);
            if !due {
                continue;
            }
            self.dumps[k].last_written = Some(step);
            if let Some(cols) = self.dumps[k].local.clone() {
                let mut data = Vec::new();
                for (cid, col) in &cols {
                    let c = self
                        .computes
                        .iter()
                        .find(|c| &c.id == cid)
                        .ok_or_else(|| format!("Could not find dump local compute ID {cid}"))?;
                    let evaluated = match local_rows.get(cid) {
                        Some(r) => r.clone(),
                        None => {
                            let r = std::rc::Rc::new(c.local(self)?);
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
                    step,
                    &self.domain,
                    &self.dumps[k].layout.names,
                    self.dumps[k].layout.format.as_deref(),
                    nrows,
                    |r, c| data[c].0 .1[r * data[c].0 .0 + data[c].1],
                )
                .map_err(|e| e.to_string())?;
                self.write_dump_text(k, step, &text)?;
                continue;
            }
            if let DumpStyle::EulerVtk = &self.dumps[k].style {
                let text = self.euler_vtk()?;
                self.write_dump_text(k, step, text.as_bytes())?;
                continue;
            }
            if let DumpStyle::LocalGranVtk(cid) = &self.dumps[k].style {
                let text = crate::engine::local_vtk::snapshot(self, cid, &self.dumps[k].file)?;
                self.write_dump_text(k, step, &text)?;
                continue;
            }
            // per-atom values of the compute columns, evaluated once per snapshot
            let mut columns = Vec::new();
            for col in &self.dumps[k].layout.columns {
                if let crate::io::dump::Column::Reference(name) = col {
                    columns.push(self.dump_reference(name, vars)?);
                }
            }
            let dump = &mut self.dumps[k];
            let mut text = Vec::new();
            let p = &self.particles;
            match &dump.style {
                DumpStyle::Text => dump
                    .layout
                    .write_snapshot(&mut text, step, p, dump.group, &self.domain, |c, i| {
                        columns[c].0.get(i, columns[c].1)
                    })
                    .map_err(|e| e.to_string())?,
                DumpStyle::Xyz(elements) => {
                    use std::io::Write;
                    let atoms: Vec<usize> = (0..p.len())
                        .filter(|&i| p.mask[i] & dump.group != 0)
                        .collect();
                    let mut w = || -> std::io::Result<()> {
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
                    };
                    w().map_err(|e| e.to_string())?;
                }
                DumpStyle::MeshStl(ids) => {
                    let (mut triangles, mut normals) = (Vec::new(), Vec::new());
                    for f in &self.fixes {
                        if let FixKind::Mesh(m) = &f.kind {
                            if ids.is_empty() || ids.contains(&f.id) {
                                triangles.extend_from_slice(m.triangles());
                                normals.extend_from_slice(&m.mesh.normal);
                            }
                        }
                    }
                    text.extend_from_slice(
                        crate::io::stl::write_ascii(&triangles, &normals).as_bytes(),
                    );
                }
                DumpStyle::MeshVtk(spec) => {
                    let meshes: Vec<&crate::engine::fixes::MeshFix> = if spec.meshes.is_empty() {
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
                    crate::io::mesh_vtk::write_mesh_vtk(&mut text, spec, &snaps)
                        .map_err(|e| e.to_string())?;
                }
                // written before the per-atom columns are evaluated
                DumpStyle::LocalGranVtk(_) | DumpStyle::EulerVtk => {}
                DumpStyle::Vtk(fields) => {
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
                        if let crate::io::dump::Column::Reference(_) = col {
                            reference[c] = r;
                            r += 1;
                        }
                    }
                    let domain = &self.domain;
                    let value = |c: usize, i: usize| match &cols[c] {
                        crate::io::dump::Column::Reference(_) => {
                            let (values, col) = &columns[reference[c]];
                            values.get(i, *col)
                        }
                        other => other.value(p, domain, i),
                    };
                    use crate::io::vtk::{write_particles, write_particles_xml, Flavor};
                    match Flavor::of(&dump.file) {
                        Some(f @ (Flavor::PolyData | Flavor::Unstructured)) => {
                            write_particles_xml(&mut text, f, &atoms, fields, |i| p.x[i], value)
                        }
                        _ => write_particles(&mut text, &atoms, fields, |i| p.x[i], value),
                    }
                    .map_err(|e| e.to_string())?;
                }
            }
            self.write_dump_text(k, step, &text)?;
        }
        Ok(())
    }
}
