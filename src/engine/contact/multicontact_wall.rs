//! `fix wall/gran ... surface multicontact`: the wall side of the multiple-contact model
//! ([`super::multicontact`]), as LIGGGHTS 3.8.0 keeps it.
//!
//! A wall contact keeps four history values before the other models' ([`WALL_HISTORY`]):
//! where the contact surface lies relative to the particle's centre and the normal force
//! of the last evaluation. `fix multicontact/halfspace` reads them before the next force
//! evaluation as one more contact of the particle, and the wall loop gives the particle
//! its radius plus the change found there. A wall contact is visited while the particle
//! is apart by less than its radius (the contact distance factor 2 less one); apart, it
//! keeps the surface at the changed radius towards the wall and no force.

use super::Vec3;

/// History values the surface model keeps per wall contact (`surfPos` x, y, z and `fn`).
pub const WALL_HISTORY: usize = 4;

/// The wall contacts a multicontact wall visits: apart by less than this many (unchanged)
/// radii (LIGGGHTS's contact distance factor less one).
pub const WALL_REACH: f64 = super::multicontact::CONTACT_DISTANCE_FACTOR - 1.0;

/// A touching contact's surface values: `to_wall` (m), the vector from the centre to the
/// closest wall point, and the normal component `|f . en|` (N) of the contact's force `f`.
pub fn touching(h: &mut [f64], to_wall: Vec3, f: Vec3, en: Vec3) {
    h[..3].copy_from_slice(&to_wall);
    h[3] = (f[0] * en[0] + f[1] * en[1] + f[2] * en[2]).abs();
}

/// A contact apart but visited: the surface at `radius` (m, the changed radius) along
/// `to_wall`, no force.
pub fn apart(h: &mut [f64], to_wall: Vec3, radius: f64) {
    let len = (to_wall[0] * to_wall[0] + to_wall[1] * to_wall[1] + to_wall[2] * to_wall[2]).sqrt();
    // LIGGGHTS scales the wall-to-centre vector by -radius / |delta|
    let rinv = if len > 1e-15 { -1.0 / len } else { 0.0 };
    for d in 0..3 {
        h[d] = -to_wall[d] * radius * rinv;
    }
    h[3] = 0.0;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn surfaces_of_wall_contacts() {
        let mut h = [9.0; 6];
        touching(&mut h, [0.0, 0.0, -0.004], [0.3, 0.0, 2.0], [0.0, 0.0, 1.0]);
        assert_eq!(&h[..4], &[0.0, 0.0, -0.004, 2.0]);
        apart(&mut h, [0.0, 0.0, -0.006], 0.005);
        assert_eq!(&h[..4], &[0.0, 0.0, -0.005, 0.0]);
        assert_eq!(h[4], 9.0, "the other models' values are theirs");
        apart(&mut h, [0.0; 3], 0.005);
        assert_eq!(&h[..4], &[0.0; 4]);
    }
}
