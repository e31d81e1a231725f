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

use std::path::Path;

use anyhow::Result;
use cosim_engine::table::SignalTable;
use crane_app::Notice;

/// The file name without its extension, labelling a results file in tables and legends.
fn stem(path: &Path) -> String {
    path.file_stem().map_or_else(|| path.display().to_string(), |s| s.to_string_lossy().into_owned())
}

/// A results CSV (the error says why it cannot be read).
fn read_results(path: &Path) -> Result<SignalTable> {
    Ok(SignalTable::read(path)?)
}

/// Shows what a use case has to say before it runs, on standard error (standard output may
/// carry results).
fn show(notices: &[Notice]) {
    for notice in notices {
        eprintln!("{notice}");
    }
}
