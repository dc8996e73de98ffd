//! Insertion into a `mesh/tet` region as LIGGGHTS 3.8.0 does it: the region's volume is the
//! sum of its tetrahedra (no Monte Carlo samples, so no draws), and each random point takes
//! four draws of the region generator: one picks a tetrahedron with probability in
//! proportion to its volume (a bisection of the running volume sums), three give a uniform
//! point in it (a unit cube folded into the unit tetrahedron, as barycentric weights).

use crate::engine::error::EngineError;
use crate::engine::tet_mesh::{signed_volume, TetMesh};
use crate::util::random::RanPark;

/// LIGGGHTS's padding of the (sub-)domain's outer faces when it tests a point (length).
const BORDER: f64 = 1.0e-8;

/// The running sums of the tetrahedra's volumes, in file order, and their total (length^3).
#[derive(Debug, Clone, PartialEq)]
pub struct TetVolumes {
    /// Volume of tetrahedra 0..=i (length^3).
    pub acc: Vec<f64>,
    /// Volume of all of them (length^3).
    pub total: f64,
}

impl TetVolumes {
    /// The sums of `mesh`'s tetrahedra (each with its nodes ordered to a volume >= 0).
    pub fn of(mesh: &TetMesh) -> TetVolumes {
        let mut acc = Vec::with_capacity(mesh.tets.len());
        let mut total = 0.0;
        for n in &mesh.tets {
            total += signed_volume(n[0], n[1], n[2], n[3]);
            acc.push(total);
        }
        TetVolumes { acc, total }
    }

    /// The tetrahedron a draw `rd` in [0, total) falls in, found by LIGGGHTS's bisection
    /// (which gives up with "internal error" where a draw hits a running sum exactly).
    fn pick(&self, rd: f64) -> Result<usize, EngineError> {
        let acc = &self.acc;
        let n = acc.len();
        if n == 0 {
            return Err(internal());
        }
        let (mut i, mut lo, mut hi) = (n / 2, 0usize, n - 1);
        for _ in 0..10000 {
            if rd < acc[i] && (i == 0 || rd > acc[i - 1]) {
                return Ok(i);
            }
            if hi == lo {
                return Err(internal());
            }
            if rd > acc[i] {
                lo = i;
                i = (hi + lo) / 2;
                if i == lo {
                    i += 1;
                }
            } else if i > 0 && rd < acc[i - 1] {
                hi = i;
                i = (hi + lo) / 2;
                if i == lo {
                    i += 1;
                }
                if i == hi && i > 0 {
                    i -= 1;
                }
            } else {
                return Err(internal());
            }
            if i >= n {
                return Err(internal());
            }
        }
        Err(internal())
    }
}

/// LIGGGHTS's message when its tetrahedron search or point loop gives up.
fn internal() -> EngineError {
    EngineError::Invalid("internal error".into())
}

/// A uniform point in tetrahedron `n`: three draws folded into barycentric weights.
fn point_in(n: &[[f64; 3]; 4], rng: &mut RanPark) -> [f64; 3] {
    let mut s = rng.uniform();
    let mut t = rng.uniform();
    let mut u = rng.uniform();
    if s + t > 1.0 {
        s = 1.0 - s;
        t = 1.0 - t;
    }
    if t + u > 1.0 {
        let keep = u;
        u = 1.0 - s - t;
        t = 1.0 - keep;
    } else if s + t + u > 1.0 {
        let keep = u;
        u = s + t + u - 1.0;
        s = 1.0 - t - keep;
    }
    let b = [1.0 - s - t - u, s, t, u];
    std::array::from_fn(|d| b[0] * n[0][d] + b[1] * n[1][d] + b[2] * n[2][d] + b[3] * n[3][d])
}

/// Whether `x` lies in the box `lo`..`hi` padded as LIGGGHTS pads a one-process sub-domain.
fn in_subdomain(x: [f64; 3], lo: [f64; 3], hi: [f64; 3]) -> bool {
    (0..3).all(|d| x[d] >= lo[d] - BORDER && x[d] < hi[d] + BORDER)
}

/// A random point of the region (the box `lo`..`hi`): a tetrahedron by volume, a point in it,
/// again while the point misses the box (10 000 tries at most).
pub fn random_point(
    mesh: &TetMesh,
    vols: &TetVolumes,
    rng: &mut RanPark,
    lo: [f64; 3],
    hi: [f64; 3],
) -> Result<[f64; 3], EngineError> {
    for _ in 0..9999 {
        let k = vols.pick(vols.total * rng.uniform())?;
        let p = point_in(&mesh.tets[k], rng);
        if p == [0.0; 3] {
            return Err("illegal RegTetMesh::mesh_randpos".into());
        }
        if in_subdomain(p, lo, hi) {
            return Ok(p);
        }
    }
    Err(internal())
}

/// The region's volume as LIGGGHTS's insertion fixes measure it: (whole, this process's
/// share), from the tetrahedra's volumes and where their nodes and centres lie in the box
/// `lo`..`hi` (length^3), with LIGGGHTS's refusals.
pub fn region_volume(
    mesh: &TetMesh,
    vols: &TetVolumes,
    lo: [f64; 3],
    hi: [f64; 3],
) -> Result<(f64, f64), EngineError> {
    if vols.total == 0.0 {
        return Err("mesh/tet region has zero volume, cannot continue".into());
    }
    let mut local = 0.0;
    for n in &mesh.tets {
        let v = signed_volume(n[0], n[1], n[2], n[3]);
        let centre: [f64; 3] =
            std::array::from_fn(|d| (((0.0 + n[0][d]) + n[1][d]) + n[2][d] + n[3][d]) / 4.0);
        for (k, p) in n.iter().chain(std::iter::once(&centre)).enumerate() {
            let weight = if k < 4 { v * 0.1 } else { v * 0.6 };
            if !(0..3).all(|d| p[d] >= lo[d] && p[d] <= hi[d]) {
                return Err("mesh point outside simulation domain".into());
            }
            if in_subdomain(*p, lo, hi) {
                local += weight;
            }
        }
    }
    if local < 1e-13 {
        return Err("Unable to calculate region volume - are you operating on a 2d region?".into());
    }
    // one process holds the whole: its share is rescaled by the sum of all shares (itself)
    Ok((vols.total, local * (vols.total / local)))
}

/// LIGGGHTS's refusal when an insertion with overlap checks meets a particle outside a
/// `side in` tet region (inside a `side out` one): it asks the region for the particle's
/// distance to its surface, which tet regions do not answer.
pub const NO_SURFACE: &str = "This feature is not available for tet mesh regions";

/// LIGGGHTS's refusal to insert into a `side out` tet region.
pub const SIDE_OUT: &str =
    "Impossible to generate random points on tet mesh region with side = out";

impl super::InsertPack {
    /// What the first run's setup of an insertion into a tet region would refuse (a dry run
    /// checks it without drawing): a flat region, a node outside the box `lo`..`hi`, a share
    /// larger than the whole.
    pub fn check_tet_region(
        &self,
        regions: &crate::engine::region::Regions,
        lo: [f64; 3],
        hi: [f64; 3],
    ) -> Result<(), EngineError> {
        let crate::engine::region::Shape::TetMesh(mesh) = &regions.list[self.region].shape else {
            return Ok(());
        };
        if self.set_up {
            return Ok(());
        }
        let vols = TetVolumes::of(mesh);
        let (whole, local) = region_volume(mesh, &vols, lo, hi)?;
        if self.rate.is_some() && local > whole + f64::EPSILON {
            return Err("Fix insert: Region volume calculation with MC failed".into());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_corner(scale: f64) -> TetMesh {
        let o = [0.0; 3];
        let tet = |k: f64| {
            [
                [k, 0.0, 0.0],
                [k + scale, 0.0, 0.0],
                [k, scale, 0.0],
                [k, 0.0, scale],
            ]
        };
        let mut t0 = tet(0.0);
        t0[0] = o;
        let mut tets = vec![t0, tet(2.0), tet(4.0)];
        for n in &mut tets {
            if signed_volume(n[0], n[1], n[2], n[3]) < 0.0 {
                n.swap(0, 3);
            }
        }
        TetMesh {
            tets,
            lo: [0.0; 3],
            hi: [4.0 + scale, scale, scale],
        }
    }

    #[test]
    fn volumes_add_up_and_points_land_in_tetrahedra_by_volume() {
        let m = cube_corner(1.0);
        let v = TetVolumes::of(&m);
        assert_eq!(v.acc.len(), 3);
        assert!((v.total - 0.5).abs() < 1e-15, "{}", v.total);
        let mut rng = RanPark::new(12345).unwrap();
        let mut per = [0usize; 3];
        for _ in 0..3000 {
            let p = random_point(&m, &v, &mut rng, [-1.0; 3], [6.0; 3]).unwrap();
            let k = (p[0] / 2.0) as usize;
            assert!(m.inside(p), "{p:?}");
            per[k] += 1;
        }
        // equal volumes: about 1000 each
        assert!(per.iter().all(|&c| (850..1150).contains(&c)), "{per:?}");
        // every draw a search can meet finds its tetrahedron, ends included
        assert_eq!(v.pick(0.0).unwrap(), 0);
        assert_eq!(v.pick(v.total * 0.999_999).unwrap(), 2);
        assert_eq!(v.pick(v.acc[0] * 1.000_001).unwrap(), 1);
    }

    #[test]
    fn flat_regions_are_refused_with_liggghts_message() {
        let m = cube_corner(0.0);
        let v = TetVolumes::of(&m);
        let e = region_volume(&m, &v, [-1.0; 3], [6.0; 3]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "mesh/tet region has zero volume, cannot continue"
        );
        let m = cube_corner(1.0);
        let v = TetVolumes::of(&m);
        let (whole, local) = region_volume(&m, &v, [-1.0; 3], [6.0; 3]).unwrap();
        assert_eq!(whole, v.total);
        assert!((local - whole).abs() <= 1e-15);
        let e = region_volume(&m, &v, [-1.0; 3], [3.0; 3]).unwrap_err();
        assert_eq!(e.to_string(), "mesh point outside simulation domain");
    }
}
