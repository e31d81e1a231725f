//! Tools the tasks need from the system, installed on first use so that `cargo xtask test` and
//! `cargo xtask demo` work on a fresh machine: Debian packages through apt-get, Rust components
//! and targets through rustup, npm packages into target/.

use crate::run_command;
use anyhow::{bail, Result};
use std::path::Path;
use std::process::{Command, Stdio};

/// Python's `venv` module with `ensurepip` (Debian ships it apart, as python3-venv).
pub fn python_venv() -> Result<()> {
    let interpreter = std::env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    let usable = || succeeds(Command::new(&interpreter).args(["-c", "import venv, ensurepip"]));
    ensure_apt("Python venv", usable, &["python3-venv"])
}

/// The shared library of the Python that `python` runs (Debian ships it apart, as
/// libpython3.X): a PythonFMU's binary takes Python from the process hosting it, so the
/// third-party tests preload this library into crane-cosim.
pub fn python_shared_library(python: &Path) -> Result<()> {
    const LOAD: &str = "import ctypes, pathlib, sysconfig as s; name = s.get_config_var('INSTSONAME'); \
                        path = pathlib.Path(s.get_config_var('LIBDIR')) / name; \
                        ctypes.CDLL(str(path) if path.exists() else name)";
    let version = Command::new(python).args(["-c", "import sys; print('%d.%d' % sys.version_info[:2])"]).output()?;
    let package = format!("libpython{}", String::from_utf8_lossy(&version.stdout).trim());
    ensure_apt("Python's shared library", || succeeds(Command::new(python).args(["-c", LOAD])), &[&package])
}

/// valgrind (callgrind counts the instructions of the budget check).
pub fn valgrind() -> Result<()> {
    ensure_apt("valgrind", || succeeds(Command::new("valgrind").arg("--version")), &["valgrind"])
}

/// rustfmt and clippy, which the style check runs.
pub fn rust_components() -> Result<()> {
    for (component, probe) in [("rustfmt", "fmt"), ("clippy", "clippy")] {
        if !succeeds(Command::new("cargo").args([probe, "--version"])) {
            run_command(Command::new("rustup").args(["component", "add", component]))?;
        }
    }
    Ok(())
}

/// A nightly toolchain and cargo-fuzz (libFuzzer with sanitizers needs nightly rustc).
pub fn cargo_fuzz() -> Result<()> {
    if !succeeds(Command::new("cargo").args(["+nightly", "--version"])) {
        run_command(Command::new("rustup").args(["toolchain", "install", "nightly", "--profile", "minimal"]))?;
    }
    if !succeeds(Command::new("cargo").args(["fuzz", "--version"])) {
        run_command(Command::new("cargo").args(["install", "cargo-fuzz", "--locked"]))?;
    }
    Ok(())
}

/// What the win64 binaries need: Rust's standard library for the Windows target, MinGW-w64 to
/// link the DLLs and Wine to run them in the tests.
pub fn windows_cross() -> Result<()> {
    use crate::package::windows;
    if !windows::CROSS.rust_std_installed() {
        run_command(Command::new("rustup").args(["target", "add", windows::TARGET]))?;
    }
    ensure_apt("MinGW-w64", || succeeds(Command::new(windows::LINKER).arg("--version")), &["gcc-mingw-w64-x86-64"])?;
    // Debian's `wine` is the `wine` command and depends on wine64, the 64-bit loader (a bare
    // `apt-get install wine64` brings the command only as a recommendation).
    ensure_apt("Wine", || succeeds(Command::new("wine").arg("--version")), &["wine"])
}

/// What the aarch64 Linux binaries need: Rust's standard library for the aarch64 target, Debian's
/// cross GCC to link the libraries (with the aarch64 glibc it links against, sysroot
/// `/usr/aarch64-linux-gnu`, which QEMU also loads them with) and QEMU's user-mode emulator to run
/// them in the tests (tests/aarch64/test_aarch64.py).
pub fn aarch64_cross() -> Result<()> {
    use crate::package::aarch64;
    if !aarch64::CROSS.rust_std_installed() {
        run_command(Command::new("rustup").args(["target", "add", aarch64::TARGET]))?;
    }
    // gcc-aarch64-linux-gnu only recommends the glibc development files the linker needs
    // (libc6-dev-arm64-cross, which brings the runtime, libc6-arm64-cross).
    let packages = ["gcc-aarch64-linux-gnu", "libc6-dev-arm64-cross"];
    ensure_apt("the aarch64 cross GCC and glibc", aarch64::linker_installed, &packages)?;
    ensure_apt("QEMU user-mode emulation", || succeeds(Command::new(aarch64::RUNNER).arg("--version")), &["qemu-user"])
}

/// Chromium and playwright-core, which check the FMU documentation pages: Debian's chromium
/// and the npm packages of tests/documentation/package-lock.json in target/node_modules
/// (reinstalled only when the lock file changes). Returns the node_modules folder.
pub fn documentation_browser() -> Result<std::path::PathBuf> {
    ensure_apt("Chromium", || succeeds(Command::new("chromium").arg("--version")), &["chromium"])?;
    npm()?;
    let source = crate::root().join("tests/documentation");
    let target = crate::root().join("target/documentation-check");
    let lock = std::fs::read_to_string(source.join("package-lock.json"))?;
    let modules = target.join("node_modules");
    if std::fs::read_to_string(target.join("package-lock.json")).ok().as_deref() != Some(lock.as_str())
        || !modules.exists()
    {
        std::fs::create_dir_all(&target)?;
        std::fs::copy(source.join("package.json"), target.join("package.json"))?;
        std::fs::write(target.join("package-lock.json"), &lock)?;
        run_command(Command::new("npm").args(["ci", "--no-audit", "--no-fund", "--prefix"]).arg(&target))?;
    }
    Ok(modules)
}

/// npm and Node.js (Debian's npm package brings both).
pub fn npm() -> Result<()> {
    ensure_apt("npm", || succeeds(Command::new("npm").arg("--version")), &["npm"])
}

fn ensure_apt(what: &str, present: impl Fn() -> bool, packages: &[&str]) -> Result<()> {
    if present() {
        return Ok(());
    }
    let list = packages.join(" ");
    if !succeeds(Command::new("apt-get").arg("--version")) {
        bail!("{what} is missing and there is no apt-get to install it: install {list}");
    }
    run_command(Command::new("apt-get").arg("update"))?;
    run_command(Command::new("apt-get").args(["install", "-y"]).args(packages))?;
    if !present() {
        bail!("{what} is still missing after `apt-get install {list}`");
    }
    Ok(())
}

fn succeeds(command: &mut Command) -> bool {
    command.stdout(Stdio::null()).stderr(Stdio::null()).status().is_ok_and(|s| s.success())
}
