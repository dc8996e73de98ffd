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
        match self.comm.as_ref().filter(|c| c.size() > 1) {
            Some(comm) => self.save_restart_on_ranks(comm, &r, path),
            None => {
                crate::io::restart::write(&r, path).map_err(|e| EngineError::Invalid(e.to_string()))
            }
        }
    }

    /// A restart file written on several ranks, every rank holding the whole set (between
    /// runs) in the order one process holds it: one file written by rank 0, the same bytes
    /// as one process writes; a `%` name gives LIGGGHTS's base file (rank 0, with the
    /// processor count and grid) and one file per rank with the particles of its brick of
    /// the box. Any rank's failure stops every rank.
    pub(super) fn save_restart_on_ranks(
        &self,
        comm: &crate::util::comm::RankComm,
        r: &crate::io::restart::Restart,
        path: &str,
    ) -> Result<(), EngineError> {
        use crate::engine::decomp::Decomposition;
        let me = comm.rank();
        let (grid, mine) = if path.contains('%') {
            let prd = [0, 1, 2].map(|d| self.domain.length(d));
            let grid = crate::engine::procmap::choose_grid(&self.procs, prd)?;
            let periodic = [0, 1, 2].map(|d| self.domain.periodic(d));
            let (lo, hi) = (self.domain.lo, self.domain.hi);
            let dec = Decomposition::new(&self.procs, &grid, me, lo, hi, periodic);
            // a particle on no brick (on an upper face) goes to the last rank
            let last = dec.size().saturating_sub(1);
            let mine: Vec<usize> = (0..self.particles.len())
                .filter(|&i| dec.owner_of(self.particles.x[i]).unwrap_or(last) == me)
                .collect();
            (grid.procs.map(|v| v as i32), mine)
        } else {
            ([1, 1, 1], Vec::new())
        };
        let written = crate::io::restart::write_processor_files(r, path, grid, me, &mine);
        let failed =
            comm.all_reduce_i64(i64::from(written.is_err()), crate::util::comm::Reduce::Max);
        match written {
            Err(e) => Err(EngineError::Invalid(e.to_string())),
            Ok(()) if failed > 0 => Err(EngineError::Invalid(format!(
                "Cannot write restart file {path}: another rank could not write its part"
            ))),
            Ok(()) => Ok(()),
        }
    }

    /// Whether this process writes the files of commands run between runs (`write_data`,
    /// `write_dump`): one process, or rank 0 of several (every rank holds the whole set
    /// between runs, so rank 0's file is the one one process writes).
    pub fn writes_files(&self) -> bool {
        self.comm.as_ref().is_none_or(|c| c.rank() == 0)
    }

    /// The outcome of a file only rank 0 wrote (`Ok` on the others), agreed by every rank:
    /// rank 0's failure fails them all. One process: `written` itself.
    pub fn agree_on_file(&self, written: Result<(), String>, name: &str) -> Result<(), String> {
        let Some(comm) = self.comm.as_ref().filter(|c| c.size() > 1) else {
            return written;
        };
        let failed =
            comm.all_reduce_i64(i64::from(written.is_err()), crate::util::comm::Reduce::Max);
        match written {
            Ok(()) if failed > 0 => Err(format!("Cannot write {name}: rank 0 could not write it")),
            other => other,
        }
    }

    /// The `restart` command's files, due at multiples of its interval (not at setup).
    pub(super) fn periodic_restart(&mut self) -> Result<(), EngineError> {
        let paths = self.restart_paths_due();
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

    /// The names of the `restart` command's files due at this step (multiples of its
    /// interval, not at setup), each write noted (and the two names' turn taken).
    pub(super) fn restart_paths_due(&mut self) -> Vec<String> {
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
        paths
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
        let dump = &self.dumps[k];
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
        if multi || dump.style.whole_files() {
            dump.style
                .write_whole(&crate::engine::dump_style::WholeSnapshot {
                    domain: &self.domain,
                    file: &dump.file,
                    name: &name,
                    step_text: &step_text,
                    binary: dump.layout.binary,
                    text,
                })?;
        } else {
            let dump = &mut self.dumps[k];
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
}
