//! LIGGGHTS 3.8.0's contact-model whitelist: the model combinations its build compiles
//! into optimised code. Any other combination runs LIGGGHTS's generic model, which says so
//! with a warning when the pair style or wall is created (contact_models.h).

use super::ModelSelection;

/// The combinations Debian's LIGGGHTS 3.8.0 build has optimised, as `[model, tangential,
/// cohesion, rolling_friction, surface]` (measured: every other combination of the models
/// regolith names prints [`WARNING`]; `surface superquadric` needs superquadric particles
/// and was not measured).
const WHITELIST: &[[&str; 5]] = &[
    ["edinburgh", "no_history", "off", "off", "default"],
    ["edinburgh/stiffness", "no_history", "off", "off", "default"],
    ["hertz", "history", "off", "cdt", "default"],
    ["hertz", "history", "off", "off", "default"],
    ["hertz", "history", "sjkr", "off", "default"],
    ["hertz", "no_history", "off", "cdt", "default"],
    ["hertz", "no_history", "off", "epsd", "default"],
    ["hertz", "no_history", "off", "off", "default"],
    ["hertz", "no_history", "off", "off", "multicontact"],
    ["hertz", "no_history", "sjkr", "off", "default"],
    ["hertz", "no_history", "sjkr2", "off", "default"],
    ["hertz", "tan_luding", "off", "off", "default"],
    ["hertz/stiffness", "history", "off", "off", "default"],
    ["hertz/stiffness", "no_history", "off", "cdt", "default"],
    ["hertz/stiffness", "no_history", "off", "off", "default"],
    ["hertz/stiffness", "no_history", "sjkr", "off", "default"],
    ["hertz/stiffness", "tan_luding", "off", "off", "default"],
    [
        "hooke",
        "history",
        "easo/capillary/viscous",
        "off",
        "default",
    ],
    ["hooke", "history", "off", "cdt", "default"],
    ["hooke", "history", "off", "cdt", "multicontact"],
    ["hooke", "history", "off", "epsd", "default"],
    ["hooke", "history", "off", "epsd", "multicontact"],
    ["hooke", "history", "off", "epsd2", "default"],
    ["hooke", "history", "off", "epsd3", "default"],
    ["hooke", "history", "off", "luding", "default"],
    ["hooke", "history", "off", "off", "default"],
    ["hooke", "history", "off", "off", "multicontact"],
    ["hooke", "history", "sjkr", "cdt", "default"],
    ["hooke", "history", "sjkr", "epsd", "default"],
    ["hooke", "history", "sjkr", "epsd2", "default"],
    ["hooke", "history", "sjkr", "off", "default"],
    ["hooke", "history", "sjkr", "off", "multicontact"],
    ["hooke", "history", "sjkr2", "cdt", "default"],
    ["hooke", "history", "sjkr2", "epsd", "default"],
    ["hooke", "history", "sjkr2", "off", "default"],
    ["hooke", "history", "sjkr2", "off", "multicontact"],
    [
        "hooke",
        "history",
        "washino/capillary/viscous",
        "off",
        "default",
    ],
    [
        "hooke",
        "no_history",
        "easo/capillary/viscous",
        "off",
        "default",
    ],
    ["hooke", "no_history", "off", "cdt", "default"],
    ["hooke", "no_history", "off", "cdt", "multicontact"],
    ["hooke", "no_history", "off", "epsd", "default"],
    ["hooke", "no_history", "off", "epsd", "multicontact"],
    ["hooke", "no_history", "off", "epsd2", "default"],
    ["hooke", "no_history", "off", "epsd2", "multicontact"],
    ["hooke", "no_history", "off", "epsd3", "default"],
    ["hooke", "no_history", "off", "luding", "default"],
    ["hooke", "no_history", "off", "off", "default"],
    ["hooke", "no_history", "off", "off", "multicontact"],
    ["hooke", "no_history", "sjkr", "cdt", "default"],
    ["hooke", "no_history", "sjkr", "cdt", "multicontact"],
    ["hooke", "no_history", "sjkr", "epsd", "default"],
    ["hooke", "no_history", "sjkr", "epsd2", "default"],
    ["hooke", "no_history", "sjkr", "epsd3", "default"],
    ["hooke", "no_history", "sjkr", "luding", "default"],
    ["hooke", "no_history", "sjkr", "off", "default"],
    ["hooke", "no_history", "sjkr", "off", "multicontact"],
    ["hooke", "no_history", "sjkr2", "cdt", "default"],
    ["hooke", "no_history", "sjkr2", "epsd", "default"],
    ["hooke", "no_history", "sjkr2", "epsd2", "default"],
    ["hooke", "no_history", "sjkr2", "off", "default"],
    ["hooke", "no_history", "sjkr2", "off", "multicontact"],
    [
        "hooke",
        "no_history",
        "washino/capillary/viscous",
        "off",
        "default",
    ],
    ["hooke", "tan_luding", "off", "cdt", "default"],
    ["hooke", "tan_luding", "off", "epsd", "default"],
    ["hooke", "tan_luding", "off", "epsd2", "default"],
    ["hooke", "tan_luding", "off", "epsd3", "default"],
    ["hooke", "tan_luding", "off", "off", "default"],
    ["hooke", "tan_luding", "off", "off", "multicontact"],
    ["hooke", "tan_luding", "sjkr", "cdt", "default"],
    ["hooke", "tan_luding", "sjkr", "off", "default"],
    ["hooke", "tan_luding", "sjkr2", "off", "default"],
    ["hooke/hysteresis", "history", "off", "cdt", "default"],
    ["hooke/hysteresis", "history", "off", "epsd", "default"],
    ["hooke/hysteresis", "history", "off", "off", "default"],
    ["hooke/hysteresis", "history", "off", "off", "multicontact"],
    ["hooke/hysteresis", "history", "sjkr", "off", "default"],
    ["hooke/hysteresis", "history", "sjkr2", "off", "default"],
    ["hooke/hysteresis", "no_history", "off", "cdt", "default"],
    ["hooke/hysteresis", "no_history", "off", "epsd", "default"],
    ["hooke/hysteresis", "no_history", "off", "epsd2", "default"],
    ["hooke/hysteresis", "no_history", "off", "off", "default"],
    [
        "hooke/hysteresis",
        "no_history",
        "off",
        "off",
        "multicontact",
    ],
    ["hooke/hysteresis", "no_history", "sjkr", "cdt", "default"],
    ["hooke/hysteresis", "no_history", "sjkr", "off", "default"],
    ["hooke/hysteresis", "no_history", "sjkr2", "off", "default"],
    ["hooke/hysteresis", "tan_luding", "off", "off", "default"],
    ["hooke/stiffness", "history", "off", "cdt", "default"],
    ["hooke/stiffness", "history", "off", "epsd", "default"],
    ["hooke/stiffness", "history", "off", "epsd2", "default"],
    ["hooke/stiffness", "history", "off", "off", "default"],
    ["hooke/stiffness", "history", "off", "off", "multicontact"],
    ["hooke/stiffness", "history", "sjkr", "cdt", "default"],
    ["hooke/stiffness", "history", "sjkr", "off", "default"],
    ["hooke/stiffness", "history", "sjkr2", "off", "default"],
    ["hooke/stiffness", "no_history", "off", "cdt", "default"],
    [
        "hooke/stiffness",
        "no_history",
        "off",
        "cdt",
        "multicontact",
    ],
    ["hooke/stiffness", "no_history", "off", "epsd", "default"],
    ["hooke/stiffness", "no_history", "off", "epsd2", "default"],
    ["hooke/stiffness", "no_history", "off", "epsd3", "default"],
    ["hooke/stiffness", "no_history", "off", "luding", "default"],
    ["hooke/stiffness", "no_history", "off", "off", "default"],
    [
        "hooke/stiffness",
        "no_history",
        "off",
        "off",
        "multicontact",
    ],
    ["hooke/stiffness", "no_history", "sjkr", "cdt", "default"],
    ["hooke/stiffness", "no_history", "sjkr", "epsd", "default"],
    ["hooke/stiffness", "no_history", "sjkr", "off", "default"],
    [
        "hooke/stiffness",
        "no_history",
        "sjkr",
        "off",
        "multicontact",
    ],
    ["hooke/stiffness", "no_history", "sjkr2", "cdt", "default"],
    ["hooke/stiffness", "no_history", "sjkr2", "off", "default"],
    ["hooke/stiffness", "tan_luding", "off", "cdt", "default"],
    ["hooke/stiffness", "tan_luding", "off", "off", "default"],
    ["hooke/stiffness", "tan_luding", "sjkr", "off", "default"],
    ["luding", "no_history", "off", "off", "default"],
    ["thornton_ning", "history", "off", "off", "default"],
    ["thornton_ning", "no_history", "off", "off", "default"],
];

/// LIGGGHTS's warning for a combination outside the whitelist, as it prints it (the
/// message starts and ends with blank lines, then the source location).
pub const WARNING: &str = "WARNING: \n\
\tThe contact model you specified is not located in any whitelist.\n\
\tBecause of this the model will be run in an unoptimized version (increasing runtime by up to 20%).\n\
\tIn order to optimize this model you have the following options:\n\
\t\t(i)  Run the genAutoExamplesWhitelist.sh script in your LIGGGHTS(R) source folder to automatically parse the input script\n\
\t\t(ii) Add the model combination by hand to your style_contact_model_user.whitelist that can be found in your LIGGGHTS(R) source folder\n\
\tIf you perform one of the steps above LIGGGHTS(R) needs to be recompiled to generate the optimized code.\n\
\n (./src/contact_models.h:364)\n";

/// Whether LIGGGHTS 3.8.0 has `sel`'s combination of models optimised (no warning).
pub fn whitelisted(sel: &ModelSelection) -> bool {
    let key = [
        sel.normal.as_str(),
        sel.tangential.as_str(),
        sel.cohesion.as_str(),
        sel.rolling.as_str(),
        sel.surface.as_str(),
    ];
    WHITELIST.contains(&key)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn select(words: &str) -> ModelSelection {
        let w: Vec<&str> = words.split_whitespace().collect();
        ModelSelection::select(&w).unwrap().0
    }

    #[test]
    fn common_combinations_are_whitelisted_and_the_default_tangential_is_not() {
        assert!(whitelisted(&select("model hertz tangential history")));
        assert!(whitelisted(&select(
            "model hertz tangential history rolling_friction cdt"
        )));
        assert!(whitelisted(&select(
            "model hooke tangential history cohesion sjkr2 rolling_friction cdt"
        )));
        assert!(whitelisted(&select(
            "model hertz tangential no_history surface multicontact"
        )));
        // LIGGGHTS 3.8.0's default tangential model is off: not whitelisted
        assert!(!whitelisted(&select("model hertz")));
        assert!(!whitelisted(&select(
            "model hertz tangential history rolling_friction epsd"
        )));
        assert!(!whitelisted(&select(
            "model hertz tangential history surface multicontact"
        )));
        assert_eq!(WHITELIST.len(), 114);
        assert!(WARNING.starts_with("WARNING: \n\tThe contact model"));
        assert!(WARNING.ends_with("code.\n\n (./src/contact_models.h:364)\n"));
    }
}
