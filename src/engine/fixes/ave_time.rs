//! `fix ave/time`: its inputs, how it combines them, and its sampling schedule.

use super::*;
use crate::engine::sim::{Simulation, VariableSource};

/// One input of `fix ave/time`.
#[derive(Debug, Clone, PartialEq)]
pub enum AveInput {
    /// `c_ID` or `c_ID[i]` (1-based): a global compute value.
    Compute(String, Option<usize>),
    /// `f_ID` or `f_ID[i]`: a global fix value.
    Fix(String, Option<usize>),
    /// `v_name`: an equal-style variable.
    Variable(String),
}

/// How `fix ave/time` combines its Nfreq averages.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AveMode {
    /// `ave one`: each output stands alone.
    One,
    /// `ave running`: the mean of all outputs so far.
    Running,
    /// `ave window M`: the mean of the last M outputs.
    Window(usize),
}

/// `fix ave/time Nevery Nrepeat Nfreq values... [ave ...] [start N] [off c] [file F]`
/// in scalar mode: averages of global values written every Nfreq steps.
pub struct AveTime {
    /// Sample every this many steps.
    pub every: i64,
    /// Samples per average.
    pub repeat: i64,
    /// Average (and write) every this many steps.
    pub freq: i64,
    /// The inputs, as written.
    pub inputs: Vec<AveInput>,
    /// Per input: `off` (take the last value, not the mean).
    pub off: Vec<bool>,
    /// How averages combine.
    pub mode: AveMode,
    /// The output file.
    pub file: Option<std::io::BufWriter<std::fs::File>>,
    /// `overwrite`: the file offset after the header, where each output starts again (bytes).
    pub overwrite: Option<u64>,
    /// `mode vector`: rows of every input (None in scalar mode).
    pub rows: Option<usize>,
    /// The next step that samples.
    pub next: i64,
    samples: i64,
    sum: Vec<f64>,
    total: Vec<f64>,
    norm: usize,
    window: Vec<Vec<f64>>,
    window_at: usize,
    window_full: bool,
}

/// When `fix ave/time` samples: `Nevery Nrepeat Nfreq` (steps).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AveSchedule {
    /// Steps between samples.
    pub every: i64,
    /// Samples per average.
    pub repeat: i64,
    /// Steps between averages.
    pub freq: i64,
}

impl AveTime {
    /// A fix defined at `step` whose averages start no earlier than `start`.
    pub fn new(
        schedule: AveSchedule,
        inputs: Vec<AveInput>,
        off: Vec<bool>,
        (mode, rows): (AveMode, Option<usize>),
        start: i64,
        step: i64,
    ) -> AveTime {
        let AveSchedule {
            every,
            repeat,
            freq,
        } = schedule;
        let n = inputs.len() * rows.unwrap_or(1);
        // the first sampling step, as LIGGGHTS's nextvalid()
        let mut next = (step / freq) * freq + freq;
        while next < start {
            next += freq;
        }
        if next - freq == step && repeat == 1 {
            next = step;
        } else {
            next -= (repeat - 1) * every;
        }
        if next < step {
            next += freq;
        }
        let window = match mode {
            AveMode::Window(m) => vec![vec![0.0; n]; m],
            _ => Vec::new(),
        };
        AveTime {
            every,
            repeat,
            freq,
            inputs,
            off,
            mode,
            file: None,
            overwrite: None,
            rows,
            next,
            samples: 0,
            sum: vec![0.0; n],
            total: vec![0.0; n],
            norm: 0,
            window,
            window_at: 0,
            window_full: false,
        }
    }

    /// Whether element `k` of the row-major value block belongs to an `off` input.
    fn off_at(&self, k: usize) -> bool {
        self.off[k % self.inputs.len()]
    }

    /// Take one sample of `values` at `step` (row-major: one value per input in scalar
    /// mode, `rows` rows of one value per input in vector mode); at the end of an Nfreq
    /// block, write the output.
    pub fn sample(&mut self, step: i64, values: &[f64]) -> Result<(), EngineError> {
        if self.samples == 0 {
            self.sum.iter_mut().for_each(|s| *s = 0.0);
        }
        for (k, v) in values.iter().enumerate() {
            if self.off_at(k) {
                self.sum[k] = *v;
            } else {
                self.sum[k] += v;
            }
        }
        self.samples += 1;
        if self.samples < self.repeat {
            self.next += self.every;
            return Ok(());
        }
        self.samples = 0;
        self.next = step + self.freq - (self.repeat - 1) * self.every;
        let repeat = self.repeat as f64;
        for k in 0..self.sum.len() {
            if !self.off_at(k) {
                self.sum[k] /= repeat;
            }
        }
        match self.mode {
            AveMode::One => {
                self.total.copy_from_slice(&self.sum);
                self.norm = 1;
            }
            AveMode::Running => {
                self.total
                    .iter_mut()
                    .zip(&self.sum)
                    .for_each(|(t, s)| *t += s);
                self.norm += 1;
            }
            AveMode::Window(m) => {
                for k in 0..self.sum.len() {
                    self.total[k] += self.sum[k];
                    if self.window_full {
                        self.total[k] -= self.window[self.window_at][k];
                    }
                    self.window[self.window_at][k] = self.sum[k];
                }
                self.window_at += 1;
                if self.window_at == m {
                    self.window_at = 0;
                    self.window_full = true;
                }
                self.norm = if self.window_full { m } else { self.window_at };
            }
        }
        for k in 0..self.sum.len() {
            if self.off_at(k) {
                self.total[k] = self.norm as f64 * self.sum[k];
            }
        }
        self.write(step)
    }

    /// Write the averages of `step` to the file: one line in scalar mode, a `step rows`
    /// line and one numbered line per row in vector mode.
    fn write(&mut self, step: i64) -> Result<(), EngineError> {
        use std::io::{Seek, Write};
        let Some(f) = self.file.as_mut() else {
            return Ok(());
        };
        let g = |t: f64| crate::util::format::g(t / self.norm as f64);
        let mut text = step.to_string();
        match self.rows {
            None => {
                for t in &self.total {
                    text.push(' ');
                    text.push_str(&g(*t));
                }
            }
            Some(rows) => {
                text.push_str(&format!(" {rows}"));
                for (r, row) in self.total.chunks(self.inputs.len()).enumerate() {
                    text.push_str(&format!("\n{}", r + 1));
                    for t in row {
                        text.push(' ');
                        text.push_str(&g(*t));
                    }
                }
            }
        }
        text.push('\n');
        let io = |e: std::io::Error| format!("fix ave/time: {e}");
        if let Some(at) = self.overwrite {
            f.seek(std::io::SeekFrom::Start(at)).map_err(io)?;
        }
        f.write_all(text.as_bytes())
            .and_then(|_| f.flush())
            .map_err(io)?;
        if let (Some(_), None) = (self.overwrite, self.rows) {
            // LIGGGHTS truncates after a scalar-mode line only
            let end = f.stream_position().map_err(io)?;
            f.get_ref().set_len(end).map_err(io)?;
        }
        Ok(())
    }

    /// `f_ID` (index None, the first value) or `f_ID[i]` (1-based): the latest average, 0
    /// before the first.
    pub fn value(&self, index: Option<usize>) -> Option<f64> {
        if let Some(rows) = self.rows {
            // mode vector with one input: a global vector, which LIGGGHTS 3.8.0 returns
            // as the running total, not divided by the number of outputs
            let k = index?.checked_sub(1)?;
            if self.inputs.len() > 1 || k >= rows {
                return None;
            }
            return Some(if self.norm > 0 { self.total[k] } else { 0.0 });
        }
        if index.is_none() && self.inputs.len() > 1 {
            return None; // LIGGGHTS: only a single-value fix ave/time has a scalar
        }
        let k = index.unwrap_or(1).checked_sub(1)?;
        let t = *self.total.get(k)?;
        Some(if self.norm > 0 {
            t / self.norm as f64
        } else {
            0.0
        })
    }
}

impl AveTime {
    /// Element (`row`, `col`) (1-based) of the global array of a vector-mode fix with
    /// several inputs: the latest average, 0 before the first.
    pub fn array(&self, row: usize, col: usize) -> Option<f64> {
        let (rows, n) = (self.rows?, self.inputs.len());
        if n < 2 || row == 0 || col == 0 || row > rows || col > n {
            return None;
        }
        let t = self.total[(row - 1) * n + col - 1];
        Some(if self.norm > 0 {
            t / self.norm as f64
        } else {
            0.0
        })
    }

    /// (rows, columns) of the fix's global array (vector mode, several inputs).
    pub fn array_size(&self) -> Option<(usize, usize)> {
        let (rows, n) = (self.rows?, self.inputs.len());
        (n > 1).then_some((rows, n))
    }

    /// A copy of the averages without the file (what stands in the fix list while the fix
    /// samples: its values and array stay readable).
    fn snapshot(&self) -> AveTime {
        AveTime {
            inputs: self.inputs.clone(),
            off: self.off.clone(),
            file: None,
            sum: self.sum.clone(),
            total: self.total.clone(),
            window: Vec::new(),
            ..*self
        }
    }

    /// Take a sample if one is due at the simulation's step (values read with `vars`).
    fn sample_due(
        &mut self,
        sim: &Simulation,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        if self.next != sim.step {
            return Ok(());
        }
        let values = sim.ave_time_values(self, vars)?;
        self.sample(sim.step, &values)
    }

    /// Length of the fix's global vector: its inputs in scalar mode (more than one), its
    /// rows in vector mode (one input); 0 without one.
    pub fn vector_len(&self) -> usize {
        match self.rows {
            Some(rows) if self.inputs.len() == 1 => rows,
            None if self.inputs.len() > 1 => self.inputs.len(),
            _ => 0,
        }
    }
}

impl FixStyle for AveTime {
    fn name(&self) -> &str {
        "ave/time"
    }

    fn global_freq(&self) -> i64 {
        self.freq
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        AveTime::value(self, index)
    }

    fn reads_computes(&self) -> bool {
        true
    }

    fn array_unsupported(&self) -> bool {
        true
    }

    fn end_of_step_sim_due(&self, step: i64) -> bool {
        self.next == step
    }

    fn end_of_step_sim(
        &mut self,
        sim: &mut Simulation,
        _k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.sample_due(sim, vars)
    }

    fn setup_pass(&self) -> Option<SetupPass> {
        Some(SetupPass::TimeAverages)
    }

    /// A sample due at the run's setup (LIGGGHTS runs `end_of_step` there too).
    fn setup_sim(
        &mut self,
        sim: &mut Simulation,
        _k: usize,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        self.sample_due(sim, vars)
    }

    fn stand_in(&self) -> Option<Box<dyn FixStyle>> {
        Some(Box::new(self.snapshot()))
    }
}
