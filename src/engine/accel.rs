//! The fast engine path (`-sf fast`, `suffix fast`) and the engine's threads (`-pk fast N`,
//! `package fast N`, or `RAYON_NUM_THREADS`).
//!
//! The fast path differs from the exact path only where order matters: particles are
//! re-sorted by cell at every neighbour-list build (so particles that interact sit together
//! in memory), the half list is built from those cells in parallel in its own order, and
//! every parallel stage adds contributions in an order fixed by the list, so results are
//! bit-identical for any number of threads. Contact models, fixes, computes and outputs are
//! the exact path's. At the end of each run the particles are put back in the order the
//! exact path would hold them in (LIGGGHTS's spatial sort every `atom_modify sort` steps,
//! inserted particles last), so commands between runs (`delete_atoms` renumbering IDs,
//! unsorted dumps) see the same order.

use std::sync::Arc;

/// Stack of the engine's threads (bytes): a run, with the commands `run ... every` executes,
/// may run on one of them.
const ENGINE_STACK: usize = 64 << 20;

/// rayon's global pool was built here (so its threads have the engine's stack size).
static GLOBAL_POOL_OURS: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// A value handed to the engine's thread that runs a whole `run` command, while the thread
/// that owns it waits for the run to end (so the value is never used by two threads at
/// once). Parallel stages started from an engine thread cost a few microseconds; started
/// from outside the thread pool, each costs a hand-over of about 20 us both ways, which on
/// a 10 000-sphere bed made two threads slower than one.
pub struct Handed<T>(pub T);

// SAFETY: `Accel::run_on_engine_thread` runs its job on one thread while the calling thread
// is blocked until the job ends: the handed value is used by one thread at a time.
unsafe impl<T> Send for Handed<T> {}

impl<T> Handed<T> {
    /// The value.
    pub fn get(&mut self) -> &mut T {
        &mut self.0
    }
}

/// What `-suffix`/`suffix` accept.
pub const SUFFIX_HELP: &str = "regolith's accelerator is `fast` (its own order of summation, \
    threads); `off` returns to the exact path, whose results are bit-identical to LIGGGHTS";

/// What `-package`/`package` accept.
pub const PACKAGE_HELP: &str = "write `fast N` with N >= 1 threads, e.g. -pk fast 2";

/// `-suffix STYLE` / `suffix STYLE`: true for `fast`, false for `off`.
pub fn parse_suffix(style: &str) -> Result<bool, AccelError> {
    match style {
        "fast" | "on" => Ok(true),
        "off" => Ok(false),
        other => Err(AccelError::Suffix(other.to_string())),
    }
}

/// `-package fast N` / `package fast N`: the thread count.
pub fn parse_package(style: &str, n: &str) -> Result<usize, AccelError> {
    if style != "fast" {
        return Err(AccelError::Package(style.to_string()));
    }
    match n.parse::<usize>() {
        Ok(k) if k >= 1 => Ok(k),
        _ => Err(AccelError::Threads(n.to_string())),
    }
}

/// A refused accelerator switch (`-sf`/`suffix`, `-pk`/`package`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum AccelError {
    /// An accelerator style other than `fast`/`off`.
    #[error(
        "suffix {0}: not supported (LAMMPS's gpu/intel/kk/omp/opt accelerators are not part of regolith)"
    )]
    Suffix(String),
    /// A package other than `fast`.
    #[error("package {0}: not supported (regolith's package is fast)")]
    Package(String),
    /// A thread count that is not an integer >= 1.
    #[error("package fast {0}: the thread count must be an integer >= 1")]
    Threads(String),
}

/// Name of the per-particle array holding the fast path's record of the exact order.
pub const ORDER_ARRAY: &str = "regolith:order";

/// Engine path and threads.
#[derive(Clone, Default)]
pub struct Accel {
    /// The fast path is on.
    pub fast: bool,
    /// Threads in use (None: rayon's default, all cores or `RAYON_NUM_THREADS`).
    pub threads: Option<usize>,
    /// The command line or the deck asked for a thread count (`-pk fast N`, `package`).
    pub asked: bool,
    /// MPI ranks sharing this machine (0 or 1: none other): the cores are shared out
    /// between them.
    pub ranks_per_node: usize,
    pool: Option<Arc<rayon::ThreadPool>>,
    /// The next rank handed to an inserted particle (fast path order record).
    pub next_rank: f64,
    /// What the fast path runs with the exact path's code, already said (said once).
    pub said: Vec<String>,
    /// The last list build fell back to the general search (the box is too short).
    pub general_list: bool,
    /// The fast path's team for a run's per-step stages (made at the first run that has
    /// more than one thread; its size follows the thread count).
    team: Option<Arc<crate::util::team::Team>>,
    /// Whether a small run's stages go to the team, measured and kept from run to run (a
    /// deck's runs one after the other are mostly the same scene).
    pub tuner: crate::util::tuner::Tuner,
}

impl std::fmt::Debug for Accel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Accel")
            .field("fast", &self.fast)
            .field("threads", &self.threads)
            .finish()
    }
}

impl Accel {
    /// Use `n` threads, as asked by `-pk fast N` or `package fast N` (None: not asked).
    pub fn ask_threads(&mut self, n: Option<usize>) {
        self.asked |= n.is_some();
        if n.is_some() {
            self.set_threads(n);
        }
    }

    /// The threads of a run nobody chose them for, decided when a run starts: every core (or
    /// `RAYON_NUM_THREADS`; under MPI the machine's cores shared out between its ranks) on
    /// the fast path, whose sums by blocks of particles split across
    /// threads; one on the exact path (its parallel sums gather every contact in list
    /// order and do not pay on two cores) unless `RAYON_NUM_THREADS` is set.
    pub fn settle_threads(&mut self) {
        if self.asked {
            return;
        }
        let env = std::env::var_os("RAYON_NUM_THREADS").is_some();
        let want = if env {
            None
        } else if self.fast && self.ranks_per_node > 1 {
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            Some((cores / self.ranks_per_node).max(1))
        } else if self.fast {
            None
        } else {
            Some(1)
        };
        if want != self.threads || (want.is_none() && self.pool.is_some()) {
            self.set_threads(want);
        }
    }

    /// Use `n` threads (None: rayon's default). The first request sizes rayon's global
    /// pool (no hand-off between threads per call); a later, different request gets a pool
    /// of its own.
    fn set_threads(&mut self, n: Option<usize>) {
        if n == self.threads {
            return;
        }
        self.threads = n;
        self.pool = None;
        // None: every core (or RAYON_NUM_THREADS), even when the global pool was sized smaller
        let n = n.unwrap_or_else(|| {
            std::env::var("RAYON_NUM_THREADS")
                .ok()
                .and_then(|v| v.parse().ok())
                .filter(|&n: &usize| n > 0)
                .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        });
        let global = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .stack_size(ENGINE_STACK)
            .build_global();
        if global.is_ok() {
            GLOBAL_POOL_OURS.store(true, std::sync::atomic::Ordering::Relaxed);
            return;
        }
        // the global pool, if built here with the same size; else a pool of the engine's own
        if rayon::current_num_threads() == n
            && GLOBAL_POOL_OURS.load(std::sync::atomic::Ordering::Relaxed)
        {
            return;
        }
        self.pool = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .stack_size(ENGINE_STACK)
            .build()
            .ok()
            .map(Arc::new);
    }

    /// Run a whole `run` command on one of the engine's threads (see [`Handed`]).
    pub fn run_on_engine_thread<R: Send>(&self, f: impl FnOnce() -> R + Send) -> R {
        match &self.pool {
            Some(p) => p.install(f),
            // rayon's global pool, if this module built it (with the engine's stack size)
            None if rayon::current_thread_index().is_none()
                && rayon::current_num_threads() > 1
                && GLOBAL_POOL_OURS.load(std::sync::atomic::Ordering::Relaxed) =>
            {
                rayon::scope(|_| f())
            }
            None => f(),
        }
    }

    /// Run `f` on the engine's threads.
    pub fn install<R: Send>(&self, f: impl FnOnce() -> R + Send) -> R {
        match &self.pool {
            Some(p) => p.install(f),
            None => f(),
        }
    }

    /// The team a fast-path run's per-step stages use (None on the exact path or one thread).
    pub fn team(&mut self) -> Option<Arc<crate::util::team::Team>> {
        let n = self.thread_count();
        if !self.fast || n < 2 {
            return None;
        }
        if self.team.as_ref().is_none_or(|t| t.threads() != n) {
            self.team = Some(Arc::new(crate::util::team::Team::new(n)));
        }
        self.team.clone()
    }

    /// Number of threads parallel stages use.
    pub fn thread_count(&self) -> usize {
        match &self.pool {
            Some(p) => p.current_num_threads(),
            None => rayon::current_num_threads(),
        }
    }
}

use crate::engine::cells::CellGrid;
use crate::engine::sim::Simulation;

impl Simulation {
    /// Fast path: sort the particles by cell and build the half list from the cells, in
    /// parallel. False (nothing done) when the box is too short for the cell search; the
    /// general build runs instead.
    pub(crate) fn build_list_fast(&mut self) -> bool {
        let n = self.particles.len();
        if n == 0 {
            return false;
        }
        let skin = self.neighbor.skin;
        let max_reach = self.particles.radius.iter().copied().fold(0.0, f64::max);
        let domain = self.list_domain();
        let Some(grid) = CellGrid::new(&self.particles.x, 2.0 * max_reach + skin, &domain) else {
            self.accel.general_list = true;
            return false;
        };
        self.assign_ranks();
        let x = &self.particles.x;
        let (order, start) = self.accel.install(|| grid.sort(x));
        if order.iter().enumerate().any(|(k, &i)| k != i) {
            self.particles.permute(&order);
            if let Some(removal) = &mut self.removal {
                removal.permute(&order);
            }
        }
        let chunk = n.div_ceil(self.accel.thread_count() * 8).max(512);
        let p = &self.particles;
        let pairs = self
            .accel
            .install(|| grid.half_list(&p.x, &p.radius, skin, &start, chunk));
        self.list.assign(pairs, &p.x, &p.radius);
        true
    }

    /// Fast path, at the start of a run: record the current (exact) order of the particles.
    pub(crate) fn start_order_record(&mut self) {
        let n = self.particles.len();
        let k = self.particles.extra_index(ORDER_ARRAY, 1);
        for (i, r) in self.particles.extra[k].data.iter_mut().enumerate() {
            *r = (i + 1) as f64;
        }
        self.accel.next_rank = (n + 1) as f64;
    }

    /// Fast path: particles inserted since the last look go last in the exact order, in
    /// the order they were inserted (appended).
    pub(crate) fn assign_ranks(&mut self) {
        let Some(k) = self.order_record_index() else {
            return;
        };
        for r in self.particles.extra[k].data.iter_mut() {
            if *r == 0.0 {
                *r = self.accel.next_rank;
                self.accel.next_rank += 1.0;
            }
        }
    }

    /// Fast path during a run: each particle's place in the exact path's order (1-based).
    pub(crate) fn exact_rank(&self) -> Option<&[f64]> {
        let k = self.order_record_index()?;
        Some(&self.particles.extra[k].data)
    }

    /// Index of the order record among the per-particle arrays, if there is one.
    fn order_record_index(&self) -> Option<usize> {
        self.particles
            .extra
            .iter()
            .position(|e| e.name == ORDER_ARRAY)
    }

    /// Fast path: LIGGGHTS's spatial sort applied to the record of the exact order (the
    /// exact path permutes the particles themselves at this point).
    pub(crate) fn sort_order_record(&mut self, sorted: impl Fn(&[[f64; 3]]) -> Option<Vec<u32>>) {
        self.assign_ranks();
        let Some(k) = self.order_record_index() else {
            return;
        };
        let ranks = &self.particles.extra[k].data;
        // the particles in exact order, their positions in that order
        let mut exact: Vec<usize> = (0..ranks.len()).collect();
        exact.sort_by(|&a, &b| ranks[a].total_cmp(&ranks[b]));
        let x: Vec<[f64; 3]> = exact.iter().map(|&i| self.particles.x[i]).collect();
        let Some(bins) = sorted(&x) else {
            return;
        };
        let mut order: Vec<usize> = (0..exact.len()).collect();
        order.sort_by_key(|&k| bins[k]);
        let data = &mut self.particles.extra[k].data;
        for (rank, &k) in order.iter().enumerate() {
            data[exact[k]] = (rank + 1) as f64;
        }
        self.accel.next_rank = (data.len() + 1) as f64;
    }

    /// Fast path, at the end of a run: put the particles back in the exact path's order
    /// and drop the record.
    pub(crate) fn restore_order(&mut self) {
        self.assign_ranks();
        let Some(k) = self.order_record_index() else {
            return;
        };
        let ranks = self.particles.extra[k].data.clone();
        let mut order: Vec<usize> = (0..ranks.len()).collect();
        order.sort_by(|&a, &b| ranks[a].total_cmp(&ranks[b]));
        if order.iter().enumerate().any(|(k, &i)| k != i) {
            self.permute_particles(&order);
        }
        self.particles.extra.remove(k);
    }

    /// Reorder the particles (`order`: new index -> old index) between list builds: the
    /// list, its history and every per-particle record of the last step follow them.
    pub(crate) fn permute_particles(&mut self, order: &[usize]) {
        self.particles.permute(order);
        if let Some(removal) = &mut self.removal {
            removal.permute(order);
        }
        let mut new_of_old = vec![0u32; order.len()];
        for (new, &old) in order.iter().enumerate() {
            new_of_old[old] = new as u32;
        }
        for pair in &mut self.list.pairs {
            pair.i = new_of_old[pair.i as usize];
            pair.j = new_of_old[pair.j as usize];
        }
        self.list.renumber_mirrors(&new_of_old);
        self.list.permute(order);
        let permute3 = |v: &mut Vec<[f64; 3]>| {
            if v.len() == order.len() {
                *v = order.iter().map(|&k| v[k]).collect();
            }
        };
        permute3(&mut self.force_time_state.0);
        permute3(&mut self.force_time_state.1);
        if self.virial.len() == order.len() {
            self.virial = order.iter().map(|&k| self.virial[k]).collect();
        }
        if self.list_ids.len() == order.len() {
            self.list_ids = order.iter().map(|&k| self.list_ids[k]).collect();
        }
        self.sum_order = Default::default();
        for fix in &mut self.fixes {
            if let Some(w) = fix.kind.mesh_wall_mut() {
                for t in &mut w.trackers {
                    t.permute(order);
                }
            }
        }
    }
}

impl Simulation {
    /// Fast path: name, once per deck, the parts of this run that run the exact path's code.
    pub(crate) fn say_unaccelerated(&mut self, out: &mut dyn FnMut(&str)) {
        use crate::engine::fixes::FixKind;
        let mut parts: Vec<&str> = Vec::new();
        for f in &self.fixes {
            let part = match &f.kind {
                kind if kind.mesh_wall().is_some() => "mesh walls (fix wall/gran ... mesh)",
                kind if kind.mover().is_some() => "moving meshes (fix move/mesh)",
                kind if kind.mesh().is_some_and(|m| m.stress.is_some()) => {
                    "mesh stresses (fix mesh/surface/stress)"
                }
                FixKind::Style(s) => match s.unaccelerated() {
                    Some(part) => part,
                    None => continue,
                },
                _ => continue,
            };
            if !parts.contains(&part) {
                parts.push(part);
            }
        }
        if self.accel.general_list {
            parts.push("the neighbour search (a periodic box shorter than three cutoffs)");
        }
        if self.pair_is_wet() {
            parts.push("liquid bridges (cohesion easo/capillary/viscous)");
        }
        if self
            .pair_selection
            .as_ref()
            .is_some_and(|s| s.surface == "multicontact")
        {
            parts.push("the pair contacts of surface multicontact");
        }
        let new: Vec<&str> = parts
            .into_iter()
            .filter(|p| !self.accel.said.iter().any(|s| s == p))
            .collect();
        if new.is_empty() {
            return;
        }
        out(&format!(
            "Fast path: {} run on the exact path's code (one thread, not accelerated yet)\n",
            new.join(", ")
        ));
        self.accel.said.extend(new.iter().map(|s| s.to_string()));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_nobody_chose_threads_for_use_every_core_on_the_fast_path_and_one_on_the_exact() {
        if std::env::var_os("RAYON_NUM_THREADS").is_some() {
            return; // the environment chose
        }
        let mut a = Accel::default();
        a.settle_threads();
        assert_eq!(a.thread_count(), 1);
        a.fast = true;
        a.settle_threads();
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        assert_eq!(a.thread_count(), cores);
        a.fast = false;
        a.settle_threads();
        assert_eq!(a.thread_count(), 1);
        // asked for: kept on either path
        let mut b = Accel::default();
        b.ask_threads(Some(3));
        b.fast = true;
        b.settle_threads();
        assert_eq!(b.thread_count(), 3);
        b.fast = false;
        b.settle_threads();
        assert_eq!(b.thread_count(), 3);
    }
}
