//! Helpers that the FMU crates and the co-simulation crates both use, kept in one place.
//!
//! This crate is on the FMU side (it is built into the FMUs, through `fmi2` and `physics`), so it
//! depends on nothing of the co-simulation side, and on nothing at all: both helpers are a few
//! lines each. A crates.io escaper (e.g. `quick-xml`'s) would still need a wrapper that refuses
//! the control characters XML 1.0 forbids, and it would add a dependency to every FMU, so the
//! escaping is written out here once instead of four times.

pub mod markup;
pub mod unit;
