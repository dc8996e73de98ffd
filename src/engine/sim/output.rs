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
                Some(crate::io::vtk::Flavor::Legacy) | None if dump.layout.binary => {
                    crate::io::vtk::write_bounding_box_binary(&mut bbox, &self.domain)
                }
                Some(crate::io::vtk::Flavor::Legacy) | None => {
                    crate::io::vtk::write_bounding_box(&mut bbox, &self.domain)
                }
                Some(_) => crate::io::vtk::write_bounding_box_xml(
                    &mut bbox,
                    &self.domain,
                    dump.layout.binary,
                ),
            }
            .map_err(|e| e.to_string())?;
            if crate::io::vtk::is_parallel(&name) {
                // the master file names its one piece (the process-0 file LIGGGHTS writes)
                let piece = crate::io::vtk::piece_name(&name);
                let source = piece.rsplit('/').next().unwrap_or(&piece);
                let flavor = crate::io::vtk::Flavor::of(&name).expect("a parallel VTK name");
                let master =
                    crate::io::vtk::parallel_master(&String::from_utf8_lossy(text), source, flavor);
                crate::io::write_atomically(&piece, text)
                    .map_err(|e| format!("Cannot open dump file {piece}: {e}"))?;
                crate::io::write_atomically(&name, master.as_bytes())
                    .map_err(|e| format!("Cannot open dump file {name}: {e}"))?;
            } else {
                crate::io::write_atomically(&name, text)
                    .map_err(|e| format!("Cannot open dump file {name}: {e}"))?;
            }
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
    pub(super) fn euler_vtk(&self) -> Result<String, EngineError> {
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
}
