//! `orientation random` of inserted particles: LIGGGHTS's random unit quaternion (three
//! draws from the insertion fix's generator) and its rotation of a clump's principal axes
//! by quaternion products, in LIGGGHTS's order of operations.

use crate::util::random::RanPark;

/// Principal axes of a clump in the space frame (unit vectors).
pub type Axes = [[f64; 3]; 3];

/// A random unit quaternion (w, x, y, z) from three uniform draws.
pub fn random_unit_quat(rng: &mut RanPark) -> [f64; 4] {
    let u1 = rng.uniform();
    let u2 = rng.uniform();
    let u3 = rng.uniform();
    let h1 = (1.0 - u1).sqrt();
    let h2 = u1.sqrt();
    let tau = 2.0 * std::f64::consts::PI;
    [
        h1 * (tau * u2).sin(),
        h1 * (tau * u2).cos(),
        h2 * (tau * u3).sin(),
        h2 * (tau * u3).cos(),
    ]
}

/// The quaternion product a b.
fn product(a: &[f64; 4], b: &[f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + b[0] * a[1] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] + b[0] * a[2] + a[3] * b[1] - a[1] * b[3],
        a[0] * b[3] + b[0] * a[3] + a[1] * b[2] - a[2] * b[1],
    ]
}

/// `v` rotated by the quaternion `q` as q (0, v) q*.
pub fn rotate(v: &[f64; 3], q: &[f64; 4]) -> [f64; 3] {
    let t = product(q, &[0.0, v[0], v[1], v[2]]);
    let r = product(&t, &[q[0], -q[1], -q[2], -q[3]]);
    [r[1], r[2], r[3]]
}

/// Each axis rotated by `q`.
pub fn rotate_axes(axes: &Axes, q: &[f64; 4]) -> Axes {
    [
        rotate(&axes[0], q),
        rotate(&axes[1], q),
        rotate(&axes[2], q),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_random_rotation_keeps_the_axes_orthonormal() {
        let mut rng = RanPark::new(12345).unwrap();
        let q = random_unit_quat(&mut rng);
        let n: f64 = q.iter().map(|c| c * c).sum();
        assert!((n - 1.0).abs() < 1e-15);
        let a = rotate_axes(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], &q);
        let dot = |u: &[f64; 3], v: &[f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        for i in 0..3 {
            assert!((dot(&a[i], &a[i]) - 1.0).abs() < 1e-14);
            assert!(dot(&a[i], &a[(i + 1) % 3]).abs() < 1e-14);
        }
        // right-handed: ex x ey = ez
        let c = [
            a[0][1] * a[1][2] - a[0][2] * a[1][1],
            a[0][2] * a[1][0] - a[0][0] * a[1][2],
            a[0][0] * a[1][1] - a[0][1] * a[1][0],
        ];
        assert!((dot(&c, &a[2]) - 1.0).abs() < 1e-14);
        assert_ne!(a[0], [1.0, 0.0, 0.0]);
    }
}
