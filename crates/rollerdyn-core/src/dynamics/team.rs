//! A team of helper threads that share the calling thread's work on short, frequent
//! parallel maps (the contacts of one right-hand side, the columns of one Jacobian).
//!
//! A right-hand side of B1 takes about 130 µs, and the integrator calls one every 30 µs or
//! so of its own serial work (LU, solver). Threads that sleep between calls (rayon's pool)
//! take tens of microseconds to wake on this kind of machine, which ate most of the gain:
//! the right-hand side ran 1.23 times faster on two threads. Here the helpers spin for
//! [`SPIN`] after their last job before they sleep, so within a run they are awake when
//! the next map is posted, and the calling thread starts on the work at once; a helper
//! that is not awake in time is simply not waited for (the caller closes the job when its
//! own share is done and waits only for the helpers that have claimed it).
//!
//! Which thread computes which index does not change any value: every index is computed
//! alone and stored in its own slot ([`Team::map`]).

use std::cell::Cell;
use std::mem::{ManuallyDrop, MaybeUninit};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex, PoisonError, TryLockError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long a helper spins for a new job after its last one before it sleeps.
const SPIN: Duration = Duration::from_millis(2);

/// The ticket's lowest bit: the job is closed to new helpers.
const CLOSED: u64 = 1;
/// The ticket's count of helpers running the job, in bits 1..32.
const ACTIVE: u64 = 2;
/// The ticket's job generation, in bits 32..64.
const GENERATION: u64 = 1 << 32;

thread_local! {
    /// This thread's index in its team (0 outside any team; helper k is k + 1).
    static SLOT: Cell<usize> = const { Cell::new(0) };
}

/// The index of the calling thread in its team: 0 for a thread outside any team (the
/// caller of [`Team::map`]), k + 1 for helper k. For per-thread accumulators.
pub fn thread_slot() -> usize {
    SLOT.with(Cell::get)
}

/// A job: the caller's closure, its lifetime erased. It is only called while the ticket
/// counts the helper as active, and the caller does not return before that count is 0.
#[derive(Clone, Copy)]
struct Job(*const (dyn Fn() + Sync));

// SAFETY: the closure is Sync, and the protocol of `Team::run` keeps it alive while used.
unsafe impl Send for Job {}

struct Shared {
    /// Generation, active helpers and the closed bit (see the constants).
    ticket: AtomicU64,
    /// The posted job (set while the ticket is closed and no helper is active).
    job: Mutex<Option<Job>>,
    /// Helpers asleep, and the condition they sleep on (with `sleep`).
    sleeping: AtomicUsize,
    sleep: Mutex<()>,
    wake: Condvar,
    shutdown: AtomicBool,
}

/// Helper threads for [`Team::map`]; see the module doc.
pub struct Team {
    shared: Arc<Shared>,
    helpers: Vec<JoinHandle<()>>,
    /// Held by the one caller whose job is posted; a second caller computes alone.
    caller: Mutex<()>,
}

impl std::fmt::Debug for Team {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Team({} helpers)", self.helpers.len())
    }
}

impl Team {
    /// A team of `helpers` threads besides the caller's.
    pub fn new(helpers: usize) -> std::io::Result<Self> {
        let shared = Arc::new(Shared {
            ticket: AtomicU64::new(CLOSED),
            job: Mutex::new(None),
            sleeping: AtomicUsize::new(0),
            sleep: Mutex::new(()),
            wake: Condvar::new(),
            shutdown: AtomicBool::new(false),
        });
        let mut team = Team {
            shared: shared.clone(),
            helpers: Vec::with_capacity(helpers),
            caller: Mutex::new(()),
        };
        for k in 0..helpers {
            let shared = shared.clone();
            let handle = std::thread::Builder::new()
                .name(format!("rollerdyn-helper-{k}"))
                .spawn(move || {
                    SLOT.with(|s| s.set(k + 1));
                    helper(&shared);
                })?;
            team.helpers.push(handle);
        }
        Ok(team)
    }

    /// Threads that work on a map: the helpers and the caller.
    pub fn threads(&self) -> usize {
        self.helpers.len() + 1
    }

    /// `f(0..n)` in order. The caller starts on the first index at once; helpers join as
    /// they take the job, each taking the next index not yet taken; every value is written
    /// once, by the thread that computed it, straight into its place in the list, so the
    /// result does not depend on the threads. `f` must not panic (the model's evaluations
    /// do not): a panic on the caller's thread unwinds from here once the helpers are done;
    /// one on a helper leaves its index unwritten and panics here.
    pub fn map<T: Send>(&self, n: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
        if n < 2 {
            return (0..n).map(f).collect();
        }
        let mut values = uninitialised::<T>(n);
        let slots = Slots(values.as_mut_ptr());
        // SAFETY: `share` hands each index of 0..n to one thread, once, while `values`
        // lives; it returns only when every index was computed, so all are written.
        unsafe {
            self.share(n, |i| slots.write(i, f(i)));
            initialised(values)
        }
    }

    /// `f(0..n)` in order, as [`Team::map`], with each pair's halves in two lists, written
    /// straight into their places, so a map of large values (a right-hand side's contact
    /// geometries and results) is not split into two lists afterwards.
    pub fn map_pairs<A: Send, B: Send>(
        &self,
        n: usize,
        f: impl Fn(usize) -> (A, B) + Sync,
    ) -> (Vec<A>, Vec<B>) {
        if n < 2 {
            return (0..n).map(f).unzip();
        }
        let (mut firsts, mut seconds) = (uninitialised::<A>(n), uninitialised::<B>(n));
        let (to_firsts, to_seconds) = (Slots(firsts.as_mut_ptr()), Slots(seconds.as_mut_ptr()));
        // SAFETY: as in `map`, for both lists.
        unsafe {
            self.share(n, |i| {
                let (a, b) = f(i);
                to_firsts.write(i, a);
                to_seconds.write(i, b);
            });
            (initialised(firsts), initialised(seconds))
        }
    }

    /// Calls `f` once for each index of 0..n, shared among the caller and the helpers (each
    /// thread takes the next index not yet taken); panics unless every call returned. (A
    /// value written before such a panic is leaked, never read: safe.)
    fn share(&self, n: usize, f: impl Fn(usize) + Sync) {
        let next = AtomicUsize::new(0);
        let done = AtomicUsize::new(0);
        let work = || loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            if i >= n {
                break;
            }
            f(i);
            done.fetch_add(1, Ordering::Release);
        };
        self.run(&work);
        assert_eq!(
            done.load(Ordering::Acquire),
            n,
            "every index was taken and computed"
        );
    }

    /// Runs `work` on the caller and on every helper that takes it before the caller is
    /// done with it; returns when every helper that took it is done.
    fn run(&self, work: &(dyn Fn() + Sync)) {
        let _caller = match self.caller.try_lock() {
            Ok(guard) => guard,
            Err(TryLockError::Poisoned(e)) => e.into_inner(),
            // Another caller's job is posted: this one computes alone.
            Err(TryLockError::WouldBlock) => return work(),
        };
        let s = &*self.shared;
        // SAFETY: erases the closure's lifetime. Helpers call it only while counted
        // active in the ticket, and this function does not return before the ticket is
        // closed with no helper active, so the closure outlives every call.
        let job = Job(unsafe {
            std::mem::transmute::<*const (dyn Fn() + Sync + '_), *const (dyn Fn() + Sync)>(
                work as *const (dyn Fn() + Sync),
            )
        });
        *s.job.lock().unwrap_or_else(PoisonError::into_inner) = Some(job);
        // Open the next generation with no helper active.
        // (Wrapping after 2³² jobs is harmless: a helper compares with the last it saw.)
        let generation =
            (s.ticket.load(Ordering::SeqCst) & !(GENERATION - 1)).wrapping_add(GENERATION);
        s.ticket.store(generation, Ordering::SeqCst);
        if s.sleeping.load(Ordering::SeqCst) > 0 {
            drop(s.sleep.lock().unwrap_or_else(PoisonError::into_inner));
            s.wake.notify_all();
        }
        // Closed and waited for when this returns, also if `work` unwinds.
        let _close = Close(s);
        work();
    }
}

/// A list of n values not yet written.
fn uninitialised<T>(n: usize) -> Vec<MaybeUninit<T>> {
    let mut values = Vec::with_capacity(n);
    values.resize_with(n, MaybeUninit::uninit);
    values
}

/// The list of values once every one of them is written.
///
/// # Safety
/// Every element of `values` must be initialised.
unsafe fn initialised<T>(values: Vec<MaybeUninit<T>>) -> Vec<T> {
    let mut values = ManuallyDrop::new(values);
    // SAFETY: MaybeUninit<T> has T's size and alignment, and every element is initialised
    // (the caller's promise); the allocation is handed over whole.
    unsafe {
        Vec::from_raw_parts(
            values.as_mut_ptr().cast::<T>(),
            values.len(),
            values.capacity(),
        )
    }
}

/// The start of a list whose elements threads write at distinct indices.
struct Slots<T>(*mut MaybeUninit<T>);

// SAFETY: the threads of one job write distinct elements only (`Team::share` hands out
// each index once), and the values are Send.
unsafe impl<T: Send> Sync for Slots<T> {}

impl<T> Slots<T> {
    /// Writes element `i`.
    ///
    /// # Safety
    /// `i` lies within the list, and no other thread reads or writes element `i` meanwhile.
    unsafe fn write(&self, i: usize, value: T) {
        // SAFETY: the caller's promise.
        unsafe { (*self.0.add(i)).write(value) };
    }
}

/// Closes the posted job to helpers that have not taken it yet and waits for those that
/// have (on drop, so also when the caller's own share unwinds).
struct Close<'a>(&'a Shared);

impl Drop for Close<'_> {
    fn drop(&mut self) {
        let s = self.0;
        s.ticket.fetch_or(CLOSED, Ordering::SeqCst);
        while s.ticket.load(Ordering::Acquire) & (GENERATION - 2) != 0 {
            std::hint::spin_loop();
        }
        *s.job.lock().unwrap_or_else(PoisonError::into_inner) = None;
    }
}

impl Drop for Team {
    fn drop(&mut self) {
        self.shared.shutdown.store(true, Ordering::SeqCst);
        drop(
            self.shared
                .sleep
                .lock()
                .unwrap_or_else(PoisonError::into_inner),
        );
        self.shared.wake.notify_all();
        for handle in self.helpers.drain(..) {
            let _ = handle.join();
        }
    }
}

/// A helper's life: take each new generation's job while it is open, spin for the next
/// for [`SPIN`], then sleep until one is posted.
fn helper(s: &Shared) {
    let mut seen = s.ticket.load(Ordering::SeqCst) >> 32;
    let mut idle_since = Instant::now();
    let mut spins = 0u32;
    loop {
        if s.shutdown.load(Ordering::SeqCst) {
            return;
        }
        let ticket = s.ticket.load(Ordering::Acquire);
        if ticket >> 32 == seen {
            spins = spins.wrapping_add(1);
            // Look at the clock only now and then: it costs more than a spin.
            if spins % 64 == 0 && idle_since.elapsed() > SPIN {
                sleep_until_posted(s, seen);
                idle_since = Instant::now();
            } else {
                std::hint::spin_loop();
            }
            continue;
        }
        seen = ticket >> 32;
        if claim(s, ticket) {
            let job = *s.job.lock().unwrap_or_else(PoisonError::into_inner);
            if let Some(Job(work)) = job {
                // SAFETY: counted active, so the caller keeps the closure alive. A panic
                // is contained here so that the count still falls (the caller then finds
                // an index not computed).
                let call = std::panic::AssertUnwindSafe(|| unsafe { (*work)() });
                let _ = std::panic::catch_unwind(call);
            }
            s.ticket.fetch_sub(ACTIVE, Ordering::Release);
        }
        idle_since = Instant::now();
    }
}

/// Counts this helper active in the job of `ticket`'s generation if that job is still
/// open (retrying while other helpers claim it too); false if it was closed first.
fn claim(s: &Shared, mut ticket: u64) -> bool {
    let generation = ticket >> 32;
    while ticket >> 32 == generation && ticket & CLOSED == 0 {
        match s.ticket.compare_exchange_weak(
            ticket,
            ticket + ACTIVE,
            Ordering::AcqRel,
            Ordering::Acquire,
        ) {
            Ok(_) => return true,
            Err(now) => ticket = now,
        }
    }
    false
}

/// Sleeps until a generation after `seen` is posted or the team shuts down.
fn sleep_until_posted(s: &Shared, seen: u64) {
    let mut guard = s.sleep.lock().unwrap_or_else(PoisonError::into_inner);
    s.sleeping.fetch_add(1, Ordering::SeqCst);
    while s.ticket.load(Ordering::SeqCst) >> 32 == seen && !s.shutdown.load(Ordering::SeqCst) {
        guard = s.wake.wait(guard).unwrap_or_else(PoisonError::into_inner);
    }
    s.sleeping.fetch_sub(1, Ordering::SeqCst);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every index once, in order, whatever the team's size; many short maps in a row
    /// (the pattern of an integration) and maps after the helpers fell asleep.
    #[test]
    fn maps_every_index_once_in_order() {
        for helpers in [0, 1, 3] {
            let team = Team::new(helpers).expect("threads");
            assert_eq!(team.threads(), helpers + 1);
            for round in 0..2_000usize {
                let n = round % 37;
                let out = team.map(n, |i| i * i + round);
                assert_eq!(out, (0..n).map(|i| i * i + round).collect::<Vec<_>>());
            }
            std::thread::sleep(SPIN * 2);
            assert_eq!(team.map(5, |i| i + 1), vec![1, 2, 3, 4, 5]);
        }
    }

    /// The helpers take part: with work that waits a little per index, a helper computes
    /// some of the indices (its slot is recorded).
    #[test]
    fn helpers_share_the_work() {
        let team = Team::new(1).expect("threads");
        let mut helped = false;
        for _ in 0..50 {
            let slots = team.map(64, |_| {
                std::thread::sleep(Duration::from_micros(50));
                thread_slot()
            });
            helped |= slots.contains(&1);
            assert!(slots.iter().all(|&s| s <= 1));
        }
        assert!(helped, "the helper never took part");
        assert_eq!(thread_slot(), 0);
    }

    /// Two callers of one team at once: one posts its job, the other computes alone; both
    /// get their own results.
    #[test]
    fn concurrent_callers_each_get_their_results() {
        let team = Team::new(1).expect("threads");
        std::thread::scope(|scope| {
            for c in 0..3usize {
                let team = &team;
                scope.spawn(move || {
                    for round in 0..500usize {
                        let out = team.map(17, |i| i * 1000 + c * 7 + round);
                        let expected: Vec<usize> =
                            (0..17).map(|i| i * 1000 + c * 7 + round).collect();
                        assert_eq!(out, expected);
                    }
                });
            }
        });
    }

    /// `map_pairs` gives `map`'s values split in two lists, whatever the team's size, also
    /// for values that own memory (each dropped once: the allocator aborts on a double
    /// free).
    #[test]
    fn map_pairs_splits_every_index_in_order() {
        for helpers in [0, 1, 3] {
            let team = Team::new(helpers).expect("threads");
            for round in 0..500usize {
                let n = round % 41;
                let (firsts, seconds) = team.map_pairs(n, |i| (i * 3 + round, vec![i; i % 5]));
                assert_eq!(firsts, (0..n).map(|i| i * 3 + round).collect::<Vec<_>>());
                let expected: Vec<Vec<usize>> = (0..n).map(|i| vec![i; i % 5]).collect();
                assert_eq!(seconds, expected);
            }
        }
    }

    /// Twenty times: `failing` panics, and `working` runs normally afterwards.
    fn panics_leave_the_team_working(failing: impl Fn(), working: impl Fn()) {
        for _ in 0..20 {
            let failed = std::panic::catch_unwind(std::panic::AssertUnwindSafe(&failing));
            assert!(failed.is_err());
            working();
        }
    }

    /// A panic in `f` (on whichever thread takes that index) comes out of `map` once the
    /// helpers are done with the job, and the team works on afterwards.
    #[test]
    fn a_panic_in_a_map_leaves_the_team_working() {
        let team = Team::new(1).expect("threads");
        panics_leave_the_team_working(
            || {
                team.map(64, |i| {
                    assert!(i != 40, "index 40 fails");
                    i
                });
            },
            || assert_eq!(team.map(6, |i| 2 * i), vec![0, 2, 4, 6, 8, 10]),
        );
    }

    /// A panic in `map_pairs`' `f` comes out of it and the team works on afterwards.
    #[test]
    fn a_panic_in_map_pairs_leaves_the_team_working() {
        let team = Team::new(1).expect("threads");
        panics_leave_the_team_working(
            || {
                team.map_pairs(64, |i| {
                    assert!(i != 40, "index 40 fails");
                    (i, vec![i])
                });
            },
            || {
                assert_eq!(
                    team.map_pairs(3, |i| (i, 2 * i)),
                    (vec![0, 1, 2], vec![0, 2, 4])
                )
            },
        );
    }
}
