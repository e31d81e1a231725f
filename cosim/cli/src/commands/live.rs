//! `crane-cosim live`: the closed loop at real time in the browser, with the operator in the
//! loop.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Args;
use cosim_engine::system::{Overrides, System, SystemFiles};
use crane_viewer::live::{self, LiveOptions};
use crane_viewer::replay;
use crane_viewer::scene::Crane;
use fmu_import::fmu::ExtractLimits;

/// Arguments of `crane-cosim live`.
#[derive(Debug, Args)]
#[command(after_help = "Examples:\n  \
    crane-cosim live scenarios/demo_profile1_compensated.json --record out/session.csv\n  \
    crane-cosim live scenarios/demo_still_compensated.json --speed 0.5 --port 8080\n  \
    crane-cosim live scenarios/full_scale_profile1_compensated.json\n\n\
    In the page: arrow keys move the load set-point north/south/east/west, PageUp/PageDown raise/lower \
    it, C switches compensation on/off, Space pauses, R resets; a gamepad's left stick, right stick, A \
    and Start do the same. The full-scale crane's controller has no set-point: there moves are refused \
    and C switches its mode between 2 (compensation) and 1 (the joints hold).\n\n\
    Open the printed address: its token is required on the page and its socket, and only Host \
    127.0.0.1:PORT or localhost:PORT (and the page's own origin) is served. A move is at most 0.1 m \
    per axis and keeps the load set-point within tip north -0.15..0.15 m, east -0.55..-0.45 m and \
    cable 0.2..1.2 m; a client may send 20 commands per second; a refused command changes nothing and \
    is answered to its page. At most 8 connections at once.")]
pub struct LiveArgs {
    /// The system or scenario file (JSON) of the closed loop; the test-scale controller is
    /// switched to its external set-point (`controller.setpoint` = 2), which the operator moves.
    /// The full-scale crane's controller (`knuckle_boom_controller`) has none: there, C switches
    /// its `mode` between 2 (compensation) and 1 (the joints hold) and moves are refused.
    pub system: PathBuf,
    /// Simulated seconds per wall-clock second.
    #[arg(long, value_name = "F", default_value_t = 1.0)]
    pub speed: f64,
    /// Port on 127.0.0.1 (0: any free port; the address to open, with its token, is printed).
    #[arg(long, value_name = "P", default_value_t = 8023)]
    pub port: u16,
    /// Record the session to this CSV (each reset records the next run to `<stem>-2.csv`, `-3`, …,
    /// up to 20 files; later runs are not recorded).
    #[arg(long, value_name = "CSV")]
    pub record: Option<PathBuf>,
    /// Write the pacing figures as JSON here [default: the record file with .summary.json].
    #[arg(long, value_name = "JSON")]
    pub summary: Option<PathBuf>,
    /// Start simulating at once instead of when the first page connects.
    #[arg(long)]
    pub no_wait: bool,
    /// Replace the stop time (s): the session ends there (or on Ctrl-C).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub stop_time: Option<f64>,
    #[command(flatten)]
    pub limits: super::limits::LimitArgs,
}

/// Runs the session and prints its pacing.
pub fn live(args: &LiveArgs, limits: ExtractLimits) -> Result<()> {
    if !(args.speed > 0.0 && args.speed.is_finite()) {
        bail!("--speed {}: expected a positive factor such as 1 or 0.5", args.speed);
    }
    let files = SystemFiles::new(limits);
    let mut overrides = Overrides { stop_time: args.stop_time, ..Overrides::default() };
    let mut system = System::load(&args.system, &overrides, &files)?;
    // The test-scale controller follows the operator through its external set-point; the
    // full-scale one has none, so its start values stay as the file gives them.
    if replay::crane_of(&system) == Crane::TestScale {
        overrides.start.push((crane_names::TEST_SCALE.setpoint_source.into(), serde_json::json!(2)));
        system = System::load(&args.system, &overrides, &files)?;
    }
    let options = LiveOptions {
        speed: args.speed,
        port: args.port,
        record: args.record.clone(),
        interrupt: Some(crate::process::interrupt()),
        wait_for_page: !args.no_wait,
    };
    let title = super::stem(&args.system);
    let pacing = live::run(&system, &title, &options, |address| {
        println!("serving {address} (Ctrl-C ends the session)");
        if !args.no_wait {
            eprintln!("waiting for the page to connect before simulating (--no-wait starts at once)");
        }
    })?;
    println!("{pacing}");
    let summary = args.summary.clone().or_else(|| args.record.as_ref().map(|r| r.with_extension("summary.json")));
    if let Some(path) = summary {
        let text = serde_json::to_string_pretty(&serde_json::json!({ "system": args.system, "pacing": pacing }))?;
        std::fs::write(&path, text + "\n").with_context(|| format!("cannot write {}", path.display()))?;
    }
    Ok(())
}
