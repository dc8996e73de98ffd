//! `neigh_modify binsize SIZE` at a run: LIGGGHTS's bins of SIZE (length) replace those of
//! half the neighbour cutoff. The bins order each particle's partners, and with them the
//! round-off of its force sums; regolith's exact path orders partners by the default bins,
//! so a size that changes the bin grid is said once, on standard error.

use crate::commands::Ctx;
use crate::script::system::Mode;

/// Bins per direction of a box of lengths `bbox` for bins of about `size` (length), as
/// LIGGGHTS counts them (at least one).
pub fn grid(bbox: [f64; 3], size: f64) -> [i64; 3] {
    bbox.map(|b| ((b * (1.0 / size)) as i64).max(1))
}

/// Before a run: tell once when the user's bins differ from the default ones.
pub fn note(ctx: &mut Ctx) {
    let user = ctx.sim.extras.neigh_binsize;
    if ctx.sys.mode != Mode::Run || user <= 0.0 || ctx.sim.extras.binsize_warned {
        return;
    }
    let bbox = [0, 1, 2].map(|d| ctx.sim.domain.length(d));
    let cut = ctx.sim.liggghts_cutneighmax();
    if cut <= 0.0 || grid(bbox, user) == grid(bbox, 0.5 * cut) {
        return;
    }
    ctx.sim.extras.binsize_warned = true;
    let text = format!(
        "WARNING: neigh_modify binsize {}: LIGGGHTS bins this box {:?} (default {:?}); regolith \
         sums each particle's contact forces in the order of the default bins, so results \
         agree with LIGGGHTS's to round-off, not bit for bit\n",
        crate::util::format::g(user),
        grid(bbox, user),
        grid(bbox, 0.5 * cut)
    );
    use std::io::Write;
    let _ = std::io::stderr().lock().write_all(text.as_bytes());
}
