//! Compute styles written as modules: one file per style (or small family of styles) and one
//! row per style name in [`TABLE`]. Adding a compute style is writing its file (its
//! declared signature, its arguments, its state and its
//! [`ComputeStyle`](crate::engine::computes::ComputeStyle) hooks) and adding its row.

mod com;
mod contact_atom;
mod coord_atom;
mod displace;
mod erotate_sphere;
mod gyration;
mod ke;
mod pair_gran_local;
mod pe;
mod pressure;
mod property_atom;
mod property_local;
mod rdf;
mod reduce;
mod slice;
mod stress_atom;
mod temp;
mod tracer_region;
mod wall_gran_local;

use crate::commands::specs::Spec;
use crate::commands::style_table::{StyleRow, StyleTable};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::ComputeStyle;

pub(crate) use coord_atom::type_range;
pub use ke::thermo_kin_eng;
pub use pair_gran_local::pair_history_width;
pub use stress_atom::StressAtom;
pub use temp::thermo_temp;

/// What a style's builder is told about the compute being defined.
#[derive(Debug, Clone, Copy)]
pub struct ComputeDef<'a> {
    /// The compute ID.
    pub id: &'a str,
    /// The group ID as written.
    pub group: &'a str,
    /// The group's bit mask.
    pub bit: u32,
    /// The style name as written.
    pub style: &'a str,
}

/// Builds a module compute style from the `compute` command's arguments (the style is
/// argument 2).
pub type Build = fn(&Args, &mut Ctx, &ComputeDef) -> Result<Box<dyn ComputeStyle>, CommandError>;

/// One row of the module compute styles: the style's declared signature (its name is the
/// spec's style; `check`, `regolith help` and `compat/SUPPORT.md` read it) and its builder.
#[derive(Debug, Clone, Copy)]
pub struct ComputeRow {
    /// The declared signature.
    pub spec: Spec,
    /// Makes the compute's state from the command's arguments.
    pub build: Build,
}

impl StyleRow for ComputeRow {
    fn spec(&self) -> &Spec {
        &self.spec
    }
}

/// The compute styles: one file each in this folder, one row here. The `compute` command
/// looks a style up here (rows registered at run time included).
pub static TABLE: StyleTable<ComputeRow> = StyleTable::new(&[
    ComputeRow {
        spec: com::SPEC,
        build: com::build,
    },
    ComputeRow {
        spec: contact_atom::SPEC,
        build: contact_atom::build,
    },
    ComputeRow {
        spec: coord_atom::SPEC,
        build: coord_atom::build,
    },
    ComputeRow {
        spec: displace::ATOM,
        build: displace::atom,
    },
    ComputeRow {
        spec: displace::MSD,
        build: displace::msd,
    },
    ComputeRow {
        spec: erotate_sphere::EROTATE,
        build: erotate_sphere::erotate,
    },
    ComputeRow {
        spec: erotate_sphere::SPHERE,
        build: erotate_sphere::sphere,
    },
    ComputeRow {
        spec: erotate_sphere::ATOM,
        build: erotate_sphere::atom,
    },
    ComputeRow {
        spec: gyration::SPEC,
        build: gyration::build,
    },
    ComputeRow {
        spec: ke::SPEC,
        build: ke::build,
    },
    ComputeRow {
        spec: ke::ATOM,
        build: ke::atom,
    },
    ComputeRow {
        spec: pair_gran_local::SPEC,
        build: pair_gran_local::build,
    },
    ComputeRow {
        spec: pe::SPEC,
        build: pe::build,
    },
    ComputeRow {
        spec: pe::ATOM,
        build: pe::atom,
    },
    ComputeRow {
        spec: pressure::SPEC,
        build: pressure::build,
    },
    ComputeRow {
        spec: property_atom::SPEC,
        build: property_atom::build,
    },
    ComputeRow {
        spec: property_local::SPEC,
        build: property_local::build,
    },
    ComputeRow {
        spec: rdf::SPEC,
        build: rdf::build,
    },
    ComputeRow {
        spec: reduce::REGION,
        build: reduce::region,
    },
    ComputeRow {
        spec: reduce::SPEC,
        build: reduce::build,
    },
    ComputeRow {
        spec: slice::SPEC,
        build: slice::build,
    },
    ComputeRow {
        spec: stress_atom::SPEC,
        build: stress_atom::build,
    },
    ComputeRow {
        spec: temp::SPEC,
        build: temp::build,
    },
    ComputeRow {
        spec: tracer_region::SPEC,
        build: tracer_region::build,
    },
    ComputeRow {
        spec: wall_gran_local::SPEC,
        build: wall_gran_local::build,
    },
]);

/// LIGGGHTS's check of a style that takes no arguments after its name.
pub(crate) fn no_arguments(a: &Args, style: &str) -> Result<(), CommandError> {
    if a.len() > 3 {
        return Err(a.error(3, format!("Illegal compute {style} command")));
    }
    Ok(())
}

/// The first word after LIGGGHTS's general compute keyword `update_on_run_end yes|no`.
pub fn after_general_keyword(a: &Args, style: &str) -> Result<usize, CommandError> {
    if a.len() < 4 || a.word(3)? != "update_on_run_end" {
        return Ok(3);
    }
    if a.len() < 5 {
        return Err(a.error(3, "Not enough arguments for keyword 'update_on_run_end'"));
    }
    match a.word(4)? {
        "no" => Ok(5),
        "yes" => Err(a.unsupported(4, &format!("compute {style} update_on_run_end yes"))),
        _ => Err(a.error(
            4,
            "Value for keyword 'update_on_run_end' must be either 'yes' or 'no'",
        )),
    }
}
