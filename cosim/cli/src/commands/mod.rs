//! The subcommands with arguments of their own, one module each.

pub mod campaign;
pub mod compare;
pub mod info;
pub mod limits;
pub mod live;
pub mod plot;
pub mod run;
pub mod shell;
pub mod sweep;
pub mod tune;
pub mod view;

use std::path::{Path, PathBuf};

use anyhow::Result;
use cosim_engine::system::scenario::ScenarioSpec;
use cosim_engine::system::{json, FileKind, SystemFiles};
use cosim_engine::table::SignalTable;
use fmu_import::fmu::ExtractLimits;

/// The file name without its extension, labelling a results file in tables and legends.
fn stem(path: &Path) -> String {
    path.file_stem().map_or_else(|| path.display().to_string(), |s| s.to_string_lossy().into_owned())
}

/// A results CSV (the error says why it cannot be read).
fn read_results(path: &Path) -> Result<SignalTable> {
    Ok(SignalTable::read(path)?)
}

/// Prints to standard error the system file a campaign or sweep runs and the FMU archives it
/// names, as absolute paths: a scenario can point into another checkout, and then it runs that
/// checkout's FMUs, which the user should see before the runs start. A file that cannot be read
/// is left to the run, which reports it in its own words.
fn announce_system(system: &Path, limits: ExtractLimits) {
    let Ok(spec) = SystemFiles::new(limits).spec(system) else { return };
    let folder = system.parent().unwrap_or_else(|| Path::new(""));
    eprintln!("system: {}", absolute(system).display());
    for (alias, archive) in &spec.fmus {
        eprintln!("  FMU {alias}: {}", absolute(&folder.join(archive)).display());
    }
}

/// The system file of the scenario `scenario` (its `system`, relative to the scenario), if the
/// scenario is a regular file that parses (read like every input: never blocking on a FIFO).
fn system_of_scenario(scenario: &Path) -> Option<PathBuf> {
    let text = fmu_import::file::read_regular_text(scenario, SCENARIO_SIZE_LIMIT).ok()?;
    let spec: ScenarioSpec = json::parse(&text, FileKind::Scenario).ok()?;
    Some(scenario.parent().unwrap_or_else(|| Path::new("")).join(spec.system))
}

/// Larger than any scenario file (they are a few kilobytes).
const SCENARIO_SIZE_LIMIT: u64 = 64 << 20;

/// `path` without `.` and `..`, from the root (as given when it cannot be resolved).
fn absolute(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).or_else(|_| std::path::absolute(path)).unwrap_or_else(|_| path.to_path_buf())
}
