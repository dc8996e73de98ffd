//! `fix lineforce` and `fix planeforce`: the group's forces kept along a line or in a plane
//! (`post_force`).

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::particles::Particles;

/// The declared signature of `lineforce`.
pub const LINE: Spec = style(
    "fix",
    "lineforce",
    "fix ID GROUP lineforce X Y Z",
    &[],
    "keep only the force component along the direction (X Y Z)",
);

/// The declared signature of `planeforce`.
pub const PLANE: Spec = style(
    "fix",
    "planeforce",
    "fix ID GROUP planeforce X Y Z",
    &[],
    "remove the force component along the plane normal (X Y Z)",
);

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

impl FixStyle for Project {
    fn name(&self) -> &str {
        if self.line {
            "lineforce"
        } else {
            "planeforce"
        }
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        self.apply(p, at.group);
    }
}

/// `fix ID GROUP lineforce|planeforce X Y Z`: the line's direction or the plane's normal.
pub fn build(a: &Args, _ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let illegal = format!("Illegal fix {} command", fix.style);
    if a.len() != 6 {
        return Err(a.error(3, &illegal));
    }
    let dir = [a.real(3)?, a.real(4)?, a.real(5)?];
    let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
    if len == 0.0 {
        return Err(a.error(3, &illegal));
    }
    Ok(Box::new(Project {
        dir: dir.map(|c| c / len),
        line: fix.style == "lineforce",
    }))
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
}
