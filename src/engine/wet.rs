//! The liquid of `cohesion easo/capillary/viscous` between steps: the model's coefficients
//! read at each run's start, and the per-atom `surfaceLiquidContent`, `liquidFlux` and
//! `liquidSource` the model keeps its liquid in (property/atom fixes of those IDs, created
//! at the first run as LIGGGHTS's `fix transportequation/scalar` creates them).
//!
//! As LIGGGHTS 3.8.0 integrates them: the flux is zeroed at the start of each step, the pair
//! loop adds the liquid of breaking bridges to it, and at the end of the step every
//! particle's content advances by `(flux + source) dt` (no capacity). The setup force
//! evaluation adds to the flux without zeroing it first.

use crate::engine::contact::easo::Easo;
use crate::engine::contact::ModelSelection;
use crate::engine::error::EngineError;
use crate::engine::fixes::{properties_named, Fix, FixKind};
use crate::engine::granular::wet::{WetInput, LIQUID_CONTENT, LIQUID_FLUX, LIQUID_SOURCE};
use crate::engine::heat::PropertyAtom;
use crate::engine::sim::Simulation;

/// The cohesion model's name as decks write it.
pub const EASO: &str = "easo/capillary/viscous";

/// What regolith does not run yet of the wet model (the feature, for "not supported yet").
pub const PERIODIC: &str = "cohesion easo/capillary/viscous across periodic boundaries";

/// What regolith does not run yet of the wet model: its contacts in a local compute.
pub const LOCAL: &str = "compute pair/gran/local with cohesion easo/capillary/viscous";

/// The caller LIGGGHTS names when a property is missing.
const CALLER: &str = "cohesion_model easo/capillary/viscous";

/// `surfaceLiquidContentInitial` as LIGGGHTS hands it on: written with `%e` to the
/// transport equation, which writes it with `%e` again as the default of the content.
pub fn initial_content(value: f64) -> f64 {
    format!("{value:.6e}").parse().unwrap_or(value)
}

/// The pair style's selection as its dry part: cohesion easo/capillary/viscous and surface
/// multicontact (the pair loops' own) taken out.
pub fn dry(sel: &ModelSelection) -> ModelSelection {
    let mut dry = sel.clone();
    if dry.cohesion == EASO {
        dry.cohesion = "off".into();
    }
    if dry.surface == "multicontact" {
        dry.surface = "default".into();
    }
    dry
}

/// Index of the per-atom array `name` (one column), if the particles hold it.
fn array(sim: &Simulation, name: &str) -> Option<usize> {
    sim.particles
        .extra
        .iter()
        .position(|e| e.name == name && e.width == 1)
}

impl Simulation {
    /// The pair style's cohesion is `easo/capillary/viscous`.
    pub(crate) fn pair_is_wet(&self) -> bool {
        self.pair_selection
            .as_ref()
            .is_some_and(|s| s.cohesion == EASO)
    }

    /// The contact distance factor of the pair style (1 without one).
    pub(crate) fn contact_factor(&self) -> f64 {
        self.pair
            .as_ref()
            .map_or(1.0, |p| p.contact_distance_factor())
    }

    /// The wet model's coefficients from the `fix property/global` definitions, with
    /// LIGGGHTS's messages for missing or bad ones.
    pub(crate) fn wet_input(&self) -> Result<WetInput, EngineError> {
        // pairs across periodic faces are seen from both sides there; the wet loop sees one
        if (0..3).any(|d| self.domain.periodic(d)) {
            return Err(format!("{PERIODIC}: not supported yet").into());
        }
        let missing = |name: &str| -> EngineError {
            format!("Could not locate a fix/property storing value(s) for {name} as requested by {CALLER}.").into()
        };
        let scalar = |name: &str| -> Result<f64, EngineError> {
            match self.property(name) {
                Some((style, _, v)) if style == "scalar" && !v.is_empty() => Ok(v[0]),
                _ => Err(missing(name)),
            }
        };
        scalar("surfaceLiquidContentInitial")?;
        let surface_tension = scalar("surfaceTension")?;
        let fluid_viscosity = scalar("fluidViscosity")?;
        let ntypes = self.ntypes as usize;
        let contact_angle = match self.property("contactAngle") {
            Some((style, _, v)) if style == "peratomtype" && v.len() >= ntypes => {
                v[..ntypes].to_vec()
            }
            _ => return Err(missing("contactAngle")),
        };
        let min_separation = scalar("minSeparationDistanceRatio")?;
        let max_separation = scalar("maxSeparationDistanceRatio")?;
        if max_separation < 1.0 {
            return Err("\n\ncohesion model easo/capillary/viscous requires maxSeparationDistanceRatio >= 1.0. Please increase this value.\n".into());
        }
        Ok(WetInput {
            easo: Easo {
                surface_tension,
                fluid_viscosity,
                min_separation,
                max_separation,
                tangential_reduce: false,
            },
            contact_angle,
        })
    }

    /// At each run's start with a wet pair style: the liquid's property/atom fixes and
    /// arrays, created at the first run (content starting at `surfaceLiquidContentInitial`).
    pub(crate) fn init_liquid(&mut self) -> Result<(), EngineError> {
        if !self.pair_is_wet() {
            return Ok(());
        }
        let initial = match self.property("surfaceLiquidContentInitial") {
            Some((_, _, v)) if !v.is_empty() => initial_content(v[0]),
            _ => 0.0,
        };
        for (name, default, restart) in [
            (LIQUID_CONTENT, initial, true),
            (LIQUID_FLUX, 0.0, true),
            (LIQUID_SOURCE, 0.0, true),
        ] {
            let exists = properties_named(&self.fixes, name).next().is_some();
            if exists {
                continue;
            }
            let held = self
                .restart_peratom
                .iter()
                .any(|(i, s)| i == name && s == "property/atom");
            let kept = held && array(self, name).is_some();
            if kept {
                let k = self.particles.extra_index(name, 1);
                self.particles.extra[k].fill = vec![default];
            } else {
                crate::engine::heat::add_property(&mut self.particles, name, &[default]);
            }
            let flag = |b: bool| if b { "yes" } else { "no" };
            let args = vec![
                name.to_string(),
                "scalar".to_string(),
                flag(restart).to_string(),
                flag(name != LIQUID_FLUX).to_string(),
                flag(name == LIQUID_FLUX).to_string(),
                format!("{default:e}"),
            ];
            self.fixes.push(Fix {
                id: name.to_string(),
                style: "property/atom".to_string(),
                group: 1,
                kind: FixKind::Style(Box::new(PropertyAtom {
                    id: name.to_string(),
                    name: name.to_string(),
                    defaults: vec![default],
                    vector: false,
                    restart,
                    fresh: false,
                })),
                args,
                clock: Default::default(),
            });
        }
        Ok(())
    }

    /// Start of a step: the liquid fluxes back to zero.
    pub(crate) fn liquid_initial_integrate(&mut self) {
        if !self.pair_is_wet() {
            return;
        }
        if let Some(k) = array(self, LIQUID_FLUX) {
            self.particles.extra[k].data.fill(0.0);
        }
    }

    /// End of a step: every particle's content advances by `(flux + source) dt`.
    pub(crate) fn liquid_final_integrate(&mut self) {
        if !self.pair_is_wet() {
            return;
        }
        let (Some(kc), Some(kf), Some(ks)) = (
            array(self, LIQUID_CONTENT),
            array(self, LIQUID_FLUX),
            array(self, LIQUID_SOURCE),
        ) else {
            return;
        };
        let dt = self.dt;
        let p = &mut self.particles;
        let mut content = std::mem::take(&mut p.extra[kc].data);
        let (flux, source) = (&p.extra[kf].data, &p.extra[ks].data);
        for (i, c) in content.iter_mut().enumerate() {
            *c += (flux[i] + source[i] * 1.0) * dt;
        }
        p.extra[kc].data = content;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_initial_content_goes_through_a_print_with_six_decimals() {
        assert_eq!(initial_content(0.05), 0.05);
        assert_eq!(initial_content(0.123456789), 0.1234568);
    }

    #[test]
    fn the_dry_part_of_a_wet_selection_has_no_cohesion() {
        let wet = ModelSelection::parse(&["model", "hertz", "cohesion", EASO]).unwrap();
        assert_eq!(dry(&wet).cohesion, "off");
        let sjkr = ModelSelection::parse(&["model", "hertz", "cohesion", "sjkr"]).unwrap();
        assert_eq!(dry(&sjkr), sjkr);
    }
}
