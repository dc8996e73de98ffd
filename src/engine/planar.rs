//! LIGGGHTS's 2d runs (`dimension 2`): particles are discs in the xy plane. Their mass is
//! their area times the density, their moment of inertia 0.5 m r^2, and `fix enforce2d`
//! keeps them in the plane.

use crate::engine::particles::Particles;

/// Moment-of-inertia prefactor of a disc (I = 0.5 m r^2), as LIGGGHTS's nve/sphere uses it in 2d.
pub const DISC_INERTIA: f64 = 0.5;

/// Mass of a disc of radius `r` (length) and density `rho` (mass per area), in LIGGGHTS's
/// operation order.
pub fn disc_mass(r: f64, rho: f64) -> f64 {
    std::f64::consts::PI * r * r * rho
}

/// Mass of a particle of radius `r` and density `rho`: a disc in 2d, a sphere in 3d.
pub fn sphere_or_disc_mass(planar: bool, r: f64, rho: f64) -> f64 {
    if planar {
        disc_mass(r, rho)
    } else {
        crate::state::particles::sphere_mass(r, rho)
    }
}

/// `fix enforce2d`: zero the z velocity and force and the x and y angular velocity and
/// torque of the particles in `group`.
pub fn enforce(p: &mut Particles, group: u32) {
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            p.v[i][2] = 0.0;
            p.f[i][2] = 0.0;
        }
    }
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            p.omega[i][0] = 0.0;
            p.omega[i][1] = 0.0;
            p.torque[i][0] = 0.0;
            p.torque[i][1] = 0.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn discs_weigh_their_area() {
        let m = disc_mass(0.004, 2500.0);
        assert!((m - 0.12566370614359174).abs() < 1e-15);
        assert_ne!(sphere_or_disc_mass(false, 0.004, 2500.0), m);
    }

    #[test]
    fn enforce2d_zeroes_out_of_plane_motion() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0; 3], 0.5, 1.0);
        p.v[0] = [1.0, 2.0, 3.0];
        p.f[0] = [1.0, 2.0, 3.0];
        p.omega[0] = [1.0, 2.0, 3.0];
        p.torque[0] = [1.0, 2.0, 3.0];
        p.mask[0] = 1;
        enforce(&mut p, 1);
        assert_eq!(p.v[0], [1.0, 2.0, 0.0]);
        assert_eq!(p.f[0], [1.0, 2.0, 0.0]);
        assert_eq!(p.omega[0], [0.0, 0.0, 3.0]);
        assert_eq!(p.torque[0], [0.0, 0.0, 3.0]);
    }
}

#[cfg(test)]
mod list_tests {
    use crate::engine::domain::{parse_boundary, Boundary, Domain};
    use crate::engine::neighbor::{BinOrder, NeighborList};

    /// A thin periodic-z box of discs at z = 0: the 2d bins (one layer, flat stencil) and
    /// the box without z images let the stencil walk list it, in the sorted build's order
    /// and with no pair across the z faces.
    #[test]
    fn the_2d_stencil_walk_lists_the_plane_in_liggghts_order() {
        let mut domain = Domain::default();
        domain.boundary = parse_boundary(&["p", "f", "p"]).unwrap();
        domain.create([0.0, 0.0, -0.005], [0.2, 0.2, 0.005]);
        let mut r = crate::util::random::RanPark::new(98765).unwrap();
        let x: Vec<[f64; 3]> = (0..300)
            .map(|_| [0.2 * r.uniform(), 0.2 * r.uniform(), 0.0])
            .collect();
        let reach = vec![0.004; x.len()];
        let (skin, cut) = (0.002, 0.01);
        let spatial = BinOrder::new(domain.lo, domain.hi, cut);
        // in 3d the short periodic z needs the general search
        assert!(!NeighborList::default().build_stencil(&x, &reach, skin, &domain, &spatial));
        let mut flat = domain.clone();
        flat.boundary[2] = [Boundary::Fixed; 2];
        let order = spatial.planar();
        let mut walked = NeighborList::default();
        assert!(walked.build_stencil(&x, &reach, skin, &flat, &order));
        let mut sorted = NeighborList::default();
        sorted.build(&x, &reach, skin, &flat, Some(&order));
        let key = |l: &NeighborList| -> Vec<(u32, u32, [f64; 3])> {
            l.pairs.iter().map(|p| (p.i, p.j, p.shift)).collect()
        };
        assert_eq!(key(&walked), key(&sorted));
        assert!(!walked.pairs.is_empty());
        assert!(walked.pairs.iter().all(|p| p.shift[2] == 0.0));
        assert!(walked.pairs.iter().any(|p| p.shift[0] != 0.0));
    }
}
