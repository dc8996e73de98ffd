//! Per-atom values of fixes in `dump custom` columns (`f_ID[N]`). Of the fixes regolith
//! runs, LIGGGHTS 3.8.0 gives per-atom values only for `fix move`: a three-column array of
//! each atom's unwrapped position when the fix was defined (length; 0 for atoms that were
//! not in its group then).

use crate::engine::computes::PerAtom;
use crate::engine::fixes::FixKind;
use crate::engine::sim::Simulation;

/// Per-atom columns of a fix kind (0: none).
fn width(kind: &FixKind) -> usize {
    match kind {
        FixKind::Move(_) => 3,
        _ => 0,
    }
}

/// The 0-based column of a dump custom column `f_ID` / `f_ID[N]`, or LIGGGHTS's error for it
/// (it checks them when the dump is defined).
pub fn column(sim: &Simulation, id: &str, index: Option<usize>) -> Result<usize, String> {
    let fix = sim
        .fixes
        .iter()
        .find(|f| f.id == id)
        .ok_or("Could not find dump custom fix ID")?;
    if matches!(fix.kind, FixKind::Tracer(_)) {
        // a per-atom scalar: the marker
        return match index {
            None => Ok(0),
            Some(_) => Err("Dump custom fix does not compute per-atom array".into()),
        };
    }
    let cols = width(&fix.kind);
    if cols == 0 {
        return Err("Dump custom fix does not compute per-atom info".into());
    }
    match index {
        // every fix with per-atom values here has an array of them
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
) -> Result<(PerAtom, usize), String> {
    let col = column(sim, id, index)?;
    let p = &sim.particles;
    if let Some(FixKind::Tracer(t)) = sim.fixes.iter().find(|f| f.id == id).map(|f| &f.kind) {
        let values = p
            .extra
            .iter()
            .find(|e| e.name == t.marker && e.width == 1)
            .map_or_else(|| vec![0.0; p.len()], |e| e.data.clone());
        return Ok((PerAtom { columns: 1, values }, col));
    }
    let mut values = Vec::with_capacity(3 * p.len());
    if let Some(FixKind::Move(m)) = sim.fixes.iter().find(|f| f.id == id).map(|f| &f.kind) {
        for i in 0..p.len() {
            values.extend(m.origin.get(&p.id[i]).copied().unwrap_or([0.0; 3]));
        }
    }
    Ok((PerAtom { columns: 3, values }, col))
}
