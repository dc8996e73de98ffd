//! The one table mechanism of the styles written as modules (fix, compute and dump styles):
//! the rows compiled in, the rows registered while the program runs, and the lookup of a
//! style's row by its name. Each kind of style keeps only its row type and its rows.

use crate::commands::registry;
use crate::commands::specs::Spec;
use crate::commands::{Args, CommandError};
use std::sync::RwLock;

/// A row of a style table: the style's declared signature (its name is the spec's style;
/// `check`, `regolith help` and `compat/SUPPORT.md` read it) and what builds the style.
pub trait StyleRow: Copy + Send + Sync + 'static {
    /// The declared signature.
    fn spec(&self) -> &Spec;

    /// The style name the row defines.
    fn name(&self) -> &'static str {
        self.spec().style.unwrap_or("")
    }
}

/// The styles of one styled command: one row per style name compiled in, and the rows
/// [`StyleTable::register`]ed while the program runs (styles defined outside the crate).
pub struct StyleTable<R: 'static> {
    modules: &'static [R],
    registered: RwLock<Vec<R>>,
}

impl<R: StyleRow> StyleTable<R> {
    /// A table of the rows compiled in (none registered yet).
    pub const fn new(modules: &'static [R]) -> Self {
        StyleTable {
            modules,
            registered: RwLock::new(Vec::new()),
        }
    }

    /// The rows compiled in, in table order (the order `regolith help` lists them).
    pub fn modules(&self) -> &'static [R] {
        self.modules
    }

    /// The declared signatures of the rows compiled in, in table order.
    pub fn specs(&self) -> impl Iterator<Item = &'static Spec> {
        self.modules.iter().map(StyleRow::spec)
    }

    /// Add a style at run time: its command runs it from then on (a row compiled in needs no
    /// registration). A row naming a style already registered replaces it.
    pub fn register(&self, row: R) {
        let mut rows = self.registered.write().unwrap_or_else(|e| e.into_inner());
        rows.retain(|r| r.name() != row.name());
        rows.push(row);
    }

    /// The row of `style`: one compiled in, else a registered one.
    pub fn row(&self, style: &str) -> Option<R> {
        if let Some(row) = self.modules.iter().find(|r| r.name() == style) {
            return Some(*row);
        }
        let rows = self.registered.read().unwrap_or_else(|e| e.into_inner());
        rows.iter().find(|r| r.name() == style).copied()
    }

    /// Whether `style` was added with [`StyleTable::register`] (its name need not be one
    /// LIGGGHTS knows).
    pub fn is_registered(&self, style: &str) -> bool {
        let rows = self.registered.read().unwrap_or_else(|e| e.into_inner());
        rows.iter().any(|r| r.name() == style)
    }

    /// The row of the style `command` names at argument 2 (`compute ID GROUP STYLE`), else
    /// the "not supported yet" report at the style word.
    pub fn row_for(&self, a: &Args, command: &str) -> Result<R, CommandError> {
        let style = a.word(2)?;
        if let Some(row) = self.row(style) {
            return Ok(row);
        }
        registry::require_style(a, command)?;
        Err(a.unsupported(2, &format!("{command} {style}")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::{compute, dump, fix, names, specs};

    /// Every row of `table` is a style of `command` declared once, named as LIGGGHTS (or
    /// `extensions`) names it, and found by its name; with `complete`, every declared style
    /// of `command` has a row.
    fn rows_agree<R: StyleRow>(
        table: &StyleTable<R>,
        command: &str,
        liggghts: &[&str],
        extensions: &[&str],
        complete: bool,
    ) {
        let declared = specs::styles(command);
        for row in table.modules() {
            let name = row.name();
            assert_eq!(row.spec().command, command, "{name}");
            assert_eq!(declared.iter().filter(|s| **s == name).count(), 1, "{name}");
            // LIGGGHTS builds mesh/surface/stress[/servo] from mesh/surface's modules
            let module = command == "fix" && name.starts_with("mesh/surface/stress");
            assert!(
                liggghts.contains(&name) || extensions.contains(&name) || module,
                "{command} {name}"
            );
            assert!(table.row(name).is_some(), "{name}");
            assert!(!table.is_registered(name), "{name}");
        }
        if complete {
            for name in declared {
                assert!(table.row(name).is_some(), "{command} {name}");
            }
        }
    }

    #[test]
    fn every_row_is_declared_once_and_a_liggghts_style() {
        let fixes = registry::EXTENSION_FIX_STYLES;
        rows_agree(&fix::TABLE, "fix", names::FIX_STYLES, fixes, false);
        rows_agree(&compute::TABLE, "compute", names::COMPUTE_STYLES, &[], true);
        let extensions = registry::EXTENSION_DUMP_STYLES;
        rows_agree(&dump::TABLE, "dump", names::DUMP_STYLES, extensions, true);
    }
}
