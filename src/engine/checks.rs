//! Checks LIGGGHTS makes when a run is set up, beyond the contact models: particles the
//! integrator can move, and neighbour bins that fit the box.

use crate::engine::fixes::FixKind;
use crate::engine::sim::Simulation;

/// LIGGGHTS's MAXSMALLINT: the most bins in one direction, or in all.
const MAX_BINS: f64 = 2_147_483_647.0;

/// LIGGGHTS's CUT2BIN_RATIO: the largest cutoff, in bin sizes, it accepts.
const CUT_TO_BIN: f64 = 100.0;

/// LIGGGHTS's neighbour bins for a box of lengths `bbox` and cutoff `cut`: the bins per
/// direction, or its error when the cutoff does not fit the box ("box size << cutoff") or the
/// box holds more bins than an int counts.
pub fn neighbor_bins(bbox: [f64; 3], cut: f64) -> Result<[f64; 3], String> {
    neighbor_bins_sized(bbox, cut, 0.0)
}

/// [`neighbor_bins`] with `neigh_modify binsize` (length; 0 for LIGGGHTS's default of half
/// the cutoff).
pub fn neighbor_bins_sized(bbox: [f64; 3], cut: f64, user: f64) -> Result<[f64; 3], String> {
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
        ));
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
            ));
        }
        if size / binsize > CUT_TO_BIN {
            return Err(format!(
                "Cannot use neighbor bins - box size << cutoff (the neighbor cutoff {} is more than {} times the box length {} along {})",
                g(cut),
                2.0 * CUT_TO_BIN,
                g(bbox[d]),
                ["x", "y", "z"][d]
            ));
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
        ));
    }
    Ok(nbins)
}

/// The most bytes this process can hope to get: what its address-space limit (`ulimit -v`)
/// leaves when one is set, and never more than the machine's physical memory.
pub fn memory_limit() -> f64 {
    let mut limit = f64::INFINITY;
    // SAFETY: getrlimit and sysinfo only write into the structs passed to them
    unsafe {
        let mut r: libc::rlimit = std::mem::zeroed();
        if libc::getrlimit(libc::RLIMIT_AS, &mut r) == 0 && r.rlim_cur != libc::RLIM_INFINITY {
            // the address space already in use counts against the limit
            let page = libc::sysconf(libc::_SC_PAGESIZE).max(1) as f64;
            let used = std::fs::read_to_string("/proc/self/statm")
                .ok()
                .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
                .map_or(0.0, |pages| pages * page);
            limit = limit.min((r.rlim_cur as f64 - used).max(0.0));
        }
        let mut info: libc::sysinfo = std::mem::zeroed();
        if libc::sysinfo(&mut info) == 0 && info.totalram > 0 {
            limit = limit.min(info.totalram as f64 * info.mem_unit.max(1) as f64);
        }
    }
    limit
}

/// LIGGGHTS's "Failed to allocate N bytes for array NAME" for `count` items of `size` bytes
/// that this machine cannot hold (see [`memory_limit`]); Ok when they may fit.
pub fn allocation(count: f64, size: usize, what: &str) -> Result<(), String> {
    let bytes = count * size as f64;
    if bytes.is_nan() || bytes > memory_limit() {
        return Err(failed_to_allocate(bytes, what));
    }
    Ok(())
}

/// The message of an allocation refused or failed.
pub fn failed_to_allocate(bytes: f64, what: &str) -> String {
    let shown = if bytes < 1e15 {
        format!("{}", bytes as u64)
    } else {
        g(bytes)
    };
    format!(
        "Failed to allocate {shown} bytes for array {what} (this machine has {} bytes to give)",
        g(memory_limit())
    )
}

/// A sphere's mass, as LIGGGHTS computes it from radius and density.
pub fn sphere_mass(radius: f64, density: f64) -> f64 {
    4.0 * std::f64::consts::PI / 3.0 * radius * radius * radius * density
}

/// Check a sphere's diameter and density where they are set: both finite, the diameter at
/// least 0, the density positive, and the mass they make finite. The error names the
/// offending `what` (`diameter` or `density`) and the range allowed for the other value.
pub fn check_sphere(diameter: f64, density: f64, what: &str) -> Result<(), String> {
    let dmax = 2.0 * (f64::MAX / sphere_mass(1.0, density)).cbrt() * (1.0 - 1e-12);
    let rhomax = f64::MAX / sphere_mass(0.5 * diameter, 1.0) * (1.0 - 1e-12);
    let ok = diameter >= 0.0
        && diameter.is_finite()
        && density > 0.0
        && density.is_finite()
        && sphere_mass(0.5 * diameter, density).is_finite();
    if ok {
        return Ok(());
    }
    Err(if what == "density" {
        if diameter > 0.0 && rhomax.is_finite() {
            format!(
                "density {} is out of range (allowed: 0 < density <= {} for diameter {}, so that the mass stays finite)",
                g(density),
                g(rhomax),
                g(diameter)
            )
        } else {
            format!(
                "density {} is out of range (allowed: a finite density > 0)",
                g(density)
            )
        }
    } else if density > 0.0 && dmax.is_finite() && dmax > 0.0 {
        format!(
            "diameter {} is out of range (allowed: 0 <= diameter <= {} for density {}, so that the mass stays finite)",
            g(diameter),
            g(dmax),
            g(density)
        )
    } else {
        format!(
            "diameter {} is out of range (allowed: a finite diameter >= 0)",
            g(diameter)
        )
    })
}

fn g(x: f64) -> String {
    crate::util::format::g(x)
}

impl Simulation {
    /// At a run's init: LIGGGHTS's own checks of the integrated particles and of the
    /// neighbour bins.
    pub fn check_run_init(&self) -> Result<(), String> {
        let p = &self.particles;
        for fix in &self.fixes {
            if let FixKind::NveSphere = fix.kind {
                let point =
                    (0..p.len()).find(|&i| p.mask[i] & fix.group != 0 && p.radius[i] == 0.0);
                if let Some(i) = point {
                    return Err(format!(
                        "Fix nve/sphere requires extended particles (atom {} has radius 0)",
                        p.id[i]
                    ));
                }
            }
        }
        if self.sort_every > 0 {
            // LIGGGHTS's atom sort bins (half the neighbour cutoff, or the user's size)
            // (LIGGGHTS's cutoff knows the particle templates' sizes before any particle
            // is inserted)
            let size = if self.sort_binsize > 0.0 {
                self.sort_binsize
            } else {
                0.5 * self.neighbor_cutoff().max(self.liggghts_cutneighmax())
            };
            if size > 0.0 {
                let bins: f64 = (0..3)
                    .map(|d| (self.domain.length(d) / size).trunc().max(1.0))
                    .product();
                if bins.is_nan() || bins > i32::MAX as f64 {
                    return Err(format!(
                        "Too many atom sorting bins (about {} bins of size {}; a larger bin size can be given with atom_modify sort)",
                        g(bins),
                        g(size)
                    ));
                }
            }
        }
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
        Ok(())
    }
}

/// Bytes of per-type properties (masses, radii, material values) per atom type.
const BYTES_PER_TYPE: usize = 64;

/// A number of atom types LIGGGHTS can count (an int) and this machine can hold per-type
/// properties for.
pub fn check_ntypes(ntypes: i64) -> std::result::Result<(), String> {
    if ntypes > i32::MAX as i64 {
        return Err(format!(
            "Too many atom types: {ntypes} (LIGGGHTS counts them in an int, at most {})",
            i32::MAX
        ));
    }
    allocation(ntypes as f64, BYTES_PER_TYPE, "per-type properties")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_ranges() {
        assert!(check_sphere(0.01, 2500.0, "diameter").is_ok());
        assert!(check_sphere(0.0, 2500.0, "diameter").is_ok());
        let e = check_sphere(1e306, 2500.0, "diameter").unwrap_err();
        assert!(
            e.contains("diameter 1e+306") && e.contains("<= 5.159"),
            "{e}"
        );
        let e = check_sphere(-1.0, 2500.0, "diameter").unwrap_err();
        assert!(e.contains("0 <= diameter"), "{e}");
        let e = check_sphere(10.0, 1e308, "density").unwrap_err();
        assert!(e.contains("0 < density <= 3.43"), "{e}");
        assert!(check_sphere(1.0, 0.0, "density").is_err());
        assert!(check_sphere(f64::NAN, 1.0, "diameter").is_err());
        assert!(check_sphere(1.0, f64::NAN, "density").is_err());
    }

    #[test]
    fn liggghts_bin_limits() {
        // a 0.2 x 0.2 x 0.5 box: the cutoff may reach 200 box lengths
        let bbox = [0.2, 0.2, 0.5];
        assert_eq!(neighbor_bins(bbox, 0.022).unwrap(), [18.0, 18.0, 45.0]);
        assert!(neighbor_bins(bbox, 1.02).is_ok());
        for cut in [100.02, 1e10, 1e308, f64::INFINITY] {
            let e = neighbor_bins(bbox, cut).unwrap_err();
            assert!(
                e.starts_with("Cannot use neighbor bins - box size << cutoff"),
                "{e}"
            );
        }
        let e = neighbor_bins([2e9, 0.2, 0.5], 0.022).unwrap_err();
        assert!(e.starts_with("Domain too large for neighbor bins"), "{e}");
        let e = neighbor_bins([2e5, 2e3, 0.5], 0.022).unwrap_err();
        assert!(e.starts_with("Too many neighbor bins"), "{e}");
        let e = neighbor_bins(bbox, f64::NAN).unwrap_err();
        assert!(e.starts_with("Domain too large"), "{e}");
    }
}
