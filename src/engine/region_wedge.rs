//! `region ID wedge axis x|y|z center C1 C2 radius R bounds LO HI angle0 A0 angle DA`: the
//! part of a cylinder between two half-planes through its axis, starting at angle A0 and
//! spanning DA degrees (LIGGGHTS 3.8.0's region style, its words, checks and inside test).

use crate::engine::error::EngineError;
use crate::engine::region::{Region, RegionContext, Regions, Shape};
use crate::util::numbers::c_atof;

/// A wedge's geometry (lengths in box units, angles in radians).
#[derive(Debug, Clone, PartialEq)]
pub struct Wedge {
    /// The cylinder's axis (0, 1, 2).
    pub axis: usize,
    /// The axis's position in the first and second cross coordinates (for axis x: y, z;
    /// y: z, x; z: x, y).
    pub c1: f64,
    /// See [`Wedge::c1`].
    pub c2: f64,
    /// The cylinder's radius.
    pub radius: f64,
    /// The flat faces' positions along the axis.
    pub lo: f64,
    /// See [`Wedge::lo`].
    pub hi: f64,
    /// The opening angle (radians).
    pub dang: f64,
    /// Outward normal of the starting face in the cross plane.
    pub normal1: [f64; 2],
    /// Outward normal of the ending face in the cross plane.
    pub normal2: [f64; 2],
    /// Bounds of a `side in` wedge (lower and upper corner).
    pub bounds: Option<([f64; 3], [f64; 3])>,
}

impl Wedge {
    /// The position along the axis and the offset from the axis in the cross plane.
    fn local(&self, x: [f64; 3]) -> (f64, [f64; 2]) {
        match self.axis {
            0 => (x[0], [x[1] - self.c1, x[2] - self.c2]),
            1 => (x[1], [x[2] - self.c1, x[0] - self.c2]),
            _ => (x[2], [x[0] - self.c1, x[1] - self.c2]),
        }
    }

    /// Inside or on the surface (LIGGGHTS's `RegWedge::inside`).
    pub fn inside(&self, x: [f64; 3]) -> bool {
        let (along, del) = self.local(x);
        if along < self.lo || along > self.hi {
            return false;
        }
        if del[0] * del[0] + del[1] * del[1] > self.radius * self.radius {
            return false;
        }
        let sp1 = self.normal1[0] * del[0] + self.normal1[1] * del[1];
        let sp2 = self.normal2[0] * del[0] + self.normal2[1] * del[1];
        if self.dang <= std::f64::consts::PI {
            !(sp1 > 0.0 || sp2 > 0.0)
        } else {
            !(sp1 > 0.0 && sp2 > 0.0)
        }
    }
}

/// The bounding box LIGGGHTS gives a `side in` wedge: the axis, the two faces' rims and
/// every multiple of 90 degrees between them.
fn bounds(w: &Wedge, angle1: f64) -> ([f64; 3], [f64; 3]) {
    let half_pi = std::f64::consts::FRAC_PI_2;
    let angle2 = angle1 + w.dang;
    let (mut amin, mut amax, mut bmin, mut bmax) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for a in [angle1, angle2] {
        amin = amin.min(a.cos());
        amax = amax.max(a.cos());
        bmin = bmin.min(a.sin());
        bmax = bmax.max(a.sin());
    }
    let mut n: i64 = 0;
    while n as f64 * half_pi > angle1 {
        n -= 1;
    }
    for _ in 0..3 {
        let phi = n as f64 * half_pi;
        if angle1 <= phi && phi <= angle1 + w.dang {
            amin = amin.min(phi.cos());
            amax = amax.max(phi.cos());
            bmin = bmin.min(phi.sin());
            bmax = bmax.max(phi.sin());
        }
        // LIGGGHTS adds 90 degrees in radians to the integer count (truncated towards 0)
        n = (n as f64 + half_pi) as i64;
    }
    let r = w.radius;
    let (amin, amax, bmin, bmax) = (amin * r, amax * r, bmin * r, bmax * r);
    match w.axis {
        0 => (
            [w.lo, w.c1 + amin, w.c2 + bmin],
            [w.hi, w.c1 + amax, w.c2 + bmax],
        ),
        1 => (
            [w.c1 + bmin, w.lo, w.c2 + amin],
            [w.c1 + bmax, w.hi, w.c2 + amax],
        ),
        _ => (
            [w.c1 + amin, w.c2 + bmin, w.lo],
            [w.c1 + amax, w.c2 + bmax, w.hi],
        ),
    }
}

impl Regions {
    /// Is region `index` a wedge or built from one (intersections and unions)?
    pub fn has_wedge(&self, index: usize) -> bool {
        match &self.list[index].shape {
            Shape::Wedge(_) => true,
            Shape::Intersect(m) | Shape::Union(m) => m.iter().any(|&k| self.has_wedge(k)),
            _ => false,
        }
    }

    /// LIGGGHTS's insertion into a wedge asks for the surface distance of every particle
    /// the region does not hold, which its wedge does not implement (an error); in a
    /// periodic box it asks for periodic images too, which regolith cannot list as LIGGGHTS
    /// does.
    pub fn wedge_insert_check(
        &self,
        index: usize,
        x: &[[f64; 3]],
        periodic: [bool; 3],
    ) -> Result<(), EngineError> {
        if !self.has_wedge(index) || x.is_empty() {
            return Ok(());
        }
        if x.iter().any(|&p| !self.matches(index, p)) {
            return Err("surface_exterior not implemented".into());
        }
        if periodic.iter().any(|&p| p) {
            return Err(EngineError::Unsupported(
                "fix insert/pack overlap checks in a wedge region of a periodic box".into(),
            ));
        }
        Ok(())
    }

    /// `region ID wedge ...` (`args` excludes the command name), with LIGGGHTS's checks.
    pub fn define_wedge(&mut self, args: &[&str], ctx: RegionContext) -> Result<(), EngineError> {
        if args.len() < 16 {
            return Err("Illegal region wegde command, not enough arguments".into());
        }
        let id = args[0];
        if self.find(id).is_some() {
            return Err("Reuse of region ID".into());
        }
        let (interior, scale, motion) = crate::engine::region::options(&args[16..], ctx)?;
        let expect = |k: usize, word: &str| -> Result<(), EngineError> {
            if args[k] == word {
                Ok(())
            } else {
                Err(format!("Illegal region wegde command, expecting keyword '{word}'").into())
            }
        };
        expect(2, "axis")?;
        // LIGGGHTS reads the axis's first letter
        let axis = match args[3].chars().next() {
            Some('x') => 0,
            Some('y') => 1,
            Some('z') => 2,
            _ => return Err("Illegal region wedge command, expecting 'x', 'y', or 'z'".into()),
        };
        expect(4, "center")?;
        // the scales LIGGGHTS applies to (c1, c2, radius) for each axis
        let (s1, s2) = match axis {
            0 => (scale[1], scale[2]),
            1 => (scale[0], scale[2]),
            _ => (scale[0], scale[1]),
        };
        let c1 = s1 * c_atof(args[5]);
        let c2 = s2 * c_atof(args[6]);
        expect(7, "radius")?;
        let radius = s1 * c_atof(args[8]);
        expect(9, "bounds")?;
        let bound = |w: &str, lo_side: bool| -> Result<f64, EngineError> {
            if let Some(b) = ctx.inf_or_edge(w, axis, lo_side)? {
                return Ok(b);
            }
            Ok(scale[axis] * c_atof(w))
        };
        let lo = bound(args[10], true)?;
        let hi = bound(args[11], false)?;
        expect(12, "angle0")?;
        let angle1 = c_atof(args[13]) * std::f64::consts::PI / 180.0;
        expect(14, "angle")?;
        let dang = c_atof(args[15]) * std::f64::consts::PI / 180.0;
        if radius <= 0.0 {
            return Err("Illegal region cylinder command".into());
        }
        if dang < 5.0 * std::f64::consts::PI / 180.0 {
            return Err("Wedge too flat. Wedge-angle has to be >= 5.0 degrees".into());
        }
        let angle2 = angle1 + dang;
        let mut wedge = Wedge {
            axis,
            c1,
            c2,
            radius,
            lo,
            hi,
            dang,
            normal1: [angle1.sin(), -angle1.cos()],
            normal2: [-angle2.sin(), angle2.cos()],
            bounds: None,
        };
        if interior {
            wedge.bounds = Some(bounds(&wedge, angle1));
        }
        self.list.push(Region {
            id: id.to_string(),
            style: "wedge".to_string(),
            shape: Shape::Wedge(Box::new(wedge)),
            interior,
            radius_variable: None,
            shaped_at: None,
            motion,
        });
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ctx() -> RegionContext {
        RegionContext {
            bounds: Some(([0.0; 3], [10.0; 3])),
            lattice: None,
        }
    }

    fn define(words: &str) -> Result<Regions, EngineError> {
        let mut r = Regions::default();
        let w: Vec<&str> = words.split_whitespace().collect();
        r.define_wedge(&w, ctx())?;
        Ok(r)
    }

    #[test]
    fn quarter_wedge_along_y() {
        // axis y: c1 is the z coordinate of the axis, c2 the x coordinate; angles from z
        let r =
            define("w wedge axis y center 5 5 radius 3 bounds 0 EDGE angle0 0 angle 90").unwrap();
        assert!(r.matches(0, [6.0, 9.0, 6.0]));
        assert!(!r.matches(0, [4.0, 9.0, 6.0]));
        assert!(!r.matches(0, [6.0, 9.0, 4.0]));
        assert!(!r.matches(0, [7.5, 5.0, 7.5]));
        let Shape::Wedge(w) = &r.list[0].shape else {
            panic!("a wedge")
        };
        let (lo, hi) = w.bounds.unwrap();
        assert_eq!((lo[1], hi[1]), (0.0, 10.0));
        assert!((lo[0] - 5.0).abs() < 1e-12 && (hi[0] - 8.0).abs() < 1e-12);
        assert!((lo[2] - 5.0).abs() < 1e-12 && (hi[2] - 8.0).abs() < 1e-12);
    }

    #[test]
    fn wide_wedge_and_errors() {
        let r =
            define("w wedge axis z center 0 0 radius 2 bounds -1 1 angle0 -45 angle 270 side out")
                .unwrap();
        // 270 degrees from -45: everything but the quadrant around -90 degrees... inverted
        assert!(!r.matches(0, [1.0, 0.0, 0.0]));
        assert!(r.matches(0, [0.0, -1.0, 0.0]));
        assert!(r.matches(0, [3.0, 0.0, 0.0]));
        assert_eq!(
            define("w wedge axis z center 0 0 radius 2 bounds -1 1 angle0 0 angle 4").unwrap_err(),
            EngineError::Invalid("Wedge too flat. Wedge-angle has to be >= 5.0 degrees".into())
        );
        assert!(
            define("w wedge axis q center 0 0 radius 2 bounds -1 1 angle0 0 angle 40").is_err()
        );
        assert!(
            define("w wedge axis z centre 0 0 radius 2 bounds -1 1 angle0 0 angle 40").is_err()
        );
        assert!(
            define("w wedge axis z center 0 0 radius 0 bounds -1 1 angle0 0 angle 40").is_err()
        );
        assert!(define("w wedge axis z center 0 0 radius 1 bounds -1 1 angle0 0").is_err());
    }
}
