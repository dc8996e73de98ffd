//! A team of worker threads that stay awake between the short parallel stages of a time step,
//! as OpenMP's active wait does: handing a stage to the team costs an atomic store and a
//! spin, not a thread wake-up (which on a virtual machine takes tens of microseconds, as
//! long as a whole stage of a 10 000-particle step). A worker idle for [`SPIN`] parks until
//! the next stage, so a team costs nothing between runs.
//!
//! A stage is `tasks` numbered tasks cut into one contiguous share per thread, in thread
//! order: each thread takes the tasks of its own share first (an atomic counter per share),
//! then helps with the others' shares. Stages over the same particles thus run mostly on the
//! same thread, so a particle's data stay in one core's cache from stage to stage and step to
//! step: handing tasks out from a single counter moved them between cores, which on a
//! virtual machine whose cores share no cache cost as much as the second thread gained.
//! Which thread runs which task still varies from run to run, so a task must write only its
//! own data (see [`Shards`]) and combine results in task order: then a stage gives the same
//! answer for any number of threads.

use std::cell::{Cell, UnsafeCell};
use std::marker::PhantomData;
use std::ops::Range;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering::Relaxed, Ordering::SeqCst};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// How long an idle worker spins for the next stage before it parks.
pub const SPIN: Duration = Duration::from_millis(1);

/// One stage's work, its lifetime erased (the stage waits for every worker that joined it
/// before it returns, so the closure outlives every use).
type Job = *const (dyn Fn(usize) + Sync + 'static);

/// What the thread that hands out stages and the workers share.
struct Shared {
    /// The stage number times two, plus one while the stage is open for workers to join.
    state: AtomicU64,
    /// The open stage's work.
    job: UnsafeCell<Option<Job>>,
    /// The open stage's number of tasks.
    tasks: AtomicUsize,
    /// Each thread's next task of its share (thread 0 hands out the stages; worker `me` is
    /// thread `me + 1`).
    next: Vec<Counter>,
    /// Workers inside the current stage.
    active: AtomicUsize,
    /// A worker's task panicked in the current stage.
    panicked: AtomicBool,
    /// Each worker's "parked (or about to park)" flag.
    parked: Vec<AtomicBool>,
    /// The team is being dropped.
    stop: AtomicBool,
    /// Stages stay on the thread that hands them out (see [`hold`]).
    held: AtomicBool,
}

// SAFETY: `job` is written only while no worker is inside a stage (the hand-out protocol
// below) and read only by workers that joined the open stage it belongs to.
unsafe impl Sync for Shared {}
unsafe impl Send for Shared {}

/// A task counter alone on its cache lines (threads count on their own without disturbing
/// each other).
#[repr(align(128))]
struct Counter(AtomicUsize);

/// The first task of thread `t`'s share of `tasks` tasks among `threads`.
fn share_start(t: usize, tasks: usize, threads: usize) -> usize {
    t * tasks / threads
}

impl Shared {
    /// Open the shares of a stage of `tasks` tasks.
    fn open_shares(&self, tasks: usize) {
        let threads = self.next.len();
        for (t, c) in self.next.iter().enumerate() {
            c.0.store(share_start(t, tasks, threads), SeqCst);
        }
    }

    /// Hand out no more tasks of the current stage.
    fn close_shares(&self) {
        for c in &self.next {
            c.0.store(usize::MAX / 2, SeqCst);
        }
    }

    /// Thread `me` runs tasks of `job`, its own share first, then what is left of the
    /// others' (in thread order after its own), until none are left; false if one panicked.
    fn work(&self, me: usize, job: &(dyn Fn(usize) + Sync)) -> bool {
        let tasks = self.tasks.load(SeqCst);
        let threads = self.next.len();
        catch_unwind(AssertUnwindSafe(|| {
            for k in 0..threads {
                let t = (me + k) % threads;
                let end = share_start(t + 1, tasks, threads);
                loop {
                    let task = self.next[t].0.fetch_add(1, SeqCst);
                    if task >= end {
                        break;
                    }
                    job(task);
                }
            }
        }))
        .is_ok()
    }
}

/// Worker threads for a run's per-step stages (`threads - 1` of them: the thread that hands
/// out a stage works on it too).
pub struct Team {
    shared: Arc<Shared>,
    workers: Vec<std::thread::JoinHandle<()>>,
}

impl std::fmt::Debug for Team {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Team({} threads)", self.threads())
    }
}

impl Team {
    /// A team of `threads` threads in all (the caller's and `threads - 1` workers).
    pub fn new(threads: usize) -> Team {
        let workers = threads.max(1) - 1;
        let shared = Arc::new(Shared {
            state: AtomicU64::new(0),
            job: UnsafeCell::new(None),
            tasks: AtomicUsize::new(0),
            next: (0..threads.max(1))
                .map(|_| Counter(AtomicUsize::new(usize::MAX / 2)))
                .collect(),
            active: AtomicUsize::new(0),
            panicked: AtomicBool::new(false),
            parked: (0..workers).map(|_| AtomicBool::new(false)).collect(),
            stop: AtomicBool::new(false),
            held: AtomicBool::new(false),
        });
        let workers = (0..workers)
            .map(|me| {
                let shared = Arc::clone(&shared);
                std::thread::Builder::new()
                    .name(format!("regolith-team-{}", me + 1))
                    .spawn(move || worker(&shared, me))
                    .expect("cannot start a worker thread")
            })
            .collect();
        Team { shared, workers }
    }

    /// Threads of the team, the caller's included.
    pub fn threads(&self) -> usize {
        self.workers.len() + 1
    }

    /// Run tasks `0..tasks` of `f` on the team (the calling thread included) and return when
    /// all are done. A panic in a task is raised again here.
    pub fn for_each(&self, tasks: usize, f: &(dyn Fn(usize) + Sync)) {
        if tasks <= 1 || self.workers.is_empty() {
            (0..tasks).for_each(f);
            return;
        }
        let s = &*self.shared;
        // SAFETY: only the lifetime is erased; `Close` below waits, on return and on unwind,
        // until no worker is inside this stage, and workers read `job` only inside it
        let job: Job = unsafe { std::mem::transmute::<&(dyn Fn(usize) + Sync), Job>(f) };
        // no worker is inside a stage here (the last one waited for them)
        unsafe { *s.job.get() = Some(job) };
        s.tasks.store(tasks, SeqCst);
        s.open_shares(tasks);
        s.panicked.store(false, SeqCst);
        let stage = (s.state.load(SeqCst) >> 1) + 1;
        s.state.store(stage << 1 | 1, SeqCst);
        for (w, parked) in self.workers.iter().zip(&s.parked) {
            if parked.load(SeqCst) {
                w.thread().unpark();
            }
        }
        let close = Close { s, stage };
        let mine = s.work(0, f);
        drop(close);
        assert!(mine, "a task of a parallel stage panicked");
        assert!(
            !s.panicked.load(SeqCst),
            "a task of a parallel stage panicked on a worker thread"
        );
    }

    /// [`Team::for_each`] over `0..n` cut into ranges of `chunk`: `f(task, range)`.
    pub fn for_each_chunk(&self, n: usize, chunk: usize, f: impl Fn(usize, Range<usize>) + Sync) {
        let chunk = chunk.max(1);
        self.for_each(n.div_ceil(chunk), &|k| {
            f(k, k * chunk..((k + 1) * chunk).min(n))
        });
    }
}

/// Closes a stage: no worker may join any more, and every worker inside has left.
struct Close<'a> {
    s: &'a Shared,
    stage: u64,
}

impl Drop for Close<'_> {
    fn drop(&mut self) {
        // no new worker takes a task (on unwind the main thread stopped taking them)
        self.s.close_shares();
        self.s.state.store(self.stage << 1, SeqCst);
        let mut spins = 0u32;
        while self.s.active.load(SeqCst) != 0 {
            // a worker descheduled mid-task (a busy machine) gets the core back sooner
            spins += 1;
            if spins.is_multiple_of(1024) {
                std::thread::yield_now();
            } else {
                std::hint::spin_loop();
            }
        }
    }
}

impl Drop for Team {
    fn drop(&mut self) {
        self.shared.stop.store(true, SeqCst);
        for w in &self.workers {
            w.thread().unpark();
        }
        for w in self.workers.drain(..) {
            let _ = w.join();
        }
    }
}

/// A worker: wait for each new stage (spinning, then parked), join it while it is open and
/// take its tasks.
fn worker(s: &Shared, me: usize) {
    let mut seen = 0u64;
    let mut idle_since = Instant::now();
    let mut spins = 0u32;
    loop {
        if s.stop.load(SeqCst) {
            return;
        }
        let state = s.state.load(SeqCst);
        let stage = state >> 1;
        if state & 1 == 1 && stage != seen {
            seen = stage;
            s.active.fetch_add(1, SeqCst);
            // joined only if the stage is still the open one (else its closer may be gone)
            if s.state.load(SeqCst) == state {
                // SAFETY: the stage is open and waits for this worker to leave it
                let job = unsafe { (*s.job.get()).expect("an open stage has work") };
                if !s.work(me + 1, unsafe { &*job }) {
                    s.panicked.store(true, SeqCst);
                }
            }
            s.active.fetch_sub(1, SeqCst);
            idle_since = Instant::now();
            spins = 0;
            continue;
        }
        spins += 1;
        if spins.is_multiple_of(256) && idle_since.elapsed() > SPIN {
            s.parked[me].store(true, SeqCst);
            let now = s.state.load(SeqCst);
            let waiting = now & 1 == 1 && now >> 1 != seen;
            if !waiting && !s.stop.load(SeqCst) {
                std::thread::park_timeout(Duration::from_millis(100));
            }
            s.parked[me].store(false, SeqCst);
            idle_since = Instant::now();
        } else if spins.is_multiple_of(64) {
            // on a busy machine, let others run now and then while waiting
            std::thread::yield_now();
        } else {
            std::hint::spin_loop();
        }
    }
}

thread_local! {
    /// The team of the run on this thread, if any.
    static ACTIVE: Cell<Option<*const Team>> = const { Cell::new(None) };
}

/// Keeps a team active on this thread (see [`activate`]).
pub struct Active<'a> {
    before: Option<*const Team>,
    _team: PhantomData<&'a Team>,
}

impl Drop for Active<'_> {
    fn drop(&mut self) {
        ACTIVE.with(|a| a.set(self.before));
    }
}

/// Make `team` the one [`stage`] uses on this thread until the returned guard drops.
pub fn activate(team: Option<&Team>) -> Active<'_> {
    let before = ACTIVE.with(|a| a.replace(team.map(|t| t as *const Team)));
    Active {
        before,
        _team: PhantomData,
    }
}

/// The active team of this thread.
fn active() -> Option<&'static Team> {
    // SAFETY: the guard that set it outlives every use on this thread (it is reset on drop)
    ACTIVE.with(|a| a.get()).map(|t| unsafe { &*t })
}

/// Is a team of more than one thread active on this thread and sharing out stages (not
/// [`held`])?
pub fn is_active() -> bool {
    active().is_some_and(|t| t.threads() > 1 && !t.shared.held.load(Relaxed))
}

/// Keep the active team's stages on this thread (`true`) or share them out again (`false`).
/// Results do not change (a stage gives the same answer for any number of threads); the
/// workers park once idle.
pub fn hold(on: bool) {
    if let Some(team) = active() {
        team.shared.held.store(on, Relaxed);
    }
}

/// Are the active team's stages held on this thread (see [`hold`])?
pub fn held() -> bool {
    active().is_some_and(|t| t.shared.held.load(Relaxed))
}

/// Run tasks `0..tasks` on the active team (unless it is [`held`]), else on rayon's threads,
/// when `parallel`; else in order on this thread.
pub fn stage(tasks: usize, parallel: bool, f: impl Fn(usize) + Sync) {
    match active() {
        Some(team) if team.threads() > 1 => {
            if parallel && !team.shared.held.load(Relaxed) {
                team.for_each(tasks, &f)
            } else {
                (0..tasks).for_each(f)
            }
        }
        _ if parallel && tasks > 1 => {
            use rayon::prelude::*;
            (0..tasks).into_par_iter().with_max_len(1).for_each(&f)
        }
        _ => (0..tasks).for_each(f),
    }
}

/// [`stage`] over `0..n` cut into ranges of `chunk`: `f(task, range)`.
pub fn stage_chunks(
    n: usize,
    chunk: usize,
    parallel: bool,
    f: impl Fn(usize, Range<usize>) + Sync,
) {
    let chunk = chunk.max(1);
    stage(n.div_ceil(chunk), parallel, |k| {
        f(k, k * chunk..((k + 1) * chunk).min(n))
    });
}

/// A mutable slice shared by a stage's tasks, each taking its own range.
pub struct Shards<'a, T> {
    ptr: *mut T,
    len: usize,
    _slice: PhantomData<&'a mut [T]>,
}

// SAFETY: tasks take disjoint ranges (the contract of `range`), as `par_chunks_mut` would
unsafe impl<T: Send> Sync for Shards<'_, T> {}
unsafe impl<T: Send> Send for Shards<'_, T> {}

impl<'a, T> Shards<'a, T> {
    /// Share `slice` among a stage's tasks.
    pub fn new(slice: &'a mut [T]) -> Self {
        Shards {
            ptr: slice.as_mut_ptr(),
            len: slice.len(),
            _slice: PhantomData,
        }
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.len
    }

    /// No elements.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The elements `r`.
    ///
    /// # Safety
    /// No two ranges in use at the same time may overlap (each task its own).
    #[allow(clippy::mut_from_ref)]
    pub unsafe fn range(&self, r: Range<usize>) -> &mut [T] {
        assert!(r.start <= r.end && r.end <= self.len, "shard out of range");
        // SAFETY: in bounds (checked), disjoint from other tasks' (the caller's contract)
        unsafe { std::slice::from_raw_parts_mut(self.ptr.add(r.start), r.end - r.start) }
    }
}

/// The first index below `n` where `test` holds, each task testing `chunk` indices (the same
/// answer for any number of threads).
pub fn first_where(
    n: usize,
    chunk: usize,
    parallel: bool,
    test: impl Fn(usize) -> bool + Sync,
) -> Option<usize> {
    let first = AtomicUsize::new(usize::MAX);
    stage_chunks(n, chunk, parallel, |_, r| {
        if r.start >= first.load(SeqCst) {
            return;
        }
        if let Some(i) = r.into_iter().find(|&i| test(i)) {
            first.fetch_min(i, SeqCst);
        }
    });
    Some(first.into_inner()).filter(|&i| i != usize::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_task_runs_once_for_any_team_size() {
        for threads in 1..=3 {
            let team = Team::new(threads);
            for tasks in [0, 1, 2, 7, 100] {
                let counts: Vec<AtomicUsize> = (0..tasks).map(|_| AtomicUsize::new(0)).collect();
                for _ in 0..50 {
                    team.for_each(tasks, &|k| {
                        counts[k].fetch_add(1, SeqCst);
                    });
                }
                assert!(
                    counts.iter().all(|c| c.load(SeqCst) == 50),
                    "{threads} {tasks}"
                );
            }
        }
    }

    #[test]
    fn shards_give_each_task_its_own_range() {
        let team = Team::new(3);
        let _on = activate(Some(&team));
        let mut v = vec![0usize; 10_000];
        let shards = Shards::new(&mut v);
        stage_chunks(10_000, 333, true, |_, r| {
            // SAFETY: the chunks of one stage are disjoint
            for (k, x) in unsafe { shards.range(r.clone()) }.iter_mut().enumerate() {
                *x = r.start + k;
            }
        });
        assert!(v.iter().enumerate().all(|(i, &x)| i == x));
    }

    #[test]
    fn a_held_team_runs_every_task_on_the_calling_thread() {
        let team = Team::new(2);
        let _on = activate(Some(&team));
        let me = std::thread::current().id();
        let others = AtomicUsize::new(0);
        let count = |others: &AtomicUsize| {
            stage(64, true, |_| {
                if std::thread::current().id() != me {
                    others.fetch_add(1, SeqCst);
                }
                // long enough for the worker to join an open stage
                std::thread::sleep(Duration::from_millis(1));
            })
        };
        hold(true);
        assert!(held() && !is_active());
        count(&others);
        assert_eq!(others.load(SeqCst), 0, "a held stage went to a worker");
        hold(false);
        assert!(!held() && is_active());
        count(&others);
        assert!(
            others.load(SeqCst) > 0,
            "the released team shared nothing out"
        );
        // a stage that is not parallel stays on this thread with the team active
        let before = others.load(SeqCst);
        stage(64, false, |_| {
            if std::thread::current().id() != me {
                others.fetch_add(1, SeqCst);
            }
        });
        assert_eq!(others.load(SeqCst), before);
    }

    #[test]
    fn first_where_finds_the_smallest_index() {
        let team = Team::new(2);
        let _on = activate(Some(&team));
        let hits = [977usize, 5_003, 9_999];
        for _ in 0..20 {
            let found = first_where(10_000, 100, true, |i| hits.contains(&i));
            assert_eq!(found, Some(977));
        }
        assert_eq!(first_where(10_000, 100, true, |_| false), None);
    }

    #[test]
    fn a_worker_parks_and_wakes_for_the_next_stage() {
        let team = Team::new(2);
        let sum = AtomicUsize::new(0);
        team.for_each(4, &|k| {
            sum.fetch_add(k, SeqCst);
        });
        std::thread::sleep(SPIN * 5);
        team.for_each(4, &|k| {
            sum.fetch_add(k, SeqCst);
        });
        assert_eq!(sum.load(SeqCst), 12);
    }

    #[test]
    fn a_panicking_task_is_raised_by_the_stage() {
        let team = Team::new(2);
        let r = catch_unwind(AssertUnwindSafe(|| {
            team.for_each(64, &|k| {
                if k == 40 {
                    panic!("task 40");
                }
            })
        }));
        assert!(r.is_err());
        // the team still works afterwards
        let n = AtomicUsize::new(0);
        team.for_each(8, &|_| {
            n.fetch_add(1, SeqCst);
        });
        assert_eq!(n.load(SeqCst), 8);
    }
}
