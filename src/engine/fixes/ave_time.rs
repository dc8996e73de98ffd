//! `fix ave/time`: its inputs, how it combines them, and its sampling schedule.

use super::*;

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
        mode: AveMode,
        start: i64,
        step: i64,
    ) -> AveTime {
        let AveSchedule {
            every,
            repeat,
            freq,
        } = schedule;
        let n = inputs.len();
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

    /// Take one sample of `values` at `step`; at the end of an Nfreq block, write the line.
    pub fn sample(&mut self, step: i64, values: &[f64]) -> Result<(), EngineError> {
        use std::io::Write;
        if self.samples == 0 {
            self.sum.iter_mut().for_each(|s| *s = 0.0);
        }
        for (k, v) in values.iter().enumerate() {
            if self.off[k] {
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
        for (k, s) in self.sum.iter_mut().enumerate() {
            if !self.off[k] {
                *s /= repeat;
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
            if self.off[k] {
                self.total[k] = self.norm as f64 * self.sum[k];
            }
        }
        if let Some(f) = self.file.as_mut() {
            let mut line = step.to_string();
            for t in &self.total {
                line.push(' ');
                line.push_str(&crate::util::format::g(t / self.norm as f64));
            }
            writeln!(f, "{line}")
                .and_then(|_| f.flush())
                .map_err(|e| format!("fix ave/time: {e}"))?;
        }
        Ok(())
    }

    /// `f_ID` (index None, the first value) or `f_ID[i]` (1-based): the latest average, 0
    /// before the first.
    pub fn value(&self, index: Option<usize>) -> Option<f64> {
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
