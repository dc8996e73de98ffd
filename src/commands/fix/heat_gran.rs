//! `fix heat/gran` and `fix heat/gran/conduction` (one style in LIGGGHTS 3.8.0): heat
//! conduction between touching particles, with the per-atom properties it creates.

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Keyword, Spec, Value, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixStyle;
use crate::engine::heat::{self, ContactArea, HeatGran};

/// The keywords both names take.
const KEYWORDS: &[Keyword] = &[
    kw(
        "contact_area",
        &[arg("overlap|projection|constant A", Value::Word)],
        "conduction area: the spheres' intersection, the larger sphere's cross-section, or A (length^2)",
    ),
    kw(
        "area_correction",
        &[arg("yes|no", YES_NO)],
        "scale overlaps by the Young's moduli over youngsModulusOriginal before the area is taken",
    ),
    kw(
        "store_contact_data",
        &[arg("yes|no", YES_NO)],
        "per-particle mean contact area and contact count (contactAreaConduction, nContactsConduction)",
    ),
];

/// The declared signature of `heat/gran`.
pub const SPEC: Spec = style(
    "fix",
    "heat/gran",
    "fix ID GROUP heat/gran initial_temperature T0",
    KEYWORDS,
    "heat conduction between touching particles: per-particle Temp (K), heatFlux and heatSource (W), thermalConductivity and thermalCapacity per type from fix property/global; f_ID is the thermal energy (J)",
);

/// The declared signature of `heat/gran/conduction`.
pub const CONDUCTION: Spec = style(
    "fix",
    "heat/gran/conduction",
    "fix ID GROUP heat/gran/conduction initial_temperature T0",
    KEYWORDS,
    "the same as heat/gran",
);

/// `fix ID GROUP heat/gran[/conduction] initial_temperature T0 [contact_area overlap|
/// projection|constant A] [area_correction yes|no] [store_contact_data yes|no]` (T0 in K,
/// A in length^2).
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let fail = |i: usize, m: &str| a.error(i, format!("Fix {} (id {}): {m}", fix.style, fix.id));
    if a.len() < 5 {
        return Err(fail(a.len() - 1, "not enough arguments")
            .with_help("fix ID GROUP heat/gran initial_temperature T0"));
    }
    if a.word(3)? != "initial_temperature" {
        return Err(fail(3, "expecting keyword 'initial_temperature'"));
    }
    let t0 = heat::initial_temperature(crate::util::numbers::c_atof(a.word(4)?));
    let mut area = ContactArea::Overlap;
    let (mut area_correction, mut store) = (false, false);
    let mut i = 5;
    while i < a.len() {
        match a.word(i)? {
            "contact_area" => {
                match a.word(i + 1).unwrap_or("") {
                    "overlap" => area = ContactArea::Overlap,
                    "projection" => area = ContactArea::Projection,
                    "constant" => {
                        if i + 3 > a.len() {
                            return Err(fail(
                                i,
                                "not enough arguments for keyword 'contact_area constant'",
                            ));
                        }
                        let value = a.real(i + 2)?;
                        if value <= 0.0 {
                            return Err(fail(i + 2, "'contact_area constant' value must be > 0"));
                        }
                        area = ContactArea::Constant(value);
                        i += 1;
                    }
                    _ => {
                        return Err(fail(
                            i + 1,
                            "expecting 'overlap', 'projection' or 'constant' after 'contact_area'",
                        ))
                    }
                }
                i += 2;
            }
            w @ ("area_correction" | "store_contact_data") => {
                if i + 2 > a.len() {
                    return Err(fail(i, &format!("not enough arguments for keyword '{w}'")));
                }
                let yes = match a.word(i + 1)? {
                    "no" => false,
                    "yes" => true,
                    _ => return Err(fail(i + 1, &format!("expecting 'yes' or 'no' after '{w}'"))),
                };
                if w == "area_correction" {
                    area_correction = yes;
                } else {
                    store = yes;
                }
                i += 2;
            }
            // heat/gran stops reading at the first word it does not know
            _ if fix.style == "heat/gran" => break,
            _ => return Err(fail(i, "unknown keyword")),
        }
    }
    if area_correction && area != ContactArea::Overlap {
        return Err(fail(
            2,
            "can use 'area_correction' only for 'contact_area = overlap'",
        ));
    }
    let mut lines = Vec::new();
    let directional =
        super::property_atom::ensure(ctx, heat::DIRECTIONAL, &[0.0; 3], false, &mut lines);
    let temp = super::property_atom::ensure(ctx, heat::TEMP, &[t0], true, &mut lines);
    let flux = super::property_atom::ensure(ctx, heat::HEAT_FLUX, &[0.0], true, &mut lines);
    let source = super::property_atom::ensure(ctx, heat::HEAT_SOURCE, &[0.0], true, &mut lines);
    let contact_data = store.then(|| {
        [
            "contactAreaConduction",
            "nContactsConduction",
            "wallHeattransferCoeff",
            "wallTemp",
        ]
        .map(|name| super::property_atom::ensure(ctx, name, &[0.0], false, &mut lines))
    });
    for line in lines {
        ctx.say(&format!("{line}\n"));
    }
    Ok(Box::new(HeatGran {
        style: fix.style.to_string(),
        t0,
        area,
        conductivity: Vec::new(),
        capacity: Vec::new(),
        arrays: [temp, flux, source, directional],
        area_correction,
        overlap_ratio: Vec::new(),
        contact_data,
    }))
}
