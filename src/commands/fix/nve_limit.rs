//! `fix nve/limit`: `fix nve` with each particle's step capped at a distance
//! (`f_ID`: the speeds capped since the run began).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "nve/limit",
    "fix ID GROUP nve/limit absolute|radius_ratio XLIMIT",
    &[],
    "fix nve with each step capped at XLIMIT (length, or times the radius); f_ID: speeds capped this run",
);

/// `fix nve/limit absolute|radius_ratio XLIMIT`.
#[derive(Debug, Clone, PartialEq)]
pub struct NveLimit {
    /// The largest distance a particle may move in one step (length), or with
    /// `radius_ratio` that distance over the particle's radius (a pure number).
    pub xlimit: f64,
    /// `radius_ratio`: the limit scales with each particle's radius.
    pub relative: bool,
    /// Speeds capped since the run began (f_ID).
    pub count: i64,
}

impl NveLimit {
    /// Cap particle `i`'s speed at xlimit / dt (times its radius with `radius_ratio`).
    #[inline]
    fn limit(&mut self, p: &mut Particles, i: usize, vlimitsq: f64) {
        let v = p.v[i];
        let vsq = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        let cap = if self.relative {
            vlimitsq * (p.radius[i] * p.radius[i])
        } else {
            vlimitsq
        };
        if vsq > cap {
            self.count += 1;
            let scale = (cap / vsq).sqrt();
            for d in 0..3 {
                p.v[i][d] *= scale;
            }
        }
    }

    /// Half-kick v, cap the speed and, with `drift`, move x a full step `dt` (time).
    fn kick_and_cap(&mut self, p: &mut Particles, group: u32, dt: f64, drift: bool) {
        let dtf = 0.5 * dt;
        let vlimitsq = (self.xlimit / dt) * (self.xlimit / dt);
        for i in 0..p.len() {
            if p.mask[i] & group != 0 {
                let dtfm = dtf / p.mass[i];
                for d in 0..3 {
                    p.v[i][d] += dtfm * p.f[i][d];
                }
                self.limit(p, i, vlimitsq);
                if drift {
                    for d in 0..3 {
                        p.x[i][d] += dt * p.v[i][d];
                    }
                }
            }
        }
    }
}

impl FixStyle for NveLimit {
    fn name(&self) -> &str {
        "nve/limit"
    }

    /// Capped speeds are counted from the start of each run (LIGGGHTS's `init`).
    fn setup(&mut self, _p: &Particles, _at: &FixStep) {
        self.count = 0;
    }

    fn initial_integrate(&mut self, p: &mut Particles, at: &FixStep) {
        self.kick_and_cap(p, at.group, at.dt, true);
    }

    fn final_integrate(&mut self, p: &mut Particles, at: &FixStep) {
        self.kick_and_cap(p, at.group, at.dt, false);
    }

    /// LIGGGHTS flags its global scalar extensive.
    fn extensive(&self, index: Option<usize>) -> bool {
        index.is_none()
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        index.is_none().then_some(self.count as f64)
    }
}

/// `fix ID GROUP nve/limit absolute|radius_ratio XLIMIT`: XLIMIT a length (absolute) or a
/// multiple of each particle's radius (radius_ratio).
pub fn build(a: &Args, _ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() != 5 {
        return Err(a.error(3, "Illegal fix nve/limit command"));
    }
    let relative = match a.word(3)? {
        "radius_ratio" => true,
        "absolute" => false,
        _ => {
            return Err(a.error(
                3,
                format!(
                    "Fix nve/limit (id {}): expecting keyword 'absolute' or 'radius_ratio'",
                    fix.id
                ),
            ))
        }
    };
    Ok(Box::new(NveLimit {
        xlimit: a.real(4)?,
        relative,
        count: 0,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speeds_are_capped_and_counted() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0, 0.0, 0.0], 0.1, 1000.0);
        p.push(2, 1, [1.0, 0.0, 0.0], 0.1, 1000.0);
        p.v = vec![[3.0, 4.0, 0.0], [0.1, 0.0, 0.0]];
        let mut n = NveLimit {
            xlimit: 1e-3,
            relative: false,
            count: 0,
        };
        let domain = crate::engine::domain::Domain::default();
        let at = FixStep::plain(1, 1, 1e-3, &domain);
        n.initial_integrate(&mut p, &at);
        // speed 5 capped at 1: direction kept
        assert!((p.v[0][0] - 0.6).abs() < 1e-12 && (p.v[0][1] - 0.8).abs() < 1e-12);
        assert_eq!(p.v[1], [0.1, 0.0, 0.0]);
        assert!((p.x[0][0] - 0.6e-3).abs() < 1e-15);
        assert_eq!(n.count, 1);
        n.relative = true; // cap 1e-3 / 1e-3 * 0.1 = 0.1
        n.final_integrate(&mut p, &at);
        assert_eq!(n.value(None), Some(2.0));
        assert!((p.v[0][0] - 0.06).abs() < 1e-12);
        assert_eq!(n.count, 2);
    }
}
