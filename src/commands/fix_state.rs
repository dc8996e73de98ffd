//! A fix re-defined after `read_restart` taking the state LIGGGHTS's fixes keep.

use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::engine::fixes::{Fix, FixKind, Move, RestoreError};

/// A fix defined while a restart file's fix states are held takes the state stored under
/// its ID and style (LIGGGHTS's Modify::add_fix); returns the lines LIGGGHTS prints. The
/// first insert/stream also takes the stored per-atom release data.
pub fn restore_fix_state(
    a: &Args,
    ctx: &mut Ctx,
    fix: &mut Fix,
) -> std::result::Result<Vec<String>, CommandError> {
    use crate::engine::restart_fixes::doubles;
    let mut lines = Vec::new();
    let held = ctx
        .sim
        .held_fix_state(&fix.id, &fix.style)
        .map(<[u8]>::to_vec);
    if let Some(bytes) = held {
        let d = doubles(&bytes);
        let bad = |what: &str| {
            a.error(
                2,
                format!(
                    "restart file: stored state of fix {} ({}) is {what}",
                    fix.id, fix.style
                ),
            )
        };
        match &mut fix.kind {
            kind if kind.mesh().is_some() => {} // its nodes were taken from the file when it was built
            kind if kind.property_atom().is_some() => {
                // the number of values; the builder kept the restart's per-atom values
                let columns = kind.property_atom().map(|pa| pa.defaults.len());
                if d.first().map(|&n| n as usize) != columns {
                    return Err(a.error(
                        2,
                        format!(
                            "Fix {} (id {}): restarted fix has incompatible data size",
                            fix.style, fix.id
                        ),
                    ));
                }
            }
            kind if kind.style_as::<Move>().is_some() => {
                // the time origin, and each atom's start position (LIGGGHTS's xoriginal)
                let start = *d.first().ok_or_else(|| bad("empty"))? as i32 as i64;
                if let Some(mv) = kind.style_as_mut::<Move>() {
                    mv.start_step = start;
                    if let Some(stored) = ctx.sim.restart_move_origins.get(&fix.id) {
                        for (id, x) in mv.origin.iter_mut() {
                            if let Some(s) = stored.get(id) {
                                *x = *s;
                            }
                        }
                    }
                }
            }
            FixKind::Style(s) => s.restore_state(&bytes).map_err(|e| match e {
                RestoreError::Unsupported(what) => {
                    a.unsupported(2, &format!("{what} (fix {} is stored there)", fix.id))
                }
                RestoreError::Malformed(what) => bad(&what),
                RestoreError::Refused(message) => a.error(2, message),
            })?,
            _ => {
                return Err(a.unsupported(
                    2,
                    &format!(
                        "fix {} taking its state from a restart file (fix {} is stored there)",
                        fix.style, fix.id
                    ),
                ))
            }
        }
        lines.push(format!(
            "Resetting global state of Fix {} Style {} from restart file info",
            fix.id, fix.style
        ));
        if (fix.kind.style_as::<Move>().is_some() || fix.kind.property_atom().is_some())
            && ctx.sim.held_peratom(&fix.id, &fix.style)
        {
            lines.push(format!(
                "Resetting per-atom state of Fix {} Style {} from restart file info",
                fix.id, fix.style
            ));
        }
    }
    if let Some(w) = fix.kind.mesh_wall_mut() {
        restore_mesh_wall_trackers(a, ctx, w, &mut lines)?;
    }
    let first_stream = fix.kind.stream().is_some() && !ctx.sim.stream_release;
    if first_stream {
        restore_release_data(a, ctx, &mut lines)?;
    }
    Ok(lines)
}

/// `fix wall/gran ... mesh` creates each mesh's neighbour count and contact tracker, which
/// take their stored state; `lines` gets what LIGGGHTS prints.
fn restore_mesh_wall_trackers(
    a: &Args,
    ctx: &Ctx,
    w: &mut crate::engine::fixes::MeshWallFix,
    lines: &mut Vec<String>,
) -> std::result::Result<(), CommandError> {
    let width = w.history_width();
    let sim = &ctx.sim;
    let mut trackers = Vec::new();
    for mesh in &w.meshes {
        let count = format!("n_neighs_mesh_{mesh}");
        if sim.held_fix_state(&count, "property/atom").is_some() {
            lines.push(format!(
                "Resetting global state of Fix {count} Style property/atom from restart file info"
            ));
        }
        if sim.held_peratom(&count, "property/atom") {
            lines.push(format!("Resetting per-atom state of Fix {count} Style property/atom from restart file info"));
        }
        let tracker = format!("tracker_{mesh}");
        let stored = sim
            .restart_mesh_history
            .get(&tracker)
            .filter(|_| sim.restart_in_progress);
        if let Some((stored_width, _)) = stored {
            if *stored_width != width {
                return Err(a.error(2, format!("Fix {tracker}: saved simulation state used different contact history model - can not restart")));
            }
        }
        if sim
            .held_fix_state(&tracker, "contacthistory/mesh")
            .is_some()
        {
            lines.push(format!("Resetting global state of Fix {tracker} Style contacthistory/mesh from restart file info"));
        }
        if sim.held_peratom(&tracker, "contacthistory/mesh") {
            lines.push(format!("Resetting per-atom state of Fix {tracker} Style contacthistory/mesh from restart file info"));
        }
        trackers.push(match stored {
            Some((_, lists)) => {
                crate::engine::mesh_wall::Tracker::from_restart(&sim.particles.id, lists)
            }
            None => Default::default(),
        });
    }
    if trackers.iter().any(|t| *t != Default::default()) {
        w.trackers = trackers;
    }
    Ok(())
}

/// The first `fix insert/stream` creates the per-atom release data (LIGGGHTS's), which
/// takes its stored state; `lines` gets what LIGGGHTS prints.
fn restore_release_data(
    a: &Args,
    ctx: &mut Ctx,
    lines: &mut Vec<String>,
) -> std::result::Result<(), CommandError> {
    use crate::engine::insert::{RELEASE_NAME, RELEASE_WIDTH};
    use crate::engine::restart_fixes::doubles;
    ctx.sim.stream_release = true;
    if let Some(bytes) = ctx.sim.held_fix_state(RELEASE_NAME, "property/atom") {
        if doubles(bytes).first().map(|&n| n as usize) != Some(RELEASE_WIDTH) {
            return Err(a.error(
                2,
                format!("Fix property/atom (id {RELEASE_NAME}): restarted fix has incompatible data size"),
            ));
        }
        lines.push(format!(
            "Resetting global state of Fix {RELEASE_NAME} Style property/atom from restart file info"
        ));
    }
    if ctx.sim.held_peratom(RELEASE_NAME, "property/atom") {
        lines.push(format!(
            "Resetting per-atom state of Fix {RELEASE_NAME} Style property/atom from restart file info"
        ));
        ctx.sim.recalc_release_steps();
    }
    ctx.sim.particles.extra_index(RELEASE_NAME, RELEASE_WIDTH);
    Ok(())
}
