//! `fix multicontact/halfspace [geometric_prefactor G]`: the half-space deformation of
//! particles with several contacts, which `pair_style gran ... surface multicontact` reads
//! before every force evaluation (the work is done in the pair loop, see
//! [`crate::engine::granular::multicontact`]).

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::contact::multicontact::DEFAULT_PREFACTOR;
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStyle, PairInit};

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "multicontact/halfspace",
    "fix ID GROUP multicontact/halfspace",
    &[kw(
        "geometric_prefactor",
        &[arg("G", Value::Real(""))],
        "empirical geometry factor gamma of the half-space displacement (default 1.125)",
    )],
    "multiple-contact model (Brodu et al. 2015): each contact's force deforms the particle at its other contacts",
);

/// `fix multicontact/halfspace`: its prefactor and ID.
#[derive(Debug, Clone, PartialEq)]
pub struct MultiContactHalfSpace {
    /// The fix ID (LIGGGHTS's messages name it).
    pub id: String,
    /// `geometric_prefactor` (dimensionless, > 0).
    pub prefactor: f64,
}

impl FixStyle for MultiContactHalfSpace {
    fn name(&self) -> &str {
        "multicontact/halfspace"
    }

    fn multicontact_prefactor(&self) -> Option<f64> {
        Some(self.prefactor)
    }

    fn init_pair(&mut self, pair: &PairInit) -> Result<(), EngineError> {
        let fail = |m: &str| -> EngineError {
            format!("Fix multicontact/halfspace (id {}): {m}", self.id).into()
        };
        if pair.pair_surface != Some("multicontact") {
            return Err(fail("Surface model is not multicontact"));
        }
        if pair.wall_surfaces.iter().any(|s| *s != "multicontact") {
            return Err(fail("Surface model of wall is not multicontact"));
        }
        Ok(())
    }
}

/// `fix ID GROUP multicontact/halfspace [geometric_prefactor G]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let fail = |i: usize, m: &str| {
        a.error(
            i,
            format!("Fix multicontact/halfspace (id {}): {m}", fix.id),
        )
    };
    let mut prefactor = DEFAULT_PREFACTOR;
    let mut k = 3;
    while k < a.len() {
        if a.word(k)? != "geometric_prefactor" {
            return Err(fail(
                k,
                &format!("unknown keyword or wrong keyword order: {}", a.word(k)?),
            ));
        }
        if a.len() < k + 2 {
            return Err(fail(
                k,
                "not enough arguments for keyword 'geometric_prefactor'",
            ));
        }
        prefactor = a.real(k + 1)?;
        if prefactor <= 0.0 {
            return Err(fail(k + 1, "geometric_prefactor > 0 required"));
        }
        k += 2;
    }
    if ctx.sim.pair_selection.is_none() {
        return Err(fail(
            0,
            "Please use a granular pair style before using this fix",
        ));
    }
    for name in ["youngsModulus", "poissonsRatio"] {
        if ctx.sim.property(name).is_none() {
            return Err(a.error(
                0,
                format!("Could not locate a fix/property storing value(s) for {name} as requested by multicontact/halfspace."),
            ));
        }
    }
    Ok(Box::new(MultiContactHalfSpace {
        id: fix.id.to_string(),
        prefactor,
    }))
}
