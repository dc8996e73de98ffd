//! Liquid bridges (`cohesion easo/capillary/viscous`) in check mode: what is not run yet is
//! reported as unsupported, by name, and nothing else is.

use regolith::engine::wet::{EASO, LOCAL, PERIODIC};

/// The unsupported diagnostics of checking `deck`.
fn unsupported(deck: &str) -> Vec<String> {
    let source = regolith::script::interp::Source::from_text("in.test", deck, false);
    regolith::session::check_deck(source, &Default::default())
        .into_iter()
        .filter(|d| d.severity == regolith::error::Severity::Unsupported)
        .map(|d| d.message.clone())
        .collect()
}

#[test]
fn periodic_boxes_and_local_contacts_are_not_supported_yet_with_bridges() {
    let deck = |boundary: &str, extra: &str| {
        format!(
            "atom_style granular\nboundary {boundary}\nregion r block 0 0.01 0 0.01 0 0.01\n\
             create_box 1 r\ncommunicate single vel yes\nnewton off\n\
             create_atoms 1 single 0.005 0.005 0.005 units box\n\
             set atom 1 diameter 0.001 density 2500\n\
             fix m1 all property/global youngsModulus peratomtype 5e6\n\
             fix m2 all property/global poissonsRatio peratomtype 0.3\n\
             fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
             fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
             fix w1 all property/global surfaceLiquidContentInitial scalar 0.05\n\
             fix w2 all property/global surfaceTension scalar 0.072\n\
             fix w3 all property/global fluidViscosity scalar 0.01\n\
             fix w4 all property/global contactAngle peratomtype 20\n\
             fix w5 all property/global minSeparationDistanceRatio scalar 1.01\n\
             fix w6 all property/global maxSeparationDistanceRatio scalar 1.1\n\
             pair_style gran model hertz tangential history cohesion {EASO}\n\
             pair_coeff * *\n{extra}run 0\n"
        )
    };
    assert!(unsupported(&deck("f f f", "")).is_empty());
    let periodic = unsupported(&deck("p f f", ""));
    assert!(
        periodic.iter().any(|m| m.starts_with(PERIODIC)),
        "{periodic:?}"
    );
    let local = unsupported(&deck("f f f", "compute c all pair/gran/local id force\n"));
    assert!(local.iter().any(|m| m.starts_with(LOCAL)), "{local:?}");
}
