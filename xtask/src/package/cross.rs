//! What the cross builds ([`super::windows`], [`super::aarch64`]) share: whether a Rust target's
//! standard library and a tool are installed, and one cargo invocation that builds every FMU crate
//! for a target with a given linker.

use crate::{cargo, root, run_command};
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// A cross build: a Rust target and the C compiler that links its libraries.
pub struct Cross {
    /// The Rust target triple.
    pub target: &'static str,
    /// The C compiler cargo links with for [`Cross::target`].
    pub linker: &'static str,
}

impl Cross {
    /// Whether rustup has installed the standard library for the target.
    pub fn rust_std_installed(&self) -> bool {
        rust_std_installed(self.target)
    }

    /// Builds the release libraries of `crates` (the same release profile as the native ones).
    pub fn build(&self, crates: &[&str]) -> anyhow::Result<()> {
        build(self.target, self.linker, crates)
    }

    /// Where [`Cross::build`] leaves the file `file` (a library's file name).
    pub fn release_file(&self, file: &str) -> PathBuf {
        root().join(format!("target/{}/release/{file}", self.target))
    }
}

/// Whether rustup has installed the standard library of `target`: rustc prints the target's
/// library folder whether or not it is installed, and `rustup target add` puts libstd there.
pub fn rust_std_installed(target: &str) -> bool {
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let Ok(out) = Command::new(rustc).args(["--print", "target-libdir", "--target", target]).output() else {
        return false;
    };
    let libdir = String::from_utf8_lossy(&out.stdout).trim().to_owned();
    out.status.success()
        && std::fs::read_dir(libdir)
            .is_ok_and(|entries| entries.flatten().any(|e| e.file_name().to_string_lossy().starts_with("libstd-")))
}

/// Whether `program --version` runs and succeeds.
pub fn tool_runs(program: &str) -> bool {
    Command::new(program)
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Builds the release libraries of `crates` for `target` in one cargo invocation (the same
/// release profile as the native libraries), linked by `linker`.
pub fn build(target: &str, linker: &str, crates: &[&str]) -> anyhow::Result<()> {
    let mut build = cargo();
    build.args(["build", "--release", "--target", target]);
    for name in crates {
        build.args(["--package", name]);
    }
    let linker_env = format!("CARGO_TARGET_{}_LINKER", target.to_uppercase().replace('-', "_"));
    run_command(build.env(linker_env, linker))
}
