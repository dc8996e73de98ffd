//! `fix aveforce`: the group's forces replaced by their mean plus an extra force
//! (`post_force`; `f_ID[1..3]` the group's summed force before it acted).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::particles::Particles;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "aveforce",
    "fix ID GROUP aveforce FX FY FZ",
    &[],
    "set every member's force to the group mean plus FX FY FZ (force; NULL: leave alone); f_ID[1..3]: the summed force before",
);

/// `fix aveforce FX FY FZ` (force; None: NULL, that component left alone).
#[derive(Debug, Clone, PartialEq)]
pub struct AveForce {
    /// The force added to the average, per component.
    pub add: [Option<f64>; 3],
    /// The group's summed force before the fix acted (f_ID[1..3]).
    pub original: [f64; 3],
}

impl AveForce {
    /// Every group member gets the group's mean force plus `add` in the set components.
    pub fn apply(&mut self, p: &mut Particles, group: u32) {
        let mut sum = [0.0; 4];
        for i in 0..p.len() {
            if p.mask[i] & group != 0 {
                for (s, f) in sum.iter_mut().zip(p.f[i]) {
                    *s += f;
                }
                sum[3] += 1.0;
            }
        }
        self.original = [sum[0], sum[1], sum[2]];
        let n = sum[3] as i32;
        if n == 0 {
            return;
        }
        let n = n as f64;
        let ave = [0, 1, 2].map(|k| sum[k] / n + self.add[k].unwrap_or(0.0));
        for i in 0..p.len() {
            if p.mask[i] & group != 0 {
                for ((f, add), a) in p.f[i].iter_mut().zip(self.add).zip(ave) {
                    if add.is_some() {
                        *f = a;
                    }
                }
            }
        }
    }
}

impl FixStyle for AveForce {
    fn name(&self) -> &str {
        "aveforce"
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        self.apply(p, at.group);
    }

    /// LIGGGHTS flags its global vector extensive.
    fn extensive(&self, index: Option<usize>) -> bool {
        index.is_some()
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        match index {
            Some(i @ 1..=3) => Some(self.original[i - 1]),
            _ => None,
        }
    }
}

/// `fix ID GROUP aveforce FX FY FZ` (force, or NULL to leave a component alone).
pub fn build(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() < 6 {
        return Err(a.error(3, "Illegal fix aveforce command"));
    }
    let mut add = [None; 3];
    for (k, slot) in add.iter_mut().enumerate() {
        let w = a.word(3 + k)?;
        if w.starts_with("v_") {
            return Err(a.unsupported(3 + k, "fix aveforce with variables"));
        }
        if w != "NULL" {
            *slot = Some(a.real(3 + k)?);
        }
    }
    if a.len() > 6 {
        return Err(match a.word(6)? {
            "region" => a.unsupported(6, "fix aveforce region"),
            _ => a.error(6, "Illegal fix aveforce command"),
        });
    }
    Ok(Box::new(AveForce {
        add,
        original: [0.0; 3],
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aveforce_sets_the_mean_plus_the_extra() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0, 0.0, 0.0], 0.1, 1000.0);
        p.push(2, 1, [1.0, 0.0, 0.0], 0.1, 1000.0);
        p.f = vec![[1.0, 2.0, 3.0], [3.0, -2.0, 1.0]];
        let mut a = AveForce {
            add: [Some(0.5), None, Some(0.0)],
            original: [0.0; 3],
        };
        a.apply(&mut p, 1);
        assert_eq!(p.f[0], [2.5, 2.0, 2.0]);
        assert_eq!(p.f[1], [2.5, -2.0, 2.0]);
        assert_eq!(a.original, [4.0, 0.0, 4.0]);
        assert_eq!(a.value(Some(3)), Some(4.0));
        assert_eq!(a.value(None), None);
    }
}
