//! In-process tests of the exporter through the C entry points `export_fmu!` generates, driven
//! the way a host drives an FMU, with a toy model (see [`toy`]).
//!
//! The test logger is a Rust function called through the variadic logger type, which is sound
//! only where variadic integer and pointer arguments are passed like fixed ones: x86-64 (System V
//! and Windows) and AArch64 outside Apple platforms.
#![cfg(any(target_arch = "x86_64", all(target_arch = "aarch64", not(target_vendor = "apple"))))]
#![allow(clippy::undocumented_unsafe_blocks)]

mod failures;
mod fmu_state;
mod host;
mod setters;
mod states;
mod toy;
