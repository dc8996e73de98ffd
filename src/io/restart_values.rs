//! Values of a restart file checked before anything is built from it.

use crate::io::restart::{flag, Restart};
use crate::state::limits::check_ntypes;

/// Values of a restart file no simulation can start from: a box that is not a box, a type
/// count or type out of range, a particle without a finite non-negative radius or a positive
/// mass. A position, velocity or spin that is not finite is refused only when `motion` says
/// so (a conversion cannot write it); a run loses such an atom as LIGGGHTS does, or stops at
/// the blow-up guard.
pub fn check_restart_values(r: &Restart, motion: bool) -> Result<(), String> {
    let (lo, hi) = r.bounds();
    for d in 0..3 {
        if !(lo[d] < hi[d] && (hi[d] - lo[d]).is_finite()) {
            return Err(format!(
                "restart: box bounds {} {} along {} are not a box",
                lo[d],
                hi[d],
                ["x", "y", "z"][d]
            ));
        }
    }
    let ntypes = r.int(flag::NTYPES).unwrap_or(0);
    if ntypes < 1 {
        return Err(format!("restart: {ntypes} atom types"));
    }
    check_ntypes(ntypes).map_err(|m| format!("restart: {m}"))?;
    for a in &r.atoms {
        if a.kind < 1 || a.kind > ntypes {
            return Err(format!(
                "restart: atom {} has type {} (the file has types 1 to {ntypes})",
                a.id, a.kind
            ));
        }
        if !(a.radius >= 0.0 && a.radius.is_finite()) {
            return Err(format!(
                "restart: atom {} has radius {} (a radius must be finite and at least 0)",
                a.id, a.radius
            ));
        }
        if !(a.mass > 0.0 && a.mass.is_finite()) {
            return Err(format!(
                "restart: atom {} has mass {} (a mass must be finite and positive)",
                a.id, a.mass
            ));
        }
        if a.radius > 0.0 && !(a.density > 0.0 && a.density.is_finite()) {
            return Err(format!(
                "restart: atom {} has density {} (a density must be finite and positive)",
                a.id, a.density
            ));
        }
        if motion
            && !a
                .x
                .iter()
                .chain(&a.v)
                .chain(&a.omega)
                .all(|c| c.is_finite())
        {
            return Err(format!(
                "restart: atom {} has a position, velocity or angular velocity that is not finite (x = {:?}, v = {:?}, omega = {:?})",
                a.id, a.x, a.v, a.omega
            ));
        }
    }
    Ok(())
}
