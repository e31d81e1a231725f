//! The instances and FMU states this library handed out and has not freed yet, by address: a
//! pointer from the host is dereferenced only if it is listed here as an object of the type it
//! is read as.
//!
//! Why a registry rather than a tag in the object: reading a tag through a freed pointer is
//! already a use after free (the memory may be unmapped, or reused by anything, whose bytes can
//! happen to match), and a tag shared by every FMU of this exporter does not tell a crane
//! component from a pendulum one inside one process. Membership tells both before any access.
//! What it cannot tell: an address freed and then reused by a new object of the same type (a
//! new instance of the same FMU) is live again, so a stale pointer to it reaches the new object
//! — wrong, but sound.
//!
//! # Reading without a lock
//!
//! Every FMI call looks its component up here, while objects are added and removed only by
//! instantiation, freeing and FMU states, so the list is published for readers as an immutable
//! snapshot (entries sorted by address, searched by bisection over the few live objects of this
//! library) behind an atomic pointer, and a lookup takes no lock. Writers are serialised by a
//! mutex; each builds a new snapshot, swaps it in and frees the old one only after every reader
//! that may still be searching it has finished — a grace period in the manner of read-copy-update
//! with two reader counters:
//!
//! * a reader adds itself to the counter of the current epoch's parity, loads the snapshot,
//!   searches it and removes itself from the same counter;
//! * after the swap, a writer flips the epoch and waits until the counter of the old parity is
//!   zero, then flips again and waits for the other counter.
//!
//! Why this is sound: the counter increments, the loads of the snapshot pointer, the swap and the
//! writer's counter reads are all sequentially consistent. A reader that loaded the old snapshot
//! did so before the swap in that single order, so its increment also precedes both of the
//! writer's waits; whichever counter it used, one wait sees it and ends only after its decrement,
//! which (release, read by an acquire load) makes the reader's search happen before the free. A
//! reader that loads the pointer after the swap gets the new snapshot. The flips only bound the
//! waits: readers arriving after a flip use the other counter, so each wait covers the readers
//! already in flight, not a stream of new ones (with one counter, steady calls from several
//! threads could keep it above zero). Reader sections are a bisection without callbacks or
//! allocation, so a writer waits at most for another thread's bounded search (yielding while
//! it waits, should that thread be preempted).
//!
//! Why not `arc-swap`: its loads use a thread-local with a destructor, which costs a TLS lookup
//! per load in a shared library (what this replaced was the lock) and pins the library in memory
//! after `dlclose` on some platforms (see `crate::panics`).
//!
//! Cost: a load of the epoch, two atomic read-modify-writes on a counter and the bisection per
//! lookup, where the mutex it replaced took its lock and unlock and two poison checks (measured
//! with `cargo xtask bench --check`, callgrind instructions per macro step). Writers allocate a
//! snapshot per change, rare next to lookups. The snapshot is freed when the last entry goes
//! (the pointer is then null), so nothing is left on the heap when a host unloads the library
//! after freeing everything.

use std::any::TypeId;
use std::ptr::null_mut;
use std::sync::atomic::{AtomicPtr, AtomicUsize, Ordering::SeqCst};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// One live object: where it is, what it is, and (for FMU states) the instance that frees it
/// with itself.
#[derive(Clone, Copy)]
struct Entry {
    address: usize,
    kind: TypeId,
    owner: usize,
}

/// This library's live objects.
static LIVE: Registry = Registry::new();

/// A list of live objects with lock-free lookups (see the module documentation); one static
/// instance serves the library, tests make their own.
struct Registry {
    /// The published list, sorted by address: null while nothing is live, else from
    /// `Box::into_raw` of a non-empty `Vec`, never changed while published.
    snapshot: AtomicPtr<Vec<Entry>>,
    /// The parity of its low bit picks the counter new readers use.
    epoch: AtomicUsize,
    /// Readers searching a snapshot, by the epoch parity they read on entry.
    readers: [AtomicUsize; 2],
    /// Held by writers for the whole change, grace period included.
    writer: Mutex<()>,
}

impl Registry {
    const fn new() -> Registry {
        Registry {
            snapshot: AtomicPtr::new(null_mut()),
            epoch: AtomicUsize::new(0),
            readers: [AtomicUsize::new(0), AtomicUsize::new(0)],
            writer: Mutex::new(()),
        }
    }

    /// Runs `f` on the current list (empty while nothing is live), which stays allocated until
    /// `f` returns.
    #[inline]
    fn read<R>(&self, f: impl FnOnce(&[Entry]) -> R) -> R {
        let counter = &self.readers[self.epoch.load(SeqCst) & 1];
        counter.fetch_add(1, SeqCst);
        let snapshot = self.snapshot.load(SeqCst);
        // SAFETY: a non-null snapshot came from `Box::into_raw` in `replace`, which frees a
        // replaced one only after the grace period, which waits for this reader's decrement
        // below (see the module documentation); published snapshots are never written.
        let result = f(unsafe { snapshot.as_ref() }.map_or(&[], Vec::as_slice));
        counter.fetch_sub(1, SeqCst);
        result
    }

    /// The writer's lock: no code holding it panics (no allocation failure unwinds), so a
    /// poisoned lock still guards a consistent list.
    fn write_lock(&self) -> MutexGuard<'_, ()> {
        self.writer.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The current list, for a writer.
    fn current<'a>(&'a self, _writer: &'a MutexGuard<'_, ()>) -> &'a [Entry] {
        // SAFETY: only writers replace and free snapshots, and the slice borrows the writer's
        // guard, so it is gone before `replace` (which takes the guard) can free it.
        unsafe { self.snapshot.load(SeqCst).as_ref() }.map_or(&[], Vec::as_slice)
    }

    /// Publishes `entries` (null if empty) and frees the snapshot it replaces once no reader can
    /// be searching it.
    fn replace(&self, _writer: MutexGuard<'_, ()>, entries: Vec<Entry>) {
        let new = if entries.is_empty() { null_mut() } else { Box::into_raw(Box::new(entries)) };
        let old = self.snapshot.swap(new, SeqCst);
        if old.is_null() {
            return;
        }
        for _ in 0..2 {
            let parity = self.epoch.fetch_add(1, SeqCst) & 1;
            while self.readers[parity].load(SeqCst) != 0 {
                std::thread::yield_now();
            }
        }
        // SAFETY: from `Box::into_raw` (it was published), unpublished by the swap, and every
        // reader that loaded it has finished (the grace period above); writers are serialised by
        // the lock.
        let mut old = unsafe { Box::from_raw(old) };
        // Tests poison what they free, so that a reader still searching it would find garbage.
        if cfg!(test) {
            old.fill(Entry { address: 0, kind: TypeId::of::<()>(), owner: 0 });
        }
        drop(old);
    }

    fn add<T: 'static>(&self, ptr: *const T, owner: usize) {
        let address = ptr as usize;
        let writer = self.write_lock();
        let mut entries = self.current(&writer).to_vec();
        let at = entries.partition_point(|e| e.address < address);
        entries.insert(at, Entry { address, kind: TypeId::of::<T>(), owner });
        self.replace(writer, entries);
    }

    #[inline]
    fn contains<T: 'static>(&self, ptr: *const T) -> bool {
        let address = ptr as usize;
        self.read(|entries| {
            entries.binary_search_by_key(&address, |e| e.address).is_ok_and(|i| entries[i].kind == TypeId::of::<T>())
        })
    }

    fn remove<T: 'static>(&self, ptr: *const T) -> bool {
        let address = ptr as usize;
        let writer = self.write_lock();
        let entries = self.current(&writer);
        let Ok(i) = entries.binary_search_by_key(&address, |e| e.address) else { return false };
        if entries[i].kind != TypeId::of::<T>() {
            return false;
        }
        let mut entries = entries.to_vec();
        entries.remove(i);
        self.replace(writer, entries);
        true
    }

    fn take_owned<T: 'static>(&self, owner: usize) -> Vec<usize> {
        let writer = self.write_lock();
        let kind = TypeId::of::<T>();
        let (taken, kept): (Vec<Entry>, Vec<Entry>) =
            self.current(&writer).iter().partition(|e| e.kind == kind && e.owner == owner);
        if !taken.is_empty() {
            self.replace(writer, kept);
        }
        taken.iter().map(|e| e.address).collect()
    }
}

/// Lists the object at `ptr`, owned by the object at `owner` (0: by nobody).
pub(crate) fn add<T: 'static>(ptr: *const T, owner: usize) {
    LIVE.add(ptr, owner);
}

/// Whether `ptr` is listed as a live `T`.
#[inline]
pub(crate) fn contains<T: 'static>(ptr: *const T) -> bool {
    LIVE.contains(ptr)
}

/// Unlists `ptr` if it is a live `T`; whether it was.
pub(crate) fn remove<T: 'static>(ptr: *const T) -> bool {
    LIVE.remove(ptr)
}

/// Unlists every `T` owned by `owner` and returns their addresses.
pub(crate) fn take_owned<T: 'static>(owner: usize) -> Vec<usize> {
    LIVE.take_owned::<T>(owner)
}

/// How many live `T`s `owner` owns.
#[cfg(test)]
pub(crate) fn owned_count<T: 'static>(owner: usize) -> usize {
    LIVE.read(|entries| entries.iter().filter(|e| e.kind == TypeId::of::<T>() && e.owner == owner).count())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;

    #[test]
    fn the_last_removal_releases_the_list() {
        let registry = Registry::new();
        let (a, b) = (8 as *const u8, 16 as *const u8);
        registry.add(a, 0);
        registry.add(b, 0);
        assert!(registry.contains(a) && registry.contains(b));
        assert!(!registry.contains(a as *const u16), "listed as another type");
        assert!(registry.remove(a));
        assert!(!registry.remove(a));
        assert!(!registry.snapshot.load(SeqCst).is_null());
        assert!(registry.remove(b));
        assert!(registry.snapshot.load(SeqCst).is_null(), "nothing may stay on the heap");
        assert!(!registry.contains(b));
    }

    #[test]
    fn owned_objects_are_taken_with_their_owner() {
        let registry = Registry::new();
        registry.add(8 as *const u8, 0);
        registry.add(16 as *const u16, 8);
        registry.add(24 as *const u16, 8);
        registry.add(32 as *const u16, 40);
        assert_eq!(registry.take_owned::<u16>(8), [16, 24]);
        assert!(registry.take_owned::<u16>(8).is_empty());
        assert!(registry.contains(32 as *const u16) && registry.contains(8 as *const u8));
    }

    /// A writer that replaces the list a reader is searching waits for that reader before it
    /// frees (and, in tests, poisons) the old list.
    #[test]
    fn a_change_waits_for_the_readers_of_the_list_it_replaces() {
        let registry = Registry::new();
        registry.add(8 as *const u8, 0);
        let (inside, removed) = (AtomicBool::new(false), AtomicBool::new(false));
        let (early, seen) = std::thread::scope(|scope| {
            scope.spawn(|| {
                while !inside.load(SeqCst) {
                    std::thread::yield_now();
                }
                assert!(registry.remove(8 as *const u8));
                removed.store(true, SeqCst);
            });
            // No assertion inside the read: a panic there would leave the writer waiting.
            registry.read(|entries| {
                inside.store(true, SeqCst);
                std::thread::sleep(std::time::Duration::from_millis(100));
                (removed.load(SeqCst), entries.iter().map(|e| e.address).collect::<Vec<_>>())
            })
        });
        assert!(!early, "the writer went on while the list it replaced was being read");
        assert_eq!(seen, [8], "the list changed under its reader");
        assert!(registry.snapshot.load(SeqCst).is_null());
    }

    /// Lookups from several threads while others list and unlist objects: a permanently listed
    /// object is always found and a never listed one never, although every change frees the
    /// snapshot it replaces (poisoned in tests), so a reader still searching a freed snapshot, or
    /// a change that lost an entry, fails the test.
    #[test]
    fn lookups_during_changes_see_a_consistent_list() {
        let registry = Registry::new();
        let (kept, never) = (0x1000_usize, 0x1008_usize);
        registry.add(kept as *const u64, 0);
        let stop = AtomicBool::new(false);
        std::thread::scope(|scope| {
            let readers: Vec<_> = (0..3)
                .map(|_| {
                    scope.spawn(|| {
                        let mut lookups = 0_u32;
                        while lookups < 1_000 || !stop.load(SeqCst) {
                            assert!(registry.contains(kept as *const u64));
                            assert!(!registry.contains(never as *const u64));
                            lookups += 1;
                        }
                    })
                })
                .collect();
            let writers: Vec<_> = (0..2_usize)
                .map(|w| {
                    let registry = &registry;
                    scope.spawn(move || {
                        for i in 0..2_000_usize {
                            let address = (0x10_0000 * (w + 1) + 8 * (i % 16)) as *const u64;
                            registry.add(address, 0);
                            assert!(registry.contains(address));
                            assert!(registry.remove(address));
                        }
                    })
                })
                .collect();
            writers.into_iter().for_each(|w| w.join().unwrap());
            stop.store(true, SeqCst);
            readers.into_iter().for_each(|r| r.join().unwrap());
        });
        assert!(registry.remove(kept as *const u64));
        assert!(registry.snapshot.load(SeqCst).is_null());
    }
}
