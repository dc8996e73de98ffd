//! The run's guards: lost atoms, particles that are not finite or jump past their
//! neighbours, deep overlaps and energy runaways, warned about or stopped as the deck's
//! settings say.

use super::*;

/// Overlap, as a fraction of the smaller radius, beyond which the guard warns (the run goes on,
/// as LIGGGHTS's does).
pub const MAX_OVERLAP: f64 = 0.5;

/// How often the energy guard takes a new baseline (steps); every step is compared with it.
pub const ENERGY_WATCH_STEPS: i64 = 10;

/// Kinetic-energy growth against the baseline that, with particles jumping more than their
/// radius per step, means a runaway.
pub const ENERGY_GROWTH: f64 = 1.0e4;

/// Radii per step the fastest particle must cover for an energy growth to count as a runaway.
pub const RUNAWAY_RADII_PER_STEP: f64 = 1.0;

// the cheap motion pass flags half a radius per step: the bounds must not be below it
const _: () = assert!(RUNAWAY_RADII_PER_STEP >= 0.5);

/// Energy `now` against `before` with the fastest particle covering `per_step` radii per
/// step: a runaway when the energy grew more than [`ENERGY_GROWTH`]-fold and
/// `per_step` exceeds [`RUNAWAY_RADII_PER_STEP`]. (A piston or an insertion raises the energy
/// by any factor, but its particles do not jump past their neighbours in one step.)
pub fn energy_runaway(before: f64, now: f64, per_step: f64) -> bool {
    before > 0.0 && now > ENERGY_GROWTH * before && per_step > RUNAWAY_RADII_PER_STEP
}

/// One kind of thing the guards warn about without stopping: its first occurrence, how many
/// steps showed it, and the worst case.
#[derive(Debug, Clone, Default)]
pub(crate) struct GuardNote {
    /// Steps at which it was seen.
    pub steps: u64,
    /// The worst value seen, with its step and atom IDs.
    pub worst: Option<(f64, i64, i64, i64)>,
}

impl GuardNote {
    /// Record `value` at `step` for atoms `a`, `b`; true the first time (warn then).
    fn record(&mut self, value: f64, step: i64, a: i64, b: i64) -> bool {
        self.steps += 1;
        if self.worst.is_none_or(|w| value > w.0) {
            self.worst = Some((value, step, a, b));
        }
        self.steps == 1
    }
}

/// The guards' notes of a run.
#[derive(Debug, Clone, Default)]
pub(crate) struct GuardNotes {
    /// Overlaps beyond [`MAX_OVERLAP`] of the smaller radius.
    pub overlap: GuardNote,
    /// Particles moving more than their radius in one step.
    pub jump: GuardNote,
}

/// Atoms named in a lost-atoms error (the rest are counted).
pub(super) const LOST_NAMED: usize = 10;

/// LIGGGHTS's "Lost atoms: original N current M", followed by each lost atom's ID, position
/// and velocity at `step` (the first [`LOST_NAMED`] of them; LIGGGHTS only counts them).
pub(super) fn lost_atoms_message(
    p: &Particles,
    lost: &[bool],
    remaining: usize,
    step: i64,
) -> String {
    // every digit: an atom just past a face must not print as on it
    let v3 = |a: &[f64; 3]| format!("({}, {}, {})", a[0], a[1], a[2]);
    let gone: Vec<usize> = (0..p.len()).filter(|&i| lost[i]).collect();
    let mut s = format!(
        "Lost atoms: original {} current {} (at step {step}, outside the box along a fixed face or without a finite position:",
        p.len(),
        remaining
    );
    for &i in gone.iter().take(LOST_NAMED) {
        s.push_str(&format!(
            " atom {} at x = {} with v = {};",
            p.id[i],
            v3(&p.x[i]),
            v3(&p.v[i])
        ));
    }
    if gone.len() > LOST_NAMED {
        s.push_str(&format!(" and {} more;", gone.len() - LOST_NAMED));
    }
    s.pop();
    s.push(')');
    s
}

/// A guard's warning: on standard error, so that the screen and log keep LIGGGHTS's lines
/// (a closed standard error is no reason to stop a run).
pub(super) fn guard_say(text: &str) {
    use std::io::Write;
    let _ = std::io::stderr().lock().write_all(text.as_bytes());
}

impl Simulation {
    /// A cheap pass that is true whenever a motion guard could fire: a position, velocity or
    /// spin is not finite (their sum is then not finite; rarely it overflows), or a particle
    /// moves more than half its radius per step (the guards' bounds are one radius, and
    /// [`RUNAWAY_RADII_PER_STEP`] is not below it). Branch-free over blocks, no square roots.
    pub(super) fn motion_flagged(&self) -> bool {
        let p = &self.particles;
        let dt = self.dt.abs();
        let dt2 = dt * dt;
        let n = p.len();
        let (x, v, w, radius) = (&p.x[..n], &p.v[..n], &p.omega[..n], &p.radius[..n]);
        let cheap = |x: &[f64; 3], v: &[f64; 3], w: &[f64; 3], r: f64| {
            let sum = x[0] + x[1] + x[2] + v[0] + v[1] + v[2] + w[0] + w[1] + w[2];
            let v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            !sum.is_finite() | ((r > 0.0) & (v2 * dt2 > 0.25 * r * r))
        };
        const BLOCK: usize = 256;
        let flagged = |b: usize| {
            let (lo, hi) = (b * BLOCK, ((b + 1) * BLOCK).min(n));
            let cols = x[lo..hi].iter().zip(&v[lo..hi]);
            let cols = cols.zip(w[lo..hi].iter().zip(&radius[lo..hi]));
            cols.fold(false, |hit, ((x, v), (w, &r))| hit | cheap(x, v, w, r))
        };
        first_where_in(p.len().div_ceil(BLOCK), BLOCK, flagged).is_some()
    }

    /// Kinetic energy and the fastest particle as (radii per step, index): one pass, on the
    /// engine's threads when there are enough particles.
    pub(super) fn motion_scan(&self) -> (f64, f64, usize) {
        let p = &self.particles;
        let dt = self.dt.abs();
        let one = |i: usize| {
            let v = p.v[i];
            let v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            let per_step = if p.radius[i] > 0.0 {
                v2.sqrt() * dt / p.radius[i]
            } else {
                0.0
            };
            (0.5 * p.mass[i] * v2, per_step, i)
        };
        let join = |a: (f64, f64, usize), b: (f64, f64, usize)| {
            let fastest = if b.1 > a.1 || (b.1 == a.1 && b.2 < a.2) {
                (b.1, b.2)
            } else {
                (a.1, a.2)
            };
            (a.0 + b.0, fastest.0, fastest.1)
        };
        // partial results per chunk, joined in chunk order: the same sum for any thread count
        const CHUNK: usize = 1024;
        let n = p.len();
        let mut parts = vec![(0.0, 0.0, usize::MAX); n.div_ceil(CHUNK)];
        let slots = crate::util::team::Shards::new(&mut parts);
        let parallel = crate::engine::integrate::parallel(n);
        crate::util::team::stage_chunks(n, CHUNK, parallel, |k, r| {
            // SAFETY: each task writes its own slot
            let slot = unsafe { slots.range(k..k + 1) };
            slot[0] = r.map(one).fold((0.0, 0.0, usize::MAX), join);
        });
        parts.into_iter().fold((0.0, 0.0, usize::MAX), join)
    }

    /// The blow-up guard on motion, run after each half-kick (before atoms are wrapped or
    /// lost): a position or velocity that is not finite, or a runaway of the kinetic energy
    /// (see [`energy_runaway`]), stops the run; a particle moving more than its radius in one
    /// step is warned about (once a run, on standard error) and the run goes on. `setup` takes the energy
    /// baseline.
    pub(super) fn guard_motion(&mut self, setup: bool) -> Result<(), EngineError> {
        let quiet = !setup
            && self.energy_watch.is_some()
            && self.step % ENERGY_WATCH_STEPS != 0
            && !self.motion_flagged();
        if quiet {
            // nothing non-finite, nobody near a radius per step: no check below can fire
            return Ok(());
        }
        let p = &self.particles;
        let finite = |i: usize| {
            p.x[i]
                .iter()
                .chain(&p.v[i])
                .chain(&p.omega[i])
                .all(|c| c.is_finite())
        };
        // the first offending particle in order, found on the engine's threads
        if let Some(i) = first_where(p.len(), |i| !finite(i)) {
            return Err(self.non_finite(i).into());
        }
        let (energy, per_step, fastest) = self.motion_scan();
        if !energy.is_finite() {
            // finite velocities whose squares overflow: a state no step can carry on from
            let p = &self.particles;
            let kinetic = |i: usize| {
                let v = p.v[i];
                0.5 * p.mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
            };
            let i = (0..p.len())
                .find(|&i| !kinetic(i).is_finite())
                .or((fastest < p.len()).then_some(fastest))
                .unwrap_or(0);
            return Err(format!(
                "blow-up at step {}: the kinetic energy is not finite (bound: finite); atom {} has v = {:?} and mass {}, and 0.5 m |v|^2 = {}; {}",
                self.step,
                p.id[i],
                p.v[i],
                p.mass[i],
                kinetic(i),
                self.blow_up_cause(i)
            ).into());
        }
        if setup || self.energy_watch.is_none() {
            self.energy_watch = Some((self.step, energy));
            return Ok(());
        }
        let p = &self.particles;
        if let Some((step, e0)) = self.energy_watch {
            if energy_runaway(e0, energy, per_step) {
                return Err(format!(
                    "blow-up at step {}: kinetic energy grew {:.1e}-fold since step {} (bound: {:.0e}-fold \
                     while a particle moves more than {} radius per step) and atom {} moves {} radii per step; \
                     the time step is probably too large for the stiffness (check Young's modulus, or use fix check/timestep/gran)",
                    self.step,
                    energy / e0,
                    step,
                    ENERGY_GROWTH,
                    RUNAWAY_RADII_PER_STEP,
                    p.id[fastest],
                    crate::util::format::g(per_step)
                ).into());
            }
        }
        if self.step % ENERGY_WATCH_STEPS == 0 {
            self.energy_watch = Some((self.step, energy));
        }
        if per_step > 1.0 {
            let id = p.id[fastest];
            if self.guard_notes.jump.record(per_step, self.step, id, id) {
                guard_say(&format!(
                    "WARNING: step {}: atom {} moves {} radii in one time step (|v| dt > r, bound 1): \
                     contacts can be missed; the time step is probably too large for its speed. \
                     The run goes on (said once a run; counted at its end)\n",
                    self.step,
                    id,
                    crate::util::format::g(per_step)
                ));
            }
        }
        Ok(())
    }

    /// The blow-up guard on forces, run after each force evaluation: a force that is not
    /// finite stops the run; two particles overlapping by more than [`MAX_OVERLAP`] of the
    /// smaller radius are warned about (once a run, on standard error) and the run goes on.
    pub(super) fn guard_forces(&mut self) -> Result<(), EngineError> {
        let p = &self.particles;
        // a branch-free block scan first; the particle is looked for only when one is flagged
        const BLOCK: usize = 256;
        let flagged = |b: usize| {
            let block = &p.f[b * BLOCK..((b + 1) * BLOCK).min(p.len())];
            any_not_finite(block.as_flattened())
        };
        if first_where_in(p.len().div_ceil(BLOCK), BLOCK, flagged).is_some() {
            if let Some(i) = first_where(p.len(), |i| !p.f[i].iter().all(|c| c.is_finite())) {
                return Err(self.non_finite(i).into());
            }
        }
        if let Some((ratio, i, j)) = self.pair.as_ref().and_then(|m| m.worst_overlap()) {
            // a particle that insert/stream still carries feels no force; LIGGGHTS can
            // insert one overlapping a particle it had frozen (after reset_timestep)
            let carried = || {
                let (ti, tj) = (p.id[i as usize], p.id[j as usize]);
                self.fixes.iter().any(|f| match f.kind.stream() {
                    Some(sf) => sf
                        .state
                        .as_ref()
                        .is_some_and(|s| s.moving.iter().any(|r| r.id == ti || r.id == tj)),
                    None => false,
                })
            };
            if ratio > MAX_OVERLAP && !carried() {
                let cause = if self.step == self.atime_step {
                    "the particles were created (or read) overlapping"
                } else {
                    "the time step may be too large for the stiffness, or the particles are \
                     driven together harder than their stiffness holds"
                };
                let (a, b) = (p.id[i as usize], p.id[j as usize]);
                if self.guard_notes.overlap.record(ratio, self.step, a, b) {
                    guard_say(&format!(
                        "WARNING: step {}: atoms {a} and {b} overlap by {:.1} % of the smaller radius \
                         (more than {:.0} %); {cause}. The run goes on (said once a run; counted at its end)\n",
                        self.step,
                        ratio * 100.0,
                        MAX_OVERLAP * 100.0
                    ));
                }
            }
        }
        Ok(())
    }

    /// The time-step margin and the composed contact models (see [`crate::engine::margin`])
    /// when they differ from those said last; None when unchanged or when there is nothing
    /// to say.
    pub fn new_margin(&mut self) -> Option<String> {
        let m = self.timestep_margin() + &self.contact_models();
        if m.is_empty() || self.margin_said.as_deref() == Some(m.as_str()) {
            return None;
        }
        self.margin_said = Some(m.clone());
        Some(m)
    }

    /// At a run's end: how often the guards' warnings recurred, and the worst case.
    pub(super) fn guard_summary(&mut self) {
        let notes = std::mem::take(&mut self.guard_notes);
        if let Some((v, step, a, b)) = notes.overlap.worst.filter(|_| notes.overlap.steps > 1) {
            guard_say(&format!(
                "WARNING: overlaps beyond {:.0} % of the smaller radius at {} steps of this run; the largest {:.1} % at step {step} (atoms {a} and {b})\n",
                MAX_OVERLAP * 100.0,
                notes.overlap.steps,
                v * 100.0
            ));
        }
        if let Some((v, step, a, _)) = notes.jump.worst.filter(|_| notes.jump.steps > 1) {
            guard_say(&format!(
                "WARNING: a particle moved more than its radius in one time step at {} steps of this run; the most {} radii at step {step} (atom {a})\n",
                notes.jump.steps,
                crate::util::format::g(v)
            ));
        }
    }

    pub(super) fn non_finite(&self, i: usize) -> String {
        let p = &self.particles;
        format!(
            "blow-up at step {}: atom {} has a non-finite position, velocity, angular velocity or force (x = {:?}, v = {:?}, omega = {:?}, f = {:?}); {}",
            self.step,
            p.id[i],
            p.x[i],
            p.v[i],
            p.omega[i],
            p.f[i],
            self.blow_up_cause(i)
        )
    }

    /// The likeliest cause of atom `i`'s non-finite value, for the blow-up message.
    pub(super) fn blow_up_cause(&self, i: usize) -> String {
        let p = &self.particles;
        let positive = |x: f64| x > 0.0;
        if !positive(p.radius[i]) || !positive(p.mass[i]) {
            return format!(
                "it has radius {} and mass {}: a particle needs a positive radius and mass",
                p.radius[i], p.mass[i]
            );
        }
        // two atoms at one point have no contact normal: their force is 0/0
        let twin = (0..p.len()).find(|&j| {
            j != i && {
                let d = [0, 1, 2].map(|k| p.x[i][k] - p.x[j][k]);
                d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= (1e-12 * p.radius[i]).powi(2)
            }
        });
        if let Some(j) = twin {
            return format!(
                "atoms {} and {} sit at the same position, so their contact has no direction (were they created on top of each other?)",
                p.id[i], p.id[j]
            );
        }
        let finite = |v: &[f64; 3]| v.iter().all(|c| c.is_finite());
        if finite(&p.x[i]) && finite(&p.v[i]) && finite(&p.omega[i]) {
            return "only the force on it is not finite: check the forces fixes add or set (an infinite value or variable?)".into();
        }
        if self.step == self.atime_step {
            // still the run's setup: nothing has been integrated yet
            return "the state the run started from already holds it (check how the atoms were created, read or set)".into();
        }
        "the time step is probably too large for the stiffness (check Young's modulus, or use fix check/timestep/gran)".into()
    }
}

/// True if any value is infinite or not a number: its exponent bits are all set. Integer
/// operations without early exit, so the loop is vectorised.
#[inline]
fn any_not_finite(values: &[f64]) -> bool {
    const EXPONENT: u64 = 0x7ff0_0000_0000_0000;
    values.iter().fold(0u64, |hit, v| {
        hit | u64::from(v.to_bits() & EXPONENT == EXPONENT)
    }) != 0
}

#[cfg(test)]
mod finite_scan_tests {
    use super::any_not_finite;

    #[test]
    fn the_bit_scan_flags_exactly_the_values_that_are_not_finite() {
        let finite = [
            0.0,
            -0.0,
            1.0,
            -3.5e300,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            5e-324,
        ];
        assert!(!any_not_finite(&finite));
        assert!(!any_not_finite(&[]));
        for bad in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN, -f64::NAN] {
            for at in [0, 3, finite.len()] {
                let mut v = finite.to_vec();
                v.insert(at, bad);
                assert!(any_not_finite(&v), "{bad} at {at}");
            }
        }
    }
}
