//! `fix property/global`: material and contact constants read by the contact models.

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixStyle;

/// The declared signature.
pub const SPEC: Spec = style("fix", "property/global", "fix ID GROUP property/global NAME scalar|vector|peratomtype|peratomtypepair N VALUES ...", &[], "material properties (youngsModulus, poissonsRatio, coefficientRestitution, coefficientFriction ...)");

/// `fix ID GROUP property/global NAME STYLE VALUES...`.
pub fn build(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    a.count(
        6..=usize::MAX,
        "fix ID GROUP property/global NAME STYLE VALUES...",
    )?;
    let style = a.word_in(
        4,
        &[
            "scalar",
            "vector",
            "peratomtype",
            "atomtype",
            "peratomtypepair",
            "atomtypepair",
            "matrix",
        ],
    )?;
    let first_value = if matches!(style, "peratomtypepair" | "atomtypepair" | "matrix") {
        6
    } else {
        5
    };
    if matches!(style, "peratomtypepair" | "atomtypepair" | "matrix") {
        let n = a.int(5)?;
        if n < 1 {
            return Err(a.error(5, "Illegal fix property/global command"));
        }
        if (a.len() - first_value) as i64 % n != 0 {
            return Err(a.error(
                5,
                "Fix property/global: the number of default values must be a multiple of nCols.",
            ));
        }
    }
    for i in first_value..a.len() {
        a.real(i)?;
    }
    crate::commands::material_check::remember(a, ctx);
    Ok(Box::new(PropertyGlobal))
}

/// `fix property/global`: no phase of its own; the contact models and checks read its
/// values from the fix's arguments.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PropertyGlobal;

impl FixStyle for PropertyGlobal {
    fn name(&self) -> &str {
        "property/global"
    }

    fn array_unsupported(&self) -> bool {
        true
    }
}
