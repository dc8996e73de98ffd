//! `fix ave/histo` of per-atom inputs (`mode vector`): the group's values counted in bins
//! between lo and hi, `repeat` samples every `every` steps ending on multiples of `freq`,
//! combined as `ave one|running|window` and written to a file as LIGGGHTS 3.8.0's
//! fix_ave_histo.cpp writes it.

use crate::engine::ave_atom::AtomInput;
use crate::engine::error::EngineError;
use crate::engine::fixes::{AveMode, FixStyle, SetupPass};
use crate::engine::sim::{Simulation, VariableSource};
use std::io::{Seek, Write};

/// LIGGGHTS's BIG: the min and max of no values.
const BIG: f64 = 1.0e20;

/// What happens to values outside lo..hi.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Beyond {
    /// Not counted in a bin (counted as missing).
    Ignore,
    /// Counted in the first or last bin.
    End,
    /// Counted in two extra bins below lo and above hi.
    Extra,
}

/// `fix ID GROUP ave/histo Nevery Nrepeat Nfreq lo hi Nbin input ... mode vector ...`.
#[derive(Debug)]
pub struct AveHisto {
    /// Steps between samples, samples per histogram, steps between histograms.
    pub schedule: (i64, i64, i64),
    /// `start N`: no histogram before this step.
    pub start: i64,
    /// The binned range (the inputs' units).
    pub range: (f64, f64),
    /// Values outside the range.
    pub beyond: Beyond,
    /// The per-atom inputs.
    pub inputs: Vec<AtomInput>,
    /// How histograms combine.
    pub mode: AveMode,
    /// `overwrite`: each output replaces the previous one in the file.
    pub overwrite: bool,
    /// The output file and where its header ends.
    pub file: Option<(std::fs::File, u64)>,
    /// The next step that samples.
    pub nvalid: i64,
    irepeat: i64,
    bininv: f64,
    coord: Vec<f64>,
    stats: [f64; 4],
    stats_total: [f64; 4],
    bin: Vec<f64>,
    bin_total: Vec<f64>,
    window: Vec<([f64; 4], Vec<f64>)>,
    iwindow: usize,
    window_full: bool,
}

impl AveHisto {
    /// A fix of `nbins` bins (two more with `beyond extra`) defined at `step`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        schedule: (i64, i64, i64),
        start: i64,
        range: (f64, f64),
        nbins: usize,
        beyond: Beyond,
        inputs: Vec<AtomInput>,
        (mode, overwrite): (AveMode, bool),
        step: i64,
    ) -> AveHisto {
        let (lo, hi) = range;
        let n = if beyond == Beyond::Extra {
            nbins + 2
        } else {
            nbins
        };
        let inner = if beyond == Beyond::Extra { n - 2 } else { n };
        let binsize = (hi - lo) / inner as f64;
        let coord = (0..n)
            .map(|i| match beyond {
                Beyond::Extra if i == 0 => lo,
                Beyond::Extra if i == n - 1 => hi,
                Beyond::Extra => lo + (i as f64 - 1.0 + 0.5) * binsize,
                _ => lo + (i as f64 + 0.5) * binsize,
            })
            .collect();
        let window = match mode {
            AveMode::Window(w) => vec![([0.0; 4], vec![0.0; n]); w],
            _ => Vec::new(),
        };
        let mut h = AveHisto {
            schedule,
            start,
            range,
            beyond,
            inputs,
            mode,
            overwrite,
            file: None,
            nvalid: 0,
            irepeat: 0,
            bininv: 1.0 / binsize,
            coord,
            stats: [0.0; 4],
            stats_total: [0.0; 4],
            bin: vec![0.0; n],
            bin_total: vec![0.0; n],
            window,
            iwindow: 0,
            window_full: false,
        };
        h.nvalid = h.next_valid(step);
        h
    }

    /// The first sampling step at or after `step`, not before `start` (LIGGGHTS's
    /// `nextvalid`).
    pub fn next_valid(&self, step: i64) -> i64 {
        let (every, repeat, freq) = self.schedule;
        let mut nvalid = (step / freq) * freq + freq;
        while nvalid < self.start {
            nvalid += freq;
        }
        if nvalid - freq == step && repeat == 1 {
            nvalid = step;
        } else {
            nvalid -= (repeat - 1) * every;
        }
        if nvalid < step {
            nvalid += freq;
        }
        nvalid
    }

    /// Count one value (LIGGGHTS's `bin_one`).
    fn bin_one(&mut self, value: f64) {
        let (lo, hi) = self.range;
        let n = self.bin.len();
        self.stats[2] = self.stats[2].min(value);
        self.stats[3] = self.stats[3].max(value);
        if value < lo || value > hi {
            if self.beyond == Beyond::Ignore {
                self.stats[1] += 1.0;
                return;
            }
            self.bin[if value < lo { 0 } else { n - 1 }] += 1.0;
        } else {
            let mut i = (((value - lo) * self.bininv) as i32 as usize).min(n - 1);
            if self.beyond == Beyond::Extra {
                i += 1;
            }
            self.bin[i] += 1.0;
        }
        self.stats[0] += 1.0;
    }

    /// The histogram combined with earlier ones.
    fn combine(&mut self) {
        match self.mode {
            AveMode::One => {
                self.stats_total = self.stats;
                self.bin_total.clone_from(&self.bin);
            }
            AveMode::Running => {
                self.stats_total[0] += self.stats[0];
                self.stats_total[1] += self.stats[1];
                self.stats_total[2] = self.stats_total[2].min(self.stats[2]);
                self.stats_total[3] = self.stats_total[3].max(self.stats[3]);
                for (t, b) in self.bin_total.iter_mut().zip(&self.bin) {
                    *t += b;
                }
            }
            AveMode::Window(w) => {
                let k = self.iwindow;
                for s in 0..2 {
                    self.stats_total[s] += self.stats[s];
                    if self.window_full {
                        self.stats_total[s] -= self.window[k].0[s];
                    }
                    self.window[k].0[s] = self.stats[s];
                }
                let used = if self.window_full { w } else { k + 1 };
                self.window[k].0[2] = self.stats[2];
                self.window[k].0[3] = self.stats[3];
                self.stats_total[2] = self.window[0].0[2];
                self.stats_total[3] = self.window[0].0[3];
                for i in 1..used {
                    self.stats_total[2] = self.stats_total[2].min(self.window[i].0[2]);
                    self.stats_total[3] = self.stats_total[3].max(self.window[i].0[3]);
                }
                for i in 0..self.bin.len() {
                    self.bin_total[i] += self.bin[i];
                    if self.window_full {
                        self.bin_total[i] -= self.window[k].1[i];
                    }
                    self.window[k].1[i] = self.bin[i];
                }
                self.iwindow += 1;
                if self.iwindow == w {
                    self.iwindow = 0;
                    self.window_full = true;
                }
            }
        }
    }

    /// One output block: `step nbins total missing min max`, then per bin its number,
    /// centre, count and fraction (`%g`).
    fn write(&mut self, step: i64) -> Result<(), EngineError> {
        let Some((file, header_end)) = &mut self.file else {
            return Ok(());
        };
        let g = crate::util::format::g;
        let t = self.stats_total;
        let mut text = format!(
            "{step} {} {} {} {} {}\n",
            self.bin.len(),
            g(t[0]),
            g(t[1]),
            g(t[2]),
            g(t[3])
        );
        for (i, c) in self.coord.iter().enumerate() {
            let (count, fraction) = if t[0] != 0.0 {
                (self.bin_total[i], self.bin_total[i] / t[0])
            } else {
                (0.0, 0.0)
            };
            text.push_str(&format!(
                "{} {} {} {}\n",
                i + 1,
                g(*c),
                g(count),
                g(fraction)
            ));
        }
        write_block(file, *header_end, self.overwrite, &text)
            .map_err(|e| EngineError::Invalid(format!("fix ave/histo file: {e}")))
    }
}

/// Append one output block to an averaging fix's `file`; with `overwrite` it replaces the
/// previous block (everything after the header's `header_end` bytes), as LIGGGHTS's
/// `overwrite` keyword does.
pub(crate) fn write_block(
    file: &mut std::fs::File,
    header_end: u64,
    overwrite: bool,
    text: &str,
) -> std::io::Result<()> {
    if overwrite {
        file.seek(std::io::SeekFrom::Start(header_end))?;
    }
    file.write_all(text.as_bytes())?;
    if overwrite {
        let end = file.stream_position()?;
        file.set_len(end)?;
    }
    Ok(())
}

impl AveHisto {
    /// LIGGGHTS's `end_of_step`: one sample of the inputs of the particles in `group`, and
    /// the histogram combined and written when the sample completes it.
    fn sample(
        &mut self,
        sim: &Simulation,
        group: u32,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let columns = self
            .inputs
            .iter()
            .map(|input| sim.ave_atom_input(input, vars))
            .collect::<Result<Vec<_>, _>>()?;
        let mask = &sim.particles.mask;
        let step = sim.step;
        if self.irepeat == 0 {
            self.stats = [0.0, 0.0, BIG, -BIG];
            self.bin.fill(0.0);
        }
        for column in &columns {
            for (i, v) in column.iter().enumerate() {
                if mask[i] & group != 0 {
                    self.bin_one(*v);
                }
            }
        }
        let (every, repeat, freq) = self.schedule;
        self.irepeat += 1;
        if self.irepeat < repeat {
            self.nvalid += every;
            return Ok(());
        }
        self.irepeat = 0;
        self.nvalid = step + freq - (repeat - 1) * every;
        self.combine();
        self.write(step)
    }
}

impl FixStyle for AveHisto {
    fn name(&self) -> &str {
        "ave/histo"
    }

    fn reads_computes(&self) -> bool {
        true
    }

    fn array_unsupported(&self) -> bool {
        true
    }

    fn end_of_step_sim_due(&self, step: i64) -> bool {
        self.nvalid == step
    }

    fn end_of_step_sim(
        &mut self,
        sim: &mut Simulation,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.sample(sim, sim.fixes[k].group, vars)
    }

    fn setup_pass(&self) -> Option<SetupPass> {
        Some(SetupPass::Histograms)
    }

    /// A schedule left behind restarts (LIGGGHTS's `init`), then a sample if one is due
    /// now (its `setup`).
    fn setup_sim(
        &mut self,
        sim: &mut Simulation,
        k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = sim.step;
        if self.nvalid < step {
            self.irepeat = 0;
            self.nvalid = self.next_valid(step);
        }
        if self.nvalid != step {
            return Ok(());
        }
        self.sample(sim, sim.fixes[k].group, vars)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_fall_in_bins_as_liggghts_bins_them() {
        let mut h = AveHisto::new(
            (10, 2, 100),
            0,
            (0.0, 1.0),
            4,
            Beyond::Extra,
            Vec::new(),
            (AveMode::One, false),
            0,
        );
        assert_eq!(h.nvalid, 90);
        assert_eq!(h.coord, [0.0, 0.125, 0.375, 0.625, 0.875, 1.0]);
        h.stats = [0.0, 0.0, BIG, -BIG];
        for v in [-0.5, 0.0, 0.3, 1.0, 1.5] {
            h.bin_one(v);
        }
        // -0.5 below lo in the first extra bin; 1.0 (= hi) and 1.5 in the last
        assert_eq!(h.bin, [1.0, 1.0, 1.0, 0.0, 0.0, 2.0]);
        assert_eq!(h.stats, [5.0, 0.0, -0.5, 1.5]);
    }
}
