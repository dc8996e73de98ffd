//! The module dump table against the declarations and LIGGGHTS's names.

use super::*;

#[test]
fn every_module_row_is_declared_once_and_a_liggghts_style() {
    let declared = crate::commands::specs::styles("dump");
    for row in MODULES {
        let name = row.name();
        assert_eq!(row.spec.command, "dump", "{name}");
        assert_eq!(declared.iter().filter(|s| **s == name).count(), 1, "{name}");
        assert!(
            crate::commands::names::DUMP_STYLES.contains(&name)
                || crate::commands::registry::EXTENSION_DUMP_STYLES.contains(&name),
            "{name}"
        );
        assert!(module_row(name).is_some(), "{name}");
    }
}

#[test]
fn every_declared_dump_style_has_a_row() {
    for name in crate::commands::specs::styles("dump") {
        assert!(module_row(name).is_some(), "{name}");
    }
}
