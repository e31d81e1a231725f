//! Build, package, test and demo entry points: `cargo xtask <command>`.

mod bench;
mod fuzz;
mod layers;
mod package;
mod python;
mod reference;
mod setup;
mod viewer;
mod wheel;
mod workspace;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::Command;

#[derive(Parser)]
#[command(about = "Project tasks for the maritime crane FMUs")]
struct Cli {
    #[command(subcommand)]
    command: Task,
}

// The variant comments are the help text, which writes placeholders as <model>, not HTML.
#[allow(rustdoc::invalid_html_tags)]
#[derive(Subcommand)]
enum Task {
    /// Build release libraries and write FMI 2.0 archives to target/fmu/<model>.fmu and FMI 3.0
    /// ones to target/fmu/fmi3/<model>.fmu (x86_64 Linux; aarch64 Linux when the
    /// aarch64-unknown-linux-gnu target and aarch64-linux-gnu-gcc are installed; win64 when the
    /// x86_64-pc-windows-gnu target and MinGW-w64 are), each with fmi-cross-check reference files
    /// (<model>_in.csv, <model>_ref.csv, <model>_ref.opt) and target/fmu/index.json listing them;
    /// the FMUs are the crates with [package.metadata.fmu].
    Package,
    /// Check docs/architecture.md against the code: the crate graph and each crate's module
    /// layers, and that every FMU crate declares itself and is in the README's FMU table.
    Layers {
        /// Print the module layers the code has, in the document's format, instead.
        #[arg(long)]
        print: bool,
    },
    /// Style (fmt, clippy, layering), Rust unit tests, package, then the integration tests: Rust
    /// (with the FMI 2.0 and 3.0 call-sequence fuzzer), the FMUs' leak test under valgrind (both
    /// APIs), Python (FMPy,
    /// SciPy, the `crane_cosim` wheel) in a local venv, 20 s of each fuzz target, then the instruction budgets
    /// (`bench --check`, needs valgrind).
    Test,
    /// Rebuild the 3D viewer's JavaScript bundle (cosim/viewer/assets/viewer.js) from viewer/
    /// with the npm packages pinned in viewer/package-lock.json.
    Viewer {
        /// Build into target/ and fail if the committed bundle differs.
        #[arg(long)]
        check: bool,
    },
    /// Package and run the default demo with the Rust importer, writing results to target/demo/.
    Demo,
    /// Package and run the thesis' campaign (tests 001-104, both variants) into target/campaign/;
    /// extra arguments go to `crane-cosim campaign` (e.g. --tests 20,60 --jobs 1).
    Campaign {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Run the cargo-fuzz targets of fuzz/ (modelDescription.xml, system/scenario files, .fmu
    /// archives) for a while each; installs nightly Rust and cargo-fuzz when missing.
    Fuzz {
        /// Seconds per target (`cargo xtask test` runs 20; a long run: 3600 or more).
        #[arg(long, default_value_t = 300)]
        seconds: u64,
    },
    /// Package, then measure the closed loop into target/bench/report.{md,json}: instructions
    /// per macro step and of the start-up (callgrind), wall times against libcosim and a Python
    /// importer over FMPy, per-FMU costs and the campaign's wall time (see bench/README.md).
    Bench {
        /// Only the instruction counts, failing when they exceed the budgets.
        #[arg(long)]
        check: bool,
        /// Wall times are the best of this many runs.
        #[arg(long, default_value_t = 3)]
        repeats: usize,
    },
    /// Build the `crane_cosim` Python wheel (python/: abi3, CPython >= 3.9) with the FMUs of
    /// target/fmu/ inside (package them first) into target/wheels/, with maturin pinned in
    /// python/requirements-build.txt (in target/maturin-venv).
    Wheel,
}

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

fn run() -> Result<()> {
    match Cli::parse().command {
        Task::Package => package::package_all().map(|_| ()),
        Task::Layers { print: false } => layers::check(),
        Task::Layers { print: true } => layers::print(),
        Task::Test => test(),
        Task::Demo => demo(),
        Task::Viewer { check } => viewer::build(check),
        Task::Campaign { args } => campaign(&args),
        Task::Fuzz { seconds } => fuzz::fuzz(seconds),
        Task::Bench { check, repeats } => bench::bench(&bench::Options { check, repeats }),
        Task::Wheel => wheel::build("release").map(|_| ()),
    }
}

/// The workspace root (xtask lives one level below it).
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("xtask is inside the workspace").to_path_buf()
}

/// Runs a command in the workspace root and fails with its name if it fails.
pub fn run_command(cmd: &mut Command) -> Result<()> {
    let status = cmd.current_dir(root()).status().with_context(|| format!("cannot start {cmd:?}"))?;
    if !status.success() {
        bail!("{cmd:?} failed with {status}");
    }
    Ok(())
}

fn cargo() -> Command {
    Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
}

/// The importer binary, built in release mode (also needed to write the FMUs' reference files).
pub fn build_master() -> Result<PathBuf> {
    run_command(cargo().args(["build", "--release", "--package", "crane-cosim"]))?;
    Ok(root().join("target/release/crane-cosim"))
}

/// The Cargo profile of the test suite's own builds (Cargo.toml: the release profile's code
/// without fat LTO); the FMUs, the master and the benchmarks are release builds.
const TEST_PROFILE: &str = "test-release";

/// Seconds per fuzz target in `cargo xtask test`.
const CI_FUZZ_SECONDS: u64 = 20;

fn test() -> Result<()> {
    style()?;
    // Unit tests first, before anything is packaged: they must not need an FMU. --show-output
    // prints the figures the physics tests measure (time constants, RMSDs).
    run_command(cargo().args([
        "test",
        "--workspace",
        "--profile",
        TEST_PROFILE,
        "--lib",
        "--bins",
        "--",
        "--show-output",
    ]))?;
    // The FMUs' win64 and aarch64 Linux binaries (and the Wine and QEMU tests that run them), and
    // the browser that checks their documentation pages.
    setup::windows_cross()?;
    setup::aarch64_cross()?;
    setup::documentation_browser()?;
    // The viewer's committed JavaScript bundle must be the one its sources build.
    viewer::build(true)?;
    package::package_all()?;
    let master = build_master()?;
    // Integration tests: the packaged FMUs through the importer, the engine and the binary.
    run_command(cargo().args([
        "test",
        "--workspace",
        "--profile",
        TEST_PROFILE,
        "--test",
        "*",
        "--",
        "--show-output",
    ]))?;
    leak_check()?;
    // The Python package's wheel, with the FMUs just packaged inside.
    let wheel = wheel::build(TEST_PROFILE)?;
    let python = python::venv()?;
    setup::python_shared_library(&python)?;
    run_command(
        Command::new(python)
            .args(["-m", "pytest", "tests", "-q", "-rA", "-s", "--durations=15"])
            .env("CRANE_COSIM", master)
            .env("CRANE_COSIM_WHEEL", wheel)
            .env("FMU_DIR", root().join("target/fmu")),
    )?;
    // A short fuzzing run of the parsers (the long one: `cargo xtask fuzz --seconds 3600`).
    fuzz::fuzz(CI_FUZZ_SECONDS)?;
    // Performance regressions: instruction counts (callgrind), not wall times, so this cannot
    // flake on a loaded machine.
    bench::bench(&bench::Options { check: true, repeats: 1 })
}

/// The FMUs' leak test: instance and load/unload cycles of every FMU library through FMI 2.0 and
/// FMI 3.0, then every library handed the instances and states of every other (`fmu-leak`),
/// under valgrind, failing on any block definitely lost or any invalid memory access.
fn leak_check() -> Result<()> {
    setup::valgrind()?;
    run_command(cargo().args(["build", "--release", "--package", "fmu-fuzz", "--bin", "fmu-leak"]))?;
    run_command(Command::new("valgrind").args([
        "--leak-check=full",
        "--errors-for-leak-kinds=definite",
        "--error-exitcode=1",
        "target/release/fmu-leak",
    ]))
}

/// Formatting, lints and API documentation (warnings are errors) and the layering of crates and
/// modules.
fn style() -> Result<()> {
    setup::rust_components()?;
    run_command(cargo().args(["fmt", "--all", "--check"]))?;
    run_command(cargo().args(["clippy", "--workspace", "--all-targets", "--", "-D", "warnings"]))?;
    // The API documentation builds without a warning: a broken or private intra-doc link fails.
    run_command(cargo().env("RUSTDOCFLAGS", "-D warnings").args(["doc", "--workspace", "--no-deps"]))?;
    layers::check()
}

fn campaign(args: &[String]) -> Result<()> {
    package::package_all()?;
    let master = build_master()?;
    run_command(Command::new(master).args(["campaign", "--out", "target/campaign"]).args(args))
}

/// The demo scenarios: the 700 mm pendulum released at θx = −23° after 10 s, crane off and
/// compensated, in still water and under ship motion profile 1.
const DEMO: [&str; 4] = ["demo_still_off", "demo_still_compensated", "demo_profile1_off", "demo_profile1_compensated"];

/// The columns `crane-cosim view` draws beyond those the demo scenarios record (the ship's
/// motion, the crane's joints, the estimated load: every variable of their groups), added to the
/// demo's CSVs so that `crane-cosim view target/demo/<name>.csv` replays them; the scenario files
/// keep the 23 variables the instruction budgets of `cargo xtask bench` are measured with.
fn demo_view_record() -> Vec<String> {
    let names = &crane_names::TEST_SCALE;
    [names.ship[0], names.joints[0], names.estimated_load.axes[0]]
        .into_iter()
        .flat_map(|name| ["--record".to_string(), group_pattern(name)])
        .collect()
}

/// `instance.group.*` of a name `instance.group.member`: the record pattern of its group.
fn group_pattern(name: &str) -> String {
    name.rsplit_once('.').map_or_else(|| name.to_string(), |(group, _)| format!("{group}.*"))
}

fn demo() -> Result<()> {
    package::package_all()?;
    let master = build_master()?;
    let out = root().join("target/demo");
    std::fs::create_dir_all(&out)?;
    let csv = |name: &str| format!("target/demo/{name}.csv");
    for name in DEMO {
        run_command(
            Command::new(&master)
                .args(["run", &format!("scenarios/{name}.json"), "--output", &csv(name), "-q"])
                .args(demo_view_record()),
        )?;
    }
    println!("\nAfter release (t = 10 s), 60 s:");
    run_command(Command::new(&master).args(["compare", "--from", "10"]).args(DEMO.map(csv)))?;
    for (pair, title) in [(&DEMO[..2], "still"), (&DEMO[2..], "profile1")] {
        for (column, label) in [("pendulum.theta_x", "theta_x (deg)"), ("pendulum.theta_y", "theta_y (deg)")] {
            let png = format!("target/demo/{title}_{}.png", column.trim_start_matches("pendulum."));
            run_command(
                Command::new(&master)
                    .args([
                        "plot",
                        "--column",
                        column,
                        "--scale",
                        "57.29577951308232",
                        "--label",
                        label,
                        "--output",
                        &png,
                    ])
                    .args(pair.iter().map(|n| csv(n))),
            )?;
        }
    }
    println!("\nCSVs, run summaries and plots in {}", out.display());
    Ok(())
}
