//! `fix buoyancy`: the weight of the displaced liquid below a level plane, as LIGGGHTS 3.8.0
//! adds it in `post_force` (partly immersed spheres displace their immersed cap).

use crate::engine::error::EngineError;
use crate::engine::particles::Particles;

/// One `fix buoyancy level L dim x|y|z density RHO [region R]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Buoyancy {
    /// The fix ID (LIGGGHTS's messages name it).
    pub id: String,
    /// Liquid density (mass/length^3).
    pub density: f64,
    /// The axis normal to the liquid surface (0, 1, 2).
    pub dim: usize,
    /// The liquid level along `dim` (length).
    pub level: f64,
    /// `region R`: only particles inside it (region index).
    pub region: Option<usize>,
    /// Per particle: inside the region this step (filled before `post_force`).
    pub inside: Vec<bool>,
    /// Total buoyancy force of the last step (force): f_ID[1..3].
    pub total: [f64; 3],
    /// The run's gravity (length/time^2), taken at the run's init.
    pub gravity: Option<[f64; 3]>,
}

impl Buoyancy {
    /// Add the buoyancy force to the particles of `group` under gravity `g`
    /// (length/time^2), which must lie along `dim`.
    pub fn apply(&mut self, p: &mut Particles, group: u32, g: [f64; 3]) {
        self.total = [0.0; 3];
        let mag = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        let direction = g[self.dim] / g[self.dim].abs();
        let c = 4. * std::f64::consts::PI / 3.;
        let pi6 = std::f64::consts::PI / 6.;
        let dim = self.dim;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 || (self.region.is_some() && !self.inside[i]) {
                continue;
            }
            let r = p.radius[i];
            let mut h = (p.x[i][dim] - self.level) * direction;
            let hmag = h.abs();
            let immersed = if hmag > r && h < 0. {
                continue;
            } else if hmag > r && h > 0. {
                c * r * r * r
            } else if h > 0. {
                // the larger part immersed: the sphere less its dry cap
                h = r - h;
                let a = (2. * r * h - h * h).sqrt();
                let cap = h * pi6 * (3. * a * a + h * h);
                c * r * r * r - cap
            } else {
                h = -h;
                h = r - h;
                let a = (2. * r * h - h * h).sqrt();
                h * pi6 * (3. * a * a + h * h)
            };
            let force = -direction * mag * immersed * self.density;
            p.f[i][dim] += force;
            self.total[dim] += force;
        }
    }
}

impl Buoyancy {
    /// LIGGGHTS's checks at a run's init, given the accelerations of the run's fixes
    /// (length/time^2): exactly one `fix gravity`, along `dim`; it is the gravity the run uses.
    pub fn init(&mut self, gravities: &[[f64; 3]]) -> Result<(), EngineError> {
        let fail = |m: &str| EngineError::from(format!("Fix buoyancy (id {}): {m}", self.id));
        if gravities.len() != 1 {
            return Err(fail("need exactly one fix gravity"));
        }
        let g = gravities[0];
        let across: f64 = (0..3).filter(|&d| d != self.dim).map(|d| g[d]).sum();
        if across.abs() > 0. || g[self.dim] == 0. {
            return Err(fail(" fix gravity direction is not equal to 'dim'"));
        }
        self.gravity = Some(g);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn immersed_volumes_follow_the_level() {
        let mut b = Buoyancy {
            id: "b".into(),
            density: 1000.,
            dim: 2,
            level: 0.0,
            region: None,
            inside: Vec::new(),
            total: [0.0; 3],
            gravity: None,
        };
        let mut p = Particles::default();
        let r = 0.01;
        p.push(1, 1, [0.0, 0.0, -0.5], r, 1.0); // fully immersed
        p.push(2, 1, [0.0, 0.0, 0.0], r, 1.0); // half
        p.push(3, 1, [0.0, 0.0, 0.5], r, 1.0); // dry
        b.apply(&mut p, 1, [0.0, 0.0, -9.81]);
        let full = 4. / 3. * std::f64::consts::PI * r * r * r * 1000. * 9.81;
        assert!((p.f[0][2] - full).abs() < 1e-12 * full);
        assert!((p.f[1][2] - 0.5 * full).abs() < 1e-9 * full);
        assert_eq!(p.f[2][2], 0.0);
    }
}
