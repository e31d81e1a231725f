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
//! Cost, measured with `cargo xtask bench --check` (callgrind, instructions per macro step of
//! the closed loop, six instances): still water 58,907 with the tag, 60,049 with the registry
//! (+1.9 %), profile 1 73,952 → 75,267 (+1.8 %), about 50 instructions per call, within the
//! ceilings of 62,000 and 78,000. Soundness for every pointer a host can pass is worth that;
//! a tag could only be documented as best effort.
//!
//! Entries are kept sorted by address in one `Vec` behind a `Mutex`: a lookup is a lock and a
//! binary search over the live objects of this library (a few per process), cheaper than
//! hashing; insertions and removals (instantiation, FMU states) are rare. The `Vec`'s buffer is
//! released when the last entry goes, so nothing is left on the heap when a host unloads the
//! library after freeing everything.

use std::any::TypeId;
use std::sync::{Mutex, MutexGuard, PoisonError};

/// One live object: where it is, what it is, and (for FMU states) the instance that frees it
/// with itself.
#[derive(Clone, Copy)]
struct Entry {
    address: usize,
    kind: TypeId,
    owner: usize,
}

static LIVE: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

/// The list, whatever a panicking thread left: no code holding the lock panics (no allocation
/// failure unwinds), so a poisoned list is still a consistent one.
fn entries() -> MutexGuard<'static, Vec<Entry>> {
    LIVE.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Lists the object at `ptr`, owned by the object at `owner` (0: by nobody).
pub(crate) fn add<T: 'static>(ptr: *const T, owner: usize) {
    let address = ptr as usize;
    let mut entries = entries();
    let at = entries.partition_point(|e| e.address < address);
    entries.insert(at, Entry { address, kind: TypeId::of::<T>(), owner });
}

/// Whether `ptr` is listed as a live `T`.
#[inline]
pub(crate) fn contains<T: 'static>(ptr: *const T) -> bool {
    let address = ptr as usize;
    let entries = entries();
    entries.binary_search_by_key(&address, |e| e.address).is_ok_and(|i| entries[i].kind == TypeId::of::<T>())
}

/// Unlists `ptr` if it is a live `T`; whether it was.
pub(crate) fn remove<T: 'static>(ptr: *const T) -> bool {
    let address = ptr as usize;
    let mut entries = entries();
    let Ok(i) = entries.binary_search_by_key(&address, |e| e.address) else { return false };
    if entries[i].kind != TypeId::of::<T>() {
        return false;
    }
    entries.remove(i);
    release_if_empty(&mut entries);
    true
}

/// Unlists every `T` owned by `owner` and returns their addresses.
pub(crate) fn take_owned<T: 'static>(owner: usize) -> Vec<usize> {
    let mut entries = entries();
    let kind = TypeId::of::<T>();
    let mut taken = Vec::new();
    entries.retain(|e| {
        let owned = e.kind == kind && e.owner == owner;
        if owned {
            taken.push(e.address);
        }
        !owned
    });
    release_if_empty(&mut entries);
    taken
}

/// How many live `T`s `owner` owns.
#[cfg(test)]
pub(crate) fn owned_count<T: 'static>(owner: usize) -> usize {
    entries().iter().filter(|e| e.kind == TypeId::of::<T>() && e.owner == owner).count()
}

fn release_if_empty(entries: &mut Vec<Entry>) {
    if entries.is_empty() {
        *entries = Vec::new();
    }
}
