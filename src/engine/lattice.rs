//! `lattice custom`: a lattice of primitive vectors a1, a2, a3 (lattice units, scaled by
//! the lattice constant) with basis points, mapped to the box as LIGGGHTS 3.8.0 does
//! (x_box = scale * (a1 i + a2 j + a3 k) + spacing * origin, no reorientation), its
//! spacings the extent of the unit cell's eight corners in x, y and z.

use crate::engine::error::EngineError;

/// A custom lattice's geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    /// The lattice constant (length).
    pub scale: f64,
    /// The primitive vectors a1, a2, a3 (lattice units).
    pub a: [[f64; 3]; 3],
    /// The origin shift (fractions of the spacings, each in [0, 1)).
    pub origin: [f64; 3],
    /// Lattice spacings in x, y, z (length).
    pub spacing: [f64; 3],
    /// Inverse of the matrix with a1, a2, a3 as columns.
    inverse: [[f64; 3]; 3],
}

fn cross(x: [f64; 3], y: [f64; 3]) -> [f64; 3] {
    [
        x[1] * y[2] - x[2] * y[1],
        x[2] * y[0] - x[0] * y[2],
        x[0] * y[1] - x[1] * y[0],
    ]
}

impl Cell {
    /// The lattice of constant `scale` (length) and primitive vectors `a`; errors for
    /// collinear or degenerate vectors.
    pub fn new(scale: f64, a: [[f64; 3]; 3], origin: [f64; 3]) -> Result<Cell, EngineError> {
        let dot = |v: [f64; 3]| v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        if dot(cross(a[0], a[1])) == 0.0
            || dot(cross(a[1], a[2])) == 0.0
            || dot(cross(a[0], a[2])) == 0.0
        {
            return Err("Lattice primitive vectors are collinear".into());
        }
        // p[r][c]: row r of the matrix whose columns are a1, a2, a3
        let p = |r: usize, c: usize| a[c][r];
        let det =
            p(0, 0) * p(1, 1) * p(2, 2) + p(0, 1) * p(1, 2) * p(2, 0) + p(0, 2) * p(1, 0) * p(2, 1)
                - p(0, 0) * p(1, 2) * p(2, 1)
                - p(0, 1) * p(1, 0) * p(2, 2)
                - p(0, 2) * p(1, 1) * p(2, 0);
        if det == 0.0 {
            return Err("Degenerate lattice primitive vectors".into());
        }
        let inverse = [
            [
                (p(1, 1) * p(2, 2) - p(1, 2) * p(2, 1)) / det,
                (p(0, 2) * p(2, 1) - p(0, 1) * p(2, 2)) / det,
                (p(0, 1) * p(1, 2) - p(0, 2) * p(1, 1)) / det,
            ],
            [
                (p(1, 2) * p(2, 0) - p(1, 0) * p(2, 2)) / det,
                (p(0, 0) * p(2, 2) - p(0, 2) * p(2, 0)) / det,
                (p(0, 2) * p(1, 0) - p(0, 0) * p(1, 2)) / det,
            ],
            [
                (p(1, 0) * p(2, 1) - p(1, 1) * p(2, 0)) / det,
                (p(0, 1) * p(2, 0) - p(0, 0) * p(2, 1)) / det,
                (p(0, 0) * p(1, 1) - p(0, 1) * p(1, 0)) / det,
            ],
        ];
        let mut cell = Cell {
            scale,
            a,
            origin,
            spacing: [0.0; 3],
            inverse,
        };
        // the unit cell's corners without the origin shift
        let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
        for corner in 0..8 {
            let l = [corner & 1, (corner >> 1) & 1, (corner >> 2) & 1].map(|b| b as f64);
            let x = cell.to_box(l);
            for d in 0..3 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
        cell.spacing = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
        Ok(cell)
    }

    /// Box coordinates (length) of a point in lattice units.
    pub fn to_box(&self, l: [f64; 3]) -> [f64; 3] {
        let v = [0, 1, 2].map(|r| {
            (self.a[0][r] * l[0] + self.a[1][r] * l[1] + self.a[2][r] * l[2]) * self.scale
        });
        // the identity orientation, applied as LIGGGHTS sums it (the signs of zeros follow)
        let mut out = [0.0; 3];
        for (r, o) in out.iter_mut().enumerate() {
            let w = [0, 1, 2].map(|c| if c == r { 1.0 } else { 0.0 });
            *o = w[0] * v[0] + w[1] * v[1] + w[2] * v[2] + self.spacing[r] * self.origin[r];
        }
        out
    }

    /// Lattice coordinates of a box point.
    fn to_lattice(&self, x: [f64; 3]) -> [f64; 3] {
        let s = [0, 1, 2].map(|d| (x[d] - self.spacing[d] * self.origin[d]) / self.scale);
        let m = &self.inverse;
        [0, 1, 2].map(|r| m[r][0] * s[0] + m[r][1] * s[1] + m[r][2] * s[2])
    }

    /// The index ranges (lo, hi, inclusive) of i, j, k that cover the box `lo`..`hi`.
    pub fn ranges(&self, lo: [f64; 3], hi: [f64; 3]) -> [(f64, f64); 3] {
        let (mut mn, mut mx) = ([f64::MAX; 3], [f64::MIN; 3]);
        for corner in 0..8 {
            let x = [0, 1, 2].map(|d| if (corner >> d) & 1 == 1 { hi[d] } else { lo[d] });
            let l = self.to_lattice(x);
            for d in 0..3 {
                mn[d] = mn[d].min(l[d]);
                mx[d] = mx[d].max(l[d]);
            }
        }
        [0, 1, 2].map(|d| {
            let mut l = mn[d].trunc() - 1.0;
            if mn[d] < 0.0 {
                l -= 1.0;
            }
            (l, mx[d].trunc() + 1.0)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spacings_and_errors_as_liggghts() {
        let s3 = 3f64.sqrt();
        let a = [
            [1.0, 0.0, 0.0],
            [0.5, s3 / 2.0, 0.0],
            [0.5, s3 / 6.0, (2.0f64 / 3.0).sqrt()],
        ];
        let c = Cell::new(0.002, a, [0.0; 3]).unwrap();
        // LIGGGHTS prints 0.004 0.0023094 0.00163299
        assert!((c.spacing[0] - 0.004).abs() < 1e-15);
        assert!((c.spacing[1] - 0.0023094).abs() < 1e-8);
        assert!((c.spacing[2] - 0.00163299).abs() < 1e-8);
        let p = c.to_box([1.0, 1.0, 1.0]);
        let back = c.to_lattice(p);
        assert!(back.iter().all(|v| (v - 1.0).abs() < 1e-12));
        let flat = [[1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(
            Cell::new(1.0, flat, [0.0; 3]),
            Err("Lattice primitive vectors are collinear".into())
        );
    }
}
