//! Values of a restart file checked before anything is built from it.

use thiserror::Error;

use crate::io::restart::{flag, Restart};
use crate::state::limits::{check_ntypes, LimitError};

/// A value of a restart file no simulation can start from.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RestartValueError {
    /// The box along `axis` (x, y or z) has no positive finite length (m).
    #[error("restart: box bounds {lo} {hi} along {axis} are not a box")]
    Bounds {
        /// Lower bound (m).
        lo: f64,
        /// Upper bound (m).
        hi: f64,
        /// The axis: x, y or z.
        axis: &'static str,
    },
    /// Fewer than one atom type.
    #[error("restart: {0} atom types")]
    NoTypes(i64),
    /// More atom types than a simulation holds.
    #[error("restart: {0}")]
    Types(LimitError),
    /// An atom's type outside 1..=ntypes.
    #[error("restart: atom {id} has type {kind} (the file has types 1 to {ntypes})")]
    AtomType {
        /// Atom ID.
        id: i64,
        /// Its type.
        kind: i64,
        /// Types in the file.
        ntypes: i64,
    },
    /// A radius that is negative or not finite (m).
    #[error("restart: atom {id} has radius {radius} (a radius must be finite and at least 0)")]
    Radius {
        /// Atom ID.
        id: i64,
        /// Its radius (m).
        radius: f64,
    },
    /// A mass that is not positive or not finite (kg).
    #[error("restart: atom {id} has mass {mass} (a mass must be finite and positive)")]
    Mass {
        /// Atom ID.
        id: i64,
        /// Its mass (kg).
        mass: f64,
    },
    /// A density that is not positive or not finite (kg/m^3), for a sphere of positive radius.
    #[error("restart: atom {id} has density {density} (a density must be finite and positive)")]
    Density {
        /// Atom ID.
        id: i64,
        /// Its density (kg/m^3).
        density: f64,
    },
    /// A position (m), velocity (m/s) or spin (rad/s) that is not finite.
    #[error("restart: atom {id} has a position, velocity or angular velocity that is not finite (x = {x:?}, v = {v:?}, omega = {omega:?})")]
    Motion {
        /// Atom ID.
        id: i64,
        /// Position (m).
        x: [f64; 3],
        /// Velocity (m/s).
        v: [f64; 3],
        /// Angular velocity (rad/s).
        omega: [f64; 3],
    },
}

/// Values of a restart file no simulation can start from: a box that is not a box, a type
/// count or type out of range, a particle without a finite non-negative radius or a positive
/// mass. A position, velocity or spin that is not finite is refused only when `motion` says
/// so (a conversion cannot write it); a run loses such an atom as LIGGGHTS does, or stops at
/// the blow-up guard.
pub fn check_restart_values(r: &Restart, motion: bool) -> Result<(), RestartValueError> {
    let (lo, hi) = r.bounds();
    for d in 0..3 {
        if !(lo[d] < hi[d] && (hi[d] - lo[d]).is_finite()) {
            return Err(RestartValueError::Bounds {
                lo: lo[d],
                hi: hi[d],
                axis: ["x", "y", "z"][d],
            });
        }
    }
    let ntypes = r.int(flag::NTYPES).unwrap_or(0);
    if ntypes < 1 {
        return Err(RestartValueError::NoTypes(ntypes));
    }
    check_ntypes(ntypes).map_err(RestartValueError::Types)?;
    for a in &r.atoms {
        if a.kind < 1 || a.kind > ntypes {
            return Err(RestartValueError::AtomType {
                id: a.id,
                kind: a.kind,
                ntypes,
            });
        }
        if !(a.radius >= 0.0 && a.radius.is_finite()) {
            return Err(RestartValueError::Radius {
                id: a.id,
                radius: a.radius,
            });
        }
        if !(a.mass > 0.0 && a.mass.is_finite()) {
            return Err(RestartValueError::Mass {
                id: a.id,
                mass: a.mass,
            });
        }
        if a.radius > 0.0 && !(a.density > 0.0 && a.density.is_finite()) {
            return Err(RestartValueError::Density {
                id: a.id,
                density: a.density,
            });
        }
        if motion
            && !a
                .x
                .iter()
                .chain(&a.v)
                .chain(&a.omega)
                .all(|c| c.is_finite())
        {
            return Err(RestartValueError::Motion {
                id: a.id,
                x: a.x,
                v: a.v,
                omega: a.omega,
            });
        }
    }
    Ok(())
}
