//! `fix lineforce`, `fix planeforce` and `fix aveforce` (`post_force`): the group's forces
//! kept along a line, kept in a plane, or replaced by their average plus an extra force.

use crate::engine::particles::Particles;

/// `fix lineforce X Y Z` (line: true) or `fix planeforce X Y Z` (line: false).
#[derive(Debug, Clone, PartialEq)]
pub struct Project {
    /// Unit direction of the line, or the plane's unit normal.
    pub dir: [f64; 3],
    /// Keep the component along `dir` (lineforce) or remove it (planeforce).
    pub line: bool,
}

impl Project {
    /// Project the group's forces (LIGGGHTS's arithmetic).
    pub fn apply(&self, p: &mut Particles, group: u32) {
        let d = self.dir;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let f = &mut p.f[i];
            let dot = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
            for k in 0..3 {
                if self.line {
                    f[k] = dot * d[k];
                } else {
                    f[k] -= dot * d[k];
                }
            }
        }
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    fn two() -> Particles {
        let mut p = Particles::default();
        p.push(1, 1, [0.0, 0.0, 0.0], 0.1, 1000.0);
        p.push(2, 1, [1.0, 0.0, 0.0], 0.1, 1000.0);
        p.f = vec![[1.0, 2.0, 3.0], [3.0, -2.0, 1.0]];
        p
    }

    #[test]
    fn line_and_plane_split_the_force() {
        let mut p = two();
        Project {
            dir: [0.0, 0.0, 1.0],
            line: true,
        }
        .apply(&mut p, 1);
        assert_eq!(p.f[0], [0.0, 0.0, 3.0]);
        let mut p = two();
        Project {
            dir: [0.0, 0.0, 1.0],
            line: false,
        }
        .apply(&mut p, 1);
        assert_eq!(p.f[1], [3.0, -2.0, 0.0]);
    }

    #[test]
    fn aveforce_sets_the_mean_plus_the_extra() {
        let mut p = two();
        let mut a = AveForce {
            add: [Some(0.5), None, Some(0.0)],
            original: [0.0; 3],
        };
        a.apply(&mut p, 1);
        assert_eq!(p.f[0], [2.5, 2.0, 2.0]);
        assert_eq!(p.f[1], [2.5, -2.0, 2.0]);
        assert_eq!(a.original, [4.0, 0.0, 4.0]);
    }
}
