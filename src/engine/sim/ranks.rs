//! Runs on more than one MPI rank (the first slice of the domain decomposition, fast path
//! only). Each rank owns the particles of its brick of the box (LIGGGHTS's `processors`
//! grid) and keeps ghost copies of the particles within the ghost cutoff of it. Pairs
//! follow LIGGGHTS's granular `newton off` rule: a rank computes every pair with at least
//! one particle it owns, so a pair of an owned particle and a ghost is computed on both
//! ranks, each keeping its own copy of the contact history; forces reach owned particles
//! without reverse communication. Each particle has a sum key at every list build: the cell
//! of a grid over the whole box that holds it, then its ID. Pairs are listed with the lower
//! key first and sorted by the two keys, so each particle adds its contacts in the order of
//! its partners' keys, whatever the rank count (the keys come from positions, which are the
//! same on every grid); owned particles are stored by key, cell by cell, so the pass over
//! the list reads its particles in memory order and their partners nearby.
//!
//! Every step the ghosts' positions and velocities are refreshed (forward communication);
//! at each neighbour-list build particles are wrapped into the box, the shrink-wrapped faces
//! move to the extent of every rank's particles (the bricks follow the box), particles
//! migrate with their contact history and per-atom fix state, and the ghosts are made again. Thermo and dumps
//! see every rank's particles gathered on rank 0 (in rank order, as LIGGGHTS gathers a
//! dump); a local compute's rows are each rank's own contacts, gathered likewise (a pair
//! across ranks reported from one side: across a periodic face from the particle with the
//! larger ID, as LIGGGHTS does, otherwise from the particle first in the exact path's
//! order, as one process does; LIGGGHTS's spatial sort is recorded in that order as on one
//! process, so the pairs are reported from the same side whatever the rank count). At the
//! end of a run every rank gets the whole set back in the exact path's order with the
//! contact history, so the commands between runs act identically on every rank.

use super::*;
use crate::engine::accel::ORDER_ARRAY;
use crate::engine::decomp::pack::{pack_particle, unpack_particle, Reader, Writer};
use crate::engine::decomp::Decomposition;
use crate::engine::decomp::SwapBuffers;
use crate::engine::decomp::{borders, forward_with, migrate, migrate_anywhere, GhostPlan, Halo};
use crate::engine::decomp::{DecompError, PartnerHistory};
use crate::engine::dump_style::SharedLocalRows;
use crate::engine::neighbor::SumOrder;
use crate::engine::particles::PerAtom;
use crate::engine::restart_state::PendingHistory;
use crate::util::comm::{Comm, RankComm, Reduce};
use std::collections::HashMap;

/// This rank's part of a run on several ranks.
struct RankState {
    /// The bricks.
    dec: Decomposition,
    /// How far ghosts reach.
    halo: Halo,
    /// The ghost swaps of the last build.
    plan: GhostPlan,
    /// Forward communication's buffers.
    swap: SwapBuffers,
    /// Owned particles (the ghosts follow them in the particle arrays).
    nlocal: usize,
    /// Pairs with at least one owned particle, the lower ID first, sorted by ID.
    pairs: Vec<Pair>,
    /// Their contact history (`flips.len()` values per pair, seen from the first particle).
    history: Vec<f64>,
    /// Which history values change sign seen from the other particle.
    flips: Vec<bool>,
    /// Owned positions at the last build (length).
    built: Vec<[f64; 3]>,
    /// Steps since the last build.
    ago: u64,
    /// Builds so far (walls refresh their own lists with it).
    builds: u64,
    /// The ghosts, kept apart while the fixes act on the owned particles and copied
    /// behind them for the pair forces (their positions and velocities refreshed then).
    ghosts: Particles,
    /// The ghosts behind the owned particles were made by the last build (not copied
    /// from `ghosts`), so they are copied there when set apart.
    fresh: bool,
    /// The ghosts' velocities (length/time) and angular velocities (1/time) at the last
    /// force evaluation, kept while a `compute pair/gran/local` reads them.
    ghost_motion: (Vec<[f64; 3]>, Vec<[f64; 3]>),
}

impl RankState {
    /// Atom IDs of the owned particles `owned` (the first `nlocal`) and of the ghosts.
    fn ids(&self, owned: &Particles) -> Vec<i64> {
        let mut ids = owned.id[..self.nlocal.min(owned.len())].to_vec();
        ids.extend_from_slice(&self.ghosts.id);
        ids
    }
}

impl From<DecompError> for EngineError {
    fn from(e: DecompError) -> Self {
        EngineError::Invalid(e.to_string())
    }
}

/// The cells of the sum keys: a grid over the whole box (the same on every rank), in
/// row-major order (x fastest).
#[derive(Debug, Clone, Copy)]
struct KeyGrid {
    /// Lower corner of the box (length).
    lo: [f64; 3],
    /// Cells per length along each axis (1/length).
    inv: [f64; 3],
    /// Cells along each axis.
    dims: [u64; 3],
}

impl KeyGrid {
    /// Cells about `cell` wide (length) over the box `lo`..`hi`.
    fn new(lo: [f64; 3], hi: [f64; 3], cell: f64) -> KeyGrid {
        let dims = [0, 1, 2].map(|d| {
            let n = ((hi[d] - lo[d]) / cell).floor();
            if n.is_finite() && n >= 1.0 {
                n.min(1e5) as u64
            } else {
                1
            }
        });
        let inv = [0, 1, 2].map(|d| {
            let len = hi[d] - lo[d];
            if len > 0.0 {
                dims[d] as f64 / len
            } else {
                0.0
            }
        });
        KeyGrid { lo, inv, dims }
    }

    /// The cell of position `x` (outside the box: the nearest cell).
    fn cell(&self, x: [f64; 3]) -> u64 {
        // a conversion truncates, which is the floor for the cells at or above zero
        let c = [0, 1, 2].map(|d| {
            let t = (x[d] - self.lo[d]) * self.inv[d];
            if t >= 0.0 {
                (t as u64).min(self.dims[d] - 1)
            } else {
                0
            }
        });
        (c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]
    }
}

/// Every pair closer than the radii plus `skin` with at least one owned particle (below
/// `nlocal`): owned pairs once, an owned particle and a ghost once; the lower sum key
/// (`cells`, then ID) first (an owned particle before its own periodic image), sorted by
/// the two keys, then by the positions' bits (images of one partner).
fn rank_pairs(p: &Particles, nlocal: usize, skin: f64, cells: &[u64]) -> Vec<Pair> {
    let n = p.len().min(cells.len());
    if nlocal == 0 {
        return Vec::new();
    }
    let key = |k: usize| (cells[k], p.id[k]);
    let bins = Bins::new(p, skin);
    let mut found: Vec<Found> = Vec::with_capacity(8 * nlocal);
    for i in 0..nlocal {
        let c = bins.cell_of(p.x[i]);
        // the three cells along x of each of the nine rows around i are one run of `order`
        for m in 0..9 {
            let row = [c[1] + m % 3 - 1, c[2] + m / 3 - 1];
            for &j in bins.row_members(c[0], row) {
                let j = j as usize;
                if j == i || (j < nlocal && j < i) || j >= n {
                    continue;
                }
                let d = [0, 1, 2].map(|k| p.x[i][k] - p.x[j][k]);
                let cut = p.radius[i] + p.radius[j] + skin;
                if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < cut * cut {
                    let ghost_first = p.id[j] != p.id[i] && key(j) < key(i);
                    let (a, b) = if ghost_first { (j, i) } else { (i, j) };
                    found.push((key(a), key(b), a as u32, b as u32));
                }
            }
        }
    }
    // by the two keys; two images of one partner (the same keys) by their positions' bits
    let bits = |k: u32| p.x[k as usize].map(f64::to_bits);
    let cmp = |q: &Found, r: &Found| {
        (q.0, q.1)
            .cmp(&(r.0, r.1))
            .then_with(|| (bits(q.3), bits(q.2)).cmp(&(bits(r.3), bits(r.2))))
    };
    let pair = |q: Found| Pair {
        i: q.2,
        j: q.3,
        shift: [0.0; 3],
    };
    if !(1..nlocal).all(|k| key(k - 1) < key(k)) {
        found.sort_unstable_by(cmp);
        return found.into_iter().map(pair).collect();
    }
    // owned particles stored by key (as a build leaves them): the entries led by an owned
    // particle come in its order and need sorting only within each particle's group; those
    // led by a ghost are sorted apart and merged in
    let (mut owned, mut ghost): (Vec<Found>, Vec<Found>) =
        found.into_iter().partition(|q| (q.2 as usize) < nlocal);
    for group in owned.chunk_by_mut(|q, r| q.2 == r.2) {
        group.sort_unstable_by(cmp);
    }
    ghost.sort_unstable_by(cmp);
    let mut out = Vec::with_capacity(owned.len() + ghost.len());
    let mut rest = ghost.into_iter().peekable();
    for q in owned {
        while let Some(g) = rest.next_if(|g| cmp(g, &q).is_lt()) {
            out.push(pair(g));
        }
        out.push(pair(q));
    }
    out.extend(rest.map(pair));
    out
}

/// One particle's pair contacts: (partner ID, history values) each.
type Contacts = Vec<(i64, Vec<f64>)>;

/// Every rank's owned particles gathered on every rank, in the exact path's order.
struct WholeSet {
    /// The particles (the order record dropped).
    particles: Particles,
    /// Each particle's pair contacts by partner ID (None without history in the pair model).
    partners: Option<HashMap<i64, Contacts>>,
    /// Each particle's per-atom fix state that travels with it, in the particles' order.
    attached: Vec<Vec<f64>>,
}

/// Velocities (length/time) and angular velocities (1/time) of particles.
type Motion = (Vec<[f64; 3]>, Vec<[f64; 3]>);

/// A listed pair as the search finds it: the sum keys of its first and second particle
/// (cell, ID) and their indices.
type Found = ((u64, i64), (u64, i64), u32, u32);

/// The particles binned in cubic cells a largest pair cutoff wide, as one array sorted by
/// cell (a counting sort), for the pair search.
struct Bins {
    /// Lower corner of cell (0, 0, 0) (length).
    lo: [f64; 3],
    /// Cell edge (length).
    cell: f64,
    /// Cells per direction.
    dims: [i64; 3],
    /// Where each cell's particles start in `order` (one more entry than cells).
    start: Vec<u32>,
    /// Particle indices, cell by cell.
    order: Vec<u32>,
}

impl Bins {
    /// Bin every particle of `p` in cells of the largest diameter plus `skin`, fewer
    /// and larger when the particles' extent would need more than eight per particle.
    fn new(p: &Particles, skin: f64) -> Bins {
        let rmax = p.radius.iter().copied().fold(0.0, f64::max);
        let mut cell = (2.0 * rmax + skin).max(f64::MIN_POSITIVE);
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for x in &p.x {
            for d in 0..3 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
        let limit = (8 * p.len()).max(64) as f64;
        let count = |cell: f64| [0, 1, 2].map(|d| ((hi[d] - lo[d]) / cell).floor() + 1.0);
        while count(cell).iter().product::<f64>() > limit {
            cell *= 2.0;
        }
        // a blown-up extent (not finite) gets one cell: the blow-up guard stops such a run
        let dims = count(cell).map(|c| {
            if c.is_finite() && c >= 1.0 {
                c as i64
            } else {
                1
            }
        });
        let mut bins = Bins {
            lo,
            cell,
            dims,
            start: Vec::new(),
            order: Vec::new(),
        };
        let total = (dims[0] * dims[1] * dims[2]) as usize;
        let index: Vec<u32> =
            p.x.iter()
                .map(|&x| bins.index(bins.cell_of(x)).unwrap_or(0) as u32)
                .collect();
        bins.start = vec![0; total + 1];
        for &c in &index {
            bins.start[c as usize + 1] += 1;
        }
        for c in 0..total {
            bins.start[c + 1] += bins.start[c];
        }
        let mut at = bins.start.clone();
        bins.order = vec![0; p.len()];
        for (j, &c) in index.iter().enumerate() {
            bins.order[at[c as usize] as usize] = j as u32;
            at[c as usize] += 1;
        }
        bins
    }

    /// The cell (possibly outside the grid) holding position `x`.
    fn cell_of(&self, x: [f64; 3]) -> [i64; 3] {
        [0, 1, 2].map(|d| {
            let t = (x[d] - self.lo[d]) / self.cell;
            // a conversion truncates: the floor at or above zero, without a library call
            if t >= 0.0 {
                t as i64
            } else {
                t.floor() as i64
            }
        })
    }

    /// The array index of cell `c`, None outside the grid.
    fn index(&self, c: [i64; 3]) -> Option<usize> {
        let inside = (0..3).all(|d| c[d] >= 0 && c[d] < self.dims[d]);
        inside.then(|| ((c[2] * self.dims[1] + c[1]) * self.dims[0] + c[0]) as usize)
    }

    /// The particles of the cells `cx - 1 ..= cx + 1` along x (those inside the grid) in
    /// row `row` (y, z), cell by cell; none when the row is outside the grid.
    fn row_members(&self, cx: i64, row: [i64; 2]) -> &[u32] {
        let (lo, hi) = ((cx - 1).max(0), (cx + 1).min(self.dims[0] - 1));
        if lo > hi {
            return &[];
        }
        match (
            self.index([lo, row[0], row[1]]),
            self.index([hi, row[0], row[1]]),
        ) {
            (Some(a), Some(b)) => &self.order[self.start[a] as usize..self.start[b + 1] as usize],
            _ => &[],
        }
    }
}

/// Does listed `pair` touch (centres closer than the radii summed)?
fn pair_touches(p: &Particles, pair: &Pair) -> bool {
    let (i, j) = (pair.i as usize, pair.j as usize);
    let d = [0, 1, 2].map(|c| p.x[i][c] - p.x[j][c]);
    let radsum = p.radius[i] + p.radius[j];
    d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < radsum * radsum
}

/// No particles, with the per-atom arrays of `like`.
fn empty_like(like: &Particles) -> Particles {
    Particles {
        extra: like
            .extra
            .iter()
            .map(|e| PerAtom {
                name: e.name.clone(),
                width: e.width,
                data: Vec::new(),
                fill: e.fill.clone(),
            })
            .collect(),
        ..Particles::default()
    }
}

impl Simulation {
    /// `run N` on more than one rank (see the module's description).
    pub(super) fn run_ranks(
        &mut self,
        nsteps: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let comm = self.comm.take().ok_or("no ranks to run on")?;
        let result = self.run_ranks_with(&comm, nsteps, out, vars);
        self.comm = Some(comm);
        result
    }

    fn run_ranks_with(
        &mut self,
        comm: &RankComm,
        nsteps: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        if !self.domain.exists {
            return Err("Run command before simulation box is defined".into());
        }
        self.init_pair()?;
        self.check_meshes_in_box()?;
        if self.contact_factor() != 1.0 {
            return Err(EngineError::Invalid(
                "a wet pair model on more than one MPI rank: not supported yet".into(),
            ));
        }
        let (first, last, started) = self.begin_run(nsteps)?;
        self.setup_fix_styles();
        // every rank holds the whole set here: the computes' run-start state is global
        self.setup_compute_styles();
        let mut st = self.rank_setup(comm)?;
        self.rank_mesh_setup()?;
        self.rank_forces(&mut st, false, true);
        self.zero_mesh_velocities(false);
        if comm.rank() == 0 {
            // LIGGGHTS's proc 0 says the history fix took its state from a restart file
            self.say_history_restored(out);
        }
        self.has_run = true;
        self.restart_in_progress = false;
        self.restart_fixes.clear();
        self.restart_peratom.clear();
        self.restart_move_origins.clear();
        self.restart_mesh_history.clear();
        self.thermo.run_start = first;
        self.thermo.run_last = last;
        self.thermo.prepare_run(self.box_changes());
        if comm.rank() == 0 {
            self.thermo.header(out);
        }
        self.loop_clock = Some(std::time::Instant::now());
        self.stats = RunStats::default();
        self.rank_output(comm, &mut st, true, last, out, vars)?;
        for _ in 0..nsteps {
            self.step += 1;
            fixes::initial_integrate(
                &mut self.fixes,
                &mut self.particles,
                self.step,
                self.dt,
                &self.domain,
            );
            fixes::move_meshes(&mut self.fixes, self.dt);
            let clock = std::time::Instant::now();
            let rebuilt = self.rank_decide(comm, &mut st);
            if rebuilt {
                let mut hist = PartnerHistory::from_pairs(
                    &st.pairs,
                    &st.history,
                    &st.ids(&self.particles),
                    st.nlocal,
                    &st.flips,
                );
                self.attach_wall_state(&mut hist, &self.particles.id[..st.nlocal]);
                self.rank_build(comm, &mut st, hist, true)?;
                self.stats.builds += 1;
                self.stats.neigh += clock.elapsed().as_secs_f64();
            } else {
                self.particles.extend_from(&st.ghosts);
                let p = &mut self.particles;
                forward_with(comm, &st.dec, &st.plan, p, false, &mut st.swap)?;
                self.stats.comm += clock.elapsed().as_secs_f64();
            }
            self.refresh_moving_meshes(rebuilt);
            let clock = std::time::Instant::now();
            let tally = self.virial_wanted(last);
            self.rank_forces(&mut st, true, tally);
            self.stats.pair += clock.elapsed().as_secs_f64();
            fixes::final_integrate(
                &mut self.fixes,
                &mut self.particles,
                self.step,
                self.dt,
                &self.domain,
            );
            self.rank_end_of_step(comm, out, vars)?;
            let clock = std::time::Instant::now();
            self.rank_output(comm, &mut st, false, last, out, vars)?;
            self.rank_periodic_restart(comm, &st)?;
            self.stats.output += clock.elapsed().as_secs_f64();
        }
        self.run_bounds = None;
        self.loop_clock = None;
        self.atime += (self.step - self.atime_step) as f64 * self.dt;
        self.atime_step = self.step;
        let loop_time = started.elapsed().as_secs_f64();
        let stats = self.rank_statistics(comm, &st, loop_time);
        self.keep_run_balance(comm, &st.dec, st.nlocal);
        self.rank_gather_all(comm, &st)?;
        out(&format!(
            "Loop time of {} on {} procs for {} steps with {} atoms\n\n",
            crate::util::format::g(loop_time),
            comm.size(),
            nsteps,
            self.particles.len()
        ));
        out(&stats);
        Ok(())
    }

    /// The `end_of_step` phase on ranks: each module fix style over this rank's particles,
    /// extremes reduced over the ranks; rank 0 writes what the styles print.
    fn rank_end_of_step(
        &mut self,
        comm: &RankComm,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let (step, dt, skin) = (self.step, self.dt, self.neighbor.skin);
        let contact = self.neighbor.cutneighmax - skin;
        let mesh_vmax_sqr = self.moving_mesh_vmax_sqr();
        let min = |values: &mut [f64]| comm.all_reduce_f64(values, Reduce::Min);
        for k in 0..self.fixes.len() {
            let fix = &mut self.fixes[k];
            if let FixKind::Style(s) = &mut fix.kind {
                let at = fixes::FixStep {
                    group: fix.group,
                    step,
                    dt,
                    domain: &self.domain,
                    virial: &[],
                    contact,
                    skin,
                    regions: Some(&self.regions),
                    mesh_vmax_sqr,
                };
                s.end_of_step_ranks(&mut self.particles, &at, &min);
                if s.outputs_at(step) {
                    if comm.rank() == 0 {
                        self.fix_style_output(k, out, vars)?;
                    } else {
                        // what rank 0 prints, the others drop
                        self.fix_style_output(k, &mut |_: &str| {}, vars)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// The whole set wrapped into the box on every rank, the exact order recorded, and
    /// this rank's brick kept, with its ghosts and pair list made.
    fn rank_setup(&mut self, comm: &RankComm) -> Result<RankState, EngineError> {
        self.pbc_and_box()?;
        self.natoms_expected = self.particles.len();
        let k = self.particles.extra_index(ORDER_ARRAY, 1);
        for (i, r) in self.particles.extra[k].data.iter_mut().enumerate() {
            *r = (i + 1) as f64;
        }
        // LIGGGHTS's spatial sort at the setup, recorded in the exact order as one process
        // records it (every rank holds the whole set here)
        if self.sort_every > 0 {
            self.sort_particles();
        }
        let flips = self.pair.as_ref().map_or(Vec::new(), |p| p.history_flips());
        let mut hist = self.history_rows(flips.len());
        let ids = self.particles.id.clone();
        self.attach_wall_state(&mut hist, &ids);
        // the grid with the cuts a balance left, moved again by a `fix balance` when due
        let mut dec = self.balanced_grid(comm.rank())?;
        self.balance_at_setup(&mut dec);
        let remove: Vec<bool> = self.particles.x.iter().map(|x| !dec.owns(*x)).collect();
        self.particles.retain_by(&remove);
        for what in [
            &mut hist.partners as &mut dyn RetainBy,
            &mut hist.values,
            &mut hist.attached,
        ] {
            what.retain_by(&remove);
        }
        let mut st = RankState {
            dec,
            halo: Halo::granular(self.neighbor.cutneighmax, self.neighbor.skin),
            plan: GhostPlan::default(),
            swap: SwapBuffers::default(),
            nlocal: self.particles.len(),
            pairs: Vec::new(),
            history: Vec::new(),
            flips,
            built: Vec::new(),
            ago: 0,
            builds: self.list.builds,
            ghosts: empty_like(&self.particles),
            fresh: false,
            ghost_motion: (Vec::new(), Vec::new()),
        };
        self.rank_build(comm, &mut st, hist, false)?;
        Ok(st)
    }

    /// The contact history of the whole set as per-particle partner lists: what
    /// `read_restart` or the last run left (`width` values per contact).
    fn history_rows(&mut self, width: usize) -> PartnerHistory {
        let n = self.particles.len();
        let mut hist = PartnerHistory::new(width, n);
        let pending = self.pending_history.take();
        if let Some(pending) = pending.filter(|h| h.width == width && width > 0) {
            for (i, id) in self.particles.id.iter().enumerate() {
                for (partner, values) in pending.partners.get(id).into_iter().flatten() {
                    hist.insert(i, *partner, values);
                }
            }
        }
        // a fresh list; its build count goes on (walls refresh their lists by it)
        let builds = self.list.builds;
        self.list = crate::engine::neighbor::NeighborList::default();
        self.list.builds = builds;
        self.history.clear();
        self.mirror_history.clear();
        hist
    }

    /// A neighbour-list build on this rank: owned particles (ghosts already dropped)
    /// wrapped into the box, those lost through fixed faces dropped, migration with the
    /// contact history `hist` (one row per owned particle), new ghosts and pair list, and
    /// the history taken back from the partner lists. `balance`: a `fix balance` may move
    /// the cuts first (not at the setup build, which the setup balanced).
    fn rank_build(
        &mut self,
        comm: &RankComm,
        st: &mut RankState,
        mut hist: PartnerHistory,
        balance: bool,
    ) -> Result<(), EngineError> {
        let p = &mut self.particles;
        // as LIGGGHTS's pbc, reset_box and exchange: periodic coordinates wrapped, the
        // shrink-wrapped faces moved to the extent of every rank's particles (the bricks
        // follow the new box), then the particles outside a fixed face lost
        let mut placed: Vec<bool> = (0..p.len())
            .map(|i| self.domain.remap(&mut p.x[i], &mut p.image[i]))
            .collect();
        if self.domain.shrinks() {
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            // a particle without a finite position is lost below; it does not stretch the box
            for x in p.x.iter().filter(|x| x.iter().all(|c| c.is_finite())) {
                for d in 0..3 {
                    lo[d] = lo[d].min(x[d]);
                    hi[d] = hi[d].max(x[d]);
                }
            }
            comm.all_reduce_f64(&mut lo, Reduce::Min);
            comm.all_reduce_f64(&mut hi, Reduce::Max);
            // no particle on any rank: the box stays (as one process leaves it)
            if lo[0] <= hi[0] {
                self.domain.shrink_wrap(lo, hi)?;
                st.dec.set_box(self.domain.lo, self.domain.hi);
            }
        }
        let mut i = 0;
        while i < p.len() {
            if !placed[i] || !self.domain.contains(p.x[i]) {
                p.fill_from_last(i);
                hist.fill_from_last(i);
                placed.swap_remove(i);
            } else {
                i += 1;
            }
        }
        // the cuts moved: particles go straight to their new ranks, however far
        if balance && self.balance_during_run(comm, &mut st.dec) {
            let p = &mut self.particles;
            migrate_anywhere(comm, &st.dec, p, Some(&mut hist))?;
        } else {
            let p = &mut self.particles;
            migrate(comm, &st.dec, p, Some(&mut hist))?;
        }
        if self.sort_every > 0 && self.step >= self.next_sort {
            self.rank_sort_order(comm)?;
        }
        let p = &mut self.particles;
        // owned particles stored by sum key, as the pair list runs: the pass over the list
        // reads the first particles of its pairs in memory order, their partners nearby
        let grid = KeyGrid::new(self.domain.lo, self.domain.hi, self.neighbor.cutneighmax);
        let mut keyed: Vec<(u64, i64, [u64; 3], usize)> = (0..p.len())
            .map(|k| (grid.cell(p.x[k]), p.id[k], p.x[k].map(f64::to_bits), k))
            .collect();
        keyed.sort_unstable();
        let order: Vec<usize> = keyed.into_iter().map(|(.., k)| k).collect();
        p.permute(&order);
        let (mut partners, mut values) = (
            std::mem::take(&mut hist.partners),
            std::mem::take(&mut hist.values),
        );
        hist.partners = order
            .iter()
            .map(|&k| std::mem::take(&mut partners[k]))
            .collect();
        hist.values = order
            .iter()
            .map(|&k| std::mem::take(&mut values[k]))
            .collect();
        let attached: Vec<Vec<f64>> = order
            .iter()
            .map(|&k| {
                hist.attached
                    .get_mut(k)
                    .map(std::mem::take)
                    .unwrap_or_default()
            })
            .collect();
        let ids = p.id.clone();
        self.restore_wall_state(&attached, &ids)?;
        let p = &mut self.particles;
        st.nlocal = p.len();
        let natoms = comm.all_reduce_i64(st.nlocal as i64, Reduce::Sum) as usize;
        if natoms != self.natoms_expected && !self.lost_ignore {
            return Err(EngineError::Invalid(format!(
                "Lost atoms: original {} current {natoms}",
                self.natoms_expected
            )));
        }
        self.natoms_expected = natoms;
        st.plan = borders(comm, &st.dec, &st.halo, p, st.nlocal)?;
        let cells: Vec<u64> = p.x.iter().map(|&x| grid.cell(x)).collect();
        st.pairs = rank_pairs(p, st.nlocal, self.neighbor.skin, &cells);
        st.history = hist.to_pairs(&st.pairs, &p.id, st.nlocal, &st.flips);
        let width = st.flips.len();
        if width > 0 {
            for (k, pair) in st.pairs.iter().enumerate() {
                if !pair_touches(p, pair) {
                    st.history[k * width..(k + 1) * width].fill(0.0);
                }
            }
        }
        st.built = p.x[..st.nlocal].to_vec();
        st.ago = 0;
        st.builds += 1;
        st.fresh = true;
        Ok(())
    }

    /// LIGGGHTS's spatial sort when due at a rebuild, applied to the record of the exact
    /// order as one process applies it: the whole set ordered by sort bin, then by its
    /// place in the exact order, each particle's place gathered from every rank.
    fn rank_sort_order(&mut self, comm: &RankComm) -> Result<(), EngineError> {
        self.next_sort = (self.step / self.sort_every) * self.sort_every + self.sort_every;
        let binsize = if self.sort_binsize > 0.0 {
            self.sort_binsize
        } else {
            0.5 * self.neighbor_cutoff()
        };
        let (lo, hi) = (self.domain.lo, self.domain.hi);
        let p = &mut self.particles;
        // the bins depend on the box alone: every rank sorts or none
        let Some(bins) = super::neighbors::sort_bins(&p.x, lo, hi, binsize, self.dimension == 2)
        else {
            return Ok(());
        };
        let k = p.extra_index(ORDER_ARRAY, 1);
        let mut w = Writer::default();
        for (&b, &r) in bins.iter().zip(&p.extra[k].data) {
            w.u32(b);
            w.f64(r);
        }
        let mut all = comm
            .gather_bytes(&w.bytes)
            .map(|v| v.concat())
            .unwrap_or_default();
        comm.broadcast_bytes(0, &mut all);
        let mut keyed = Vec::with_capacity(all.len() / 12);
        let mut r = Reader::new(&all);
        while !r.done() {
            let bin = r.u32()?;
            keyed.push((bin, r.f64()?));
        }
        keyed.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        // each old place's new one, looked up by the old place
        let mut moved: Vec<(f64, f64)> = keyed
            .iter()
            .enumerate()
            .map(|(new, &(_, old))| (old, (new + 1) as f64))
            .collect();
        moved.sort_by(|a, b| a.0.total_cmp(&b.0));
        for r in p.extra[k].data.iter_mut() {
            if let Ok(at) = moved.binary_search_by(|m| m.0.total_cmp(r)) {
                *r = moved[at].1;
            }
        }
        self.accel.next_rank = (keyed.len() + 1) as f64;
        Ok(())
    }

    /// LIGGGHTS's rebuild decision, the same on every rank: the delay and every settings,
    /// then whether any rank's particle moved more than half the skin.
    fn rank_decide(&mut self, comm: &RankComm, st: &mut RankState) -> bool {
        st.ago += 1;
        // a `fix balance` rebalancing at this step forces a build (every rank alike), and so
        // does a `restart` file due now, as on one process
        if self.balance_forces_build() || self.restart_due() {
            return true;
        }
        // a moving mesh's node went more than half the skin since the last build (every
        // rank moves the same meshes alike)
        if self.mesh_rebuild_at == Some(self.step) {
            return true;
        }
        let n = &self.neighbor;
        if st.ago < n.delay || !st.ago.is_multiple_of(n.every) {
            return false;
        }
        if !n.check {
            return true;
        }
        let limit = (0.5 * n.skin) * (0.5 * n.skin);
        let x = &self.particles.x[..st.nlocal];
        let moved = x.iter().zip(&st.built).any(|(a, b)| {
            let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
            d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > limit
        });
        let rebuild = comm.all_reduce_i64(i64::from(moved), Reduce::Max) > 0;
        if rebuild && st.ago == n.every.max(n.delay) {
            self.stats.dangerous += 1;
        }
        rebuild
    }

    /// Pair forces on owned particles and ghosts (the ghosts behind the owned particles;
    /// their forces are not used), then the ghosts set apart and the forcing fixes run on
    /// the owned particles; `update` false in the setup evaluation.
    /// `want_virial`: tally the per-atom pair virial if a `compute stress/atom` reads it (an
    /// owned particle's is whole: every pair with an owned particle is computed on its rank).
    fn rank_forces(&mut self, st: &mut RankState, update: bool, want_virial: bool) {
        let tally = want_virial && self.computes.iter().any(|c| c.style().reads_virial());
        self.virial.clear();
        self.virial_step = tally.then_some(self.step);
        if tally {
            self.virial.resize(self.particles.len(), [0.0; 6]);
        }
        match self.pair.as_mut() {
            Some(pair) => pair.compute(
                &mut self.particles,
                &st.pairs,
                &mut st.history,
                self.dt,
                update,
                tally.then_some(&mut self.virial[..]),
                &SumOrder::ListOrder,
                None,
            ),
            None => self.particles.clear_forces(),
        }
        if st.fresh {
            self.particles.copy_tail_into(st.nlocal, &mut st.ghosts);
            st.fresh = false;
        }
        if self
            .computes
            .iter()
            .any(|c| c.style().reads_pair_contacts())
        {
            let (v, omega) = &mut st.ghost_motion;
            v.clear();
            v.extend_from_slice(&self.particles.v[st.nlocal..]);
            omega.clear();
            omega.extend_from_slice(&self.particles.omega[st.nlocal..]);
        }
        self.particles.truncate(st.nlocal);
        self.virial.truncate(st.nlocal);
        // the mesh lists use the full skin when the box can change, as on one process
        let moving_skin = self.box_changes();
        fixes::post_force(
            &mut self.fixes,
            &mut self.particles,
            (self.step, &self.domain),
            self.dt,
            update,
            (st.builds, self.neighbor.skin),
            moving_skin,
        );
    }

    /// This rank's owned particles as one message (with their contact history rows).
    fn pack_owned(&self, st: &RankState, hist: Option<&PartnerHistory>) -> Vec<u8> {
        let mut w = Writer::default();
        for i in 0..st.nlocal {
            pack_particle(&mut w, &self.particles, i, [0.0; 3], hist);
        }
        w.bytes
    }

    /// Thermo and dumps due at this step, written by rank 0 from every rank's particles
    /// gathered in rank order.
    fn rank_output(
        &mut self,
        comm: &RankComm,
        st: &mut RankState,
        setup: bool,
        last: i64,
        out: Sink<'_>,
        vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let step = self.step;
        let thermo = setup || self.thermo.due(step, last);
        let dump = setup
            || self
                .dumps
                .iter()
                .any(|d| d.every > 0 && step % d.every == 0);
        if !thermo && !dump {
            return Ok(());
        }
        // the rows of the local computes the due dumps write, every rank's gathered
        let local_rows = self.rank_local_rows(comm, st, setup)?;
        // the per-atom virials of a stress compute, in the order of the particles below
        let virials = (self.virial_step == Some(step)).then(|| {
            let bytes: Vec<u8> = self
                .virial
                .iter()
                .flatten()
                .flat_map(|v| v.to_le_bytes())
                .collect();
            comm.gather_bytes(&bytes)
        });
        let Some(all) = comm.gather_bytes(&self.pack_owned(st, None)) else {
            // what rank 0 writes is written: the dumps' records agree on every rank
            for k in 0..self.dumps.len() {
                if self.dump_due(k, setup) {
                    self.dumps[k].last_written = Some(step);
                }
            }
            return Ok(());
        };
        let mut full = empty_like(&self.particles);
        for bytes in &all {
            let mut r = Reader::new(bytes);
            while !r.done() {
                unpack_particle(&mut r, &mut full, None)?;
            }
        }
        let mut full_virial: Vec<[f64; 6]> = virials
            .flatten()
            .unwrap_or_default()
            .concat()
            .chunks_exact(48)
            .map(|row| {
                std::array::from_fn(|c| {
                    f64::from_le_bytes(row[8 * c..8 * c + 8].try_into().unwrap_or([0; 8]))
                })
            })
            .collect();
        std::mem::swap(&mut self.particles, &mut full);
        std::mem::swap(&mut self.virial, &mut full_virial);
        let written = || -> Result<(), EngineError> {
            if thermo {
                self.thermo_line(out, vars)?;
            }
            self.write_dumps_with(setup, vars, local_rows)
        };
        let result = written();
        std::mem::swap(&mut self.particles, &mut full);
        std::mem::swap(&mut self.virial, &mut full_virial);
        result
    }

    /// The rows of the local computes that the dumps due at this step write: each rank
    /// evaluates its own contacts ([`Self::rank_contact_view`]) and rank 0 gets every
    /// rank's rows, in rank order (as LIGGGHTS's parallel `dump local` writes them; empty
    /// on the other ranks).
    fn rank_local_rows(
        &mut self,
        comm: &RankComm,
        st: &mut RankState,
        setup: bool,
    ) -> Result<SharedLocalRows, EngineError> {
        let mut wanted: Vec<String> = Vec::new();
        for k in 0..self.dumps.len() {
            if self.dump_due(k, setup) {
                for id in self.dumps[k].style.local_computes() {
                    if !wanted.contains(&id) {
                        wanted.push(id);
                    }
                }
            }
        }
        let mut shared = SharedLocalRows::new();
        if wanted.is_empty() {
            return Ok(shared);
        }
        // the ghosts behind the owned particles with this moment's positions and motion
        self.particles.extend_from(&st.ghosts);
        let p = &mut self.particles;
        if let Err(e) = forward_with(comm, &st.dec, &st.plan, p, false, &mut st.swap) {
            self.particles.truncate(st.nlocal);
            return Err(e.into());
        }
        let (pairs, history, motion) = self.rank_contact_view(st);
        let list_pairs = std::mem::replace(&mut self.list.pairs, pairs);
        let list_history = std::mem::replace(&mut self.history, history);
        let force_time = std::mem::replace(&mut self.force_time_state, motion);
        let mut failed = None;
        let mut mine = Vec::new();
        for id in &wanted {
            // every rank takes part in the gather, whatever its evaluation gave
            let rows = match self.computes.iter().find(|c| &c.id == id) {
                Some(c) => c.local(self),
                None => Err(format!("Could not find dump local compute ID {id}").into()),
            };
            let (ncols, values) = rows.unwrap_or_else(|e| {
                failed.get_or_insert(e);
                (0, Vec::new())
            });
            mine.push((ncols, values));
        }
        self.list.pairs = list_pairs;
        self.history = list_history;
        self.force_time_state = force_time;
        self.particles.truncate(st.nlocal);
        for (id, (ncols, values)) in wanted.iter().zip(mine) {
            let mut w = Writer::default();
            w.u32(ncols as u32);
            values.iter().for_each(|&v| w.f64(v));
            if let Some(all) = comm.gather_bytes(&w.bytes) {
                let (mut ncols, mut rows) = (0, Vec::new());
                for bytes in &all {
                    let mut r = Reader::new(bytes);
                    if r.done() {
                        continue;
                    }
                    ncols = ncols.max(r.u32()? as usize);
                    while !r.done() {
                        rows.push(r.f64()?);
                    }
                }
                shared.insert(id.clone(), std::rc::Rc::new((ncols, rows)));
            }
        }
        match failed {
            Some(e) => Err(e),
            None => Ok(shared),
        }
    }

    /// This rank's contacts as a local compute reads them on one process, for the owned
    /// particles and the ghosts behind them (refreshed): the ghosts moved back by their
    /// periodic images, with the pairs' shifts instead; only the pairs this rank reports
    /// (from an owned particle, as one process reports them: across a periodic face from
    /// the particle with the larger ID, otherwise from the one first in the exact path's
    /// order), with their contact history; the motion at the last force evaluation (the
    /// ghosts', which one process uses for the partner across a periodic face).
    fn rank_contact_view(&mut self, st: &RankState) -> (Vec<Pair>, Vec<f64>, Motion) {
        let n = st.nlocal;
        let length = [0, 1, 2].map(|d| self.domain.length(d));
        let p = &mut self.particles;
        let image = |i: usize| {
            i.checked_sub(n)
                .and_then(|g| st.plan.ghost_image.get(g).copied())
                .unwrap_or([0; 3])
        };
        for i in n..p.len() {
            let m = image(i);
            for d in 0..3 {
                if m[d] != 0 {
                    p.x[i][d] -= f64::from(m[d]) * length[d];
                }
            }
        }
        let k = p.extra.iter().position(|e| e.name == ORDER_ARRAY);
        let place = |i: usize| k.map_or(i as f64, |k| p.extra[k].data[i]);
        let width = st.flips.len();
        let (mut pairs, mut history) = (Vec::new(), Vec::new());
        for (k, pr) in st.pairs.iter().enumerate() {
            let (a, b) = (pr.i as usize, pr.j as usize);
            let (ma, mb) = (image(a), image(b));
            let reporter = if ma != [0; 3] || mb != [0; 3] {
                if p.id[a] > p.id[b] {
                    a
                } else {
                    b
                }
            } else if place(a) < place(b) {
                a
            } else {
                b
            };
            if reporter >= n {
                continue;
            }
            pairs.push(Pair {
                i: pr.i,
                j: pr.j,
                shift: [0, 1, 2].map(|d| f64::from(mb[d] - ma[d]) * length[d]),
            });
            history.extend_from_slice(&st.history[k * width..(k + 1) * width]);
        }
        let mut v = p.v[..n].to_vec();
        let mut omega = p.omega[..n].to_vec();
        if st.ghost_motion.0.len() == p.len() - n {
            v.extend_from_slice(&st.ghost_motion.0);
            omega.extend_from_slice(&st.ghost_motion.1);
        }
        (pairs, history, (v, omega))
    }

    /// The end of a run: every rank's particles and contact history on every rank, in
    /// the exact path's order (the order record dropped), the history kept by atom ID for
    /// the next run.
    fn rank_gather_all(&mut self, comm: &RankComm, st: &RankState) -> Result<(), EngineError> {
        let WholeSet {
            particles: full,
            partners,
            attached,
        } = self.rank_whole_set(comm, st)?;
        // the mesh walls' contacts of the whole set, in its order
        self.restore_wall_state(&attached, &full.id)?;
        if let Some(partners) = partners {
            self.pending_history = Some(PendingHistory {
                width: st.flips.len(),
                partners,
                live: true,
            });
        }
        self.particles = full;
        self.list = crate::engine::neighbor::NeighborList::default();
        self.list.builds = st.builds;
        self.history.clear();
        self.mirror_history.clear();
        self.list_ids.clear();
        Ok(())
    }

    /// Every rank's owned particles on every rank, in the exact path's order (the order
    /// record dropped), with each particle's contacts by partner ID (None without history
    /// in the pair model); the run's own state is left as it is.
    fn rank_whole_set(&self, comm: &RankComm, st: &RankState) -> Result<WholeSet, EngineError> {
        let mut hist = PartnerHistory::from_pairs(
            &st.pairs,
            &st.history,
            &st.ids(&self.particles),
            st.nlocal,
            &st.flips,
        );
        self.attach_wall_state(&mut hist, &self.particles.id[..st.nlocal]);
        let mine = self.pack_owned(st, Some(&hist));
        let mut all = comm
            .gather_bytes(&mine)
            .map(|v| v.concat())
            .unwrap_or_default();
        comm.broadcast_bytes(0, &mut all);
        let mut full = empty_like(&self.particles);
        let mut rows = PartnerHistory::new(hist.width, 0);
        let mut r = Reader::new(&all);
        while !r.done() {
            unpack_particle(&mut r, &mut full, Some(&mut rows))?;
        }
        let width = hist.width;
        let partners = (width > 0).then(|| {
            let mut partners = HashMap::new();
            for (i, id) in full.id.iter().enumerate() {
                let contacts: Vec<(i64, Vec<f64>)> = rows.partners[i]
                    .iter()
                    .zip(rows.values[i].chunks(width))
                    .map(|(&p, v)| (p, v.to_vec()))
                    .collect();
                if !contacts.is_empty() {
                    partners.insert(*id, contacts);
                }
            }
            partners
        });
        let mut attached = rows.attached;
        if let Some(k) = full.extra.iter().position(|e| e.name == ORDER_ARRAY) {
            let ranks = full.extra[k].data.clone();
            let mut order: Vec<usize> = (0..ranks.len()).collect();
            order.sort_by(|&a, &b| ranks[a].total_cmp(&ranks[b]));
            full.permute(&order);
            full.extra.remove(k);
            attached = order
                .iter()
                .map(|&k| attached.get_mut(k).map(std::mem::take).unwrap_or_default())
                .collect();
        }
        Ok(WholeSet {
            particles: full,
            partners,
            attached,
        })
    }

    /// The `restart` command's files due at this step, written from every rank's particles
    /// gathered in the exact path's order: one file by rank 0 (what one process holding the
    /// particles in that order writes), or for a `%` name LIGGGHTS's base file and one file
    /// per rank (as `write_restart` between runs). Positions are not re-wrapped (the run
    /// goes on), as on one process.
    fn rank_periodic_restart(
        &mut self,
        comm: &RankComm,
        st: &RankState,
    ) -> Result<(), EngineError> {
        let paths = self.restart_paths_due();
        if paths.is_empty() {
            return Ok(());
        }
        let WholeSet {
            particles: mut full,
            partners,
            attached,
        } = self.rank_whole_set(comm, st)?;
        let mut partners = partners.unwrap_or_default();
        // each particle's contacts by partner ID, as the fast path lists them on one process
        for contacts in partners.values_mut() {
            contacts.sort_by_key(|c| c.0);
        }
        // the mesh walls' contacts of the whole set while the files are written
        let trackers = self.save_wall_trackers();
        self.restore_wall_state(&attached, &full.id)?;
        std::mem::swap(&mut self.particles, &mut full);
        let written = (|| {
            self.check_restart_size()?;
            let r = self.to_restart(&partners);
            for path in &paths {
                self.save_restart_on_ranks(comm, &r, path)?;
            }
            Ok(())
        })();
        std::mem::swap(&mut self.particles, &mut full);
        self.put_wall_trackers(trackers);
        written
    }

    /// LIGGGHTS's per-process counts after a run (ave, max, min over ranks) and the
    /// neighbour-list figures.
    fn rank_statistics(&self, comm: &RankComm, st: &RankState, loop_time: f64) -> String {
        use crate::util::format::g;
        let n = comm.size() as f64;
        let nghost = st.ghosts.len();
        let mut s = String::new();
        // the time split, each part averaged over the ranks, as LIGGGHTS prints it
        let t = &self.stats;
        let mut parts = [t.pair, t.neigh, t.comm, t.output];
        comm.all_reduce_f64(&mut parts, Reduce::Sum);
        let parts = parts.map(|v| v / n);
        let other = (loop_time - parts.iter().sum::<f64>()).max(0.0);
        let names = ["Pair ", "Neigh", "Comm ", "Outpt", "Other"];
        for (name, v) in names.iter().zip(parts.iter().chain([&other])) {
            let pct = if loop_time > 0.0 {
                100.0 * v / loop_time
            } else {
                0.0
            };
            s.push_str(&format!("{name} time (%) = {} ({})\n", g(*v), g(pct)));
        }
        s.push('\n');
        let mut total_neighs = 0.0;
        for (name, v) in [
            ("Nlocal", st.nlocal as f64),
            ("Nghost", nghost as f64),
            ("Neighs", st.pairs.len() as f64),
        ] {
            let mut sum = [v];
            let mut max = [v];
            let mut min = [v];
            comm.all_reduce_f64(&mut sum, Reduce::Sum);
            comm.all_reduce_f64(&mut max, Reduce::Max);
            comm.all_reduce_f64(&mut min, Reduce::Min);
            if name == "Neighs" {
                total_neighs = sum[0];
            }
            s.push_str(&format!(
                "{name}:    {} ave {} max {} min\n",
                g(sum[0] / n),
                g(max[0]),
                g(min[0])
            ));
        }
        let natoms = self.natoms_expected.max(1) as f64;
        s.push_str(&format!("\nTotal # of neighbors = {}\n", g(total_neighs)));
        s.push_str(&format!("Ave neighs/atom = {}\n", g(total_neighs / natoms)));
        s.push_str(&format!("Neighbor list builds = {}\n", self.stats.builds));
        s.push_str(&format!("Dangerous builds = {}\n\n", self.stats.dangerous));
        s
    }
}

/// Vectors whose rows follow the particles when some are removed.
trait RetainBy {
    /// Remove the rows for which `remove` is true, keeping the others' order.
    fn retain_by(&mut self, remove: &[bool]);
}

impl<T> RetainBy for Vec<T> {
    fn retain_by(&mut self, remove: &[bool]) {
        let mut k = 0;
        self.retain(|_| {
            let keep = !remove.get(k).copied().unwrap_or(false);
            k += 1;
            keep
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Particles on a jittered grid with mixed radii (IDs in reverse order of storage).
    fn cloud(n: usize) -> Particles {
        let mut p = Particles::default();
        let mut s = 12345u64;
        let mut r = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..n {
            let x = [r() * 0.02, r() * 0.02, r() * 0.01];
            p.push((n - k) as i64, 1, x, 0.0008 + 0.0006 * r(), 2500.0);
        }
        p
    }

    #[test]
    fn the_cell_search_lists_every_pair_within_reach_once_by_key() {
        let p = cloud(800);
        let (nlocal, skin) = (500, 0.0005);
        let grid = KeyGrid::new([0.0; 3], [0.02, 0.02, 0.01], 0.0025);
        let cells: Vec<u64> = p.x.iter().map(|&x| grid.cell(x)).collect();
        assert_eq!(grid.dims, [8, 8, 4]);
        let key = |k: usize| (cells[k], p.id[k]);
        let pairs = rank_pairs(&p, nlocal, skin, &cells);
        let mut want = Vec::new();
        for i in 0..p.len() {
            for j in i + 1..p.len() {
                if i >= nlocal && j >= nlocal {
                    continue;
                }
                let d = [0, 1, 2].map(|k| p.x[i][k] - p.x[j][k]);
                let cut = p.radius[i] + p.radius[j] + skin;
                if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < cut * cut {
                    want.push(if key(j) < key(i) { (j, i) } else { (i, j) });
                }
            }
        }
        let mut got: Vec<(usize, usize)> =
            pairs.iter().map(|q| (q.i as usize, q.j as usize)).collect();
        let keys = |v: &[(usize, usize)]| -> Vec<((u64, i64), (u64, i64))> {
            v.iter().map(|&(a, b)| (key(a), key(b))).collect()
        };
        // listed in key order, the lower key first
        let listed = keys(&got);
        assert!(listed.windows(2).all(|w| w[0] < w[1]));
        assert!(listed.iter().all(|&(a, b)| a < b));
        got.sort_unstable();
        want.sort_unstable();
        assert!(want.len() > 1000, "{} pairs", want.len());
        assert_eq!(got, want);
        // owned particles stored by key, as a build leaves them: the same list by the merge
        let mut order: Vec<usize> = (0..nlocal).collect();
        order.sort_unstable_by_key(|&k| key(k));
        order.extend(nlocal..p.len());
        let mut q = p.clone();
        q.permute(&order);
        let cells_q: Vec<u64> = q.x.iter().map(|&x| grid.cell(x)).collect();
        let merged = rank_pairs(&q, nlocal, skin, &cells_q);
        let as_ids = |v: &[Pair], p: &Particles| -> Vec<(i64, i64)> {
            v.iter()
                .map(|e| (p.id[e.i as usize], p.id[e.j as usize]))
                .collect()
        };
        assert_eq!(as_ids(&merged, &q), as_ids(&pairs, &p));
    }

    #[test]
    fn ghosts_set_apart_and_copied_back_are_the_same_rows() {
        let mut p = cloud(50);
        let k = p.extra_index("history_w", 3);
        for (n, v) in p.extra[k].data.iter_mut().enumerate() {
            *v = n as f64;
        }
        let whole = p.clone();
        let mut ghosts = empty_like(&p);
        p.copy_tail_into(30, &mut ghosts);
        p.truncate(30);
        assert_eq!((p.len(), ghosts.len()), (30, 20));
        p.extend_from(&ghosts);
        assert_eq!(p.x, whole.x);
        assert_eq!(p.id, whole.id);
        assert_eq!(p.extra, whole.extra);
        // an array made while the ghosts were apart gets its fill values for them
        p.truncate(30);
        let k = p.extra_index("new", 2);
        p.extra[k].fill = vec![7.0, 8.0];
        p.extend_from(&ghosts);
        assert_eq!(p.extra[k].data.len(), 100);
        assert_eq!(&p.extra[k].data[98..], &[7.0, 8.0]);
    }
}
