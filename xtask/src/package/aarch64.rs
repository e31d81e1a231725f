//! The aarch64 Linux binaries: the same FMU crates cross-compiled for `aarch64-unknown-linux-gnu`
//! with Debian's cross GCC as the linker, when both are installed (`cargo xtask test` installs
//! them through [`crate::setup::aarch64_cross`]; `cargo xtask package` without them packages no
//! aarch64 binary). The libraries need only the aarch64 glibc (libc, libm) and libgcc_s, like the
//! x86_64 ones; tests/aarch64/test_aarch64.py runs them under QEMU's user-mode emulator against
//! the x86_64 results.

use super::cross::{self, Cross};
use std::path::{Path, PathBuf};

/// The Rust target of the `aarch64-linux` platform.
pub const TARGET: &str = "aarch64-unknown-linux-gnu";
/// The cross C compiler that links the libraries (Debian package `gcc-aarch64-linux-gnu`).
pub const LINKER: &str = "aarch64-linux-gnu-gcc";
/// Where Debian's cross packages put the aarch64 glibc (`libc6-arm64-cross`), which the linker
/// links against and QEMU loads the programs with (`qemu-aarch64 -L`).
pub const SYSROOT: &str = "/usr/aarch64-linux-gnu";
/// QEMU's user-mode emulator, which runs aarch64 Linux programs on another machine (Debian
/// package `qemu-user`).
pub const RUNNER: &str = "qemu-aarch64";
/// The cross build of [`TARGET`], linked by [`LINKER`].
pub const CROSS: Cross = Cross { target: TARGET, linker: LINKER };

/// Whether the Rust standard library for [`TARGET`] and the cross linker are installed.
pub fn available() -> bool {
    CROSS.rust_std_installed() && linker_installed()
}

/// Whether the cross GCC runs and the aarch64 glibc's development files it links against are in
/// [`SYSROOT`] (Debian's gcc-aarch64-linux-gnu only recommends them).
pub fn linker_installed() -> bool {
    cross::tool_runs(LINKER) && Path::new(SYSROOT).join("lib/libc.so").exists()
}

/// Where [`Cross::build`] leaves the library of `name`.
pub fn library(name: &str) -> PathBuf {
    CROSS.release_file(&format!("lib{name}.so"))
}
