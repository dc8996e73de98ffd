//! `group ID variable NAME` (atoms where an atom-style variable is non-zero join the group)
//! and `group ID initialize` (the group is made, empty, if it does not exist), as LIGGGHTS
//! 3.8.0 does them.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::lang::system::Mode;
use crate::lang::variables::Style;

/// The atoms an atom-style variable selects (non-zero values, NaN included, as C compares);
/// None in a dry run that cannot evaluate the variable.
pub fn selected(a: &Args, ctx: &mut Ctx) -> Result<Option<Vec<bool>>, CommandError> {
    let name = a.word(2).map_err(|_| {
        a.error(1, "Illegal group command")
            .with_help("group ID variable NAME (an atom-style variable)")
    })?;
    match ctx.vars.get(name).map(|v| v.style) {
        None => return Err(a.error(2, "Variable name for group does not exist")),
        Some(Style::Atom | Style::AtomFile) => {}
        Some(_) => {
            return Err(a
                .error(2, "Variable for group is invalid style")
                .with_help("group ID variable needs an atom-style variable"))
        }
    }
    let check = ctx.sys.mode == Mode::Check;
    let mut scope = crate::lang::scope::Scope::new(ctx.vars, ctx.sys, ctx.sim);
    match scope.atom_variable(name) {
        Ok(values) => Ok(Some(values.iter().map(|&v| v != 0.0).collect())),
        Err(e) if check || e.is_known_when_run() => Ok(None),
        Err(e) => Err(a.error(2, e.to_string())),
    }
}

/// `group ID initialize` takes no further arguments.
pub fn initialize(a: &Args) -> Result<(), CommandError> {
    if a.len() != 2 {
        return Err(a
            .error(2, "Illegal group command")
            .with_help("group ID initialize"));
    }
    Ok(())
}
