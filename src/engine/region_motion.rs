//! The `move` and `rotate` keywords of `region`: a dynamic region displaced by equal-style
//! variables (`move v_x v_y v_z`, NULL for none) and turned by an angle variable (radians)
//! around an axis through a point (`rotate v_theta Px Py Pz Rx Ry Rz`). As LIGGGHTS does,
//! the variables are evaluated at most once per step, and a point is tested by undoing the
//! displacement first and the rotation (around the original point) second.

use crate::engine::error::EngineError;
use crate::util::numbers::numeric;

/// A region's motion and its values at the last evaluation.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// Variables of the x, y, z displacement (length); `None` for NULL or no `move`.
    pub shift: [Option<String>; 3],
    /// Whether `move` was given.
    pub moving: bool,
    /// The rotation: angle variable (radians), point on the axis (length), unit axis.
    pub rotate: Option<(String, [f64; 3], [f64; 3])>,
    /// The displacement at the last evaluation (length).
    pub dx: [f64; 3],
    /// The angle at the last evaluation (radians).
    pub theta: f64,
}

impl Motion {
    /// Parse `move` (3 words) or `rotate` (7 words) at `words[0]` into `self`; returns the
    /// words consumed. `scale` is the lattice scale of the rotation point.
    pub fn parse(
        motion: &mut Option<Motion>,
        words: &[&str],
        scale: [f64; 3],
    ) -> Result<usize, EngineError> {
        let m = motion.get_or_insert_with(|| Motion {
            shift: [None, None, None],
            moving: false,
            rotate: None,
            dx: [0.0; 3],
            theta: 0.0,
        });
        let variable = |w: &str| -> Result<String, EngineError> {
            w.strip_prefix("v_")
                .map(str::to_string)
                .ok_or_else(|| "Illegal region command".into())
        };
        if words[0] == "move" {
            if words.len() < 4 {
                return Err("Illegal region command".into());
            }
            for d in 0..3 {
                if words[1 + d] != "NULL" {
                    m.shift[d] = Some(variable(words[1 + d])?);
                }
            }
            m.moving = true;
            return Ok(4);
        }
        if words.len() < 8 {
            return Err("Illegal region command".into());
        }
        let name = variable(words[1])?;
        let mut v = [0.0; 6];
        for (k, w) in words[2..8].iter().enumerate() {
            v[k] = numeric(w)?;
        }
        let point = [v[0] * scale[0], v[1] * scale[1], v[2] * scale[2]];
        let len = (v[3] * v[3] + v[4] * v[4] + v[5] * v[5]).sqrt();
        if len == 0.0 {
            return Err("Region cannot have 0 length rotation vector".into());
        }
        m.rotate = Some((name, point, [v[3] / len, v[4] / len, v[5] / len]));
        Ok(8)
    }

    /// The variables this motion reads, each with the error LIGGGHTS gives when it is not
    /// equal-style (the x displacement's message differs from the others').
    pub fn variables(&self) -> Vec<(&str, &'static str)> {
        let mut out = Vec::new();
        for (d, s) in self.shift.iter().enumerate() {
            if let Some(n) = s {
                let m = if d == 0 {
                    "Variable for region is invalid style"
                } else {
                    "Variable for region is not equal style"
                };
                out.push((n.as_str(), m));
            }
        }
        if let Some((n, _, _)) = &self.rotate {
            out.push((n.as_str(), "Variable for region is not equal style"));
        }
        out
    }

    /// Evaluate the displacement and angle now.
    pub fn update(
        &mut self,
        equal: &mut dyn FnMut(&str) -> Result<f64, EngineError>,
    ) -> Result<(), EngineError> {
        for d in 0..3 {
            if let Some(n) = &self.shift[d] {
                self.dx[d] = equal(n)?;
            }
        }
        if let Some((n, _, _)) = &self.rotate {
            self.theta = equal(n)?;
        }
        Ok(())
    }

    /// A point of the moved region mapped back into the region's own frame.
    pub fn inverse(&self, x: [f64; 3]) -> [f64; 3] {
        let mut p = x;
        if self.moving {
            for (c, d) in p.iter_mut().zip(&self.dx) {
                *c -= d;
            }
        }
        match &self.rotate {
            Some((_, point, axis)) => turn(p, point, axis, -self.theta),
            None => p,
        }
    }
}

/// `x` turned by `angle` (right-hand rule) around the axis `r` (unit) through `point`.
fn turn(x: [f64; 3], point: &[f64; 3], r: &[f64; 3], angle: f64) -> [f64; 3] {
    let (sine, cosine) = (angle.sin(), angle.cos());
    let d = [x[0] - point[0], x[1] - point[1], x[2] - point[2]];
    let along = d[0] * r[0] + d[1] * r[1] + d[2] * r[2];
    let c = [along * r[0], along * r[1], along * r[2]];
    let a = [d[0] - c[0], d[1] - c[1], d[2] - c[2]];
    let b = [
        r[1] * a[2] - r[2] * a[1],
        r[2] * a[0] - r[0] * a[2],
        r[0] * a[1] - r[1] * a[0],
    ];
    let mut out = [0.0; 3];
    for k in 0..3 {
        out[k] = point[k] + c[k] + (a[k] * cosine + b[k] * sine);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn move_then_rotate_is_undone_in_reverse() {
        let mut m = None;
        Motion::parse(&mut m, &["move", "v_a", "NULL", "NULL"], [1.0; 3]).unwrap();
        Motion::parse(
            &mut m,
            &["rotate", "v_t", "0", "0", "0", "0", "0", "2"],
            [1.0; 3],
        )
        .unwrap();
        let mut m = m.unwrap();
        m.update(&mut |n| {
            Ok(if n == "a" {
                1.0
            } else {
                std::f64::consts::FRAC_PI_2
            })
        })
        .unwrap();
        // (1, 1, 0) minus the shift is (0, 1, 0), turned back a quarter: (1, 0, 0)
        let p = m.inverse([1.0, 1.0, 0.0]);
        assert!((p[0] - 1.0).abs() < 1e-15 && p[1].abs() < 1e-15);
        assert_eq!(
            Motion::parse(
                &mut None,
                &["rotate", "v_t", "0", "0", "0", "0", "0", "0"],
                [1.0; 3]
            ),
            Err("Region cannot have 0 length rotation vector".into())
        );
        assert!(Motion::parse(&mut None, &["move", "1", "NULL", "NULL"], [1.0; 3]).is_err());
    }
}
