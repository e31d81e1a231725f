//! Studies over any scenario: many runs of one base scenario with varied start values, each run
//! a case with its own result file, so that a study can be split into jobs (one case, a shard,
//! all on a thread pool) that share an output folder, be resumed, and be collected into one table.
//!
//! * [`error`]: [`StudyError`], why a study cannot be read, run or collected (the tuning's error
//!   wraps it);
//! * [`files`]: the study's files, read defensively and written atomically;
//! * [`sweep`]: parameter sweeps (plan, run by case or shard, collect to CSV, Parquet and plots).
//!
//! It holds no thesis campaign (`crane-campaign`) and no optimiser (`crane-tune`); the metrics
//! of a case are `crane-metrics`', its plots `cosim-plot`'s. Other kinds of study go beside
//! [`sweep`], on the same error, files and case machinery.

pub mod error;
pub mod files;
pub mod sweep;

pub use error::StudyError;
