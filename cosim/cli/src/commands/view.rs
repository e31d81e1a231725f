//! `crane-cosim view`: a recorded run as one self-contained HTML page with the crane in 3D.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use cosim_engine::system::single::SingleFmu;
use cosim_engine::system::{Overrides, System, SystemFiles};
use cosim_engine::table::SignalTable;
use cosim_engine::text::{counted, Decimal};
use crane_app::Source;
use crane_viewer::page::{self, PageData};
use crane_viewer::replay::{self, FrameColumns};
use crane_viewer::scene::Crane;
use fmu_import::fmu::ExtractLimits;

/// Arguments of `crane-cosim view`.
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  \
    crane-cosim view scenarios/demo_profile1_compensated.json -o out/replay.html\n  \
    crane-cosim view scenarios/full_scale_profile1_compensated.json -o out/full_scale.html\n  \
    crane-cosim view out/run.csv -o out/run.html\n\n\
    The crane drawn is the one the input holds: the full-scale knuckle-boom crane for \
    `knuckle_boom.joint.*` (a CSV: at the FMU's default pedestal position base = (0, -8, 0) m), \
    else the test-scale crane (`crane.joint.*`).\n\n\
    The view reads the closed loop by its instance names: platform (ship.x, ship.y, ship.z, \
    ship.roll, ship.pitch, ship.yaw), crane (joint.theta2z, joint.theta3x, joint.theta4x; or \
    knuckle_boom.joint.slew, .boom, .jib), pendulum (load.x, load.y, load.z, theta_x, theta_y) and \
    controller (est.load.*, sp.load.*; test scale only). There is no option to map other names: a \
    system must name its instances so, and a CSV must have these columns.")]
pub struct ViewArgs {
    /// A results CSV with the columns the view draws, or a system or scenario file (JSON), SSP
    /// archive, OSP system structure or lone FMU, which is run first with those variables
    /// recorded in memory. Test-scale or
    /// full-scale crane, whichever it holds.
    pub input: PathBuf,
    /// The HTML file to write [default: INPUT with the extension .html].
    #[arg(short, long, value_name = "HTML")]
    pub output: Option<PathBuf>,
    /// (systems) Replace the stop time (s).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub stop_time: Option<f64>,
    #[command(flatten)]
    pub limits: super::limits::LimitArgs,
}

/// Writes the replay page and says where.
pub fn view(args: &ViewArgs, limits: ExtractLimits) -> Result<()> {
    // A results CSV shows its crane at the default arm parameters; a system, at its own.
    let (table, crane) = if is_csv(&args.input) {
        (super::read_results(&args.input)?, None)
    } else {
        run(&args.input, args.stop_time, limits)?
    };
    let frames = FrameColumns::from_table(&table, crane)?;
    let title = super::stem(&args.input);
    let html = page::html(&PageData::Replay { title: &title, frames: &frames })?;
    let output = args.output.clone().unwrap_or_else(|| args.input.with_extension("html"));
    std::fs::write(&output, html).with_context(|| format!("cannot write {}", output.display()))?;
    println!(
        "wrote {} ({}, t = {} to {} s)",
        output.display(),
        counted(frames.time.len() as u64, "frame"),
        Decimal(first(&frames)),
        Decimal(last(&frames))
    );
    Ok(())
}

fn is_csv(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("csv"))
}

/// Runs a system or scenario file with the view's variables recorded in memory; the recording
/// and the crane the system holds.
fn run(file: &Path, stop_time: Option<f64>, limits: ExtractLimits) -> Result<(SignalTable, Option<Crane>)> {
    let overrides = Overrides { stop_time, ..Overrides::default() };
    let files = SystemFiles::new(limits);
    let system = if matches!(Source::of(file), Source::Fmu(_)) {
        // Refused with the instances it lacks, like any system without the closed loop's.
        System::load_fmu(file, &SingleFmu::default(), &overrides, &files)?
    } else {
        System::load(file, &overrides, &files)?
    };
    let table = replay::record(&system, Some(&crate::process::interrupt()))?;
    Ok((table, Some(replay::crane_of(&system))))
}

fn first(frames: &FrameColumns) -> f64 {
    frames.time.first().copied().unwrap_or(f64::NAN)
}

fn last(frames: &FrameColumns) -> f64 {
    frames.time.last().copied().unwrap_or(f64::NAN)
}
