//! The module compute table against the declarations and LIGGGHTS's names.

use super::*;

#[test]
fn every_module_row_is_declared_once_and_a_liggghts_style() {
    let declared = crate::commands::specs::styles("compute");
    for row in MODULES {
        let name = row.name();
        assert_eq!(row.spec.command, "compute", "{name}");
        assert_eq!(declared.iter().filter(|s| **s == name).count(), 1, "{name}");
        assert!(
            crate::commands::names::COMPUTE_STYLES.contains(&name),
            "{name}"
        );
        assert!(module_row(name).is_some(), "{name}");
    }
}
