//! Per-type-pair contact coefficients from `fix property/global` (youngsModulus,
//! poissonsRatio, coefficientRestitution, coefficientFriction), mixed as LIGGGHTS mixes them.

/// Coefficient tables indexed by 1-based atom types.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Material {
    ntypes: usize,
    yeff: Vec<f64>,
    geff: Vec<f64>,
    betaeff: Vec<f64>,
    friction: Vec<f64>,
    cohesion: Vec<f64>,
    rolling_friction: Vec<f64>,
    rolling_viscous: Vec<f64>,
    restitution_log: Vec<f64>,
    /// characteristicVelocity (length/time), NaN when not defined.
    pub char_vel: f64,
}

/// The raw per-type inputs.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialInput {
    /// Young's modulus per type (pressure).
    pub youngs: Vec<f64>,
    /// Poisson's ratio per type.
    pub poisson: Vec<f64>,
    /// Restitution per type pair, row-major ntypes x ntypes.
    pub restitution: Vec<f64>,
    /// Friction per type pair, row-major.
    pub friction: Vec<f64>,
    /// `soft_particles yes`: allow E < 5e6.
    pub soft: bool,
    /// `hard_particles yes`: allow E > 1e9.
    pub hard: bool,
    /// regolith extension (`-zero_restitution`): allow 0 <= e <= 0.05.
    pub zero_restitution: bool,
    /// cohesionEnergyDensity per type pair (energy/volume), if defined.
    pub cohesion: Option<Vec<f64>>,
    /// coefficientRollingFriction per type pair, if defined.
    pub rolling_friction: Option<Vec<f64>>,
    /// coefficientRollingViscousDamping per type pair, if defined.
    pub rolling_viscous: Option<Vec<f64>>,
    /// characteristicVelocity (length/time), if defined.
    pub char_vel: Option<f64>,
}

impl Material {
    /// Mix the per-type inputs into per-pair coefficients, with LIGGGHTS's checks.
    pub fn new(input: &MaterialInput) -> Result<Material, String> {
        let n = input.youngs.len();
        if input.poisson.len() != n
            || input.restitution.len() != n * n
            || input.friction.len() != n * n
        {
            return Err("material property tables do not match the number of atom types".into());
        }
        for &y in &input.youngs {
            if !input.soft && y < 5e6 {
                return Err("youngsModulus >= 5e6 required for SI units (use command 'soft_particles yes' to override)".into());
            }
            if !input.hard && y > 1e9 {
                return Err("youngsModulus <= 1e9 required for SI units (use command 'hard_particles yes' to override)".into());
            }
        }
        for &v in &input.poisson {
            if !(0.0..=0.5).contains(&v) {
                return Err("0 <= poissonsRatio <= 0.5 required".into());
            }
        }
        for &e in &input.restitution {
            let low_ok = input.zero_restitution && e >= 0.0;
            if (e <= 0.05 && !low_ok) || e > 1.0 {
                return Err("0.05 < coefficientRestitution <= 1 required (regolith: run with -zero_restitution to allow values down to 0)".into());
            }
        }
        let mut m = Material {
            ntypes: n,
            cohesion: input.cohesion.clone().unwrap_or_default(),
            rolling_friction: input.rolling_friction.clone().unwrap_or_default(),
            rolling_viscous: input.rolling_viscous.clone().unwrap_or_default(),
            char_vel: input.char_vel.unwrap_or(f64::NAN),
            ..Material::default()
        };
        for i in 0..n {
            for j in 0..n {
                let (yi, yj, vi, vj) = (
                    input.youngs[i],
                    input.youngs[j],
                    input.poisson[i],
                    input.poisson[j],
                );
                m.yeff
                    .push(1. / ((1. - vi.powf(2.)) / yi + (1. - vj.powf(2.)) / yj));
                m.geff
                    .push(1. / (2. * (2. - vi) * (1. + vi) / yi + 2. * (2. - vj) * (1. + vj) / yj));
                let log_e = input.restitution[i * n + j].ln();
                // e = 0 (extension) is the limit of critical damping: beta = -1
                let beta = if log_e.is_infinite() {
                    -1.0
                } else {
                    log_e / (log_e.powf(2.) + std::f64::consts::PI.powf(2.)).sqrt()
                };
                m.betaeff.push(beta);
                m.friction.push(input.friction[i * n + j]);
                m.restitution_log.push(log_e);
            }
        }
        Ok(m)
    }

    #[inline(always)]
    fn at(&self, table: &[f64], i: usize, j: usize) -> f64 {
        table[(i - 1) * self.ntypes + (j - 1)]
    }

    /// Effective Young's modulus of a type pair (pressure).
    #[inline(always)]
    pub fn yeff(&self, i: usize, j: usize) -> f64 {
        self.at(&self.yeff, i, j)
    }

    /// Effective shear modulus (pressure).
    #[inline(always)]
    pub fn geff(&self, i: usize, j: usize) -> f64 {
        self.at(&self.geff, i, j)
    }

    /// Damping ratio from the restitution: ln e / sqrt(ln^2 e + pi^2).
    #[inline(always)]
    pub fn betaeff(&self, i: usize, j: usize) -> f64 {
        self.at(&self.betaeff, i, j)
    }

    /// Error unless cohesionEnergyDensity is defined.
    pub fn require_cohesion(&self, caller: &str) -> Result<(), String> {
        if self.cohesion.len() != self.ntypes * self.ntypes {
            return Err(format!("Could not locate a fix/property storing value(s) for cohesionEnergyDensity as requested by {caller}."));
        }
        Ok(())
    }

    /// Error unless the rolling coefficients are defined (viscous damping only if `viscous`).
    pub fn require_rolling(&self, caller: &str, viscous: bool) -> Result<(), String> {
        let nn = self.ntypes * self.ntypes;
        if self.rolling_friction.len() != nn {
            return Err(format!("Could not locate a fix/property storing value(s) for coefficientRollingFriction as requested by {caller}."));
        }
        if viscous && self.rolling_viscous.len() != nn {
            return Err(format!("Could not locate a fix/property storing value(s) for coefficientRollingViscousDamping as requested by {caller}."));
        }
        Ok(())
    }

    /// characteristicVelocity, or LIGGGHTS's error if the deck defines none.
    pub fn characteristic_velocity(&self, caller: &str) -> Result<f64, String> {
        if self.char_vel.is_nan() {
            return Err(format!("Could not locate a fix/property storing value(s) for characteristicVelocity as requested by {caller}."));
        }
        Ok(self.char_vel)
    }

    /// ln(coefficient of restitution) of a type pair.
    #[inline(always)]
    pub fn restitution_log(&self, i: usize, j: usize) -> f64 {
        self.at(&self.restitution_log, i, j)
    }

    /// Cohesion energy density (energy/volume).
    #[inline(always)]
    pub fn cohesion(&self, i: usize, j: usize) -> f64 {
        self.at(&self.cohesion, i, j)
    }

    /// Rolling friction coefficient.
    #[inline(always)]
    pub fn rolling_friction(&self, i: usize, j: usize) -> f64 {
        self.at(&self.rolling_friction, i, j)
    }

    /// Rolling viscous damping coefficient.
    #[inline(always)]
    pub fn rolling_viscous(&self, i: usize, j: usize) -> f64 {
        self.at(&self.rolling_viscous, i, j)
    }

    /// Coulomb friction coefficient.
    #[inline(always)]
    pub fn friction(&self, i: usize, j: usize) -> f64 {
        self.at(&self.friction, i, j)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(e: f64, zero: bool) -> MaterialInput {
        MaterialInput {
            youngs: vec![5e6],
            poisson: vec![0.2],
            restitution: vec![e],
            friction: vec![0.5],
            soft: false,
            hard: false,
            cohesion: None,
            rolling_friction: None,
            rolling_viscous: None,
            char_vel: None,
            zero_restitution: zero,
        }
    }

    #[test]
    fn restitution_limits_and_zero_extension() {
        assert!(Material::new(&input(0.0, false))
            .unwrap_err()
            .contains("0.05 < coefficientRestitution <= 1"));
        assert!(Material::new(&input(1.01, true)).is_err());
        let m = Material::new(&input(0.0, true)).unwrap();
        assert_eq!(m.betaeff(1, 1), -1.0);
        let tiny = Material::new(&input(1e-300, true)).unwrap();
        assert!((tiny.betaeff(1, 1) + 1.0).abs() < 1e-4);
        let half = Material::new(&input(0.5, false)).unwrap();
        let l = 0.5f64.ln();
        assert!(
            (half.betaeff(1, 1) - l / (l * l + std::f64::consts::PI.powi(2)).sqrt()).abs() < 1e-15
        );
    }
}
