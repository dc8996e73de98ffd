//! Checks LIGGGHTS makes when a run is set up, beyond the contact models: particles the
//! integrator can move, and neighbour bins that fit the box.

use crate::engine::error::EngineError;
use crate::engine::fixes::FixKind;
use crate::engine::sim::Simulation;
pub use crate::state::limits::{
    allocation, check_ntypes, check_sphere, failed_to_allocate, memory_limit, sphere_mass,
};

/// LIGGGHTS's MAXSMALLINT: the most bins in one direction, or in all.
const MAX_BINS: f64 = 2_147_483_647.0;

/// LIGGGHTS's CUT2BIN_RATIO: the largest cutoff, in bin sizes, it accepts.
const CUT_TO_BIN: f64 = 100.0;

/// LIGGGHTS's neighbour bins for a box of lengths `bbox` and cutoff `cut`: the bins per
/// direction, or its error when the cutoff does not fit the box ("box size << cutoff") or the
/// box holds more bins than an int counts.
pub fn neighbor_bins(bbox: [f64; 3], cut: f64) -> Result<[f64; 3], EngineError> {
    neighbor_bins_sized(bbox, cut, 0.0)
}

/// [`neighbor_bins`] with `neigh_modify binsize` (length; 0 for LIGGGHTS's default of half
/// the cutoff).
pub fn neighbor_bins_sized(bbox: [f64; 3], cut: f64, user: f64) -> Result<[f64; 3], EngineError> {
    let size = if user > 0.0 {
        user
    } else if cut == 0.0 {
        bbox[0]
    } else {
        0.5 * cut
    };
    let inv = 1.0 / size;
    if bbox
        .iter()
        .any(|&b| (b * inv).is_nan() || b * inv > MAX_BINS)
    {
        return Err(format!(
            "Domain too large for neighbor bins (a box of {} by {} by {} in bins of {} makes more than {MAX_BINS} bins in one direction)",
            g(bbox[0]),
            g(bbox[1]),
            g(bbox[2]),
            g(size)
        ).into());
    }
    let mut nbins = [1.0; 3];
    let mut total = 1.0;
    for d in 0..3 {
        nbins[d] = (bbox[d] * inv).trunc().max(1.0);
        let binsize = bbox[d] / nbins[d];
        if size / binsize > CUT_TO_BIN && user > 0.0 {
            return Err(format!(
                "Cannot use neighbor bins - box size << cutoff (neigh_modify binsize {} is more than {CUT_TO_BIN} times the box length {} along {})",
                g(user),
                g(bbox[d]),
                ["x", "y", "z"][d]
            ).into());
        }
        if size / binsize > CUT_TO_BIN {
            return Err(format!(
                "Cannot use neighbor bins - box size << cutoff (the neighbor cutoff {} is more than {} times the box length {} along {})",
                g(cut),
                2.0 * CUT_TO_BIN,
                g(bbox[d]),
                ["x", "y", "z"][d]
            ).into());
        }
        // the bins LIGGGHTS allocates: the box, the ghost cutoff on each side, and one more
        let ghost = (cut / binsize).trunc() + 1.0;
        total *= nbins[d] + 2.0 * ghost + 3.0;
    }
    if total > MAX_BINS {
        let why = if user > 0.0 {
            format!("neigh_modify binsize {}", g(user))
        } else {
            format!("a neighbor cutoff of {}", g(cut))
        };
        return Err(format!(
            "Too many neighbor bins (about {} for {why} in this box)",
            g(total)
        )
        .into());
    }
    Ok(nbins)
}

fn g(x: f64) -> String {
    crate::util::format::g(x)
}

impl Simulation {
    /// LIGGGHTS's check of the atom types in use when the contact models read their
    /// materials (a granular pair style or wall): the smallest type among the particles,
    /// walls, meshes and particle distributions must be 1 (so a run with no particles and
    /// nothing that will insert any fails), the largest at most the box's type count.
    pub fn check_types(&self) -> Result<(), EngineError> {
        let walls = self.fixes.iter().any(|f| f.kind.wall_selection().is_some());
        if self.pair_selection.is_none() && !walls {
            return Ok(());
        }
        let (mut lo, mut hi) = (100_000_u64, 1_u64);
        for &t in &self.particles.kind {
            lo = lo.min(t as u64);
            hi = hi.max(t as u64);
        }
        for f in &self.fixes {
            let types = wall_or_template_types(&f.kind);
            for t in types.into_iter().filter(|&t| t > 0) {
                lo = lo.min(t);
                hi = hi.max(t);
            }
        }
        if lo != 1 {
            return Err("Atom types must start from 1 for granular simulations".into());
        }
        if hi > self.ntypes as u64 {
            return Err("Please increase the number of atom types in the 'create_box' command to match the number of atom types you use in the simulation".into());
        }
        Ok(())
    }

    /// LIGGGHTS's init of the first `fix particletemplate/multisphere`: the templates'
    /// multisphere types (`type MT`) are unique and run from 1 to their count.
    fn check_clump_types(&self) -> Result<(), EngineError> {
        use crate::engine::multisphere::ClumpTemplate;
        let clumps: Vec<(&str, u32)> = self
            .fixes
            .iter()
            .filter_map(|f| Some((f.id.as_str(), f.kind.style_as::<ClumpTemplate>()?)))
            .map(|(id, t)| (id, t.spec.shape_type))
            .collect();
        let Some(&(first, _)) = clumps.first() else {
            return Ok(());
        };
        let fail = |m: &str| -> Result<(), EngineError> {
            Err(format!("Fix particletemplate/multisphere (id {first}): {m}").into())
        };
        let types: Vec<u32> = clumps.iter().map(|c| c.1).collect();
        for (i, t) in types.iter().enumerate() {
            if types[i + 1..].contains(t) {
                return fail("multisphere template types have to be unique");
            }
        }
        let (lo, hi) = (types.iter().min(), types.iter().max());
        if lo != Some(&1) || hi != Some(&(types.len() as u32)) {
            return fail("multisphere template types have to be consecutive starting from 1");
        }
        Ok(())
    }

    /// At a run's init: LIGGGHTS's own checks of the integrated particles (and the checks of
    /// the module fix styles, in fix order) and of the neighbour bins.
    pub fn check_run_init(&self) -> Result<(), EngineError> {
        self.check_types()?;
        self.check_clump_types()?;
        let p = &self.particles;
        for (k, fix) in self.fixes.iter().enumerate() {
            if let FixKind::Style(s) = &fix.kind {
                s.check(p, fix.group, self.dimension)?;
            }
            // LIGGGHTS runs one mesh wall fix (which lists all meshes)
            let other_mesh_wall = || {
                self.fixes
                    .iter()
                    .enumerate()
                    .any(|(j, f)| j != k && f.kind.mesh_wall().is_some())
            };
            // the stress module's init: wear needs its coefficients
            let wears = (fix.kind.mesh())
                .and_then(|m| m.stress.as_ref())
                .is_some_and(|st| st.wear_on);
            if wears && self.property("k_finnie").is_none() {
                return Err(crate::engine::sim::no_k_finnie(&fix.id));
            }
            if fix.kind.mesh_wall().is_some() && other_mesh_wall() {
                return Err(format!(
                    "Fix wall/gran (id {}): More than one wall of type 'mesh' is not supported",
                    fix.id
                )
                .into());
            }
        }
        if self.sort_every > 0 {
            // LIGGGHTS's atom sort bins (half the neighbour cutoff, or the user's size)
            // (LIGGGHTS's cutoff knows the particle templates' sizes before any particle
            // is inserted)
            let size = self.sort_bin_size();
            if size > 0.0 {
                // a single layer of bins in 2d
                let layers = if self.dimension == 2 { 2 } else { 3 };
                let bins: f64 = (0..layers)
                    .map(|d| (self.domain.length(d) / size).trunc().max(1.0))
                    .product();
                if bins.is_nan() || bins > i32::MAX as f64 {
                    return Err(format!(
                        "Too many atom sorting bins (about {} bins of size {}; a larger bin size can be given with atom_modify sort)",
                        g(bins),
                        g(size)
                    ).into());
                }
            }
        }
        self.check_count_computes()?;
        if self.pair_selection.is_some() {
            let bbox = [0, 1, 2].map(|d| self.domain.length(d));
            // LIGGGHTS adds the skin only to a positive contact cutoff: without particle
            // sizes its cutoff is 0 and a single bin spans the box
            let contact = 2.0 * self.largest_radius();
            let cut = if contact > 0.0 {
                contact + self.neighbor.skin
            } else {
                0.0
            };
            neighbor_bins_sized(bbox, cut, self.extras.neigh_binsize)?;
        }
        // the run's setup, after the init checks above: LIGGGHTS's neighbour cutoff is 0
        // without a pair style, and without any particle size (no particles, no
        // distributions); it cannot bin the atoms for sorting then
        let no_cutoff = self.pair_selection.is_none() || self.largest_radius() == 0.0;
        if self.sort_every > 0 && self.sort_binsize <= 0.0 && no_cutoff {
            return Err("Atom sorting has bin size = 0.0".into());
        }
        Ok(())
    }

    /// LIGGGHTS's init checks of the computes, in compute order: each style's `init` hook
    /// (`rdf` and `property/local` need a pair style that supports them).
    fn check_count_computes(&self) -> Result<(), EngineError> {
        for c in &self.computes {
            c.style().init(self)?;
        }
        Ok(())
    }
}

/// The atom types a fix brings into a run: a primitive wall's or a mesh's wall type, a
/// particle distribution's template types (none for other fixes).
fn wall_or_template_types(kind: &FixKind) -> Vec<u64> {
    if let Some(w) = kind.primitive_wall() {
        return vec![w.wall_type as u64];
    }
    if let Some(m) = kind.mesh() {
        return vec![m.wall_type as u64];
    }
    kind.distribution().map_or(Vec::new(), |d| {
        d.templates.iter().map(|t| t.atom_type as u64).collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn liggghts_bin_limits() {
        // a 0.2 x 0.2 x 0.5 box: the cutoff may reach 200 box lengths
        let bbox = [0.2, 0.2, 0.5];
        assert_eq!(neighbor_bins(bbox, 0.022).unwrap(), [18.0, 18.0, 45.0]);
        assert!(neighbor_bins(bbox, 1.02).is_ok());
        for cut in [100.02, 1e10, 1e308, f64::INFINITY] {
            let e = neighbor_bins(bbox, cut).unwrap_err().to_string();
            assert!(
                e.starts_with("Cannot use neighbor bins - box size << cutoff"),
                "{e}"
            );
        }
        let e = neighbor_bins([2e9, 0.2, 0.5], 0.022)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("Domain too large for neighbor bins"), "{e}");
        let e = neighbor_bins([2e5, 2e3, 0.5], 0.022)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("Too many neighbor bins"), "{e}");
        let e = neighbor_bins(bbox, f64::NAN).unwrap_err().to_string();
        assert!(e.starts_with("Domain too large"), "{e}");
    }
}
