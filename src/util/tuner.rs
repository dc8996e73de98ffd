//! Whether a small run's stages go to the team of threads or stay on one thread, chosen from
//! measured step times. On a scene of a few thousand particles a stage is a few microseconds
//! of work, and handing it out, waiting for the slowest thread and moving the particles' data
//! between cores can cost more than a second thread gains; which way it goes depends on the
//! scene (a ring of 2 400 spheres whose step is half serial formula evaluation runs faster on
//! one thread, a channel of 3 600 spheres faster on two). Results are the same either way (a
//! stage gives the same answer on any number of threads), so the choice costs no accuracy.

/// Particles from which a run always shares its stages out (never measured): beds this large
/// gain from every thread.
pub const TUNE_BELOW: usize = 8192;

/// Steps timed in each mode per trial.
pub const TRIAL_STEPS: usize = 100;

/// Steps between trials (a pour's particle count grows; a scene's contacts change).
pub const RETRIAL_STEPS: u64 = 5000;

/// What the tuner is doing.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    /// Timing steps with the stages shared out.
    TryShared,
    /// Timing steps on one thread; the shared steps' median time (s).
    TryAlone(f64),
    /// Running as chosen (`true`: on one thread) for this many more steps.
    Chosen(bool, u64),
}

/// Chooses, trial after trial, the faster of "stages shared out" and "stages on one thread"
/// by the median step time of each (a median, so output steps and a busy machine's stalls
/// count little).
#[derive(Debug, Clone)]
pub struct Tuner {
    mode: Mode,
    times: Vec<f64>,
    trial: usize,
    every: u64,
}

impl Default for Tuner {
    fn default() -> Self {
        Tuner::new(TRIAL_STEPS, RETRIAL_STEPS)
    }
}

impl Tuner {
    /// A tuner timing `trial` steps in each mode, again after `every` steps.
    pub fn new(trial: usize, every: u64) -> Tuner {
        Tuner {
            mode: Mode::TryShared,
            times: Vec::with_capacity(trial.max(1)),
            trial: trial.max(1),
            every,
        }
    }

    /// Should the next step keep its stages on one thread?
    pub fn alone(&self) -> bool {
        match self.mode {
            Mode::TryShared => false,
            Mode::TryAlone(_) => true,
            Mode::Chosen(alone, _) => alone,
        }
    }

    /// The choice made by the last trial, if one is complete (`true`: one thread).
    #[cfg(test)]
    pub fn chosen(&self) -> Option<bool> {
        match self.mode {
            Mode::Chosen(alone, _) => Some(alone),
            _ => None,
        }
    }

    /// Record the wall time (s) of the step just run in the mode [`Tuner::alone`] gave.
    pub fn record(&mut self, seconds: f64) {
        match self.mode {
            Mode::TryShared | Mode::TryAlone(_) => {
                self.times.push(seconds);
                if self.times.len() < self.trial {
                    return;
                }
                let median = median(&mut self.times);
                self.times.clear();
                self.mode = match self.mode {
                    Mode::TryShared => Mode::TryAlone(median),
                    Mode::TryAlone(shared) => Mode::Chosen(median < shared, self.every),
                    chosen => chosen,
                };
            }
            Mode::Chosen(alone, left) => {
                self.mode = if left <= 1 {
                    Mode::TryShared
                } else {
                    Mode::Chosen(alone, left - 1)
                };
            }
        }
    }
}

/// The median of `v` (reordered; the upper middle for an even count), 0 for none.
fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let mid = v.len() / 2;
    *v.select_nth_unstable_by(mid, f64::total_cmp).1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Run `steps` steps, each taking `shared` or `alone` seconds by the tuner's mode; the
    /// modes used in order.
    fn drive(t: &mut Tuner, steps: usize, shared: f64, alone: f64) -> Vec<bool> {
        (0..steps)
            .map(|_| {
                let a = t.alone();
                t.record(if a { alone } else { shared });
                a
            })
            .collect()
    }

    #[test]
    fn the_faster_mode_is_kept_until_the_next_trial() {
        let mut t = Tuner::new(3, 10);
        let modes = drive(&mut t, 6, 2e-5, 1e-5);
        assert_eq!(modes, [false, false, false, true, true, true]);
        assert_eq!(t.chosen(), Some(true));
        // ten steps alone, then a new trial starting shared
        let modes = drive(&mut t, 11, 2e-5, 1e-5);
        assert_eq!(modes[..10], [true; 10]);
        assert!(!modes[10]);
        assert_eq!(t.chosen(), None);
    }

    #[test]
    fn a_scene_that_gains_from_threads_stays_shared() {
        let mut t = Tuner::new(4, 100);
        drive(&mut t, 8, 1e-5, 1.8e-5);
        assert_eq!(t.chosen(), Some(false));
        assert!(drive(&mut t, 50, 1e-5, 1.8e-5).iter().all(|a| !a));
    }

    #[test]
    fn the_choice_follows_the_median_not_a_slow_output_step() {
        // shared steps take 1e-5 s except one that writes a dump (1e-2 s); alone 1.5e-5 s
        let mut t = Tuner::new(5, 100);
        for k in 0..5 {
            t.record(if k == 2 { 1e-2 } else { 1e-5 });
        }
        for _ in 0..5 {
            t.record(1.5e-5);
        }
        assert_eq!(t.chosen(), Some(false));
    }

    #[test]
    fn median_of_few() {
        assert_eq!(median(&mut []), 0.0);
        assert_eq!(median(&mut [3.0]), 3.0);
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), 3.0);
    }
}
