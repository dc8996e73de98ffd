//! Limits checked where state is set: the memory a process may allocate, atom type counts,
//! and sphere sizes and densities whose mass stays finite.

use thiserror::Error;

/// A value beyond what this machine or LIGGGHTS's types can hold.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum LimitError {
    /// LIGGGHTS's "Failed to allocate": `bytes` for the array `what`.
    #[error("{}", failed_to_allocate(*bytes, what))]
    Allocation {
        /// Bytes asked for.
        bytes: f64,
        /// The array they were for.
        what: String,
    },
    /// A sphere diameter (m) out of range for its density (kg/m^3): negative, not finite, or
    /// making an infinite mass; `max` is the largest allowed, if any.
    #[error("{}", diameter_range(*diameter, *density, *max))]
    Diameter {
        /// The diameter given (m).
        diameter: f64,
        /// The density it goes with (kg/m^3).
        density: f64,
        /// The largest diameter this density allows (m), when there is one.
        max: Option<f64>,
    },
    /// A sphere density (kg/m^3) out of range for its diameter (m); `max` as for diameters.
    #[error("{}", density_range(*density, *diameter, *max))]
    Density {
        /// The density given (kg/m^3).
        density: f64,
        /// The diameter it goes with (m).
        diameter: f64,
        /// The largest density this diameter allows (kg/m^3), when there is one.
        max: Option<f64>,
    },
    /// More atom types than LIGGGHTS's int counts.
    #[error("Too many atom types: {0} (LIGGGHTS counts them in an int, at most {max})", max = i32::MAX)]
    TooManyTypes(i64),
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
pub fn allocation(count: f64, size: usize, what: &str) -> Result<(), LimitError> {
    let bytes = count * size as f64;
    if bytes.is_nan() || bytes > memory_limit() {
        return Err(LimitError::Allocation {
            bytes,
            what: what.to_string(),
        });
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
pub fn check_sphere(diameter: f64, density: f64, what: &str) -> Result<(), LimitError> {
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
        LimitError::Density {
            density,
            diameter,
            max: (diameter > 0.0 && rhomax.is_finite()).then_some(rhomax),
        }
    } else {
        LimitError::Diameter {
            diameter,
            density,
            max: (density > 0.0 && dmax.is_finite() && dmax > 0.0).then_some(dmax),
        }
    })
}

/// The message of a diameter out of range.
fn diameter_range(diameter: f64, density: f64, max: Option<f64>) -> String {
    match max {
        Some(max) => format!(
            "diameter {} is out of range (allowed: 0 <= diameter <= {} for density {}, so that the mass stays finite)",
            g(diameter),
            g(max),
            g(density)
        ),
        None => format!(
            "diameter {} is out of range (allowed: a finite diameter >= 0)",
            g(diameter)
        ),
    }
}

/// The message of a density out of range.
fn density_range(density: f64, diameter: f64, max: Option<f64>) -> String {
    match max {
        Some(max) => format!(
            "density {} is out of range (allowed: 0 < density <= {} for diameter {}, so that the mass stays finite)",
            g(density),
            g(max),
            g(diameter)
        ),
        None => format!(
            "density {} is out of range (allowed: a finite density > 0)",
            g(density)
        ),
    }
}

fn g(x: f64) -> String {
    crate::util::format::g(x)
}

/// Bytes of per-type properties (masses, radii, material values) per atom type.
const BYTES_PER_TYPE: usize = 64;

/// A number of atom types LIGGGHTS can count (an int) and this machine can hold per-type
/// properties for.
pub fn check_ntypes(ntypes: i64) -> Result<(), LimitError> {
    if ntypes > i32::MAX as i64 {
        return Err(LimitError::TooManyTypes(ntypes));
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
        let e = check_sphere(1e306, 2500.0, "diameter")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("diameter 1e+306") && e.contains("<= 5.159"),
            "{e}"
        );
        let e = check_sphere(-1.0, 2500.0, "diameter")
            .unwrap_err()
            .to_string();
        assert!(e.contains("0 <= diameter"), "{e}");
        let e = check_sphere(10.0, 1e308, "density")
            .unwrap_err()
            .to_string();
        assert!(e.contains("0 < density <= 3.43"), "{e}");
        assert!(matches!(
            check_sphere(1.0, 0.0, "density"),
            Err(LimitError::Density { max: None, .. })
        ));
        assert_eq!(
            check_ntypes(1 << 40).unwrap_err().to_string(),
            "Too many atom types: 1099511627776 (LIGGGHTS counts them in an int, at most 2147483647)"
        );
        assert!(check_sphere(f64::NAN, 1.0, "diameter").is_err());
        assert!(check_sphere(1.0, f64::NAN, "density").is_err());
    }
}
