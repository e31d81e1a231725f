//! In-process tests of the exporter through the C entry points `export_fmu!` generates, driven
//! the way a host drives an FMU, with a toy model (see [`toy`]).
//!
//! Stable Rust cannot define a variadic function, so the test logger is a fixed-argument Rust
//! function called through the variadic logger type. That relies on the platform calling
//! convention, not on a Rust guarantee: it holds where variadic integer and pointer arguments
//! travel like fixed ones, x86-64 (System V and Windows) and AArch64 outside Apple platforms.
//! Elsewhere these tests are not compiled (a C logger would need a build script for every FMU).
#![cfg(any(target_arch = "x86_64", all(target_arch = "aarch64", not(target_vendor = "apple"))))]

mod failures;
mod fmi3;
mod fmu_state;
mod host;
mod live;
mod logging;
mod setters;
mod states;
mod toy;
mod vectors;
