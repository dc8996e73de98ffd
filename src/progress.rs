//! A one-line run status on a terminal: step, % of the run, particle-steps per second and the
//! time left, on standard error, redrawn at most four times a second. It is only installed
//! when standard error is a terminal; logs and screen output are untouched (screen lines
//! clear the status line first, and the next update redraws it).

use std::io::{IsTerminal, Write};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The engine calls these while it runs (see `Simulation::observer`).
pub trait StepObserver {
    /// A run from step `first` to `last` starts its loop with `atoms` particles.
    fn run_started(&mut self, first: i64, last: i64, atoms: usize);
    /// The loop finished `step`; called every [`OBSERVE_EVERY`] steps.
    fn step(&mut self, step: i64, atoms: usize);
    /// The run's loop ended.
    fn run_finished(&mut self);
}

/// How often (in steps) the engine calls [`StepObserver::step`].
pub const OBSERVE_EVERY: i64 = 64;

/// The status line on standard error.
pub struct TerminalProgress {
    shown: Arc<AtomicBool>,
    first: i64,
    last: i64,
    started: Instant,
    last_draw: Instant,
    particle_steps: f64,
    last_step: i64,
}

impl TerminalProgress {
    /// A status line sharing `shown` with the screen writer that clears it.
    pub fn new(shown: Arc<AtomicBool>) -> TerminalProgress {
        let now = Instant::now();
        TerminalProgress {
            shown,
            first: 0,
            last: 0,
            started: now,
            last_draw: now,
            particle_steps: 0.0,
            last_step: 0,
        }
    }
}

/// Seconds as `1h02m`, `3m05s` or `12s`.
pub fn duration_text(s: f64) -> String {
    let s = s.max(0.0).round() as u64;
    match s {
        0..=59 => format!("{s}s"),
        60..=3599 => format!("{}m{:02}s", s / 60, s % 60),
        _ => format!("{}h{:02}m", s / 3600, (s % 3600) / 60),
    }
}

/// The status text.
pub fn status_line(step: i64, first: i64, last: i64, rate: f64, elapsed: f64) -> String {
    let total = (last - first).max(1) as f64;
    let done = (step - first) as f64;
    let eta = if done > 0.0 {
        elapsed * (total - done) / done
    } else {
        0.0
    };
    format!(
        "step {step} of {last}  {:5.1}%  {:.3} M particle-steps/s  ETA {}",
        100.0 * done / total,
        rate / 1e6,
        duration_text(eta)
    )
}

impl StepObserver for TerminalProgress {
    fn run_started(&mut self, first: i64, last: i64, _atoms: usize) {
        let now = Instant::now();
        (self.first, self.last, self.started, self.last_draw) = (first, last, now, now);
        self.particle_steps = 0.0;
        self.last_step = first;
    }

    fn step(&mut self, step: i64, atoms: usize) {
        self.particle_steps += (step - self.last_step) as f64 * atoms as f64;
        self.last_step = step;
        if self.last_draw.elapsed() < Duration::from_millis(250) {
            return;
        }
        self.last_draw = Instant::now();
        let elapsed = self.started.elapsed().as_secs_f64();
        let line = status_line(
            step,
            self.first,
            self.last,
            self.particle_steps / elapsed,
            elapsed,
        );
        let mut e = std::io::stderr().lock();
        let _ = write!(e, "\r\x1b[2K{line}");
        let _ = e.flush();
        self.shown.store(true, Ordering::Relaxed);
    }

    fn run_finished(&mut self) {
        clear(&self.shown);
    }
}

fn clear(shown: &AtomicBool) {
    if shown.swap(false, Ordering::Relaxed) {
        let mut e = std::io::stderr().lock();
        let _ = write!(e, "\r\x1b[2K");
        let _ = e.flush();
    }
}

/// A screen writer that clears the status line before anything it writes.
pub struct ClearingWriter<W: Write> {
    inner: W,
    shown: Arc<AtomicBool>,
}

impl<W: Write> Write for ClearingWriter<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        clear(&self.shown);
        self.inner.write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// The screen writer (None: `-screen none`).
pub type Screen = Option<Box<dyn Write>>;

/// When standard error is a terminal: the status line, and the screen writer wrapped so that
/// it clears the line before writing. Otherwise no status line and the screen unchanged.
pub fn attach(screen: Option<Box<dyn Write>>) -> (Option<Box<dyn StepObserver>>, Screen) {
    if !std::io::stderr().is_terminal() {
        return (None, screen);
    }
    let shown = Arc::new(AtomicBool::new(false));
    let screen = screen.map(|inner| {
        Box::new(ClearingWriter {
            inner,
            shown: shown.clone(),
        }) as Box<dyn Write>
    });
    (Some(Box::new(TerminalProgress::new(shown))), screen)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn status_text() {
        let s = status_line(1500, 1000, 2000, 2.5e6, 10.0);
        assert_eq!(
            s,
            "step 1500 of 2000   50.0%  2.500 M particle-steps/s  ETA 10s"
        );
        assert_eq!(duration_text(125.0), "2m05s");
        assert_eq!(duration_text(7300.0), "2h01m");
    }

    #[test]
    fn screen_writes_clear_a_shown_line() {
        let shown = Arc::new(AtomicBool::new(true));
        let mut w = ClearingWriter {
            inner: Vec::new(),
            shown: shown.clone(),
        };
        w.write_all(b"Step KinEng\n").unwrap();
        assert!(!shown.load(Ordering::Relaxed));
        assert_eq!(w.inner, b"Step KinEng\n");
    }
}
