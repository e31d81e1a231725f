//! The win64 binaries: the same FMU crates cross-compiled for `x86_64-pc-windows-gnu` with
//! MinGW-w64 as the linker, when both are installed (`cargo xtask test` installs them through
//! [`crate::setup::windows_cross`]; `cargo xtask package` without them packages no Windows binary).
//!
//! The DLLs need no MinGW runtime DLL: Rust's windows-gnu target links libgcc's unwinder and the
//! C runtime start-up objects statically, so a DLL imports only Windows' own (kernel32, ntdll,
//! msvcrt and the `api-ms-win-core-synch` API set) and loads on any 64-bit Windows from 8 on;
//! tests/windows/test_win64.py checks the import table.

use super::cross::{self, Cross};
use std::path::PathBuf;

/// The Rust target of FMI's `win64` platform.
pub const TARGET: &str = "x86_64-pc-windows-gnu";
/// MinGW-w64's C compiler, which links the DLLs.
pub const LINKER: &str = "x86_64-w64-mingw32-gcc";
/// The cross build of [`TARGET`], linked by [`LINKER`].
pub const CROSS: Cross = Cross { target: TARGET, linker: LINKER };

/// Whether the Rust standard library for [`TARGET`] and the MinGW-w64 linker are installed.
pub fn available() -> bool {
    CROSS.rust_std_installed() && cross::tool_runs(LINKER)
}

/// Where [`Cross::build`] leaves the DLL of `name`.
pub fn dll(name: &str) -> PathBuf {
    CROSS.release_file(&format!("{name}.dll"))
}
