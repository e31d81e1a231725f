//! What a run will cost, judged before it starts: a mistyped time grid (a start time of −1e9 s,
//! a step size in seconds meant as milliseconds) must not start writing terabytes.

use fmu_import::file::human_bytes;

use crate::system::System;

/// Most macro steps a run may have without `RunOptions::force`: 10⁹, i.e. 116 days at 10 ms.
pub const MAX_STEPS: u64 = 1_000_000_000;

/// Largest results CSV a run may be expected to write without `RunOptions::force`: 16 GiB.
pub const MAX_CSV_BYTES: u64 = 16 << 30;

/// Characters per recorded number, separator included: the shortest round-trip text of a
/// double is typically 18–22 characters ("0.12345678901234567,").
const BYTES_PER_VALUE: u64 = 21;

/// A run's size: steps and the rows and bytes of CSV it will write.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Workload {
    pub steps: u64,
    pub rows: u64,
    /// An estimate (`BYTES_PER_VALUE` per value, time included).
    pub csv_bytes: u64,
}

/// A run too large to start without being forced.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "the run has {} steps and would write about {} of CSV (without RunOptions::force at most {} steps and {}): \
     check start_time, stop_time, step_size and the record interval, or pass RunOptions::force",
    workload.steps,
    human_bytes(workload.csv_bytes),
    MAX_STEPS,
    human_bytes(MAX_CSV_BYTES)
)]
pub struct WorkloadTooLarge {
    pub workload: Workload,
}

impl Workload {
    /// The size of a run of `system`.
    pub fn of(system: &System) -> Self {
        let steps = system.grid.steps();
        let rows = steps / system.record.every.max(1) + 1;
        let columns = system.record.variables.len() as u64 + 1;
        Self { steps, rows, csv_bytes: rows.saturating_mul(columns).saturating_mul(BYTES_PER_VALUE) }
    }

    /// Refuses a workload over [`MAX_STEPS`] or [`MAX_CSV_BYTES`].
    pub fn check(self) -> Result<Self, WorkloadTooLarge> {
        if self.steps > MAX_STEPS || self.csv_bytes > MAX_CSV_BYTES {
            Err(WorkloadTooLarge { workload: self })
        } else {
            Ok(self)
        }
    }
}
