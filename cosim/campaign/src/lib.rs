//! The thesis' simulation campaign (Chapter 7): tests 001–104 in two feedback variants, run in
//! parallel over `systems/closed_loop.json` with the co-simulation engine, each evaluated with
//! the §7.2.2 metrics, and a report beside Tables 7.1–7.3.
//!
//! The metrics themselves are `crane-metrics`', the plots' parts `cosim-plot`'s; studies over
//! any scenario (sweeps) are `cosim-studies`', the tuning that scores by this campaign is
//! `crane-tune`.
//!
//! Modules, bottom up (each uses only modules above it in this list):
//! * [`scale`], [`output`]: the test-scale rig or the full-scale crane, and the lengths of each;
//!   the list of the files a campaign wrote;
//! * [`matrix`]: the test definitions (Tables 7.4–7.7) and the scenario of each run;
//! * [`evaluate`]: one run's metrics from its results;
//! * [`results`]: what a campaign produced;
//! * [`summary`]: percentage changes (eq. 7.1) and the group means of Tables 7.1–7.3;
//! * [`runner`], [`figures`]: running the campaign in parallel; the figures;
//! * [`report`]: the Markdown report and per-run CSV/JSON.

pub mod evaluate;
pub mod figures;
pub mod matrix;
pub mod output;
pub mod report;
pub mod results;
pub mod runner;
pub mod scale;
pub mod summary;

pub use results::{Campaign, RunResult, DETAILED};
pub use runner::{run_campaign, CampaignError, CampaignOptions};
