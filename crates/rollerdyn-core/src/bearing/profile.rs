//! Where the time of a right-hand side goes: the sampling profiler of the model (not in the
//! paper; reported with every run and by `rollerdyn bench model`).
//!
//! One in `PROFILE_EVERY` (8) contact evaluations is timed, and each thread adds to a slot of
//! its own, so that profiling neither costs much nor makes the threads contend.

use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::Instant;

/// Where the time of a right-hand side goes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Profile {
    /// Roller end–flange detection [s].
    pub detection: f64,
    /// Line contacts (slices: geometry, films, traction) [s].
    pub line_contacts: f64,
    /// Roller end–flange forces (Hertz, film, traction) [s].
    pub flange_forces: f64,
    /// Detections made.
    pub detections: usize,
    /// Gradient method: pairings that converged from neither the warm nor the cold start,
    /// or only off their patch, and took the valid semi-analytical solution instead.
    pub gradient_fallbacks: usize,
}

impl Profile {
    /// The sum of two profiles.
    fn plus(&self, other: &Profile) -> Profile {
        Profile {
            detection: self.detection + other.detection,
            line_contacts: self.line_contacts + other.line_contacts,
            flange_forces: self.flange_forces + other.flange_forces,
            detections: self.detections + other.detections,
            gradient_fallbacks: self.gradient_fallbacks + other.gradient_fallbacks,
        }
    }
}

/// One thread's share of the [`Profile`], on a cache line of its own.
#[derive(Debug, Default)]
#[repr(align(128))]
struct ProfileSlot {
    profile: Mutex<Profile>,
    /// Sections entered so far (one in [`PROFILE_EVERY`] is timed, see [`sampled`]).
    sections: AtomicU32,
}

/// One in how many contact evaluations the [`Profile`] times (a power of 2): a clock read
/// costs about 25 ns, and timing every one of B1's 187 sections per right-hand side cost
/// 5 % of it. Over the millions of sections of a run the sample's error is far below a
/// percent.
const PROFILE_EVERY: u32 = 8;

/// Whether the n-th section is timed: the top bits of n's Fibonacci hash are zero.
fn sampled(n: u32) -> bool {
    n.wrapping_mul(0x9E37_79B9) >> (32 - PROFILE_EVERY.trailing_zeros()) == 0
}

/// The time since `start` scaled to all the sections it samples [s] (0 if not timed).
fn elapsed(start: Option<Instant>) -> f64 {
    start.map_or(0.0, |s| {
        s.elapsed().as_secs_f64() * f64::from(PROFILE_EVERY)
    })
}

/// The profile of a model, one slot per thread that evaluates it.
#[derive(Debug)]
pub(super) struct Profiler {
    slots: Vec<ProfileSlot>,
}

impl Profiler {
    /// A profiler for a model evaluated on the calling thread only (one slot).
    pub(super) fn single() -> Self {
        Self {
            slots: vec![ProfileSlot::default()],
        }
    }

    /// A profiler for `threads` threads (the calling thread and its team's helpers,
    /// `dynamics::team`): one slot each, and one to spare.
    pub(super) fn for_threads(threads: usize) -> Self {
        Self {
            slots: (0..=threads).map(|_| ProfileSlot::default()).collect(),
        }
    }

    /// Time spent so far, by kind of work (the sum of the slots).
    pub(super) fn total(&self) -> Profile {
        self.slots.iter().fold(Profile::default(), |sum, slot| {
            sum.plus(&slot.profile.lock().unwrap_or_else(PoisonError::into_inner))
        })
    }

    /// Starts timing one in [`PROFILE_EVERY`] sections, chosen by the top bits of the
    /// section count's Fibonacci hash (Knuth, TAOCP vol. 3, 6.4): spread evenly but not
    /// periodically, so that a fixed order of contacts cannot time the same ones always.
    pub(super) fn stopwatch(&self) -> Option<Instant> {
        let n = self
            .slot()
            .sections
            .fetch_add(1, Ordering::Relaxed)
            .wrapping_add(1);
        sampled(n).then(Instant::now)
    }

    /// Adds the time of a section begun by [`Self::stopwatch`] (nothing to do when it was
    /// not timed).
    pub(super) fn spend_time(&self, start: Option<Instant>, f: impl FnOnce(&mut Profile, f64)) {
        if start.is_some() {
            self.spend(|p| f(p, elapsed(start)));
        }
    }

    /// Adds the time of a detection begun by [`Self::stopwatch`] (0 when it was not timed)
    /// and counts it.
    pub(super) fn count_detection(&self, start: Option<Instant>) {
        self.spend(|p| {
            p.detection += elapsed(start);
            p.detections += 1;
        });
    }

    /// Changes this thread's profile by `f`.
    pub(super) fn spend(&self, f: impl FnOnce(&mut Profile)) {
        f(&mut self
            .slot()
            .profile
            .lock()
            .unwrap_or_else(PoisonError::into_inner));
    }

    /// This thread's profile slot: the team's helpers have one each, other threads share
    /// the first (so that the threads never contend for one lock or cache line).
    fn slot(&self) -> &ProfileSlot {
        let index = crate::dynamics::team::thread_slot();
        &self.slots[index % self.slots.len()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The profile's sample takes one section in PROFILE_EVERY, and does so within every
    /// residue class of the periods a fixed contact order could have (B1 enters 100 to 200
    /// sections per right-hand side), so no contact is always or never timed.
    #[test]
    fn the_profile_samples_evenly_without_aliasing() {
        let count = 1_000_000u32;
        let taken = (1..=count).filter(|&n| sampled(n)).count() as f64;
        let share = taken / f64::from(count);
        assert!(
            (share * f64::from(PROFILE_EVERY) - 1.0).abs() < 0.01,
            "{share}"
        );
        for period in 2..=256u32 {
            for residue in 0..period {
                let members = (0..count / period / 4).map(|k| k * period + residue + 1);
                let (n, hits) = members.fold((0.0, 0.0), |(n, h), m| {
                    (n + 1.0, h + f64::from(u8::from(sampled(m))))
                });
                let class_share = hits / n * f64::from(PROFILE_EVERY);
                assert!(
                    (0.5..1.5).contains(&class_share),
                    "period {period}, residue {residue}: {class_share}"
                );
            }
        }
    }
}
