//! The win64 binaries: the same FMU crates cross-compiled for `x86_64-pc-windows-gnu` with
//! MinGW-w64 as the linker, when both are installed (`cargo xtask test` installs them through
//! [`crate::setup::windows_cross`]; `cargo xtask package` without them packages linux64 only).
//!
//! The DLLs need no MinGW runtime DLL: Rust's windows-gnu target links libgcc's unwinder and the
//! C runtime start-up objects statically, so a DLL imports only Windows' own (kernel32, ntdll,
//! msvcrt and the `api-ms-win-core-synch` API set) and loads on any 64-bit Windows from 8 on;
//! tests/windows/test_win64.py checks the import table.

use crate::{cargo, root, run_command};
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// The Rust target of FMI's `win64` platform.
pub const TARGET: &str = "x86_64-pc-windows-gnu";
/// MinGW-w64's C compiler, which links the DLLs.
pub const LINKER: &str = "x86_64-w64-mingw32-gcc";

/// Whether the Rust standard library for [`TARGET`] and the MinGW-w64 linker are installed.
pub fn available() -> bool {
    let linker = Command::new(LINKER).arg("--version").stdout(Stdio::null()).stderr(Stdio::null()).status();
    rust_std_installed() && linker.is_ok_and(|s| s.success())
}

/// rustc prints the target's library folder whether or not it is installed; rustup's
/// `target add` puts libstd there.
pub fn rust_std_installed() -> bool {
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let Ok(out) = Command::new(rustc).args(["--print", "target-libdir", "--target", TARGET]).output() else {
        return false;
    };
    let libdir = String::from_utf8_lossy(&out.stdout).trim().to_owned();
    out.status.success()
        && std::fs::read_dir(libdir)
            .is_ok_and(|entries| entries.flatten().any(|e| e.file_name().to_string_lossy().starts_with("libstd-")))
}

/// Builds the release DLLs of `crates` (the same release profile as the Linux libraries).
pub fn build(crates: &[&str]) -> anyhow::Result<()> {
    let mut build = cargo();
    build.args(["build", "--release", "--target", TARGET]);
    for name in crates {
        build.args(["--package", name]);
    }
    let linker_env = format!("CARGO_TARGET_{}_LINKER", TARGET.to_uppercase().replace('-', "_"));
    run_command(build.env(linker_env, LINKER))
}

/// Where [`build`] leaves the DLL of `name`.
pub fn dll(name: &str) -> PathBuf {
    root().join(format!("target/{TARGET}/release/{name}.dll"))
}
