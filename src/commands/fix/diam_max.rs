//! `fix diam/max`: the largest particle diameter of the deck's first particle distribution,
//! as `f_ID` (LIGGGHTS reads it where the fix is defined and again at every run's init).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixInit, FixStyle, PairInit};
use crate::engine::global_values::zero_freq;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "diam/max",
    "fix ID GROUP diam/max",
    &[],
    "f_ID: twice the largest bounding radius of the first particledistribution/discrete fix (length; 0 without one)",
);

/// `fix diam/max`: the largest bounding radius it last read (length).
#[derive(Debug, Clone, PartialEq)]
pub struct DiamMax {
    /// The fix's ID.
    id: String,
    /// The first distribution's largest bounding radius (length).
    bound: f64,
}

impl FixStyle for DiamMax {
    fn name(&self) -> &str {
        "diam/max"
    }

    /// LIGGGHTS leaves the output interval at 0: the value is read between runs only.
    fn global_freq(&self) -> i64 {
        0
    }

    /// Thermo reading the fix crashes LIGGGHTS 3.8.0 at the run's init (its interval is 0).
    fn init_pair(&mut self, pair: &PairInit) -> Result<(), EngineError> {
        let key = format!("f_{}", self.id);
        let read = |k: &&str| {
            k.strip_prefix(key.as_str())
                .is_some_and(|r| r.is_empty() || r.starts_with('['))
        };
        if pair.thermo_keywords.iter().any(read) {
            return Err(zero_freq(&self.id));
        }
        Ok(())
    }

    fn init(&mut self, run: &FixInit) -> Result<(), EngineError> {
        self.bound = run.first_distribution_bound;
        Ok(())
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        index.is_none().then_some(2.0 * self.bound)
    }
}

/// `fix ID GROUP diam/max`: LIGGGHTS's constructor reads no arguments (extra words are
/// ignored, as there).
pub fn build(_a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    Ok(Box::new(DiamMax {
        id: fix.id.to_string(),
        bound: crate::engine::fixes::first_distribution_bound(&ctx.sim.fixes),
    }))
}
