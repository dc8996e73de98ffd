//! `surface multicontact` with `fix multicontact/halfspace`: the multiple-contact model of
//! Brodu, Dijksman and Behringer (Phys. Rev. E 91, 032201, 2015) as LIGGGHTS 3.8.0 runs it.
//!
//! A particle pressed at several contacts deforms as an elastic half space: each contact's
//! normal force moves the surface at the particle's other contacts. Before the forces of a
//! step, every particle's contacts are gathered ([`Entry`], LIGGGHTS's `contactproperty/atom`
//! data): where the contact surface lies relative to the centre and the normal force the
//! contact carried at its last evaluation. From them each contact gets a radius change
//! ([`radius_changes`]) that the pair loop adds to the particle's radius for that contact
//! alone.
//!
//! The surface model itself has the kinematics of `surface default`; it keeps per pair
//! contact three history values before the other models' (`radij`, `radji`, `fn`, see
//! [`PAIR_HISTORY`]): i's radius as the pair loop passes it (LIGGGHTS keeps the unchanged
//! one there), j's changed radius and the normal component of the force on i. Pairs apart
//! by less than [`CONTACT_DISTANCE_FACTOR`] times their (changed) radius sum store both
//! radii and a zero force.

use super::Vec3;

/// LIGGGHTS's contact distance factor of the model: pairs are listed and visited while
/// apart by less than twice the sum of their radii.
pub const CONTACT_DISTANCE_FACTOR: f64 = 2.0;

/// History values the surface model keeps per pair contact (`radij`, `radji`, `fn`).
pub const PAIR_HISTORY: usize = 3;

/// `fix multicontact/halfspace`'s default `geometric_prefactor`.
pub const DEFAULT_PREFACTOR: f64 = 1.125;

/// One contact of a particle as the fix gathers it: the contact surface's position
/// relative to the particle's centre (m) and the normal force (N); after
/// [`radius_changes`], the radius change (m) in place of the force.
pub type Entry = [f64; 4];

/// The elastic constants of the half-space model for one particle type.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HalfSpace {
    /// `-(1 + nu) gamma / (2 pi Y)` (m/N).
    pub c1: f64,
    /// `3 - 4 nu`.
    pub c2: f64,
    /// `1 - 2 nu`.
    pub c3: f64,
    /// Young's modulus Y (Pa), for the force threshold.
    pub youngs: f64,
}

impl HalfSpace {
    /// The constants for Young's modulus `y` (Pa), Poisson ratio `nu` and the geometric
    /// prefactor `gamma`, as LIGGGHTS forms them.
    pub fn new(y: f64, nu: f64, gamma: f64) -> Self {
        HalfSpace {
            c1: -(1.0 + nu) / (2.0 * std::f64::consts::PI * y) * gamma,
            c2: 3.0 - 4.0 * nu,
            c3: 1.0 - 2.0 * nu,
            youngs: y,
        }
    }

    /// Forces at or below this (N) count as no contact: `Y r^2 1e-14` for a particle of
    /// radius `r` (m).
    pub fn force_eps(&self, r: f64) -> f64 {
        self.youngs * r * r * 1e-14
    }
}

fn dot(a: &Vec3, b: &[f64]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The contact surface of a listed pair from its history `[radij, radji, fn]`, relative to
/// i and to j: the midpoint of the two surfaces along the centre line when the pair carried
/// a force above `f_eps` (N), else each surface at its stored radius. `xij` is `x_j - x_i`.
pub fn pair_surfaces(xij: Vec3, hist: &[f64], f_eps: f64) -> (Vec3, Vec3) {
    let len = (xij[0] * xij[0] + xij[1] * xij[1] + xij[2] * xij[2]).sqrt();
    if hist[2] > f_eps {
        let s = (hist[0] - hist[1]) * 0.5 / len;
        let tmp = [xij[0] * s, xij[1] * s, xij[2] * s];
        let ij = std::array::from_fn(|d| tmp[d] + 0.5 * xij[d]);
        let ji = std::array::from_fn(|d| tmp[d] + -0.5 * xij[d]);
        (ij, ji)
    } else {
        let a = hist[0] / len;
        let b = -hist[1] / len;
        (xij.map(|v| v * a), xij.map(|v| v * b))
    }
}

/// One particle's radius change at each of its contacts (in place of the force in
/// `entries[k][3]`): every pair of contacts (ij before ik) with a force above `f_eps` (N)
/// changes the other one's radius by the half-space displacement, summed in LIGGGHTS's
/// order. `r` is the particle's radius (m).
// negated comparisons keep LIGGGHTS's tests for NaN
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub fn radius_changes(entries: &mut [Entry], hs: &HalfSpace, r: f64, f_eps: f64) {
    let n = entries.len();
    let inv: Vec<f64> = entries
        .iter()
        .map(|e| {
            1.0 / (e[0] * e[0] + e[1] * e[1] + e[2] * e[2])
                .sqrt()
                .max(1e-6 * r)
        })
        .collect();
    let mut delta = vec![0.0; n];
    for a in 0..n.saturating_sub(1) {
        for b in a + 1..n {
            let (sa, sb) = (&entries[a], &entries[b]);
            let (f_ij, f_ik) = (sa[3], sb[3]);
            if !(f_ij > f_eps || f_ik > f_eps) {
                continue;
            }
            let ukc = [sa[0] - sb[0], sa[1] - sb[1], sa[2] - sb[2]];
            let inv_dkc = 1.0 / (ukc[0] * ukc[0] + ukc[1] * ukc[1] + ukc[2] * ukc[2]).sqrt();
            if !(inv_dkc < 1e10) {
                continue;
            }
            let nk_dot_nc = dot(&[sa[0], sa[1], sa[2]], &sb[..3]) * inv[a] * inv[b];
            let ukc_dot_nc = -dot(&ukc, &sa[..3]) * inv[a] * inv_dkc;
            let ukc_dot_nk = -dot(&ukc, &sb[..3]) * inv[b] * inv_dkc;
            let careful = hs.c2 * nk_dot_nc + ukc_dot_nk * ukc_dot_nc;
            if f_ik > f_eps {
                let mut c3term = 0.0;
                if hs.c3.abs() > 1e-6 {
                    let divisor = 1.0 + ukc_dot_nk;
                    if divisor > 1e-6 {
                        c3term = -hs.c3 * (nk_dot_nc + ukc_dot_nc) / divisor;
                    }
                }
                delta[a] += hs.c1 * f_ik * (careful + c3term) * inv_dkc;
            }
            if f_ij > f_eps {
                let mut c3term = 0.0;
                if hs.c3.abs() > 1e-6 {
                    let divisor = 1.0 - ukc_dot_nc;
                    if divisor > 1e-6 {
                        c3term = -hs.c3 * (nk_dot_nc - ukc_dot_nk) / divisor;
                    }
                }
                delta[b] += hs.c1 * f_ij * (careful + c3term) * inv_dkc;
            }
        }
    }
    for (e, d) in entries.iter_mut().zip(delta) {
        e[3] = d;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_loaded_contact_moves_the_surface_at_the_opposite_one() {
        // a sphere of radius 1 pressed at +x (1 N) and touched at -x without force
        let hs = HalfSpace::new(1e4, 0.25, 1.125);
        let mut e = [[1.0, 0.0, 0.0, 1.0], [-1.0, 0.0, 0.0, 0.0]];
        radius_changes(&mut e, &hs, 1.0, hs.force_eps(1.0));
        // d = 2, n_k . n_c = -1, u_kc . n_c = -1 ... the opposite contact: careful = -c2 + 1
        // (u . n_k = 1, u . n_c = -1), c3 term: divisor 1 - (-1) = 2, -(c3)(-1 - 1)/2 = c3
        let c1 = -(1.25) / (2.0 * std::f64::consts::PI * 1e4) * 1.125;
        let want = c1 * 1.0 * (-(3.0 - 1.0) + -1.0 + 0.5) * 0.5;
        assert!((e[1][3] - want).abs() < 1e-18, "{} {}", e[1][3], want);
        // the loaded contact feels nothing from the unloaded one
        assert_eq!(e[0][3], 0.0);
        assert!(e[1][3] > 0.0, "pressing one side pushes the other side out");
    }

    #[test]
    fn surfaces_of_a_loaded_pair_meet_midway() {
        let (ij, ji) = pair_surfaces([2.0, 0.0, 0.0], &[1.2, 1.0, 5.0], 0.0);
        assert_eq!(ij, [1.1, 0.0, 0.0]);
        assert_eq!(ji, [-0.9, 0.0, 0.0]);
        let (ij, ji) = pair_surfaces([2.0, 0.0, 0.0], &[1.2, 1.0, 0.0], 0.0);
        assert_eq!(ij, [1.2, 0.0, 0.0]);
        assert_eq!(ji, [-1.0, 0.0, 0.0]);
    }
}
