//! `fix check/timestep/gran`: the time step against Rayleigh and Hertz times, checked every
//! N steps (`end_of_step`, warnings to the screen; f_ID[1..3] the fractions).

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, VELOCITY, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::error::EngineError;
use crate::engine::fixes::{CheckTimestep, FixStep, FixStyle, PairInit, StepInputs};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "check/timestep/gran",
    "fix ID GROUP check/timestep/gran N RAYLEIGH_FRACTION HERTZ_FRACTION",
    &[
        kw(
            "warn",
            &[arg("yes|no", YES_NO)],
            "warn when a limit is exceeded",
        ),
        kw(
            "vmax",
            &[arg("V", VELOCITY)],
            "largest expected relative velocity",
        ),
    ],
    "compare the time step with Rayleigh and Hertz times",
);

impl FixStyle for CheckTimestep {
    fn name(&self) -> &str {
        "check/timestep/gran"
    }

    fn init_pair(&mut self, pair: &PairInit) -> Result<(), EngineError> {
        CheckTimestep::init_pair(self, pair)
    }

    fn global_freq(&self) -> i64 {
        self.every
    }

    fn end_of_step(&mut self, p: &mut Particles, at: &FixStep) {
        if at.step % self.every == 0 {
            self.warnings = self.evaluate(p, at.group, at.dt, at.skin, at.mesh_vmax_sqr);
        }
    }

    fn end_of_step_ranks(&mut self, p: &mut Particles, at: &FixStep, min: &dyn Fn(&mut [f64])) {
        if at.step % self.every == 0 {
            self.warnings =
                self.evaluate_over_ranks(p, at.group, at.dt, at.skin, at.mesh_vmax_sqr, min);
        }
    }

    fn outputs_at(&self, _step: i64) -> bool {
        !self.warnings.is_empty()
    }

    fn end_of_step_output(
        &mut self,
        _at: &FixStep,
        _inputs: &mut dyn StepInputs,
        out: &mut dyn FnMut(&str),
    ) -> Result<(), EngineError> {
        for m in self.warnings.drain(..) {
            out(&format!("WARNING: {m}\n"));
        }
        Ok(())
    }

    /// LIGGGHTS flags its global vector extensive.
    fn extensive(&self, index: Option<usize>) -> bool {
        index.is_some()
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        match index {
            Some(i @ 1..=3) => Some(self.values[i - 1]),
            _ => None,
        }
    }
}

/// `fix ID GROUP check/timestep/gran N RAYLEIGH_LIMIT HERTZ_LIMIT [warn yes|no] [error yes|no] [vmax V]`.
pub fn build(a: &Args, _ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    a.count(6..=usize::MAX, "fix ID GROUP check/timestep/gran N RAYLEIGH_LIMIT HERTZ_LIMIT [warn yes|no] [error yes|no] [vmax V]")?;
    let every = a.int(3)?;
    if every <= 0 {
        return Err(a.error(3, "Illegal fix check/timestep/gran command"));
    }
    let mut c = CheckTimestep {
        id: fix.id.to_string(),
        every,
        rayleigh_limit: a.real(4)?,
        hertz_limit: a.real(5)?,
        warn: true,
        error: false,
        vmax_user: 0.0,
        values: [0.0; 3],
        materials: Vec::new(),
        warnings: Vec::new(),
    };
    let mut i = 6;
    while i < a.len() {
        match a.word(i)? {
            "warn" => c.warn = a.word_in(i + 1, &["yes", "no"])? == "yes",
            "error" => c.error = a.word_in(i + 1, &["yes", "no"])? == "yes",
            "vmax" => c.vmax_user = a.real(i + 1)?,
            _ => return Err(a.keyword_error(i, &["warn", "error", "vmax"])),
        }
        i += 2;
    }
    if c.error {
        return Err(a.unsupported(6, "fix check/timestep/gran error yes"));
    }
    Ok(Box::new(c))
}
