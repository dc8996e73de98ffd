//! Per-type-pair contact coefficients, mixed from the `fix property/global` values the way
//! LIGGGHTS 3.8.0's property registry mixes them (`Yeff`, `Geff`, `betaeff`, ...), with the
//! same sanity checks and error messages, checked in the order LIGGGHTS checks them.
//!
//! A contact model lists the derived quantities it needs ([`Property`], with the caller name
//! LIGGGHTS puts in its messages, e.g. `model hertz`); [`Material::new`] creates each base
//! property the first time one of them asks for it, so a missing or out-of-range value is
//! reported exactly where LIGGGHTS would stop.
//!
//! Extension (regolith only): [`MaterialInput::allow_zero_restitution`] accepts
//! `0 <= coefficientRestitution <= 1` instead of `0.05 < e <= 1`. For `e = 0` the damping
//! ratio takes its limit `betaeff = -1` (critical damping) and `log(e) = -inf`, which the
//! Hooke model maps onto its limit `gamman = sqrt(4 meff kn)`; for `e > 0` nothing changes.

use crate::engine::error::EngineError;
use std::f64::consts::PI;

/// Unit style of the run: LIGGGHTS's limits on Young's modulus and on the characteristic
/// velocity apply only to `si` and `cgs`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum UnitStyle {
    /// `units si` (the default; E in Pa, velocities in m/s).
    #[default]
    Si,
    /// `units cgs` (E in Ba).
    Cgs,
    /// Any other style (no range checks).
    Other,
}

/// The raw `fix property/global` values of a run, by LIGGGHTS name; per-type vectors hold
/// `ntypes` values, per-type-pair tables `ntypes * ntypes` values row-major (type 1 first).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MaterialInput {
    /// Number of atom types (`create_box N`).
    pub ntypes: usize,
    /// Unit style, for the E and characteristic-velocity limits.
    pub units: UnitStyle,
    /// `soft_particles yes`: allow youngsModulus below 5e6 Pa.
    pub soft_particles: bool,
    /// `hard_particles yes`: allow youngsModulus above 1e9 Pa.
    pub hard_particles: bool,
    /// regolith extension: accept coefficientRestitution down to 0 (see the module docs).
    pub allow_zero_restitution: bool,
    /// `youngsModulus peratomtype` (Pa).
    pub youngs_modulus: Option<Vec<f64>>,
    /// `poissonsRatio peratomtype` (dimensionless).
    pub poissons_ratio: Option<Vec<f64>>,
    /// `coefficientRestitution peratomtypepair` (dimensionless).
    pub coefficient_restitution: Option<Vec<f64>>,
    /// `coefficientFriction peratomtypepair` (dimensionless).
    pub coefficient_friction: Option<Vec<f64>>,
    /// `coefficientRollingFriction peratomtypepair` (dimensionless).
    pub coefficient_rolling_friction: Option<Vec<f64>>,
    /// `coefficientRollingViscousDamping peratomtypepair` (dimensionless).
    pub coefficient_rolling_viscous_damping: Option<Vec<f64>>,
    /// `cohesionEnergyDensity peratomtypepair` (J/m^3).
    pub cohesion_energy_density: Option<Vec<f64>>,
    /// `characteristicVelocity scalar` (m/s), for `model hooke`.
    pub characteristic_velocity: Option<f64>,
    /// `rollingStiffness scalar` (dimensionless), for `rolling_friction epsd3`.
    pub rolling_stiffness: Option<f64>,
    /// `kn peratomtypepair` (N/m, or N/m^1.5 for hertz/stiffness).
    pub kn: Option<Vec<f64>>,
    /// `kt peratomtypepair` (N/m, or N/m^1.5 for hertz/stiffness).
    pub kt: Option<Vec<f64>>,
    /// `gamman peratomtypepair` (1/s, multiplied by meff).
    pub gamman: Option<Vec<f64>>,
    /// `gammat peratomtypepair` (1/s, multiplied by meff).
    pub gammat: Option<Vec<f64>>,
    /// `gamman_abs peratomtypepair` (kg/s), for `absolute_damping on`.
    pub gamman_abs: Option<Vec<f64>>,
    /// `gammat_abs peratomtypepair` (kg/s), for `absolute_damping on`.
    pub gammat_abs: Option<Vec<f64>>,
    /// `FluidViscosity peratomtypepair` (Pa s), for `model hooke viscous on`.
    pub fluid_viscosity: Option<Vec<f64>>,
    /// `MaximumRestitution peratomtypepair` (dimensionless), for `viscous on`.
    pub maximum_restitution: Option<Vec<f64>>,
    /// `CriticalStokes peratomtypepair` (dimensionless), for `viscous on`.
    pub critical_stokes: Option<Vec<f64>>,
    /// `coefficientMaxElasticStiffness peratomtypepair` (dimensionless), for hooke/hysteresis.
    pub max_elastic_stiffness: Option<Vec<f64>>,
    /// `coefficientAdhesionStiffness peratomtypepair` (dimensionless), for hooke/hysteresis.
    pub adhesion_stiffness: Option<Vec<f64>>,
    /// `coefficientPlasticityDepth peratomtypepair` (dimensionless), for hooke/hysteresis.
    pub plasticity_depth: Option<Vec<f64>>,
}

/// A derived per-type-pair quantity a sub-model asks for (LIGGGHTS's registry names).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Property {
    /// `Yeff` = 1 / ((1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j) (Pa).
    Yeff,
    /// `Geff` = 1 / (2 (2 - nu_i)(1 + nu_i)/E_i + 2 (2 - nu_j)(1 + nu_j)/E_j) (Pa).
    Geff,
    /// `betaeff` = ln e / sqrt(ln^2 e + pi^2) (dimensionless).
    BetaEff,
    /// `coeffRestLog` = ln e (dimensionless).
    CoeffRestLog,
    /// `charVel`: characteristicVelocity (m/s).
    CharVel,
    /// `coeffFrict`: coefficientFriction.
    CoeffFrict,
    /// `cohEnergyDens`: cohesionEnergyDensity (J/m^3).
    CohEnergyDens,
    /// `coeffRollFrict`: coefficientRollingFriction.
    CoeffRollFrict,
    /// `coeffRollVisc`: coefficientRollingViscousDamping.
    CoeffRollVisc,
    /// `coeffRollStiffness`: rollingStiffness (scalar).
    RollingStiffness,
    /// `k_n`: kn table.
    Kn,
    /// `k_t`: kt table.
    Kt,
    /// `gamman` table.
    Gamman,
    /// `gammat` table.
    Gammat,
    /// `gamman_abs` table.
    GammanAbs,
    /// `gammat_abs` table.
    GammatAbs,
    /// `coeffMu`: FluidViscosity.
    CoeffMu,
    /// `coeffStc`: CriticalStokes.
    CoeffStc,
    /// `coeffRestMax`: MaximumRestitution (stored as its logarithm).
    CoeffRestMax,
    /// `kn2kcMax`: coefficientMaxElasticStiffness (k2Max / kn, dimensionless).
    CoeffMaxElasticStiffness,
    /// `kn2kc`: coefficientAdhesionStiffness (kc / kn, dimensionless).
    CoeffAdhesionStiffness,
    /// `phiF`: coefficientPlasticityDepth (dimensionless).
    CoeffPlasticityDepth,
}

/// Every coefficient of one type pair, in SI units; quantities no selected model asked for
/// stay 0.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairCoeffs {
    /// Effective Young's modulus (Pa).
    pub yeff: f64,
    /// Effective shear modulus (Pa).
    pub geff: f64,
    /// Damping ratio ln e / sqrt(ln^2 e + pi^2) (dimensionless, <= 0).
    pub betaeff: f64,
    /// ln e (dimensionless, <= 0).
    pub coeff_rest_log: f64,
    /// characteristicVelocity (m/s), a run-wide scalar copied into every pair.
    pub char_vel: f64,
    /// Coulomb friction coefficient (dimensionless).
    pub coeff_frict: f64,
    /// Cohesion energy density (J/m^3).
    pub cohesion_energy_density: f64,
    /// Rolling friction coefficient (dimensionless).
    pub coeff_roll_frict: f64,
    /// Rolling viscous damping coefficient (dimensionless).
    pub coeff_roll_visc: f64,
    /// rollingStiffness of epsd3 (dimensionless), a run-wide scalar.
    pub rolling_stiffness: f64,
    /// Normal stiffness kn (N/m; N/m^1.5 for hertz/stiffness).
    pub kn: f64,
    /// Tangential stiffness kt (N/m; N/m^1.5 for hertz/stiffness).
    pub kt: f64,
    /// Relative normal damping gamman (1/s).
    pub gamman: f64,
    /// Relative tangential damping gammat (1/s).
    pub gammat: f64,
    /// Absolute normal damping gamman_abs (kg/s).
    pub gamman_abs: f64,
    /// Absolute tangential damping gammat_abs (kg/s).
    pub gammat_abs: f64,
    /// Fluid viscosity for hooke `viscous on` (Pa s).
    pub fluid_viscosity: f64,
    /// Critical Stokes number for hooke `viscous on` (dimensionless).
    pub critical_stokes: f64,
    /// ln(MaximumRestitution) for hooke `viscous on` (dimensionless).
    pub log_coeff_rest_max: f64,
    /// k2Max / kn of hooke/hysteresis (dimensionless).
    pub kn_to_k2_max: f64,
    /// kc / kn of hooke/hysteresis (dimensionless).
    pub kn_to_kc: f64,
    /// Plasticity depth phiF of hooke/hysteresis (dimensionless).
    pub phi_f: f64,
}

/// Where the sub-models read their coefficients from: one [`PairCoeffs`] (one contact, f64)
/// or [`CoeffLanes`] (one per lane of a batch).
pub trait Coeffs<S: super::real::Real> {
    /// The field `f` picks, per lane.
    fn get<F: Fn(&PairCoeffs) -> f64>(&self, f: F) -> S;
}

impl Coeffs<f64> for PairCoeffs {
    #[inline(always)]
    fn get<F: Fn(&PairCoeffs) -> f64>(&self, f: F) -> f64 {
        f(self)
    }
}

/// The coefficients of the four contacts of a batch.
#[derive(Debug, Clone, Copy)]
pub struct CoeffLanes<'a>(pub [&'a PairCoeffs; super::real::LANES]);

impl Coeffs<super::real::F64x4> for CoeffLanes<'_> {
    #[inline(always)]
    fn get<F: Fn(&PairCoeffs) -> f64>(&self, f: F) -> super::real::F64x4 {
        super::real::F64x4([f(self.0[0]), f(self.0[1]), f(self.0[2]), f(self.0[3])])
    }
}

/// The coefficients of the eight contacts of a wide batch.
#[derive(Debug, Clone, Copy)]
pub struct CoeffWideLanes<'a>(pub [&'a PairCoeffs; super::real::WIDE_LANES]);

impl Coeffs<super::real::F64x8> for CoeffWideLanes<'_> {
    #[inline(always)]
    fn get<F: Fn(&PairCoeffs) -> f64>(&self, f: F) -> super::real::F64x8 {
        let c = &self.0;
        super::real::F64x8([
            f(c[0]),
            f(c[1]),
            f(c[2]),
            f(c[3]),
            f(c[4]),
            f(c[5]),
            f(c[6]),
            f(c[7]),
        ])
    }
}

/// Per-type-pair coefficient tables, indexed by 1-based atom types.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Material {
    ntypes: usize,
    pairs: Vec<PairCoeffs>,
    /// Every type pair has the same coefficients, bit for bit.
    same_for_all: bool,
}

/// Are all the tables' entries the same, bit for bit? (`Debug` prints each double so that it
/// reads back exactly, telling -0.0 from 0.0.)
fn all_same(pairs: &[PairCoeffs]) -> bool {
    let first = pairs.first().map(|p| format!("{p:?}"));
    pairs.iter().all(|p| Some(format!("{p:?}")) == first)
}

/// Base `fix property/global` values, in the order LIGGGHTS may create them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Base {
    Youngs,
    Poisson,
    Restitution,
    CharVel,
    Friction,
    RollFrict,
    RollVisc,
    Cohesion,
    RollStiffness,
    Kn,
    Kt,
    Gamman,
    Gammat,
    GammanAbs,
    GammatAbs,
    FluidViscosity,
    CriticalStokes,
    MaxRestitution,
    MaxElasticStiffness,
    AdhesionStiffness,
    PlasticityDepth,
}

impl Property {
    /// The base values this quantity is made of, in LIGGGHTS's creation order.
    fn bases(self) -> &'static [Base] {
        match self {
            Property::Yeff | Property::Geff => &[Base::Youngs, Base::Poisson],
            Property::BetaEff | Property::CoeffRestLog => &[Base::Restitution],
            Property::CharVel => &[Base::CharVel],
            Property::CoeffFrict => &[Base::Friction],
            Property::CohEnergyDens => &[Base::Cohesion],
            Property::CoeffRollFrict => &[Base::RollFrict],
            Property::CoeffRollVisc => &[Base::RollVisc],
            Property::RollingStiffness => &[Base::RollStiffness],
            Property::Kn => &[Base::Kn],
            Property::Kt => &[Base::Kt],
            Property::Gamman => &[Base::Gamman],
            Property::Gammat => &[Base::Gammat],
            Property::GammanAbs => &[Base::GammanAbs],
            Property::GammatAbs => &[Base::GammatAbs],
            Property::CoeffMu => &[Base::FluidViscosity],
            Property::CoeffStc => &[Base::CriticalStokes],
            Property::CoeffRestMax => &[Base::MaxRestitution],
            Property::CoeffMaxElasticStiffness => &[Base::MaxElasticStiffness],
            Property::CoeffAdhesionStiffness => &[Base::AdhesionStiffness],
            Property::CoeffPlasticityDepth => &[Base::PlasticityDepth],
        }
    }
}

impl Base {
    /// LIGGGHTS's `fix property/global` variable name.
    fn name(self) -> &'static str {
        match self {
            Base::Youngs => "youngsModulus",
            Base::Poisson => "poissonsRatio",
            Base::Restitution => "coefficientRestitution",
            Base::CharVel => "characteristicVelocity",
            Base::Friction => "coefficientFriction",
            Base::RollFrict => "coefficientRollingFriction",
            Base::RollVisc => "coefficientRollingViscousDamping",
            Base::Cohesion => "cohesionEnergyDensity",
            Base::RollStiffness => "rollingStiffness",
            Base::Kn => "kn",
            Base::Kt => "kt",
            Base::Gamman => "gamman",
            Base::Gammat => "gammat",
            Base::GammanAbs => "gamman_abs",
            Base::GammatAbs => "gammat_abs",
            Base::FluidViscosity => "FluidViscosity",
            Base::CriticalStokes => "CriticalStokes",
            Base::MaxRestitution => "MaximumRestitution",
            Base::MaxElasticStiffness => "coefficientMaxElasticStiffness",
            Base::AdhesionStiffness => "coefficientAdhesionStiffness",
            Base::PlasticityDepth => "coefficientPlasticityDepth",
        }
    }
}

/// LIGGGHTS's message for a property no fix defines.
fn missing(name: &str, caller: &str) -> String {
    format!("Could not locate a fix/property storing value(s) for {name} as requested by {caller}.")
}

impl MaterialInput {
    /// A per-type vector, checked for presence and length.
    fn per_type(
        &self,
        v: &Option<Vec<f64>>,
        base: Base,
        caller: &str,
    ) -> Result<Vec<f64>, EngineError> {
        let v = v.as_ref().ok_or_else(|| missing(base.name(), caller))?;
        if v.len() != self.ntypes {
            return Err(format!(
                "Fix property/global: Length not correct for variable {}, length should be equal to {} (= number of atom types)",
                base.name(),
                self.ntypes
            ).into());
        }
        Ok(v.clone())
    }

    /// A per-type-pair table, checked for presence and length.
    fn per_pair(
        &self,
        v: &Option<Vec<f64>>,
        base: Base,
        caller: &str,
    ) -> Result<Vec<f64>, EngineError> {
        let v = v.as_ref().ok_or_else(|| missing(base.name(), caller))?;
        let nn = self.ntypes * self.ntypes;
        if v.len() != nn {
            return Err(format!(
                "Fix property/global: Length not correct for variable {}, length should be equal to {} ( = number of atom types * number of atom types)",
                base.name(),
                nn
            ).into());
        }
        Ok(v.clone())
    }
}

/// Base values created so far (None until a model asked for them).
#[derive(Default)]
struct Bases {
    youngs: Option<Vec<f64>>,
    poisson: Option<Vec<f64>>,
    restitution: Option<Vec<f64>>,
    char_vel: Option<f64>,
    friction: Option<Vec<f64>>,
    roll_frict: Option<Vec<f64>>,
    roll_visc: Option<Vec<f64>>,
    cohesion: Option<Vec<f64>>,
    roll_stiffness: Option<f64>,
    kn: Option<Vec<f64>>,
    kt: Option<Vec<f64>>,
    gamman: Option<Vec<f64>>,
    gammat: Option<Vec<f64>>,
    gamman_abs: Option<Vec<f64>>,
    gammat_abs: Option<Vec<f64>>,
    fluid_viscosity: Option<Vec<f64>>,
    critical_stokes: Option<Vec<f64>>,
    max_restitution: Option<Vec<f64>>,
    max_elastic_stiffness: Option<Vec<f64>>,
    adhesion_stiffness: Option<Vec<f64>>,
    plasticity_depth: Option<Vec<f64>>,
}

impl Bases {
    /// Create one base value with LIGGGHTS's checks, unless it exists already.
    fn create(&mut self, inp: &MaterialInput, base: Base, caller: &str) -> Result<(), EngineError> {
        let si = inp.units == UnitStyle::Si;
        match base {
            Base::Youngs if self.youngs.is_none() => {
                let v = inp.per_type(&inp.youngs_modulus, base, caller)?;
                youngs_limits(inp, &v)?;
                self.youngs = Some(v);
            }
            Base::Poisson if self.poisson.is_none() => {
                let v = inp.per_type(&inp.poissons_ratio, base, caller)?;
                if v.iter().any(|&p| p < 0.0 || p > 0.5) {
                    return Err("0 <= poissonsRatio <= 0.5 required".into());
                }
                self.poisson = Some(v);
            }
            Base::Restitution if self.restitution.is_none() => {
                let v = inp.per_pair(&inp.coefficient_restitution, base, caller)?;
                restitution_limits(inp, &v)?;
                self.restitution = Some(v);
            }
            Base::CharVel if self.char_vel.is_none() => {
                let v = inp
                    .characteristic_velocity
                    .ok_or_else(|| missing(base.name(), caller))?;
                if si && v < 1e-2 {
                    return Err("characteristicVelocity >= 1e-2 required for SI units".into());
                }
                self.char_vel = Some(v);
            }
            Base::RollStiffness if self.roll_stiffness.is_none() => {
                let v = inp
                    .rolling_stiffness
                    .ok_or_else(|| missing(base.name(), caller))?;
                if si && v < 1.0 {
                    return Err("rollingStiffness >= 1 required for SI units".into());
                }
                self.roll_stiffness = Some(v);
            }
            Base::FluidViscosity if self.fluid_viscosity.is_none() => {
                let v = inp.per_pair(&inp.fluid_viscosity, base, caller)?;
                if v.iter().any(|&x| x <= 0.0) {
                    return Err("coeffMu > 0 required".into());
                }
                self.fluid_viscosity = Some(v);
            }
            Base::CriticalStokes if self.critical_stokes.is_none() => {
                let v = inp.per_pair(&inp.critical_stokes, base, caller)?;
                if v.iter().any(|&x| x <= 0.0) {
                    return Err("CriticalStokes > 0 required".into());
                }
                self.critical_stokes = Some(v);
            }
            Base::MaxRestitution if self.max_restitution.is_none() => {
                let v = inp.per_pair(&inp.maximum_restitution, base, caller)?;
                if v.iter().any(|&x| x <= 0.0 || x > 1.0) {
                    return Err("0 < MaximumRestitution <= 1 required".into());
                }
                self.max_restitution = Some(v);
            }
            Base::Friction if self.friction.is_none() => {
                self.friction = Some(inp.per_pair(&inp.coefficient_friction, base, caller)?)
            }
            Base::RollFrict if self.roll_frict.is_none() => {
                self.roll_frict =
                    Some(inp.per_pair(&inp.coefficient_rolling_friction, base, caller)?)
            }
            Base::RollVisc if self.roll_visc.is_none() => {
                self.roll_visc =
                    Some(inp.per_pair(&inp.coefficient_rolling_viscous_damping, base, caller)?)
            }
            Base::Cohesion if self.cohesion.is_none() => {
                self.cohesion = Some(inp.per_pair(&inp.cohesion_energy_density, base, caller)?)
            }
            Base::Kn if self.kn.is_none() => self.kn = Some(inp.per_pair(&inp.kn, base, caller)?),
            Base::Kt if self.kt.is_none() => self.kt = Some(inp.per_pair(&inp.kt, base, caller)?),
            Base::Gamman if self.gamman.is_none() => {
                self.gamman = Some(inp.per_pair(&inp.gamman, base, caller)?)
            }
            Base::Gammat if self.gammat.is_none() => {
                self.gammat = Some(inp.per_pair(&inp.gammat, base, caller)?)
            }
            Base::GammanAbs if self.gamman_abs.is_none() => {
                self.gamman_abs = Some(inp.per_pair(&inp.gamman_abs, base, caller)?)
            }
            Base::MaxElasticStiffness if self.max_elastic_stiffness.is_none() => {
                self.max_elastic_stiffness =
                    Some(inp.per_pair(&inp.max_elastic_stiffness, base, caller)?)
            }
            Base::AdhesionStiffness if self.adhesion_stiffness.is_none() => {
                self.adhesion_stiffness =
                    Some(inp.per_pair(&inp.adhesion_stiffness, base, caller)?)
            }
            Base::PlasticityDepth if self.plasticity_depth.is_none() => {
                self.plasticity_depth = Some(inp.per_pair(&inp.plasticity_depth, base, caller)?)
            }
            Base::GammatAbs if self.gammat_abs.is_none() => {
                self.gammat_abs = Some(inp.per_pair(&inp.gammat_abs, base, caller)?)
            }
            _ => {}
        }
        Ok(())
    }
}

/// LIGGGHTS's bounds on Young's moduli `v` (Pa, or barye in cgs) for the deck's units,
/// unless `soft_particles` / `hard_particles` lift them.
fn youngs_limits(inp: &MaterialInput, v: &[f64]) -> Result<(), EngineError> {
    let si = inp.units == UnitStyle::Si;
    let cgs = inp.units == UnitStyle::Cgs;
    for &y in v {
        if !inp.soft_particles {
            if si && y < 5e6 {
                return Err("youngsModulus >= 5e6 required for SI units (use command 'soft_particles yes' to override)".into());
            }
            if cgs && y < 5e7 {
                return Err("youngsModulus >= 5e7 required for CGS units (use command 'soft_particles yes' to override)".into());
            }
        }
        if !inp.hard_particles {
            if si && y > 1e9 {
                return Err("youngsModulus <= 1e9 required for SI units (use command 'hard_particles yes' to override)".into());
            }
            if cgs && y > 1e10 {
                return Err("youngsModulus <= 1e10 required for CGS units (use command 'hard_particles yes' to override)".into());
            }
        }
    }
    Ok(())
}

/// LIGGGHTS's bounds on restitution coefficients `v` (regolith's -zero_restitution allows
/// values down to 0).
fn restitution_limits(inp: &MaterialInput, v: &[f64]) -> Result<(), EngineError> {
    for &e in v {
        if inp.allow_zero_restitution {
            if e < 0.0 || e > 1.0 {
                return Err("0 <= coefficientRestitution <= 1 required (regolith extension -zero_restitution)".into());
            }
        } else if e <= 0.05 || e > 1.0 {
            return Err("0.05 < coefficientRestitution <= 1 required (regolith: run with -zero_restitution to allow values down to 0)".into());
        }
    }
    Ok(())
}

/// LIGGGHTS's `Yeff` mixing of two types.
#[inline]
pub fn mix_yeff(yi: f64, yj: f64, vi: f64, vj: f64) -> f64 {
    1. / ((1. - vi.powf(2.)) / yi + (1. - vj.powf(2.)) / yj)
}

/// LIGGGHTS's `Geff` mixing of two types.
#[inline]
pub fn mix_geff(yi: f64, yj: f64, vi: f64, vj: f64) -> f64 {
    1. / (2. * (2. - vi) * (1. + vi) / yi + 2. * (2. - vj) * (1. + vj) / yj)
}

/// LIGGGHTS's `betaeff` of one restitution coefficient; its limit -1 at e = 0.
#[inline]
pub fn beta_of_restitution(e: f64) -> f64 {
    if e == 0.0 {
        return -1.0;
    }
    let l = e.ln();
    l / (l.powf(2.) + PI.powf(2.)).sqrt()
}

impl Material {
    /// Mix the raw values into per-type-pair coefficients for the quantities `requests`
    /// names, in request order, with LIGGGHTS's checks and messages; `requests` comes from
    /// [`crate::engine::contact::ContactModel::properties`].
    pub fn new(
        input: &MaterialInput,
        requests: &[(Property, &str)],
    ) -> Result<Material, EngineError> {
        let n = input.ntypes;
        let mut b = Bases::default();
        for &(prop, caller) in requests {
            for &base in prop.bases() {
                b.create(input, base, caller)?;
            }
        }
        let mut pairs = Vec::new();
        let size = std::mem::size_of::<PairCoeffs>();
        n.checked_mul(n)
            .and_then(|nn| pairs.try_reserve_exact(nn).ok())
            .ok_or_else(|| {
                crate::engine::checks::failed_to_allocate(
                    (n as f64) * (n as f64) * size as f64,
                    "pair coefficients",
                )
            })?;
        pairs.resize(n * n, PairCoeffs::default());
        for i in 0..n {
            for j in 0..n {
                let k = i * n + j;
                let p = &mut pairs[k];
                if let (Some(y), Some(v)) = (&b.youngs, &b.poisson) {
                    p.yeff = mix_yeff(y[i], y[j], v[i], v[j]);
                    p.geff = mix_geff(y[i], y[j], v[i], v[j]);
                }
                if let Some(e) = &b.restitution {
                    p.coeff_rest_log = e[k].ln();
                    p.betaeff = beta_of_restitution(e[k]);
                }
                let at = |t: &Option<Vec<f64>>| t.as_ref().map_or(0.0, |t| t[k]);
                p.char_vel = b.char_vel.unwrap_or(0.0);
                p.rolling_stiffness = b.roll_stiffness.unwrap_or(0.0);
                p.coeff_frict = at(&b.friction);
                p.cohesion_energy_density = at(&b.cohesion);
                p.coeff_roll_frict = at(&b.roll_frict);
                p.coeff_roll_visc = at(&b.roll_visc);
                p.kn = at(&b.kn);
                p.kt = at(&b.kt);
                p.gamman = at(&b.gamman);
                p.gammat = at(&b.gammat);
                p.gamman_abs = at(&b.gamman_abs);
                p.gammat_abs = at(&b.gammat_abs);
                p.fluid_viscosity = at(&b.fluid_viscosity);
                p.critical_stokes = at(&b.critical_stokes);
                p.log_coeff_rest_max = b.max_restitution.as_ref().map_or(0.0, |t| t[k].ln());
                p.kn_to_k2_max = at(&b.max_elastic_stiffness);
                p.kn_to_kc = at(&b.adhesion_stiffness);
                p.phi_f = at(&b.plasticity_depth);
            }
        }
        let same_for_all = all_same(&pairs);
        Ok(Material {
            ntypes: n,
            pairs,
            same_for_all,
        })
    }

    /// A table of `ntypes` types where every pair has the coefficients `c` (for tests and
    /// hand-built setups).
    pub fn uniform(ntypes: usize, c: PairCoeffs) -> Material {
        Material {
            ntypes,
            pairs: vec![c; ntypes * ntypes],
            same_for_all: true,
        }
    }

    /// Number of atom types.
    pub fn ntypes(&self) -> usize {
        self.ntypes
    }

    /// Coefficients of the type pair (itype, jtype), both 1-based.
    #[inline(always)]
    pub fn pair(&self, itype: usize, jtype: usize) -> &PairCoeffs {
        &self.pairs[(itype - 1) * self.ntypes + (jtype - 1)]
    }

    /// Every type pair has the same coefficients, bit for bit (kernels then read one set).
    pub fn same_for_all(&self) -> bool {
        self.same_for_all
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input() -> MaterialInput {
        MaterialInput {
            ntypes: 2,
            youngs_modulus: Some(vec![5e6, 1e7]),
            poissons_ratio: Some(vec![0.2, 0.3]),
            coefficient_restitution: Some(vec![0.5, 0.6, 0.6, 0.7]),
            coefficient_friction: Some(vec![0.3, 0.05, 0.05, 0.4]),
            ..MaterialInput::default()
        }
    }

    const HERTZ: &[(Property, &str)] = &[
        (Property::Yeff, "model hertz"),
        (Property::Geff, "model hertz"),
        (Property::BetaEff, "model hertz"),
        (Property::CoeffFrict, "tangential_model history"),
    ];

    #[test]
    fn mixing_matches_the_closed_forms() {
        let m = Material::new(&input(), HERTZ).unwrap();
        let p = m.pair(1, 2);
        let y = 1.0 / ((1.0 - 0.04) / 5e6 + (1.0 - 0.09) / 1e7);
        assert!((p.yeff - y).abs() < 1e-9 * y);
        let g = 1.0 / (2.0 * 1.8 * 1.2 / 5e6 + 2.0 * 1.7 * 1.3 / 1e7);
        assert!((p.geff - g).abs() < 1e-9 * g);
        let l = 0.6f64.ln();
        assert!((p.betaeff - l / (l * l + PI * PI).sqrt()).abs() < 1e-15);
        assert_eq!(p.coeff_frict, 0.05);
        assert_eq!(m.pair(2, 2).coeff_frict, 0.4);
        // symmetric mixing
        assert_eq!(m.pair(1, 2).yeff, m.pair(2, 1).yeff);
    }

    #[test]
    fn liggghts_checks_and_messages() {
        let mut i = input();
        i.youngs_modulus = Some(vec![1e6, 1e7]);
        assert_eq!(
            Material::new(&i, HERTZ).unwrap_err().to_string(),
            "youngsModulus >= 5e6 required for SI units (use command 'soft_particles yes' to override)"
        );
        i.soft_particles = true;
        assert!(Material::new(&i, HERTZ).is_ok());
        i.youngs_modulus = Some(vec![5e6, 2e9]);
        assert_eq!(
            Material::new(&i, HERTZ).unwrap_err().to_string(),
            "youngsModulus <= 1e9 required for SI units (use command 'hard_particles yes' to override)"
        );
        i.hard_particles = true;
        assert!(Material::new(&i, HERTZ).is_ok());
        i.coefficient_restitution = Some(vec![0.05, 0.6, 0.6, 0.7]);
        assert_eq!(
            Material::new(&i, HERTZ).unwrap_err().to_string(),
            "0.05 < coefficientRestitution <= 1 required (regolith: run with -zero_restitution to allow values down to 0)"
        );
        i.coefficient_restitution = Some(vec![1.01, 0.6, 0.6, 0.7]);
        assert!(Material::new(&i, HERTZ).is_err());
        i.poissons_ratio = Some(vec![0.6, 0.3]);
        assert_eq!(
            Material::new(&i, HERTZ).unwrap_err().to_string(),
            "0 <= poissonsRatio <= 0.5 required"
        );
        let mut i = input();
        i.coefficient_friction = None;
        assert_eq!(
            Material::new(&i, HERTZ).unwrap_err().to_string(),
            "Could not locate a fix/property storing value(s) for coefficientFriction as requested by tangential_model history."
        );
        // a property nobody asks for is never checked
        let mut i = input();
        i.youngs_modulus = Some(vec![1.0, 1.0]);
        assert!(Material::new(&i, &[(Property::CoeffFrict, "x")]).is_ok());
        let mut i = input();
        i.youngs_modulus = Some(vec![5e6]);
        assert!(Material::new(&i, HERTZ)
            .unwrap_err()
            .to_string()
            .contains("length should be equal to 2"));
    }

    #[test]
    fn zero_restitution_extension() {
        let mut i = input();
        i.coefficient_restitution = Some(vec![0.0, 0.01, 0.01, 0.7]);
        assert!(Material::new(&i, HERTZ).is_err());
        i.allow_zero_restitution = true;
        let m = Material::new(&i, HERTZ).unwrap();
        assert_eq!(m.pair(1, 1).betaeff, -1.0);
        assert_eq!(m.pair(1, 1).coeff_rest_log, f64::NEG_INFINITY);
        assert!(m.pair(1, 2).betaeff > -1.0 && m.pair(1, 2).betaeff < -0.8);
        // e > 0.05 is unchanged by the flag
        assert_eq!(
            m.pair(2, 2).betaeff,
            Material::new(&input(), HERTZ).unwrap().pair(2, 2).betaeff
        );
    }

    #[test]
    fn characteristic_velocity_and_rolling_stiffness_limits() {
        let mut i = input();
        i.characteristic_velocity = Some(1e-3);
        assert_eq!(
            Material::new(&i, &[(Property::CharVel, "model hooke")])
                .unwrap_err()
                .to_string(),
            "characteristicVelocity >= 1e-2 required for SI units"
        );
        i.rolling_stiffness = Some(0.5);
        assert_eq!(
            Material::new(&i, &[(Property::RollingStiffness, "rolling_model epsd3")])
                .unwrap_err()
                .to_string(),
            "rollingStiffness >= 1 required for SI units"
        );
    }
}
