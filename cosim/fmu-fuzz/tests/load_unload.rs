//! Loading and unloading an FMU library keeps no memory (measured as the resident set of this
//! process; a test binary of its own, so that no other test allocates meanwhile).

use fmu_fuzz::fmu::Api;
use fmu_fuzz::{cycles, fmu};

/// Loading and unloading a library keeps nothing: after a warm-up, 200 load/unload cycles (each
/// with one instance, through FMI 2.0 and FMI 3.0 in turn) must not grow the resident set by more than 256 KiB in all, 1.3 KiB per
/// cycle, far below the 45 KiB per cycle that a cached model description used to leak (9 MB per
/// 200 cycles). The allocator's page-sized noise reaches 250 KiB in one batch now and then but
/// not in every batch, while a leak grows every batch: the least growth of three batches counts.
#[test]
fn load_unload_cycles_do_not_grow_the_resident_set() {
    for model in fmu::models().unwrap() {
        for k in 0..20 {
            cycles::load_cycle(&model, Api::BOTH[k % 2]).unwrap();
        }
        let growths: Vec<u64> = (0..3)
            .map(|_| {
                let before = cycles::resident_bytes().unwrap();
                for k in 0..200 {
                    cycles::load_cycle(&model, Api::BOTH[k % 2]).unwrap();
                }
                cycles::resident_bytes().unwrap().saturating_sub(before)
            })
            .collect();
        let growth = growths.iter().copied().min().unwrap_or(0);
        println!(
            "{model}: resident set growth over 200 load/unload cycles: {growth} bytes ({} per cycle; batches {growths:?})",
            growth / 200
        );
        assert!(growth <= 256 * 1024, "{model}: the resident set grew by {growths:?} bytes in three batches");
    }
}
