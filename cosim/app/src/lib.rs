//! The front door of the crane co-simulation: what a user asks for, as typed requests, and one
//! function per use case that answers it — a run of a system ([`run`]), the thesis' campaign
//! ([`campaign`]), a parameter sweep ([`sweep`]) and controller tuning ([`tune`]).
//!
//! The command line (`crane-cosim`) and the Python package (`crane_cosim`) are adapters onto
//! these functions: each turns its own arguments into a request, calls the use case and shows
//! what comes back. Nothing here prints: notes and warnings are returned as [`Notice`]s, and a
//! message that names a setting names it as a typed [`Setting`], which each front end words its
//! own way ([`setting::reword`]: `--start x` on the command line, `start={"x": …}` in Python).
//! A new use case adds one request and one function here, and one adapter in each front end.

pub mod campaign;
pub mod notice;
pub mod run;
pub mod setting;
pub mod source;
pub mod sweep;
pub mod tune;

pub use notice::Notice;
pub use setting::{reword, Setting, Wording};
pub use source::Source;
