//! Ray counters of an [`super::Accel`]: closest-hit and occlusion queries traced, for the
//! per-stage throughput ledger (`stagelight bench`, `--stats`).
//!
//! Each thread adds to its own cache-line-sized slot (threads are dealt slots round-robin
//! the first time they trace anything), so counting costs a thread-local read and a plain
//! load and store on a line no other thread writes, per query or per batch of the batch API
//! (no locked instruction, no sharing); a reader sums the slots. Counts never influence what
//! is traced, so images stay deterministic.
//!
//! The totals are exact as long as no two threads that share a slot trace through the same
//! accelerator at the same time: threads are numbered in the order they first trace, and
//! share a slot only when their numbers differ by a multiple of 256 (a pool's workers number
//! consecutively, so any pool of up to 256 workers counts exactly).

use std::cell::Cell;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

/// Slots per accelerator (32 KiB; a power of two); threads numbered this far apart share one.
const SLOTS: usize = 256;

/// Rays traced through one accelerator.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Closest-hit queries ([`super::Accel::intersect`] and its batch form).
    pub closest: u64,
    /// Occlusion (any-hit) queries ([`super::Accel::occluded`] and its batch form).
    pub occlusion: u64,
}

impl RayCounts {
    /// Both kinds together.
    pub fn total(&self) -> u64 {
        self.closest + self.occlusion
    }

    /// Counts traced since `earlier` (saturating, for counts of a replaced accelerator).
    pub fn since(&self, earlier: RayCounts) -> RayCounts {
        RayCounts {
            closest: self.closest.saturating_sub(earlier.closest),
            occlusion: self.occlusion.saturating_sub(earlier.occlusion),
        }
    }
}

/// One thread's counters, alone on its cache line(s).
#[derive(Default)]
#[repr(align(128))]
struct Slot {
    closest: AtomicU64,
    occlusion: AtomicU64,
}

/// Per-thread counters of one accelerator.
pub(crate) struct Counters {
    slots: Box<[Slot]>,
}

static NEXT_SLOT: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static MY_SLOT: Cell<usize> = const { Cell::new(usize::MAX) };
}

/// This thread's slot index.
#[inline]
fn slot_index() -> usize {
    MY_SLOT.with(|s| {
        let mut i = s.get();
        if i == usize::MAX {
            i = NEXT_SLOT.fetch_add(1, Ordering::Relaxed) % SLOTS;
            s.set(i);
        }
        i
    })
}

/// Adds `n` to a counter only this thread writes: a plain load and store, not a locked
/// read-modify-write.
#[inline]
fn bump(c: &AtomicU64, n: u64) {
    c.store(c.load(Ordering::Relaxed).wrapping_add(n), Ordering::Relaxed);
}

impl Counters {
    /// Zeroed counters.
    pub(crate) fn new() -> Self {
        Self {
            slots: (0..SLOTS).map(|_| Slot::default()).collect(),
        }
    }

    /// Counts `n` closest-hit queries on this thread.
    #[inline]
    pub(crate) fn add_closest(&self, n: u64) {
        bump(&self.slots[slot_index() & (SLOTS - 1)].closest, n);
    }

    /// Counts `n` occlusion queries on this thread.
    #[inline]
    pub(crate) fn add_occlusion(&self, n: u64) {
        bump(&self.slots[slot_index() & (SLOTS - 1)].occlusion, n);
    }

    /// The totals over every thread. Exact once the tracing threads are done (a stage has
    /// returned); approximate while they still run.
    pub(crate) fn totals(&self) -> RayCounts {
        self.slots
            .iter()
            .fold(RayCounts::default(), |acc, s| RayCounts {
                closest: acc.closest + s.closest.load(Ordering::Relaxed),
                occlusion: acc.occlusion + s.occlusion.load(Ordering::Relaxed),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_from_many_threads_add_up() {
        let c = Counters::new();
        std::thread::scope(|s| {
            for _ in 0..8 {
                s.spawn(|| {
                    for _ in 0..1000 {
                        c.add_closest(1);
                    }
                    c.add_occlusion(12);
                });
            }
        });
        assert_eq!(
            c.totals(),
            RayCounts {
                closest: 8000,
                occlusion: 96
            }
        );
        assert_eq!(
            c.totals()
                .since(RayCounts {
                    closest: 1,
                    occlusion: 100
                })
                .occlusion,
            0
        );
    }
}
