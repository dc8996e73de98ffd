//! Per-atom values of fixes in `dump custom` columns (`f_ID[N]`). Of the fixes regolith
//! runs, LIGGGHTS 3.8.0 gives per-atom values for `fix move` (a three-column array of each
//! atom's unwrapped position when the fix was defined, length; 0 for atoms that were not in
//! its group then), `fix property/atom` (its values: a per-atom vector for a scalar
//! property, read as `f_ID` or `f_ID[0]`, an array for a vector one) and the heat fixes
//! (the temperature, K, as a per-atom vector).

use crate::engine::computes::PerAtom;
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixKind, PerAtomShape};
use crate::engine::sim::Simulation;

/// Per-atom columns of a fix kind (0: none) and whether they are a per-atom vector
/// (one value per atom, LIGGGHTS's `size_peratom_cols` 0) rather than an array.
fn width(kind: &FixKind) -> (usize, bool) {
    match kind {
        FixKind::Style(s) => shape_width(s.per_atom_shape()),
        _ => (0, false),
    }
}

/// [`width`] of a module fix style's per-atom shape.
fn shape_width(shape: PerAtomShape) -> (usize, bool) {
    match shape {
        PerAtomShape::None => (0, false),
        PerAtomShape::Vector => (1, true),
        PerAtomShape::Array(n) => (n, false),
    }
}

/// The 0-based column of a dump custom column `f_ID` / `f_ID[N]`, or LIGGGHTS's error for it
/// (it checks them when the dump is defined).
pub fn column(sim: &Simulation, id: &str, index: Option<usize>) -> Result<usize, EngineError> {
    let fix = sim
        .fixes
        .iter()
        .find(|f| f.id == id)
        .ok_or("Could not find dump custom fix ID")?;
    if fix.style == "property/atom/tracer" {
        // a per-atom scalar, the marker, which LIGGGHTS reads as f_ID only
        return match index {
            None => Ok(0),
            Some(_) => Err("Dump custom fix does not compute per-atom array".into()),
        };
    }
    let (cols, vector) = width(&fix.kind);
    if cols == 0 {
        return Err("Dump custom fix does not compute per-atom info".into());
    }
    if vector {
        return match index {
            None | Some(0) => Ok(0),
            Some(_) => Err("Dump custom fix does not calculate per-atom array".into()),
        };
    }
    match index {
        None | Some(0) => Err("Dump custom fix does not compute per-atom vector".into()),
        Some(k) if k > cols => Err("Dump custom fix vector is accessed out-of-range".into()),
        Some(k) => Ok(k - 1),
    }
}

/// The per-atom values of fix `id` and the column `index` selects.
pub fn per_atom(
    sim: &Simulation,
    id: &str,
    index: Option<usize>,
) -> Result<(PerAtom, usize), EngineError> {
    let col = column(sim, id, index)?;
    let p = &sim.particles;
    match sim.fixes.iter().find(|f| f.id == id).map(|f| &f.kind) {
        Some(FixKind::Style(s)) => {
            let columns = shape_width(s.per_atom_shape()).0;
            let values = s.per_atom(p);
            Ok((PerAtom { columns, values }, col))
        }
        _ => Err("Dump custom fix does not compute per-atom info".into()),
    }
}
