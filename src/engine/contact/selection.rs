//! The contact models a deck selects: `model ... tangential ... cohesion ...
//! rolling_friction ... surface ...` with its on/off settings, as LIGGGHTS 3.8.0 reads
//! them, and why a selection is refused.

use super::*;

/// The on/off settings `pair_style gran` and `fix wall/gran` accept after the model names.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelOptions {
    /// `tangential_damping` (default on; normal models).
    pub tangential_damping: bool,
    /// `limitForce` (default off; normal models).
    pub limit_force: bool,
    /// `absolute_damping` (default off; hooke/stiffness).
    pub absolute_damping: bool,
    /// `viscous` (default off; hooke).
    pub viscous: bool,
    /// `ktToKnUser` (default off; hooke).
    pub kt_to_kn: bool,
    /// `tangential_reduce` (default off; sjkr, sjkr2).
    pub tangential_reduce: bool,
    /// `torsionTorque` (default off; cdt, epsd, epsd2, epsd3).
    pub torsion_torque: bool,
    /// The run is 2d (`dimension 2`; not a keyword): epsd/epsd3 inertia factor 1.5.
    pub two_d: bool,
}

impl Default for ModelOptions {
    fn default() -> Self {
        ModelOptions {
            tangential_damping: true,
            limit_force: false,
            absolute_damping: false,
            viscous: false,
            kt_to_kn: false,
            tangential_reduce: false,
            torsion_torque: false,
            two_d: false,
        }
    }
}

/// Why a contact model selection is refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ModelError {
    /// Invalid in LIGGGHTS too; the message is LIGGGHTS's.
    #[error("{0}")]
    Invalid(String),
    /// Valid LIGGGHTS that regolith does not run: the model or setting as the deck names it
    /// (`model luding`, `'heating_normal_hertz on'`).
    #[error("{0} is not supported by regolith")]
    Unsupported(String),
}

/// A parsed `model ... tangential ... cohesion ... rolling_friction ... surface ...`
/// selection with its settings.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelSelection {
    /// Normal model name (`off` if no `model` keyword).
    pub normal: String,
    /// Tangential model name (`off` by default).
    pub tangential: String,
    /// Cohesion model name (`off` by default).
    pub cohesion: String,
    /// Rolling model name (`off` by default).
    pub rolling: String,
    /// Surface model name (`default` by default).
    pub surface: String,
    /// Settings.
    pub options: ModelOptions,
}

pub(super) const NORMAL_NAMES: &[&str] = &[
    "off",
    "hertz",
    "hooke",
    "hertz/stiffness",
    "hooke/stiffness",
    "hooke/hysteresis",
    "edinburgh",
    "edinburgh/stiffness",
    "luding",
    "thornton_ning",
];

pub(super) const TANGENTIAL_NAMES: &[&str] = &[
    "off",
    "no_history",
    "history",
    "tan_luding",
    "history_total_cap",
];

pub(super) const COHESION_NAMES: &[&str] = &[
    "off",
    "sjkr",
    "sjkr2",
    "easo/capillary/viscous",
    "washino/capillary/viscous",
];

pub(super) const ROLLING_NAMES: &[&str] = &["off", "cdt", "epsd", "epsd2", "epsd3", "luding"];

pub(super) const SURFACE_NAMES: &[&str] = &["default", "multicontact", "superquadric"];

/// LIGGGHTS's message for an unknown or empty model selection.
pub(super) const INVALID_MODEL: &str =
    "Invalid model specified (check for typos and enable at least one model)";

impl Default for ModelSelection {
    fn default() -> Self {
        ModelSelection {
            normal: "off".into(),
            tangential: "off".into(),
            cohesion: "off".into(),
            rolling: "off".into(),
            surface: "default".into(),
            options: ModelOptions::default(),
        }
    }
}

impl ModelSelection {
    /// Consume the model keywords at the start of `args` in LIGGGHTS's fixed order
    /// (`model`, `tangential`, `cohesion`, `rolling_friction`, `surface`); returns the
    /// selection and the number of arguments consumed.
    pub fn select(args: &[&str]) -> Result<(ModelSelection, usize), ModelError> {
        let mut sel = ModelSelection::default();
        let mut k = 0;
        let steps: [(&str, &[&str]); 5] = [
            ("model", NORMAL_NAMES),
            ("tangential", TANGENTIAL_NAMES),
            ("cohesion", COHESION_NAMES),
            ("rolling_friction", ROLLING_NAMES),
            ("surface", SURFACE_NAMES),
        ];
        for (i, (kw, names)) in steps.iter().enumerate() {
            if args.len() - k > 1 && args[k] == *kw {
                let name = args[k + 1];
                if !names.contains(&name) {
                    return Err(ModelError::Invalid(INVALID_MODEL.into()));
                }
                let slot = match i {
                    0 => &mut sel.normal,
                    1 => &mut sel.tangential,
                    2 => &mut sel.cohesion,
                    3 => &mut sel.rolling,
                    _ => &mut sel.surface,
                };
                *slot = name.to_string();
                k += 2;
            }
        }
        if sel.normal == "off"
            && sel.tangential == "off"
            && sel.cohesion == "off"
            && sel.rolling == "off"
        {
            return Err(ModelError::Invalid(INVALID_MODEL.into()));
        }
        Ok((sel, k))
    }

    /// The on/off settings the selected sub-models register, with whether regolith
    /// implements the `on` value.
    fn settings(&self) -> Vec<(&'static str, bool)> {
        let mut s = vec![
            ("computeElasticPotential", false),
            ("computeDissipatedEnergy", false),
        ];
        match self.normal.as_str() {
            "hertz" => s.extend([
                ("tangential_damping", true),
                ("limitForce", true),
                ("heating_normal_hertz", false),
                ("heating_tracking", false),
                ("disableNormalWhenBonded", false),
            ]),
            "hooke" => s.extend([
                ("viscous", true),
                ("tangential_damping", true),
                ("limitForce", true),
                ("ktToKnUser", true),
                ("heating_normal_hooke", false),
                ("heating_tracking", false),
                ("disableNormalWhenBonded", false),
            ]),
            // LIGGGHTS registers hooke's settings but its hysteresis force ignores limitForce
            // and ktToKnUser: regolith refuses `on` rather than ignore it
            "hooke/hysteresis" => s.extend([
                ("viscous", true),
                ("tangential_damping", true),
                ("limitForce", false),
                ("ktToKnUser", false),
                ("heating_normal_hooke", false),
                ("heating_tracking", false),
                ("disableNormalWhenBonded", false),
            ]),
            "hertz/stiffness" => s.extend([("tangential_damping", true), ("limitForce", true)]),
            "hooke/stiffness" => s.extend([
                ("tangential_damping", true),
                ("absolute_damping", true),
                ("limitForce", true),
            ]),
            _ => {}
        }
        match self.tangential.as_str() {
            "no_history" => s.push(("disableTangentialWhenBonded", false)),
            "history" | "history_total_cap" => s.extend([
                ("heating_tangential_history", false),
                ("heating_tracking", false),
            ]),
            _ => {}
        }
        if matches!(
            self.cohesion.as_str(),
            "sjkr" | "sjkr2" | "easo/capillary/viscous"
        ) {
            s.push(("tangential_reduce", true));
        }
        if matches!(self.rolling.as_str(), "cdt" | "epsd" | "epsd2" | "epsd3") {
            s.push(("torsionTorque", true));
        }
        s
    }

    /// Apply `keyword on|off` settings (any order), with LIGGGHTS's messages for unknown
    /// keywords and values; `on` for an energy/heating/bond option regolith lacks is
    /// [`ModelError::Unsupported`] (the other settings still apply).
    pub fn apply_settings(&mut self, args: &[&str]) -> Result<(), ModelError> {
        let known = self.settings();
        let mut unsupported: Option<&str> = None;
        let mut k = 0;
        while k < args.len() {
            let kw = args[k];
            let Some(&(_, supported)) = known.iter().find(|(n, _)| *n == kw) else {
                return Err(ModelError::Invalid(format!(
                    "Unknown argument or wrong keyword order: '{kw}'"
                )));
            };
            let val = args.get(k + 1).copied().unwrap_or("");
            let on = match val {
                "on" => true,
                "off" => false,
                _ => {
                    return Err(ModelError::Invalid(format!(
                    "while parsing '{kw}' argument: unknown option or wrong keyword order: '{val}'"
                )))
                }
            };
            if on && !supported {
                // the rest still applies: the caller reports this one as unsupported
                unsupported.get_or_insert(kw);
                k += 2;
                continue;
            }
            let o = &mut self.options;
            match kw {
                "tangential_damping" => o.tangential_damping = on,
                "limitForce" => o.limit_force = on,
                "absolute_damping" => o.absolute_damping = on,
                "viscous" => o.viscous = on,
                "ktToKnUser" => o.kt_to_kn = on,
                "tangential_reduce" => o.tangential_reduce = on,
                "torsionTorque" => o.torsion_torque = on,
                _ => {}
            }
            k += 2;
        }
        match unsupported {
            Some(kw) => Err(ModelError::Unsupported(format!("'{kw} on'"))),
            None => Ok(()),
        }
    }

    /// Parse a whole `pair_style gran` argument list (after `gran`): model keywords, then
    /// settings.
    pub fn parse(args: &[&str]) -> Result<ModelSelection, ModelError> {
        let (mut sel, k) = ModelSelection::select(args)?;
        sel.apply_settings(&args[k..])?;
        Ok(sel)
    }

    /// The run-time sub-models of this selection.
    pub fn sub_models(
        &self,
    ) -> Result<(AnyNormal, AnyTangential, AnyCohesion, AnyRolling), ModelError> {
        let o = self.options;
        let unsupported =
            |kind: &str, name: &str| ModelError::Unsupported(format!("{kind} {name}"));
        let normal = match self.normal.as_str() {
            "hertz" => AnyNormal::Hertz(Hertz {
                tangential_damping: o.tangential_damping,
                limit_force: o.limit_force,
            }),
            "hooke" => AnyNormal::Hooke(Hooke {
                tangential_damping: o.tangential_damping,
                limit_force: o.limit_force,
                viscous: o.viscous,
                kt_to_kn: o.kt_to_kn,
            }),
            "hertz/stiffness" => AnyNormal::HertzStiffness(HertzStiffness {
                tangential_damping: o.tangential_damping,
                limit_force: o.limit_force,
            }),
            "hooke/stiffness" => AnyNormal::HookeStiffness(HookeStiffness {
                tangential_damping: o.tangential_damping,
                absolute_damping: o.absolute_damping,
                limit_force: o.limit_force,
            }),
            "hooke/hysteresis" => AnyNormal::HookeHysteresis(HookeHysteresis {
                hooke: Hooke {
                    tangential_damping: o.tangential_damping,
                    limit_force: false,
                    viscous: o.viscous,
                    kt_to_kn: false,
                },
            }),
            n => return Err(unsupported("model", n)),
        };
        let tangential = match self.tangential.as_str() {
            "off" => AnyTangential::Off(NoTangential),
            "no_history" => AnyTangential::NoHistory(NoHistory),
            "history" => AnyTangential::History(History),
            "history_total_cap" => AnyTangential::TotalCap(HistoryTotalCap),
            n => return Err(unsupported("tangential", n)),
        };
        let cohesion = match self.cohesion.as_str() {
            "off" => AnyCohesion::Off(NoCohesion),
            "sjkr" => AnyCohesion::Sjkr(Sjkr {
                tangential_reduce: o.tangential_reduce,
            }),
            "sjkr2" => AnyCohesion::Sjkr2(Sjkr2 {
                tangential_reduce: o.tangential_reduce,
            }),
            n => return Err(unsupported("cohesion", n)),
        };
        let rolling = match self.rolling.as_str() {
            "off" => AnyRolling::Off(NoRolling),
            "cdt" => AnyRolling::Cdt(Cdt {
                torsion_torque: o.torsion_torque,
            }),
            "epsd" => AnyRolling::Epsd(Epsd {
                torsion_torque: o.torsion_torque,
                two_d: o.two_d,
            }),
            "epsd2" => AnyRolling::Epsd2(Epsd2 {
                torsion_torque: o.torsion_torque,
            }),
            "epsd3" => AnyRolling::Epsd3(Epsd3 {
                torsion_torque: o.torsion_torque,
                two_d: o.two_d,
            }),
            n => return Err(unsupported("rolling_friction", n)),
        };
        if self.surface != "default" {
            return Err(unsupported("surface", &self.surface));
        }
        Ok((normal, tangential, cohesion, rolling))
    }
}
